"""The validation report: built once as a document, written as Markdown, HTML, JUnit, JSON, CSV and a figure.

Modules: ``rows`` (a check in engineering units), ``records`` (statuses,
``results.json``, ``results.csv``), ``points`` (accuracy against cost),
``figure`` and ``labels`` (``error_vs_time.png``), ``document`` (the
document's dataclasses), ``contents`` (what the report says), ``markdown``,
``html`` and ``junit`` (how each format writes it).

``results.json`` schema (stable; fields are added, never removed)::

    {"fidelity": str, "passed": bool, "strict": bool, "strict_time": bool,
     "complete": bool, "not_run": [str],
     "counts": {"pass", "known gap", "findings", "not applicable", "inconclusive", "fail", "error"},
     "scenes": [{"name", "description", "kind", "status", "passed", "error", "not_applicable", "inconclusive",
                 "wall_time_s", "budget_s", "over_budget", "interrupted", "peak_memory_gb",
                 "scene_peak_memory_gb", "declared_memory_gb", "over_memory",
                 "artifacts": [str], "notes": [str],
                 "outputs": [{"model", "quantity", "unit", "value", "reference",
                              "source", "rel_error", "tolerance", "passed",
                              "time_s", "relation", "note", "kind", "scale",
                              "why", "status", "known_gap_reason",
                              "known_gap_evidence", "family", "level"}],
                 "tables": [{"title", "header": [str], "rows": [[str]]}]}]}   # tables: only when a scene has some

``scene_peak_memory_gb`` is the scene's own peak resident memory (the peak while it ran above the resident memory
at its start, docs/validation.md, "Memory"), ``peak_memory_gb`` the process's peak while it ran (what earlier scenes
left loaded included), both 0 where not measured (a measured scene's own peak may be 0: it needed nothing the
process did not hold already); ``declared_memory_gb`` what the scene declares at the run's
fidelity, ``over_memory`` whether its own peak is above that.
``not_applicable`` is why a case file's scene does not apply to its case (status ``not applicable``; ``""`` for a
scene that applies).  ``inconclusive`` is why its reference is too uncertain to judge at the run's fidelity, with
what settles it (status ``inconclusive``; ``""`` when the reference is conclusive).
A scene's ``status`` is one of ``counts``' keys; an output's is ``pass``, ``fail``, ``outside accuracy`` (a
finding: a model outside its declared accuracy on a case's own geometry, docs/validation.md), ``known gap``,
``unexpected pass``, ``within budget`` or ``over budget``.
``family`` is one of ``scene.FAMILIES`` or ``""`` (undeclared), ``level`` the
model's fidelity level in words (``""`` without levels).  JSON and CSV carry SI
values; report.md and report.html show engineering units (mm, um, MPa, mN,
...) and errors in percent and as a multiple of the tolerance.
"""
from __future__ import annotations

import json
from pathlib import Path
from typing import Sequence

from ballbench.validation.report import contents, document
from ballbench.validation.report import html as html_page
from ballbench.validation.report import junit as junit_xml
from ballbench.validation.report import markdown as markdown_text
from ballbench.validation.report.figure import error_figure, plot_error_vs_time
from ballbench.validation.report.points import error_points, front_line, mesh_level_points, pareto_front
from ballbench.validation.report.records import CSV_FIELDS, Tally, results_from_json, tally, to_json, write_csv
from ballbench.validation.report.rows import (check_line, count, engineering, failure_lines, fmt_number, fmt_ratio,
                                              fmt_time, row, status_word)
from ballbench.validation.scene import SceneResult

__all__ = ["write_report", "to_markdown", "to_html", "to_junit", "to_json", "write_csv", "results_from_json",
           "tally", "Tally", "CSV_FIELDS", "error_points", "mesh_level_points", "pareto_front", "front_line",
           "error_figure", "plot_error_vs_time", "row", "check_line", "failure_lines", "status_word", "count",
           "engineering", "fmt_number", "fmt_ratio", "fmt_time"]


def _document(results, fidelity, out_dir=None, *, strict=False, strict_time=False, not_run=(), points=(),
              figure=None) -> document.Document:
    counted = tally(results, strict=strict, strict_time=strict_time, not_run=not_run)
    return contents.build_document(results, fidelity, counted, points=points, figure=figure, out_dir=out_dir)


def to_markdown(results: Sequence[SceneResult], fidelity: str, *, strict: bool = False, strict_time: bool = False,
                not_run: Sequence[str] = (), points: Sequence[dict] = ()) -> str:
    """``report.md`` of ``results`` (``points``: the error-against-time points, for the error-budget section)."""
    figure = "error_vs_time.png" if points else None
    return markdown_text.render(_document(results, fidelity, strict=strict, strict_time=strict_time, not_run=not_run,
                                     points=points, figure=figure))


def to_html(results: Sequence[SceneResult], fidelity: str, out_dir: Path, *, strict: bool = False,
            strict_time: bool = False, not_run: Sequence[str] = (), points: Sequence[dict] = ()) -> str:
    """``report.html`` of ``results``; figures are read from ``out_dir`` and inlined."""
    figure = "error_vs_time.png" if points else None
    built = _document(results, fidelity, Path(out_dir), strict=strict, strict_time=strict_time, not_run=not_run,
                      points=points, figure=figure)
    return html_page.render(built, Path(out_dir))


def to_junit(results: Sequence[SceneResult], *, strict: bool = False, strict_time: bool = False,
             not_run: Sequence[str] = ()) -> bytes:
    """JUnit XML of ``results``: one test case per scene."""
    return junit_xml.render(_document(results, "", strict=strict, strict_time=strict_time, not_run=not_run))


def write_report(results: Sequence[SceneResult], out_dir: Path, fidelity: str, *, strict: bool = False,
                 strict_time: bool = False, not_run: Sequence[str] = (), junit: Path | None = None) -> dict[str, Path]:
    """Write every report file into ``out_dir`` (and the JUnit XML to ``junit``); returns their paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = {
        "markdown": out_dir / "report.md",
        "html": out_dir / "report.html",
        "csv": out_dir / "results.csv",
        "json": out_dir / "results.json",
    }
    counted = tally(results, strict=strict, strict_time=strict_time, not_run=not_run)
    data = to_json(results, fidelity, counted=counted)
    paths["json"].write_text(json.dumps(data, indent=2))
    write_csv(results, paths["csv"])
    points: list[dict] = []
    if results:
        paths["png"], paths["points"] = out_dir / "error_vs_time.png", out_dir / "error_vs_time.csv"
        points = plot_error_vs_time(data, paths["png"], out_dir)
    built = contents.build_document(results, fidelity, counted, points=points,
                           figure="error_vs_time.png" if points else None, out_dir=out_dir)
    paths["markdown"].write_text(markdown_text.render(built))
    paths["html"].write_text(html_page.render(built, out_dir))
    if junit is not None:
        Path(junit).write_bytes(junit_xml.render(built))
        paths["junit"] = Path(junit)
    return paths
