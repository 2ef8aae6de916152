"""The sun2021 ball screw (cases.sun2021) through its models: the eq 1 load, the dry contact (BEM on the exact
helical gap against Hertz), FE of the same contact, the EHL domain of eq 18 and the mixed-lubrication friction
of eqs 20-23 on the WM raceway.  Shared by the sun2021 scenes and the benchmarks.

Points: A on the screw (left flank), B diametrically opposite on the nut (right flank).  The EHL domain: x along
the track (entrainment, the contact frame's minor direction), y across the groove, x in [-277, 277] um (eq 18), y
widened to 1.3 times the Hertz semi-axis a (the paper's 277 um cuts the contact, a = 275 um at A).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ballbench.fem import contact, hertz_case, postprocess
from ballbench.fem.mortar import build_mortar_model
from ballbench.lowmodel.contact import ehl, halfspace, hertz, mixed, roughness, screw_contact
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import groove, helix
from ballbench.lowmodel.screw import friction_torque
from ballbench.validation.cases import sun2021 as case

__all__ = ["POINTS", "contact_load", "dry_contact", "ehl_domain", "ehl_case", "raceway_heights", "contact_speeds",
           "mixed_point", "clearance", "transition", "scale_at_first_touch", "dry_rough", "central_ehl_pressure",
           "second_moment_angle", "fe_contact", "EHL_ITERATIONS", "COARSEST", "READING"]

SCREW = case.SCREW
POINTS = {"A": ("screw", "left"), "B": ("nut", "right")}  # A on the screw, B diametrically opposite on the nut
E_STAR = SCREW.material.contact_modulus  # two steel bodies (Johnson eq 4.22)
EHL_ITERATIONS = 30  # converged points take 6-12 Newton steps; where the solver stalls (slow speeds) fail fast
# nested iteration from the 64 x 16 grid stalls below ~250 mm/s screw speed (its across-groove cells are 44 um);
# the 128 x 32 grid started from the dry pressure converges down to 83 mm/s in 8-9 Newton steps
COARSEST = 32
READING = "pm"  # the unit the printed G = 0.41 is read in (docs/mixed_lubrication.md)


def contact_load() -> float:
    """Normal ball load Q_A = Q_B [N] (sun2021 eq 1, Table 1).

    eq 1 at the Table 1 helix angle, held for the parameter study (the paper's Hertz central pressure "does not
    change with the helix angle", Sec 4.2: the load is fixed)."""
    return screw_contact.preload_contact_load(SCREW.preload, SCREW.ball_count, case.HELIX_ANGLE, SCREW.nominal_angle)


def _lead(helix_angle_deg: float) -> float:
    return float(helix.lead_from_angle(math.radians(helix_angle_deg), SCREW.pitch_radius))


def dry_contact(helix_angle_deg: float, point: str, n: int):
    """BEM (n x n) and Hertz models of the Table 1 contact at ``point`` "A" (screw) or "B" (nut), helix angle [deg]."""
    body, flank = POINTS[point]
    return screw_contact.groove_contact(SCREW.ball_radius, SCREW.conformity, SCREW.pitch_radius,
                                        _lead(helix_angle_deg), SCREW.nominal_angle, contact_load(), body, flank,
                                        youngs_modulus=SCREW.material.youngs_modulus,
                                        poisson_ratio=SCREW.material.poisson_ratio, n=n)


def ehl_domain(helix_angle_deg: float, point: str, n: int, helix_free: bool = False):
    """Grid (2n x n/2 cells; x along the track = entrainment, y across the groove), smooth gap [m] of the EHL
    domain (eq 18) and the contact frame of the helical groove (lowmodel.geometry.groove); ``helix_free``: the
    groove with lead 0."""
    body, flank = POINTS[point]
    lead = 0.0 if helix_free else _lead(helix_angle_deg)
    args = (SCREW.ball_radius, SCREW.conformity, SCREW.pitch_radius, lead, SCREW.nominal_angle, body)
    frame = groove.contact_frame(groove.helical_groove(*args, flank))
    ball = (1.0 / SCREW.ball_radius, 1.0 / SCREW.ball_radius)
    contact = hertz.solve_load(hertz.from_curvatures(ball, (frame.curvature_major, frame.curvature_minor),
                                                     **SCREW.material.keywords), contact_load())
    grid = halfspace.surface_grid(case.EHL_HALF_WIDTH, max(case.EHL_HALF_WIDTH, 1.3 * float(contact.a)), 2 * n,
                                  n // 2)
    X, Y = grid.coordinates()
    gap = groove.pair_initial_gap(*args, flank=flank)(Y, X)
    return grid, gap - gap.min(), frame


def ehl_case(helix_angle_deg: float, point: str, n: int, speed: float = case.ENTRAINMENT_SPEED):
    """Smooth EHL of the contact at ``point`` (lowmodel.contact.ehl.solve_reynolds) at the entrainment ``speed``
    [m/s] and its Hamrock-Dowson film with the full-tensor radii R_x (track), R_y (across): (solution, reference)."""
    grid, gap, frame = ehl_domain(helix_angle_deg, point, n)
    radius_x = 1.0 / (1.0 / SCREW.ball_radius + frame.curvature_minor)  # along the track
    radius_y = 1.0 / (1.0 / SCREW.ball_radius + frame.curvature_major)  # across the groove
    oil = SCREW.lubricant
    alpha = ehl.roelands_pressure_viscosity_coefficient(oil.viscosity)
    reference = ehl.hamrock_dowson_film(speed, contact_load(), radius_x, radius_y, 2 * E_STAR, oil.viscosity, alpha)
    solution = ehl.solve_reynolds(gap, grid, E_STAR, contact_load(), speed, oil.viscosity, oil.density,
                                  initial_film=reference["h_c"], coarsest=16)
    return solution, reference


def raceway_heights(grid, reading: str = READING, seed: int = 0) -> roughness.RacewayRoughness:
    """The seeded WM raceway of sun2021 Sec 2.3 on ``grid`` with G read in ``reading`` ("pm" or "nm")."""
    return roughness.raceway_roughness(grid, case.FRACTAL_DIMENSION,
                                       case.FRACTAL_SCALE * case.FRACTAL_SCALE_READINGS[reading],
                                       sample_length=case.FRACTAL_SAMPLE_LENGTH,
                                       cutoff_length=case.FRACTAL_CUTOFF_LENGTH, seed=seed)


def contact_speeds(surface_speed: float):
    """wang2022 entrainment and sliding of the contacts at the screw speed Omega' [m/s]
    (lowmodel.screw.friction_torque.contact_speeds)."""
    return friction_torque.contact_speeds(surface_speed, SCREW.pitch_radius, SCREW.ball_radius, SCREW.lead,
                                          SCREW.nominal_angle)


def mixed_point(grid, gap, heights, surface_speed: float, point: str = "B", coupled: bool = True):
    """Mixed contact, friction (eqs 21-23), eq 20 torque [N m] and entrainment [m/s] at screw speed [m/s]."""
    speeds = contact_speeds(surface_speed)
    u = float(speeds.entrainment_B if point == "B" else speeds.entrainment_A)
    sliding = speeds.sliding_B if point == "B" else speeds.sliding_A
    oil = SCREW.lubricant
    contact = mixed.solve(gap, heights, grid, E_STAR, contact_load(), u, oil.viscosity, oil.density,
                                initial_film=8e-8, ehl_iterations=EHL_ITERATIONS, coarsest=COARSEST,
                                coupled=coupled)
    friction = mixed.mixed_friction(contact, float(np.linalg.norm(sliding)), oil.viscosity, case.EYRING_STRESS,
                                    case.DRY_FRICTION)
    torque = friction_torque.friction_torque(friction.friction_coefficient, contact_load(), speeds.sliding_B,
                                             ball_count=SCREW.ball_count, lead_angle=case.HELIX_ANGLE,
                                             pitch_radius=SCREW.pitch_radius, ball_radius=SCREW.ball_radius,
                                             contact_angle_B=SCREW.nominal_angle)
    return contact, friction, torque, u


def _smooth_film(gap, grid, surface_speed: float, **options):
    u = float(contact_speeds(surface_speed).entrainment_B)
    oil = SCREW.lubricant
    return ehl.solve_reynolds(gap, grid, E_STAR, contact_load(), u, oil.viscosity, oil.density, initial_film=8e-8,
                              coarsest=COARSEST, max_iterations=EHL_ITERATIONS, **options)


def clearance(grid, gap, heights, surface_speed: float, coupled: bool = True) -> float:
    """Smallest rough film [m] at the nut contact; -inf where the coupled film closes (its solve fails).

    ``coupled``: the Reynolds equation with the roughness in the film (sun2021 eq 15); otherwise the rigid
    roughness against the smooth film, ``min(h_s - z)``.  ConvergenceError when the smooth solve fails too.
    """
    if coupled:
        try:
            return _smooth_film(gap - heights, grid, surface_speed).minimum_film
        except ConvergenceError:
            pass
    film = _smooth_film(gap, grid, surface_speed)
    return -math.inf if coupled else float(np.min(film.film - heights))


def transition(grid, gap, heights, clearances: dict, steps: int, factor: float = 0.9, coupled: bool = True):
    """Screw speed [m/s] where the rough film first touches (clearance 0), from the sweep's ``clearances``
    ({speed: clearance}), and how it was found.

    Below the slowest full-film speed: bracket downward (x ``factor``) until the film touches or the EHL solve stops
    converging (then the slowest full-film speed is an upper bound), then bisect in log speed.
    """
    full = sorted(speed for speed, c in clearances.items() if c > 0.0)
    if not full:
        return None, "the rough film touches at every speed of the sweep"
    hi = full[0]
    touching = [speed for speed, c in clearances.items() if c <= 0.0 and speed < hi]
    lo = max(touching) if touching else None
    c_hi = clearances[hi]
    speed = hi
    while lo is None and speed > 0.4 * full[0]:
        speed *= factor
        try:
            c = clearance(grid, gap, heights, speed, coupled)
        except ConvergenceError as error:
            return hi, (f"upper bound: full film (film >= {c_hi * 1e9:+.1f} nm) at {hi * 1e3:.0f} mm/s, the "
                        f"slowest speed the EHL solve reaches (no convergence at {speed * 1e3:.0f} mm/s: {error})")
        if c <= 0.0:
            lo = speed
        else:
            hi, c_hi = speed, c
    if lo is None:
        return hi, f"upper bound: still full film at {hi * 1e3:.0f} mm/s"
    for _ in range(steps):
        mid = math.sqrt(lo * hi)
        if clearance(grid, gap, heights, mid, coupled) > 0.0:
            hi = mid
        else:
            lo = mid
    return math.sqrt(lo * hi), f"bracket [{lo * 1e3:.1f}, {hi * 1e3:.1f}] mm/s"


def scale_at_first_touch(grid, gap, heights, surface_speed: float) -> float:
    """Factor s on the heights at which the rough film first touches at ``surface_speed`` (s z = h_s somewhere).

    WM heights scale as G^(D-2) with the phases fixed, so G* = G s^(1/(D-2)) puts the first touch there.
    """
    film = _smooth_film(gap, grid, surface_speed).film
    up = heights > 0.0
    return float(np.min(film[up] / heights[up]))


def dry_rough(helix_angle_deg: float, point: str, n: int, helix_free: bool):
    """Dry BEM contact of the smooth and the rough (WM, G in pm) raceway on the EHL domain: (smooth, rough);
    the boundary limit, where the rough raceway carries the whole load."""
    grid, gap, _ = ehl_domain(helix_angle_deg, point, n, helix_free)
    heights = raceway_heights(grid).heights
    smooth = halfspace.solve(gap, grid, E_STAR, force=contact_load())
    rough = halfspace.solve(gap - heights, grid, E_STAR, force=contact_load())
    return smooth, rough


def central_ehl_pressure(helix_angle_deg: float, point: str, n: int, surface_speed: float,
                         helix_free: bool = False) -> float:
    """Central pressure [Pa] of the smooth EHL contact at ``point`` at the screw speed Omega' [m/s]."""
    grid, gap, _ = ehl_domain(helix_angle_deg, point, n, helix_free)
    speeds = contact_speeds(surface_speed)
    u = float(speeds.entrainment_B if point == "B" else speeds.entrainment_A)
    oil = SCREW.lubricant
    return ehl.solve_reynolds(gap, grid, E_STAR, contact_load(), u, oil.viscosity, oil.density, initial_film=8e-8,
                              coarsest=COARSEST, max_iterations=EHL_ITERATIONS).central_pressure


def second_moment_angle(x: np.ndarray, y: np.ndarray, weight: np.ndarray) -> float:
    """Angle [rad] of the major axis of the ``weight``-weighted second moments of points ``(x, y)`` [m], from x.

    ``0.5 atan2(2 m_xy, m_xx - m_yy)`` about the weighted centroid; the same estimator as
    :func:`ballbench.lowmodel.contact.halfspace.pressure_ellipse` (whose cell-size term is isotropic and
    does not change the angle).
    """
    total = float(np.sum(weight))
    if not total > 0.0:
        raise ValueError("weight must have a positive sum")
    xc, yc = float(np.sum(weight * x)) / total, float(np.sum(weight * y)) / total
    dx, dy = x - xc, y - yc
    mxx, myy, mxy = (float(np.sum(weight * f)) / total for f in (dx * dx, dy * dy, dx * dy))
    return 0.5 * math.atan2(2.0 * mxy, mxx - myy)


def fe_contact(helix_angle_deg: float, point: str, level, hertz_contact, gap_limit: float):
    """FE of the Table 1 contact at ``point`` with the exact meshed gap (P2 mortar, no Hertz or BEM gap given) at
    the mesh level ``(n = b/h, growth)``; candidate zone ``gap_limit`` times the Hertz approach.  Returns a dict
    of p0 [Pa], a, b [m], angle [rad] (major axis from the contact frame's x), force [N], ndofs, timings [s] and
    the quadrature pressure."""
    from ballbench.meshes.assemblies import screw_pair

    n, growth = level
    body, flank = POINTS[point]
    a, b = float(hertz_contact.a), float(hertz_contact.b)
    start = time.perf_counter()
    path = screw_pair.ball_in_screw_groove_pair(SCREW.ball_radius, SCREW.conformity, SCREW.pitch_radius,
                                                _lead(helix_angle_deg), SCREW.nominal_angle, body, h_contact=b / n,
                                                growth=growth, flank=flank, fine_radius=1.2 * b,
                                                fine_half_length=1.0 * a)
    meshed = time.perf_counter()
    model = build_mortar_model(path, SCREW.material.pair, gap_limit * float(hertz_contact.delta),
                               order=2)  # initial_gap None: the gap of the meshed surfaces
    built = time.perf_counter()
    state = contact.solve_force(model, contact_load(), tol=1e-10)
    solved = time.perf_counter()
    fit = hertz_case.fit_contact_patch(model, state)
    postprocess.mesh_check(hertz_case.contact_edge_length(model, state.active), min(fit.a, fit.b))
    xq, matrix = postprocess.force_operator(model.pair.points, model.pair.surfaces["ball_contact"], model.candidates)
    weight = np.asarray(matrix.sum(axis=0)).ravel()  # quadrature weights [m^2]
    pressure_q = (matrix.T @ state.pressure) / np.where(weight > 0, weight, 1.0)  # the P1 mortar pressure at xq
    angle = second_moment_angle(xq[:, 0], xq[:, 1], weight * pressure_q)
    return {"p0": fit.p0, "a": fit.a, "b": fit.b, "centre": (fit.x0, fit.y0), "angle": angle, "force": state.force,
            "ndofs": model.ndofs, "xq": xq, "pressure_q": pressure_q,
            "timings": {"mesh_s": meshed - start, "model_s": built - meshed, "contact_s": solved - built}}
