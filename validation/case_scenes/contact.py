"""``<stem>-contact``: the most loaded contact of a case (or the case's own contact) up the ladder: exact Hertz,
the BEM on the exact gap on two or three grids, the FE on three or more meshes sized from its ellipse, the
Richardson extrapolation of the FE study with its uncertainty as the reference, every model's error against it and
its run time; its fields (fields.vtu) and 3D screenshots."""
from __future__ import annotations

import time
from pathlib import Path

from ballbench.validation.case_scenes.common import REFERENCE_UNCERTAINTY, fmt
from ballbench.validation.cases.case import ContactCase

__all__ = ["contact_scene", "show_contact"]


def _governing(case) -> ContactCase:
    from ballbench.validation.studies import ladder

    return ladder.contact_fe(ladder.governing_contact(case))


def contact_scene(run, *, case, rungs, deadline) -> None:
    """The scene function of ``<stem>-contact``: ``rungs`` those to run, ``deadline`` a ``time.monotonic()`` value
    (``--budget``) past which no further FE level starts."""
    from ballbench.lowmodel.contact import hertz
    from ballbench.validation.references.richardson import extrapolate
    from ballbench.validation.studies import fe_contact, ladder

    contact = _governing(case)
    run.note(f"Contact: {contact.name}; pair {contact.pair}, R_B {fmt(contact.ball_radius * 1e3)} mm"
             + (f", conformity {contact.conformity:g}" if contact.conformity else "") + f", F {fmt(contact.force)} N.")
    models = []  # (model, family, level, values, time)
    hertz_model = "lowmodel.contact.hertz"
    ref_hertz, time_h = run.time(ladder.hertz_values, contact)
    models.append((hertz_model, "analytical", "", ref_hertz, time_h))
    geometry = fe_contact.hertz_geometry(contact)
    radius = geometry.reference_radius
    run.check(model=hertz_model, family="analytical", quantity="a / R (Hertz's small-contact assumption)", unit="1",
              value=ref_hertz["a"] / radius, reference=hertz.VALIDITY_RATIO, relation="le", tolerance=0.0,
              time_s=time_h, source="lowmodel.contact.hertz.VALIDITY_RATIO (docs/hertz.md, validity)", finding=True)
    if "BEM" in rungs:
        for n in ladder.BEM_GRIDS[run.fidelity]:
            run.checkpoint()
            values, wall = ladder.timed(ladder.bem_values, contact, n)
            models.append(("lowmodel.contact.halfspace (exact gap)", "BEM", f"{n} x {n}", values, wall))
    fe_rows, fe_results, fe_levels = [], [], []
    if "FE" in rungs:
        pair = fe_contact.pair_model(contact)
        levels = contact.fe.levels[run.fidelity]
        sizes, times = [], []
        for level in run.progress(levels, desc=f"{run.scene.name} FE mesh levels"):
            size = ref_hertz["b"] / level.n
            if deadline is not None and times:
                predicted = ladder.predicted_time(times, sizes, size)
                if time.monotonic() + predicted > deadline:
                    run.note(f"--budget: FE levels from n = b/h {level.n:g} on not run (predicted {predicted:.0f} s "
                             "beyond the budget)")
                    break
            start = time.perf_counter()
            result, ref = fe_contact.solve_level(pair, level)
            wall = time.perf_counter() - start
            sizes.append(size)
            times.append(wall)
            values = {q: float(getattr(result, q)) for q, _ in ladder.QUANTITIES}
            words = f"n = b/h {level.n:g}, growth {level.growth:g}"
            models.append(("fem.contact", "FE", words, values, wall))
            fe_rows.append(dict(n=level.n, growth=level.growth, h_contact=result.h_contact, ndofs=result.ndofs,
                                iterations=result.iterations, residual=result.residual, wall_s=wall,
                                force_sum=result.force_sum, **{f"{q}": v for q, v in values.items()}))
            if fe_results and fe_results[-1].model.factor is not None:
                fe_results[-1].model.factor.free()  # only the finest level's factor is kept (for the fields)
            fe_results.append(result)
            fe_levels.append(level)
            if deadline is not None and time.monotonic() > deadline:
                run.note("--budget reached after this level")
                break
    reference, source, uncertainty = _contact_reference(run, models, fe_rows, extrapolate)
    if reference is None:
        run.table("Contact by each rung", ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]",
                                           "one evaluation [s]"), _model_rows(models))
        return
    for model, family, level, values, wall in models:
        if values is reference:
            continue  # the model that is the reference (one FE level, or the finest BEM grid): no check of itself
        tolerances = (ladder.FE_TOLERANCES[run.fidelity] if family == "FE" else
                      {q: ladder.BEM_TOLERANCE for q, _ in ladder.QUANTITIES} if family == "BEM"
                      else ladder.HERTZ_TOLERANCES)
        for quantity, unit in ladder.QUANTITIES:
            run.check(model=model, family=family, level=level, quantity=quantity, unit=unit, value=values[quantity],
                      reference=reference[quantity], source=source, tolerance=tolerances[quantity], time_s=wall,
                      note=_tolerance_note(family, run.fidelity), finding=True)
    if fe_results:
        finest = fe_results[-1]
        run.check(model="fem.contact", family="FE", level=models[-1][2], quantity="force_sum", unit="N",
                  value=finest.force_sum, reference=contact.force, tolerance=1e-9, time_s=models[-1][4],
                  source="load equilibrium (sum of contact forces)")
        if uncertainty is not None:
            worst = max(uncertainty.values())
            run.check(model="Richardson extrapolation of the FE study", family="FE", level="h -> 0",
                      quantity="relative uncertainty of the reference, worst of a, b, p0, delta", unit="1",
                      value=worst, reference=REFERENCE_UNCERTAINTY, relation="le", tolerance=0.0,
                      time_s=sum(m[4] for m in models if m[1] == "FE"),
                      source="grid convergence index (references.richardson; Roache 1994)",
                      note="the reference must be known better than the tolerances it judges; a larger value asks "
                           "for finer levels (--fine)")
        run.write_csv("levels.csv", fe_rows)
        _fields(run, contact, finest, fe_levels[-1])
    run.table("Contact by each rung (reference: " + source + ")",
              ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]", "one evaluation [s]"),
              _model_rows(models) + [("reference", "h -> 0" if uncertainty else "", fmt(reference["a"] * 1e3),
                                      fmt(reference["b"] * 1e3), fmt(reference["p0"] / 1e6),
                                      fmt(reference["delta"] * 1e6), "")])


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


def _contact_reference(run, models, fe_rows, extrapolate):
    """(reference values, source text, relative uncertainties or None): the extrapolated FE study (>= 2 levels),
    the one FE level, or the finest BEM grid; None when only Hertz ran."""
    from ballbench.validation.studies import ladder

    fe = [m for m in models if m[1] == "FE"]
    if len(fe) >= 2:
        sizes = [r["h_contact"] for r in fe_rows]
        reference, uncertainty, notes = {}, {}, []
        for quantity, _ in ladder.QUANTITIES:
            e = extrapolate(sizes, [r[quantity] for r in fe_rows])
            reference[quantity] = e.value
            uncertainty[quantity] = e.relative_uncertainty
            notes.append(f"{quantity}: {e.note}, U = {100 * e.relative_uncertainty:.2g} %")
        run.note("Reference: Richardson extrapolation of the FE levels (" + "; ".join(notes) + ").")
        return reference, f"FE extrapolated to h -> 0 from {len(fe)} levels (references.richardson)", uncertainty
    if len(fe) == 1:
        run.note("Reference: the one FE level that ran (no extrapolation, its uncertainty unknown).")
        return fe[0][3], f"FE, {fe[0][2]} (one level)", None
    bem = [m for m in models if m[1] == "BEM"]
    if bem:
        run.note("Reference: the finest BEM grid (no FE rung in this run).")
        return bem[-1][3], f"BEM {bem[-1][2]} (finest grid)", None
    run.note("Hertz only (--levels analytical): no reference to judge it against.")
    return None, "", None


def _fields(run, contact: ContactCase, result, level) -> None:
    """fields.vtu and fields.json of the finest FE level that ran (studies.fe_contact.write_fields) and their 3D
    screenshots (figures.render3d), as artifacts of the scene."""
    from ballbench.lowmodel.contact import hertz
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_contact

    ref = hertz.solve_load(fe_contact.hertz_geometry(contact), contact.force)
    for path in fe_contact.write_fields(result, ref, run.path(""), scene_name=run.scene.name, fidelity=run.fidelity,
                                        level=level, material=contact.material):
        run.add_artifact(path)
    for path in render3d.artifacts(run.path(""), run.note):
        run.add_artifact(path)


def show_contact(case, scene_dir, fidelity: str) -> list[Path]:
    """The ``show`` hook of ``<stem>-contact``: pictures of the saved fields (solved at ``fidelity`` if none)."""
    from ballbench.validation.studies import fe_contact

    return fe_contact.show_fields(_governing(case), scene_dir, fidelity, cost_s=60.0)
