"""The model ladder of the B2B force with stick/slip ball-to-groove contacts (docs/b2b_rolling.md): the runs of the
``rolling-b2b-*`` scenes on lin2019's two-ball cases (:data:`cases.lin2019.TABLE3`, ``TABLE5``).

Every rung on the same case:

* analytical (lin2019 eq 30, linear bearing) and the low-order full-slip models (eqs 4-10, 54-61);
* stick/slip on two half-spaces with Hertz's pressure (``b2b_rolling``, the grids of
  :data:`cases.stick_slip.LEVELS`) and its full-slip limit on the same cells;
* FE-informed full slip (``b2b_traction`` on the FE module's pressure: :mod:`.fe_b2b_linear`,
  :mod:`.fe_b2b_screw`, the ``fe-b2b-*`` scenes' runs and levels);
* stick/slip with the FE pressure on two half-spaces, and on the FE compliance of a ball-in-groove pair
  condensed onto one grid that holds every contact of the module (``fem.rolling_compliance``, cached on disk).
"""
from __future__ import annotations

import csv
import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.bearing_results import axial_shares
from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.linear_bearing import b2b as linear_b2b
from ballbench.lowmodel.linear_bearing import b2b_analytical
from ballbench.lowmodel.linear_bearing import b2b_rolling as linear_rolling
from ballbench.lowmodel.screw import b2b_rolling as screw_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.state import friction_increase
from ballbench.validation.cases import FIDELITIES, lin2019, stick_slip
from ballbench.validation.figures import stickslip3d
from ballbench.validation.references.published import lin2019 as printed
from ballbench.validation.studies import fe_b2b_linear, fe_b2b_screw

__all__ = ["Rung", "linear_ladder", "screw_ladder", "record_ladder", "pair_compliance", "compliance",
           "largest_semi_axes", "pressure_samples", "level_name", "TIME_BUDGET_S"]

STEEL = lin2019.STEEL


def level_name(cells) -> str:
    return f"{cells[0]} x {cells[1]} cells"


def pressure_samples(model, result) -> list:
    """The solved FE contacts as ``(name, top, points (q, 3) [m], pressure (q,) [Pa], areas (q,) [m^2])`` in the
    ball frame of the lowmodel (``model.geometry.to_ball_frame``: lin2019 Fig 2, or the ball's CS3)."""
    geometry = model.geometry
    return [(c.name, geometry.moving(i), geometry.to_ball_frame(c.points), np.clip(c.pressure, 0.0, None), c.areas)
            for i, c in enumerate(result.contacts)]


def compliance(product: str, level: stick_slip.ComplianceLevel):
    """The FE compliance of a ball in a straight groove of the product's conformity (``"linear"``: lin2019
    Table 1, ``"screw"``: Table 4) condensed onto the grid that holds every contact of the product's Table cases:
    ``(grid, RollingCompliance, seconds)`` (:func:`pair_compliance`)."""
    along, across = largest_semi_axes(product)
    cover = stick_slip.LEVELS[product].cover
    body = lin2019.GUIDE if product == "linear" else lin2019.SCREW
    return pair_compliance(body.ball_radius, body.conformity, cover[0] * along, cover[1] * across,
                           level.cells_along, level.cells_across, level.h_factor)


@lru_cache(maxsize=8)
def pair_compliance(radius: float, conformity: float, along: float, across: float, cells_along: int,
                    cells_across: int, h_factor: float, material: tuple[float, float] = STEEL.pair):
    """The FE compliance of a ball (``radius`` [m]) in a straight groove of ``conformity`` condensed onto the grid of
    ``cells`` over the half-widths ``along`` x ``across`` [m] (``fem.rolling_compliance``, disk-cached; P2, the
    contact-pair mesh with its fine slab over the grid, element size ``h_factor`` cells): ``(grid,
    RollingCompliance, seconds)``; ``material``: ``(E [Pa], nu)`` of ball and groove.  The pair (the groove
    straight, its block 0.6 R_B deep) stands for every contact of a module: the steady-state operator
    ``(W(x) - W(x + dx)) / dx`` does not see the far field (the module's other contacts, its truncated bodies), only
    the local shape of ball and groove (docs/b2b_rolling.md)."""
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    grid = rolling.hertz_grid(along, across, (cells_along, cells_across))
    start = time.perf_counter()
    # the pair mesh: x across the groove (Kalker's -y), y along it (Kalker's x); the fine slab over the grid, as
    # thick as about half the contacts' semi-axis along the groove
    path = contact_pairs.ball_in_groove_pair(radius, conformity, h_factor * min(grid.dx, grid.dy), 1.3,
                                             symmetry="full", element_order=2,
                                             fine_ellipse=(across + grid.dy, along + grid.dx, 0.35 * along))
    result = rolling_compliance.condense(path, material, grid, order=2, cache=True)
    return grid, result, time.perf_counter() - start


@lru_cache(maxsize=2)
def largest_semi_axes(product: str) -> tuple[float, float]:
    """(along, across) [m]: the largest Hertz semi-axes of the product's two cases (low-order contacts)."""
    if product == "linear":
        rows = [fe_b2b_linear.low_order_contacts(case) for case in lin2019.TABLE3.values()]
        along = max(float((c.semi_major * c.b_over_a).max()) for c in rows)
        across = max(float(c.semi_major.max()) for c in rows)
        return along, across
    along = across = 0.0
    for case in lin2019.TABLE5.values():
        contacts, _, state = fe_b2b_screw.low_order(case)
        along = max(along, float((state.semi_major * contacts.b_over_a).max()))
        across = max(across, float(state.semi_major.max()))
    return along, across


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
    h_contact: float = math.nan  # the FE module's element size [m] (FE rungs)


def rolling_rung(model: str, family: str, level: str, result, seconds: float, b2b_check=(math.nan, math.nan)) -> Rung:
    return Rung(model, family, level, float(result.b2b_force[0]), float(result.friction_increase), seconds,
                float(result.full_slip.b2b_force[0]), float(result.full_slip_increase), float(result.power_balance),
                result.touching.contacts, b2b_check)


def linear_ladder(case: str, level: str, *, progress=lambda x, desc="": x, with_fe: bool = True) -> list[Rung]:  # noqa: ARG005 - Run.progress's signature
    """Every rung of the linear bearing's ladder for Table 2/3 case ``case`` at fidelity ``level``."""
    rungs = []
    case, level = checks.choice("case", case, tuple(lin2019.TABLE3)), checks.choice("level", level, FIDELITIES)
    module_case, guide, levels = lin2019.TABLE3[case], lin2019.GUIDE, stick_slip.LINEAR
    contacts = fe_b2b_linear.low_order_contacts(module_case)
    linear_b2b.solve(contacts, [0.0])  # the friction map's disk cache, outside the timed calls
    if case == "a":
        start = time.perf_counter()
        analytical = b2b_analytical.from_case(module_case)
        rungs.append(Rung("lowmodel.linear_bearing.b2b_analytical", "analytical", "", float(analytical.b2b_force),
                          math.nan, time.perf_counter() - start))
    start = time.perf_counter()
    low = linear_b2b.solve(contacts, [0.0])
    seconds = time.perf_counter() - start
    free = linear_b2b.solve(contacts, [1e-3])
    rungs.append(Rung("lowmodel.linear_bearing.b2b", "low-order numerical", "", float(low.b2b_force[0]),
                      100.0 * friction_increase(low, free), seconds))
    cells = levels.hertz_cells.checked(level)
    start = time.perf_counter()
    balls = [linear_rolling.hertz_contacts(contacts, j, cells=cells, guide=guide)
             for j in range(2)]
    result = linear_rolling.module_b2b(balls, guide)
    seconds = time.perf_counter() - start
    check = linear_rolling.b2b_contact_check(result.touching, guide=guide)
    rungs.append(rolling_rung("b2b_rolling stick/slip, Hertz + half-space", "BEM", level_name(cells), result, seconds,
                              check))
    if not with_fe:
        return rungs
    fe_level = module_case.fe.levels.checked(level)
    start = time.perf_counter()
    model, results, _ = fe_b2b_linear.solve_fe_level(module_case, fe_level)
    fe_s = time.perf_counter() - start
    h_um = fe_level.h_contact * 1e6
    start = time.perf_counter()
    full = fe_b2b_linear.fe_informed(module_case, model, results)
    free_full = fe_b2b_linear.fe_informed(module_case, model, results, gaps=[1e-3])
    rungs.append(Rung("b2b_traction full slip, FE pressure", "FE-informed", f"h {h_um:.0f} um",
                      float(full.b2b_force[0]), 100.0 * friction_increase(full, free_full),
                      fe_s + time.perf_counter() - start, power_balance=float(full.power_balance)))
    samples = [pressure_samples(model, r) for r in results]
    # past its pressure samples the FE module is not needed: freed before the compliance's condensation, which
    # would otherwise hold both (docs/validation.md, "Memory")
    del model, results
    start = time.perf_counter()
    balls = [linear_rolling.sampled_contacts(s, guide=guide, cells=cells) for s in samples]
    result = linear_rolling.module_b2b(balls, guide)
    rungs.append(rolling_rung("b2b_rolling stick/slip, FE pressure + half-space", "FE-informed",
                              f"h {h_um:.0f} um, {level_name(cells)}", result, fe_s + time.perf_counter() - start))
    for compliance_level in progress(levels.compliance[level], desc="FE compliance levels"):
        grid, fe_compliance, condense_s = compliance("linear", compliance_level)
        operator = fe_compliance.operator()
        start = time.perf_counter()
        for label, op in (("FE compliance", operator), ("half-space, FE compliance grid", None)):
            balls = [linear_rolling.sampled_contacts(s, guide=guide, grid=grid, operator=op, outside=levels.outside)
                     for s in samples]
            result = linear_rolling.module_b2b(balls, guide)
            family = "FE-informed"
            rungs.append(rolling_rung(f"b2b_rolling stick/slip, FE pressure + {label}", family,
                                      f"h {h_um:.0f} um, {level_name(compliance_level)}, "
                                      f"{fe_compliance.ndofs} DOFs", result,
                                      fe_s + condense_s + time.perf_counter() - start))
    return rungs


def screw_ladder(case: str, level: str, *, progress=lambda x, desc="": x, with_fe: bool = True) -> list[Rung]:  # noqa: ARG005 - Run.progress's signature
    """Every rung of the ball screw's ladder for Table 5 case ``case`` at fidelity ``level``."""
    rungs = []
    case, level = checks.choice("case", case, tuple(lin2019.TABLE5)), checks.choice("level", level, FIDELITIES)
    module_case, levels = lin2019.TABLE5[case], stick_slip.SCREW
    start = time.perf_counter()
    contacts, free, state = fe_b2b_screw.low_order(module_case)
    seconds = time.perf_counter() - start
    module = screw_contacts.module(module_case.screw)
    rungs.append(Rung("lowmodel.screw.b2b", "low-order numerical", "", float(state.b2b_force[0]),
                      100.0 * friction_increase(state, free), seconds))
    cells = levels.hertz_cells.checked(level)
    start = time.perf_counter()
    balls = [screw_rolling.hertz_contacts(state, contacts, j, cells=cells) for j in range(2)]
    result = screw_rolling.module_b2b(balls, module)
    rungs.append(rolling_rung("b2b_rolling stick/slip, Hertz + half-space", "BEM", level_name(cells), result,
                              time.perf_counter() - start))
    if not with_fe:
        return rungs
    fe_level = module_case.fe.levels.checked(level)
    start = time.perf_counter()
    models, results, _ = fe_b2b_screw.solve_fe_level(module_case, fe_level,
                                                     axial_shares(contacts, state))
    fe_s = time.perf_counter() - start
    h_um = fe_level.h_contact * 1e6
    start = time.perf_counter()
    full = fe_b2b_screw.fe_informed(module_case, models, results)
    rungs.append(Rung("screw.b2b_traction full slip, FE pressure", "FE-informed", f"h {h_um:.0f} um",
                      float(full.b2b_force[0]), float(full.friction_increase), fe_s + time.perf_counter() - start,
                      power_balance=float(full.power_balance), h_contact=fe_level.h_contact))
    samples = [pressure_samples(m, r) for m, r in zip(models, results)]
    del models, results  # freed before the condensation, as in linear_ladder
    start = time.perf_counter()
    balls = [screw_rolling.sampled_contacts(s, module, cells=cells) for s in samples]
    result = screw_rolling.module_b2b(balls, module)
    rungs.append(rolling_rung("b2b_rolling stick/slip, FE pressure + half-space", "FE-informed",
                              f"h {h_um:.0f} um, {level_name(cells)}", result, fe_s + time.perf_counter() - start))
    for compliance_level in progress(levels.compliance[level], desc="FE compliance levels"):
        grid, fe_compliance, condense_s = compliance("screw", compliance_level)
        operator = fe_compliance.operator()
        start = time.perf_counter()
        for label, op in (("FE compliance", operator), ("half-space, FE compliance grid", None)):
            balls = [screw_rolling.sampled_contacts(s, module, grid=grid, operator=op, outside=levels.outside)
                     for s in samples]
            result = screw_rolling.module_b2b(balls, module)
            rungs.append(rolling_rung(f"b2b_rolling stick/slip, FE pressure + {label}", "FE-informed",
                                      f"h {h_um:.0f} um, {level_name(compliance_level)}, "
                                      f"{fe_compliance.ndofs} DOFs", result,
                                      fe_s + condense_s + time.perf_counter() - start))
    return rungs


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


def write_contacts(path, rungs: list[Rung], friction_coefficient: float) -> None:
    """contacts.csv: every contact of every stick/slip rung (touching state)."""
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["model", "level", "ball", "contact", "F_N", "Lambda", "creepage_parameter", "stick_fraction",
                         "along_groove_over_muF", "lateral_over_muF", "spin_moment_Nm", "rigid_power_W"])
        for r in rungs:
            for ball, row in enumerate(r.contacts):
                for c in row:
                    scale = friction_coefficient * c.normal_force
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
# the validity map (docs/b2b_rolling.md, 'Validity of full slip'): full slip's B2B force is within 2.5 % of
# stick/slip's in every solved case (F_B2B is a small difference of the balls' equilibria: on coarse cells the
# difference is the grid's, 'Grid error of the comparison'); a free ball's friction within 1 % wherever mu <= 0.1
FULL_SLIP_TOLERANCE = 0.025
CASE_B_FE_TOLERANCE = 0.01  # the fe-b2b scenes' bound on an FE-informed case (b) force (the FE's asymmetry)
# wall-time limit per stick/slip scene [s] (docs/b2b_rolling.md, "Costs")
TIME_BUDGET_S = {"quick": 120.0, "default": 600.0, "fine": 3000.0}


def _stick_slip_pictures(run, rungs: list[Rung]) -> None:
    """Save the touching state's contacts of the Hertz + half-space rung and of the finest FE-compliance rung and
    draw their stick and slip areas (:mod:`validation.figures.stickslip3d`)."""
    chosen = {"hertz_halfspace": next((r for r in rungs if r.model.endswith("Hertz + half-space")), None),
              "fe_compliance": next((r for r in reversed(rungs) if r.model.endswith("+ FE compliance")), None)}
    for name, rung in chosen.items():
        contacts = [(f"ball {ball + 1} {c.name}", c.solution) for ball, row in enumerate(rung.contacts) for c in row
                    if c.solution is not None] if rung is not None else []
        if contacts:
            stickslip3d.artifacts(run, name, contacts, title=f"{rung.model} [{rung.level}], the touching balls")


def record_ladder(run, product: str, case: str) -> list[Rung]:
    """Run the ladder of ``product`` ("linear" or "screw") for ``case`` at ``run.fidelity`` and record its checks,
    ladder.csv, contacts.csv and the notes."""
    level = run.fidelity
    product = checks.choice("product", product, ("linear", "screw"))
    start = time.perf_counter()
    ladder = linear_ladder if product == "linear" else screw_ladder
    rungs = ladder(case, level, progress=lambda it, desc="": run.progress(it, desc=desc))
    wall = time.perf_counter() - start
    if product == "linear":
        printed_low = printed.PRINTED.f_b2b_numerical
        ansys = printed.PRINTED.f_b2b_ansys if case == "a" else 0.0
        tolerance, source = 0.07, f"lin2019 Table 3 case ({case}), ANSYS FEA"
        scale = printed.PRINTED.f_b2b_numerical
        mu = lin2019.GUIDE.friction_coefficient
        increase_ref = None
    else:
        table5 = printed.TABLE5[case]
        printed_low, ansys = table5.f_b2b_numerical, table5.f_b2b_ansys
        tolerance, source = 0.10, f"lin2019 Table 5 case ({case}), ANSYS FEA"
        scale = 0.0
        increase_ref = table5.friction_increase
        mu = lin2019.SCREW.friction_coefficient
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
            # the fe-b2b-screw scenes' model at its own mesh level: the same declared gap
            gap = (fe_b2b_screw.ANSYS_GAP if product == "screw" and rung.model.startswith("screw.b2b_traction")
                   and any(case == c and abs(rung.h_contact - h) < 1e-9 for c, h in fe_b2b_screw.ANSYS_GAP_LEVELS)
                   else None)
            run.check(model=rung.model, quantity="F_B2B", unit="N", value=rung.b2b_force, reference=ansys,
                      source=source, tolerance=tolerance, time_s=rung.time_s, family=rung.family, level=rung.level,
                      known_gap=gap,
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
                # case (b) has no B2B force: the FE's residual force (mN, its asymmetry) is judged on the case (a)
                # force, as the zero check above; a relative error of two residuals would measure nothing
                zero_case = ansys == 0.0
                run.check(model=rung.model, quantity="F_B2B against full slip on the same cells", unit="N",
                          value=rung.b2b_force, reference=rung.full_slip_force, tolerance=FULL_SLIP_TOLERANCE,
                          time_s=rung.time_s, family=rung.family, level=rung.level,
                          scale=scale if zero_case else 0.0,
                          why="a residual force of the FE's asymmetry in a case without B2B force, judged against "
                              "the case (a) force" if zero_case else "",
                          source="the full-slip limit of the same contacts (pointwise Coulomb, b2b_traction); the "
                                 "validity map: within 2.5 % in every solved case (docs/b2b_rolling.md)",
                          note=contact_note(rung))
        if not math.isnan(rung.b2b_check[0]):
            run.check(model=rung.model, quantity="B2B contact as a rolling contact: |F| / (mu F_B2B)", unit="1",
                      value=rung.b2b_check[0], reference=1.0, tolerance=1e-4, time_s=rung.time_s, family=rung.family,
                      level=rung.level, source="lin2019 eq 6: full sliding at the B2B contact",
                      note=f"creepage parameter |dv|/V G/(mu p0) = {rung.b2b_check[1]:.3g} (the surfaces move in "
                           "opposite directions: full sliding)")
    run.budget(model="scene", quantity="wall time of the ladder", unit="s", value=wall,
               budget=TIME_BUDGET_S[level],
               source="the limit per stick/slip scene at this level (docs/b2b_rolling.md, Costs)")
    write_rungs(run.path("ladder.csv"), rungs)
    write_contacts(run.path("contacts.csv"), rungs, mu)
    run.add_artifact(run.path("ladder.csv"))
    run.add_artifact(run.path("contacts.csv"))
    _stick_slip_pictures(run, rungs)
    run.note("Ladder (ladder.csv; per contact: contacts.csv): " + "; ".join(
        f"{r.model} [{r.level or r.family}]: F_B2B {r.b2b_force:.4f} N"
        + ("" if math.isnan(r.full_slip_force) else f" (full slip on the same cells {r.full_slip_force:.4f} N)")
        + ("" if math.isnan(r.friction_increase) else f", increase {r.friction_increase:.2f} %")
        + f", {r.time_s:.1f} s" for r in rungs))
    return rungs
