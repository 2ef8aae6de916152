"""What the report says, decided once: the :class:`~.document.Document` of a run.

The opening banner (counts under the run's options), unexpected passes, findings (models outside their declared
accuracy on a case's own geometry), the summary (one row per scene with its model families), known gaps, budgets,
"which model for an error budget" (per declared model family), then one
section per scene with a table per model run (its family, level and run time).
"""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

from ballbench.validation.report.document import (Block, Bullets, Document, Files, Image, Paragraph, Quote, Section,
                                                  Span, Table, Text, Verdict)
from ballbench.validation.report.points import family_order
from ballbench.validation.report.records import Tally
from ballbench.validation.report.rows import (FINDINGS_MEANING, INCONCLUSIVE_MEANING, NOT_APPLICABLE_MEANING,
                                              check_line, count,
                                              failure_lines, family_of, fmt_time, ratio_text, row, scene_budget_text,
                                              status_word, worst_ratio_text)
from ballbench.validation.scene import Output, SceneResult


def _status(status: str) -> Span:
    return Span(status, status=status)


def model_runs(result: SceneResult) -> list[tuple[str, str, str, float, list[Output]]]:
    """The scene's accuracy outputs grouped by model run: (model, family, level, time of one evaluation [s],
    outputs), in the order the scene checked them."""
    groups: dict[tuple[str, str, str, float], list[Output]] = {}
    for o in result.outputs:
        if o.kind == "accuracy":
            groups.setdefault((o.model, family_of(o), o.level, o.time_s), []).append(o)
    return [(*key, outputs) for key, outputs in groups.items()]


def known_gap_rows(gaps: Sequence[tuple[SceneResult, Output]]) -> list[tuple[str, ...]]:
    """Rows of the known-gaps table: (scene, check, value, published, status, reason, evidence); a check of the
    same scene declared with the same reason and evidence as the row above says "as above" instead of repeating
    a paragraph (a scene may declare several checks with one reason)."""
    rows, previous = [], None
    for r, o in gaps:
        key = (r.name, o.known_gap.reason, o.known_gap.evidence)
        reason, evidence = (SAME_AS_ABOVE, SAME_AS_ABOVE) if key == previous else key[1:]
        rows.append((r.name, o.quantity, row(o).value_with_unit, row(o).reference_with_unit, _status(o.status),
                     reason, evidence))
        previous = key
    return rows


SAME_AS_ABOVE = "as above"
NO_BUDGET_ROWS = "None in this run: no model budget recorded and no scene over its wall-time budget."
ERROR_NOTE = ("Errors are relative: |value - reference| / max(|reference|, scale) (for a bound only the violating "
              "side counts); ", Span("error / tol", "em"), " is that error as a multiple of the check's tolerance "
              "(1 = at tolerance). Values are shown in engineering units; results.json and results.csv stay SI.")


def family_table(points: Sequence[dict]) -> list[tuple]:
    """Per model family: points, time range of one evaluation, median and worst error / tolerance, models."""
    rows = []
    for family in family_order(p["family"] for p in points):
        members = [p for p in points if p["family"] == family]
        times = sorted(p["time_s"] for p in members)
        errors = sorted(p["error"] for p in members)
        levels: dict[str, list[str]] = {}  # model -> its levels, fastest first
        for p in sorted(members, key=lambda p: p["time_s"]):
            known = levels.setdefault(p["model"].removeprefix("lowmodel."), [])
            if p["level"] and p["level"] not in known and not p["model"].endswith(f"({p['level']})"):
                known.append(p["level"])
        models = [m + (f" ({', '.join(levels[m])})" if levels[m] else "") for m in sorted(levels)]
        rows.append((family, str(len(members)), f"{fmt_time(times[0])} - {fmt_time(times[-1])}",
                     ratio_text(errors[len(errors) // 2]), ratio_text(errors[-1]), ", ".join(models)))
    return rows


def same_scene_comparisons(points: Sequence[dict]) -> list[tuple]:
    """Scenes where models of different families answer the same question: (scene, family, model, level, time,
    error / tolerance), fastest first."""
    rows = []
    for scene_name in sorted({p["scene"] for p in points}):
        members = [p for p in points if p["scene"] == scene_name]
        if len({p["family"] for p in members}) < 2:
            continue
        for p in sorted(members, key=lambda p: p["time_s"]):
            rows.append((scene_name, p["family"], p["model"], p["level"] or "-", fmt_time(p["time_s"]),
                         ratio_text(p["error"])))
    return rows


def _verdict(r: SceneResult, status: str, counted: Tally) -> Verdict:
    options = dict(strict=counted.strict, strict_time=counted.strict_time)
    return Verdict(r.name, r.kind, status, r.wall_time_s, scene_budget_text(r), r.error,
                   tuple(failure_lines(r, limit=50, **options)),
                   tuple(f"{o.quantity}: {o.known_gap.reason}" for o in r.outputs_with("known gap")),
                   tuple(f"{check_line(o)}: {o.status}" for o in r.outputs), r.not_applicable, r.inconclusive)


def _head(results, fidelity, counted: Tally) -> list[Block]:
    c = counted.counts
    mode = ", ".join(m for m, on in (("--strict", counted.strict), ("--strict-time", counted.strict_time)) if on)
    ok = c["fail"] == 0 and c["error"] == 0 and not counted.not_run
    findings = f"{c['findings']} passed with findings, " if c["findings"] else ""
    unfit = f"{c['not applicable']} do not apply to this case, " if c["not applicable"] else ""
    unsure = f"{c['inconclusive']} inconclusive (no conclusive reference at this fidelity), " if c["inconclusive"] \
        else ""
    blocks = [Paragraph(("Fidelity ", Span(fidelity, "code"), f", mode {mode or 'default'}. "
                         f"{count(len(results), 'scene')}: {c['pass']} passed, {c['known gap']} passed with known "
                         f"gaps, {findings}{unfit}{unsure}{c['fail']} failed, {c['error']} raised."),
                        tone=("warn" if c["findings"] or c["not applicable"] or c["inconclusive"] else "ok")
                        if ok else "bad")]
    if counted.not_run:
        blocks.append(Paragraph((Span(f"Partial report: the run was interrupted; "
                                      f"{count(len(counted.not_run), 'scene')} did not run:", "strong"),
                                 " " + ", ".join(counted.not_run)), tone="warn"))
    return blocks


def _unexpected(results) -> list[Section]:
    unexpected = [(r, o) for r in results for o in r.outputs if o.status == "unexpected pass"]
    if not unexpected:
        return []
    return [Section("Unexpected passes: declared known gaps that now pass", "unexpected", (
        Paragraph(("Remove the ", Span("known_gap=", "code"), " declaration of each; the run fails until then.")),
        Table(("scene", "check", "value", "reference"),
              tuple((r.name, o.quantity, row(o).value, row(o).reference) for r, o in unexpected))), loud=True)]


def _findings(results, counted: Tally) -> list[Section]:
    """Models outside their declared accuracy on a case's own geometry: what each missed and what to conclude."""
    found = [(r, o) for r in results for o in r.outputs_with("outside accuracy")]
    if not found:
        return []
    consequence = ("; this ", Span("--strict", "code"), " run counts them as failures.") if counted.strict else (
        "; they do not fail the run (", Span("--strict", "code"), " makes them fail).")
    rows = []
    for r, o in found:
        shown = row(o)
        rows.append((r.name, o.model + (f" ({o.level})" if o.level else ""), o.quantity, shown.value_with_unit,
                     shown.reference_with_unit, shown.error, shown.tolerance, Span(o.status, status=o.status),
                     o.source))
    return [Section("Findings: models outside their accuracy on this geometry", "findings", (
        Paragraph(("Each row is ", FINDINGS_MEANING, consequence, " A model of a lower rung that misses its "
                   "declared accuracy against a higher one here is not to be trusted to that accuracy on this "
                   "bearing (docs/your_own_bearing.md, 'Reading the verdict').")),
        Table(("scene", "model", "quantity", "value", "reference", "error", "tolerance", "status", "reference from"),
              tuple(rows), numeric=(3, 4, 5, 6))))]


def _not_applicable(results, counted: Tally) -> list[Section]:
    """The scenes whose model has no state on the case, each with its reason: what the reader cannot learn here."""
    unfit = [r for r in results if r.not_applicable and not r.error]
    if not unfit:
        return []
    consequence = ("; this ", Span("--strict", "code"), " run counts them as failures.") if counted.strict else (
        "; they do not fail the run (", Span("--strict", "code"), " makes them fail).")
    return [Section("Rungs that do not apply to this case", "not-applicable", (
        Paragraph(("Each scene below ended with ", Span("does not apply", status="not applicable"), ": ",
                   NOT_APPLICABLE_MEANING, consequence, " The reason names the limit and the number "
                   "(docs/your_own_bearing.md, 'Reading the verdict').")),
        Table(("scene", "status", "reason"),
              tuple((Span(r.name, link=f"#{r.name}"), Span(status_word(s), status=s), r.not_applicable)
                    for r, s in zip(results, counted.statuses) if r in unfit))))]


def _inconclusive(results, counted: Tally) -> list[Section]:
    """The scenes without a conclusive reference at this fidelity, each with its reason and what settles it."""
    unsure = [r for r in results if r.inconclusive and not r.error and not r.not_applicable]
    if not unsure:
        return []
    consequence = ("; this ", Span("--strict", "code"), " run counts them as failures") if counted.strict else (
        "; they do not fail the run (", Span("--strict", "code"), " makes them fail)")
    return [Section("Scenes without a conclusive reference at this fidelity", "inconclusive", (
        Paragraph(("Each scene below ended ", Span("inconclusive", status="inconclusive"), ": ", INCONCLUSIVE_MEANING,
                   consequence, " (docs/verification.md, 'Bounds and INCONCLUSIVE').")),
        Table(("scene", "status", "reason and what settles it"),
              tuple((Span(r.name, link=f"#{r.name}"), Span(status_word(s), status=s), r.inconclusive)
                    for r, s in zip(results, counted.statuses) if r in unsure))))]


def _summary(results, counted: Tally) -> Section:
    rows = []
    for r, s in zip(results, counted.statuses):
        families = family_order(family_of(o) for o in r.outputs if o.kind == "accuracy")
        rows.append((Span(r.name, link=f"#{r.name}"), r.kind, ", ".join(families) or "-",
                     Span(status_word(s) + (" (interrupted)" if r.interrupted else ""), status=s),
                     str(len([o for o in r.outputs if o.kind == "accuracy"])), worst_ratio_text(r.outputs),
                     fmt_time(r.wall_time_s), scene_budget_text(r), scene_memory_text(r)))
    return Section("Summary", "summary", (
        Paragraph(ERROR_NOTE, small=True),
        Table(("scene", "kind", "model families", "status", "checks", "worst error / tol", "wall time", "budget",
               "scene peak memory / declared"),
              tuple(rows), numeric=(4, 5, 6, 8))))


def scene_memory_text(r) -> str:
    """The summary's memory cell: the scene's own peak over the memory it declares, the process's peak beside them
    (docs/validation.md, "Memory"); "-" where not measured."""
    if r.scene_peak_memory_gb <= 0 and r.peak_memory_gb <= 0:
        return "-"
    declared = f" / {r.declared_memory_gb:.1f}" if r.declared_memory_gb > 0 else ""
    process = f" (process {r.peak_memory_gb:.1f})" if r.peak_memory_gb > 0 else ""
    return f"{r.scene_peak_memory_gb:.2f}{declared} GB{process}" + (" over" if r.over_memory else "")


def _known_gaps(results, counted: Tally) -> Section:
    gaps = [(r, o) for r in results for o in r.outputs if o.known_gap is not None]
    if not gaps:
        return Section("Known gaps", "known-gaps", (Paragraph("None in this run."),))
    consequence = ("; this ", Span("--strict", "code"), " run counts them as failures.") if counted.strict else (
        " but do not fail the run (", Span("--strict", "code"), " makes them fail).")
    return Section("Known gaps", "known-gaps", (
        Paragraph(("Published numbers this project does not reproduce, declared with their reason and evidence. "
                   "They are checked and reported like any other check", *consequence)),
        Table(("scene", "check", "value", "published", "status", "reason", "evidence"),
              tuple(known_gap_rows(gaps)))))


def _budgets(results) -> Section:
    rows = [(r.name, "scene wall time", fmt_time(r.wall_time_s), fmt_time(r.budget_s), _status("over budget"))
            for r in results if r.wall_time_s > r.budget_s]
    rows += [(r.name, "scene peak memory", f"{r.scene_peak_memory_gb:.2f} GB", f"{r.declared_memory_gb:.1f} GB",
              _status("over budget")) for r in results if r.over_memory]
    for r in results:
        for o in r.outputs_with("within budget") + r.outputs_with("over budget"):
            shown = row(o)
            rows.append((r.name, o.quantity, shown.value_with_unit, shown.reference_with_unit, _status(o.status)))
    intro = Paragraph(("Reported; they decide pass/fail only with ", Span("--strict-time", "code"), ". Every "
                       "scene's wall time and budget, and its own peak memory and the memory it declares, stand in "
                       "the summary; here the model budgets and the scenes over their budget of time or memory."),
                      small=True)
    table = (Table(("scene", "what", "measured", "budget", "result"), tuple(rows), numeric=(2, 3)) if rows
             else Paragraph(NO_BUDGET_ROWS))
    return Section("Budgets", "budgets", (intro, table))


def _error_budget(points, figure: str | None) -> list[Section]:
    if not points:
        return []
    blocks = [Paragraph("Each point of the figure below is one (scene, model, fidelity level): the model's worst "
                        "error there as a multiple of its tolerance, at the run time of one evaluation. Families "
                        "are declared by each check (docs/validation.md, 'Model identity'). Per model family:"),
              Table(("family", "points", "time of one evaluation", "median error / tol", "worst error / tol",
                     "models (level)"), tuple(family_table(points)), numeric=(1, 3, 4))]
    comparisons = same_scene_comparisons(points)
    if comparisons:
        blocks += [Paragraph("Scenes where models of different families answer the same question:"),
                   Table(("scene", "family", "model", "level", "one evaluation", "worst error / tol"),
                         tuple(comparisons), numeric=(4, 5))]
    if figure:
        blocks.append(Image(figure, "error against run time"))
    return [Section("Which model for an error budget", "error-vs-time", tuple(blocks))]


def _run_heading(model: str, family: str, level: str, time_s: float) -> Text:
    return (Span(model, "strong"), f" ({family}" + (f", {level}" if level else "") + f"), one evaluation "
            f"{fmt_time(time_s)}:")


def _scene(r: SceneResult, status: str, out_dir: Path | None) -> Section:
    blocks: list[Block] = [
        Paragraph(r.description),
        Paragraph((f"Kind {r.kind}; status ", Span(status_word(status), "strong", status=status),
                   f"; wall time {fmt_time(r.wall_time_s)} (budget {scene_budget_text(r)})."))]
    if r.error:
        blocks.append(Paragraph((Span("Error:", "strong", status="error"), " ", Span(r.error, "code"))))
    elif r.not_applicable:
        blocks.append(Paragraph((Span("Does not apply:", "strong", status="not applicable"), " ", r.not_applicable),
                                tone="muted"))
    elif r.inconclusive:
        blocks.append(Paragraph((Span("Inconclusive:", "strong", status="inconclusive"), " ", r.inconclusive),
                                tone="muted"))
    for title, header, rows in r.tables:  # results for the reader (loads, friction), before the checks
        blocks.append(Paragraph(Span(title, "strong")))
        blocks.append(Table(header, rows, numeric=tuple(range(1, len(header)))))
    for model, family, level, t, outputs in model_runs(r):
        blocks.append(Paragraph(_run_heading(model, family, level, t)))
        shown = [row(o) for o in outputs]
        blocks.append(Table(("quantity", "value", "reference", "unit", "error", "tolerance", "error / tol", "status",
                             "source"),
                            tuple((x.quantity, x.value, x.reference, x.unit or "-", x.error, x.tolerance, x.ratio,
                                   _status(x.status), x.source) for x in shown), numeric=(1, 2, 4, 5, 6)))
        notes = [f"{x.quantity}: {x.note}" for x in shown if x.note]
        notes += [f"{o.quantity}: known gap: {o.known_gap.reason} Evidence: {o.known_gap.evidence}"
                  for o in outputs if o.known_gap is not None]
        if notes:
            blocks.append(Bullets(tuple(notes)))
    blocks += [Quote(note) for note in r.notes]
    files = []
    for artifact in r.artifacts:
        if artifact.endswith(".png") and (out_dir is None or (out_dir / artifact).exists()):
            blocks.append(Image(artifact, artifact))
        else:
            files.append(artifact)
    if files:
        blocks.append(Files(tuple(files)))
    return Section(r.name, r.name, tuple(blocks), scene=True)


def build_document(results: Sequence[SceneResult], fidelity: str, counted: Tally, *, points: Sequence[dict] = (),
          figure: str | None = None, out_dir: Path | None = None) -> Document:
    """The report of ``results`` (``counted``: their :class:`Tally`; ``points``: the error-against-time points;
    ``figure``: the name of their PNG in the report folder; ``out_dir``: where the scenes' files are, to leave
    out a figure that was not written)."""
    out_dir = Path(out_dir) if out_dir is not None else None
    verdicts = tuple(_verdict(r, s, counted) for r, s in zip(results, counted.statuses))
    sections = [Section("", "", tuple(_head(results, fidelity, counted)))]
    sections += _unexpected(results)
    sections += _not_applicable(results, counted)
    sections += _inconclusive(results, counted)
    sections += _findings(results, counted)
    sections += [_summary(results, counted), _known_gaps(results, counted), _budgets(results)]
    sections += _error_budget(points, figure)
    sections += [_scene(r, s, out_dir) for r, s in zip(results, counted.statuses)]
    return Document("ballbench validation report", fidelity, counted, verdicts, tuple(sections),
                    tuple(r.name for r in results))
