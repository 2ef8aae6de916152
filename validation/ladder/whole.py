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

__all__ = ["whole_scene", "STATIC_PRESSURE", "LOAD_FACTORS", "TRAVEL_STEPS", "FE_WALL_LEVELS", "FE_LOAD_TOLERANCE",
           "FE_STIFFNESS_TOLERANCE"]

# ISO 14728-2 (rolling bearings, linear motion, static load ratings): the static load rating of a ball guide is the
# load giving 4200 MPa at the centre of the most heavily loaded contact
STATIC_PRESSURE = 4200e6  # Pa
LOAD_FACTORS = np.linspace(0.0, 1.5, 7)  # the load-deflection curves: the case's load times these
TRAVEL_STEPS = {"quick": 4, "default": 10, "fine": 20}  # the friction over one ball pitch of travel: steps per fidelity
# the FE rung of an elastic carriage (fem.carriage_fe): the slot walls' mesh size over the patch radius, two levels
# per fidelity (the coarser one's difference from the finer one the FE's own uncertainty; docs/carriage.md)
FE_WALL_LEVELS = {"quick": (1.5, 2.0), "default": (2.0, 3.0), "fine": (3.0, 4.0)}
FE_LOAD_TOLERANCE = 0.05  # the rigid carriage's ball loads against the elastic body's, over the largest ball load
FE_STIFFNESS_TOLERANCE = 0.10  # and its stiffness's diagonal, relative


def whole_scene(run, *, case, rungs=("low-order",)) -> None:
    """The scene function of ``<stem>-whole`` (``case`` a LinearGuideCase with ``carriage`` and ``carriage_load``;
    with ``"FE"`` in ``rungs`` the FE rung of an elastic carriage)."""
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
    at_rest = _friction_table(run, body, state)
    _friction_over_travel(run, body, load, figures, at_rest)
    if "FE" in rungs:
        _fe_rung(run, body, load, figures)
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
             f"{fmt(load.yaw)} N m, M_z {fmt(load.roll)} N m; {state.iterations} Newton steps.")


def _contact_names(body) -> list[list[str]]:
    """Per row its contacts' names: lin2019's BL, BR, TR, TL for a gothic-arch row, rail / carriage for two-point."""
    return [list(CONTACT_NAMES) if len(row.normals) == 4 else ["rail", "carriage"][:len(row.normals)]
            for row in body.rows]


def _friction_table(run, body, state):
    """The friction of the carriage's rows at the state (lowmodel.linear_bearing.carriage_friction.friction): per row
    the drive force over its balls touching in chains, the laws that gave it and the balls without a model; returns
    the CarriageFriction."""
    result, time_s = run.time(carriage_friction.friction, body, state)
    rows = []
    for r, row in enumerate(result.rows):
        counts = {law: row.law.count(law) for law in dict.fromkeys(row.law)}
        laws = ", ".join(f"{n} {law or 'no model'}" for law, n in counts.items())
        rows.append((r + 1, fmt(row.force), laws, fmt(float(np.max(row.b2b_forces, initial=0.0))), row.reason or "-"))
    run.table(f"Friction of the rows at the load: each row's balls touching in chains (lin2019 eqs 4-10 on the "
              f"carriage's contact loads; {time_s:.2f} s)", ("row", "friction force [N]", "balls by law",
                                                             "largest F_B2B [N]", "what the row says"), rows)
    total = "" if result.complete else (" (approximate: touching balls solved in separate chains, or a ball without a "
                                        "state; the rows say which)")
    run.note(f"Friction force of the carriage at this load: {fmt(result.force)} N{total}, the drive force over every "
             "row's balls (lowmodel.linear_bearing.carriage_friction; a loose ball carries neither load nor friction, "
             "a ball with one to three open contacts takes the stick/slip law on its loaded ones; docs/carriage.md).")
    return result


def _friction_over_travel(run, body, load, figures, at_rest) -> None:
    """The drive force over one ball pitch of travel, with B2B contact and every ball alone, and the carriage's
    sinking over it (carriage_friction.friction_over_travel): a table of the steps, ``friction_over_travel.csv`` and
    ``.png``."""
    steps = TRAVEL_STEPS.get(run.fidelity, TRAVEL_STEPS["default"])
    result, time_s = run.time(carriage_friction.friction_over_travel, body, load, steps=steps, at_rest=at_rest,
                              loop=lambda travels: run.progress(travels, desc=f"{run.scene.name} travel"))
    rows = [(fmt(t * 1e3), fmt(f), fmt(a), "yes" if c else "no", "yes" if p else "no", fmt(d[1] * 1e6))
            for t, f, a, c, p, d in zip(result.travel, result.force, result.force_alone, result.complete,
                                        result.parted, result.displacement)]
    run.table(f"Friction over one ball pitch of travel ({steps} steps, {time_s:.1f} s): the balls advance, leave "
              "the groove at one end and enter at the other", ("travel [mm]", "drive force with B2B [N]",
                                                             "every ball alone [N]", "complete",
                                                             "a chain parted", "u_y [um]"), rows)
    run.write_csv("friction_over_travel.csv", [dict(travel_m=float(t), force_N=float(f), force_alone_N=float(a),
                                                    complete=bool(c), parted=bool(p), u_y_m=float(d[1]))
                                               for t, f, a, c, p, d in zip(result.travel, result.force,
                                                                           result.force_alone, result.complete,
                                                                           result.parted, result.displacement)])
    run.save_figure(figures.friction_over_travel(result.travel, result.force, result.force_alone, result.complete,
                                                 result.displacement[:, 1], result.parted),
                    "friction_over_travel.png")
    bound = "" if all(result.complete) else (f" ({int(np.sum(~result.complete))} of {steps} steps approximate: "
                                             "touching balls in separate chains, or a ball without a state)")
    run.note(f"Over one pitch of travel the drive force is {fmt(result.mean)} N on average with B2B contact, ripple "
             f"{fmt(result.ripple)} N peak to peak{bound}; every ball alone {fmt(float(np.mean(result.force_alone)))}"
             f" N, ripple {fmt(float(np.ptp(result.force_alone)))} N; the carriage's u_y ripples by "
             f"{fmt(float(np.ptp(result.displacement[:, 1])) * 1e9)} nm (docs/carriage.md).")


def _fe_rung(run, body, load, figures) -> None:
    """The elastic carriage body (fem.carriage_fe) against the rigid carriage at the case's load: per ball the
    largest contact load both ways, the worst ball, the stiffness's diagonal; two mesh levels, their difference the
    FE's own uncertainty."""
    from ballbench.fem import carriage_fe  # scikit-fem and gmsh: only on the FE rung

    radius = carriage_fe.default_patch_radius(body)
    shape = carriage_fe.body_shape(body)
    h_max = max(shape.half_width - shape.slot_half_width, shape.top - shape.slot_top) / 2.0
    levels, results = FE_WALL_LEVELS.get(run.fidelity, FE_WALL_LEVELS["default"]), []
    for ratio in run.progress(levels, desc=f"{run.scene.name} FE levels"):
        comparison, time_s = run.time(carriage_fe.compare, body, load, h_max=h_max, h_wall=radius / ratio)
        results.append((comparison, time_s))
    (coarse, _), (fine, time_s) = results
    model = "lowmodel.linear_bearing.carriage (rigid)"
    scale = float(fine.elastic_load.max())
    level_change = float(np.max(np.abs(coarse.elastic_load - fine.elastic_load))) / scale
    run.check(model="fem.carriage_fe", family="FE", quantity="load balance of the elastic carriage and its balls",
              unit="1", value=fine.elastic.balance, reference=0.0, scale=1.0, tolerance=carriage.BALANCE_TOLERANCE,
              time_s=time_s, source="the elastic carriage's solve (carriage.solve with the FE grooves' compliance)",
              why="the value is itself a relative force residual: zero judged on the scale 1")
    r, k = fine.worst
    run.check(model=model, family="low-order numerical", quantity="ball load of the worst ball against the elastic "
              "carriage", unit="N", value=float(fine.rigid_load[r, k]), reference=float(fine.elastic_load[r, k]),
              scale=scale, tolerance=FE_LOAD_TOLERANCE, time_s=time_s, finding=True,
              why="a ball's load is judged against the largest ball load of the carriage (a lightly loaded ball's "
                  "own load would magnify a small shift of load)",
              source=f"fem.carriage_fe: the carriage body elastic (P2, {fine.compliance.dofs} DOFs), the balls "
                     "Hertz's springs, the rail rigid",
              note=f"row {r + 1}, ball {k + 1}; error over the largest ball load {fmt(scale)} N; the FE levels "
                   f"differ by {fmt(level_change * 100)} % of it")
    names5 = carriage.DISPLACEMENT_NAMES
    vertical = 1
    run.check(model=model, family="low-order numerical", quantity="vertical stiffness against the elastic carriage",
              unit="N/m", value=float(fine.rigid.stiffness[vertical, vertical]),
              reference=float(fine.elastic.stiffness[vertical, vertical]), tolerance=FE_STIFFNESS_TOLERANCE,
              time_s=time_s, finding=True, source="fem.carriage_fe (as above)",
              note="the rigid carriage leaves out the body's own deflection")
    labels = [f"row {i + 1}" for i in range(len(body.rows))]
    run.table(f"Rigid against elastic carriage: the largest contact load of each ball [N] (FE {fine.compliance.dofs} "
              f"DOFs, {time_s:.1f} s; the coarser level {coarse.compliance.dofs} DOFs)",
              ("row", "ball", "z [mm]", "rigid", "elastic", "error [% of the largest]", "FE levels differ [N]"),
              [(labels[i], j + 1, fmt(float(fine.rigid.z[j]) * 1e3), fmt(float(fine.rigid_load[i, j])),
                fmt(float(fine.elastic_load[i, j])), fmt(float(fine.error[i, j]) * 100),
                fmt(float(coarse.elastic_load[i, j] - fine.elastic_load[i, j])))
               for i in range(len(body.rows)) for j in range(body.balls_per_row)])
    run.table("Stiffness's diagonal, rigid against elastic carriage [N/m, N m/rad]",
              ("", "rigid", "elastic", "rigid over elastic - 1 [%]"),
              [(names5[i], f"{fine.rigid.stiffness[i, i]:.4g}", f"{fine.elastic.stiffness[i, i]:.4g}",
                fmt(float(fine.stiffness_change[i]) * 100)) for i in range(5)])
    run.write_csv("rigid_elastic.csv", [dict(row=i + 1, ball=j + 1, z_m=float(fine.rigid.z[j]),
                                             rigid_N=float(fine.rigid_load[i, j]),
                                             elastic_N=float(fine.elastic_load[i, j]),
                                             elastic_coarse_N=float(coarse.elastic_load[i, j]))
                                        for i in range(len(body.rows)) for j in range(body.balls_per_row)])
    run.save_figure(figures.rigid_elastic(fine.rigid.z, fine.rigid_load, fine.elastic_load, labels),
                    "rigid_elastic.png")
    run.add_artifact(carriage_fe.write_vtu(run.path("elastic_carriage.vtu"), fine))
    run.note(f"FE rung (fem.carriage_fe, docs/carriage.md): the carriage body elastic, {fine.compliance.dofs} DOFs "
             f"(patch radius {fmt(radius * 1e3)} mm on the slot's walls, Hertz's local part "
             f"{fmt(fine.compliance.local * 1e9)} nm/N removed), {time_s:.1f} s; its displacement field in "
             "elastic_carriage.vtu (ParaView).  The rigid carriage is off by "
             f"{fmt(float(np.max(np.abs(fine.error))) * 100)} % of the largest ball load at its worst ball and "
             f"overestimates the vertical stiffness by {fmt(float(fine.stiffness_change[vertical]) * 100)} %; the two "
             f"FE levels differ by {fmt(level_change * 100)} % of the largest ball load.")
