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
"""
from __future__ import annotations

import time
from dataclasses import dataclass

from ballbench.validation.cases.case import BallScrewCase

__all__ = ["GRID_N", "ELLIPTICITY_RANGE", "EHLContact", "applies", "entrainment_speeds", "ehl_contact",
           "contacts"]

GRID_N = {"quick": 64, "default": 128, "fine": 256}  # grid 2n x n/2, as the sun2021-ehl scene (docs/ehl.md)
# Hamrock & Dowson (1977), Part III: the 34 fully flooded cases of the fit span the ellipticity k = 1 to 8; the
# formulas are not checked outside it (an extrapolation of the fit, not a claim)
ELLIPTICITY_RANGE = (1.0, 8.0)
INLET, OUTLET, ACROSS = 4.0, 1.5, 1.3  # the domain in Hertz semi-axes (module docstring)
# the grid nested under 128 x 32 (64 x 16) has 16 cells across a slender ellipse and its film closes; the
# 128 x 32 grid started from the dry pressure converges (studies.sun2021.COARSEST, the same choice)
COARSEST = 32


@dataclass(frozen=True)
class EHLContact:
    """The EHL of one distinct contact: ``label`` (``"screw side"``, ``"nut side"``), ``load`` [N],
    ``speed`` the entrainment speed U [m/s], ``radius_x`` (track), ``radius_y`` (across) [m], the Hertz ``a``
    (across), ``b`` (along) [m] and ``p0`` [Pa], ``reference`` (hamrock_dowson_film: h_c, h_min [m], U, G, W, k),
    ``solution`` (an EHLSolution), ``grid`` (``"nx x ny"``), ``time_s`` the wall time of the solve [s]."""

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


def ehl_contact(case: BallScrewCase, pair: str, load: float, speed: float, n: int, label: str = "") -> EHLContact:
    """The smooth EHL of the ``pair`` ("screw" or "nut") contact of ``case`` under ``load`` [N] at the entrainment
    ``speed`` [m/s] on the ``2n x n/2`` grid, and its Hamrock-Dowson film."""
    from ballbench.lowmodel.contact import ehl, halfspace, hertz
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
    grid = halfspace.surface_grid(0.5 * (INLET + OUTLET) * b, ACROSS * a, 2 * n, n // 2,
                                  centre=(-0.5 * (INLET - OUTLET) * b, 0.0))
    X, Y = grid.coordinates()
    gap = groove.pair_initial_gap(*args)(Y, X)  # the groove's first coordinate runs across (studies.sun2021)
    radius_x = 1.0 / (1.0 / s.ball_radius + frame.curvature_minor)  # along the track
    radius_y = 1.0 / (1.0 / s.ball_radius + frame.curvature_major)  # across the groove
    alpha = ehl.roelands_pressure_viscosity_coefficient(oil.viscosity)
    reference = ehl.hamrock_dowson_film(speed, load, radius_x, radius_y, 2.0 * e_star, oil.viscosity, alpha)
    start = time.perf_counter()
    solution = ehl.solve_reynolds(gap - gap.min(), grid, e_star, load, speed, oil.viscosity, oil.density,
                                  initial_film=reference["h_c"], coarsest=COARSEST)
    wall = time.perf_counter() - start
    return EHLContact(label or f"{pair} side", load, speed, radius_x, radius_y, a, b, float(contact.p0), reference,
                      solution, f"{grid.nx} x {grid.ny}", wall)


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
