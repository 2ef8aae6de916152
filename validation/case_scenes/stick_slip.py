"""``<stem>-stick-slip`` of a linear guide or ball screw case (rung ``stick-slip``): the case's balls with
stick/slip contacts against lin2019's full slip on the same cells (studies.case_stick_slip): per contact Lambda, the
stick fraction, the force along rolling and the spin moment by both laws and the lateral force full slip lacks as a
share of mu F; the B2B force and the balls' friction by both laws, judged at full slip's declared accuracy
(docs/b2b_rolling.md, 'Validity of full slip'); the touching balls' stick/slip fields as ``stickslip_touching.npz``,
``.json`` and one ``stickslip_touching_<k>.vtu`` per contact, and their picture (validation.figures.stickslip3d,
docs/render3d.md)."""
from __future__ import annotations

from ballbench.validation.case_scenes.common import NEAR_ZERO_B2B, fmt
from ballbench.validation.cases.case import LinearGuideCase

__all__ = ["stick_slip_scene"]


def stick_slip_scene(run, *, case) -> None:
    """The scene function of ``<stem>-stick-slip`` (``case`` a LinearGuideCase or BallScrewCase)."""
    from ballbench.lowmodel import full_slip_validity as fsv
    from ballbench.validation.studies import case_stick_slip as study
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    guide = isinstance(case, LinearGuideCase)
    mu = case.guide.friction_coefficient if guide else case.screw.friction_coefficient
    result, wall = run.time(study.module, case, run.fidelity)
    cells = study.CELLS[run.fidelity]
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
    from ballbench.validation.figures import stickslip3d

    contacts = [(f"ball {ball + 1} {c.name}", c.solution) for ball, row in enumerate(result.touching.contacts)
                for c in row if c.solution is not None]
    if contacts:
        stickslip3d.artifacts(run, "touching", contacts, title=f"stick/slip contacts of the touching balls, {level}")
    run.note("Lambda = |phi| b G / (mu p0), the spin parameter: full slip holds for Lambda >> 1; the lateral force is "
             "what lin2019's full-slip maps (eqs A4-A7) leave out; the full-slip law on the same cells is pointwise "
             "Coulomb on the slip field, whose lateral force is shown beside; docs/b2b_rolling.md, 'Validity of full "
             "slip'.")

