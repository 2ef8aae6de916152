"""``<stem>-b2b-fe`` of a linear guide or ball screw case (rung ``FE-informed``): the FE modules of the two balls on
meshes from their ellipses, the FE-informed B2B force per level and the uncertainty of its finest level by Eca and
Hoekstra's least squares (references.uncertainty), the reference of the analytical and low-order B2B forces; a
reference too uncertain to judge at the run's fidelity ends the scene inconclusive; the modules' fields and
screenshots."""
from __future__ import annotations

import functools
import math
import time
from pathlib import Path

import numpy as np

from ballbench.lowmodel.bearing_results import axial_shares
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.screw.contacts import CONTACT_NAMES
from ballbench.lowmodel.state import friction_increase
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.ladder import rungs as ladder_rungs
from ballbench.validation.ladder.common import (B2B_TOLERANCE, NEAR_ZERO_B2B, POWER_TOLERANCE, REFERENCE_UNCERTAINTY,
                                                fmt, oversize_for, preload_loss, preload_loss_words, settle_words,
                                                B2B_SETTLE_CAVEAT)
from ballbench.validation.ladder.common import not_truncated, touching_state, truncations
from ballbench.validation.scene import NotApplicable
from ballbench.validation.ladder.rungs import module_fe
from ballbench.validation.references.richardson import extrapolate
from ballbench.validation.references.uncertainty import eca_hoekstra
from ballbench.validation.runner import GB

__all__ = ["b2b_fe_scene", "show_module", "judge_b2b", "B2B_UNCERTAINTY"]


def b2b_fe_scene(run, *, case, deadline) -> None:
    """The scene function of ``<stem>-b2b-fe``: ``deadline`` as for the contact scene (``--budget``).  Does not
    apply where a contact ellipse reaches its groove's shoulder (common.not_truncated, docs/truncation.md)."""
    from ballbench.fem.fourpoint import ShoulderContact, ZoneEdgeContact

    result = touching_state(case)  # solved once: the truncation check and the module's sizes (None: no state)
    if result is not None:
        not_truncated(case, result)
    sized = module_fe(case, result)  # without a state it solves again and raises lin2019's limit (limited)
    try:
        if isinstance(case, LinearGuideCase):
            _guide_b2b_fe(run, sized, deadline)
        else:
            _screw_b2b_fe(run, sized, deadline)
    except ShoulderContact as error:  # the FE pressure reaches the flank's end where Hertz's ellipse stops short
        worst = min(truncations(case, result), key=lambda t: t.margin)
        raise NotApplicable(f"{error}, though the low-order ellipses stop short of it (closest: {worst.text()}, "
                            f"{math.degrees(worst.margin):.1f} deg short): the FE module's contact is an edge "
                            "contact its flank does not resolve") from error
    except ZoneEdgeContact as error:  # a heavy ellipse wider than the largest ball cap the module can mesh
        if case.fe is not None or sized.fe.min_cap_angle is None:
            raise
        radius = (case.guide if isinstance(case, LinearGuideCase) else case.screw).ball_radius
        a_max = max(t.a for t in truncations(case, result))
        asked, half = math.degrees(sized.fe.min_cap_angle), math.degrees(math.asin(min(1.0, a_max / radius)))
        raise NotApplicable(f"{error}: the FE contact fills the ball cap the module meshes for it (asked for "
                            f"{asked:.1f} deg, the ellipse to {ladder_rungs.CAP_MARGIN:g} a; "
                            f"a / R_B = {a_max / radius:.3f}, half-angle {half:.1f} deg; the caps may not pass 0.45 x "
                            "the angle between two contacts, meshes.parts.ball.cap_limit): a contact this wide is "
                            "outside what the module resolves (docs/truncation.md)") from error


def _levels(run, case, deadline, solve, dofs, bytes_per_dof: float = ladder_rungs.BYTES_PER_DOF):
    """Run ``solve(level) -> dict`` over the case's module levels, stopping where the budget would be passed or
    where a level's predicted memory exceeds the memory available (:func:`_memory_guard`, ``dofs(level)`` its P2
    DOFs, ``bytes_per_dof`` the study's measured peak memory per DOF); returns the rows.  A study whose first level
    does not fit raises MemoryError (nothing to judge)."""
    rows, sizes, times = [], [], []
    for level in run.progress(case.fe.levels[run.fidelity], desc=f"{run.scene.name} FE module levels"):
        if deadline is not None and times:
            predicted = ladder_rungs.predicted_time(times, sizes, level.h_contact)
            if time.monotonic() + predicted > deadline:
                run.note(f"--budget: module levels from h {level.h_contact * 1e6:.0f} um on not run (predicted "
                         f"{predicted:.0f} s beyond the budget)")
                break
        words = _memory_guard(run, level, dofs(level), bytes_per_dof)
        if words:
            if not rows:
                raise MemoryError(f"the FE module study: {words}")
            run.note(f"memory: module levels from h {level.h_contact * 1e6:.0f} um on not run: {words}")
            break
        start = time.perf_counter()
        row = solve(level)
        row["wall_s"] = time.perf_counter() - start
        rows.append(row)
        sizes.append(level.h_contact)
        times.append(row["wall_s"])
    return rows


def _memory_guard(run, level, ndofs: int, bytes_per_dof: float) -> str:
    """"" when the module level ``level`` of ``ndofs`` P2 DOFs may run, else why not: its peak memory predicted
    from its DOFs (ladder.rungs.predicted_memory, the measured bytes per DOF of docs/your_own_bearing.md) above
    the memory the machine has available now (ladder.rungs.available_memory) or above the memory the scene
    declares (:meth:`Scene.memory_for`), as the contact scene's guard decides."""
    need = ladder_rungs.predicted_memory(ndofs, bytes_per_dof)
    available, declared = ladder_rungs.available_memory(), run.scene.memory_for(run.fidelity) * GB
    if need <= min(available, declared):
        return ""
    return (f"{ndofs} P2 DOFs (h {level.h_contact * 1e6:.0f} um) need about {need / GB:.1f} GB "
            f"({bytes_per_dof / 1e3:g} kB per DOF, docs/your_own_bearing.md), {available / GB:.1f} GB "
            f"available, {declared / GB:g} GB declared by the scene")


B2B_UNCERTAINTY = REFERENCE_UNCERTAINTY * 5  # 5 % against the 7-10 % claims the FE-informed force judges


def judge_b2b(run, kind: str, rows, low, scale: float) -> float:
    """The FE-informed reference of the module study ``rows`` (per level, coarse to fine: ``h_contact_um``,
    ``F_B2B`` [N], ``wall_s``) and the B2B models ``low`` ((model, family, F_B2B [N], time [s]), ...) judged against
    it with ``kind``'s tolerance (:data:`B2B_TOLERANCE`), or the scene inconclusive when the reference's uncertainty
    exceeds :data:`B2B_UNCERTAINTY`; ``scale`` is mu times the ball load [N] (a force near zero is judged on
    :data:`NEAR_ZERO_B2B` of it).  Returns the reference [N]."""
    reference, source, extrapolation = _b2b_reference(run, rows)
    _b2b_checks(run, kind, reference, source, extrapolation, low, rows, scale)
    return reference


def _b2b_reference(run, rows, key: str = "F_B2B"):
    """(reference, source, its uncertainty or None): the finest FE-informed level with its uncertainty by Eca and
    Hoekstra (>= 3 levels), the Richardson extrapolation of two levels (formal order 2, F_s 3), or the one level."""
    if len(rows) >= 3:
        u = eca_hoekstra([r["h_contact_um"] for r in rows], [r[key] for r in rows])
        run.note(f"Reference F_B2B: the finest FE-informed level, its uncertainty by Eca and Hoekstra's least squares "
                 f"over the levels ({u.note}; U = {u.uncertainty:.3g} N; phi_0 of the fit {u.extrapolated:.4g} N).")
        return u.value, f"FE-informed, finest of {len(rows)} levels (h {rows[-1]['h_contact_um']:.0f} um)", u
    if len(rows) == 2:
        e = extrapolate([r["h_contact_um"] for r in rows], [r[key] for r in rows])
        run.note(f"Reference F_B2B: Richardson extrapolation of the two FE-informed levels ({e.note}, U = "
                 f"{e.uncertainty:.3g} N).")
        return e.value, "FE-informed extrapolated to h -> 0 from 2 levels", e
    run.note("Reference F_B2B: the one FE-informed level that ran (no extrapolation).")
    return rows[-1][key], "FE-informed, one level", None


def _b2b_checks(run, kind, reference, source, extrapolation, low, rows, scale) -> None:
    tolerance = B2B_TOLERANCE[kind]
    claim = "lin2019's own claim: within 7 % (docs/fe_b2b.md)" if kind == "linear-guide" else \
        "within 10 % (docs/fe_b2b.md)"
    scale = NEAR_ZERO_B2B * scale
    why = "" if abs(reference) >= scale else "a B2B force near zero judged against 5 % of mu times the ball load"
    use_scale = scale if abs(reference) < scale else 0.0
    relative = extrapolation.uncertainty / max(abs(extrapolation.value), scale) if extrapolation is not None else None
    if relative is not None and relative > B2B_UNCERTAINTY:
        _inconclusive(run, relative, rows, low, reference)
        return
    for model, family, value, time_s in low:
        run.check(model=model, family=family, quantity="F_B2B", unit="N", value=value, reference=reference,
                  scale=use_scale, source=source, tolerance=tolerance, time_s=time_s, note=claim, why=why,
                  finding=True)
    # with two levels the finest is judged against their extrapolation; with three or more it is the reference; the
    # coarser ones are the convergence study, summarised by the uncertainty below and listed with their errors in the
    # levels table (_module_table)
    for r in rows[-1:] if extrapolation is not None and len(rows) == 2 else ():
        words = f"h {r['h_contact_um']:.0f} um"
        run.check(model=f"FE-informed B2B ({words})", family="FE-informed", level=words, quantity="F_B2B", unit="N",
                  value=r["F_B2B"], reference=reference, scale=use_scale, source=source, tolerance=tolerance,
                  time_s=r["wall_s"], note=claim, why=why, finding=True)
    if extrapolation is not None:
        run.check(model="uncertainty of the FE-informed levels", family="FE-informed",
                  level="finest level" if len(rows) >= 3 else "h -> 0",
                  quantity="relative uncertainty of the F_B2B reference", unit="1", value=relative,
                  reference=B2B_UNCERTAINTY, relation="le", tolerance=0.0, time_s=sum(r["wall_s"] for r in rows),
                  source="Eca & Hoekstra 2014, J. Comput. Phys. 262, 104, eqs 19-21 (references.uncertainty; two "
                         "levels: Richardson with F_s 3); 5 % against the 7-10 % claims",
                  note="above the bound the scene is inconclusive")


def _inconclusive(run, relative: float, rows, low, reference: float) -> None:
    """End the scene inconclusive: the FE-informed reference's uncertainty above :data:`B2B_UNCERTAINTY`; the models
    it would judge side by side with it, unjudged, and what settles it."""
    sizes = [r["h_contact_um"] for r in rows]
    ratio = sizes[-2] / sizes[-1]
    levels = ", ".join(f"{h:.0f}" for h in sizes)
    finer = ", ".join(f"{sizes[-1] / ratio ** k:.0f}" for k in (1, 2))
    run.inconclusive(f"no conclusive reference: the uncertainty of the FE-informed F_B2B is {100 * relative:.3g} % "
                     f"(Eca-Hoekstra on {len(rows)} module levels h_contact = {levels} um) against the "
                     f"{100 * B2B_UNCERTAINTY:g} % it needs to judge the B2B models, so they are not judged here. "
                     + settle_words(run.fidelity, f"[fe] module levels h_contact = {levels}, {finer} um (the ratio "
                                                  f"{ratio:.3g} continued)", B2B_SETTLE_CAVEAT))
    run.table("B2B force by model, side by side (no conclusive reference: nothing judged)",
              ("model", "family", "F_B2B [N]"),
              [(model, family, fmt(value)) for model, family, value, _ in low]
              + [(f"FE-informed, h {r['h_contact_um']:.0f} um", "FE-informed", fmt(r["F_B2B"])) for r in rows]
              + [("finest FE-informed level (the would-be reference)", "FE-informed", fmt(reference))])


def _guide_b2b_fe(run, case: LinearGuideCase, deadline) -> None:
    from ballbench.lowmodel.linear_bearing import b2b_analytical
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_linear

    guide = case.guide
    contacts = fe_b2b_linear.low_order_contacts(case)
    b2b.solve(contacts, [0.0])  # loads the friction map outside the timed call
    low_state, time_low = run.time(b2b.solve, contacts, [0.0])
    low = [("lowmodel.linear_bearing.b2b", "low-order numerical", float(low_state.b2b_force[0]), time_low)]
    analytical, time_a = run.time(b2b_analytical.from_case, case)
    low.append(("lowmodel.linear_bearing.b2b_analytical", "analytical", float(analytical.b2b_force), time_a))
    kept = {}

    def solve(level):
        kept.clear()  # the previous level's module goes before the next level's is built
        model, results, timings = fe_b2b_linear.solve_fe_level(case, level)
        state = fe_b2b_linear.fe_informed(case, model, results)
        free = fe_b2b_linear.fe_informed(case, model, results, gaps=[1e-3])
        kept.update(model=model, results=results, level=level, state=state)
        v = abs(guide.groove_velocity)
        return dict(h_contact_um=level.h_contact * 1e6, growth=level.growth, ndofs=model.ndofs,
                    F_B2B=float(state.b2b_force[0]), friction_force_N=state.input_power / v,
                    friction_force_free_N=free.input_power / v,
                    friction_increase=friction_increase(state, free),
                    power_balance=float(state.power_balance), **{k: float(x) for k, x in timings.items()})

    rows = _levels(run, case, deadline, solve, functools.partial(fe_b2b_linear.level_dofs, case))
    reference = judge_b2b(run, "linear-guide", rows, low, guide.friction_coefficient * case.vertical_force)
    _informed_power_check(run, rows[-1], "energy conservation incl. B2B loss (lin2019 eq 7; docs/fe_b2b.md: 1e-6)")
    _module_table(run, rows, "friction_force_N", "friction force [N]", low_state, guide.groove_velocity, reference)
    run.write_csv("levels.csv", rows)
    render3d.module_artifacts(run, kept["model"], kept["results"], materials=guide.material.pair,
                              case=case.name, level={"h_contact_m": kept["level"].h_contact,
                                                     "growth": kept["level"].growth})


def _module_table(run, rows, key, label, low_state, speed, reference) -> None:
    def error(value):
        return fmt(100 * (value / reference - 1.0), 3) + " %" if reference else "-"

    low = float(low_state.b2b_force[0])
    table = [("low-order numerical", "-", "-", fmt(low), error(low), fmt(low_state.input_power / abs(speed)), "-")]
    table += [(f"FE-informed, h {r['h_contact_um']:.0f} um", str(r["ndofs"]), f"{r['wall_s']:.0f}", fmt(r["F_B2B"]),
               error(r["F_B2B"]), fmt(r[key]), fmt(100 * r["friction_increase"]) + " %") for r in rows]
    table.append(("reference (" + ("h -> 0" if len(rows) == 2 else "finest level") + ")", "", "", fmt(reference), "",
                  "", ""))
    run.table("B2B force and friction by model and mesh level", ("model", "DOFs", "wall [s]", "F_B2B [N]",
                                                                 "F_B2B error", label, "friction increase"), table)


def _informed_power_check(run, finest: dict, source: str) -> None:
    """The relative power balance of the FE-informed B2B state on the finest module level (row of the study)."""
    words = f"h {finest['h_contact_um']:.0f} um"
    run.check(model=f"FE-informed B2B ({words})", family="FE-informed", level=words,
              quantity="power balance (input - losses)/input", unit="1", value=finest["power_balance"],
              reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=finest["wall_s"], source=source,
              why="the value is itself a relative power error: zero judged on the scale 1")


def _screw_b2b_fe(run, case: BallScrewCase, deadline) -> None:
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_screw

    (contacts, free, state), time_low = run.time(fe_b2b_screw.low_order, case)
    lost = _unloaded(state)
    if lost:
        raise NotApplicable(_unloaded_reason(case, lost))
    low = [("lowmodel.screw.b2b", "low-order numerical", float(state.b2b_force[0]), time_low)]
    shares = axial_shares(contacts, state)
    kept = {}
    speed = abs(case.screw.nut_speed)

    def solve(level):
        kept.clear()  # the previous level's modules go before the next level's are built
        models, results, timings = fe_b2b_screw.solve_fe_level(case, level, shares)
        informed = fe_b2b_screw.fe_informed(case, models, results)
        kept.update(models=models, results=results, level=level)
        return dict(h_contact_um=level.h_contact * 1e6, growth=level.growth, ndofs=sum(m.ndofs for m in models),
                    F_B2B=float(informed.b2b_force[0]), friction_torque_Nm=informed.touching.input_power / speed,
                    friction_increase=float(informed.friction_increase) / 100.0,
                    power_balance=float(informed.power_balance), **{k: float(x) for k, x in timings.items()})

    rows = _levels(run, case, deadline, solve, functools.partial(fe_b2b_screw.level_dofs, case),
                   ladder_rungs.SCREW_MODULE_BYTES_PER_DOF)
    reference = judge_b2b(run, "ball-screw", rows, low, case.screw.friction_coefficient * max(case.axial_load, 1.0))
    _informed_power_check(run, rows[-1], "energy conservation incl. B2B loss (docs/fe_b2b.md: 1e-6)")
    _module_table(run, rows, "friction_torque_Nm", "friction torque [N m]", state, speed, reference)
    run.write_csv("levels.csv", rows)
    render3d.module_artifacts(run, kept["models"], kept["results"], materials=case.screw.material.pair,
                              case=case.name, level={"h_contact_m": kept["level"].h_contact,
                                                     "growth": kept["level"].growth,
                                                     "per_contact": case.fe.per_contact})


def _unloaded_reason(case: BallScrewCase, lost: list[str]) -> str:
    """Why the FE screw module does not apply: the contacts lin2019's state leaves unloaded, with the preload loss."""
    loss = preload_loss(case)
    past = (f"past the preload loss at {loss.axial_load:.4g} N" if case.axial_load > loss.axial_load else
            f"below the frictionless preload loss at {loss.axial_load:.4g} N (friction unloads it first)")
    return (f"{', '.join(lost)} carry no load in lin2019's state at the axial load {case.axial_load:.4g} N and "
            f"oversize {case.screw.oversize * 1e6:.3g} um, {past} {preload_loss_words(case)}: the FE screw module "
            f"(fem.screw_module, lin2017 eq 37) needs all four contacts of each ball loaded. Raise the oversize "
            f"(preload) until lin2019's state loads all four: the frictionless preload loss reaches this load at about "
            f"{oversize_for(case, case.axial_load) * 1e6:.2g} um, friction unloads a contact earlier; or run "
            "--levels FE.")


def _unloaded(state) -> list[str]:
    """The contacts ("ball 1 SR", ...) that lin2019's ball-screw ``state`` leaves without load."""
    return [f"ball {j + 1} {name}" for j, row in enumerate(np.asarray(state.normal_force))
            for name, force in zip(CONTACT_NAMES, row) if not force > 0]


def _screw_unloaded(case: BallScrewCase) -> None:
    """NotApplicable when lin2019's state of ``case`` leaves a contact unloaded (the show hook's check)."""
    from ballbench.validation.studies import fe_b2b_screw

    lost = _unloaded(fe_b2b_screw.low_order(case)[2])
    if lost:
        raise NotApplicable(_unloaded_reason(case, lost))


def show_module(case, scene_dir, fidelity: str, solve: bool = False) -> list[Path]:
    """The ``show`` hook of ``<stem>-b2b-fe``: pictures of the saved module fields (none saved: NotApplicable where
    the module cannot be built, else FileNotFoundError, or with ``solve`` the module solved first)."""
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_linear, fe_b2b_screw
    if render3d.has_fields(scene_dir):
        return render3d.render(scene_dir)
    not_truncated(case)
    if isinstance(case, BallScrewCase):
        _screw_unloaded(case)
    if not solve:
        raise FileNotFoundError(f"no saved module fields in {scene_dir} (fields.json)")
    show = fe_b2b_linear.show_module if isinstance(case, LinearGuideCase) else fe_b2b_screw.show_module
    return show(module_fe(case), scene_dir, "quick" if fidelity == "quick" else "default", solve)
