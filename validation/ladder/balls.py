"""``<stem>-balls`` of a linear guide or ball screw case: the low-order numerical model of the balls, touching and
apart: loads, angles, ellipses and pressures per ball and contact, the friction force [N] or torque [N m] with and
without B2B contact, the friction increase, the B2B forces (lowmodel.bearing_results); power balance and statics
checks; for a two-ball guide the analytical B2B model (lin2019 eq 30) against the numerical one."""
from __future__ import annotations


import numpy as np

from ballbench.lowmodel import bearing_results
from ballbench.lowmodel.geometry.fourpoint import contact_normals
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.ladder.common import (B2B_TOLERANCE, NEAR_ZERO_B2B, contact_table, fmt, power_check,
                                                truncation_check)

__all__ = ["balls_scene"]


def balls_scene(run, *, case, rungs) -> None:
    """The scene function of ``<stem>-balls``: ``case`` a LinearGuideCase or BallScrewCase, ``rungs`` those to run."""
    if isinstance(case, LinearGuideCase):
        _guide_balls(run, case, rungs, bearing_results)
    else:
        _screw_balls(run, case, bearing_results)


def _guide_balls(run, case: LinearGuideCase, rungs, bearing_results) -> None:
    guide = case.guide
    contacts = b2b.contacts(case)
    model = "lowmodel.linear_bearing.b2b"
    touching, time_touching = run.time(b2b.solve, contacts, np.zeros(case.n_balls - 1))
    free, time_free = run.time(b2b.solve, contacts, np.full(case.n_balls - 1, 1e-3))
    result = bearing_results.guide_result(case, touching, free, contacts)
    truncation_check(run, case, result, time_s=time_touching)
    power_check(run, model, touching, time_touching, "balls touching")
    power_check(run, model, free, time_free, "balls apart")
    statics = _eq36_residual(case, contacts)
    run.check(model=model, family="low-order numerical", quantity="ball statics, max |residual| / N_y", unit="1",
              value=statics, reference=0.0, scale=1.0, tolerance=1e-12, time_s=time_touching,
              source="vertical and lateral balance of each ball with the contact forces along the contact normals "
                     "(lin2017 Fig 2, eq 36)", why="the value is itself a relative force residual")
    if "analytical" in rungs and case.n_balls == 2 and case.deviations[0] == -case.deviations[1]:
        _guide_analytical(run, case, result)
    contact_table(run, result, "balls touching")
    v = abs(guide.groove_velocity)
    run.table("Friction of the balls (the carriage's drive force over them)",
              ("state", "friction force [N]", "power [W]", "B2B forces [N]", "velocity deviation epsilon [%]"),
              [("balls apart", fmt(result.friction_force_free), fmt(result.power_free), "-",
                " / ".join(fmt(100 * e) for e in result.velocity_deviation_free)),
               ("balls touching", fmt(result.friction_force), fmt(result.power),
                " / ".join(fmt(f) for f in result.b2b_forces), "-"),
               ("friction increase by B2B", fmt(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction force = power of the carriage's drive / speed ({fmt(v * 1e3)} mm/s), for the {case.n_balls} "
             "balls of the case; free balls: epsilon > 0 on ball 1 (behind) and < 0 on ball 2 makes them touch "
             "(lin2019 Sec 2.4).")


def _eq36_residual(case: LinearGuideCase, contacts) -> float:
    """Largest force residual of the balls' statics with the low-order normal forces [N_y]: with the outward unit
    normals ``n_i`` of lin2017 eq 1 the four forces of a ball balance, ``sum_i F_i n_i = 0``, and its two rail
    contacts (BL, BR) carry the ball's load, ``F_BL n_BL + F_BR n_BR = (N_x, -N_y)`` (lin2017 eq 36)."""
    worst = 0.0
    for ball in range(contacts.normal_forces.shape[0]):
        normals = np.asarray(contact_normals(contacts.contact_angles[ball]))  # (4, 2)
        forces = contacts.normal_forces[ball]
        load = np.array([case.side_force(ball), -case.vertical_force])
        residuals = (forces @ normals, forces[:2] @ normals[:2] - load)
        worst = max(worst, *(float(np.max(np.abs(r))) for r in residuals))
    return worst / case.vertical_force


def _guide_analytical(run, case: LinearGuideCase, result) -> None:
    from ballbench.lowmodel.linear_bearing import b2b_analytical

    guide = case.guide
    analytical, time_a = run.time(b2b_analytical.from_case, case)
    numerical = result.b2b_forces[0]
    scale = NEAR_ZERO_B2B * guide.friction_coefficient * case.vertical_force
    run.check(model="lowmodel.linear_bearing.b2b_analytical", family="analytical", quantity="F_B2B", unit="N",
              value=float(analytical.b2b_force), reference=numerical, scale=scale if numerical < scale else 0.0,
              tolerance=B2B_TOLERANCE["linear-guide"], time_s=time_a,
              source="the low-order numerical model (lowmodel.linear_bearing.b2b) of the same case",
              note="k_f = 1.38, Psi from Hertz; lin2019's own claim for eq 30: within 6-7 % of the numerical model",
              why="" if numerical >= scale else "a B2B force near zero judged against 5 % of mu N_y", finding=True)


def _screw_balls(run, case: BallScrewCase, bearing_results) -> None:
    model = "lowmodel.screw.b2b"
    contacts, time_contacts = run.time(screw_b2b.contacts, case)
    (free, touching), time_s = run.time(bearing_results.screw_states, case, contacts)
    time_s += time_contacts  # the model's run: its contacts and both states
    result = bearing_results.screw_result(case, touching, free, contacts)
    truncation_check(run, case, result, time_s=time_s)
    power_check(run, model, touching, time_s, "balls touching")
    power_check(run, model, free, time_s, "balls apart")
    shares = bearing_results.axial_shares(contacts, touching)
    run.check(model=model, family="low-order numerical", quantity="axial balance: sum of the balls' axial loads",
              unit="N", value=float(np.sum(shares)), reference=case.axial_load,
              scale=0.0 if case.axial_load > 0 else 1.0, tolerance=1e-9, time_s=time_s,
              source="the case's axial load on the screw (lin2019 eq 55)",
              why="" if case.axial_load > 0 else "zero axial load judged on 1 N")
    contact_table(run, result, "balls touching")
    run.table("Friction torque on the nut",
              ("state", "friction torque [N m]", "power [W]", "B2B forces [N]", "axial loads [N]"),
              [("balls apart", fmt(result.friction_torque_free), fmt(result.power_free), "-", "-"),
               ("balls touching", fmt(result.friction_torque), fmt(result.power),
                " / ".join(fmt(f) for f in result.b2b_forces), " / ".join(fmt(s) for s in result.axial_shares)),
               ("friction increase by B2B", fmt(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction torque = input power of the nut / its speed ({fmt(case.screw.nut_speed)} rad/s), for the "
             f"{len(case.deviations)} balls of the case; deviation reading {case.reading!r} (docs/ball_screw.md).")
