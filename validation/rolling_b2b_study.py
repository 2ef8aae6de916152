"""The model ladder of the B2B force with stick/slip ball-to-groove contacts (docs/b2b_rolling.md): the runs
behind the scenes of ``validation/scenes/rolling_b2b.py``.

lin2019's two-ball modules (linear bearing Sec 2.4-2.5, Tables 1-3; ball screw Sec 3.3, Tables 4-5), every
rung on the same case:

* analytical (lin2019 eq 30, linear bearing) and the low-order full-slip models (eqs 4-10, 54-61);
* stick/slip on two half-spaces with Hertz's pressure (``b2b_rolling``, grids of ``HERTZ_CELLS``) and its
  full-slip limit on the same cells;
* FE-informed full slip (``b2b_traction`` on the FE module's pressure, the ``fe-b2b-*`` scenes' model);
* stick/slip with the FE pressure on two half-spaces, and on the FE compliance of a ball-in-groove pair
  condensed onto one grid that holds every contact of the module (``fem.rolling_compliance``, cached on disk).

Thin versions of what the ``fe-b2b-*`` scene modules and ``lin2019_screw`` hold today (the FE module runs, the
screw's preload fit and axial shares; nothing may import a scene module): the same inputs
(:mod:`validation.papers.lin2019`), the same mesh levels and constants, called through ``fem`` and ``lowmodel``
directly.  To be unified with the shared run logic of ``validation/studies`` when it lands.
"""
from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.linear_bearing import b2b as linear_b2b
from ballbench.lowmodel.linear_bearing import b2b_rolling as linear_rolling
from ballbench.lowmodel.linear_bearing import b2b_traction as linear_traction
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_rolling
from ballbench.lowmodel.screw import b2b_traction as screw_traction
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.papers import lin2019

T1, T4, CASE = lin2019.TABLE1, lin2019.TABLE4, lin2019.CASE
PRINTED_LINEAR = lin2019.PRINTED
PRINTED_SCREW = {"a": lin2019.TABLE5_A, "b": lin2019.TABLE5_B}
AXIAL_LOAD = lin2019.WHOLE_SCREW.axial_load_two_ball  # N on the screw (lin2019 Sec 3.3)
READING = "tilted"  # lin2019 Fig 17 as docs/ball_screw.md reads it

# cells (along the groove, across it) of the per-contact grids of the half-space rungs
HERTZ_CELLS = {"quick": (12, 48), "default": (20, 80), "fine": (30, 120)}
# The FE module levels of the fe-b2b scenes (validation/scenes/fe_b2b.py, fe_b2b_screw.py): (h_contact, growth,
# fine_radius) [m] (linear, elliptic fine slabs FINE_ELLIPSE) and (h_contact, growth, fine_radius, h_max) (screw).
LINEAR_FE = {"quick": (4.0e-5, 1.4, 1.5e-4), "default": (3.0e-5, 1.35, 1.5e-4), "fine": (3.0e-5, 1.35, 1.5e-4)}
LINEAR_FINE_ELLIPSE = (0.6, 1.3, 0.5)
LINEAR_GAP_LIMIT = 6e-6
SCREW_FE = {"quick": (4.0e-5, 1.5, 1.5e-4, 1.0e-3), "default": (3.0e-5, 1.4, 1.5e-4, 1.0e-3),
            "fine": (3.0e-5, 1.4, 1.5e-4, 1.0e-3)}
SCREW_GAP_LIMIT = 5e-6
# The FE compliance grids: one grid holds every contact of the module, (cells along, across, h_contact / cell);
# the grid spans COVER (along, across) times the largest Hertz semi-axes of the product's two cases: the FE pressure
# reaches about one element beyond Hertz's ellipse (40 um at the quick level: 1.4 b for the linear module's
# b = 102 um, 1.6 b for the screw's b = 65-70 um); a piecewise-linear tail beyond the grid's inner cells may carry
# at most the share OUTSIDE of a contact's force (dropped, the force restored).  The fine level condenses two
# grids (mesh convergence of the rung).
COMPLIANCE_LEVELS = {"quick": [(6, 24, 1.0)], "default": [(8, 32, 0.8)], "fine": [(6, 24, 1.0), (8, 32, 0.8)]}
COVER = {"linear": (1.4, 1.15), "screw": (1.7, 1.2)}
OUTSIDE = 2e-3
E_STEEL, NU_STEEL = T1.youngs_modulus, T1.poisson_ratio


def level_name(cells) -> str:
    return f"{cells[0]} x {cells[1]} cells"


# --------------------------------------------------------------------------
# linear bearing (lin2019 Sec 2.4-2.5, Table 1-3)
# --------------------------------------------------------------------------
def linear_deviations(case: str) -> tuple:
    """(BL, BR, TR, TL) contact angle deviations [rad] of lin2019 Table 2 case ``case``."""
    top = (0.0, 0.0) if case == "a" else (-CASE.theta, CASE.theta)
    return (-CASE.theta, CASE.theta) + top


def linear_contacts(case: str, *, friction_coefficient: float = T1.friction_coefficient, theta: float = CASE.theta,
                    conformity: float = T1.conformity, vertical_force: float = T1.vertical_force,
                    side_force_ratio: float = CASE.side_force_ratio):
    top = (0.0, 0.0) if case == "a" else (-theta, theta)
    return linear_b2b.module_contacts(theta, side_force_ratio, top_deviations=top, vertical_force=vertical_force,
                                      ball_radius=T1.ball_radius, conformity=conformity,
                                      friction_coefficient=friction_coefficient, groove_velocity=T1.groove_velocity,
                                      youngs_modulus=E_STEEL, poisson_ratio=NU_STEEL)


def linear_side(ball: int) -> float:
    """N_x [N] of ball ``ball`` (0 behind: rho N_y; 1: -rho N_y; lin2019 Fig 7)."""
    return (1.0 if ball == 0 else -1.0) * CASE.side_force_ratio * T1.vertical_force


def linear_fe(case: str, level: str):
    """The FE four-point module of ``case`` at ``level`` solved for both balls' loads: ``(model, results, seconds)``
    (the run of validation/scenes/fe_b2b.py: one mesh and condensation, two contact solves)."""
    from ballbench.fem import fourpoint as fp
    from ballbench.lowmodel.contact import hertz
    from ballbench.lowmodel.linear_bearing import fourpoint as rigid
    from ballbench.meshes.assemblies.fourpoint_module import fourpoint_module

    h_contact, growth, fine_radius = LINEAR_FE[level]
    start = time.perf_counter()
    deviations = linear_deviations(case)
    angles = CASE.nominal_angle + np.asarray(deviations)
    geometry = hertz.ball_in_groove(T1.ball_radius, T1.conformity, youngs_modulus=E_STEEL, poisson_ratio=NU_STEEL)
    refs = [hertz.solve_load(geometry, rigid.normal_forces(linear_side(b), T1.vertical_force, angles)) for b in (0, 1)]
    a = np.maximum(np.asarray(refs[0].a), np.asarray(refs[1].a))
    b = np.maximum(np.asarray(refs[0].b), np.asarray(refs[1].b))
    k1, k2, k3 = LINEAR_FINE_ELLIPSE
    slabs = [(k1 * float(a_i), k2 * float(b_i), k3 * float(b_i)) for a_i, b_i in zip(a, b)]
    path = fourpoint_module(T1.ball_radius, T1.conformity, CASE.nominal_angle, deviations, 1, h_contact=h_contact,
                            growth=growth, fine_radius=fine_radius, fine_ellipses=slabs)
    module_geometry = fp.ModuleGeometry(T1.ball_radius, T1.conformity, tuple(angles))
    model = fp.build_module_model(path, module_geometry, materials=(E_STEEL, NU_STEEL), gap_limit=LINEAR_GAP_LIMIT)
    results = [fp.solve(model, linear_side(b), T1.vertical_force) for b in (0, 1)]
    return model, results, time.perf_counter() - start


def pressure_samples(model, result) -> list:
    """The solved FE contacts as ``(name, top, points (q, 3) [m], pressure (q,) [Pa], areas (q,) [m^2])`` in the
    ball frame of the lowmodel (``model.geometry.to_ball_frame``: lin2019 Fig 2, or the ball's CS3)."""
    geometry = model.geometry
    return [(c.name, geometry.moving(i), geometry.to_ball_frame(c.points), np.clip(c.pressure, 0.0, None), c.areas)
            for i, c in enumerate(result.contacts)]


def fe_patches(model, results) -> list:
    from ballbench.fem import fourpoint as fp

    return [fp.traction_patches(model, r) for r in results]


def compliance(product: str, cells_along: int, cells_across: int, h_factor: float):
    """The FE compliance of a ball in a straight groove of the product's conformity (``"linear"``: lin2019
    Table 1, ``"screw"``: Table 4) condensed onto the grid that holds every contact of the product's Table cases:
    ``(grid, RollingCompliance, seconds)`` (:func:`pair_compliance`)."""
    along, across = largest_semi_axes(product)
    cover = COVER[product]
    radius = T1.ball_radius if product == "linear" else T4.ball_radius
    conformity = T1.conformity if product == "linear" else T4.conformity
    return pair_compliance(radius, conformity, cover[0] * along, cover[1] * across, cells_along, cells_across,
                           h_factor)


@lru_cache(maxsize=8)
def pair_compliance(radius: float, conformity: float, along: float, across: float, cells_along: int,
                    cells_across: int, h_factor: float):
    """The FE compliance of a ball (``radius`` [m]) in a straight groove of ``conformity`` condensed onto the grid of
    ``cells`` over the half-widths ``along`` x ``across`` [m] (``fem.rolling_compliance``, disk-cached; P2, the
    contact-pair mesh with its fine slab over the grid, element size ``h_factor`` cells): ``(grid,
    RollingCompliance, seconds)``.  The pair (the groove straight, its block 0.6 R_B deep) stands for every contact
    of a module: the steady-state operator ``(W(x) - W(x + dx)) / dx`` does not see the far field (the module's
    other contacts, its truncated bodies), only the local shape of ball and groove (docs/b2b_rolling.md)."""
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    grid = rolling.hertz_grid(along, across, (cells_along, cells_across))
    start = time.perf_counter()
    # the pair mesh: x across the groove (Kalker's -y), y along it (Kalker's x); the fine slab over the grid, as
    # thick as about half the contacts' semi-axis along the groove
    path = contact_pairs.ball_in_groove_pair(radius, conformity, h_factor * min(grid.dx, grid.dy), 1.3,
                                             symmetry="full", element_order=2,
                                             fine_ellipse=(across + grid.dy, along + grid.dx, 0.35 * along))
    result = rolling_compliance.condense(path, (E_STEEL, NU_STEEL), grid, order=2, cache=True)
    return grid, result, time.perf_counter() - start


@lru_cache(maxsize=2)
def largest_semi_axes(product: str) -> tuple[float, float]:
    """(along, across) [m]: the largest Hertz semi-axes of the product's two cases (low-order contacts)."""
    if product == "linear":
        rows = [linear_contacts(case) for case in ("a", "b")]
        along = max(float((c.semi_major * c.b_over_a).max()) for c in rows)
        across = max(float(c.semi_major.max()) for c in rows)
        return along, across
    along = across = 0.0
    for case in ("a", "b"):
        contacts, _, state = screw_low_order(case)
        along = max(along, float((state.semi_major * contacts.b_over_a).max()))
        across = max(across, float(state.semi_major.max()))
    return along, across


# --------------------------------------------------------------------------
# ball screw (lin2019 Sec 3.3, Tables 4-5)
# --------------------------------------------------------------------------
def table4_module(oversize: float, friction_coefficient: float = T4.friction_coefficient,
                  conformity: float = T4.conformity) -> screw_contacts.ScrewModule:
    """lin2019 Table 4 with the preload ``oversize`` [m] (validation/scenes/lin2019_screw.py's table4_module)."""
    return screw_contacts.screw_module(ball_radius=T4.ball_radius, conformity=conformity, pitch_radius=T4.pitch_radius,
                                       lead=T4.lead, nominal_angle=T4.nominal_angle, nut_speed=T4.nut_angular_velocity,
                                       friction_coefficient=friction_coefficient, oversize=oversize, **T4.material)


def screw_two_ball(theta: float, oversize: float, **module_options):
    """(contacts, free, touching) low-order states of the two-ball module: ball 1 theta 0, ball 2 ``theta``."""
    contacts = screw_contacts.ball_contacts(table4_module(oversize, **module_options), np.array([0.0, theta]),
                                            reading=READING)
    free = screw_b2b.solve(contacts, AXIAL_LOAD, with_b2b=False)
    return contacts, free, screw_b2b.solve(contacts, AXIAL_LOAD)


@lru_cache(maxsize=1)
def fitted_oversize() -> float:
    """The preload of docs/ball_screw.md: the oversize [m] at which the low-order case (a) gives the paper's 1.92 N
    (brentq, 1e-12 m; lin2019_screw.fitted_oversize)."""
    from scipy.optimize import brentq

    target = PRINTED_SCREW["a"].f_b2b_numerical
    theta = PRINTED_SCREW["a"].theta
    return float(brentq(lambda o: screw_two_ball(theta, o)[2].b2b_force[0] - target, 1.0e-6, 3.0e-6, xtol=1e-12))


@lru_cache(maxsize=4)
def screw_low_order(case: str):
    """(contacts, free, touching) of Table 5 case ``case`` at the fitted preload."""
    return screw_two_ball(PRINTED_SCREW[case].theta, fitted_oversize())


def axial_shares(contacts, state) -> np.ndarray:
    """(n,) N: each ball's axial load, the force of its screw contacts (normal + friction) along the screw axis."""
    alpha = contacts.module.lead_angle
    z_hat = np.array([0.0, math.sin(alpha), math.cos(alpha)])
    angles = state.contact_angle[:, :2]
    e = np.stack([-np.cos(angles), np.zeros_like(angles), np.array([-1.0, 1.0]) * np.sin(angles)], axis=-1)
    normal = -state.normal_force[:, :2, None] * e
    return ((normal + state.friction_force[:, :2]) @ z_hat).sum(axis=1)


def screw_fe(case: str, level: str):
    """One FE screw module per ball of Table 5 case ``case`` at ``level`` (ball 1 theta 0, ball 2 theta), each
    carrying its low-order axial share: ``(models, results, seconds)`` (the run of fe_b2b_screw.py)."""
    from ballbench.fem import screw_module as sm
    from ballbench.meshes.assemblies.ball_screw_module import ball_screw_module
    from ballbench.meshes.parts.groove_segment import BODY_DEPTH

    contacts, _, state = screw_low_order(case)
    shares = axial_shares(contacts, state)
    h_contact, growth, fine_radius, h_max = SCREW_FE[level]
    start = time.perf_counter()
    models, results = [], []
    for ball, theta in enumerate((0.0, PRINTED_SCREW[case].theta)):
        path = ball_screw_module(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead, T4.nominal_angle,
                                 (theta, theta, 0.0, 0.0), 1, h_contact=h_contact, growth=growth,
                                 fine_radius=fine_radius, h_max=h_max,
                                 screw_back_radius=T4.pitch_radius - BODY_DEPTH * T4.ball_radius,
                                 nut_back_radius=T4.pitch_radius + BODY_DEPTH * T4.ball_radius)
        geometry = sm.screw_module_geometry(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead,
                                            sm.flank_angles_tilted(T4.nominal_angle, theta), fitted_oversize())
        model = sm.build_screw_model(path, geometry, materials=(E_STEEL, NU_STEEL), gap_limit=SCREW_GAP_LIMIT)
        results.append(sm.solve(model, float(shares[ball])))
        models.append(model)
    return models, results, time.perf_counter() - start


# --------------------------------------------------------------------------
# the ladder
# --------------------------------------------------------------------------
@dataclass
class Rung:
    """One model of the ladder: F_B2B [N], friction increase [%], wall time [s], per-contact rows, the state."""

    model: str
    family: str
    level: str
    b2b_force: float
    friction_increase: float
    time_s: float
    full_slip_force: float = math.nan  # the full-slip limit on the same cells (stick/slip rungs)
    full_slip_increase: float = math.nan
    power_balance: float = 0.0
    contacts: tuple = ()  # per ball the ContactSummary tuple of the touching stick/slip state
    b2b_check: tuple = (math.nan, math.nan)


def rolling_rung(model: str, family: str, level: str, result, seconds: float, b2b_check=(math.nan, math.nan)) -> Rung:
    return Rung(model, family, level, float(result.b2b_force[0]), float(result.friction_increase), seconds,
                float(result.full_slip.b2b_force[0]), float(result.full_slip_increase), float(result.power_balance),
                result.touching.contacts, b2b_check)


def linear_ladder(case: str, level: str, *, progress=lambda x, desc="": x, with_fe: bool = True) -> list[Rung]:
    """Every rung of the linear bearing's ladder for Table 2/3 case ``case`` at fidelity ``level``."""
    from ballbench.lowmodel.contact import hertz
    from ballbench.lowmodel.linear_bearing import b2b_analytical

    rungs = []
    contacts = linear_contacts(case)
    linear_b2b.solve(contacts, [0.0])  # the friction map's disk cache, outside the timed calls
    common = dict(ball_radius=T1.ball_radius, friction_coefficient=T1.friction_coefficient,
                  groove_velocity=T1.groove_velocity)
    if case == "a":
        geometry = hertz.ball_in_groove(T1.ball_radius, T1.conformity, youngs_modulus=E_STEEL, poisson_ratio=NU_STEEL)
        start = time.perf_counter()
        analytical = b2b_analytical.two_ball_case(CASE.theta, CASE.side_force_ratio, normal_load=T1.vertical_force,
                                                  groove_velocity=T1.groove_velocity,
                                                  friction_coefficient=T1.friction_coefficient,
                                                  psi=hertz.psi_constant(geometry, T1.ball_radius),
                                                  ball_radius=T1.ball_radius)
        rungs.append(Rung("lowmodel.linear_bearing.b2b_analytical", "analytical", "", float(analytical.b2b_force),
                          math.nan, time.perf_counter() - start))
    start = time.perf_counter()
    low = linear_b2b.solve(contacts, [0.0])
    seconds = time.perf_counter() - start
    free = linear_b2b.solve(contacts, [1e-3])
    rungs.append(Rung("lowmodel.linear_bearing.b2b", "low-order numerical", "", float(low.b2b_force[0]),
                      100.0 * (low.total_loss / free.total_loss - 1.0), seconds))
    cells = HERTZ_CELLS[level]
    start = time.perf_counter()
    balls = [linear_rolling.hertz_contacts(contacts, j, cells=cells, conformity=T1.conformity, youngs_modulus=E_STEEL,
                                           poisson_ratio=NU_STEEL) for j in range(2)]
    result = linear_rolling.module_b2b(balls, **common)
    seconds = time.perf_counter() - start
    check = linear_rolling.b2b_contact_check(result.touching, ball_radius=T1.ball_radius,
                                             friction_coefficient=T1.friction_coefficient, youngs_modulus=E_STEEL,
                                             poisson_ratio=NU_STEEL)
    rungs.append(rolling_rung("b2b_rolling stick/slip, Hertz + half-space", "BEM", level_name(cells), result, seconds,
                              check))
    if not with_fe:
        return rungs
    model, results, fe_s = linear_fe(case, level)
    h_um = LINEAR_FE[level][0] * 1e6
    start = time.perf_counter()
    full = linear_traction.solve(fe_patches(model, results), **common)
    free_full = linear_traction.solve(fe_patches(model, results), gaps=[1e-3], **common)
    rungs.append(Rung("b2b_traction full slip, FE pressure", "FE-informed", f"h {h_um:.0f} um",
                      float(full.b2b_force[0]), 100.0 * (full.total_loss / free_full.total_loss - 1.0),
                      fe_s + time.perf_counter() - start, power_balance=float(full.power_balance)))
    samples = [pressure_samples(model, r) for r in results]
    start = time.perf_counter()
    balls = [linear_rolling.sampled_contacts(s, ball_radius=T1.ball_radius, conformity=T1.conformity, cells=cells,
                                             youngs_modulus=E_STEEL, poisson_ratio=NU_STEEL) for s in samples]
    result = linear_rolling.module_b2b(balls, **common)
    rungs.append(rolling_rung("b2b_rolling stick/slip, FE pressure + half-space", "FE-informed",
                              f"h {h_um:.0f} um, {level_name(cells)}", result, fe_s + time.perf_counter() - start))
    for along, across, h_factor in progress(COMPLIANCE_LEVELS[level], desc="FE compliance levels"):
        grid, fe_compliance, condense_s = compliance("linear", along, across, h_factor)
        operator = fe_compliance.operator()
        start = time.perf_counter()
        for label, op in (("FE compliance", operator), ("half-space, FE compliance grid", None)):
            balls = [linear_rolling.sampled_contacts(s, ball_radius=T1.ball_radius, conformity=T1.conformity,
                                                     grid=grid, operator=op, youngs_modulus=E_STEEL,
                                                     poisson_ratio=NU_STEEL, outside=OUTSIDE) for s in samples]
            result = linear_rolling.module_b2b(balls, **common)
            family = "FE-informed"
            rungs.append(rolling_rung(f"b2b_rolling stick/slip, FE pressure + {label}", family,
                                      f"h {h_um:.0f} um, {level_name((along, across))}, {fe_compliance.ndofs} DOFs",
                                      result, fe_s + condense_s + time.perf_counter() - start))
    return rungs


def screw_ladder(case: str, level: str, *, progress=lambda x, desc="": x, with_fe: bool = True) -> list[Rung]:
    """Every rung of the ball screw's ladder for Table 5 case ``case`` at fidelity ``level``."""
    rungs = []
    start = time.perf_counter()
    contacts, free, state = screw_low_order(case)
    seconds = time.perf_counter() - start
    module = table4_module(fitted_oversize())
    rungs.append(Rung("lowmodel.screw.b2b", "low-order numerical", "", float(state.b2b_force[0]),
                      100.0 * (state.total_loss / free.total_loss - 1.0), seconds))
    cells = HERTZ_CELLS[level]
    start = time.perf_counter()
    balls = [screw_rolling.hertz_contacts(state, contacts, j, cells=cells) for j in range(2)]
    result = screw_rolling.module_b2b(balls, module)
    rungs.append(rolling_rung("b2b_rolling stick/slip, Hertz + half-space", "BEM", level_name(cells), result,
                              time.perf_counter() - start))
    if not with_fe:
        return rungs
    models, results, fe_s = screw_fe(case, level)
    h_um = SCREW_FE[level][0] * 1e6
    start = time.perf_counter()
    full = screw_traction.module_b2b(fe_patches_screw(models, results), module)
    rungs.append(Rung("screw.b2b_traction full slip, FE pressure", "FE-informed", f"h {h_um:.0f} um",
                      float(full.b2b_force[0]), float(full.friction_increase), fe_s + time.perf_counter() - start,
                      power_balance=float(full.power_balance)))
    samples = [pressure_samples(m, r) for m, r in zip(models, results)]
    start = time.perf_counter()
    balls = [screw_rolling.sampled_contacts(s, module, cells=cells) for s in samples]
    result = screw_rolling.module_b2b(balls, module)
    rungs.append(rolling_rung("b2b_rolling stick/slip, FE pressure + half-space", "FE-informed",
                              f"h {h_um:.0f} um, {level_name(cells)}", result, fe_s + time.perf_counter() - start))
    for along, across, h_factor in progress(COMPLIANCE_LEVELS[level], desc="FE compliance levels"):
        grid, fe_compliance, condense_s = compliance("screw", along, across, h_factor)
        operator = fe_compliance.operator()
        start = time.perf_counter()
        for label, op in (("FE compliance", operator), ("half-space, FE compliance grid", None)):
            balls = [screw_rolling.sampled_contacts(s, module, grid=grid, operator=op, outside=OUTSIDE)
                     for s in samples]
            result = screw_rolling.module_b2b(balls, module)
            rungs.append(rolling_rung(f"b2b_rolling stick/slip, FE pressure + {label}", "FE-informed",
                                      f"h {h_um:.0f} um, {level_name((along, across))}, {fe_compliance.ndofs} DOFs",
                                      result, fe_s + condense_s + time.perf_counter() - start))
    return rungs


def fe_patches_screw(models, results) -> list:
    from ballbench.fem import fourpoint as fp

    return [fp.traction_patches(m, r) for m, r in zip(models, results)]


def write_rungs(path, rungs: list[Rung]) -> None:
    """ladder.csv: one row per rung."""
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["model", "family", "level", "F_B2B_N", "friction_increase_pct", "full_slip_same_cells_N",
                         "full_slip_increase_pct", "stick_slip_minus_full_slip_pct", "power_balance", "time_s",
                         "b2b_contact_F_over_muF", "b2b_contact_creepage_parameter"])
        for r in rungs:
            diff = 100.0 * (r.b2b_force / r.full_slip_force - 1.0) if r.full_slip_force > 0 else math.nan
            writer.writerow([r.model, r.family, r.level, f"{r.b2b_force:.5f}", f"{r.friction_increase:.3f}",
                             f"{r.full_slip_force:.5f}", f"{r.full_slip_increase:.3f}", f"{diff:.4f}",
                             f"{r.power_balance:.2e}", f"{r.time_s:.2f}", f"{r.b2b_check[0]:.7f}",
                             f"{r.b2b_check[1]:.4g}"])


def write_contacts(path, rungs: list[Rung]) -> None:
    """contacts.csv: every contact of every stick/slip rung (touching state)."""
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["model", "level", "ball", "contact", "F_N", "Lambda", "creepage_parameter", "stick_fraction",
                         "along_groove_over_muF", "lateral_over_muF", "spin_moment_Nm", "rigid_power_W"])
        for r in rungs:
            for ball, row in enumerate(r.contacts):
                for c in row:
                    scale = T1.friction_coefficient * c.normal_force
                    writer.writerow([r.model, r.level, ball + 1, c.name, f"{c.normal_force:.3f}",
                                     f"{c.spin_parameter:.2f}", f"{c.creepage:.3f}", f"{c.stick_fraction:.4f}",
                                     f"{c.along_groove / scale:+.5f}", f"{c.lateral / scale:+.5f}",
                                     f"{c.spin_moment:+.5e}", f"{c.rigid_power:.5e}"])


def contact_note(rung: Rung) -> str:
    """Per contact of ball 1 and 2: Lambda and stick fraction, e.g. ``BL 57/0.000``."""
    parts = []
    for ball, row in enumerate(rung.contacts):
        parts.append(f"ball {ball + 1}: " + ", ".join(f"{c.name} Lambda {c.spin_parameter:.0f} stick "
                                                       f"{c.stick_fraction:.3f}" for c in row))
    return "; ".join(parts)



# --------------------------------------------------------------------------
# the checks of the scenes (validation/scenes/rolling_b2b.py)
# --------------------------------------------------------------------------
POWER_WHY = "the value is itself a relative power error |P_in - P_loss| / P_in: zero judged on the scale 1"
FULL_SLIP_TOLERANCE = 0.01  # the validity map: at Lambda ~ 60 full slip is within 1 % of stick/slip (docs)
CASE_B_FE_TOLERANCE = 0.01  # the fe-b2b scenes' bound on an FE-informed case (b) force (the FE's asymmetry)
TIME_BUDGET_S = {"quick": 120.0, "default": 600.0, "fine": 3000.0}  # per stick/slip scene (the limits)


def record_ladder(run, product: str, case: str) -> list[Rung]:
    """Run the ladder of ``product`` ("linear" or "screw") for ``case`` at ``run.fidelity`` and record its checks,
    ladder.csv, contacts.csv and the notes."""
    level = run.fidelity
    start = time.perf_counter()
    ladder = linear_ladder if product == "linear" else screw_ladder
    rungs = ladder(case, level, progress=lambda it, desc="": run.progress(it, desc=desc))
    wall = time.perf_counter() - start
    if product == "linear":
        printed_low = PRINTED_LINEAR.f_b2b_numerical
        ansys = PRINTED_LINEAR.f_b2b_ansys if case == "a" else 0.0
        tolerance, source = 0.07, f"lin2019 Table 3 case ({case}), ANSYS FEA"
        scale = PRINTED_LINEAR.f_b2b_numerical
        increase_ref = None
    else:
        printed = PRINTED_SCREW[case]
        printed_low, ansys = printed.f_b2b_numerical, printed.f_b2b_ansys
        tolerance, source = 0.10, f"lin2019 Table 5 case ({case}), ANSYS FEA"
        scale = 0.0
        increase_ref = printed.friction_increase
    for rung in rungs:
        stick_slip = not math.isnan(rung.full_slip_force)
        fe = rung.family == "FE-informed"
        note = f"{rung.time_s:.1f} s"
        if stick_slip:
            diff = 100.0 * (rung.b2b_force / rung.full_slip_force - 1.0) if rung.full_slip_force > 0 else 0.0
            lam = [c.spin_parameter for row in rung.contacts for c in row]
            stick = [c.stick_fraction for row in rung.contacts for c in row]
            note += (f"; full slip on the same cells {rung.full_slip_force:.4f} N (stick/slip {diff:+.3f} %); Lambda "
                     f"{min(lam):.0f}-{max(lam):.0f}, stick fraction up to {max(stick):.4f}")
        if ansys > 0.0:
            run.check(model=rung.model, quantity="F_B2B", unit="N", value=rung.b2b_force, reference=ansys,
                      source=source, tolerance=tolerance, time_s=rung.time_s, family=rung.family, level=rung.level,
                      note=note + f"; lin2019's own low-order model is within {100 * tolerance:g} % (its claim)")
        else:
            run.check(model=rung.model, quantity="F_B2B", unit="N", value=rung.b2b_force, reference=0.0, scale=scale,
                      tolerance=CASE_B_FE_TOLERANCE if fe else 1e-9, source=source + " (no B2B contact)",
                      time_s=rung.time_s, family=rung.family, level=rung.level,
                      why="zero force judged against the case (a) force 4.01 N",
                      note=note + ("; FE: zero holds by the pi-rotation symmetry of case (b), which the independently "
                                   "meshed rails keep only to the discretisation error (as fe-b2b-linear-b)"
                                   if fe else ""))
        if rung.family == "low-order numerical" and not (product == "screw" and case == "a") and ansys > 0.0:
            run.check(model=rung.model, quantity="F_B2B (the paper's low-order value)", unit="N",
                      value=rung.b2b_force, reference=printed_low, tolerance=0.05 if product == "screw" else 0.03,
                      source=f"lin2019 Table {'3' if product == 'linear' else '5'} case ({case}), low-order numerical",
                      time_s=rung.time_s, family=rung.family)
        if increase_ref is not None and not math.isnan(rung.friction_increase):
            run.check(model=rung.model, quantity="friction increase by B2B", unit="%", value=rung.friction_increase,
                      reference=increase_ref, tolerance=3.0 / increase_ref, time_s=rung.time_s, family=rung.family,
                      level=rung.level, source="lin2019 Sec 3.3 (the paper's low-order value; no FE value printed)",
                      note="tolerance 3 points")
        if stick_slip:
            run.check(model=rung.model, quantity="power balance, worst of the four solves", unit="1",
                      value=rung.power_balance, reference=0.0, scale=1.0, tolerance=1e-6, time_s=rung.time_s,
                      family=rung.family, level=rung.level, why=POWER_WHY,
                      source="input power = rigid power of every contact + B2B loss (lin2019 eqs 7, 58)")
            if rung.full_slip_force > 0.0:
                run.check(model=rung.model, quantity="F_B2B against full slip on the same cells", unit="N",
                          value=rung.b2b_force, reference=rung.full_slip_force, tolerance=FULL_SLIP_TOLERANCE,
                          time_s=rung.time_s, family=rung.family, level=rung.level,
                          source="the full-slip limit of the same contacts (pointwise Coulomb, b2b_traction); the "
                                 "validity map's 1 % at Lambda >= 50 (docs/b2b_rolling.md)",
                          note=contact_note(rung))
        if not math.isnan(rung.b2b_check[0]):
            run.check(model=rung.model, quantity="B2B contact as a rolling contact: |F| / (mu F_B2B)", unit="1",
                      value=rung.b2b_check[0], reference=1.0, tolerance=1e-4, time_s=rung.time_s, family=rung.family,
                      level=rung.level, source="lin2019 eq 6: full sliding at the B2B contact",
                      note=f"creepage parameter |dv|/V G/(mu p0) = {rung.b2b_check[1]:.3g} (the surfaces move in "
                           "opposite directions: full sliding)")
    run.budget(model="scene", quantity="wall time of the ladder", unit="s", value=wall,
               budget=TIME_BUDGET_S[level], source="the issue's limit per stick/slip scene at this level")
    write_rungs(run.path("ladder.csv"), rungs)
    write_contacts(run.path("contacts.csv"), rungs)
    run.add_artifact(run.path("ladder.csv"))
    run.add_artifact(run.path("contacts.csv"))
    run.note("Ladder (ladder.csv; per contact: contacts.csv): " + "; ".join(
        f"{r.model} [{r.level or r.family}]: F_B2B {r.b2b_force:.4f} N"
        + ("" if math.isnan(r.full_slip_force) else f" (full slip on the same cells {r.full_slip_force:.4f} N)")
        + ("" if math.isnan(r.friction_increase) else f", increase {r.friction_increase:.2f} %")
        + f", {r.time_s:.1f} s" for r in rungs))
    return rungs


# --------------------------------------------------------------------------
# the validity map of full slip (lowmodel.full_slip_validity)
# --------------------------------------------------------------------------
MAP_GRID = {
    "quick": dict(mu=(0.1, 0.5), conformity=(0.52, 0.6), theta_deg=(3.0,), linear_load=(100.0,), screw_load=(50.0,)),
    "default": dict(mu=(0.05, 0.1, 0.2, 0.35, 0.5), conformity=(0.51, 0.53, 0.56, 0.6), theta_deg=(1.0, 3.0),
                    linear_load=(10.0, 100.0, 1000.0), screw_load=(10.0, 50.0, 200.0)),
}
MAP_GRID["fine"] = MAP_GRID["default"]
MAP_CELLS = (8, 32)


def validity_points(level: str, progress=None) -> list:
    """The map's points of both products at ``level`` (MAP_GRID; Hertz contacts of MAP_CELLS)."""
    from ballbench.lowmodel import full_slip_validity as fsv

    grid = MAP_GRID[level]
    thetas = [math.radians(t) for t in grid["theta_deg"]]
    points = fsv.validity_map("linear", grid["mu"], grid["conformity"], thetas, grid["linear_load"],
                              progress=progress, cells=MAP_CELLS)
    points += fsv.validity_map("screw", grid["mu"], grid["conformity"], thetas, grid["screw_load"],
                               progress=progress, cells=MAP_CELLS, oversize=fitted_oversize())
    return points


def write_points(path, points) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["product", "mu", "conformity", "theta_deg", "load_N", "Lambda_min", "creepage_parameter_min",
                         "stick_fraction_max", "F_B2B_stick_slip_N", "F_B2B_full_slip_N", "b2b_difference_pct",
                         "friction_difference_pct", "friction_increase_pct", "friction_increase_full_slip_pct",
                         "time_s", "error"])
        for p in points:
            q = p.parameters
            writer.writerow([p.product, q["mu"], q["conformity"], f"{math.degrees(q['theta']):g}", q["load"],
                             f"{p.spin_parameter:.3f}", f"{p.creepage_parameter:.3f}", f"{p.stick_fraction:.4f}",
                             f"{p.b2b_force:.5f}", f"{p.b2b_force_full_slip:.5f}", f"{100 * p.b2b_difference:+.4f}",
                             f"{100 * p.friction_difference:.4f}", f"{p.friction_increase:.3f}",
                             f"{p.friction_increase_full_slip:.3f}", f"{p.time_s:.2f}", p.error[:200]])


def map_figure(points):
    """Per product, the largest difference over deviation and load at each (mu, conformity): B2B force and a free
    ball's friction, with the 1 % and 5 % contours; and every point's difference against Lambda."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 5, figsize=(22, 4.4), layout="constrained")
    products = ("linear bearing", "ball screw")
    panels = [(p, key) for p in products for key in ("b2b_difference", "friction_difference")]
    for ax, (product, key) in zip(axes[:4], panels):
        rows = [p for p in points if p.product == product and not p.error]
        mus = sorted({p.parameters["mu"] for p in rows})
        fs = sorted({p.parameters["conformity"] for p in rows})
        value = np.full((len(fs), len(mus)), np.nan)
        for p in rows:
            i, j = fs.index(p.parameters["conformity"]), mus.index(p.parameters["mu"])
            value[i, j] = np.nanmax([value[i, j], 100.0 * abs(getattr(p, key))])
        image = ax.pcolormesh(mus, fs, value, shading="nearest", cmap="viridis", vmin=0.0,
                              vmax=max(5.0, float(np.nanmax(value))))
        if len(mus) > 1 and len(fs) > 1:
            lines = ax.contour(mus, fs, value, levels=[1.0, 5.0], colors=["w", "r"], linewidths=1.5)
            ax.clabel(lines, fmt="%g %%", fontsize=8)
        fig.colorbar(image, ax=ax, label="|full slip / stick-slip - 1| [%]")
        what = "B2B force" if key == "b2b_difference" else "free ball's friction"
        ax.set_title(f"{product}: {what}\n(largest over theta and load)", fontsize=10)
        ax.set_xlabel("friction coefficient mu")
        ax.set_ylabel("conformity")
    ax = axes[4]
    for product, marker in zip(products, ("o", "s")):
        rows = [p for p in points if p.product == product and not p.error]
        ax.semilogx([p.spin_parameter for p in rows], [100 * abs(p.b2b_difference) for p in rows], marker,
                    mfc="none", label=f"{product}: B2B force")
        ax.semilogx([p.spin_parameter for p in rows], [100 * p.friction_difference for p in rows], marker,
                    ms=3, label=f"{product}: free ball's friction")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.axhline(5.0, color="r", lw=0.8, ls="--")
    ax.set_xlabel("smallest spin parameter Lambda of the contacts")
    ax.set_ylabel("|full slip / stick-slip - 1| [%]")
    ax.legend(fontsize=7)
    ax.set_title("every case against Lambda", fontsize=10)
    return fig


def record_map(run) -> list:
    """The map's points, map.csv, map.png and the checks of the scene ``full-slip-validity-map``."""
    level = "quick" if run.fidelity == "quick" else "default"
    start = time.perf_counter()
    points = validity_points(level, progress=lambda it: run.progress(it, desc="validity map"))
    wall = time.perf_counter() - start
    write_points(run.path("map.csv"), points)
    run.add_artifact(run.path("map.csv"))
    run.save_figure(map_figure(points), "map.png")
    solved = [p for p in points if not p.error]
    failed = len(points) - len(solved)
    for product in ("linear bearing", "ball screw"):
        rows = [p for p in solved if p.product == product]
        worst = max(rows, key=lambda p: p.worst)
        q = worst.parameters
        run.check(model="lowmodel.full_slip_validity", quantity=f"{product}: largest |full slip / stick-slip - 1| "
                  "(B2B force or a free ball's friction)", unit="1", value=worst.worst, reference=0.0, scale=1.0,
                  relation="le", tolerance=0.05, time_s=wall, family="BEM", level=level_name(MAP_CELLS),
                  source="the issue's 5 % contour: where full slip is off by more, the low-order model's docs say so",
                  why="an upper bound on a relative difference (zero judged on the scale 1)",
                  note=f"at mu {q['mu']:g}, conformity {q['conformity']:g}, theta {math.degrees(q['theta']):g} deg, "
                       f"load {q['load']:g} N: B2B {100 * worst.b2b_difference:+.2f} %, friction "
                       f"{100 * worst.friction_difference:.2f} %, Lambda {worst.spin_parameter:.1f}; {len(rows)} "
                       f"cases solved")
    run.note(f"{len(points)} cases, {failed} without a quasi-static state of either law (map.csv, column error: "
             "light loads and high mu, where lin2019's full-sliding model has no state either).")
    return points


# --------------------------------------------------------------------------
# the worst case of the map (scene full-slip-validity)
# --------------------------------------------------------------------------
# The map's case where full slip is off the most (map.csv of full-slip-validity-map, docs/b2b_rolling.md): an input
# of the scene, found by the map.
WORST = dict(product="linear", mu=0.5, conformity=0.6, theta_deg=1.0, load=100.0)
WORST_CELLS = {"quick": [(8, 32)], "default": [(8, 32), (16, 64)], "fine": [(8, 32), (16, 64), (24, 96)]}
WORST_COMPLIANCE = {"quick": [], "default": [(8, 32, 0.8)], "fine": [(8, 32, 0.8)]}
WORST_TOLERANCE = 0.05  # the 5 % contour: the docs say where full slip is off by more


def worst_point(cells):
    from ballbench.lowmodel import full_slip_validity as fsv

    theta = math.radians(WORST["theta_deg"])
    if WORST["product"] == "linear":
        return fsv.linear_point(theta, friction_coefficient=WORST["mu"], conformity=WORST["conformity"],
                                vertical_force=WORST["load"], cells=cells)
    return fsv.screw_point(theta, friction_coefficient=WORST["mu"], conformity=WORST["conformity"],
                           axial_load=WORST["load"], cells=cells, oversize=fitted_oversize())


def worst_module(cells, operator_for=None):
    """The worst case's two-ball module with stick/slip contacts on ``cells`` (a SurfaceGrid for a fixed grid)."""
    theta = math.radians(WORST["theta_deg"])
    if WORST["product"] == "linear":
        contacts = linear_contacts("a", friction_coefficient=WORST["mu"], theta=theta,
                                   conformity=WORST["conformity"], vertical_force=WORST["load"])
        balls = [linear_rolling.hertz_contacts(contacts, j, cells=cells, conformity=WORST["conformity"],
                                               youngs_modulus=E_STEEL, poisson_ratio=NU_STEEL,
                                               operator_for=operator_for) for j in range(2)]
        along = float((contacts.semi_major * contacts.b_over_a).max())
        across = float(contacts.semi_major.max())
        return balls, (along, across), lambda: linear_rolling.module_b2b(
            balls, ball_radius=T1.ball_radius, friction_coefficient=WORST["mu"], groove_velocity=T1.groove_velocity)
    contacts, _, state = screw_two_ball(theta, fitted_oversize(), friction_coefficient=WORST["mu"],
                                        conformity=WORST["conformity"])
    balls = [screw_rolling.hertz_contacts(state, contacts, j, cells=cells, operator_for=operator_for)
             for j in range(2)]
    along = float((state.semi_major * contacts.b_over_a).max())
    across = float(state.semi_major.max())
    module = table4_module(fitted_oversize(), friction_coefficient=WORST["mu"], conformity=WORST["conformity"])
    return balls, (along, across), lambda: screw_rolling.module_b2b(balls, module)


def record_worst(run) -> None:
    """The checks of the scene ``full-slip-validity``: full slip against stick/slip at the map's worst case on
    refined grids, and the FE compliance's effect there."""
    q = WORST
    name = (f"{'linear bearing' if q['product'] == 'linear' else 'ball screw'}, mu {q['mu']:g}, conformity "
            f"{q['conformity']:g}, theta {q['theta_deg']:g} deg, load {q['load']:g} N")
    rows = []
    for cells in run.progress(WORST_CELLS[run.fidelity], desc="grids"):
        point = worst_point(cells)
        if point.error:
            raise RuntimeError(f"the worst case has no state on {level_name(cells)}: {point.error}")
        rows.append((cells, point))
        note = (f"{name}: B2B force {100 * point.b2b_difference:+.3f} % (F_B2B {point.b2b_force:.3f} N stick/slip, "
                f"{point.b2b_force_full_slip:.3f} N full slip), free ball's friction "
                f"{100 * point.friction_difference:.3f} %, friction increase {point.friction_increase:.1f} / "
                f"{point.friction_increase_full_slip:.1f} %, "
                f"Lambda {point.spin_parameter:.1f}, creepage parameter {point.creepage_parameter:.2f}, stick "
                f"fraction up to {point.stick_fraction:.3f}")
        run.check(model="lowmodel.full_slip_validity", quantity="|full slip / stick-slip - 1|, largest of the B2B "
                  "force and a free ball's friction", unit="1", value=point.worst, reference=0.0, scale=1.0,
                  relation="le", tolerance=WORST_TOLERANCE, time_s=point.time_s, family="BEM",
                  level=level_name(cells), why="an upper bound on a relative difference (zero judged on the scale 1)",
                  source="the validity map: no case of the models' domain reaches 5 % (docs/b2b_rolling.md)",
                  note=note)
    if len(rows) > 1:
        run.note("Grid convergence of the worst case's differences (B2B force, friction): " + "; ".join(
            f"{level_name(c)}: {100 * p.b2b_difference:+.3f} %, {100 * p.friction_difference:.3f} %"
            for c, p in rows))
    for along_cells, across_cells, h_factor in WORST_COMPLIANCE[run.fidelity]:
        radius = T1.ball_radius if WORST["product"] == "linear" else T4.ball_radius
        _, (along, across), _ = worst_module((8, 32))
        cover = COVER[WORST["product"]]
        grid, fe, condense_s = pair_compliance(radius, WORST["conformity"], cover[0] * along, cover[1] * across,
                                               along_cells, across_cells, h_factor)
        start = time.perf_counter()
        half = worst_module(grid)[2]()
        on_fe = worst_module(grid, operator_for=lambda g: fe.operator())[2]()
        seconds = time.perf_counter() - start + condense_s
        level = f"{level_name((along_cells, across_cells))}, P2, h {h_factor:g} cell, {fe.ndofs} DOFs"
        speed = abs(T1.groove_velocity) if WORST["product"] == "linear" else abs(T4.nut_angular_velocity)
        drag = [np.array([sum(c.drive_power for c in row) for row in r.free.contacts]) / speed for r in (half, on_fe)]
        for quantity, value, reference in (
                ("F_B2B, stick/slip on the FE compliance", float(on_fe.b2b_force[0]), float(half.b2b_force[0])),
                ("free ball 1's friction (drag), stick/slip on the FE compliance", float(drag[1][0]),
                 float(drag[0][0])),
                ("free ball 2's friction (drag), stick/slip on the FE compliance", float(drag[1][1]),
                 float(drag[0][1]))):
            run.check(model="b2b_rolling stick/slip, FE compliance", quantity=quantity, unit="N" if "F_B2B" in quantity
                      or WORST["product"] == "linear" else "N m", value=value, reference=reference, tolerance=0.01,
                      time_s=seconds, family="FE-informed", level=level,
                      source="the same stick/slip solve on the half-space (same grid): the FE rung's effect where "
                             "full slip is worst",
                      note=f"power balance {on_fe.power_balance:.1e}; full slip on the same cells "
                           f"{float(on_fe.full_slip.b2b_force[0]):.4f} N; stick fraction up to "
                           f"{max(c.stick_fraction for row in on_fe.touching.contacts for c in row):.3f}")
