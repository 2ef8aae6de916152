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

__all__ = ["balls_scene", "GRID_CHECK_CELLS", "GRID_TOLERANCE"]

# where a guide's balls run on the stick/slip law (lowmodel.bearing_results.guide_states), its friction on these
# coarser cells bounds the grid error of the result's cells (lowmodel.bearing_results.STICK_SLIP_CELLS), judged at
# full slip's declared accuracy (lowmodel.full_slip_validity.TOLERANCE: 1 %)
GRID_CHECK_CELLS = (12, 48)
GRID_TOLERANCE = 0.01


def balls_scene(run, *, case, rungs) -> None:
    """The scene function of ``<stem>-balls``: ``case`` a LinearGuideCase or BallScrewCase, ``rungs`` those to run."""
    if isinstance(case, LinearGuideCase):
        _guide_balls(run, case, rungs, bearing_results)
    else:
        _screw_balls(run, case, bearing_results)


def _guide_balls(run, case: LinearGuideCase, rungs, bearing_results) -> None:
    guide = case.guide
    contacts = b2b.contacts(case)
    states, time_s = run.time(bearing_results.guide_states, case, contacts)
    model = states.model
    result = bearing_results.guide_result(case, contacts=contacts, states=states)
    truncation_check(run, case, result, time_s=time_s)
    power_check(run, model, states.touching, time_s, "balls touching")
    power_check(run, model, states.free, time_s, "balls apart")
    statics = _eq36_residual(case, contacts)
    run.check(model=model, family="low-order numerical", quantity="ball statics, max |residual| / N_y", unit="1",
              value=statics, reference=0.0, scale=1.0, tolerance=1e-12, time_s=time_s,
              source="vertical and lateral balance of each ball with the contact forces along the contact normals "
                     "(lin2017 Fig 2, eq 36)", why="the value is itself a relative force residual")
    if states.law == bearing_results.STICK_SLIP:
        _stick_slip_law(run, case, contacts, states, bearing_results.guide_stick_slip_states)
    elif "analytical" in rungs and case.n_balls == 2 and case.deviations[0] == -case.deviations[1]:
        _guide_analytical(run, case, result)
    contact_table(run, result, "balls touching")
    v = abs(guide.groove_velocity)
    run.table(f"Friction of the balls (the carriage's drive force over them; contact law: {result.law})",
              ("state", "friction force [N]", "power [W]", "B2B forces [N]", "velocity deviation epsilon [%]"),
              [("balls apart", fmt(result.friction_force_free), fmt(result.power_free), "-",
                " / ".join(fmt(100 * e) for e in result.velocity_deviation_free)),
               ("balls touching", fmt(result.friction_force), fmt(result.power),
                " / ".join(fmt(f) for f in result.b2b_forces), "-"),
               ("friction increase by B2B", fmt(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction force = power of the carriage's drive / speed ({fmt(v * 1e3)} mm/s), for the {case.n_balls} "
             "balls of the case; free balls: epsilon > 0 on ball 1 (behind) and < 0 on ball 2 makes them touch "
             "(lin2019 Sec 2.4).")


def _stick_slip_law(run, case, contacts, states, solve_states) -> None:
    """Where lin2019's full sliding has no state: say why, which law gave the numbers per ball and contact, and the
    stick/slip solve's grid error (the friction on :data:`GRID_CHECK_CELLS` against the result's cells; the states
    again by the stick/slip law alone, ``solve_states(case, contacts, cells=...)``)."""
    cells = states.cells
    guide = isinstance(case, LinearGuideCase)
    loads = ("lin2017 eq 36's, as under full sliding" if guide else
             "those of the frictionless statics (lowmodel.screw.preload; contacts unload past the preload loss)")
    run.note(f"Contact law: {bearing_results.STICK_SLIP} ({cells[0]} x {cells[1]} cells per contact, "
             f"{states.model}, docs/b2b_rolling.md), for every ball: lin2019's full-sliding solve found no state here "
             f"({states.reason}). A contact may stick (roll without spin) and its traction is then below mu p; the "
             f"loads are {loads}.")
    coarse, time_coarse = run.time(solve_states, case, contacts, cells=GRID_CHECK_CELLS)
    speed = abs(case.guide.groove_velocity if guide else case.screw.nut_speed)
    what, unit = ("friction force", "N") if guide else ("friction torque", "N m")
    level = f"{GRID_CHECK_CELLS[0]} x {GRID_CHECK_CELLS[1]} cells"
    for words, fine_state, coarse_state in (("balls apart", states.free, coarse.free),
                                            ("balls touching", states.touching, coarse.touching)):
        run.check(model=states.model, family="low-order numerical", level=level,
                  quantity=f"{what}, {words} (grid error of the stick/slip solve)", unit=unit,
                  value=coarse_state.input_power / speed, reference=fine_state.input_power / speed,
                  tolerance=GRID_TOLERANCE, time_s=time_coarse,
                  source=f"the same solve on {cells[0]} x {cells[1]} cells (the result's)",
                  note="the coarser grid's difference bounds the result's grid error (docs/b2b_rolling.md, 'Where "
                       "full sliding has no state')")
    mu = case.guide.friction_coefficient if guide else case.screw.friction_coefficient
    rows = []
    for ball, (touching_row, free_row) in enumerate(zip(states.touching.contacts, states.free.contacts)):
        for c_t, c_f in zip(touching_row, free_row):
            rows.append((ball + 1, c_t.name, fmt(c_t.normal_force), fmt(100 * c_t.stick_fraction, 3),
                         fmt(100 * c_f.stick_fraction, 3), fmt(c_t.spin_parameter, 3), fmt(c_t.spin_to_roll, 3),
                         fmt(abs(c_t.along_groove) / (mu * c_t.normal_force), 3)))
    run.table("Contact law per ball and contact (stick/slip on a half-space): stick area, spin and traction along "
              "the groove", ("ball", "contact", "F [N]", "stick touching [%]", "stick apart [%]",
                             "spin parameter Lambda", "spin / roll, touching", "F_along / (mu F), touching"), rows)
    run.write_csv("contact_law.csv", [dict(ball=r[0], contact=r[1], normal_force_N=r[2], stick_touching_pct=r[3],
                                           stick_apart_pct=r[4], spin_parameter=r[5], spin_to_roll=r[6],
                                           traction_ratio=r[7]) for r in rows])
    least = []
    for ball, row in enumerate(states.touching.contacts):
        loaded = [c for c in row if c.normal_force > 0]
        quiet = min(loaded, key=lambda c: c.spin_to_roll)
        spinning = sorted(c.spin_to_roll for c in loaded)
        least.append(f"ball {ball + 1}: {quiet.name} (spin / roll {fmt(quiet.spin_to_roll, 3)}, stick "
                     f"{fmt(100 * quiet.stick_fraction, 3)} %; next {fmt(spinning[1], 3)})")
    run.note("Race control as a result (Jones; Harris & Kotzalas: one contact rolls without spin, the others carry "
             "it): the contact of least spin per touching ball, " + "; ".join(least) + ". A contact rolls without "
             "spin where its spin / roll is small against the others' (docs/b2b_rolling.md, 'Where full sliding has "
             "no state').")


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
    contacts, time_contacts = run.time(screw_b2b.contacts, case)
    states, time_s = run.time(bearing_results.screw_law_states, case, contacts)
    time_s += time_contacts  # the model's run: its contacts and both states
    model = states.model
    result = bearing_results.screw_result(case, contacts=contacts, states=states)
    truncation_check(run, case, result, time_s=time_s)
    power_check(run, model, states.touching, time_s, "balls touching")
    power_check(run, model, states.free, time_s, "balls apart")
    if states.law == bearing_results.FULL_SLIDING:
        shares, words = bearing_results.axial_shares(contacts, states.touching), "sum of the balls' axial loads"
        source = "the case's axial load on the screw (lin2019 eq 55)"
    else:  # the normal loads are the frictionless statics': they carry the load, friction is not fed back
        shares = bearing_results.axial_shares(contacts, bearing_results.stick_slip_forces(states.loads,
                                                                                          states.touching, False))
        words = "sum of the balls' axial loads by their normal forces (frictionless statics)"
        source = "the case's axial load on the screw (lowmodel.screw.preload.frictionless_statics, lin2019 eq 53)"
    run.check(model=model, family="low-order numerical", quantity=f"axial balance: {words}",
              unit="N", value=float(np.sum(shares)), reference=case.axial_load,
              scale=0.0 if case.axial_load > 0 else 1.0, tolerance=1e-9, time_s=time_s, source=source,
              why="" if case.axial_load > 0 else "zero axial load judged on 1 N")
    if states.law != bearing_results.FULL_SLIDING:
        _stick_slip_law(run, case, contacts, states, bearing_results.screw_stick_slip_states)
        friction_share = float(np.sum(result.axial_shares) - np.sum(shares))
        run.note(f"Normal loads and friction are decoupled on this law: the friction's axial force on the balls, "
                 f"{fmt(friction_share)} N ({fmt(100 * friction_share / max(case.axial_load, 1.0), 3)} % of the "
                 "axial load), is not fed back into the frictionless loads (as in every stick/slip rung, "
                 "docs/b2b_rolling.md).")
    contact_table(run, result, "balls touching")
    run.table(f"Friction torque on the nut (contact law: {result.law})",
              ("state", "friction torque [N m]", "power [W]", "B2B forces [N]", "axial loads [N]"),
              [("balls apart", fmt(result.friction_torque_free), fmt(result.power_free), "-", "-"),
               ("balls touching", fmt(result.friction_torque), fmt(result.power),
                " / ".join(fmt(f) for f in result.b2b_forces), " / ".join(fmt(s) for s in result.axial_shares)),
               ("friction increase by B2B", fmt(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction torque = input power of the nut / its speed ({fmt(case.screw.nut_speed)} rad/s), for the "
             f"{len(case.deviations)} balls of the case; deviation reading {case.reading!r} (docs/ball_screw.md).")
