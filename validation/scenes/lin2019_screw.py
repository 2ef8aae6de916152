"""Scenes for the ball-screw B2B model (lin2019 Sec 3.1-3.3, Tables 4-5).

Models: lowmodel.screw.screw_ball (eqs 34-55), lowmodel.screw.screw_b2b (eqs 56-61).
Two-ball module of lin2019 Sec 3.3 (Table 4 parameters, the screw_module
defaults): ball 1 (behind, ball 0 here) theta = 0, ball 2 theta = 2 deg (case a)
or 3 deg (case b), 50 N axial load on the screw, balls touching.

Two readings the paper leaves open (docs/ball_screw.md):

* preload: Table 4 gives none.  ``oversize`` (the approach of every contact of a
  centred ball) is fitted on case (a)'s low-order B2B force alone; case (b) and
  both friction increases are then predictions.
* deviation (Fig 17 is missing): ``tilted`` (both screw flanks at beta_0 + theta)
  reproduces the paper; ``rotated`` (the screw profile turned by theta) cannot
  reach 1.92 N at any preload (its B2B force falls with preload from 1.0 N).

The literal reading (no preload) is reported beside it; where it misses the
paper it is a known gap (note of each scene).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ballbench.lowmodel.screw import screw_b2b, screw_ball
from ballbench.validation.scene import scene

MODEL = "lowmodel.screw.screw_b2b"
AXIAL_LOAD = 50.0  # N on the screw, lin2019 Sec 3.3
# lin2019 Table 5 (low-order numerical / ANSYS) and Sec 3.3 (friction increase)
PRINTED = {"a": {"theta_deg": 2.0, "f_b2b": 1.92, "f_b2b_ansys": 1.80, "increase": 39.2},
           "b": {"theta_deg": 3.0, "f_b2b": 2.89, "f_b2b_ansys": 2.71, "increase": 60.2}}
READING = "tilted"


def _module(oversize: float) -> screw_ball.ScrewModule:
    return screw_ball.screw_module(oversize=oversize)   # lin2019 Table 4 defaults (E = 210 GPa)


def two_ball(case: str, oversize: float, reading: str = READING):
    """(free balls, touching balls) of Table 5 case ``case`` at preload ``oversize`` [m]."""
    theta = math.radians(PRINTED[case]["theta_deg"])
    contacts = screw_ball.ball_contacts(_module(oversize), np.array([0.0, theta]), reading=reading)
    free = screw_b2b.solve(contacts, AXIAL_LOAD, with_b2b=False)
    state = screw_b2b.solve(contacts, AXIAL_LOAD)
    return free, state


def friction_increase(free, state) -> float:
    """Friction increase by B2B contact [%]: total loss of the touching balls over the free balls' loss."""
    return 100.0 * (state.total_loss / free.total_loss - 1.0)


@lru_cache(maxsize=2)
def fitted_oversize(reading: str = READING) -> float:
    """Preload (oversize [m]) at which case (a)'s B2B force is the paper's 1.92 N (brentq, 1e-12 m)."""
    from scipy.optimize import brentq

    target = PRINTED["a"]["f_b2b"]
    return float(brentq(lambda oversize: two_ball("a", oversize, reading)[1].b2b_force[0] - target, 1.0e-6,
                        3.0e-6, xtol=1e-12))


def _table5(run, case: str):
    printed = PRINTED[case]
    oversize = fitted_oversize()
    (free, state), time_s = run.time(two_ball, case, oversize)
    contacts = screw_ball.ball_contacts(_module(oversize), np.array([0.0, math.radians(printed["theta_deg"])]),
                                        reading=READING)
    _, solve_s = run.time(screw_b2b.solve, contacts, AXIAL_LOAD)
    force = float(state.b2b_force[0])
    increase = friction_increase(free, state)
    balance = max(abs(s.input_power - s.total_loss) / s.total_loss for s in (free, state))
    fitted = "fitted on this case" if case == "a" else "prediction (preload fitted on case a)"
    if case == "b":
        run.check(model=MODEL, quantity="F_B2B, case b", unit="N", value=force, reference=printed["f_b2b"],
                  source="lin2019 Table 5, low-order numerical", tolerance=0.05, time_s=solve_s, note=fitted)
    run.check(model=MODEL, quantity=f"F_B2B, case {case}", unit="N", value=force, reference=printed["f_b2b_ansys"],
              source="lin2019 Table 5, ANSYS FEA", tolerance=0.07, time_s=solve_s,
              note="the paper's own model is 6.7 % off ANSYS")
    run.check(model=MODEL, quantity=f"friction increase by B2B, case {case}", unit="%", value=increase,
              reference=printed["increase"], source="lin2019 Sec 3.3", tolerance=3.0 / printed["increase"],
              time_s=time_s, note="prediction (the fit uses the force only); tolerance 3 points")
    run.check(model=MODEL, quantity="power balance |P_in - P_loss| / P_loss", unit="1", value=balance,
              reference=0.0, scale=1.0, source="energy conservation (screw at rest, nut drives)",
              tolerance=1e-8, time_s=time_s)
    # literal reading: no preload (Table 4 gives none); the deviation reading does not matter there
    free_0, state_0 = two_ball(case, 0.0)
    force_0, increase_0 = float(state_0.b2b_force[0]), friction_increase(free_0, state_0)
    run.note(f"Preload fitted on case a: oversize {oversize * 1e6:.4f} um (every contact of a centred ball "
             f"approaches by this much; {READING} deviation reading, beta_SL = beta_SR = 45 deg + theta).  "
             f"Normal forces (SL, SR, NR, NL) of ball 2: {np.round(state.normal_force[1], 2).tolist()} N; "
             f"orbit speeds before contact {np.round(free.orbit_speed / (2 * math.pi), 5).tolist()} rev/s, "
             f"together {state.orbit_speed[0] / (2 * math.pi):.5f} rev/s; B2B loss {state.b2b_friction_loss[0]:.4e} W "
             f"of {state.total_loss:.4e} W.")
    run.note(f"Known gap, literal reading (no preload): F_B2B = {force_0:.3f} N against the paper's "
             f"{printed['f_b2b']} N ({100 * (force_0 / printed['f_b2b'] - 1):+.1f} %), friction increase "
             f"{increase_0:.1f} % against {printed['increase']} %.  Without preload the 50 N load leaves the "
             f"diagonal SR-NL unloaded except for the third contact NL that friction pushes each ball onto "
             f"(forces {np.round(state_0.normal_force[1], 2).tolist()} N), and F_B2B no longer scales with "
             f"theta as the paper's 2.89/1.92 = 1.505 = 3 deg/2 deg does (docs/ball_screw.md).")


@scene("lin2019-table5-a", "Ball screw, two balls, theta = 0 / 2 deg: B2B force and friction increase (Table 5 a)",
       tags=("lowmodel", "screw", "b2b"))
def lin2019_table5_a(run):
    _table5(run, "a")


@scene("lin2019-table5-b", "Ball screw, two balls, theta = 0 / 3 deg: predicted B2B force and friction increase "
       "(Table 5 b)", tags=("lowmodel", "screw", "b2b"))
def lin2019_table5_b(run):
    _table5(run, "b")
    oversize = fitted_oversize()
    force_a = two_ball("a", oversize)[1].b2b_force[0]
    force_b = two_ball("b", oversize)[1].b2b_force[0]
    force_a0 = two_ball("a", 0.0)[1].b2b_force[0]
    force_b0 = two_ball("b", 0.0)[1].b2b_force[0]
    run.note(f"F_B2B(b)/F_B2B(a): {force_b / force_a:.4f} with the fitted preload, {force_b0 / force_a0:.4f} "
             f"without (paper 2.89/1.92 = {2.89 / 1.92:.4f}).")
