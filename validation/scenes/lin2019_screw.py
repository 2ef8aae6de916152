"""Scenes for the ball-screw B2B model (lin2019 Sec 3.1-3.3, Tables 4-5).

Models: lowmodel.screw.ball (eqs 34-55), lowmodel.screw.b2b (eqs 56-61), through
studies.screw_two_ball.  Two-ball module of lin2019 Sec 3.3 (cases.lin2019.TABLE5): ball 1 (behind, ball 0
here) theta = 0, ball 2 theta = 2 deg (case a) or 3 deg (case b), 50 N axial load on the screw, balls touching.

Two readings the paper leaves open (docs/ball_screw.md):

* preload: Table 4 gives none.  The screw's ``oversize`` (the approach of every contact of a
  centred ball) is fitted on case (a)'s low-order B2B force alone (cases.lin2019.OVERSIZE_FIT); case (b)
  and both friction increases are then predictions.
* deviation (Fig 17 is missing): ``tilted`` (both screw flanks at beta_0 + theta)
  reproduces the paper; ``rotated`` (the screw profile turned by theta) cannot
  reach 1.92 N at any preload (its B2B force falls with preload from 1.0 N).

The literal reading (no preload) is checked beside it against the same printed
force and declared a known gap (``TABLE5_LITERAL_GAP``); so are the whole-screw
numbers of Fig 21 that depend on the missing Fig 19 (``FIG21_GAP``).
"""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import lin2019
from ballbench.validation.figures import lin2019 as figures
from ballbench.validation.references.published import lin2019 as published
from ballbench.validation.scene import KnownGap, scene
from ballbench.validation.studies.screw_two_ball import friction_increase, two_ball

MODEL = "lowmodel.screw.b2b"
LOW = dict(model=MODEL, family="low-order numerical")
PRINTED = published.TABLE5
POWER_WHY = "the value is itself a relative power error |P_in - P_loss| / P_loss: zero judged on the scale 1"
TABLE5_LITERAL_GAP = KnownGap(
    reason="Table 4 gives no preload.  Without one the 50 N load leaves the diagonal SR-NL unloaded except for the "
           "third contact NL that friction (the helix's relative rotation of nut and screw) pushes each ball onto, "
           "so F_B2B neither reaches the printed value nor scales with theta as the paper's numbers do "
           "(2.89 / 1.92 = 1.505 = 3 deg / 2 deg).",
    evidence="this scene: the fitted-preload reading (same model, oversize fitted on case a alone) predicts case b "
             "within 5 % and both friction increases within 3 points; the note gives the zero-preload contact "
             "forces and lin2019-table5-b the F_B2B(b)/F_B2B(a) ratio of both readings; docs/ball_screw.md "
             "(preload reading, 'rotated' reading unable to reach 1.92 N at any preload).")


def _table5(run, which: str):
    case = lin2019.TABLE5[which]
    printed = PRINTED[which]
    oversize = case.screw.oversize
    (free, state), time_s = run.time(two_ball, case)
    contacts = screw_b2b.contacts(case)
    _, solve_s = run.time(screw_b2b.solve, contacts, case.axial_load)
    force = float(state.b2b_force[0])
    increase = friction_increase(free, state)
    balance = max(abs(s.input_power - s.total_loss) / s.total_loss for s in (free, state))
    fitted = "fitted on this case" if which == "a" else "prediction (preload fitted on case a)"
    if which == "b":
        run.check(**LOW, quantity="F_B2B, case b", unit="N", value=force, reference=printed.f_b2b_numerical,
                  source="lin2019 Table 5, low-order numerical", tolerance=0.05, time_s=solve_s, note=fitted)
    run.check(**LOW, quantity=f"F_B2B, case {which}", unit="N", value=force, reference=printed.f_b2b_ansys,
              source="lin2019 Table 5, ANSYS FEA", tolerance=0.07, time_s=solve_s,
              note="the paper's own model is 6.7 % off ANSYS")
    run.check(**LOW, quantity=f"friction increase by B2B, case {which}", unit="%", value=increase,
              reference=printed.friction_increase, source="lin2019 Sec 3.3",
              tolerance=3.0 / printed.friction_increase,
              time_s=time_s, note="prediction (the fit uses the force only); tolerance 3 points")
    run.check(**LOW, quantity="power balance |P_in - P_loss| / P_loss", unit="1", value=balance,
              reference=0.0, scale=1.0, source="energy conservation (screw at rest, nut drives)",
              tolerance=1e-8, time_s=time_s, why=POWER_WHY)
    # literal reading: no preload (Table 4 gives none); the deviation reading does not matter there
    (free_0, state_0), time_0 = run.time(two_ball, case, 0.0)
    force_0, increase_0 = float(state_0.b2b_force[0]), friction_increase(free_0, state_0)
    run.check(**LOW, quantity=f"F_B2B, case {which}, literal reading (no preload)", unit="N", value=force_0,
              reference=printed.f_b2b_numerical, source="lin2019 Table 5, low-order numerical", tolerance=0.05,
              time_s=time_0, known_gap=TABLE5_LITERAL_GAP, note="the tolerance of the fitted-preload prediction")
    run.check(**LOW, quantity=f"friction increase by B2B, case {which}, literal reading (no preload)",
              unit="%", value=increase_0, reference=printed.friction_increase, source="lin2019 Sec 3.3",
              tolerance=3.0 / printed.friction_increase, time_s=time_0,
              known_gap=TABLE5_LITERAL_GAP if which == "b" else None,
              note="tolerance 3 points, as for the fitted-preload prediction"
                   + ("; met in case a although the force is not" if which == "a" else ""))
    run.note(f"Preload fitted on case a: oversize {oversize * 1e6:.4f} um (every contact of a centred ball "
             f"approaches by this much; {case.reading} deviation reading, beta_SL = beta_SR = 45 deg + theta).  "
             f"Normal forces (SL, SR, NR, NL) of ball 2: {np.round(state.normal_force[1], 2).tolist()} N; "
             f"orbit speeds before contact {np.round(free.orbit_speed / (2 * math.pi), 5).tolist()} rev/s, "
             f"together {state.orbit_speed[0] / (2 * math.pi):.5f} rev/s; B2B loss "
             f"{state.b2b_friction_loss[0]:.4e} W of {state.total_loss:.4e} W.")
    run.note(f"Literal reading (no preload, known gap): F_B2B = {force_0:.3f} N against the paper's "
             f"{printed.f_b2b_numerical} N ({100 * (force_0 / printed.f_b2b_numerical - 1):+.1f} %), friction "
             f"increase {increase_0:.1f} % against {printed.friction_increase} %.  Without preload the "
             f"{case.axial_load:g} N load leaves the diagonal SR-NL unloaded except for the third contact NL that "
             f"friction pushes each ball onto (forces {np.round(state_0.normal_force[1], 2).tolist()} N), and "
             f"F_B2B no longer scales with theta as the paper's (ratio of the cases = ratio of the deviations, "
             f"3 deg / 2 deg) does (docs/ball_screw.md).")


@scene("lin2019-table5-a", "Ball screw, two balls, theta = 0 / 2 deg: B2B force and friction increase (Table 5 a)",
       tags=("lowmodel", "screw", "b2b"), kind="low-order", cost_s=1.0, case=lin2019.TABLE5_A)
def lin2019_table5_a(run):
    _table5(run, "a")


@scene("lin2019-table5-b", "Ball screw, two balls, theta = 0 / 3 deg: predicted B2B force and friction increase "
       "(Table 5 b)", tags=("lowmodel", "screw", "b2b"), kind="low-order", cost_s=2.5, case=lin2019.TABLE5_B)
def lin2019_table5_b(run):
    _table5(run, "b")
    force_a = two_ball(lin2019.TABLE5_A)[1].b2b_force[0]
    force_b = two_ball(lin2019.TABLE5_B)[1].b2b_force[0]
    force_a0 = two_ball(lin2019.TABLE5_A, 0.0)[1].b2b_force[0]
    force_b0 = two_ball(lin2019.TABLE5_B, 0.0)[1].b2b_force[0]
    ratio = PRINTED["b"].f_b2b_numerical / PRINTED["a"].f_b2b_numerical
    run.note(f"F_B2B(b)/F_B2B(a): {force_b / force_a:.4f} with the fitted preload, {force_b0 / force_a0:.4f} "
             f"without (paper {ratio:.4f}).")


# --------------------------------------------------------------------------
# whole screw (lin2019 Sec 3.4, Figs 19-21)
# --------------------------------------------------------------------------
FIG21 = published.WHOLE_SCREW
WHOLE = dict(model="lowmodel.screw.whole_screw", family="low-order numerical")
FIG21_AMPLITUDE = math.radians(3.0)  # rad, deviation amplitude (Fig 19 missing): the largest Table 5 value
READING = lin2019.TABLE5_A.reading  # the deviation reading of the Table 5 fit (docs/ball_screw.md)
# the paper's 200 steps at every level: 50 steps resolve the gap history differently (5 groups instead of 4)
# and save only about 1 s of the scene's ~12 s
FIG21_STEPS = {"quick": lin2019.WHOLE_SCREW_STEPS, "default": lin2019.WHOLE_SCREW_STEPS,
               "fine": lin2019.WHOLE_SCREW_STEPS}
FIG21_ANGLE_TOLERANCE = 10.0  # deg of nut angle on the printed angles (Fig 21 is read to a few degrees)
FIG21_GAP = KnownGap(
    reason="Fig 19 (the deviation theta along the screw: amplitude and phase) is missing and the static load "
           "distribution of lin2019's ref [19] is not given, so the whole screw is simulated with an assumed "
           "amplitude (3 deg, the largest Table 5 deviation), phase and a documented low-order load distribution "
           "(lowmodel.screw.load_distribution); the preload is the one fitted on Table 5 a.  The groups form and "
           "dissolve as in the paper (four groups, checked), but the peak height and the angles follow the "
           "unknown inputs.",
    evidence="docs/ball_screw.md, whole-screw table: the peak extra torque is very sensitive to the amplitude "
             "(18.3 % at 104 deg for 2 deg, 52.7 % at 90 deg for 2.7 deg, 70.5 % at 101 deg for 3 deg; first "
             "angle without B2B 248 / 281 / 292 deg), so an amplitude near 2.65 deg would match the peak height "
             "but not its angle; fig20.png / fig21.png of this scene.")


def _whole_screw(steps: int, progress=None):
    """History of lin2019 Sec 3.4 with the Table 5 preload fit and the tilted deviation reading."""
    from ballbench.lowmodel.screw import whole_screw as ws
    return ws.simulate(screw_contacts.module(lin2019.SCREW), n_balls=lin2019.WHOLE_SCREW_BALLS,
                       axial_load=lin2019.WHOLE_SCREW_AXIAL_LOAD, duration=lin2019.WHOLE_SCREW_DURATION,
                       steps=steps, amplitude=FIG21_AMPLITUDE, cycles=lin2019.WHOLE_SCREW_THETA_CYCLES,
                       reading=READING, progress=progress)


def _fig21_summary(history) -> dict:
    """Groups, peak extra torque [%] and its nut angle [deg], the first nut angle after the peak with no B2B."""
    ratio = history.b2b_torque / history.groove_torque
    degrees = np.degrees(history.nut_angle)
    peak = int(np.argmax(ratio))
    after = np.flatnonzero(history.b2b_torque[peak:] == 0.0)
    groups = [history.groups(step) for step in range(len(history.time))]
    return {"groups": max(groups), "groups_per_step": groups, "peak_increase": 100.0 * float(ratio[peak]),
            "peak_angle_deg": float(degrees[peak]),
            "zero_angle_deg": float(degrees[peak + after[0]]) if after.size else float("nan"),
            "min_after_peak": float(ratio[peak:].min())}


@scene("lin2019-fig21", "Whole ball screw, 37 balls, 1500 N, 2 s: B2B groups and friction torque (Figs 20-21)",
       tags=("lowmodel", "screw", "b2b", "slow"), kind="low-order", cost_s=13.0)
def lin2019_fig21(run):
    steps = FIG21_STEPS[run.fidelity]
    start = time.perf_counter()
    history = _whole_screw(steps, progress=lambda it: run.progress(it, desc="whole screw steps"))
    elapsed = time.perf_counter() - start
    summary = _fig21_summary(history)
    run.check(**WHOLE, quantity="power balance, worst step", unit="1",
              value=float(history.power_error.max()), reference=0.0, scale=1.0, tolerance=1e-8, time_s=elapsed,
              source="energy conservation (screw at rest, nut drives)", why=POWER_WHY)
    run.check(**WHOLE, quantity="number of B2B groups", unit="1",
              value=summary["groups"], reference=FIG21.groups, tolerance=0.0, time_s=elapsed,
              source="lin2019 Sec 3.4 / Fig 20: four groups", note="most groups at any step")
    run.check(**WHOLE, quantity="B2B torque / groove torque after the peak, minimum",
              unit="1", value=summary["min_after_peak"], reference=0.0, scale=1.0, tolerance=0.0, time_s=elapsed,
              source="lin2019 Sec 3.4 / Fig 21: the groups dissolve (zero B2B torque at 306 deg)")
    run.check(**WHOLE, quantity="peak extra friction torque by B2B", unit="%",
              value=summary["peak_increase"], reference=FIG21.peak_increase, tolerance=0.1, time_s=elapsed,
              source="lin2019 Sec 3.4 / Fig 21: 49.6 %", known_gap=FIG21_GAP, note="tolerance 10 % of the peak")
    peak_deg, zero_deg = math.degrees(FIG21.peak_angle), math.degrees(FIG21.zero_angle)
    run.check(**WHOLE, quantity="nut angle of the peak extra torque", unit="deg",
              value=summary["peak_angle_deg"], reference=peak_deg, tolerance=FIG21_ANGLE_TOLERANCE / peak_deg,
              time_s=elapsed, source="lin2019 Sec 3.4 / Fig 21: 126 deg", known_gap=FIG21_GAP,
              note=f"tolerance {FIG21_ANGLE_TOLERANCE:g} deg")
    run.check(**WHOLE, quantity="first nut angle after the peak without B2B", unit="deg",
              value=summary["zero_angle_deg"], reference=zero_deg, tolerance=FIG21_ANGLE_TOLERANCE / zero_deg,
              time_s=elapsed, source="lin2019 Sec 3.4 / Fig 21: 306 deg", known_gap=FIG21_GAP,
              note=f"tolerance {FIG21_ANGLE_TOLERANCE:g} deg")
    run.note(f"Beside the paper (Fig 21): peak extra torque by B2B {summary['peak_increase']:.1f} % at nut angle "
             f"{summary['peak_angle_deg']:.0f} deg (paper {FIG21.peak_increase} % at "
             f"{math.degrees(FIG21.peak_angle):.0f} deg); no B2B first at {summary['zero_angle_deg']:.0f} deg after "
             f"the peak (paper {math.degrees(FIG21.zero_angle):.0f} deg); groups {summary['groups']} (paper "
             f"{FIG21.groups}).  Known gap (checks above): not fitted are the deviation amplitude "
             f"({math.degrees(FIG21_AMPLITUDE):.1f} deg, the largest Table 5 deviation; Fig 19 is missing; the peak "
             f"is 18 % at 2 deg and 53 % at 2.7 deg), the phase of theta along the screw, the load distribution "
             f"(ref [19] unavailable; lowmodel.screw.load_distribution) and the preload (fitted on Table 5 a); "
             f"docs/ball_screw.md.")
    run.note(f"{steps} steps over {lin2019.WHOLE_SCREW_DURATION} s ({run.fidelity}); "
             f"{int(history.iterations.sum())} Newton iterations in {elapsed:.1f} s; axial loads per ball "
             f"{history.axial_load.min():.1f} .. "
             f"{history.axial_load.max():.1f} N; friction torque ball-to-groove "
             f"{1e3 * history.groove_torque.mean():.1f} mN m (mean).")
    run.save_figure(figures.whole_screw_spacing(history), "fig20.png")
    run.save_figure(figures.whole_screw_torque(history), "fig21.png")


# --------------------------------------------------------------------------
# robustness of the screw solvers
# --------------------------------------------------------------------------
def _stability_cases(fidelity: str) -> list[dict]:
    """Cases of ``lin2019-screw-stability``: lead angle, preload, deviation, number of balls, load."""
    quick = fidelity == "quick"
    cases = []
    for lead_deg in ((2.0, 25.0) if quick else (2.0, 5.0, 10.0, 15.0, 20.0, 25.0)):
        cases.append({"what": f"lead angle {lead_deg:g} deg", "lead_angle_deg": lead_deg, "oversize": 1.7e-6,
                      "thetas": (0.0, 2.0), "load": 25.0})
    for theta in ((0.0, 3.0) if quick else (0.0, 1.0, 2.0, 3.0)):
        for load in ((1.0, 100.0) if quick else (1.0, 25.0, 100.0)):
            cases.append({"what": f"no preload (contacts open), theta {theta:g} deg, {load:g} N", "oversize": 0.0,
                          "thetas": (0.0, theta), "load": load})
    for reading in ("rotated", "tilted"):
        for theta in (-3.0, 3.0):
            cases.append({"what": f"theta {theta:+g} deg ({reading})", "oversize": 1.7e-6, "thetas": (0.0, theta),
                          "load": 25.0, "reading": reading})
    rng = np.random.default_rng(11)
    for n in ((1, 2, 20) if quick else (1, 2, 5, 20, 100)):
        cases.append({"what": f"{n} balls, random theta in [-3, 3] deg", "oversize": 1.7e-6,
                      "thetas": tuple(rng.uniform(-3.0, 3.0, n)), "load": 25.0})
    for load in ((1.0, 5000.0) if quick else (1.0, 10.0, 100.0, 1000.0, 5000.0)):
        cases.append({"what": f"{load:g} N per ball", "oversize": 1.7e-6, "thetas": (0.0, 2.0), "load": load})
    return cases


def _run_stability_case(case: dict):
    """Solve one case; returns the state (ConvergenceError / ValueError propagate)."""
    pitch_radius = lin2019.SCREW.pitch_radius
    lead = 2.0 * math.pi * pitch_radius * math.tan(math.radians(case.get("lead_angle_deg", math.degrees(
        math.atan(lin2019.SCREW.lead / (2 * math.pi * pitch_radius))))))
    module = screw_contacts.module(dataclasses.replace(lin2019.SCREW, lead=lead, oversize=case["oversize"]))
    contacts = screw_contacts.ball_contacts(module, np.radians(case["thetas"]), reading=case.get("reading", READING))
    return screw_b2b.solve(contacts, case["load"] * len(case["thetas"]))


@scene("lin2019-screw-stability", "Ball-screw solvers over lead angle, preload, deviation, 1-100 balls, 1 N-5 kN",
       tags=("lowmodel", "screw", "robustness"), kind="low-order", cost_s=21.0)
def lin2019_screw_stability(run):
    cases = _stability_cases(run.fidelity)
    converged, failures, no_state, worst_power, nan_count = 0, [], [], 0.0, 0
    start = time.perf_counter()
    for case in run.progress(cases, desc="stability cases"):
        try:
            state = _run_stability_case(case)
        except (ConvergenceError, ValueError) as error:
            if "no full-sliding state" in str(error):
                no_state.append(f"{case['what']}: {error}")
            else:
                failures.append(f"{case['what']}: {error}")
            continue
        arrays = (state.orbit_speed, state.omega, state.normal_force, state.friction_loss, state.b2b_force)
        nan_count += int(sum(np.count_nonzero(~np.isfinite(a)) for a in arrays))
        worst_power = max(worst_power, abs(state.input_power - state.total_loss) / state.total_loss)
        converged += 1
    elapsed = time.perf_counter() - start
    exists = len(cases) - len(no_state)
    run.check(**LOW, quantity="converged cases / cases with a state", unit="1", value=converged / exists,
              reference=1.0, tolerance=0.0, time_s=elapsed / len(cases),
              source="docs/ball_screw.md (robustness): 100 % converged where a state exists",
              note=f"{len(cases)} cases, {len(no_state)} without a full-sliding state (reasons below)")
    run.check(**LOW, quantity="non-finite outputs", unit="1", value=nan_count, reference=0.0, scale=1.0,
              tolerance=0.0, time_s=elapsed / len(cases), source="docs/ball_screw.md (robustness): no NaN")
    run.check(**LOW, quantity="power balance, worst case", unit="1", value=worst_power, reference=0.0,
              scale=1.0, tolerance=1e-8, time_s=elapsed / len(cases), source="energy conservation", why=POWER_WHY)
    run.note("Cases: " + "; ".join(case["what"] for case in cases) + ".")
    if no_state:
        run.note("No state (friction saturated, reason given by the solver): " + " | ".join(no_state))
    if failures:
        run.note("Failures: " + " | ".join(failures))
