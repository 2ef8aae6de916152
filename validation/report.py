"""Write scene results as Markdown, CSV, JSON and an error-against-run-time plot.

``results.json`` schema (stable; later scenes add rows, never fields removed)::

    {"fidelity": str, "passed": bool,
     "scenes": [{"name", "description", "passed", "error", "wall_time_s",
                 "artifacts": [str], "notes": [str],
                 "outputs": [{"model", "quantity", "unit", "value", "reference",
                              "source", "rel_error", "tolerance", "passed",
                              "time_s", "relation", "note"}]}]}
"""
from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Sequence

from ballbench.validation.scene import Output, SceneResult

CSV_FIELDS = ("scene", "model", "quantity", "unit", "value", "reference", "source",
              "rel_error", "tolerance", "passed", "time_s", "relation", "note")


def _json_number(x: float):
    return x if math.isfinite(x) else str(x)


def to_json(results: Sequence[SceneResult], fidelity: str) -> dict:
    return {
        "fidelity": fidelity,
        "passed": all(r.passed for r in results),
        "scenes": [
            {
                "name": r.name,
                "description": r.description,
                "passed": r.passed,
                "error": r.error,
                "wall_time_s": r.wall_time_s,
                "artifacts": list(r.artifacts),
                "notes": list(r.notes),
                "outputs": [
                    {k: (_json_number(v) if isinstance(v, float) else v) for k, v in o.as_dict().items()}
                    for o in r.outputs
                ],
            }
            for r in results
        ],
    }


def _fmt(x: float) -> str:
    if not math.isfinite(x):
        return str(x)
    if x == 0.0:
        return "0"
    if 1e-3 <= abs(x) < 1e5:
        return f"{x:.6g}"
    return f"{x:.4e}"


def _fmt_time(t: float) -> str:
    if t < 1e-3:
        return f"{t * 1e6:.1f} us"
    if t < 1.0:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.2f} s"


def _relation_symbol(o: Output) -> str:
    return {"eq": "", "ge": ">= ", "le": "<= "}[o.relation]


def to_markdown(results: Sequence[SceneResult], fidelity: str) -> str:
    n_pass = sum(r.passed for r in results)
    lines = [
        "# ballbench validation report",
        "",
        f"Fidelity: `{fidelity}`. Scenes passed: {n_pass} of {len(results)}.",
        "",
        "Error is relative: |value - reference| / |reference| (for a zero reference, "
        "divided by the scale stated in the note; for a bound, only the side that "
        "violates it counts). Run time is the wall time of one model evaluation "
        "(median of repeats for fast models).",
        "",
        "| scene | passed | outputs | wall time |",
        "|---|---|---|---|",
    ]
    for r in results:
        lines.append(f"| [{r.name}](#{r.name}) | {'yes' if r.passed else '**NO**'} | {len(r.outputs)} | {_fmt_time(r.wall_time_s)} |")
    lines.append("")
    for r in results:
        lines += [f"## {r.name}", "", r.description, ""]
        if r.error:
            lines += [f"**Error:** `{r.error}`", ""]
        if r.outputs:
            lines += [
                "| model | quantity | unit | value | reference | source | error | tolerance | run time | pass |",
                "|---|---|---|---|---|---|---|---|---|---|",
            ]
            for o in r.outputs:
                lines.append(
                    f"| {o.model} | {o.quantity} | {o.unit} | {_fmt(o.value)} | {_relation_symbol(o)}{_fmt(o.reference)} "
                    f"| {o.source} | {_fmt(o.rel_error)} | {_fmt(o.tolerance)} | {_fmt_time(o.time_s)} "
                    f"| {'yes' if o.passed else '**NO**'} |"
                )
            lines.append("")
            notes = [f"- {o.quantity} ({o.model}): {o.note}" for o in r.outputs if o.note]
            if notes:
                lines += notes + [""]
        for note in r.notes:
            lines += [f"> {note}", ""]
        for artifact in r.artifacts:
            if artifact.endswith(".png"):
                lines += [f"![{artifact}]({artifact})", ""]
            else:
                lines += [f"- [{artifact}]({artifact})", ""]
    if any(a for r in results for a in r.artifacts) or results:
        lines += ["## Error against run time", "", "![error_vs_time](error_vs_time.png)", ""]
    return "\n".join(lines)


def write_csv(results: Sequence[SceneResult], path: Path) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for r in results:
            for o in r.outputs:
                row = o.as_dict()
                row["scene"] = r.name
                writer.writerow({k: row[k] for k in CSV_FIELDS})


def plot_error_vs_time(results: Sequence[SceneResult], path: Path) -> None:
    """Log-log error against run time, one marker per (model, scene).

    Each marker is the worst relative error of that model in that scene at the
    summed run time of its outputs.  Exact zero errors are drawn at 1e-17.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    floor = 1e-17
    figure, axes = plt.subplots(figsize=(8, 5.5))
    markers = "osD^v<>pPX*h"
    points = {}
    for r in results:
        for o in r.outputs:
            key = (o.model, r.name)
            err = o.rel_error if math.isfinite(o.rel_error) else 1e3
            t = max(o.time_s, 1e-9)
            worst, total, passed = points.get(key, (0.0, 0.0, True))
            points[key] = (max(worst, err), total + t, passed and o.passed)
    models = sorted({m for m, _ in points})
    for i, model in enumerate(models):
        xs, ys, edge = [], [], []
        for (m, name), (err, t, passed) in points.items():
            if m == model:
                xs.append(t)
                ys.append(max(err, floor))
                edge.append("black" if passed else "red")
        axes.scatter(xs, ys, marker=markers[i % len(markers)], s=45, label=model, edgecolors=edge, linewidths=1.0)
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("run time per evaluation [s]")
    axes.set_ylabel("worst relative error in scene [-]")
    axes.set_title("ballbench: error against run time (red edge: failed)")
    axes.grid(True, which="both", alpha=0.3)
    if models:
        axes.legend(fontsize=7, loc="best")
    figure.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(figure)


def write_report(results: Sequence[SceneResult], out_dir: Path, fidelity: str) -> dict[str, Path]:
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = {
        "markdown": out_dir / "report.md",
        "csv": out_dir / "results.csv",
        "json": out_dir / "results.json",
        "png": out_dir / "error_vs_time.png",
    }
    paths["markdown"].write_text(to_markdown(results, fidelity))
    write_csv(results, paths["csv"])
    paths["json"].write_text(json.dumps(to_json(results, fidelity), indent=2))
    plot_error_vs_time(results, paths["png"])
    return paths
