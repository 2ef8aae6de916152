"""``<stem>-contact``: the most loaded contact of a case (or the case's own contact) up the ladder: exact Hertz,
the BEM on the exact gap on two or three grids, the FE on three or more meshes sized from its ellipse, the finest FE
level with its uncertainty by Eca and Hoekstra's least squares (references.uncertainty) as the reference, every
model's error against it and its run time; its fields (fields.vtu) and 3D screenshots.  A reference too uncertain
to judge at the run's fidelity ends the scene inconclusive (:func:`_inconclusive`); a rung outside its own validity
is no referee (:data:`HALF_SPACE_RATIO`).  A ball screw past its preload loss, where lin2019's model
has no state, runs on the loads of the frictionless two-point statics (lowmodel.screw.preload; :func:`_distinct`)."""
from __future__ import annotations

import math
import time
from pathlib import Path

from ballbench.lowmodel import bearing_results
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.validation.cases.case import BallScrewCase, ContactCase, LinearGuideCase
from ballbench.validation.ladder import rungs as ladder_rungs
from ballbench.validation.ladder.common import (FRICTIONLESS_WORDS, REFERENCE_UNCERTAINTY, fmt,
                                               past_preload_loss, settle_words)
from ballbench.validation.ladder.common import truncation_check
from ballbench.validation.references.richardson import extrapolate
from ballbench.validation.references.uncertainty import eca_hoekstra
from ballbench.validation.runner import GB

__all__ = ["contact_scene", "show_contact", "HALF_SPACE_RATIO"]

# The half-space rungs (Hertz, the BEM on the exact gap) model each body as an elastic half-space: the contact must be
# small against the radii of both surfaces (docs/hertz.md and docs/halfspace.md, "Validity").  The limit is Hertz's
# flag, a / R <= 0.3 (lowmodel.contact.hertz.VALIDITY_RATIO) with R the smallest principal radius of either surface
# (the ball's: a groove's radius f D is larger, so a / r_groove < a / R_B and one ratio bounds both).  A half-space
# rung beyond it is no referee of another model: there the FE study can put the BEM further from the FE than Hertz
# (docs/verification.md, "No reference at this level", the measured case).
HALF_SPACE_RATIO = hertz.VALIDITY_RATIO


def contact_scene(run, *, case, rungs, deadline) -> None:
    """The scene function of ``<stem>-contact``: every distinct contact geometry of ``case`` at its largest load
    (ladder.rungs.distinct_contacts: one for a guide or a contact, the screw and the nut side of a screw) up the
    ladder; ``rungs`` those to run, ``deadline`` a ``time.monotonic()`` value (``--budget``) past which no further FE
    level starts.  The fields and pictures are those of the most loaded contact.  Past a ball screw's preload loss,
    where lin2019's model has no state, the loads are those of the frictionless statics (:func:`_distinct`), and the
    scene says so."""
    start = time.perf_counter()
    distinct, reason, result = _distinct(case)
    time_s = time.perf_counter() - start  # lin2019's state (once: the contacts' loads come from it)
    if reason:
        _frictionless_table(run, case, reason)
    if result is not None:  # the ellipses of lin2019's state against the grooves' shoulders (docs/truncation.md)
        truncation_check(run, case, result, time_s=time_s)
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
    """(ladder.rungs.distinct_contacts of ``case``, the reason its loads are the frictionless statics' or "", the
    low-order state they come from or None): a ball screw where lin2019's model finds no state (past its preload
    loss, or below it where friction unloads a contact first; common.past_preload_loss) runs on the loads of the
    frictionless statics (lowmodel.screw.preload.frictionless_statics) instead of not applying: the contact rung
    needs a contact geometry and a load, not lin2019's friction.  Any other ConvergenceError stays as it is.  A
    guide's loads are lin2017 eq 36's (lowmodel.bearing_results.guide_contacts) under either contact law."""
    if isinstance(case, LinearGuideCase):  # eq 36's loads and ellipses, the same under either contact law
        loads = bearing_results.guide_contacts(case)
        return ladder_rungs.distinct_contacts(case, loads), "", loads
    try:  # lin2019's state where it has one (its loaded contact angles), without the stick/slip law's solves
        result = None
        if isinstance(case, BallScrewCase):
            free, touching = bearing_results.screw_states(case)
            result = bearing_results.screw_result(case, touching, free)
        return ladder_rungs.distinct_contacts(case, result), "", result
    except ConvergenceError as error:
        reason = past_preload_loss(case, error)
        if not reason:
            raise
    return ladder_rungs.distinct_contacts(case, frictionless=True), reason, None


def _frictionless_table(run, case, reason: str) -> None:
    """The notes and the per-ball, per-contact table of the frictionless statics a ball screw's scene runs on."""
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
    reference, source, uncertainty = _contact_reference(run, models, fe_rows, tag, radius)
    suffix = f" ({tag})" if tag else ""
    worst = max(uncertainty.values()) if uncertainty else None
    conclusive = reference is not None and (worst is None or worst <= REFERENCE_UNCERTAINTY)
    if reference is not None and not conclusive:
        _inconclusive(run, uncertainty, fe_rows, tag)
    if not conclusive:
        run.table("Contact by each rung, side by side (" + ("no conclusive reference at this fidelity"
                                                            if reference is not None else
                                                            "no reference at this level") + ": nothing judged)"
                  + suffix,
                  ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]", "one evaluation [s]"),
                  _model_rows(models))
        if fe_results:
            _fe_self_checks(run, contact, fe_rows, fe_results, fe_levels, models, uncertainty, tag, fields)
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
        _fe_self_checks(run, contact, fe_rows, fe_results, fe_levels, models, uncertainty, tag, fields)
    run.table("Contact by each rung" + suffix + " (reference: " + source + ")",
              ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]", "one evaluation [s]"),
              _model_rows(models) + [("reference", "finest FE level +- U" if uncertainty else "",
                                      fmt(reference["a"] * 1e3), fmt(reference["b"] * 1e3),
                                      fmt(reference["p0"] / 1e6), fmt(reference["delta"] * 1e6), "")])


def _fe_self_checks(run, contact, fe_rows, fe_results, fe_levels, models, uncertainty, tag: str,
                    fields: bool) -> None:
    """The FE study's own checks (load equilibrium of the finest level; the reference's uncertainty within its
    bound when it is conclusive), its levels.csv and the fields of the finest level."""
    finest = fe_results[-1]
    fe_models = [m for m in models if m[1] == "FE"]
    run.check(model="fem.contact", family="FE", level=_tagged(fe_models[-1][2], tag), quantity="force_sum",
              unit="N", value=finest.force_sum, reference=contact.force, tolerance=1e-9, time_s=fe_models[-1][4],
              source="load equilibrium (sum of contact forces)")
    if uncertainty is not None and max(uncertainty.values()) <= REFERENCE_UNCERTAINTY:
        run.check(model="uncertainty of the FE study", family="FE", level=_tagged("finest level", tag),
                  quantity="relative uncertainty of the reference, worst of a, b, p0, delta", unit="1",
                  value=max(uncertainty.values()), reference=REFERENCE_UNCERTAINTY, relation="le", tolerance=0.0,
                  time_s=sum(m[4] for m in fe_models), source=_UNCERTAINTY_SOURCE,
                  note="the reference must be known better than the tolerances it judges; above the bound the "
                       "scene is inconclusive")
    run.write_csv("levels.csv" if not tag else f"levels-{tag.replace(' ', '-')}.csv", fe_rows)
    if fields:
        _fields(run, contact, finest, fe_levels[-1])


_UNCERTAINTY_SOURCE = ("Eca & Hoekstra 2014, J. Comput. Phys. 262, 104, eqs 19-21 (references.uncertainty; two "
                       "levels: Richardson with F_s 3, references.richardson)")


def _inconclusive(run, uncertainty: dict, fe_rows, tag: str) -> None:
    """End the scene inconclusive: the FE reference's uncertainty above :data:`REFERENCE_UNCERTAINTY`, with the
    quantity, the levels and what settles it."""
    quantity, worst = max(uncertainty.items(), key=lambda item: item[1])
    levels = ", ".join(f"{r['n']:g}" for r in fe_rows)
    ratio = fe_rows[-1]["n"] / fe_rows[-2]["n"]
    finer = ", ".join(f"{fe_rows[-1]['n'] * ratio ** k:.3g}" for k in (1, 2))
    run.inconclusive(_head(tag) + f"no conclusive reference: the uncertainty of the FE reference is "
                     f"{100 * worst:.3g} % in {quantity} (worst of a, b, p0, delta; Eca-Hoekstra on {len(fe_rows)} "
                     f"levels n = b/h {levels}) against the {100 * REFERENCE_UNCERTAINTY:g} % it needs to judge the "
                     f"models, so Hertz, the BEM and the coarser FE levels are not judged here. "
                     + settle_words(run.fidelity, f"FE levels n = b/h {levels}, {finer} (the ratio {ratio:.3g} "
                                                  "continued)"))


def _fe_study(run, contact: ContactCase, b: float, deadline, tag: str, models: list):
    """The FE levels of ``contact`` (sizes ``h = b / n`` from its Hertz semi-axis ``b``), stopped where ``--budget``
    would be passed or where a level's predicted memory exceeds the memory available (:func:`_memory_guard`);
    appends each level to ``models``; returns (rows, results, levels)."""
    from ballbench.validation.studies import fe_contact

    fe_rows, fe_results, fe_levels = [], [], []
    room = fe_contact.block_room(contact)
    if room:  # an ellipse the FE pair cannot hold: said, and the rungs below shown (docs/truncation.md)
        run.note(_head(tag) + "FE study not run: " + room + ".")
        return fe_rows, fe_results, fe_levels
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


def _contact_reference(run, models, fe_rows, tag: str = "", radius: float = math.inf):
    """(reference values, source text, relative uncertainties or None): the finest FE level with its uncertainty by
    Eca and Hoekstra (>= 3 levels), the Richardson extrapolation of two levels (formal order 2, F_s 3), the one FE
    level, or the finest BEM grid where the BEM is inside its validity (a / R <= :data:`HALF_SPACE_RATIO`, ``radius``
    the contact's R); None when no rung above Hertz can judge."""
    fe = [m for m in models if m[1] == "FE"]
    if len(fe) >= 3:
        sizes = [r["h_contact"] for r in fe_rows]
        uncertainty, notes = {}, []
        for quantity, _ in ladder_rungs.QUANTITIES:
            u = eca_hoekstra(sizes, [r[quantity] for r in fe_rows])
            uncertainty[quantity] = u.relative_uncertainty
            notes.append(f"{quantity}: {u.note}, U = {100 * u.relative_uncertainty:.2g} % (phi_0 of the fit "
                         f"{100 * (u.extrapolated / u.value - 1.0):+.2g} % from the finest)")
        run.note(_head(tag) + "Reference: the finest FE level, its uncertainty by Eca and Hoekstra's least squares "
                 "over the levels (" + "; ".join(notes) + ").")
        return fe[-1][3], f"FE {fe[-1][2]} (finest of {len(fe)} levels, references.uncertainty)", uncertainty
    if len(fe) == 2:
        sizes = [r["h_contact"] for r in fe_rows]
        reference, uncertainty, notes = {}, {}, []
        for quantity, _ in ladder_rungs.QUANTITIES:
            e = extrapolate(sizes, [r[quantity] for r in fe_rows])
            reference[quantity] = e.value
            uncertainty[quantity] = e.relative_uncertainty
            notes.append(f"{quantity}: {e.note}, U = {100 * e.relative_uncertainty:.2g} %")
        run.note(_head(tag) + "Reference: Richardson extrapolation of the two FE levels (" + "; ".join(notes) + ").")
        return reference, "FE extrapolated to h -> 0 from 2 levels (references.richardson)", uncertainty
    if len(fe) == 1:
        run.note(_head(tag) + "Reference: the one FE level that ran (no extrapolation, its uncertainty unknown).")
        return fe[0][3], f"FE, {fe[0][2]} (one level)", None
    bem = [m for m in models if m[1] == "BEM"]
    if bem:
        ratio = bem[-1][3]["a"] / radius
        if ratio <= HALF_SPACE_RATIO:
            run.note(_head(tag) + f"Reference: the finest BEM grid (no FE rung in this run; a/R = {ratio:.3g} within "
                     f"the half-space rungs' validity {HALF_SPACE_RATIO:g}).")
            return bem[-1][3], f"BEM {bem[-1][2]} (finest grid)", None
        run.note(_head(tag) + f"No reference at this level: the BEM (the highest rung run) gives a/R = {ratio:.3g}, "
                 f"beyond the half-space rungs' validity a/R <= {HALF_SPACE_RATIO:g} (docs/hertz.md, docs/halfspace.md,"
                 " 'Validity'), so it judges no model here; the table shows the rungs side by side. The FE rung "
                 "(--levels FE or the default) is the referee of such a contact where its pair holds the ellipse.")
        return None, "", None
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
