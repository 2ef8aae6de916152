"""The EHL rung of a ball-screw case with a lubricant (studies.ladder, rung ``EHL``): each distinct contact of the
case (studies.ladder.distinct_contacts) at its load and the entrainment speed of the case's kinematics, the smooth
isothermal EHL solve (lowmodel.contact.ehl.solve_reynolds, sun2021 eqs 14-19) on the exact helical gap beside the
Hamrock-Dowson film (lowmodel.contact.ehl.hamrock_dowson_film) with the full-tensor radii; docs/ehl.md.

Domain and grid follow the sun2021 scene (studies.sun2021.ehl_domain, docs/ehl.md 'sun2021 scenes'): x along the
track (the entrainment, the contact frame's minor direction), y across the groove; ``2n x n/2`` cells, four times
finer along the track; x from -4 b to 1.5 b (inlet upstream, as the ``ehl-hamrock-dowson`` scene's grids), y to
1.3 a either side (the sun2021 choice for a conformal groove), a and b the Hertz semi-axes across and along.

Entrainment speed (wang2022 eqs 1-2, lowmodel.screw.kinematics.kinematics): ``U = |V_1 + V_2| / 2`` of the two
surfaces relative to the contact, at the screw speed ``omega`` with the nut at rest; a nut turning at ``omega_N``
with the screw at rest differs from a screw turning at ``-omega_N`` by a rigid rotation of the whole screw, which
leaves velocities relative to the contact unchanged, so ``|omega_N|`` is used (screw driven: ``|omega|``).  The
contact angle is the nominal one (the kinematics of wang2022 take equal angles on both sides).

Grid convergence (docs/ehl.md, 'On a case file'): each contact is solved a second time on the grid of the next
coarser level (``n/2``: half the cells each way, the factor between the fidelity levels), and the change of h_c and
h_min between the two, relative to the level's own film, is the solve's grid uncertainty; within
:data:`GRID_TOLERANCE` the film counts as grid-converged.  Where the coarser grid does not resolve the film (its
solve stops with a ConvergenceError, e.g. the film closes) the next finer grid (``2n``) is the second grid instead.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

from ballbench.validation.cases.case import BallScrewCase

__all__ = ["GRID_N", "GRID_TOLERANCE", "ELLIPTICITY_RANGE", "EHLContact", "applies", "entrainment_speeds",
           "ehl_contact", "contacts"]

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


def applies(case) -> bool:
    """Whether the EHL rung runs on ``case``: a ball screw whose file gives a ``[lubricant]``."""
    return isinstance(case, BallScrewCase) and case.screw.lubricant is not None


def entrainment_speeds(case: BallScrewCase) -> dict[str, float]:
    """``{"screw": U_screw, "nut": U_nut}`` [m/s] of the case's drive (module docstring; wang2022 eqs 1-2)."""
    from ballbench.lowmodel.screw import kinematics

    s = case.screw
    speed = s.screw_speed if s.screw_speed is not None else s.nut_speed
    if speed is None or not abs(speed) > 0.0:
        raise ValueError(f"screw.nut_speed (or screw.screw_speed) must be non-zero for the EHL rung (no "
                         f"entrainment, no film), got {speed!r}")
    state = kinematics.kinematics(s.pitch_radius, s.ball_radius, s.lead, abs(speed), s.nominal_angle)
    return {"screw": float(state.entrainment_screw), "nut": float(state.entrainment_nut)}


def ehl_contact(case: BallScrewCase, pair: str, load: float, speed: float, n: int, label: str = "", *,
                second_grid: bool = True) -> EHLContact:
    """The smooth EHL of the ``pair`` ("screw" or "nut") contact of ``case`` under ``load`` [N] at the entrainment
    ``speed`` [m/s] on the ``2n x n/2`` grid, and its Hamrock-Dowson film; with ``second_grid`` also on the
    coarser ``n x n/4`` grid (or, where that one gives no film, the finer ``4n x n``: module docstring)."""
    from ballbench.lowmodel.contact import ehl, hertz
    from ballbench.lowmodel.errors import ConvergenceError
    from ballbench.lowmodel.geometry import groove

    s = case.screw
    oil = s.lubricant
    e_star = s.material.contact_modulus
    args = (s.ball_radius, s.conformity, s.pitch_radius, s.lead, s.nominal_angle, pair)
    frame = groove.contact_frame(groove.helical_groove(*args))
    ball = (1.0 / s.ball_radius, 1.0 / s.ball_radius)
    contact = hertz.solve_load(hertz.from_curvatures(ball, (frame.curvature_major, frame.curvature_minor),
                                                     **s.material.keywords), load)
    a, b = float(contact.a), float(contact.b)  # across the groove, along the track
    radius_x = 1.0 / (1.0 / s.ball_radius + frame.curvature_minor)  # along the track
    radius_y = 1.0 / (1.0 / s.ball_radius + frame.curvature_major)  # across the groove
    alpha = ehl.roelands_pressure_viscosity_coefficient(oil.viscosity)
    reference = ehl.hamrock_dowson_film(speed, load, radius_x, radius_y, 2.0 * e_star, oil.viscosity, alpha)
    gap = groove.pair_initial_gap(*args)

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
    from ballbench.lowmodel.contact import ehl, halfspace

    grid = halfspace.surface_grid(0.5 * (INLET + OUTLET) * b, ACROSS * a, 2 * n, n // 2,
                                  centre=(-0.5 * (INLET - OUTLET) * b, 0.0))
    X, Y = grid.coordinates()
    h = gap(Y, X)  # the groove's first coordinate runs across (studies.sun2021)
    start = time.perf_counter()
    solution = ehl.solve_reynolds(h - h.min(), grid, e_star, load, speed, oil.viscosity, oil.density,
                                  initial_film=initial_film, coarsest=COARSEST)
    return f"{grid.nx} x {grid.ny}", solution, time.perf_counter() - start


def contacts(case: BallScrewCase, fidelity: str, progress=None) -> list[EHLContact]:
    """The EHL of every distinct contact of ``case`` (studies.ladder.distinct_contacts) at ``fidelity``;
    ``progress``: a wrapper of the iterable of contacts (a scene's ``run.progress``)."""
    from ballbench.validation.studies.ladder import distinct_contacts

    if not applies(case):
        raise ValueError(f"the EHL rung needs a ball-screw case with a [lubricant] table, got {case.name!r}")
    speeds = entrainment_speeds(case)
    n = GRID_N[fidelity]
    found = distinct_contacts(case)
    return [ehl_contact(case, d.contact.pair, d.contact.force, speeds[d.contact.pair], n, d.label)
            for d in (progress(found, desc="contacts") if progress is not None else found)]
