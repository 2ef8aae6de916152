"""Scenes of steady rolling contact with stick and slip (lowmodel.contact.rolling, .fastsim; docs/rolling_contact.md).

The ladder of the rolling solver, each rung against a reference computed without it
(validation.references.rolling): Carter's 2D creep curve, the Cattaneo-Mindlin shift, Kalker's linear-theory
coefficients (Table E.3) after grid extrapolation, CONTACT's stored creep curve ``tractcurv`` on CONTACT's own
grid, the full-slip limit against the ellipse-friction maps; then the four contacts of lin2019 Table 1
(case (a), free ball) with stick and slip against full slip.
"""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ballbench.lowmodel.contact import ellipse_friction, fastsim, rolling
from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.linear_bearing import b2b, rolling_contacts
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.validation.cases import lin2019
from ballbench.validation.figures import render3d, stickslip3d
from ballbench.validation.figures import rolling as figures
from ballbench.validation.references import rolling as ref
from ballbench.validation.references.richardson import extrapolate
from ballbench.validation.scene import scene

MODEL = "lowmodel.contact.rolling"
G, NU, MU = 82e9, 0.28, 0.3  # steel-like half-spaces of the closed-form rungs


def _cells(n) -> str:
    return f"{n} x {n} cells" if isinstance(n, int) else f"{n[0]} x {n[1]} cells"


@scene("rolling-carter", "Steady rolling of two cylinders (plane strain) with stick and slip against Carter's creep "
       "curve and traction, grid convergence", kind="low-order", cost_s=2.0)
def rolling_carter(run):
    a, load = 1e-3, 2e5
    p0 = 2 * load / (math.pi * a)
    levels = (100, 200) if run.fidelity == "quick" else (100, 200, 400)
    for kappa in (0.15, 0.45, 0.75):
        creepage = kappa * 2 * (1 - NU) * MU * p0 / G
        reference = ref.carter_force(creepage, p0, G, NU, MU)
        values = []
        for n in levels:
            result, time_s = run.time(rolling.steady_rolling_line, a, load, G, NU, MU, creepage, n, budget_s=0.0,
                                      max_repeat=1)
            values.append(result.force_rolling / (MU * load))
        exact = ref.carter_traction(result.grid.x, a, creepage, p0, G, NU, MU)
        run.check(model=MODEL, quantity=f"Q/(mu P), kappa {kappa}, {levels[-1]} cells", unit="1", value=values[-1],
                  reference=reference, source="Carter (1926); Johnson (1985) eq 8.30", tolerance=2e-3,
                  time_s=time_s, family="BEM", level=f"{levels[-1]} cells",
                  note="grid levels " + ", ".join(f"{n}: {v:.5f}" for n, v in zip(levels, values)))
        run.check(model=MODEL, quantity=f"max traction error / (mu p0), kappa {kappa}", unit="1",
                  value=float(np.max(np.abs(result.traction[:, 0, 0] - exact))) / (MU * p0), reference=0.0,
                  scale=1.0, relation="le", source="Carter's traction (Johnson 1985 eq 8.29)", tolerance=0.03,
                  time_s=time_s, family="BEM", level=f"{levels[-1]} cells",
                  why="the traction error is judged against the traction bound mu p0 (scale 1)")
        extrapolated = extrapolate([1.0 / n for n in levels[-2:]], values[-2:], formal_order=1.0).value
        run.check(model=MODEL, quantity=f"Q/(mu P), kappa {kappa}, extrapolated (first order)", unit="1",
                  value=extrapolated, reference=reference, source="Carter (1926)", tolerance=2e-4, time_s=0.0,
                  family="BEM", level="extrapolated")


@scene("rolling-cattaneo", "Cattaneo-Mindlin shift of a Hertz circle (nu = 0): tangential force at Mindlin's shift and "
       "stick radius", kind="low-order", cost_s=3.0, show=render3d.show_saved)
def rolling_cattaneo(run):
    a, force = 1e-3, 1000.0
    n = 40 if run.fidelity == "quick" else 60 if run.fidelity == "default" else 80
    grid = rolling.hertz_grid(a, a, (n, n))
    pressure = rolling.hertz_pressure(grid, a, a, force)
    shifts = []
    for ratio in (0.3, 0.7):
        delta = ref.mindlin_shift(ratio, force, a, G, 0.0, MU)
        result, time_s = run.time(rolling.shift, pressure, grid, G, 0.0, MU, (delta, 0.0), budget_s=0.0, max_repeat=1)
        shifts.append((f"Mindlin's shift at Q/(mu P) = {ratio}", result))
        run.check(model=MODEL, quantity=f"Q/(mu P) at Mindlin's shift, {ratio}", unit="1",
                  value=-result.force_rolling / (MU * force), reference=ratio, tolerance=4e-3, time_s=time_s,
                  source="Mindlin (1949); Johnson (1985) eq 7.42", family="BEM", level=_cells(n))
        radius = math.sqrt(np.count_nonzero(result.stick) * grid.cell_area / math.pi)
        run.check(model=MODEL, quantity=f"stick radius / a, Q/(mu P) = {ratio}", unit="1", value=radius / a,
                  reference=ref.mindlin_stick_radius(ratio, 1.0), tolerance=0.02, time_s=time_s,
                  source="Cattaneo (1938); Johnson (1985) eq 7.38", family="BEM", level=_cells(n),
                  note="radius of the circle with the stick cells' area")
    stickslip3d.artifacts(run, "shift", shifts, title="Cattaneo-Mindlin shift of a Hertz circle (arrows: the shift's "
                          "slip)", ellipses=[(a, a)] * len(shifts))


@scene("rolling-kalker", "Kalker's creepage coefficients C11, C22, C23 (linear theory) from the exact solver, "
       "extrapolated over three grids, against Kalker (1990) Table E.3", kind="low-order", cost_s=6.0)
def rolling_kalker(run):
    b, force, nu, tiny = 1e-3, 1000.0, 0.25, 1e-9
    sizes = (24, 48, 96) if run.fidelity == "fine" else (16, 32, 64)  # 12, 24, 48: 12 is not yet asymptotic
    for aob, published in ref.KALKER_TABLE_E3_NU_025.items():
        a = aob * b
        c = math.sqrt(a * b)
        values = {name: [] for name in ("C11", "C22", "C23")}
        start = time.perf_counter()
        for n in sizes:
            values["C11"].append(-rolling.steady_rolling(a, b, force, G, nu, MU, tiny, 0, 0, n).force_rolling
                                 / (G * c * c * tiny))
            values["C22"].append(-rolling.steady_rolling(a, b, force, G, nu, MU, 0, tiny, 0, n).force_lateral
                                 / (G * c * c * tiny))
            values["C23"].append(-rolling.steady_rolling(a, b, force, G, nu, MU, 0, 0, tiny / c, n).force_lateral
                                 / (G * c * c * tiny))
        time_s = time.perf_counter() - start
        for index, name in enumerate(values):
            v = values[name]
            study = extrapolate([1.0 / n for n in sizes], v)
            extrapolated = study.value
            run.check(model=MODEL, quantity=f"{name}, a/b = {aob}, nu = {nu}", unit="1", value=extrapolated,
                      reference=published[index], source=ref.KALKER_SOURCE, tolerance=0.02, time_s=time_s,
                      family="BEM", level="extrapolated from " + ", ".join(_cells(n) for n in sizes),
                      note="grids " + ", ".join(f"{n}: {x:.4f}" for n, x in zip(sizes, v)) + f"; {study.note}")


def _tractcurv_normal():
    d = ref.TRACTCURV_INPUT
    grid = hs.SurfaceGrid(*d["grid"], *d["cell"])
    gap = hs.quadratic_gap(grid, d["curvature_rolling"], d["curvature_lateral"])
    normal = hs.solve(gap, grid, d["shear_modulus"] / (1 - d["poisson_ratio"]), force=d["normal_force"],
                      tolerance=1e-10)
    return grid, normal.pressure


@scene("rolling-tractcurv", "CONTACT's creep-force curve example tractcurv (FN 106.7 kN, mu 0.33): the exact solver "
       "on CONTACT's grid and BEM pressure, the grid-converged curve and FASTSIM beside it", kind="low-order",
       cost_s=4.0, show=render3d.show_saved)
def rolling_tractcurv(run):
    d = ref.TRACTCURV_INPUT
    mu, force = d["friction_coefficient"], d["normal_force"]
    grid, pressure = _tractcurv_normal()
    operator = rolling.half_space_operator(grid, d["shear_modulus"], d["poisson_ratio"])
    n_fine = 32 if run.fidelity == "quick" else 64
    curves = {"CONTACT's grid": [], "Hertz, " + _cells(n_fine): [], "FASTSIM": []}
    fields = []
    for creepage, published in zip(ref.TRACTCURV_CREEPAGES, ref.TRACTCURV_FX_OVER_MU_FN):
        w = rolling.rigid_slip(grid, creepage, 0.0, 0.0)
        result, time_s = run.time(rolling.solve, pressure, operator, mu, w, budget_s=0.0, max_repeat=1)
        run.check(model=MODEL, quantity=f"|FX|/(mu FN), xi = {creepage:.1e}", unit="1",
                  value=-result.force_rolling / (mu * force), reference=published, source=ref.TRACTCURV_SOURCE,
                  tolerance=0.01, time_s=time_s, family="BEM", level="48 x 44 cells (CONTACT's grid)")
        fine, fine_s = run.time(rolling.steady_rolling, d["semi_axis_rolling"], d["semi_axis_lateral"], force,
                                d["shear_modulus"], d["poisson_ratio"], mu, creepage, 0.0, 0.0, n_fine,
                                budget_s=0.0, max_repeat=1)
        fields.append((f"xi = {creepage:.1e}", fine))
        run.check(model=MODEL, quantity=f"|FX|/(mu FN), xi = {creepage:.1e}, Hertz pressure", unit="1",
                  value=-fine.force_rolling / (mu * force), reference=published, source=ref.TRACTCURV_SOURCE,
                  tolerance=0.03, time_s=fine_s, family="BEM", level=_cells(n_fine),
                  note="the Hertz pressure on a finer grid: differs from CONTACT's 48 x 44 by the discretisation")
        simple, simple_s = run.time(fastsim.fastsim, d["semi_axis_rolling"], d["semi_axis_lateral"], force,
                                    d["shear_modulus"], d["poisson_ratio"], mu, creepage, 0.0, 0.0)
        run.check(model="lowmodel.contact.fastsim", quantity=f"|FX|/(mu FN), xi = {creepage:.1e}", unit="1",
                  value=-float(simple.force_rolling) / (mu * force), reference=published,
                  source=ref.TRACTCURV_SOURCE, tolerance=0.05, time_s=simple_s, family="low-order numerical",
                  level="20 x 20 elements", note="FASTSIM (Kalker's simplified theory, parabolic bound)")
        for curve, value in zip(curves.values(), (result.force_rolling, fine.force_rolling,
                                                   float(simple.force_rolling))):
            curve.append(-value / (mu * force))
    run.save_figure(figures.creep_figure(ref.TRACTCURV_CREEPAGES, ref.TRACTCURV_FX_OVER_MU_FN, curves),
                    "creep_curve.png")
    stickslip3d.artifacts(run, "creep_curve", fields[::2] + fields[-1:],
                          title=f"CONTACT's tractcurv along the creep curve (Hertz pressure, {_cells(n_fine)})",
                          ellipses=[(d["semi_axis_rolling"], d["semi_axis_lateral"])] * 4)


@scene("rolling-full-slip", "The full-slip limit: stick/slip forces and spin moment converge to the ellipse-friction "
       "maps (lin2019 eqs A4-A7) as the spin parameter grows", kind="low-order", cost_s=12.0)
def rolling_full_slip(run):
    a, b, force = 0.1e-3, 0.6e-3, 50.0
    p0 = 1.5 * force / (math.pi * a * b)
    n = 64 if run.fidelity == "quick" else 128
    lam = 1e5
    for kappa in (0.0, 0.3, 0.9, 2.0):
        mapped = ellipse_friction.friction(kappa, a / b)
        phi = lam * MU * p0 / (b * G)
        result, time_s = run.time(rolling.steady_rolling, a, b, force, G, NU, MU, kappa * phi * b, 0.0, phi, n,
                                  budget_s=0.0, max_repeat=1)
        run.check(model=MODEL, quantity=f"F_x/(mu F), c/a = {kappa}, Lambda 1e5", unit="1",
                  value=result.force_rolling / (MU * force), reference=float(mapped.force), scale=1.0,
                  tolerance=1e-3, time_s=time_s, source="lowmodel.contact.ellipse_friction (lin2019 eq A4)",
                  family="BEM", level=_cells(n), why="judged against mu F (the full-slip force scale)")
        run.check(model=MODEL, quantity=f"M_z/(mu F b), c/a = {kappa}, Lambda 1e5", unit="1",
                  value=-result.spin_moment / (MU * force * b), reference=float(mapped.moment), scale=1.0,
                  tolerance=1e-3, time_s=time_s, source="lowmodel.contact.ellipse_friction (lin2019 eq A5)",
                  family="BEM", level=_cells(n), why="judged against mu F b (the full-slip moment scale)")
    kappa = 0.3
    mapped = ellipse_friction.friction(kappa, a / b)
    rows = []
    for lam in (1.0, 10.0, 100.0, 1e3, 1e4):
        phi = lam * MU * p0 / (b * G)
        result = rolling.steady_rolling(a, b, force, G, NU, MU, kappa * phi * b, 0.0, phi, 48)
        rows.append((lam, result.force_rolling / (MU * force) - float(mapped.force),
                     -result.spin_moment / (MU * force * b) - float(mapped.moment),
                     result.force_lateral / (MU * force), result.stick_fraction))
    run.note("Approach to full slip at c/a = 0.3, 48 x 48 cells (Lambda: F_x - map, M_z - map, F_y [all / mu F, "
             "mu F b], stick fraction): " + "; ".join(f"{lam:g}: {f:+.4f}, {m:+.4f}, {y:+.4f}, {s:.3f}"
                                                       for lam, f, m, y, s in rows))
    run.check(model=MODEL, quantity="|F_y|/(mu F) x Lambda at Lambda 1e3 and 1e4 (the lateral force falls as 1/Lambda)",
              unit="1", value=abs(rows[4][3]) * 1e4, reference=abs(rows[3][3]) * 1e3, tolerance=0.1, time_s=0.0,
              source="full slip has no lateral force: the stick/slip excess decays as 1/Lambda", family="BEM",
              level="48 x 48 cells")


NAMES = ("BL", "BR", "TR", "TL")


@scene("rolling-lin2019-contacts", "The four contacts of lin2019 Table 1, case (a) free ball, at the creepages and "
       "spin of the converged low-order state: stick/slip on two half-spaces (Heathcote slip included) against "
       "lin2019's full slip", kind="low-order", cost_s=4.0, show=render3d.show_saved)
def rolling_lin2019_contacts(run):
    cells = {"quick": (12, 48), "default": (20, 80), "fine": (30, 120)}[run.fidelity]
    contacts = b2b.contacts(lin2019.TABLE3_A).ball(0)
    state = bearing_ball.solve(contacts)
    mu = contacts.friction_coefficient
    material = lin2019.GUIDE.material.keywords
    # the mapping of frames and signs: at mu 1e-5 (Lambda ~ 6e5) without Heathcote's slip the stick/slip
    # solution is full slip and must give lin2019's forces and moments
    faint = dataclasses.replace(contacts, friction_coefficient=1e-5)
    faint_state = bearing_ball.solve(faint)
    limit = rolling_contacts.solve_contacts(faint, faint_state, lin2019.GUIDE.conformity, cells=cells, heathcote=False,
                                            **material)
    for i, contact in enumerate(limit):
        scale = 1e-5 * faint.normal_forces[0, i]
        run.check(model="lowmodel.linear_bearing.rolling_contacts", quantity=f"f_{NAMES[i]}/(mu F), Lambda "
                  f"{contact.spin_parameter:.0f}, no Heathcote", unit="1", value=contact.friction_force / scale,
                  reference=faint_state.friction_force[0, i] / scale, scale=1.0, tolerance=2e-3, time_s=0.0,
                  source="lin2019 eq A4 (lowmodel.linear_bearing.ball, full slip)", family="BEM",
                  level=_cells(cells), why="judged against mu F")
    start = time.perf_counter()
    results = rolling_contacts.solve_contacts(contacts, state, lin2019.GUIDE.conformity, cells=cells, **material)
    time_s = (time.perf_counter() - start) / 4
    plain = rolling_contacts.solve_contacts(contacts, state, lin2019.GUIDE.conformity, cells=cells, heathcote=False,
                                            **material)
    lines = []
    for i, (contact, centre_only) in enumerate(zip(results, plain)):
        force_scale = mu * contacts.normal_forces[0, i]
        moment_scale = force_scale * contacts.semi_major[0, i]
        name = NAMES[i]
        full_f = state.friction_force[0, i] / force_scale
        full_m = state.friction_moment[0, i] / moment_scale
        level = _cells(cells)
        run.check(model="lowmodel.linear_bearing.rolling_contacts", quantity=f"f_{name}/(mu F), stick/slip",
                  unit="1", value=contact.friction_force / force_scale, reference=full_f, scale=1.0, tolerance=0.02,
                  time_s=time_s, source="lin2019 full slip (eq A4), low-order state of case (a)", family="BEM",
                  level=level, why="judged against mu F; the difference to full slip is the finding",
                  note=f"Lambda {contact.spin_parameter:.1f}, stick {contact.solution.stick_fraction:.4f}")
        run.check(model="lowmodel.linear_bearing.rolling_contacts", quantity=f"M_{name}/(mu F a), stick/slip",
                  unit="1", value=contact.spin_moment / moment_scale, reference=full_m, scale=1.0, tolerance=0.02,
                  time_s=time_s, source="lin2019 full slip (eq A5), low-order state of case (a)", family="BEM",
                  level=level, why="judged against mu F a; the difference to full slip is the finding")
        run.check(model="lowmodel.linear_bearing.rolling_contacts", quantity=f"|lateral force {name}|/(mu F)",
                  unit="1", value=abs(contact.lateral_force) / force_scale, reference=0.0, scale=1.0, relation="le",
                  tolerance=0.1, time_s=time_s, source="full slip has none; 'a few percent of mu F' (spin "
                  "parameter near 60)", family="BEM", level=level,
                  why="an upper bound: the lateral force full slip lacks stays a few percent of mu F at Lambda ~ 60")
        lines.append(f"{name}: F {contacts.normal_forces[0, i]:.2f} N, Lambda {contact.spin_parameter:.1f}, "
                     f"xi {contact.motion.creepage_rolling:+.3e}, phi {contact.motion.spin:+.1f} rad/m, stick "
                     f"{contact.solution.stick_fraction:.4f}; f/(mu F) full slip {full_f:+.4f}, stick/slip "
                     f"{contact.friction_force / force_scale:+.4f} (centre slip only "
                     f"{centre_only.friction_force / force_scale:+.4f}); M/(mu F a) {full_m:+.4f}, "
                     f"{contact.spin_moment / moment_scale:+.4f} ({centre_only.spin_moment / moment_scale:+.4f}); "
                     f"lateral/(mu F) {contact.lateral_force / force_scale:+.4f}")
    run.note("Per contact (Kalker's creepage and spin of the lin2019 case (a) state; stick/slip with Heathcote's "
             "slip, in brackets without it): " + " | ".join(lines))
    run.save_figure(figures.contacts_figure(NAMES, results), "contacts.png")
    stickslip3d.artifacts(run, "contacts", [(name, c.solution) for name, c in zip(NAMES, results)],
                          title="lin2019 Table 1 case (a), free ball: the four contacts with Heathcote's slip",
                          ellipses=[(c.motion.semi_axis_rolling, c.motion.semi_axis_lateral) for c in results])


# --------------------------------------------------------------------------
# FE compliance (fem.rolling_compliance)
# --------------------------------------------------------------------------
# (cells across, h_contact / cell) of the flat-like contact.  The quick level is the default one: coarser grids or
# meshes miss the 2 % (6 x 6 cells at h 0.7 or 0.525 cell, 8 x 8 at h 1.0: 2.0-3.7 %; docs/rolling_contact.md);
# its condensation is cached on disk, so a default run after a quick one loads it.
FE_LEVELS = {"quick": (8, 0.7), "default": (8, 0.7), "fine": (12, 0.7)}
# h_contact / cell of the groove pairs (6 x 24 cells): FE minus half-space moves by < 1e-3 of mu F from 1.1 to 0.8
GROOVE_H = {"default": 1.1, "fine": 0.8}


def _flat_like(cells: int, h_factor: float):
    """Ball (R 10 mm) on a flat block, steel, 100 N: the contact is 0.19 mm across (R/a 53, depth 53 a)."""
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    e, nu = lin2019.GUIDE.material.pair
    radius, force = 10e-3, 100.0
    a = (3.0 * force * radius / (4.0 * e / (2.0 * (1.0 - nu * nu)))) ** (1.0 / 3.0)  # Hertz, Johnson eq 4.22
    grid = rolling.hertz_grid(a, a, (cells, cells))
    start = time.perf_counter()
    path = contact_pairs.ball_on_flat_pair(radius, h_factor * grid.dx, 1.3, symmetry="full", element_order=2,
                                           fine_ellipse=(1.2 * a + grid.dx, 1.2 * a + grid.dx, 0.5 * a))
    compliance = rolling_compliance.condense(path, (e, nu), grid, order=2, cache=True)  # W reused across runs
    return a, force, grid, compliance, time.perf_counter() - start


@scene("rolling-fe-compliance", "Rolling contact on an FE compliance (W = B K^-1 B^T condensed onto the grid) against "
       "the half-space on a flat-like contact (ball R 10 mm on a block, 100 N); the lin2019 Table 1 contact BL in "
       "the f = 0.56 and 0.52 grooves on FE compliance against the half-space", kind="FE", cost_s=260.0,
       budget_s={"quick": 180.0, "default": 600.0, "fine": 3600.0}, level="8 x 8 cells, P2, h 0.7 cell",
       show=render3d.show_saved)
def rolling_fe_compliance(run):
    cells, h_factor = FE_LEVELS[run.fidelity]
    a, force, grid, compliance, build_s = _flat_like(cells, h_factor)
    e, nu = lin2019.GUIDE.material.pair
    shear = e / (2.0 * (1.0 + nu))
    level = f"{cells} x {cells} cells, P2, h {h_factor} cell, {compliance.ndofs} DOFs"
    pressure = rolling.hertz_pressure(grid, a, a, force)
    half_space = rolling.half_space_operator(grid, shear, nu)
    fe = compliance.operator(coupling=False)
    p0 = 1.5 * force / (math.pi * a * a)
    fields = []
    cases = {"linear (xi 1e-9)": (1e-9, 0.0), "xi 0.3 mu p0 / G": (0.3 * MU * p0 / shear, 0.0),
             "spin 0.5 mu p0 / (a G)": (0.0, 0.5 * MU * p0 / (a * shear))}
    for name, (xi, phi) in cases.items():
        w = rolling.rigid_slip(grid, xi, 0.0, phi)
        reference, reference_s = run.time(rolling.solve, pressure, half_space, MU, w, budget_s=0.0, max_repeat=1)
        value, value_s = run.time(rolling.solve, pressure, fe, MU, w)
        fields = [(f"FE compliance, {name}", value), (f"half-space, {name}", reference)] if phi else fields
        quantity, attribute = ("F_y", "force_lateral") if phi else ("F_x", "force_rolling")
        run.check(model="fem.rolling_compliance", quantity=f"{quantity}, {name}", unit="N",
                  value=getattr(value, attribute), reference=getattr(reference, attribute), tolerance=0.02,
                  time_s=value_s, source="the same solve on the half-space (lowmodel.contact.influence)",
                  family="FE-informed", level=level,
                  note=f"solve {value_s * 1e3:.1f} ms on the FE compliance, {reference_s * 1e3:.1f} ms on the "
                  f"half-space; " + (f"condensation loaded from the disk cache ({build_s:.0f} s with the mesh)"
                                     if "cached_s" in compliance.timings else
                                     f"condensation {compliance.timings.get('condense_s', 0):.0f} s, mesh and "
                                     f"assembly {build_s - compliance.timings.get('condense_s', 0):.0f} s"))
        if phi:
            run.check(model="fem.rolling_compliance", quantity=f"M_z, {name}", unit="N m", value=value.spin_moment,
                      reference=reference.spin_moment, tolerance=0.02, time_s=value_s, family="FE-informed",
                      level=level, source="the same solve on the half-space (lowmodel.contact.influence)")
        run.budget(model="fem.rolling_compliance", quantity=f"solve time / half-space solve time, {name}", unit="1",
                   value=value_s / max(reference_s, 1e-9), budget=10.0,
                   source="target: within 10x of the half-space solve after condensation (docs/rolling_contact.md)")
    if fields:
        stickslip3d.artifacts(run, "spin", fields, title=f"ball on a block, spin: FE compliance against the "
                              f"half-space, {level}", ellipses=[(a, a)] * len(fields))
    if run.fidelity == "quick":
        return
    _fe_grooves(run, GROOVE_H[run.fidelity])


def _fe_grooves(run, h_factor: float):
    """BL of lin2019 Table 1 case (a) (the most loaded contact) on FE compliance of the f = 0.56 and 0.52 grooves."""
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    e, nu = lin2019.GUIDE.material.pair
    cells = (6, 24)
    for conformity in (0.56, 0.52):
        contacts = b2b.contacts(lin2019.module_case(lin2019.THETA, lin2019.SIDE_FORCE_RATIO,
                                                    conformity=conformity)).ball(0)
        state = bearing_ball.solve(contacts)
        a_lin, b_lin = contacts.semi_major[0, 0], contacts.semi_major[0, 0] * contacts.b_over_a[0, 0]
        grid = rolling.hertz_grid(b_lin, a_lin, cells)
        start = time.perf_counter()
        path = contact_pairs.ball_in_groove_pair(lin2019.GUIDE.ball_radius, conformity, h_factor * grid.dx, 1.3,
                                                 symmetry="full", element_order=2,
                                                 fine_ellipse=(a_lin + grid.dy, b_lin + grid.dx, 0.5 * b_lin))
        compliance = rolling_compliance.condense(path, (e, nu), grid, order=2, cache=True)
        build_s = time.perf_counter() - start
        material = dict(youngs_modulus=e, poisson_ratio=nu)
        half = rolling_contacts.solve_contacts(contacts, state, conformity, cells=cells, **material)[0]
        on_fe = rolling_contacts.solve_contacts(contacts, state, conformity, cells=cells,
                                                operator_for=lambda g, m: compliance.operator(), **material)[0]  # noqa: ARG005, B023 - the operator_for signature; called in this iteration
        scale = contacts.friction_coefficient * contacts.normal_forces[0, 0]
        moment_scale = scale * a_lin
        level = f"{cells[0]} x {cells[1]} cells, P2, h {h_factor:g} cell, {compliance.ndofs} DOFs"
        for quantity, value, reference, unit_scale in (
                ("f_BL/(mu F)", on_fe.friction_force, half.friction_force, scale),
                ("M_BL/(mu F a)", on_fe.spin_moment, half.spin_moment, moment_scale),
                ("lateral BL/(mu F)", on_fe.lateral_force, half.lateral_force, scale)):
            run.check(model="fem.rolling_compliance", quantity=f"{quantity}, groove f = {conformity}", unit="1",
                      value=value / unit_scale, reference=reference / unit_scale, scale=1.0, tolerance=0.05,
                      time_s=build_s, family="FE-informed", level=level,
                      source="the half-space (the difference is the conformal groove's own compliance)",
                      why="judged against mu F (mu F a): the difference is what the FE rung adds",
                      note=f"Lambda {half.spin_parameter:.1f}; stick {half.solution.stick_fraction:.4f} "
                      f"(half-space), {on_fe.solution.stick_fraction:.4f} (FE); condensation "
                      f"{compliance.timings.get('condense_s', 0):.0f} s (0: from the disk cache)")
