"""``<stem>-whole`` of a ball-screw case with a ``[nut]`` table: the whole nut (lowmodel.screw.nut; docs/nut.md).
A single nut: the axial load of every ball along the nut, the axial stiffness curve, the friction torque over one
nut revolution (lin2019 Sec 3.4's whole screw over the nut's turns) with its ball-to-groove and B2B parts and its
power balance; at the FE rung an elastic nut against the bar (fem.nut_fe).  A double nut: the halves' loads against
the axial load, the lift-off load (exact two-point balls and Hertz's ``2^(3/2) F_pr``), the stiffness; its friction
has no model yet (two-point balls)."""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.validation.ladder.common import fmt

__all__ = ["nut_scene", "LOAD_FACTORS", "ROTATION_STEPS", "POWER_TOLERANCE", "FE_BORE_LEVELS", "FE_LOAD_TOLERANCE",
           "FE_STIFFNESS_TOLERANCE"]

LOAD_FACTORS = np.linspace(0.0, 1.5, 7)  # the stiffness curve: the nut's load times these
ROTATION_STEPS = {"quick": 40, "default": 200, "fine": 400}  # the friction over one nut revolution
POWER_TOLERANCE = 1e-8  # the whole screw's power balance |P_in - P_loss| / P_loss of every step
# the FE rung of an elastic nut (fem.nut_fe): the bore's mesh size over the patch radius, two levels per fidelity
FE_BORE_LEVELS = {"quick": (2.0, 3.0), "default": (3.0, 4.5), "fine": (4.5, 6.0)}
FE_LOAD_TOLERANCE = 0.05  # the bar nut's ball loads against the elastic nut's, over the largest ball load
FE_STIFFNESS_TOLERANCE = 0.10  # and its axial stiffness, relative


def nut_scene(run, *, case, rungs=("low-order",)) -> None:
    """The scene function of ``<stem>-whole`` for a BallScrewCase with a ``nut`` (with ``"FE"`` in ``rungs`` a
    single nut's FE rung of an elastic nut)."""
    from ballbench.lowmodel.screw import nut as nuts  # the nut's models: only when the scene runs
    from ballbench.validation.figures import nut as figures

    if case.nut.arrangement == "double":
        _double(run, case, nuts, figures)
    else:
        _single(run, case, nuts, figures, fe="FE" in rungs)


def _single(run, case, nuts, figures, fe: bool) -> None:
    body, load = case.nut, case.nut_load
    model = "lowmodel.screw.nut"
    state, time_s = run.time(nuts.distribution, body, load)
    run.check(model=model, family="low-order numerical", quantity="axial balance of the nut's balls", unit="1",
              value=state.balance, reference=0.0, scale=1.0, tolerance=nuts.BALANCE_TOLERANCE_SINGLE,
              time_s=time_s, source="the balls' axial loads against the nut's axial load (docs/nut.md)",
              why="the value is itself a relative force residual: zero judged on the scale 1")
    q = state.ball_loads
    head = (f"The whole single nut (lowmodel.screw.nut, docs/nut.md): {body.balls} balls in {body.turns} turns, "
            f"{fmt(load)} N; the loaded end's ball carries {fmt(float(q[0] / q.mean()))} times the mean (screw and "
            "nut as bars).")
    run.table(f"Axial ball loads along the nut ({body.balls} balls in {body.turns} turns, {fmt(load)} N; "
              f"{time_s:.2f} s)", ("", "ball 1 (loaded end)", "ball n", "largest", "smallest", "mean"),
              [("q [N]", fmt(float(q[0])), fmt(float(q[-1])), fmt(float(q.max())), fmt(float(q.min())),
                fmt(float(q.mean())))])
    run.write_csv("ball_loads.csv", [dict(ball=k + 1, azimuth_rad=float(p), z_m=float(z), axial_load_N=float(f))
                                     for k, (p, z, f) in enumerate(zip(state.positions, state.z, q))])
    run.save_figure(figures.ball_loads(state.z, q, f"{case.name}: {body.balls} balls, {fmt(load)} N"),
                    "ball_loads.png")
    curve = [(0.0, 0.0)] + [(f * load, nuts.distribution(body, f * load).shift) for f in LOAD_FACTORS[1:]]
    loads, shifts = np.array(curve).T
    stiffness = np.diff(loads) / np.diff(shifts)
    run.table("Axial stiffness curve of the nut: load against its shift at the loaded end",
              ("axial load [N]", "shift [um]", "secant stiffness [N/um]"),
              [(fmt(f), fmt(u * 1e6), fmt(k / 1e6) if i else "-")
               for i, (f, u, k) in enumerate(zip(loads, shifts, np.r_[0.0, stiffness]))])
    run.write_csv("stiffness.csv", [dict(axial_load_N=float(f), shift_m=float(u)) for f, u in zip(loads, shifts)])
    run.save_figure(figures.load_shift(loads, shifts, "single nut, preloaded by the ball oversize"), "stiffness.png")
    if fe:
        _fe_rung(run, body, load, nuts, figures)
    amplitude, cycles = case.nut_deviation
    steps = ROTATION_STEPS.get(run.fidelity, ROTATION_STEPS["default"])
    try:
        history, time_s = run.time(nuts.friction_over_rotation, body, load, steps=steps, amplitude=amplitude,
                                   cycles=cycles,
                                   progress=lambda it: run.progress(it, desc=f"{run.scene.name} rotation"))
    except (ConvergenceError, ValueError) as error:  # lin2019's four-point balls: no state past the preload loss
        run.note(f"{head}  No friction torque over rotation: lin2019's whole screw has no state at this load "
                 f"({error}); its balls past their preload loss run in two-point contact, whose friction the "
                 "module's stick/slip law gives (<stem>-balls, docs/b2b_rolling.md), not yet a whole nut's.")
        return
    run.check(model="lowmodel.screw.whole_screw", family="low-order numerical",
              quantity="power balance of every step of the rotation", unit="1",
              value=float(history.power_error.max()), reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE,
              time_s=time_s, source="|P_in - P_loss| / P_loss of each solve (lin2019 Sec 3.4)",
              why="the value is itself a relative power residual: zero judged on the scale 1")
    total = history.total_torque
    run.table(f"Friction torque over one nut revolution ({steps} steps, {time_s:.1f} s; deviation amplitude "
              f"{fmt(math.degrees(amplitude))} deg, {cycles} cycles over the turns)",
              ("", "mean [N m]", "min [N m]", "max [N m]", "ripple (peak to peak) [N m]"),
              [(name, fmt(float(np.mean(t))), fmt(float(np.min(t))), fmt(float(np.max(t))), fmt(float(np.ptp(t))))
               for name, t in (("total", total), ("ball-to-groove", history.groove_torque),
                               ("ball-to-ball", history.b2b_torque))])
    run.write_csv("torque.csv", [dict(nut_angle_rad=float(a), groove_torque_Nm=float(g), b2b_torque_Nm=float(b))
                                 for a, g, b in zip(history.nut_angle, history.groove_torque, history.b2b_torque)])
    run.save_figure(figures.torque_over_rotation(history.nut_angle, history.groove_torque, history.b2b_torque),
                    "torque.png")
    run.note(f"{head}  Friction torque {fmt(float(np.mean(total)))} N m on average, "
             f"{fmt(float(np.mean(history.b2b_torque) / np.mean(total) * 100))} % of it ball-to-ball.")


def _fe_rung(run, body, load, nuts, figures) -> None:
    """The elastic nut (fem.nut_fe) against the nut as a bar at the case's load: per ball the axial load both ways,
    the worst ball, the axial stiffness; two mesh levels, their difference the FE's own uncertainty."""
    from ballbench.fem import nut_fe  # scikit-fem and gmsh: only on the FE rung

    radius = nut_fe.default_patch_radius(body)
    shape = nut_fe.nut_shape(body)
    h_max = (shape.outer_radius - shape.inner_radius) / 2.0
    levels, results = FE_BORE_LEVELS.get(run.fidelity, FE_BORE_LEVELS["default"]), []
    for ratio in run.progress(levels, desc=f"{run.scene.name} FE levels"):
        results.append(run.time(nut_fe.compare, body, load, h_max=h_max, h_bore=radius / ratio))
    (coarse, _), (fine, time_s) = results
    bar, elastic = fine.bar.ball_loads, fine.elastic.ball_loads
    scale = float(elastic.max())
    level_change = float(np.max(np.abs(coarse.elastic.ball_loads - elastic))) / scale
    run.check(model="fem.nut_fe", family="FE", quantity="axial balance of the elastic nut's balls", unit="1",
              value=fine.elastic.balance, reference=0.0, scale=1.0, tolerance=nuts.BALANCE_TOLERANCE_SINGLE,
              time_s=time_s, source="the elastic nut's load distribution (nut.distribution with the FE compliance)",
              why="the value is itself a relative force residual: zero judged on the scale 1")
    k = fine.worst
    model = "lowmodel.screw.nut (nut as a bar)"
    run.check(model=model, family="low-order numerical", quantity="axial load of the worst ball against the elastic "
              "nut", unit="N", value=float(bar[k]), reference=float(elastic[k]), scale=scale,
              tolerance=FE_LOAD_TOLERANCE, time_s=time_s, finding=True,
              why="a ball's load is judged against the largest ball load of the nut",
              source=f"fem.nut_fe: the nut a tube, elastic (P2, {fine.compliance.dofs} DOFs), held at its flange at "
                     f"the {body.flange}; the balls their axial law, the screw a bar",
              note=f"ball {k + 1}; error over the largest ball load {fmt(scale)} N; the FE levels differ by "
                   f"{fmt(level_change * 100)} % of it")
    run.check(model=model, family="low-order numerical", quantity="axial stiffness against the elastic nut",
              unit="N/m", value=fine.stiffness_bar, reference=fine.stiffness_elastic, tolerance=FE_STIFFNESS_TOLERANCE,
              time_s=time_s, finding=True, source="fem.nut_fe (as above); load over the shift at the flange",
              note="the bar leaves out the shear lag of the nut's wall between the bore and the flange")
    rows = [(k + 1, fmt(float(z) * 1e3), fmt(float(b)), fmt(float(e)), fmt(float(x) * 100),
             fmt(float(c - e))) for k, (z, b, e, x, c) in enumerate(zip(fine.bar.z, bar, elastic, fine.error,
                                                                       coarse.elastic.ball_loads))]
    run.table(f"Nut as a bar against the elastic nut: each ball's axial load [N] (FE {fine.compliance.dofs} DOFs, "
              f"{time_s:.1f} s; the coarser level {coarse.compliance.dofs} DOFs)",
              ("ball", "z [mm]", "bar", "elastic", "error [% of the largest]", "FE levels differ [N]"), rows)
    run.table("Axial stiffness at the case's load, bar against elastic nut [N/um]",
              ("bar", "elastic", "bar over elastic - 1 [%]"),
              [(fmt(fine.stiffness_bar / 1e6), fmt(fine.stiffness_elastic / 1e6),
                fmt(fine.stiffness_change * 100))])
    run.write_csv("bar_elastic.csv", [dict(ball=k + 1, z_m=float(z), bar_N=float(b), elastic_N=float(e),
                                           elastic_coarse_N=float(c))
                                      for k, (z, b, e, c) in enumerate(zip(fine.bar.z, bar, elastic,
                                                                           coarse.elastic.ball_loads))])
    run.save_figure(figures.bar_elastic(fine.bar.z, bar, elastic, coarse.elastic.ball_loads), "bar_elastic.png")
    run.add_artifact(nut_fe.write_vtu(run.path("elastic_nut.vtu"), fine))
    run.note(f"FE rung (fem.nut_fe, docs/nut.md): the nut a tube, elastic, {fine.compliance.dofs} DOFs (patch "
             f"radius {fmt(radius * 1e3)} mm on the bore, Hertz's local part {fmt(fine.compliance.local * 1e9)} nm/N "
             f"removed), {time_s:.1f} s; its displacement field in elastic_nut.vtu (ParaView).  The bar nut is off by "
             f"{fmt(float(np.max(np.abs(fine.error))) * 100)} % of the largest ball load at ball {k + 1} and "
             f"overestimates the axial stiffness by {fmt(fine.stiffness_change * 100)} %; the two FE levels differ "
             f"by {fmt(level_change * 100)} % of the largest ball load.")


def _double(run, case, nuts, figures) -> None:
    body, load = case.nut, case.nut_load
    model = "lowmodel.screw.nut"
    hertz = nuts.ball_law(body.module, "hertz")
    lift_hertz, time_s = run.time(nuts.lift_off, body, hertz)
    run.check(model=model, family="low-order numerical", quantity="lift-off load of the double nut, Hertz's law",
              unit="N", value=lift_hertz, reference=2 ** 1.5 * body.preload, tolerance=1e-9, time_s=time_s,
              source="Hertz's law of two opposed preloaded sets: 2^(3/2) F_pr (docs/nut.md)")
    top = max(LOAD_FACTORS[-1] * load, 1.5 * 2 ** 1.5 * body.preload)
    law, time_s = run.time(nuts.ball_law, body.module, "exact", max_load=1.2 * top / body.balls)
    lift = nuts.lift_off(body, law)
    state = nuts.double_nut(body, load, law)
    run.check(model=model, family="low-order numerical", quantity="axial balance of the double nut's halves",
              unit="1", value=state.balance, reference=0.0, scale=1.0, tolerance=nuts.BALANCE_TOLERANCE,
              time_s=time_s, source="half A's load less half B's against the axial load (docs/nut.md)",
              why="the value is itself a relative force residual: zero judged on the scale 1")
    loads = np.linspace(0.0, top, 13)
    states = [nuts.double_nut(body, f, law) for f in loads]
    run.table(f"Double nut: two halves of {body.balls} balls in {body.turns} turns, preload {fmt(body.preload)} N "
              "(exact two-point balls)", ("axial load [N]", "half A [N]", "half B [N]", "shift [um]",
                                          "stiffness [N/um]", "B lifted off"),
              [(fmt(s.axial_load), fmt(float(s.half_loads[0])), fmt(float(s.half_loads[1])), fmt(s.shift * 1e6),
                fmt(s.stiffness / 1e6), "yes" if s.lifted else "no") for s in states])
    run.write_csv("halves.csv", [dict(axial_load_N=float(s.axial_load), half_a_N=float(s.half_loads[0]),
                                      half_b_N=float(s.half_loads[1]), shift_m=float(s.shift),
                                      stiffness_N_per_m=float(s.stiffness), lift_off_N=float(lift))
                                 for s in states])
    run.save_figure(figures.preload_diagram(loads, [s.half_loads for s in states], lift), "preload.png")
    run.note(f"Lift-off of half B at {fmt(lift)} N with the exact two-point balls, "
             f"{fmt((lift / (2 ** 1.5 * body.preload) - 1) * 100)} % from Hertz's 2^(3/2) F_pr = "
             f"{fmt(2 ** 1.5 * body.preload)} N (the contact lines turn under load).  At the case's {fmt(load)} N: "
             f"halves {fmt(float(state.half_loads[0]))} / {fmt(float(state.half_loads[1]))} N.  The friction of a "
             "double nut's two-point balls has no model yet (lin2019's is four-point; docs/nut.md).")
