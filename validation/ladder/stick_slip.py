"""``<stem>-stick-slip`` of a linear guide or ball screw case (rung ``stick-slip``): the case's balls with
stick/slip contacts against lin2019's full slip on the same cells (studies.case_stick_slip): per contact Lambda, the
stick fraction, the force along rolling and the spin moment by both laws and the lateral force full slip lacks as a
share of mu F; the B2B force and the balls' friction by both laws, judged at full slip's declared accuracy
(docs/b2b_rolling.md, 'Validity of full slip'), with the grid error of that comparison against finer cells
(docs/b2b_rolling.md, 'Grid error of the comparison'); the touching balls' stick/slip fields as
``stickslip_touching.npz``, ``.json`` and one ``stickslip_touching_<k>.vtu`` per contact, and their picture
(validation.figures.stickslip3d, docs/render3d.md)."""
from __future__ import annotations

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.validation.ladder.common import NEAR_ZERO_B2B, fmt, truncation_check
from ballbench.validation.cases.case import LinearGuideCase

__all__ = ["stick_slip_scene"]


def stick_slip_scene(run, *, case) -> None:
    """The scene function of ``<stem>-stick-slip`` (``case`` a LinearGuideCase or BallScrewCase)."""
    from ballbench.lowmodel import full_slip_validity as fsv
    from ballbench.lowmodel.contact.rolling_friction import FULL_SLIP_NAME
    from ballbench.validation.studies import case_stick_slip as study
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    guide = isinstance(case, LinearGuideCase)
    mu = case.guide.friction_coefficient if guide else case.screw.friction_coefficient
    truncation_check(run, case)  # full slip and stick/slip on half-spaces: Hertz's ellipses (docs/truncation.md)
    try:
        solved, wall = run.time(study.module, case, run.fidelity)
    except ConvergenceError as error:  # full slip on the cells has no state: nothing to compare, the law alone
        if not (guide and FULL_SLIP_NAME in str(error)):
            raise
        _stick_slip_alone(run, case, error, mu)
        return
    result, cells = solved.result, solved.cells
    if solved.note:
        run.note(solved.note)
    level = f"{cells[0]} x {cells[1]} cells"
    model = "full slip (lin2019 eqs A4-A7) on the same cells"
    source = "stick/slip on two half-spaces (lowmodel.contact.rolling_friction), the same case and cells"
    run.check(model="stick/slip (lowmodel.contact.rolling_friction)", family="low-order numerical", level=level,
              quantity="power balance |P_in - P_loss| / P_in, worst of the four solves", unit="1",
              value=result.power_balance, reference=0.0, scale=1.0, tolerance=1e-6, time_s=wall,
              source="energy conservation incl. the B2B loss (lin2019 eq 7; docs/b2b_rolling.md: 1e-6)",
              why="the value is itself a relative power error: zero judged on the scale 1")
    stick, full = float(result.touching.b2b_force[0]), float(result.full_slip.b2b_force[0])
    load = case.vertical_force if guide else max(case.axial_load, 1.0)
    near_zero = NEAR_ZERO_B2B * mu * load
    run.check(model=model, family="low-order numerical", level=level, quantity="F_B2B", unit="N", value=full,
              reference=stick, scale=near_zero if abs(stick) < near_zero else 0.0, tolerance=FULL_SLIP_TOLERANCE,
              time_s=wall, source=source, finding=True,
              note="full slip's declared accuracy on the B2B force: 2.5 % (validity map, docs/b2b_rolling.md)",
              why="" if abs(stick) >= near_zero else "a B2B force near zero judged against 5 % of mu times the load")
    speed = study.drive_speed(case)
    what, unit = ("friction force", "N") if guide else ("friction torque", "N m")
    for words, s, f in (("balls apart", result.free, result.full_slip_free),
                        ("balls touching", result.touching, result.full_slip)):
        run.check(model=model, family="low-order numerical", level=level, quantity=f"{what}, {words}", unit=unit,
                  value=f.input_power / speed, reference=s.input_power / speed, tolerance=fsv.TOLERANCE,
                  time_s=wall, source=source, finding=True,
                  note="full slip is enough where within 1 % of stick/slip (lowmodel.full_slip_validity.TOLERANCE)")
    rows = []
    for ball, (row_s, row_f) in enumerate(zip(result.touching.contacts, result.full_slip.contacts)):
        for c, g in zip(row_s, row_f):
            friction = mu * c.normal_force
            rows.append((ball + 1, c.name, fmt(c.normal_force), fmt(c.spin_parameter, 3), fmt(c.stick_fraction, 3),
                         fmt(c.along_groove), fmt(g.along_groove), fmt(c.spin_moment * 1e3),
                         fmt(g.spin_moment * 1e3), *((fmt(100 * abs(c.lateral) / friction, 3),
                                                      fmt(100 * abs(g.lateral) / friction, 3)) if friction > 0
                                                     else ("-", "-"))))
    run.table("Per contact, balls touching: stick/slip against full slip",
              ("ball", "contact", "F [N]", "Lambda", "stick fraction", "along rolling, stick/slip [N]",
               "along rolling, full slip [N]", "spin moment, stick/slip [N mm]", "spin moment, full slip [N mm]",
               "lateral / (mu F), stick/slip [%]", "lateral / (mu F), full slip [%]"), rows)
    run.table("B2B force and friction by law", ("law", "F_B2B [N]", f"{what} apart [{unit}]",
                                                f"{what} touching [{unit}]", "friction increase [%]"),
              [("stick/slip", fmt(stick), fmt(result.free.input_power / speed),
                fmt(result.touching.input_power / speed), fmt(result.friction_increase)),
               ("full slip", fmt(full), fmt(result.full_slip_free.input_power / speed),
                fmt(result.full_slip.input_power / speed), fmt(result.full_slip_increase))])
    _grid_error(run, case, solved, near_zero, what, unit, level)
    from ballbench.validation.figures import stickslip3d

    contacts = [(f"ball {ball + 1} {c.name}", c.solution) for ball, row in enumerate(result.touching.contacts)
                for c in row if c.solution is not None]
    if contacts:
        stickslip3d.artifacts(run, "touching", contacts, title=f"stick/slip contacts of the touching balls, {level}")
    _compliance_rungs(run, case, mu, load, speed, what, unit)
    run.note("Lambda = |phi| b G / (mu p0), the spin parameter: full slip holds for Lambda >> 1; the lateral force is "
             "what lin2019's full-slip maps (eqs A4-A7) leave out; the full-slip law on the same cells is pointwise "
             "Coulomb on the slip field, whose lateral force is shown beside; docs/b2b_rolling.md, 'Validity of full "
             "slip'.")


def _stick_slip_alone(run, case: LinearGuideCase, error, mu: float) -> None:
    """A guide whose module has no full-slip state on the rung's cells: the stick/slip law's states alone (its power
    balance, friction and B2B force, per contact Lambda and stick), and why there is no comparison."""
    from ballbench.validation.studies import case_stick_slip as study

    alone, wall = run.time(study.stick_slip_alone, case, run.fidelity)
    level = f"{alone.cells[0]} x {alone.cells[1]} cells"
    run.note(f"Full slip on the same cells has no state here ({str(error).split(' (residual')[0]}): there is no "
             "full-slip side to judge, and the rung gives the stick/slip law's states alone (as -balls does; "
             "docs/b2b_rolling.md, 'Where full sliding has no state').")
    for words, state in (("balls touching", alone.touching), ("balls apart", alone.free)):
        run.check(model="stick/slip (lowmodel.contact.rolling_friction)", family="low-order numerical", level=level,
                  quantity=f"power balance |P_in - P_loss| / P_in, {words}", unit="1", value=state.power_balance,
                  reference=0.0, scale=1.0, tolerance=1e-6, time_s=wall,
                  source="energy conservation incl. the B2B loss (lin2019 eq 7; docs/b2b_rolling.md: 1e-6)",
                  why="the value is itself a relative power error: zero judged on the scale 1")
    speed = abs(case.guide.groove_velocity)
    touching, free = alone.touching, alone.free
    run.table("B2B force and friction by the stick/slip law (full slip on the cells has no state)",
              ("law", "F_B2B [N]", "friction force apart [N]", "friction force touching [N]",
               "friction increase [%]"),
              [("stick/slip", fmt(float(touching.b2b_force[0])), fmt(free.input_power / speed),
                fmt(touching.input_power / speed), fmt(100 * (touching.total_loss / free.total_loss - 1.0)))])
    run.table("Per contact, balls touching: the stick/slip law",
              ("ball", "contact", "F [N]", "Lambda", "stick fraction", "along rolling [N]", "spin moment [N mm]",
               "lateral / (mu F) [%]"),
              [(ball + 1, c.name, fmt(c.normal_force), fmt(c.spin_parameter, 3), fmt(c.stick_fraction, 3),
                fmt(c.along_groove), fmt(c.spin_moment * 1e3), fmt(100 * abs(c.lateral) / (mu * c.normal_force), 3))
               for ball, row in enumerate(touching.contacts) for c in row])


def _grid_error(run, case, solved, near_zero: float, what: str, unit: str, level: str) -> None:
    """The grid error of the comparison of the laws (studies.case_stick_slip.grid_error): the change of full slip's
    difference to stick/slip from the rung's cells to finer ones, judged against the tolerance the difference is
    judged by (docs/b2b_rolling.md, 'Grid error of the comparison')."""
    from ballbench.lowmodel import full_slip_validity as fsv
    from ballbench.validation.studies import case_stick_slip as study
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    result = solved.result
    try:
        error = study.grid_error(case, run.fidelity, solved, near_zero)
    except ConvergenceError as failure:
        cells = study.GRID_CELLS[run.fidelity]
        run.note(f"No grid error of the comparison: the module on {cells[0]} x {cells[1]} cells has no converged "
                 f"state ({failure}); the checks above stand on {level} alone.")
        return
    finer = f"{error.finer[0]} x {error.finer[1]} cells"
    source = f"the same comparison on {finer} (both laws)"
    why = ("an estimate of the discretisation error of a judged relative difference (zero judged on the scale 1): "
           "the change to finer cells, within the tolerance the difference is judged by")
    run.check(model="stick/slip against full slip, the comparison's grid", family="low-order numerical", level=level,
              quantity="grid error of F_B2B (full slip - stick/slip) / stick/slip", unit="1", value=error.b2b,
              reference=0.0, scale=1.0, relation="le", tolerance=FULL_SLIP_TOLERANCE, time_s=error.finer_s,
              source=source, why=why,
              note=f"{level}: {100 * error.differences[0]:+.3f} %; {finer}: {100 * error.finer_differences[0]:+.3f} %"
                   + ("" if abs(float(result.touching.b2b_force[0])) >= near_zero else
                      " (a B2B force near zero: against 5 % of mu times the load)"))
    run.check(model="stick/slip against full slip, the comparison's grid", family="low-order numerical", level=level,
              quantity=f"grid error of the {what} full slip / stick/slip - 1", unit="1", value=error.friction,
              reference=0.0, scale=1.0, relation="le", tolerance=fsv.TOLERANCE, time_s=error.finer_s,
              source=source, why=why,
              note=f"apart, touching: {level}: {100 * error.differences[1]:+.3f} %, "
                   f"{100 * error.differences[2]:+.3f} %; {finer}: {100 * error.finer_differences[1]:+.3f} %, "
                   f"{100 * error.finer_differences[2]:+.3f} %")
    speed = study.drive_speed(case)
    rows = [(f"{cells[0]} x {cells[1]}", fmt(float(r.touching.b2b_force[0])), fmt(float(r.full_slip.b2b_force[0])),
             f"{100 * d[0]:+.3f}", f"{100 * d[1]:+.3f}", f"{100 * d[2]:+.3f}", fmt(r.touching.input_power / speed))
            for cells, r, d in ((error.cells, result, error.differences),
                                (error.finer, error.finer_result, error.finer_differences))]
    run.table("Grid error of the comparison: the rung's cells against finer ones",
              ("cells per contact", "F_B2B, stick/slip [N]", "F_B2B, full slip [N]", "F_B2B difference [%]",
               f"{what} apart, difference [%]", f"{what} touching, difference [%]",
               f"{what} touching, stick/slip [{unit}]"), rows)


def _compliance_rungs(run, case, mu: float, load: float, speed: float, what: str, unit: str) -> None:
    """The FE compliance rungs (studies.case_stick_slip.compliance_rungs): stick/slip with Hertz's pressure on the
    FE compliance of the case's groove (power balance) against the same module on two half-spaces on that grid:
    the half-space, the compliance of the rung above, judged at full slip's declared accuracy (F_B2B 2.5 %,
    friction 1 %; findings), the accuracy at which it judges full slip."""
    from ballbench.lowmodel import full_slip_validity as fsv
    from ballbench.validation.studies import case_stick_slip as study
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    rows = []
    for rung in study.compliance_rungs(case, run.fidelity, progress=run.progress):
        along, across, h = rung.level
        level = f"{along} x {across} cells, FE compliance P2, h {h:g} cell, {rung.ndofs} DOFs"
        reference = f"stick/slip, Hertz pressure + FE compliance of the case's groove ({along} x {across} cells)"
        model = f"stick/slip, Hertz pressure + two half-spaces ({along} x {across} cells of the FE compliance grid)"
        wall = rung.condense_s + rung.fe_s
        fe, half = rung.fe, rung.half_space
        run.check(model=reference, family="FE-informed", level=level,
                  quantity="power balance |P_in - P_loss| / P_in, worst of the four solves", unit="1",
                  value=fe.power_balance, reference=0.0, scale=1.0, tolerance=1e-6, time_s=wall,
                  source="energy conservation incl. the B2B loss (lin2019 eq 7; docs/b2b_rolling.md: 1e-6)",
                  why="the value is itself a relative power error: zero judged on the scale 1")
        stick, half_force = float(fe.touching.b2b_force[0]), float(half.touching.b2b_force[0])
        near_zero = NEAR_ZERO_B2B * mu * load
        note = ("the half-space is the compliance of the stick/slip rung above, which judges full slip at 2.5 % "
                "(F_B2B) and 1 % (friction): it is judged at the same accuracy")
        run.check(model=model, family="BEM", level=level, quantity="F_B2B", unit="N", value=half_force,
                  reference=stick, scale=near_zero if abs(stick) < near_zero else 0.0,
                  tolerance=FULL_SLIP_TOLERANCE, time_s=rung.half_space_s, source=reference, finding=True,
                  note=note, why="" if abs(stick) >= near_zero else "a B2B force near zero judged against 5 % of mu "
                                                                    "times the load")
        for words, h_state, f_state in (("balls apart", half.free, fe.free),
                                        ("balls touching", half.touching, fe.touching)):
            run.check(model=model, family="BEM", level=level, quantity=f"{what}, {words}", unit=unit,
                      value=h_state.input_power / speed, reference=f_state.input_power / speed,
                      tolerance=fsv.TOLERANCE, time_s=rung.half_space_s, source=reference, finding=True, note=note)
        for label, result, seconds in (("FE compliance", fe, wall), ("two half-spaces", half, rung.half_space_s)):
            lam = [c.spin_parameter for row in result.touching.contacts for c in row]
            stick_f = [c.stick_fraction for row in result.touching.contacts for c in row]
            rows.append((f"{along} x {across}", label, fmt(float(result.touching.b2b_force[0])),
                         fmt(float(result.full_slip.b2b_force[0])), fmt(result.free.input_power / speed),
                         fmt(result.touching.input_power / speed), fmt(result.friction_increase),
                         f"{min(lam):.0f}-{max(lam):.0f}", fmt(max(stick_f), 3), f"{seconds:.1f}"))
    if rows:
        run.table("Stick/slip on the FE compliance of the case's groove against two half-spaces on the same grid",
                  ("grid [cells]", "compliance", "F_B2B [N]", "F_B2B, full slip on the same cells [N]",
                   f"{what} apart [{unit}]", f"{what} touching [{unit}]", "friction increase [%]", "Lambda",
                   "stick fraction, largest", "time [s]"), rows)
        run.note("FE compliance: a ball of the case's radius in a straight groove of its conformity and material (P2, "
                 "condensed onto one grid over every contact; fem.rolling_compliance, cached on disk); it stands for "
                 "every contact of the module since the steady-state operator sees only the local shape of ball and "
                 "groove (docs/b2b_rolling.md). The FE rung's time includes the condensation (seconds when cached). "
                 "The compliance grid is coarser than the contacts' own grids above (one grid over every contact): "
                 "the forces of both laws move with it, so the laws are compared on the contacts' own grids above "
                 "and the compliances here.")
