"""Scenes of the calibration (lowmodel/calibration.py, validation/studies/calibration/, docs/calibration.md).

* ``calibration-roundtrip``: synthetic data from known constants plus noise;
  the fits recover them within their 95 % intervals, and over many seeds the
  intervals cover the truth as often as they claim.
* ``calibration-effect``: the contact stiffness law of the ball in a 0.56
  groove calibrated on FE (or given with ``--calibration FILE``) beside the
  Hertz-only values: approach and stiffness at 100 N, F_B2B of lin2019 Table 3
  case (a) by the analytical (eq 30) and the low-order numerical model.
"""
from __future__ import annotations

import csv
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b, b2b_analytical
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import lin2019
from ballbench.validation.references.published import lin2019 as published
from ballbench.validation.scene import scene
from ballbench.validation.studies import screw_two_ball
from ballbench.validation.studies.calibration import roundtrip as study
from ballbench.validation.studies.calibration.command import active_calibration
from ballbench.validation.studies.calibration.fe_laws import contact_law
from ballbench.validation.studies.fe_contact import load_sweep
from ballbench.validation.sweep.functions import with_psi

MODEL = "lowmodel.calibration"
CAL = dict(model=MODEL, family="low-order numerical")
GUIDE = lin2019.GUIDE
GROUP = f"ball-groove-{GUIDE.conformity:g}"
SEEDS = {"quick": 100, "default": 400, "fine": 2000}
SCREW_B2B = dict(model="lowmodel.screw.b2b", family="low-order numerical")
SCREW_BALL = dict(model="lowmodel.screw.ball", family="low-order numerical")
DISTRIBUTION = dict(model="lowmodel.screw.load_distribution", family="low-order numerical")
POWER_WHY = "the value is itself a relative power error |P_in - P_loss| / P_loss: zero judged on the scale 1"


@scene("calibration-roundtrip", "Calibration round trip: synthetic load-approach, contact-size, friction (CSV) and "
       "k_f data from known constants plus noise; the fits recover them within their 95 % intervals; coverage "
       "over many seeds", kind="low-order", cost_s=8.0)
def calibration_roundtrip(run):
    truth = study.synthetic_truth()
    with tempfile.TemporaryDirectory() as work:
        fitted, time_s = run.time(study.synthetic_fit, 2019, truth, Path(work), budget_s=0.05, max_repeat=3)
        path = cal.save(cal.Calibration({"roundtrip": fitted}), Path(work) / "calibration.json")
        loaded = cal.load(path)
    for name, constant in fitted.items():
        half = 0.5 * (constant.ci_high - constant.ci_low)
        run.check(**CAL, quantity=f"abs({name} - truth) / half-width of its 95 % interval (seed 2019)", unit="1",
                  value=abs(constant.value - truth[name]) / half, reference=1.0, relation="le", tolerance=0.0,
                  source=f"synthetic truth {truth[name]:.6g} {constant.unit}", time_s=time_s,
                  note=f"fit {constant.value:.6g} +- {constant.std_error:.2g} (1 SE)")
    same = all(loaded.get("roundtrip", n) == c for n, c in fitted.items())
    run.check(**CAL, quantity="constants that change through save/load of the calibration file", unit="count",
              value=float(not same), reference=0.0, scale=1.0, tolerance=0.0, source="JSON round trip",
              time_s=time_s)
    seeds = np.arange(SEEDS[run.fidelity])
    start = time.perf_counter()
    shares = study.coverage(seeds, truth)
    elapsed = (time.perf_counter() - start) / seeds.size
    for name, share in shares.items():
        run.check(**CAL, quantity=f"coverage of the 95 % interval of {name} over {seeds.size} seeds", unit="1",
                  value=share, reference=0.90, relation="ge", tolerance=0.0, time_s=elapsed,
                  source="docs/calibration.md: >= 90 % of seeded trials",
                  note=f"binomial sd of the share at 95 %: {math.sqrt(0.95 * 0.05 / seeds.size):.3f}")
    run.note(f"Truth: C = {truth['hertz_constant']:.6g} m N^-2/3 and Psi = {truth['psi']:.6g} (m^2/N)^(1/3) (Hertz, "
             f"conformity 0.56, R_B 5 mm), C_b = {study.BULK:g} m/N, mu = {study.MU_0} + {study.MU_V} s/m * v, "
             f"k_f = {study.K_F}. Noise: approach {study.NOISE_U:g} m, contact size {100 * study.NOISE_A:g} %, "
             f"friction {study.NOISE_F} N; {study.LOADS.size} loads {study.LOADS[0]:g}-{study.LOADS[-1]:g} N, "
             "12 friction rows (4 loads x 3 speeds, CSV in N and mm/s). Intervals: "
             "scipy least_squares, covariance s^2 (J^T J)^-1, Student t.")


# --------------------------------------------------------------------------
# effect of the calibrated contact law
# --------------------------------------------------------------------------
def _calibrated_contact_law(run) -> tuple[cal.Calibration, str]:
    """The contact law of the 0.56 groove: from ``--calibration FILE`` when it has one, else FE at the run's level."""
    given = active_calibration()
    if given is not None and GROUP in given.constants and "psi" in given.constants[GROUP]:
        return given, "the --calibration file"
    case = lin2019.CONTACT_GROOVE_056
    sweep = load_sweep(case, run.fidelity)
    geometry = sweep["geometry"]
    law = cal.fit_contact_law(sweep["force"], sweep["approach"], semi_axes=sweep["a"], ball_radius=case.ball_radius,
                              source=f"FE {case.name} {run.fidelity} level",
                              hertz_constant=hertz.hertz_constant(geometry),
                              psi=hertz.psi_constant(geometry, case.ball_radius))
    return cal.Calibration({GROUP: law.constants()}), (f"FE {case.name}, {run.fidelity} level "
                                                      f"({sweep['ndofs']} DOFs, {sweep['wall_time_s']:.0f} s)")


def _b2b_force_with_psi(psi: float, case) -> tuple[float, float]:
    """F_B2B [N] of the linear-guide ``case`` with contact semi-axes ``a = psi R^(1/3) F^(1/3)`` (lin2019 eq 15):
    (analytical eq 30, low-order numerical eqs 4-10)."""
    analytical = b2b_analytical.from_case(case, psi=psi)
    contacts = with_psi(b2b.contacts(case), psi)  # lin2017 eq 36 forces
    return float(analytical.b2b_force), float(b2b.solve(contacts, [0.0]).b2b_force[0])


@scene("calibration-effect", "The contact law of the 0.56 groove calibrated on FE (Psi, C, C_b) beside Hertz: "
       "approach and stiffness at 100 N, F_B2B of lin2019 Table 3 case (a), analytical and numerical",
       kind="low-order", cost_s=29.0)
def calibration_effect(run):
    start = time.perf_counter()
    calibration, origin = _calibrated_contact_law(run)
    fit_time = time.perf_counter() - start
    geometry = hertz.groove_geometry(GUIDE)
    c_hertz, psi_hertz = hertz.hertz_constant(geometry), hertz.psi_constant(geometry, GUIDE.ball_radius)
    psi = calibration.get(GROUP, "psi")
    c = calibration.get(GROUP, "hertz_constant")
    c_b = calibration.get(GROUP, "bulk_compliance")
    case = lin2019.TABLE3_A
    (hertz_analytical, hertz_numerical), time_h = run.time(_b2b_force_with_psi, psi_hertz, case)
    (cal_analytical, cal_numerical), time_c = run.time(_b2b_force_with_psi, psi.value, case)
    run.check(model="lowmodel.linear_bearing.b2b_analytical", family="analytical",
              quantity="F_B2B ratio calibrated / Hertz Psi, eq 30", unit="1", value=cal_analytical / hertz_analytical,
              reference=psi_hertz / psi.value, tolerance=1e-12,
              source="lin2019 eq 30: F_B2B proportional to 1/Psi", time_s=time_c)
    run.check(model="lowmodel.linear_bearing.b2b", family="low-order numerical",
              quantity="F_B2B, calibrated Psi, numerical model", unit="N",
              value=cal_numerical, reference=published.PRINTED.f_b2b_ansys, tolerance=0.07, time_s=time_c,
              source="lin2019 Table 3 case (a), ANSYS FEA",
              note=f"Hertz Psi: {hertz_numerical:.4f} N; tolerance: the paper's own claim (within 6-7 %)")
    law = cal.ContactLaw(c, c_b, psi)
    load = case.vertical_force
    approach_cal = float(law.approach(load))
    approach_hertz = c_hertz * load ** (2 / 3)  # lin2019 eq 53
    run.check(**CAL, quantity="calibrated approach U(100 N) against C F^(2/3) + C_b F", unit="m",
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
             "distribution over the balls of a screw: calibration-effect-screw.")
    from ballbench.validation.figures.hertz import approach_law

    run.save_figure(approach_law(law, c_hertz), "approach_law.png")


# --------------------------------------------------------------------------
# effect of the calibrated screw and nut groove laws on the ball screw
# --------------------------------------------------------------------------
SCREW_FE = {"screw": ("screw-groove", lin2019.CONTACT_SCREW), "nut": ("nut-groove", lin2019.CONTACT_NUT)}
SCREW_FE_FIDELITY = "quick"  # the full helical pairs: ~240k P2 DOFs, 1.5-2.5 min each at the quick level
WHOLE_SCREW_BALLS, WHOLE_SCREW_LOAD = lin2019.WHOLE_SCREW_BALLS, lin2019.WHOLE_SCREW_AXIAL_LOAD  # Sec 3.4


def _calibrated_groove_laws():
    """Laws of the screw and nut grooves: from ``--calibration FILE`` when it has the groups ``screw-groove`` and
    ``nut-groove``, else fitted to FE load sweeps of the Table 4 screw and nut contacts at the quick level.
    Returns (:class:`screw_contacts.GrooveContactLaws`, origin text)."""
    given = active_calibration()
    groups = [group for group, _ in SCREW_FE.values()]
    if given is not None and all(g in given.constants and "psi" in given.constants[g] for g in groups):
        return screw_contacts.GrooveContactLaws.from_calibration(given, *groups), "the --calibration file"
    laws, origin = {}, []
    for body, (_, case) in SCREW_FE.items():
        laws[body], sweep = contact_law(case, SCREW_FE_FIDELITY)
        origin.append(f"{sweep['source']} in {sweep['wall_time_s']:.0f} s")
    return screw_contacts.GrooveContactLaws(laws["screw"], laws["nut"]), "; ".join(origin)


def _whole_screw_loads(module, contact_law=None, *, n_balls: int = WHOLE_SCREW_BALLS,
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
       "friction increase of lin2019 Table 5", kind="low-order", cost_s=240.0, budget_s=400.0,
       memory_gb=5.0)
def calibration_effect_screw(run):
    case_a, printed_a = lin2019.TABLE5_A, published.TABLE5_A
    start = time.perf_counter()
    laws, origin = _calibrated_groove_laws()
    fit_time = time.perf_counter() - start
    hertz_oversize = lin2019.SCREW.oversize
    module = screw_contacts.module(lin2019.SCREW)
    # 1. the laws as the model uses them: every loaded contact of ball 1 (theta = 0, flanks at beta_0) obeys
    #    delta = C F^(2/3) + C_b F of its groove (reference from the calibrated constants and Hertz, not the model)
    (free_c, state_c), time_c = run.time(screw_two_ball.two_ball, case_a, None, None, laws)
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
    run.check(**SCREW_BALL, quantity="max relative misfit of delta = C F^(2/3) + C_b F over "
              "the loaded contacts of ball 1 (Table 5 a, calibrated)", unit="1", value=worst, reference=0.0,
              scale=1.0, tolerance=1e-9, source="the calibrated law of each groove", time_s=time_c,
              why="a relative misfit: zero judged on the scale 1")
    # 2. Table 5 at the same oversize (geometric preload fitted with Hertz) and with the oversize refitted
    refit_oversize = screw_two_ball.fit_oversize(case_a, printed_a.f_b2b_numerical, None, laws)
    rows, balance = [], 0.0
    friction_increase, two_ball = screw_two_ball.friction_increase, screw_two_ball.two_ball
    for case in ("a", "b"):
        printed, screw_case = published.TABLE5[case], lin2019.TABLE5[case]
        (free_h, state_h), _ = run.time(two_ball, screw_case)
        (free_c, state_c), time_c = run.time(two_ball, screw_case, None, None, laws)
        (free_r, state_r), time_r = run.time(two_ball, screw_case, refit_oversize, None, laws)
        balance = max([balance] + [abs(s.input_power - s.total_loss) / s.total_loss
                                   for s in (free_c, state_c, free_r, state_r)])
        rows.append((case, float(state_h.b2b_force[0]), float(state_c.b2b_force[0]), float(state_r.b2b_force[0]),
                     friction_increase(free_h, state_h), friction_increase(free_c, state_c),
                     friction_increase(free_r, state_r)))
        if case == "b":
            run.check(**SCREW_B2B, quantity="F_B2B, case b, calibrated laws (preload refitted "
                      "on case a)", unit="N", value=float(state_r.b2b_force[0]), reference=printed.f_b2b_numerical,
                      source="lin2019 Table 5, low-order numerical", tolerance=0.05, time_s=time_r,
                      note="the tolerance of lin2019-table5-b's Hertz prediction")
        run.check(**SCREW_B2B, quantity=f"friction increase by B2B, case {case}, calibrated "
                  "laws (preload refitted on case a)", unit="%", value=friction_increase(free_r, state_r),
                  reference=printed.friction_increase, source="lin2019 Sec 3.3",
                  tolerance=3.0 / printed.friction_increase, time_s=time_r,
                  note="tolerance 3 points, as lin2019-table5-a/b")
    run.check(**SCREW_B2B, quantity="power balance |P_in - P_loss| / P_loss, calibrated laws",
              unit="1", value=balance, reference=0.0, scale=1.0, tolerance=1e-8, time_s=time_c,
              source="energy conservation (screw at rest, nut drives)", why=POWER_WHY)
    # 3. load distribution over the balls of the nut
    (psi, loads_h, table_h), time_h = run.time(_whole_screw_loads, module)
    (_, loads_c, table_c), time_l = run.time(_whole_screw_loads, module, laws)
    for name, loads, t in (("Hertz", loads_h, time_h), ("calibrated", loads_c, time_l)):
        run.check(**DISTRIBUTION, quantity=f"sum of the ball loads, {name} contacts",
                  unit="N", value=float(loads.sum()), reference=WHOLE_SCREW_LOAD, tolerance=1e-9, time_s=t,
                  source="axial equilibrium of the nut")
    mean = WHOLE_SCREW_LOAD / WHOLE_SCREW_BALLS
    shift_h, shift_c = float(table_h.shift(mean)), float(table_c.shift(mean))
    spread_h, spread_c = loads_h.max() / loads_h.min(), loads_c.max() / loads_c.min()
    stiffer = abs(shift_c) < abs(shift_h)
    run.check(**DISTRIBUTION, quantity="load spread max/min, calibrated over Hertz "
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
        c_hertz, a_unit, _ = screw_contacts.hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                                     module.lead_angle, module.nominal_angle, body,
                                                     module.youngs_modulus, module.poisson_ratio)
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
    run.note(f"lin2019 Table 5 (50 N, {case_a.reading} reading): oversize fitted with Hertz "
             f"{hertz_oversize * 1e6:.4f} um, refitted with the calibrated laws {refit_oversize * 1e6:.4f} um. "
             f"{table}.  At the same oversize the stiffer calibrated contacts carry more preload and press the "
             "balls together harder.")
    run.note(f"Load distribution, {WHOLE_SCREW_BALLS} balls evenly over 2 turns, {WHOLE_SCREW_LOAD:g} N "
             f"(lowmodel.screw.load_distribution, preload {hertz_oversize * 1e6:.4f} um): ball 1 (loaded end) "
             f"Hertz {loads_h[0]:.3f} N, calibrated {loads_c[0]:.3f} N ({change[0]:+.3f} %); ball "
             f"{WHOLE_SCREW_BALLS} {loads_h[-1]:.3f} / {loads_c[-1]:.3f} N ({change[-1]:+.3f} %); change per ball "
             f"{change.min():+.3f} to {change.max():+.3f} % (load_distribution.csv); max/min {spread_h:.4f} (Hertz), "
             f"{spread_c:.4f} (calibrated). Axial shift of one ball at the mean load {mean:.2f} N: Hertz "
             f"{shift_h * 1e6:.4f} um, calibrated {shift_c * 1e6:.4f} um. lin2019 Table 5 printed "
             f"{published.TABLE5_A.f_b2b_numerical} / {published.TABLE5_B.f_b2b_numerical} N.")
