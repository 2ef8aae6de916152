"""Scenes of the calibration (lowmodel/calibration.py, validation/calibrate.py, docs/calibration.md).

* ``calibration-roundtrip``: synthetic data from known constants plus noise;
  the fits recover them within their 95 % intervals, and over many seeds the
  intervals cover the truth as often as they claim.
* ``calibration-effect``: the contact stiffness law of the ball in a 0.56
  groove calibrated on FE (or given with ``--calibration FILE``) beside the
  Hertz-only values: approach and stiffness at 100 N, F_B2B of lin2019 Table 3
  case (a) by the analytical (eq 30) and the low-order numerical model.
"""
from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.validation.papers.lin2019 import CASE, PRINTED, TABLE1
from ballbench.validation.scene import scene

MODEL = "lowmodel.calibration"
RADIUS = TABLE1.ball_radius  # m, lin2019 Table 1
CONFORMITY = TABLE1.conformity
GROUP = f"ball-groove-{CONFORMITY:g}"
# the synthetic truth: Hertz C and Psi of the Table 1 groove, a bulk compliance of the order FE finds, and a
# friction coefficient with a speed dependence
BULK = 2e-11  # m/N
MU_0, MU_V = 0.1, 0.5  # 1, s/m
K_F = PRINTED.k_f  # lin2019 Sec 2.3.2
LOADS = np.linspace(25.0, 150.0, 9)  # N
NOISE_U = 2e-9  # m (0.07 % of U at 150 N)
NOISE_A = 0.003  # relative, contact size
NOISE_F = 0.02  # N, friction force
SEEDS = {"quick": 100, "default": 400, "fine": 2000}


def synthetic_truth() -> dict:
    """The constants the synthetic data are drawn from (SI units)."""
    geometry = hertz.ball_in_groove(RADIUS, CONFORMITY, **TABLE1.material)
    return {"hertz_constant": hertz.hertz_constant(geometry), "bulk_compliance": BULK,
            "psi": hertz.psi_constant(geometry, RADIUS), "mu": MU_0, "mu_speed_slope": MU_V, "k_f": K_F}


def synthetic_fit(seed: int, truth: dict, work: Path | None = None, confidence: float = 0.95) -> dict:
    """Fit every constant to synthetic data of ``seed``; returns ``{name: Constant}``.

    With ``work`` the friction data go through a CSV file (units N and mm/s, read back by
    :func:`validation.calibrate.read_friction_csv`).
    """
    rng = np.random.default_rng(seed)
    approach = truth["hertz_constant"] * LOADS ** (2 / 3) + truth["bulk_compliance"] * LOADS  # lin2019 eq 53 + C_b F
    approach = approach + rng.normal(0.0, NOISE_U, LOADS.size)
    semi_axis = truth["psi"] * RADIUS ** (1 / 3) * LOADS ** (1 / 3) * (1 + rng.normal(0.0, NOISE_A, LOADS.size))
    law = cal.fit_contact_law(LOADS, approach, semi_axes=semi_axis, ball_radius=RADIUS, confidence=confidence,
                              source=f"synthetic, seed {seed}")
    normal = np.repeat([20.0, 60.0, 120.0, 200.0], 3)  # N
    speed = np.tile([0.01, 0.05, 0.1], 4)  # m/s
    friction = (truth["mu"] + truth["mu_speed_slope"] * speed) * normal + rng.normal(0.0, NOISE_F, normal.size)
    if work is not None:
        from ballbench.validation.calibrate import read_friction_csv

        path = work / f"friction-{seed}.csv"
        lines = ["# synthetic friction data (calibration-roundtrip)",
                 "normal_force [N],friction_force [N],speed [mm/s]"]
        lines += [f"{float(n)!r},{float(f)!r},{float(v) * 1e3!r}" for n, f, v in zip(normal, friction, speed)]
        path.write_text("\n".join(lines) + "\n")
        data = read_friction_csv(path)
        normal, friction, speed = data["normal_force"], data["friction_force"], data["speed"]
    mu = cal.fit_friction_coefficient(normal, friction, speed, confidence=confidence)
    kappa = np.linspace(-0.5, 0.5, 21)
    k_f = cal.fit_line_through_origin(kappa, -truth["k_f"] * kappa + rng.normal(0.0, 0.01, kappa.size),
                                      confidence=confidence)
    return {**law.constants(), **mu, "k_f": k_f}


def coverage(seeds, truth: dict, confidence: float = 0.95) -> dict:
    """Share of ``seeds`` whose interval covers the truth, per constant."""
    hits = {name: 0 for name in truth}
    for seed in seeds:
        for name, constant in synthetic_fit(int(seed), truth, confidence=confidence).items():
            hits[name] += constant.covers(truth[name])
    return {name: count / len(seeds) for name, count in hits.items()}


@scene("calibration-roundtrip", "Calibration round trip: synthetic load-approach, contact-size, friction (CSV) and "
       "k_f data from known constants plus noise; the fits recover them within their 95 % intervals; coverage "
       "over many seeds", kind="low-order", cost_s=8.0)
def calibration_roundtrip(run):
    truth = synthetic_truth()
    with tempfile.TemporaryDirectory() as work:
        fitted, time_s = run.time(synthetic_fit, 2019, truth, Path(work), budget_s=0.05, max_repeat=3)
        path = cal.save(cal.Calibration({"roundtrip": fitted}), Path(work) / "calibration.json")
        loaded = cal.load(path)
    for name, constant in fitted.items():
        half = 0.5 * (constant.ci_high - constant.ci_low)
        run.check(model=MODEL, quantity=f"abs({name} - truth) / half-width of its 95 % interval (seed 2019)", unit="1",
                  value=abs(constant.value - truth[name]) / half, reference=1.0, relation="le", tolerance=0.0,
                  source=f"synthetic truth {truth[name]:.6g} {constant.unit}", time_s=time_s,
                  note=f"fit {constant.value:.6g} +- {constant.std_error:.2g} (1 SE)")
    same = all(loaded.get("roundtrip", n) == c for n, c in fitted.items())
    run.check(model=MODEL, quantity="constants that change through save/load of the calibration file", unit="count",
              value=float(not same), reference=0.0, scale=1.0, tolerance=0.0, source="JSON round trip",
              time_s=time_s)
    seeds = np.arange(SEEDS[run.fidelity])
    start = time.perf_counter()
    shares = coverage(seeds, truth)
    elapsed = (time.perf_counter() - start) / seeds.size
    for name, share in shares.items():
        run.check(model=MODEL, quantity=f"coverage of the 95 % interval of {name} over {seeds.size} seeds", unit="1",
                  value=share, reference=0.90, relation="ge", tolerance=0.0, time_s=elapsed,
                  source="issue 13: >= 90 % of seeded trials",
                  note=f"binomial sd of the share at 95 %: {math.sqrt(0.95 * 0.05 / seeds.size):.3f}")
    run.note(f"Truth: C = {truth['hertz_constant']:.6g} m N^-2/3 and Psi = {truth['psi']:.6g} (m^2/N)^(1/3) (Hertz, "
             f"conformity 0.56, R_B 5 mm), C_b = {BULK:g} m/N, mu = {MU_0} + {MU_V} s/m * v, k_f = {K_F}. Noise: "
             f"approach {NOISE_U:g} m, contact size {100 * NOISE_A:g} %, friction {NOISE_F} N; {LOADS.size} loads "
             f"{LOADS[0]:g}-{LOADS[-1]:g} N, 12 friction rows (4 loads x 3 speeds, CSV in N and mm/s). Intervals: "
             "scipy least_squares, covariance s^2 (J^T J)^-1, Student t.")


# --------------------------------------------------------------------------
# effect of the calibrated contact law
# --------------------------------------------------------------------------
def calibrated_contact_law(run) -> tuple[cal.Calibration, str]:
    """The contact law of the 0.56 groove: from ``--calibration FILE`` when it has one, else FE at the run's level."""
    from ballbench.validation.calibrate import active_calibration, fe_load_sweep

    given = active_calibration()
    if given is not None and GROUP in given.constants and "psi" in given.constants[GROUP]:
        return given, "the --calibration file"
    sweep = fe_load_sweep("fe-hertz-groove-056", run.fidelity)
    geometry = hertz.ball_in_groove(RADIUS, CONFORMITY, **TABLE1.material)
    law = cal.fit_contact_law(sweep["force"], sweep["approach"], semi_axes=sweep["a"], ball_radius=RADIUS,
                              source=f"FE fe-hertz-groove-056 {run.fidelity} level",
                              hertz_constant=hertz.hertz_constant(geometry), psi=hertz.psi_constant(geometry, RADIUS))
    return cal.Calibration({GROUP: law.constants()}), (f"FE fe-hertz-groove-056, {run.fidelity} level "
                                                      f"({sweep['ndofs']} DOFs, {sweep['wall_time_s']:.0f} s)")


def b2b_force_with_psi(psi: float, theta: float, rho: float) -> tuple[float, float]:
    """F_B2B [N] of lin2019 Table 3 case (a) with contact semi-axes ``a = psi R^(1/3) F^(1/3)`` (eq 15):
    (analytical eq 30, low-order numerical eqs 4-10); Table 1 otherwise."""
    from ballbench.lowmodel.linear_bearing import b2b, b2b_analytical
    from ballbench.validation.sweep_cases import with_psi

    analytical = b2b_analytical.two_ball_case(theta, rho, normal_load=TABLE1.vertical_force,
                                              groove_velocity=TABLE1.groove_velocity,
                                              friction_coefficient=TABLE1.friction_coefficient, psi=psi,
                                              ball_radius=RADIUS)
    contacts = with_psi(b2b.module_contacts(theta, rho, ball_radius=RADIUS, conformity=CONFORMITY,
                                            vertical_force=TABLE1.vertical_force,
                                            groove_velocity=TABLE1.groove_velocity,
                                            friction_coefficient=TABLE1.friction_coefficient, **TABLE1.material),
                        psi)  # lin2017 eq 36 forces
    return float(analytical.b2b_force), float(b2b.solve(contacts, [0.0]).b2b_force[0])


@scene("calibration-effect", "The contact law of the 0.56 groove calibrated on FE (Psi, C, C_b) beside Hertz: "
       "approach and stiffness at 100 N, F_B2B of lin2019 Table 3 case (a), analytical and numerical",
       kind="low-order", cost_s=29.0)
def calibration_effect(run):
    start = time.perf_counter()
    calibration, origin = calibrated_contact_law(run)
    fit_time = time.perf_counter() - start
    geometry = hertz.ball_in_groove(RADIUS, CONFORMITY, **TABLE1.material)
    c_hertz, psi_hertz = hertz.hertz_constant(geometry), hertz.psi_constant(geometry, RADIUS)
    psi = calibration.get(GROUP, "psi")
    c = calibration.get(GROUP, "hertz_constant")
    c_b = calibration.get(GROUP, "bulk_compliance")
    theta, rho = CASE.theta, CASE.side_force_ratio
    (hertz_analytical, hertz_numerical), time_h = run.time(b2b_force_with_psi, psi_hertz, theta, rho)
    (cal_analytical, cal_numerical), time_c = run.time(b2b_force_with_psi, psi.value, theta, rho)
    run.check(model="lowmodel.linear_bearing.b2b_analytical", quantity="F_B2B ratio calibrated / Hertz Psi, eq 30",
              unit="1", value=cal_analytical / hertz_analytical, reference=psi_hertz / psi.value, tolerance=1e-12,
              source="lin2019 eq 30: F_B2B proportional to 1/Psi", time_s=time_c)
    run.check(model="lowmodel.linear_bearing.b2b", quantity="F_B2B, calibrated Psi, numerical model", unit="N",
              value=cal_numerical, reference=PRINTED.f_b2b_ansys, tolerance=0.07, time_s=time_c,
              source="lin2019 Table 3 case (a), ANSYS FEA",
              note=f"Hertz Psi: {hertz_numerical:.4f} N; tolerance: the paper's own claim (within 6-7 %)")
    law = cal.ContactLaw(c, c_b, psi)
    load = TABLE1.vertical_force
    approach_cal = float(law.approach(load))
    approach_hertz = c_hertz * load ** (2 / 3)  # lin2019 eq 53
    run.check(model=MODEL, quantity="calibrated approach U(100 N) against C F^(2/3) + C_b F", unit="m",
              value=approach_cal, reference=c.value * load ** (2 / 3) + c_b.value * load, tolerance=1e-12,
              source="the fitted law", time_s=fit_time)
    rows = [("Psi [(m^2/N)^(1/3)]", psi_hertz, psi.value, f"[{psi.ci_low:.5g}, {psi.ci_high:.5g}]"),
            ("C [m N^-2/3]", c_hertz, c.value, f"[{c.ci_low:.5g}, {c.ci_high:.5g}]"),
            ("C_b [m/N]", 0.0, c_b.value, f"[{c_b.ci_low:.4g}, {c_b.ci_high:.4g}]"),
            ("approach U at 100 N [m]", approach_hertz, approach_cal, ""),
            ("stiffness dF/dU at 100 N [N/m]", float(hertz.solve_load(geometry, load).stiffness),
             float(law.stiffness(load)), ""),
            ("F_B2B analytical eq 30 [N]", hertz_analytical, cal_analytical, ""),
            ("F_B2B low-order numerical [N]", hertz_numerical, cal_numerical, "")]
    table = "; ".join(f"{name}: Hertz {h:.5g}, calibrated {v:.5g}" + (f" ({100 * (v / h - 1):+.2f} %)" if h else "")
                      + (f", 95 % interval {ci}" if ci else "") for name, h, v, ci in rows)
    run.note(f"Calibrated on {origin}. {table}.")
    if c_b.value < 0:
        run.note("C_b < 0: the FE approach is that of the ball's load face and the counter block's support face, "
                 "which lie closer than Hertz's 'distant points' of two half-spaces, so the finite bodies come out "
                 "stiffer than Hertz and the linear term of the law is negative (the fe-hertz scenes note the same "
                 f"C_b). Hertz's C lies {'inside' if c.covers(c_hertz) else 'outside'} the 95 % interval of the "
                 "fitted C; docs/calibration.md.")
    run.note("Load distribution: in the linear bearing the four normal forces of a ball are statically determinate "
             "(lin2017 eq 36) and do not depend on the contact stiffness; the calibrated stiffness changes the load "
             "distribution over the balls of a screw, which needs the ball-screw model (issue 11): not done here.")
    _figure(run, law, c_hertz)


def _figure(run, law: cal.ContactLaw, c_hertz: float) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    force = np.linspace(1.0, 200.0, 200)
    figure, ax = plt.subplots(figsize=(6, 4))
    ax.plot(force, 1e6 * c_hertz * force ** (2 / 3), label="Hertz, C F^(2/3) (lin2019 eq 53)")
    ax.plot(force, 1e6 * law.approach(force), "--", label="calibrated, C F^(2/3) + C_b F")
    ax.set_xlabel("F [N]")
    ax.set_ylabel("approach [um]")
    ax.legend()
    ax.set_title("ball in a 0.56 groove, R_B 5 mm")
    run.save_figure(figure, "approach_law.png")


# --------------------------------------------------------------------------
# effect of the calibrated screw and nut groove laws on the ball screw
# --------------------------------------------------------------------------
SCREW_FE = {"screw": ("screw-groove", "fe-hertz-screw"), "nut": ("nut-groove", "fe-hertz-nut")}
SCREW_FE_FIDELITY = "quick"  # the full helical pairs: ~240k P2 DOFs, 1.5-2.5 min each at the quick level
WHOLE_SCREW_BALLS, WHOLE_SCREW_LOAD = 37, 1500.0  # lin2019 Sec 3.4 (validation.papers.lin2019.WHOLE_SCREW)


def calibrated_groove_laws():
    """Laws of the screw and nut grooves: from ``--calibration FILE`` when it has the groups ``screw-groove`` and
    ``nut-groove``, else fitted to FE load sweeps of ``fe-hertz-screw`` / ``fe-hertz-nut`` at the quick level.
    Returns (:class:`screw_contacts.GrooveContactLaws`, origin text)."""
    from ballbench.lowmodel.screw import contacts as screw_contacts
    from ballbench.validation.calibrate import active_calibration, fe_contact_law

    given = active_calibration()
    groups = [group for group, _ in SCREW_FE.values()]
    if given is not None and all(g in given.constants and "psi" in given.constants[g] for g in groups):
        return screw_contacts.GrooveContactLaws.from_calibration(given, *groups), "the --calibration file"
    laws, origin = {}, []
    for body, (_, fe_name) in SCREW_FE.items():
        laws[body], sweep = fe_contact_law(fe_name, SCREW_FE_FIDELITY)
        origin.append(f"{sweep['source']} in {sweep['wall_time_s']:.0f} s")
    return screw_contacts.GrooveContactLaws(laws["screw"], laws["nut"]), "; ".join(origin)


def whole_screw_loads(module, contact_law=None, *, n_balls: int = WHOLE_SCREW_BALLS,
                      total: float = WHOLE_SCREW_LOAD) -> tuple[np.ndarray, np.ndarray, object]:
    """Axial load [N] of ``n_balls`` evenly spaced over the two loaded turns (nut azimuth
    ``psi_j = (j + 1/2) 4 pi / n``) under ``total`` [N] (lowmodel.screw.load_distribution, bar model);
    returns (psi, loads, axial stiffness table)."""
    from ballbench.lowmodel.screw import load_distribution as ld
    from ballbench.lowmodel.screw.whole_screw import TRACK_TURNS

    psi = (np.arange(n_balls) + 0.5) * 2.0 * math.pi * TRACK_TURNS / n_balls
    stiffness = ld.axial_stiffness(module, 3.0 * total / n_balls, contact_law=contact_law)
    loads = ld.distribute(psi, total, stiffness, ld.bar_sections(module), module.lead, module.youngs_modulus)
    return psi, loads, stiffness


@scene("calibration-effect-screw", "The contact laws of the screw and nut grooves (lin2019 Table 4) calibrated on FE "
       "(C, C_b, Psi) beside Hertz: load distribution over the 37 balls of the nut (1500 N) and F_B2B and the "
       "friction increase of lin2019 Table 5", kind="low-order", cost_s=240.0, budget_s=400.0)
def calibration_effect_screw(run):
    import csv

    from ballbench.lowmodel.screw import contacts as screw_contacts
    from ballbench.validation.papers import lin2019
    from ballbench.validation.scenes import lin2019_screw as ls

    start = time.perf_counter()
    laws, origin = calibrated_groove_laws()
    fit_time = time.perf_counter() - start
    hertz_oversize = ls.fitted_oversize()
    module = ls.table4_module(hertz_oversize)
    # 1. the laws as the model uses them: every loaded contact of ball 1 (theta = 0, flanks at beta_0) obeys
    #    delta = C F^(2/3) + C_b F of its groove (reference from the calibrated constants and Hertz, not the model)
    (free_c, state_c), time_c = run.time(ls.two_ball, "a", hertz_oversize, ls.READING, laws)
    worst = 0.0
    for i, body in enumerate(("screw", "screw", "nut", "nut")):
        law = getattr(laws, body)
        c_hertz = screw_contacts.hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                              module.lead_angle, module.nominal_angle, body, module.youngs_modulus,
                                              module.poisson_ratio)[0]
        c = law.hertz_constant.value * c_hertz / (law.hertz_constant.reference or c_hertz)
        force = float(state_c.normal_force[0, i])
        if force > 0.0:
            expected = c * force ** (2 / 3) + law.bulk_compliance.value * force
            worst = max(worst, abs(float(state_c.approach[0, i]) / expected - 1.0))
    run.check(model="lowmodel.screw.ball", quantity="max relative misfit of delta = C F^(2/3) + C_b F over "
              "the loaded contacts of ball 1 (Table 5 a, calibrated)", unit="1", value=worst, reference=0.0,
              scale=1.0, tolerance=1e-9, source="the calibrated law of each groove", time_s=time_c,
              why="a relative misfit: zero judged on the scale 1")
    # 2. Table 5 at the same oversize (geometric preload fitted with Hertz) and with the oversize refitted
    refit_oversize = ls.fitted_oversize(ls.READING, laws)
    rows, balance = [], 0.0
    for case in ("a", "b"):
        printed = ls.PRINTED[case]
        (free_h, state_h), _ = run.time(ls.two_ball, case, hertz_oversize)
        (free_c, state_c), time_c = run.time(ls.two_ball, case, hertz_oversize, ls.READING, laws)
        (free_r, state_r), time_r = run.time(ls.two_ball, case, refit_oversize, ls.READING, laws)
        balance = max([balance] + [abs(s.input_power - s.total_loss) / s.total_loss
                                   for s in (free_c, state_c, free_r, state_r)])
        rows.append((case, float(state_h.b2b_force[0]), float(state_c.b2b_force[0]), float(state_r.b2b_force[0]),
                     ls.friction_increase(free_h, state_h), ls.friction_increase(free_c, state_c),
                     ls.friction_increase(free_r, state_r)))
        if case == "b":
            run.check(model="lowmodel.screw.b2b", quantity="F_B2B, case b, calibrated laws (preload refitted "
                      "on case a)", unit="N", value=float(state_r.b2b_force[0]), reference=printed.f_b2b_numerical,
                      source="lin2019 Table 5, low-order numerical", tolerance=0.05, time_s=time_r,
                      note="the tolerance of lin2019-table5-b's Hertz prediction")
        run.check(model="lowmodel.screw.b2b", quantity=f"friction increase by B2B, case {case}, calibrated "
                  "laws (preload refitted on case a)", unit="%", value=ls.friction_increase(free_r, state_r),
                  reference=printed.friction_increase, source="lin2019 Sec 3.3",
                  tolerance=3.0 / printed.friction_increase, time_s=time_r,
                  note="tolerance 3 points, as lin2019-table5-a/b")
    run.check(model="lowmodel.screw.b2b", quantity="power balance |P_in - P_loss| / P_loss, calibrated laws",
              unit="1", value=balance, reference=0.0, scale=1.0, tolerance=1e-8, time_s=time_c,
              source="energy conservation (screw at rest, nut drives)", why=ls.POWER_WHY)
    # 3. load distribution over the balls of the nut
    (psi, loads_h, table_h), time_h = run.time(whole_screw_loads, module)
    (_, loads_c, table_c), time_l = run.time(whole_screw_loads, module, laws)
    for name, loads, t in (("Hertz", loads_h, time_h), ("calibrated", loads_c, time_l)):
        run.check(model="lowmodel.screw.load_distribution", quantity=f"sum of the ball loads, {name} contacts",
                  unit="N", value=float(loads.sum()), reference=WHOLE_SCREW_LOAD, tolerance=1e-9, time_s=t,
                  source="axial equilibrium of the nut")
    mean = WHOLE_SCREW_LOAD / WHOLE_SCREW_BALLS
    shift_h, shift_c = float(table_h.shift(mean)), float(table_c.shift(mean))
    spread_h, spread_c = loads_h.max() / loads_h.min(), loads_c.max() / loads_c.min()
    stiffer = abs(shift_c) < abs(shift_h)
    run.check(model="lowmodel.screw.load_distribution", quantity="load spread max/min, calibrated over Hertz "
              f"({'>= 1: stiffer' if stiffer else '<= 1: softer'} calibrated ball contacts)", unit="1",
              value=float(spread_c / spread_h), reference=1.0, relation="ge" if stiffer else "le", tolerance=0.0,
              time_s=time_l, source="bar model: stiffer balls against the same screw and nut bars spread the load "
                                    "less evenly (the limit of rigid balls puts it all on the first ball)")
    with open(run.path("load_distribution.csv"), "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["ball", "nut_azimuth_rad", "load_hertz_N", "load_calibrated_N", "change_percent"])
        for j, (p, h, c) in enumerate(zip(psi, loads_h, loads_c)):
            writer.writerow([j + 1, f"{p:.6f}", f"{h:.6f}", f"{c:.6f}", f"{100 * (c / h - 1):+.4f}"])
    run.add_artifact(run.path("load_distribution.csv"))
    change = 100 * (loads_c / loads_h - 1)
    parts = []
    for body in ("screw", "nut"):
        law = getattr(laws, body)
        c_hertz, a_unit, _ = screw_contacts.hertz_direct(module.ball_radius, module.conformity,
                                                         module.pitch_radius, module.lead_angle,
                                                         module.nominal_angle, body, module.youngs_modulus,
                                                         module.poisson_ratio)
        psi_hertz = a_unit / module.ball_radius ** (1 / 3)  # lin2019 eq 15
        parts.append(f"{body} groove: C {law.hertz_constant.value:.6g} m N^-2/3 (Hertz {c_hertz:.6g}, "
                     f"{100 * (law.hertz_constant.value / c_hertz - 1):+.2f} %), C_b {law.bulk_compliance.value:.4g} "
                     f"m/N [{law.bulk_compliance.ci_low:.4g}, {law.bulk_compliance.ci_high:.4g}], Psi "
                     f"{law.psi.value:.6g} (Hertz {psi_hertz:.6g}, {100 * (law.psi.value / psi_hertz - 1):+.2f} %)")
    constants = "; ".join(parts)
    run.note(f"Calibrated on {origin} ({fit_time:.0f} s). {constants}.")
    table = "; ".join(
        f"case {case}: F_B2B Hertz {fh:.4f} N, calibrated same oversize {fc:.4f} N ({100 * (fc / fh - 1):+.2f} %), "
        f"calibrated refitted oversize {fr:.4f} N ({100 * (fr / fh - 1):+.2f} %); friction increase Hertz "
        f"{ih:.2f} %, calibrated {ic:.2f} % / {ir:.2f} %" for case, fh, fc, fr, ih, ic, ir in rows)
    run.note(f"lin2019 Table 5 (50 N, {ls.READING} reading): oversize fitted with Hertz {hertz_oversize * 1e6:.4f} um, "
             f"refitted with the calibrated laws {refit_oversize * 1e6:.4f} um. {table}.  At the same oversize the "
             "stiffer calibrated contacts carry more preload and press the balls together harder.")
    run.note(f"Load distribution, {WHOLE_SCREW_BALLS} balls evenly over 2 turns, {WHOLE_SCREW_LOAD:g} N "
             f"(lowmodel.screw.load_distribution, preload {hertz_oversize * 1e6:.4f} um): ball 1 (loaded end) "
             f"Hertz {loads_h[0]:.3f} N, calibrated {loads_c[0]:.3f} N ({change[0]:+.3f} %); ball "
             f"{WHOLE_SCREW_BALLS} {loads_h[-1]:.3f} / {loads_c[-1]:.3f} N ({change[-1]:+.3f} %); change per ball "
             f"{change.min():+.3f} to {change.max():+.3f} % (load_distribution.csv); max/min {spread_h:.4f} (Hertz), "
             f"{spread_c:.4f} (calibrated). Axial shift of one ball at the mean load {mean:.2f} N: Hertz "
             f"{shift_h * 1e6:.4f} um, calibrated {shift_c * 1e6:.4f} um. lin2019 Table 5 printed "
             f"{lin2019.TABLE5_A.f_b2b_numerical} / {lin2019.TABLE5_B.f_b2b_numerical} N.")
