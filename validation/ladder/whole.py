"""``<stem>-whole`` of a linear-guide case with a ``[carriage]`` table: the rigid carriage under the case's external
load (lowmodel.linear_bearing.carriage; docs/carriage.md): per row the ball loads, contact angles and pressures, the
carriage's displacement and 5 x 5 stiffness, the load-deflection curves; the balance of the carriage and of every
ball, and the contact pressure against the static limit of ISO 14728-2 (4200 MPa) as a finding; the friction of its
rows at the load and over a ball pitch of travel (lowmodel.linear_bearing.carriage_friction)."""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES
from ballbench.lowmodel.linear_bearing import carriage, carriage_friction
from ballbench.validation.ladder.common import fmt

__all__ = ["whole_scene", "STATIC_PRESSURE", "LOAD_FACTORS", "TRAVEL_STEPS"]

# ISO 14728-2 (rolling bearings, linear motion, static load ratings): the static load rating of a ball guide is the
# load giving 4200 MPa at the centre of the most heavily loaded contact
STATIC_PRESSURE = 4200e6  # Pa
LOAD_FACTORS = np.linspace(0.0, 1.5, 7)  # the load-deflection curves: the case's load times these
TRAVEL_STEPS = {"quick": 8, "default": 20, "fine": 40}  # the friction over one ball pitch of travel: steps per fidelity


def whole_scene(run, *, case) -> None:
    """The scene function of ``<stem>-whole`` (``case`` a LinearGuideCase with ``carriage`` and ``carriage_load``)."""
    from ballbench.validation.figures import carriage as figures

    body, load = case.carriage, case.carriage_load
    model = "lowmodel.linear_bearing.carriage"
    state, time_s = run.time(carriage.solve, body, load)
    run.check(model=model, family="low-order numerical", quantity="load balance of the carriage and of every ball",
              unit="1", value=state.balance, reference=0.0, scale=1.0, tolerance=carriage.BALANCE_TOLERANCE,
              time_s=time_s, source="the external load on the carriage (forces, moments over the half-length) and "
                                    "each ball's statics, over the largest force (docs/carriage.md)",
              why="the value is itself a relative force residual: zero judged on the scale 1")
    worst = float(state.p0.max())
    run.check(model=model, family="low-order numerical", quantity="largest contact pressure p0", unit="Pa",
              value=worst, reference=STATIC_PRESSURE, relation="le", tolerance=0.0, time_s=time_s, finding=True,
              source="the static limit of ISO 14728-2: 4200 MPa at the centre of the most loaded contact",
              note="beyond it the carriage is loaded past its static load rating")
    names = _contact_names(body)
    labels = [f"row {r + 1} (x {fmt(row.x * 1e3)} mm, y {fmt(row.y * 1e3)} mm)" for r, row in enumerate(body.rows)]
    rows = []
    for r, label in enumerate(labels):
        for c, name in enumerate(names[r]):
            q = state.normal_force[r, :, c]
            loaded = q > 0
            angles = np.degrees(state.contact_angle[r, :, c][loaded])
            spread = f"{fmt(float(np.min(angles)))} - {fmt(float(np.max(angles)))}" if np.any(loaded) else "-"
            least = fmt(float(q[loaded].min())) if np.any(loaded) else "-"
            rows.append((label, name, f"{int(loaded.sum())} / {len(q)}", fmt(float(q.max())), least,
                         fmt(float(state.p0[r, :, c].max()) / 1e6), spread))
    run.table(f"Ball loads per row and contact ({body.balls_per_row} balls per row, pitch {fmt(body.pitch * 1e3)} mm, "
              f"oversize {fmt(body.oversize * 1e6)} um)",
              ("row", "contact", "loaded balls", "Q max [N]", "Q min loaded [N]", "p0 max [MPa]",
               "contact angle to the lateral axis [deg]"), rows)
    run.table("Displacement of the carriage under the load",
              ("u_x [um]", "u_y [um]", "phi_x [mrad]", "phi_y [mrad]", "phi_z [mrad]"),
              [tuple(fmt(x) for x in (*(state.displacement[:2] * 1e6), *(state.displacement[2:] * 1e3)))])
    names5 = carriage.DISPLACEMENT_NAMES
    run.table("Stiffness of the carriage at the load, K = -dR/dq [N/m, N/rad; N m/m, N m/rad]",
              ("", *names5), [(names5[i], *(f"{state.stiffness[i, j]:.4g}" for j in range(5))) for i in range(5)])
    run.write_csv("balls.csv", [dict(row=r + 1, ball=k + 1, z_m=float(state.z[k]), contact=names[r][c],
                                     normal_force_N=float(state.normal_force[r, k, c]),
                                     contact_angle_rad=float(state.contact_angle[r, k, c]),
                                     a_m=float(state.a[r, k, c]), b_m=float(state.b[r, k, c]),
                                     p0_Pa=float(state.p0[r, k, c]))
                                for r in range(len(body.rows)) for k in range(body.balls_per_row)
                                for c in range(len(names[r]))])
    run.save_figure(figures.ball_loads(state.z, state.normal_force, labels, names[0]), "ball_loads.png")
    _friction_table(run, body, state)
    _friction_over_travel(run, body, load, figures)
    curve = []
    for factor in LOAD_FACTORS:
        if factor == 1.0:  # the state above
            curve.append(state.displacement)
            continue
        scaled = carriage.Load(*(factor * getattr(load, f) for f in ("lateral", "vertical", "pitch", "yaw", "roll")))
        curve.append(carriage.solve(body, scaled).displacement)
    run.save_figure(figures.load_deflection(LOAD_FACTORS, np.array(curve), "the case's carriage load"),
                    "load_deflection.png")
    run.write_csv("load_deflection.csv", [dict(factor=float(f), **{n: float(x) for n, x in zip(names5, q)})
                                          for f, q in zip(LOAD_FACTORS, curve)])
    run.note(f"The rigid carriage (lowmodel.linear_bearing.carriage, docs/carriage.md): {len(body.rows)} rows, "
             f"{body.balls_per_row} balls each, every ball's contacts by the curvature-centre distance and Hertz's "
             "law, "
             f"under F_x {fmt(load.lateral)} N, F_y {fmt(load.vertical)} N, M_x {fmt(load.pitch)} N m, M_y "
             f"{fmt(load.yaw)} N m, M_z {fmt(load.roll)} N m; {state.iterations} Newton steps.  The FE rung of "
             "an elastic carriage is not yet in this scene.")


def _contact_names(body) -> list[list[str]]:
    """Per row its contacts' names: lin2019's BL, BR, TR, TL for a gothic-arch row, rail / carriage for two-point."""
    return [list(CONTACT_NAMES) if len(row.normals) == 4 else ["rail", "carriage"][:len(row.normals)]
            for row in body.rows]


def _friction_table(run, body, state) -> None:
    """The friction of the carriage's rows at the state (lowmodel.linear_bearing.carriage_friction.friction): per row
    the drive force over its balls touching in chains, the laws that gave it and the balls without a model."""
    result, time_s = run.time(carriage_friction.friction, body, state)
    rows = []
    for r, row in enumerate(result.rows):
        counts = {law: row.law.count(law) for law in dict.fromkeys(row.law)}
        laws = ", ".join(f"{n} {law or 'no model'}" for law, n in counts.items())
        rows.append((r + 1, fmt(row.force), laws, fmt(float(np.max(row.b2b_forces, initial=0.0))), row.reason or "-"))
    run.table(f"Friction of the rows at the load: each row's balls touching in chains (lin2019 eqs 4-10 on the "
              f"carriage's contact loads; {time_s:.2f} s)", ("row", "friction force [N]", "balls by law",
                                                             "largest F_B2B [N]", "what the row says"), rows)
    total = "" if result.complete else " (a lower bound: balls without a model carry none here)"
    run.note(f"Friction force of the carriage at this load: {fmt(result.force)} N{total}, the drive force over every "
             "row's balls (lowmodel.linear_bearing.carriage_friction; a loose ball carries neither load nor friction, "
             "a ball with one to three open contacts has no model yet; docs/carriage.md).")


def _friction_over_travel(run, body, load, figures) -> None:
    """The drive force over one ball pitch of travel, with B2B contact and every ball alone, and the carriage's
    sinking over it (carriage_friction.friction_over_travel): a table of the steps, ``friction_over_travel.csv`` and
    ``.png``."""
    steps = TRAVEL_STEPS.get(run.fidelity, TRAVEL_STEPS["default"])
    result, time_s = run.time(carriage_friction.friction_over_travel, body, load, steps=steps,
                              loop=lambda travels: run.progress(travels, desc=f"{run.scene.name} travel"))
    rows = [(fmt(t * 1e3), fmt(f), fmt(a), "yes" if c else "no (lower bound)", fmt(d[1] * 1e6))
            for t, f, a, c, d in zip(result.travel, result.force, result.force_alone, result.complete,
                                     result.displacement)]
    run.table(f"Friction over one ball pitch of travel ({steps} steps, {time_s:.1f} s): the balls advance, leave "
              "the groove at one end and enter at the other", ("travel [mm]", "drive force with B2B [N]",
                                                             "every ball alone [N]", "every ball modelled",
                                                             "u_y [um]"), rows)
    run.write_csv("friction_over_travel.csv", [dict(travel_m=float(t), force_N=float(f), force_alone_N=float(a),
                                                    complete=bool(c), u_y_m=float(d[1]))
                                               for t, f, a, c, d in zip(result.travel, result.force,
                                                                        result.force_alone, result.complete,
                                                                        result.displacement)])
    run.save_figure(figures.friction_over_travel(result.travel, result.force, result.force_alone, result.complete,
                                                 result.displacement[:, 1]), "friction_over_travel.png")
    bound = "" if all(result.complete) else " (steps with balls without a model: lower bounds)"
    run.note(f"Over one pitch of travel the drive force is {fmt(result.mean)} N on average with B2B contact, ripple "
             f"{fmt(result.ripple)} N peak to peak{bound}; every ball alone {fmt(float(np.mean(result.force_alone)))}"
             f" N, ripple {fmt(float(np.ptp(result.force_alone)))} N; the carriage's u_y ripples by "
             f"{fmt(float(np.ptp(result.displacement[:, 1])) * 1e9)} nm (docs/carriage.md).")
