"""The EHL rung of a ball-screw or linear-guide case with a lubricant (ladder.rungs, rung ``EHL``): each distinct
contact of the case (ladder.rungs.distinct_contacts) at its load and the entrainment speed of the case's
kinematics, the smooth isothermal EHL solve (lowmodel.contact.ehl.solve_reynolds, sun2021 eqs 14-19) on the exact
gap (helical groove: lowmodel.geometry.groove.pair_initial_gap; straight groove: straight_pair_initial_gap) beside
the Hamrock-Dowson film (lowmodel.contact.ehl.hamrock_dowson_film) with the full-tensor radii; docs/ehl.md.

Domain and grid follow the sun2021 scene (studies.sun2021.ehl_domain, docs/ehl.md 'sun2021 scenes'): x along the
track (the entrainment, the contact frame's minor direction), y across the groove; ``2n x n/2`` cells, four times
finer along the track; x from -4 b to 1.5 b (inlet upstream, as the ``ehl-hamrock-dowson`` scene's grids), y to
1.3 a either side (the sun2021 choice for a conformal groove), a and b the Hertz semi-axes across and along.

Entrainment speed (wang2022 eqs 1-2, lowmodel.screw.kinematics.kinematics): ``U = |V_1 + V_2| / 2`` of the two
surfaces relative to the contact, at the screw speed ``omega`` with the nut at rest; a nut turning at ``omega_N``
with the screw at rest differs from a screw turning at ``-omega_N`` by a rigid rotation of the whole screw, which
leaves velocities relative to the contact unchanged, so ``|omega_N|`` is used (screw driven: ``|omega|``).  The
contact angle is the nominal one (the kinematics of wang2022 take equal angles on both sides).

Entrainment speed of a linear guide (:func:`guide_entrainment_speeds`): the rigid rolling/sliding state of each
four-point ball (lin2017, lowmodel.linear_bearing.fourpoint.solve at the case's contact angles beta_0 + deviations,
its side force and N_y, the carriage speed ``groove_velocity``): the ball centre moves at ``v_B`` along the grooves
and turns at ``omega = (omega_x, omega_y, 0)``; at contact ``i`` (point ``q_i = R_B n_i``, lin2017 eq 1) the
ball's surface moves at ``V_1 = v_B + omega_x q_y - omega_y q_x`` (lin2017 eqs 4, 6: the rows of eq 7) and the
groove's at ``V_2 = 0`` (rail: BL, BR) or ``v`` (carriage: TR, TL); relative to the contact, which travels with the
ball centre, ``U_e = |(V_1 - v_B) + (V_2 - v_B)| / 2`` (as wang2022 eqs 1-2 for the screw).  Hand limit: in pure
rolling with the rail contacts at beta_b and the carriage contacts at beta_t (left-right symmetric, so lin2017's
C_beta = 0), ``omega_y = 0`` and no slip gives ``v_B = omega_x R_B cos beta_b`` and ``v - v_B = omega_x R_B cos
beta_t``, so ``U_e = v r_i / (r_b + r_t)`` with the rolling radii ``r = R_B cos beta``: half the carriage speed
where the radii are equal (tests/validation/studies/test_case_ehl.py).  On a tie of lin2017 (motion not unique) the
centroid motion of fourpoint.solve is used.  A guide's one distinct contact (rail and carriage share the
conformity) runs at the load and entrainment of the most loaded contact of the low-order balls (lin2019,
lowmodel.bearing_results.guide_result).

Grid convergence (docs/ehl.md, 'On a case file'): each contact is solved a second time on the grid of the next
coarser level (``n/2``: half the cells each way, the factor between the fidelity levels), and the change of h_c and
h_min between the two, relative to the level's own film, is the solve's grid uncertainty; within
:data:`GRID_TOLERANCE` the film counts as grid-converged.  Where the coarser grid does not resolve the film (its
solve stops with a ConvergenceError, e.g. the film closes) the next finer grid (``2n``) is the second grid instead.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import bearing_results
from ballbench.lowmodel.contact import ehl, halfspace, hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import groove
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_normals
from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.lowmodel.screw import kinematics
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.ladder.rungs import distinct_contacts

__all__ = ["GRID_N", "GRID_TOLERANCE", "ELLIPTICITY_RANGE", "EHLContact", "applies", "lubricant",
           "entrainment_speeds", "guide_entrainment_speeds", "ehl_contact", "contacts"]

GRID_N = {"quick": 64, "default": 128, "fine": 256}  # grid 2n x n/2, as the sun2021-ehl scene (docs/ehl.md)
# Hamrock & Dowson (1977), Part III: the 34 fully flooded cases of the fit span the ellipticity k = 1 to 8; the
# formulas are not checked outside it (an extrapolation of the fit, not a claim)
ELLIPTICITY_RANGE = (1.0, 8.0)
INLET, OUTLET, ACROSS = 4.0, 1.5, 1.3  # the domain in Hertz semi-axes (module docstring)
# the grid nested under 128 x 32 (64 x 16) has 16 cells across a slender ellipse and its film closes; the
# 128 x 32 grid started from the dry pressure converges (studies.sun2021.COARSEST, the same choice)
COARSEST = 32
# the largest change of h_c or h_min between the level's grid and the second grid (relative to the level's film)
# at which the solve counts as grid-converged: a third of the 15 % Hamrock-Dowson is judged by, so that the solve
# can judge it; on the shipped oil example the quick grid moves h_min by 1.3 % (docs/ehl.md, 'On a case file')
GRID_TOLERANCE = 0.05


@dataclass(frozen=True)
class EHLContact:
    """The EHL of one distinct contact: ``label`` (``"screw side"``, ``"nut side"``), ``load`` [N],
    ``speed`` the entrainment speed U [m/s], ``radius_x`` (track), ``radius_y`` (across) [m], the Hertz ``a``
    (across), ``b`` (along) [m] and ``p0`` [Pa], ``reference`` (hamrock_dowson_film: h_c, h_min [m], U, G, W, k),
    ``solution`` (an EHLSolution), ``grid`` (``"nx x ny"``), ``time_s`` the wall time of the solve [s];
    the grid study (module docstring): ``second`` the EHLSolution on the second grid, ``second_grid``
    (``"nx x ny"``), ``second_time_s`` [s], ``coarser_failure`` the reason the coarser grid gave no film (empty
    when it did; then ``second`` is the finer grid's)."""

    label: str
    load: float
    speed: float
    radius_x: float
    radius_y: float
    a: float
    b: float
    p0: float
    reference: dict
    solution: object
    grid: str
    time_s: float
    second: object = None
    second_grid: str = ""
    second_time_s: float = 0.0
    coarser_failure: str = ""

    @property
    def grid_change(self) -> dict[str, float]:
        """``{"h_c": ..., "h_min": ...}``: ``|h(second grid) - h(level grid)| / h(level grid)`` [-]."""
        if self.second is None:
            raise ValueError(f"{self.label}: no second grid was solved (ehl_contact(..., second_grid=False))")
        s, t = self.solution, self.second
        return {"h_c": abs(t.central_film - s.central_film) / s.central_film,
                "h_min": abs(t.minimum_film - s.minimum_film) / s.minimum_film}

    @property
    def grid_converged(self) -> bool:
        """Whether both films change by at most :data:`GRID_TOLERANCE` between the two grids."""
        return max(self.grid_change.values()) <= GRID_TOLERANCE

    @property
    def within_fit(self) -> bool:
        """Whether the ellipticity lies in the range Hamrock-Dowson fitted (:data:`ELLIPTICITY_RANGE`)."""
        return ELLIPTICITY_RANGE[0] <= self.reference["k"] <= ELLIPTICITY_RANGE[1]


def lubricant(case):
    """The case's oil (a Lubricant) or None: a ball screw's or a linear guide's ``[lubricant]``."""
    if isinstance(case, BallScrewCase):
        return case.screw.lubricant
    if isinstance(case, LinearGuideCase):
        return case.guide.lubricant
    return None


def applies(case) -> bool:
    """Whether the EHL rung runs on ``case``: a ball screw or linear guide whose file gives a ``[lubricant]``."""
    return lubricant(case) is not None


def guide_entrainment_speeds(case: LinearGuideCase):
    """``(n_balls, 4)`` entrainment speeds U_e [m/s] of each ball's contacts (BL, BR, TR, TL) at the carriage speed
    (module docstring; lin2017 eqs 1, 4, 6, 7)."""
    g = case.guide
    v = float(g.groove_velocity)
    if not abs(v) > 0.0:
        raise ValueError(f"guide.groove_velocity must be non-zero for the EHL rung (no entrainment, no film), got "
                         f"{g.groove_velocity!r}")
    angles = np.asarray(case.contact_angles, dtype=float)
    normals = contact_normals(angles)  # (4, 2): q_i = R_B n_i, lin2017 eq 1
    groove = np.array([0.0, 0.0, v, v])  # rail at rest, carriage at v
    speeds = []
    for ball in range(1, case.n_balls + 1):
        state = fourpoint.solve(angles, case.side_force(ball), case.vertical_force, ball_radius=g.ball_radius,
                                friction_coefficient=g.friction_coefficient, groove_velocity=v)
        v_b = float(state.ball_velocity)
        omega_x, omega_y = float(state.omega[0]), float(state.omega[1])
        surface = v_b + g.ball_radius * (omega_x * normals[:, 1] - omega_y * normals[:, 0])  # lin2017 eqs 4, 6
        speeds.append(np.abs((surface - v_b) + (groove - v_b)) / 2.0)
    return np.asarray(speeds)


def entrainment_speeds(case: BallScrewCase) -> dict[str, float]:
    """``{"screw": U_screw, "nut": U_nut}`` [m/s] of the case's drive (module docstring; wang2022 eqs 1-2)."""
    s = case.screw
    speed = s.screw_speed if s.screw_speed is not None else s.nut_speed
    if speed is None or not abs(speed) > 0.0:
        raise ValueError(f"screw.nut_speed (or screw.screw_speed) must be non-zero for the EHL rung (no "
                         f"entrainment, no film), got {speed!r}")
    state = kinematics.kinematics(s.pitch_radius, s.ball_radius, s.lead, abs(speed), s.nominal_angle)
    return {"screw": float(state.entrainment_screw), "nut": float(state.entrainment_nut)}


def ehl_contact(case, pair: str, load: float, speed: float, n: int, label: str = "", *,
                second_grid: bool = True) -> EHLContact:
    """The smooth EHL of the ``pair`` ("screw" or "nut" of a BallScrewCase, "groove" of a LinearGuideCase) contact of
    ``case`` under ``load`` [N] at the entrainment
    ``speed`` [m/s] on the ``2n x n/2`` grid, and its Hamrock-Dowson film; with ``second_grid`` also on the
    coarser ``n x n/4`` grid (or, where that one gives no film, the finer ``4n x n``: module docstring)."""
    oil = lubricant(case)
    if pair == "groove":  # a linear guide's straight groove (lowmodel.geometry.groove)
        g = case.guide
        ball_radius, material = g.ball_radius, g.material
        across, along = groove.straight_groove_curvatures(ball_radius, g.conformity)
        gap = groove.straight_pair_initial_gap(ball_radius, "groove", g.conformity)  # (x across, y along)
    else:
        s = case.screw
        ball_radius, material = s.ball_radius, s.material
        args = hertz.helical_pair(s.contact(pair, load))
        frame = groove.contact_frame(groove.helical_groove(*args))
        across, along = frame.curvature_major, frame.curvature_minor
        gap = groove.pair_initial_gap(*args)  # the groove's first coordinate runs across (studies.sun2021)
    e_star = material.contact_modulus
    ball = (1.0 / ball_radius, 1.0 / ball_radius)
    contact = hertz.solve_load(hertz.from_curvatures(ball, (across, along), **material.keywords), load)
    a, b = float(contact.a), float(contact.b)  # across the groove, along the track
    radius_x = 1.0 / (1.0 / ball_radius + along)  # along the track
    radius_y = 1.0 / (1.0 / ball_radius + across)  # across the groove
    alpha = ehl.roelands_pressure_viscosity_coefficient(oil.viscosity)
    reference = ehl.hamrock_dowson_film(speed, load, radius_x, radius_y, 2.0 * e_star, oil.viscosity, alpha)

    def solve(cells):
        return _solve(gap, a, b, cells, e_star, load, speed, oil, reference["h_c"])

    grid, solution, wall = solve(n)
    second, second_grid_words, second_wall, failure = None, "", 0.0, ""
    if second_grid:
        try:
            second_grid_words, second, second_wall = solve(n // 2)
        except ConvergenceError as error:  # the coarser grid does not resolve the film: the finer one instead
            failure = error.reason or str(error)
            second_grid_words, second, second_wall = solve(2 * n)
    return EHLContact(label or f"{pair} side", load, speed, radius_x, radius_y, a, b, float(contact.p0), reference,
                      solution, grid, wall, second, second_grid_words, second_wall, failure)


def _solve(gap, a, b, n, e_star, load, speed, oil, initial_film):
    """The EHL solve on the ``2n x n/2`` grid of the module docstring: ``("nx x ny", EHLSolution, wall [s])``."""
    grid = halfspace.surface_grid(0.5 * (INLET + OUTLET) * b, ACROSS * a, 2 * n, n // 2,
                                  centre=(-0.5 * (INLET - OUTLET) * b, 0.0))
    X, Y = grid.coordinates()
    h = gap(Y, X)  # both gaps take (across, along)
    start = time.perf_counter()
    solution = ehl.solve_reynolds(h - h.min(), grid, e_star, load, speed, oil.viscosity, oil.density,
                                  initial_film=initial_film, coarsest=COARSEST)
    return f"{grid.nx} x {grid.ny}", solution, time.perf_counter() - start


def contacts(case, fidelity: str, progress=None) -> list[EHLContact]:
    """The EHL of every distinct contact of ``case`` (ladder.rungs.distinct_contacts) at ``fidelity``;
    ``progress``: a wrapper of the iterable of contacts (a scene's ``run.progress``)."""
    if not applies(case):
        raise ValueError(f"the EHL rung needs a ball-screw or linear-guide case with a [lubricant] table, got "
                         f"{case.name!r}")
    n = GRID_N[fidelity]
    if isinstance(case, LinearGuideCase):
        result = bearing_results.guide_result(case)
        (found,) = distinct_contacts(case, result)
        worst = max(result.contacts, key=lambda c: c.normal_force)  # the contact distinct_contacts runs
        speed = guide_entrainment_speeds(case)[worst.ball - 1, CONTACT_NAMES.index(worst.contact)]
        items = [("groove", found.contact.force, float(speed), f"groove, ball {worst.ball} {worst.contact}")]
    else:
        speeds = entrainment_speeds(case)
        items = [(d.contact.pair, d.contact.force, speeds[d.contact.pair], d.label) for d in distinct_contacts(case)]
    return [ehl_contact(case, pair, load, speed, n, label)
            for pair, load, speed, label in (progress(items, desc="contacts") if progress is not None else items)]
