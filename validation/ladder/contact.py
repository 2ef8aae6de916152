"""``<stem>-contact``: the most loaded contact of a case (or the case's own contact) up the ladder: exact Hertz,
the BEM on the exact gap on two or three grids, the FE on three or more meshes sized from its ellipse, the
Richardson extrapolation of the FE study with its uncertainty as the reference, every model's error against it and
its run time; its fields (fields.vtu) and 3D screenshots.  A ball screw past its preload loss, where lin2019's model
has no state, runs on the loads of the frictionless two-point statics (lowmodel.screw.preload; :func:`_distinct`)."""
from __future__ import annotations

import math
import time
from pathlib import Path

from ballbench.lowmodel import bearing_results
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.validation.cases.case import ContactCase
from ballbench.validation.ladder import rungs as ladder_rungs
from ballbench.validation.ladder.common import (FRICTIONLESS_WORDS, REFERENCE_UNCERTAINTY, fmt,
                                               past_preload_loss)
from ballbench.validation.references.richardson import extrapolate
from ballbench.validation.runner import GB

__all__ = ["contact_scene", "show_contact"]


def contact_scene(run, *, case, rungs, deadline) -> None:
    """The scene function of ``<stem>-contact``: every distinct contact geometry of ``case`` at its largest load
    (ladder.rungs.distinct_contacts: one for a guide or a contact, the screw and the nut side of a screw) up the
    ladder; ``rungs`` those to run, ``deadline`` a ``time.monotonic()`` value (``--budget``) past which no further FE
    level starts.  The fields and pictures are those of the most loaded contact.  Past a ball screw's preload loss,
    where lin2019's model has no state, the loads are those of the frictionless statics (:func:`_distinct`), and the
    scene says so."""
    distinct, reason = _distinct(case)
    if reason:
        _frictionless_table(run, case, reason)
    # the quick level keeps the cost of one FE study (docs/your_own_bearing.md, "Memory and time of the FE rung");
    # the default and fine levels run it on every contact
    fe_on = [index == 0 or run.fidelity != "quick" for index in range(len(distinct))]
    ran = [", ".join(r for r in rungs if r in ("analytical", "BEM", "FE") and (r != "FE" or on)) for on in fe_on]
    run.table("Contacts run (each distinct geometry at its largest load" + (", loads of the frictionless two-point "
              "statics, lowmodel.screw.preload" if reason else "") + ")",
              ("contact", "pair", "F [N]", "rungs", "stands for", "why"),
              [(d.label, d.contact.pair, fmt(d.contact.force), r, ", ".join(d.members), d.why)
               for d, r in zip(distinct, ran)])
    if not all(fe_on) and "FE" in rungs:
        run.note("--quick: the FE study runs on the most loaded contact only; the other contacts up to the BEM "
                 "(the default level runs the FE on every contact).")
    for index, d in enumerate(distinct):
        tag = d.label if len(distinct) > 1 else ""
        chosen = rungs if fe_on[index] else tuple(r for r in rungs if r != "FE")
        _one_contact(run, ladder_rungs.contact_fe(d.contact), chosen, deadline, tag, fields=index == 0)


def _distinct(case):
    """(ladder.rungs.distinct_contacts of ``case``, the reason its loads are the frictionless statics' or ""): a ball
    screw where lin2019's model finds no state (past its preload loss, or below it where friction unloads a contact
    first; common.past_preload_loss) runs on the loads of the frictionless statics
    (lowmodel.screw.preload.frictionless_statics) instead of not applying: the contact rung needs a contact geometry
    and a load, not lin2019's friction.  Any other ConvergenceError stays as it is."""
    try:
        return ladder_rungs.distinct_contacts(case), ""
    except ConvergenceError as error:
        reason = past_preload_loss(case, error)
        if not reason:
            raise
    return ladder_rungs.distinct_contacts(case, frictionless=True), reason


def _frictionless_table(run, case, reason: str) -> None:
    """The notes and the per-ball, per-contact table of the frictionless statics the scene runs on."""
    run.note("Loads: " + FRICTIONLESS_WORDS + ".")
    run.note("Why: " + reason)
    rows = bearing_results.screw_frictionless_contacts(case)
    kind = "two-point " if any(c.normal_force <= 0.0 for c in rows) else ""
    run.table(f"Per ball and contact (frictionless {kind}statics at {fmt(case.axial_load)} N, "
              "lowmodel.screw.preload; not lin2019's friction model)",
              ("ball", "contact", "F [N]", "angle [deg]", "approach [um]"),
              [(c.ball, c.contact, fmt(c.normal_force), fmt(math.degrees(c.contact_angle)), fmt(c.approach * 1e6))
               for c in rows])


def _head(tag: str) -> str:
    """The start of a note about one of several contacts."""
    return f"{tag}: " if tag else ""


def _tagged(level: str, tag: str) -> str:
    """The level of a check with the contact it belongs to when the scene runs more than one."""
    return ", ".join(x for x in (tag, level) if x)


def _one_contact(run, contact: ContactCase, rungs, deadline, tag: str, *, fields: bool) -> None:
    from ballbench.validation.studies import fe_contact

    run.note(_head(tag) + f"Contact: {contact.name}; pair {contact.pair}, R_B "
             f"{fmt(contact.ball_radius * 1e3)} mm" + (f", conformity {contact.conformity:g}" if contact.conformity
                                                       else "") + f", F {fmt(contact.force)} N.")
    models = []  # (model, family, level, values, time)
    hertz_model = "lowmodel.contact.hertz"
    ref_hertz, time_h = run.time(ladder_rungs.hertz_values, contact)
    models.append((hertz_model, "analytical", "", ref_hertz, time_h))
    geometry = fe_contact.hertz_geometry(contact)
    radius = geometry.reference_radius
    run.check(model=hertz_model, family="analytical", level=tag, quantity="a / R (Hertz's small-contact assumption)",
              unit="1", value=ref_hertz["a"] / radius, reference=hertz.VALIDITY_RATIO, relation="le", tolerance=0.0,
              time_s=time_h, source="lowmodel.contact.hertz.VALIDITY_RATIO (docs/hertz.md, validity)", finding=True)
    if "BEM" in rungs:
        for n in ladder_rungs.BEM_GRIDS[run.fidelity]:
            run.checkpoint()
            values, wall = ladder_rungs.timed(ladder_rungs.bem_values, contact, n)
            models.append(("lowmodel.contact.halfspace (exact gap)", "BEM", f"{n} x {n}", values, wall))
    fe_rows, fe_results, fe_levels = (_fe_study(run, contact, ref_hertz["b"], deadline, tag, models) if "FE" in rungs
                                      else ([], [], []))
    reference, source, uncertainty = _contact_reference(run, models, fe_rows, extrapolate, tag)
    suffix = f" ({tag})" if tag else ""
    if reference is None:
        run.table("Contact by each rung" + suffix, ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]",
                                                    "one evaluation [s]"), _model_rows(models))
        return
    for model, family, level, values, wall in models:
        if values is reference:
            continue  # the model that is the reference (one FE level, or the finest BEM grid): no check of itself
        tolerances = (ladder_rungs.FE_TOLERANCES[run.fidelity] if family == "FE" else
                      {q: ladder_rungs.BEM_TOLERANCE for q, _ in ladder_rungs.QUANTITIES} if family == "BEM"
                      else ladder_rungs.HERTZ_TOLERANCES)
        for quantity, unit in ladder_rungs.QUANTITIES:
            run.check(model=model, family=family, level=_tagged(level, tag), quantity=quantity, unit=unit,
                      value=values[quantity], reference=reference[quantity], source=source,
                      tolerance=tolerances[quantity], time_s=wall,
                      note=_tolerance_note(family, run.fidelity), finding=True)
    if fe_results:
        finest = fe_results[-1]
        run.check(model="fem.contact", family="FE", level=_tagged(models[-1][2], tag), quantity="force_sum",
                  unit="N", value=finest.force_sum, reference=contact.force, tolerance=1e-9, time_s=models[-1][4],
                  source="load equilibrium (sum of contact forces)")
        if uncertainty is not None:
            worst = max(uncertainty.values())
            run.check(model="Richardson extrapolation of the FE study", family="FE", level=_tagged("h -> 0", tag),
                      quantity="relative uncertainty of the reference, worst of a, b, p0, delta", unit="1",
                      value=worst, reference=REFERENCE_UNCERTAINTY, relation="le", tolerance=0.0,
                      time_s=sum(m[4] for m in models if m[1] == "FE"),
                      source="grid convergence index (references.richardson; Roache 1994)",
                      note="the reference must be known better than the tolerances it judges; a larger value asks "
                           "for finer levels (--fine)")
        run.write_csv("levels.csv" if not tag else f"levels-{tag.replace(' ', '-')}.csv", fe_rows)
        if fields:
            _fields(run, contact, finest, fe_levels[-1])
    run.table("Contact by each rung" + suffix + " (reference: " + source + ")",
              ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]", "one evaluation [s]"),
              _model_rows(models) + [("reference", "h -> 0" if uncertainty else "", fmt(reference["a"] * 1e3),
                                      fmt(reference["b"] * 1e3), fmt(reference["p0"] / 1e6),
                                      fmt(reference["delta"] * 1e6), "")])


def _fe_study(run, contact: ContactCase, b: float, deadline, tag: str, models: list):
    """The FE levels of ``contact`` (sizes ``h = b / n`` from its Hertz semi-axis ``b``), stopped where ``--budget``
    would be passed or where a level's predicted memory exceeds the memory available (:func:`_memory_guard`);
    appends each level to ``models``; returns (rows, results, levels)."""
    from ballbench.validation.studies import fe_contact

    fe_rows, fe_results, fe_levels = [], [], []
    pair = fe_contact.pair_model(contact)
    levels = contact.fe.levels[run.fidelity]
    sizes, times = [], []
    for level in run.progress(levels, desc=f"{run.scene.name} FE mesh levels" + (f" ({tag})" if tag else "")):
        size = b / level.n
        if deadline is not None and not times and time.monotonic() > deadline:
            run.note(_head(tag) + "--budget: passed before this contact's FE study; no FE level run")
            break
        if deadline is not None and times:
            predicted = ladder_rungs.predicted_time(times, sizes, size)
            if time.monotonic() + predicted > deadline:
                run.note(_head(tag) + f"--budget: FE levels from n = b/h {level.n:g} on not run (predicted "
                         f"{predicted:.0f} s beyond the budget)")
                break
        if fe_results and fe_results[-1].model.factor is not None:
            # only one level's factor alive at a time: the fields of the finest level refactorise if they need it
            fe_results[-1].model.factor.free()
        if not _memory_guard(run, pair, level, tag):
            break
        start = time.perf_counter()
        result, ref = fe_contact.solve_level(pair, level)
        wall = time.perf_counter() - start
        sizes.append(size)
        times.append(wall)
        values = {q: float(getattr(result, q)) for q, _ in ladder_rungs.QUANTITIES}
        words = f"n = b/h {level.n:g}, growth {level.growth:g}"
        models.append(("fem.contact", "FE", words, values, wall))
        fe_rows.append(dict(n=level.n, growth=level.growth, h_contact=result.h_contact, ndofs=result.ndofs,
                            iterations=result.iterations, residual=result.residual, wall_s=wall,
                            force_sum=result.force_sum, **{f"{q}": v for q, v in values.items()}))
        fe_results.append(result)
        fe_levels.append(level)
        if deadline is not None and time.monotonic() > deadline:
            run.note("--budget reached after this level")
            break
    return fe_rows, fe_results, fe_levels


def _memory_guard(run, pair, level, tag: str) -> bool:
    """Whether the FE level ``level`` of ``pair`` may run: its peak memory predicted from the P2 DOFs of its mesh
    (ladder.rungs.predicted_memory, the measured bytes per DOF of docs/your_own_bearing.md) within the memory the
    machine has available now (ladder.rungs.available_memory) and within the memory the scene declares
    (:meth:`Scene.memory_for`, what the distributed runner reserves for it).  When not, a note says so and the level
    and those above it do not run (the study keeps the levels that ran, as ``--budget`` does)."""
    from ballbench.validation.studies import fe_contact

    ndofs = fe_contact.level_dofs(pair, level)
    need = ladder_rungs.predicted_memory(ndofs)
    available, declared = ladder_rungs.available_memory(), run.scene.memory_for(run.fidelity) * GB
    if need <= min(available, declared):
        return True
    run.note(_head(tag) + f"memory: FE levels from n = b/h {level.n:g} on not run: {ndofs} P2 DOFs need about "
             f"{need / GB:.1f} GB ({ladder_rungs.BYTES_PER_DOF / 1e3:g} kB per DOF, docs/your_own_bearing.md), "
             f"{available / GB:.1f} GB available, {declared / GB:g} GB declared by the scene")
    return False


def _model_rows(models) -> list[tuple]:
    return [(m, level or "-", fmt(v["a"] * 1e3), fmt(v["b"] * 1e3), fmt(v["p0"] / 1e6), fmt(v["delta"] * 1e6),
             f"{t:.3g}") for m, _, level, v, t in models]


def _tolerance_note(family: str, fidelity: str) -> str:
    if family == "FE":
        return f"tolerance: the {fidelity} level's stated accuracy (docs/fem.md)"
    if family == "BEM":
        return "tolerance: the BEM's stated accuracy at its grids (docs/halfspace.md: 0.5 %)"
    return "tolerance: FE and Hertz agree within it for the papers' contacts (docs/fem.md); a miss flags a contact " \
           "outside Hertz's assumptions"


def _contact_reference(run, models, fe_rows, extrapolate, tag: str = ""):
    """(reference values, source text, relative uncertainties or None): the extrapolated FE study (>= 2 levels),
    the one FE level, or the finest BEM grid; None when only Hertz ran."""
    fe = [m for m in models if m[1] == "FE"]
    if len(fe) >= 2:
        sizes = [r["h_contact"] for r in fe_rows]
        reference, uncertainty, notes = {}, {}, []
        for quantity, _ in ladder_rungs.QUANTITIES:
            e = extrapolate(sizes, [r[quantity] for r in fe_rows])
            reference[quantity] = e.value
            uncertainty[quantity] = e.relative_uncertainty
            notes.append(f"{quantity}: {e.note}, U = {100 * e.relative_uncertainty:.2g} %")
        run.note(_head(tag) + "Reference: Richardson extrapolation of the FE levels (" + "; ".join(notes) + ").")
        return reference, f"FE extrapolated to h -> 0 from {len(fe)} levels (references.richardson)", uncertainty
    if len(fe) == 1:
        run.note(_head(tag) + "Reference: the one FE level that ran (no extrapolation, its uncertainty unknown).")
        return fe[0][3], f"FE, {fe[0][2]} (one level)", None
    bem = [m for m in models if m[1] == "BEM"]
    if bem:
        run.note(_head(tag) + "Reference: the finest BEM grid (no FE rung in this run).")
        return bem[-1][3], f"BEM {bem[-1][2]} (finest grid)", None
    run.note(_head(tag) + "Hertz only (--levels analytical): no reference to judge it against.")
    return None, "", None


def _fields(run, contact: ContactCase, result, level) -> None:
    """fields.vtu and fields.json of the finest FE level that ran (studies.fe_contact.write_fields) and their 3D
    screenshots (figures.render3d), as artifacts of the scene."""
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_contact

    ref = hertz.solve_load(fe_contact.hertz_geometry(contact), contact.force)
    for path in fe_contact.write_fields(result, ref, run.path(""), scene_name=run.scene.name, fidelity=run.fidelity,
                                        level=level, material=contact.material):
        run.add_artifact(path)
    for path in render3d.artifacts(run.path(""), run.note):
        run.add_artifact(path)


def show_contact(case, scene_dir, fidelity: str, solve: bool = False) -> list[Path]:
    """The ``show`` hook of ``<stem>-contact``: pictures of the saved fields of its most loaded contact (none saved:
    FileNotFoundError, or with ``solve`` solved at ``fidelity`` first)."""
    from ballbench.validation.studies import fe_contact

    governing = _distinct(case)[0][0].contact
    return fe_contact.show_fields(ladder_rungs.contact_fe(governing), scene_dir, fidelity, solve, cost_s=60.0)
