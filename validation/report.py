"""Write scene results as Markdown, HTML, CSV, JSON, JUnit XML and an error-against-run-time figure.

``results.json`` schema (stable; fields are added, never removed)::

    {"fidelity": str, "passed": bool, "strict": bool, "strict_time": bool,
     "complete": bool, "not_run": [str],
     "counts": {"pass", "known gap", "fail", "error"},
     "scenes": [{"name", "description", "kind", "status", "passed", "error",
                 "wall_time_s", "budget_s", "over_budget", "interrupted",
                 "artifacts": [str], "notes": [str],
                 "outputs": [{"model", "quantity", "unit", "value", "reference",
                              "source", "rel_error", "tolerance", "passed",
                              "time_s", "relation", "note", "kind", "scale",
                              "why", "status", "known_gap_reason",
                              "known_gap_evidence"}]}]}

JSON and CSV carry SI values; report.md and report.html show engineering
units (mm, um, MPa, mN, ...) and errors in percent and as a multiple of the
tolerance.
"""
from __future__ import annotations

import base64
import csv
import html
import json
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from ballbench.validation.scene import Output, SceneResult

CSV_FIELDS = ("scene", "model", "quantity", "unit", "value", "reference", "source", "rel_error", "tolerance",
              "passed", "status", "time_s", "relation", "kind", "scale", "note", "why", "known_gap_reason",
              "known_gap_evidence")
# Okabe-Ito colours (safe for the common colour-vision deficiencies) and distinct markers for print
STYLE = {
    "pass": ("#0072B2", "o", "passed"),
    "known gap": ("#E69F00", "s", "known gap"),
    "fail": ("#D55E00", "X", "failed"),
    "unexpected pass": ("#CC79A7", "D", "known gap that now passes"),
}
FLOOR = 1e-8     # error / tolerance drawn at this floor when it is exactly 0 (or below it)
CEILING = 1e4    # ... and at this ceiling when infinite (a missed bound of tolerance 0, a non-finite value)
# closed forms and explicit formulas (lin2017 rigid four-point, Hertz, the friction map, lin2019 eqs 22-33, wang2022)
ANALYTICAL_MODELS = ("lowmodel.contact.hertz", "lowmodel.contact.ellipse_friction",
                     "lowmodel.linear_bearing.b2b_analytical", "lowmodel.screw.kinematics",
                     "lowmodel.ball_bearing.harris", "lowmodel.linear_bearing.fourpoint")
# numerical solutions of the low-order equations: Newton on the ball equilibria (lin2019 eqs 1-10, 54-61), the
# whole screw in time, the load distribution, and the BEM / EHL / mixed-lubrication solvers (sun2021)
LOW_ORDER_MODELS = ("lowmodel.linear_bearing.ball", "lowmodel.linear_bearing.b2b",
                    "lowmodel.linear_bearing.b2b_traction", "lowmodel.screw.ball", "lowmodel.screw.b2b",
                    "lowmodel.screw.b2b_traction", "lowmodel.screw.load_distribution",
                    "lowmodel.screw.whole_screw", "lowmodel.contact.halfspace", "lowmodel.contact.screw_contact",
                    "lowmodel.contact.ehl", "lowmodel.contact.mixed")


# ----------------------------------------------------------------------------------------------- numbers
def _is_model(model: str, module: str) -> bool:
    """``model`` names ``module`` itself, one of its functions (``module.f``) or a variant (``module (note)``)."""
    return model == module or model.startswith(module + " ") or model.startswith(module + ".")


def model_family(model: str) -> str:
    """``"FE"``, ``"low-order numerical"``, ``"analytical"`` or ``"other"`` (by the model's module name; ``other``:
    fits, sampling and the harness itself, e.g. ``lowmodel.calibration``, ``lowmodel.contact.roughness``)."""
    if model.startswith("fem."):
        return "FE"
    if any(_is_model(model, m) for m in LOW_ORDER_MODELS):
        return "low-order numerical"
    if any(_is_model(model, m) for m in ANALYTICAL_MODELS):
        return "analytical"
    return "other"


# SI unit -> ((threshold, factor, display unit), ...) from the largest: the first whose threshold <= |x|
_ENGINEERING = {
    "m": ((1e-3, 1e3, "mm"), (0.0, 1e6, "um")),
    "Pa": ((0.0, 1e-6, "MPa"),),
    "N": ((1.0, 1.0, "N"), (0.0, 1e3, "mN")),
    "W": ((1.0, 1.0, "W"), (0.0, 1e3, "mW")),
    "m/s": ((1.0, 1.0, "m/s"), (0.0, 1e3, "mm/s")),
    "N/m": ((0.0, 1e-6, "N/um"),),
    "s": ((1.0, 1.0, "s"), (1e-3, 1e3, "ms"), (0.0, 1e6, "us")),
}


def engineering(unit: str, *numbers: float) -> tuple[float, str]:
    """(factor, display unit) for showing ``numbers`` (SI ``unit``) in one engineering unit."""
    if unit not in _ENGINEERING:
        return 1.0, unit
    finite = [abs(x) for x in numbers if math.isfinite(x) and x != 0.0]
    magnitude = max(finite) if finite else 0.0
    for threshold, factor, shown in _ENGINEERING[unit]:
        if magnitude >= threshold:
            return factor, shown
    return _ENGINEERING[unit][-1][1:]


def fmt_number(x: float, digits: int = 5) -> str:
    """``digits`` significant figures; plain notation from 1e-3 to 1e6, else ``1.234e-09``."""
    if isinstance(x, str):
        return x
    if not math.isfinite(x):
        return str(x)
    if x == 0.0:
        return "0"
    rounded = float(f"{x:.{digits}g}")  # so that 0.999999 counts as 1.0000, not 0.99999..
    if 1e-3 <= abs(rounded) < 1e7:
        before = math.floor(math.log10(abs(rounded))) + 1
        return f"{x:.{max(0, digits - before)}f}"
    return f"{x:.{digits - 1}e}"


def count(n: int, noun: str) -> str:
    """``"1 scene"``, ``"35 scenes"``: a count with its noun (regular plural)."""
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def fmt_time(t: float) -> str:
    if not math.isfinite(t):
        return str(t)
    if t < 1e-3:
        return f"{t * 1e6:.3g} us"
    if t < 1.0:
        return f"{t * 1e3:.3g} ms"
    return f"{t:.3g} s"


def fmt_percent(rel_error: float) -> str:
    if not math.isfinite(rel_error):
        return str(rel_error)
    if rel_error == 0.0:
        return "0 %"
    value = rel_error * 100
    return f"{value:.3g} %" if value >= 1e-3 else f"{value:.2e} %"


def fmt_ratio(o: Output) -> str:
    """Error as a multiple of the tolerance (1 = at tolerance)."""
    if o.kind == "budget":
        return ""
    met = "0 (bound met)" if o.relation != "eq" else "0 (exact)"  # a bound that holds has error 0 too
    if o.tolerance == 0:
        return met if o.rel_error == 0 else "bound missed" if o.relation != "eq" else "not exact"
    r = o.error_over_tolerance
    if r == 0:
        return met
    return f"{r:.2g}" if r >= 1e-3 else f"{r:.1e}"


def _relation_symbol(o: Output) -> str:
    return {"eq": "", "ge": ">= ", "le": "<= "}[o.relation]


@dataclass(frozen=True)
class Row:
    """An output as the report shows it (engineering units, formatted)."""

    model: str
    quantity: str
    value: str
    reference: str
    unit: str
    error: str
    tolerance: str
    ratio: str
    status: str
    source: str
    time: str
    note: str

    @property
    def value_with_unit(self) -> str:
        return f"{self.value} {self.unit}" if self.unit else self.value

    @property
    def reference_with_unit(self) -> str:
        return f"{self.reference} {self.unit}" if self.unit else self.reference


DIMENSIONLESS = ("1", "-", "")  # shown without a unit after the number and as "-" in a unit column


def row(o: Output) -> Row:
    factor, unit = engineering(o.unit, o.value, o.reference)
    unit = "" if unit in DIMENSIONLESS else unit
    value = fmt_number(o.value * factor)
    reference = _relation_symbol(o) + fmt_number(o.reference * factor)
    if o.kind == "budget":
        tolerance = "budget"
        error = "" if o.passed else fmt_percent(o.rel_error) + " over"
    elif o.tolerance == 0:
        tolerance = "bound" if o.relation != "eq" else "exact"
        error = fmt_percent(o.rel_error)
    else:
        tolerance = fmt_percent(o.tolerance)
        error = fmt_percent(o.rel_error)
    note = o.note
    if o.why:
        note = (note + "; " if note else "") + "why this tolerance/scale: " + o.why
    return Row(o.model, o.quantity, value, reference, unit, error, tolerance, fmt_ratio(o), o.status, o.source,
               fmt_time(o.time_s), note)


def model_runs(result: SceneResult) -> list[tuple[str, float, list[Output]]]:
    """The scene's accuracy outputs grouped by model run: (model, time of one evaluation [s], outputs)."""
    groups: dict[tuple[str, float], list[Output]] = {}
    for o in result.outputs:
        if o.kind == "accuracy":
            groups.setdefault((o.model, o.time_s), []).append(o)
    return [(model, t, outputs) for (model, t), outputs in groups.items()]


def worst_ratio_text(outputs: Sequence[Output]) -> str:
    """The summary's worst error / tolerance; a 0 says whether it is exact agreement or bounds that hold."""
    worst = worst_ratio(outputs)
    if worst != 0:
        return _ratio_text(worst)
    relations = {o.relation == "eq" for o in outputs if o.kind == "accuracy"}
    if not relations:
        return "-"
    return {frozenset({True}): "0 (exact)", frozenset({False}): "0 (bounds met)"}.get(
        frozenset(relations), "0 (exact; bounds met)")


def worst_ratio(outputs: Sequence[Output]) -> float:
    ratios = [o.error_over_tolerance for o in outputs if o.kind == "accuracy"]
    return max(ratios) if ratios else 0.0


# ----------------------------------------------------------------------------------------------- points
def error_points(data: dict) -> list[dict]:
    """One point per (scene, model) of ``results.json`` data, as the error-against-time figure draws it.

    ``error`` is the model's worst error as a multiple of its tolerance in
    that scene; ``time_s`` the run time of one evaluation of the model: the
    evaluation that produced that worst error (the longest one on a tie);
    budget rows are not accuracy and are left out, and so are checks
    timed at 0 s (consistency checks of a paper's data, no model run).  ``status`` is the worst
    status of the model's checks (fail > unexpected pass > known gap > pass).
    """
    order = {"pass": 0, "known gap": 1, "unexpected pass": 2, "fail": 3}
    points = []
    for index, s in enumerate(data["scenes"]):
        by_model: dict[str, list[dict]] = {}
        for o in s["outputs"]:
            if o.get("kind", "accuracy") == "accuracy":
                by_model.setdefault(o["model"], []).append(o)
        for model, outputs in by_model.items():
            outputs = [o for o in outputs if _float(o["time_s"]) > 0]  # 0: no model was evaluated (a data check)
            if not outputs:
                continue

            def ratio(o):
                rel, tol = _float(o["rel_error"]), _float(o["tolerance"])
                if tol > 0:
                    return rel / tol
                return 0.0 if rel == 0 else math.inf

            worst = max(ratio(o) for o in outputs)
            time_s = max(float(o["time_s"]) for o in outputs if ratio(o) == worst)
            status = max((o["status"] for o in outputs), key=order.__getitem__)
            points.append({"scene": s["name"], "model": model, "family": model_family(model), "time_s": time_s,
                           "error": worst, "status": status, "scene_index": index})
    return points


def _float(x) -> float:
    return float(x) if not isinstance(x, str) else float(x.replace("Infinity", "inf"))


def pareto_front(points: Sequence[dict]) -> list[dict]:
    """Points of one family that no other point beats in both time and error (sorted by time)."""
    front, best = [], math.inf
    for p in sorted(points, key=lambda p: (p["time_s"], p["error"])):
        if p["error"] < best:
            front.append(p)
            best = p["error"]
    return front


def front_line(points: Sequence[dict]) -> tuple[list[float], list[float]]:
    """The step line of a family's front as drawn (``where="post"``): the front's (time, error / tol) and a last
    vertex at the family's longest run time, so the best error reached so far holds to the right edge; a front of
    one point (the fastest point is also the most accurate) is then a visible horizontal line, not a lone vertex."""
    front = pareto_front(points)
    if not front:
        return [], []
    times = [p["time_s"] for p in front]
    errors = [min(max(p["error"], FLOOR), CEILING) for p in front]
    longest = max(p["time_s"] for p in points)
    if longest > times[-1] or len(front) == 1:
        times.append(max(longest, times[-1] * 1.5))  # a lone point at the longest time: a short stub to the right
        errors.append(errors[-1])
    return times, errors


def mesh_level_points(data: dict, out_dir: Path) -> list[dict]:
    """Every mesh level of the scenes that saved a ``convergence.csv`` (FE scenes), as accuracy-cost points.

    A level's error is ``max_q |err_q| / tol_q`` over the quantities ``q``
    that the scene checked (columns ``err_<q>``; tolerances from its checks),
    its time the level's ``wall_s``; at the default fidelity the one level is
    the checked one, at ``--fine`` the convergence study gives a front.
    """
    levels = []
    for s in data["scenes"]:
        if not any(a.endswith("convergence.csv") for a in s["artifacts"]):
            continue
        path = Path(out_dir) / next(a for a in s["artifacts"] if a.endswith("convergence.csv"))
        tolerance = {o["quantity"]: _float(o["tolerance"]) for o in s["outputs"] if o.get("kind") == "accuracy"}
        try:
            with open(path, newline="") as handle:
                rows = list(csv.DictReader(handle))
        except OSError:
            continue
        for r in rows:
            ratios = [abs(float(r[f"err_{q}"])) / tol for q, tol in tolerance.items() if f"err_{q}" in r and tol > 0]
            if ratios and "wall_s" in r:
                levels.append({"scene": s["name"], "time_s": float(r["wall_s"]), "error": max(ratios),
                               "level": f"n = {r.get('n', '?')}, growth {r.get('growth', '?')}"})
    return levels


def plot_error_vs_time(data: dict, path: Path, out_dir: Path | None = None) -> list[dict]:
    """Error (multiple of tolerance) against the run time of one evaluation; returns the plotted points.

    Left: one numbered point per (scene, model), coloured and shaped by
    status, with a key of the numbers.  Right: each model family's front of
    accuracy against cost.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = error_points(data)
    for p in points:
        p["y"] = min(max(p["error"], FLOOR), CEILING)
    figure = plt.figure(figsize=(15, 7.5))
    grid = figure.add_gridspec(1, 3, width_ratios=(1.25, 1.0, 0.62), wspace=0.25)
    left, right, key = figure.add_subplot(grid[0]), figure.add_subplot(grid[1]), figure.add_subplot(grid[2])
    for status, (colour, marker, label) in STYLE.items():
        chosen = [p for p in points if p["status"] == status]
        if chosen:
            left.scatter([p["time_s"] for p in chosen], [p["y"] for p in chosen], c=colour, marker=marker, s=60,
                         edgecolors="black", linewidths=0.6, label=f"{label} ({len(chosen)})", zorder=3)
    for number, p in enumerate(points, start=1):
        p["number"] = number
        left.annotate(str(number), (p["time_s"], p["y"]), textcoords="offset points", xytext=(5, 4), fontsize=7)
    for axes in (left, right):
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.set_ylim(FLOOR / 5, CEILING * 5)
        axes.axhline(1.0, color="black", lw=1.0, ls="--")
        axes.axhspan(FLOOR / 5, FLOOR * 2, color="0.9", zorder=0)
        axes.axhspan(CEILING / 2, CEILING * 5, color="0.9", zorder=0)
        axes.text(0.01, 0.015, "floor: error 0 (exact, or all bounds met) or below 1e-8",
                  transform=axes.transAxes, fontsize=7)
        axes.text(0.01, 0.965, "ceiling: tolerance-0 bound missed / non-finite", transform=axes.transAxes,
                  fontsize=7, va="top")
        axes.set_xlabel("run time of one model evaluation [s]")
        axes.grid(True, which="major", alpha=0.3)
    left.text(0.01, 1.15, "1 = at tolerance", transform=left.get_yaxis_transform(), fontsize=7, ha="left",
              va="bottom")
    left.set_ylabel("worst error / tolerance [-]")
    left.set_title("Each (scene, model): worst error against run time")
    if points:
        left.legend(loc="upper left", bbox_to_anchor=(0.0, 0.92), fontsize=8)
    families = sorted({p["family"] for p in points})
    styles = {"analytical": ("#009E73", "^", "-"), "low-order numerical": ("#56B4E9", "v", "--"),
              "FE": ("#000000", "P", "-."), "other": ("#999999", ".", ":")}
    for family in families:
        colour, marker, line = styles.get(family, styles["other"])
        members = [p for p in points if p["family"] == family]
        right.scatter([p["time_s"] for p in members], [p["y"] for p in members], c=colour, marker=marker, s=30,
                      alpha=0.5)
        right.step(*front_line(members), where="post", color=colour, ls=line, lw=2,
                   label=f"{family} ({count(len(members), 'point')})")
    levels = mesh_level_points(data, out_dir) if out_dir is not None else []
    for scene_name in sorted({p["scene"] for p in levels}):
        chosen = sorted((p for p in levels if p["scene"] == scene_name), key=lambda p: p["time_s"])
        right.plot([p["time_s"] for p in chosen], [min(max(p["error"], FLOOR), CEILING) for p in chosen], "o-",
                   color="0.35", ms=3, lw=0.8, label="FE mesh levels of a scene" if scene_name == min(
                       p["scene"] for p in levels) else None)
    # one time axis for both panels, at least a decade wide (a narrower log axis labels its minor ticks on top
    # of each other, e.g. a run of one FE scene)
    if points or levels:
        low = min(left.get_xlim()[0], right.get_xlim()[0])
        high = max(left.get_xlim()[1], right.get_xlim()[1])
        if high < 10.0 * low:
            centre = math.sqrt(low * high)
            low, high = centre / math.sqrt(10.0), centre * math.sqrt(10.0)
        for axes in (left, right):
            axes.set_xlim(low, high)
    right.set_title("Accuracy against cost: front of each model family")
    if points:
        right.legend(loc="upper left", bbox_to_anchor=(0.0, 0.92), fontsize=8)
    key.axis("off")
    lines = [f"{p['number']:>2}  {p['scene']}  ·  {p['model'].replace('lowmodel.', '')}" for p in points]
    key.text(0.0, 1.0, "Key: number, scene, model\n" + "\n".join(lines), va="top", ha="left",
             fontsize=7 if len(lines) < 45 else 5.5, family="monospace",
             transform=key.transAxes)
    figure.suptitle(f"ballbench run at fidelity {data.get('fidelity', '')}: error against run time "
                    "(1 = at tolerance; below the dashed line passes)", fontsize=11)
    figure.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(figure)
    with open(Path(path).with_suffix(".csv"), "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=("number", "scene", "model", "family", "time_s",
                                                    "error_over_tolerance", "plotted_at", "status"))
        writer.writeheader()
        for p in points:
            writer.writerow({"number": p["number"], "scene": p["scene"], "model": p["model"], "family": p["family"],
                             "time_s": repr(p["time_s"]), "error_over_tolerance": repr(p["error"]),
                             "plotted_at": repr(p["y"]), "status": p["status"]})
    return points


# ----------------------------------------------------------------------------------------------- JSON, CSV
def _json_number(x):
    return x if not isinstance(x, float) or math.isfinite(x) else str(x)


def to_json(results: Sequence[SceneResult], fidelity: str, *, strict: bool = False, strict_time: bool = False,
            not_run: Sequence[str] = ()) -> dict:
    statuses = [r.status(strict=strict, strict_time=strict_time) for r in results]
    counts = {k: statuses.count(k) for k in ("pass", "known gap", "fail", "error")}
    return {
        "fidelity": fidelity,
        "passed": all(s in ("pass", "known gap") for s in statuses) and not not_run,
        "strict": strict,
        "strict_time": strict_time,
        "complete": not not_run,
        "not_run": list(not_run),
        "counts": counts,
        "scenes": [
            {
                "name": r.name,
                "description": r.description,
                "kind": r.kind,
                "status": status,
                "passed": status in ("pass", "known gap"),
                "error": r.error,
                "wall_time_s": r.wall_time_s,
                "budget_s": _json_number(r.budget_s),
                "over_budget": r.over_budget,
                "interrupted": r.interrupted,
                "artifacts": list(r.artifacts),
                "notes": list(r.notes),
                "outputs": [{k: _json_number(v) for k, v in o.as_dict().items()} for o in r.outputs],
            }
            for r, status in zip(results, statuses)
        ],
    }


def write_csv(results: Sequence[SceneResult], path: Path) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for r in results:
            for o in r.outputs:
                data = o.as_dict()
                data["scene"] = r.name
                writer.writerow({k: data[k] for k in CSV_FIELDS})


# ----------------------------------------------------------------------------------------------- summaries
def status_word(status: str) -> str:
    return {"pass": "PASS", "known gap": "PASS (known gap)", "fail": "FAIL", "error": "ERROR"}[status]


def check_line(o: Output) -> str:
    """One check as a line: quantity, model, value and reference with unit, source, error and tolerance."""
    r = row(o)
    tolerance = f"tolerance {r.tolerance}" if o.kind == "accuracy" else "budget"
    return (f"  {o.quantity} [{o.model}]: {r.value_with_unit} vs reference {r.reference_with_unit} ({o.source}): "
            f"error {r.error or '0 %'}, {tolerance}")


def failure_lines(result: SceneResult, *, strict: bool = False, strict_time: bool = False, limit: int = 5) -> list[str]:
    """One line per failed check: quantity, model, value, reference, error and tolerance."""
    bad = [o for o in result.outputs if o.status in ("fail", "unexpected pass")
           or (strict and o.status == "known gap") or (strict_time and o.status == "over budget")]
    lines = []
    for o in bad[:limit]:
        what = {"unexpected pass": "known gap now PASSES (remove its declaration)",
                "known gap": "known gap (--strict)", "over budget": "over budget (--strict-time)"}.get(o.status, "")
        lines.append(check_line(o) + (f"; {what}" if what else ""))
    if strict_time and result.wall_time_s > result.budget_s:
        lines.append(f"  scene wall time {fmt_time(result.wall_time_s)} over its budget {fmt_time(result.budget_s)} "
                     "(--strict-time)")
    if len(bad) > limit:
        lines.append(f"  ... and {len(bad) - limit} more failed checks (report.md)")
    return lines


SAME_AS_ABOVE = "as above"
NO_BUDGET_ROWS = "None in this run: no model budget recorded and no scene over its wall-time budget."


def known_gap_rows(gaps: Sequence[tuple[SceneResult, Output]]) -> list[tuple[str, ...]]:
    """Rows of the known-gaps table: (scene, check, value, published, status, reason, evidence); a check of the
    same scene declared with the same reason and evidence as the row above says "as above" instead of repeating
    a paragraph (lin2019-fig21 declares three checks with one reason)."""
    rows, previous = [], None
    for r, o in gaps:
        key = (r.name, o.known_gap.reason, o.known_gap.evidence)
        reason, evidence = (SAME_AS_ABOVE, SAME_AS_ABOVE) if key == previous else key[1:]
        rows.append((r.name, o.quantity, row(o).value_with_unit, row(o).reference_with_unit, o.status, reason,
                     evidence))
        previous = key
    return rows


def _scene_budget_text(r: SceneResult) -> str:
    if not math.isfinite(r.budget_s):
        return "-"
    return f"{fmt_time(r.budget_s)} ({'over' if r.wall_time_s > r.budget_s else 'under'})"


def family_table(points: Sequence[dict]) -> list[tuple[str, int, str, str, str, str]]:
    """Per model family: points, time range of one evaluation, median and worst error / tolerance, scenes."""
    rows = []
    for family in ("analytical", "low-order numerical", "FE", "other"):
        members = [p for p in points if p["family"] == family]
        if not members:
            continue
        times = sorted(p["time_s"] for p in members)
        errors = sorted(p["error"] for p in members)
        median = errors[len(errors) // 2]
        rows.append((family, len(members), f"{fmt_time(times[0])} - {fmt_time(times[-1])}",
                     _ratio_text(median), _ratio_text(errors[-1]),
                     ", ".join(sorted({p['model'].replace('lowmodel.', '') for p in members}))))
    return rows


def _ratio_text(r: float) -> str:
    if r == 0:
        return "0 (exact)"
    if not math.isfinite(r):
        return "bound missed"
    return f"{r:.2g}"


def same_scene_comparisons(points: Sequence[dict]) -> list[tuple[str, str, str, str, str]]:
    """Scenes where models of different families answer the same question: (scene, family, model, time, error)."""
    rows = []
    for scene_name in sorted({p["scene"] for p in points}):
        members = [p for p in points if p["scene"] == scene_name]
        if len({p["family"] for p in members}) < 2:
            continue
        for p in sorted(members, key=lambda p: p["time_s"]):
            rows.append((scene_name, p["family"], p["model"], fmt_time(p["time_s"]), _ratio_text(p["error"])))
    return rows


# ----------------------------------------------------------------------------------------------- Markdown
def _md_cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _md_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_md_cell(c) for c in r) + " |" for r in rows]
    return lines + [""]


def to_markdown(results: Sequence[SceneResult], fidelity: str, *, strict: bool = False, strict_time: bool = False,
                not_run: Sequence[str] = (), points: Sequence[dict] = ()) -> str:
    data_status = [r.status(strict=strict, strict_time=strict_time) for r in results]
    counts = {k: data_status.count(k) for k in ("pass", "known gap", "fail", "error")}
    lines = ["# ballbench validation report", ""]
    mode = ", ".join(m for m, on in (("--strict", strict), ("--strict-time", strict_time)) if on) or "default"
    lines += [f"Fidelity `{fidelity}`, mode {mode}. {count(len(results), 'scene')}: {counts['pass']} passed, "
              f"{counts['known gap']} passed with known gaps, {counts['fail']} failed, {counts['error']} raised.", ""]
    if not_run:
        lines += [f"**Partial report: the run was interrupted; {count(len(not_run), 'scene')} did not run:** "
                  + ", ".join(not_run), ""]
    unexpected = [(r, o) for r in results for o in r.outputs if o.status == "unexpected pass"]
    if unexpected:
        lines += ["## UNEXPECTED PASSES: declared known gaps that now pass", "",
                  "Remove the `known_gap=` declaration of each (the run fails until then).", ""]
        lines += _md_table(("scene", "check", "value", "reference"),
                           [(r.name, o.quantity, row(o).value, row(o).reference) for r, o in unexpected])
    lines += ["## Summary", ""]
    lines += ["Errors are relative: |value - reference| / max(|reference|, scale) (for a bound only the violating "
              "side counts); *error / tol* is that error as a multiple of the check's tolerance (1 = at "
              "tolerance). Values are shown in engineering units; results.json and results.csv stay SI.", ""]
    lines += _md_table(("scene", "kind", "status", "checks", "worst error / tol", "wall time", "budget"), [
        (f"[{r.name}](#{r.name})", r.kind, status_word(s) + (" (interrupted)" if r.interrupted else ""),
         f"{len([o for o in r.outputs if o.kind == 'accuracy'])}", worst_ratio_text(r.outputs),
         fmt_time(r.wall_time_s), _scene_budget_text(r)) for r, s in zip(results, data_status)])
    gaps = [(r, o) for r in results for o in r.outputs if o.known_gap is not None]
    lines += ["## Known gaps", ""]
    if gaps:
        lines += ["Published numbers this project does not reproduce, declared with their reason and evidence. "
                  "They are checked and reported like any other check" + (
                      "; this `--strict` run counts them as failures." if strict else
                      " but do not fail the run (`--strict` makes them fail)."), ""]
        lines += _md_table(("scene", "check", "value", "published", "status", "reason", "evidence"),
                           known_gap_rows(gaps))
    else:
        lines += ["None in this run.", ""]
    lines += ["## Budgets (reported; they decide pass/fail only with `--strict-time`)", ""]
    lines += ["Every scene's wall time and budget stand in the summary; here the model budgets and the scenes "
              "over their budget.", ""]
    budget_rows = [(r.name, "scene wall time", fmt_time(r.wall_time_s), fmt_time(r.budget_s), "**over budget**")
                   for r in results if r.wall_time_s > r.budget_s]
    for r in results:
        for o in r.outputs_with("within budget") + r.outputs_with("over budget"):
            rr = row(o)
            budget_rows.append((r.name, o.quantity, rr.value_with_unit, rr.reference_with_unit,
                                "within budget" if o.passed else "**over budget**"))
    lines += (_md_table(("scene", "what", "measured", "budget", "result"), budget_rows) if budget_rows
              else [NO_BUDGET_ROWS, ""])
    if points:
        lines += ["## Which model for an error budget", "",
                  "Each point of the figure below is one (scene, model): its worst error as a multiple of its "
                  "tolerance at the run time of one evaluation. Per model family:", ""]
        lines += _md_table(("family", "points", "time of one evaluation", "median error / tol",
                            "worst error / tol", "models"), family_table(points))
        comparisons = same_scene_comparisons(points)
        if comparisons:
            lines += ["Scenes where models of different families answer the same question:", ""]
            lines += _md_table(("scene", "family", "model", "one evaluation", "worst error / tol"), comparisons)
        lines += ["![error against run time](error_vs_time.png)", ""]
    for r, s in zip(results, data_status):
        lines += [f"## {r.name}", "", r.description, "",
                  f"Kind {r.kind}; status **{status_word(s)}**; wall time {fmt_time(r.wall_time_s)} "
                  f"(budget {_scene_budget_text(r)}).", ""]
        if r.error:
            lines += [f"**Error:** `{r.error}`", ""]
        for model, t, outputs in model_runs(r):
            lines += [f"**{model}**, one evaluation {fmt_time(t)}:", ""]
            rows = [row(o) for o in outputs]
            lines += _md_table(("quantity", "value", "reference", "unit", "error", "tolerance", "error / tol",
                                "status", "source"),
                               [(x.quantity, x.value, x.reference, x.unit or "-", x.error, x.tolerance, x.ratio,
                                 x.status if x.status == "pass" else f"**{x.status}**", x.source) for x in rows])
            notes = [f"- {x.quantity}: {x.note}" for x in rows if x.note]
            notes += [f"- {o.quantity}: known gap: {o.known_gap.reason} Evidence: {o.known_gap.evidence}"
                      for o in outputs if o.known_gap is not None]
            if notes:
                lines += notes + [""]
        for note in r.notes:
            lines += [f"> {note}", ""]
        for artifact in r.artifacts:
            if artifact.endswith(".png"):
                lines += [f"![{artifact}]({artifact})", ""]
            else:
                lines += [f"- [{artifact}]({artifact})", ""]
    return "\n".join(lines)


# ----------------------------------------------------------------------------------------------- HTML
_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:1.5em auto;max-width:1300px;
color:#222;line-height:1.35;padding:0 1em}
table{border-collapse:collapse;margin:.5em 0 1em;font-size:13px}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#f0f0f0}td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.pass{color:#0072B2}.fail,.error,.unexpected{color:#D55E00;font-weight:bold}.gap{color:#9a6b00;font-weight:bold}
.banner{padding:.6em 1em;border-radius:4px;margin:.5em 0}.banner.ok{background:#e6f0fa}
.banner.bad{background:#fde3d6}.banner.warn{background:#fff1d0}
blockquote{margin:.4em 0 .4em 1em;padding-left:.8em;border-left:3px solid #ccc;color:#444;font-size:13px}
img{max-width:100%;border:1px solid #ddd;margin:.3em 0}figure{margin:.5em 0}figcaption{font-size:12px;color:#555}
h2{border-bottom:1px solid #ddd;padding-bottom:.2em;margin-top:1.6em}nav a{margin-right:.6em;font-size:13px}
.small{font-size:12px;color:#555}
"""


def _status_class(status: str) -> str:
    return {"pass": "pass", "within budget": "pass", "known gap": "gap", "fail": "fail", "error": "error",
            "unexpected pass": "unexpected", "over budget": "gap"}.get(status, "")


def _table(header: Sequence[str], rows: Sequence[Sequence], numeric: Sequence[int] = (),
           status_column: int | None = None) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr></thead><tbody>"]
    for r in rows:
        cells = []
        for i, cell in enumerate(r):
            if isinstance(cell, tuple):  # pre-escaped HTML
                text = cell[0]
            else:
                text = html.escape(str(cell))
            attrs = []
            if i in numeric:
                attrs.append('class="num"')
            if status_column is not None and i == status_column:
                attrs.append(f'class="{_status_class(str(cell))}"')
            cells.append(f"<td {' '.join(attrs)}>{text}</td>" if attrs else f"<td>{text}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


def _image(path: Path, alt: str) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return (f'<figure><img alt="{html.escape(alt)}" data-artifact="{html.escape(alt)}" '
            f'src="data:image/png;base64,{data}"><figcaption>{html.escape(alt)}</figcaption></figure>')


def to_html(results: Sequence[SceneResult], fidelity: str, out_dir: Path, *, strict: bool = False,
            strict_time: bool = False, not_run: Sequence[str] = (), points: Sequence[dict] = ()) -> str:
    """A self-contained page (inline CSS, figures as data URIs, no script): opens offline in any browser."""
    out_dir = Path(out_dir)
    statuses = [r.status(strict=strict, strict_time=strict_time) for r in results]
    counts = {k: statuses.count(k) for k in ("pass", "known gap", "fail", "error")}
    ok = counts["fail"] == 0 and counts["error"] == 0 and not not_run
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             "<title>ballbench validation report</title>", f"<style>{_CSS}</style></head><body>",
             "<h1>ballbench validation report</h1>",
             f'<div class="banner {"ok" if ok else "bad"}"><b>{count(len(results), "scene")}</b>: '
             f'{counts["pass"]} passed, '
             f'{counts["known gap"]} passed with known gaps, {counts["fail"]} failed, {counts["error"]} raised. '
             f'Fidelity <code>{html.escape(fidelity)}</code>'
             f'{", --strict" if strict else ""}{", --strict-time" if strict_time else ""}.</div>']
    if not_run:
        parts.append(f'<div class="banner warn"><b>Partial report</b>: interrupted; not run: '
                     f'{html.escape(", ".join(not_run))}</div>')
    unexpected = [(r, o) for r in results for o in r.outputs if o.status == "unexpected pass"]
    if unexpected:
        parts.append('<h2 id="unexpected" class="unexpected">Unexpected passes: declared known gaps that now pass'
                     '</h2><p>Remove the known-gap declaration of each; the run fails until then.</p>')
        parts.append(_table(("scene", "check", "value", "reference"),
                            [(r.name, o.quantity, row(o).value, row(o).reference) for r, o in unexpected]))
    parts.append("<nav>" + "".join(f'<a href="#{html.escape(r.name)}">{html.escape(r.name)}</a>' for r in results)
                 + "</nav>")
    parts.append('<h2 id="summary">Summary</h2><p class="small">Errors are relative: |value - reference| / '
                 "max(|reference|, scale) (for a bound only the violating side counts); <i>error / tol</i> is that "
                 "error as a multiple of the check's tolerance (1 = at tolerance). Engineering units here; "
                 "results.json and results.csv stay SI.</p>")
    parts.append(_table(("scene", "kind", "status", "checks", "worst error / tol", "wall time", "budget"), [
        ((f'<a href="#{html.escape(r.name)}">{html.escape(r.name)}</a>',), r.kind, s,
         len([o for o in r.outputs if o.kind == "accuracy"]), worst_ratio_text(r.outputs),
         fmt_time(r.wall_time_s), _scene_budget_text(r)) for r, s in zip(results, statuses)],
        numeric=(3, 4, 5), status_column=2))
    gaps = [(r, o) for r in results for o in r.outputs if o.known_gap is not None]
    parts.append('<h2 id="known-gaps">Known gaps</h2>')
    if gaps:
        parts.append("<p>Published numbers this project does not reproduce, declared with reason and evidence. "
                     "Checked and reported like any other check; " + (
                         "this <code>--strict</code> run counts them as failures.</p>" if strict else
                         "they do not fail the run (<code>--strict</code> makes them fail).</p>"))
        parts.append(_table(("scene", "check", "value", "published", "status", "reason", "evidence"),
                            known_gap_rows(gaps), status_column=4))
    else:
        parts.append("<p>None in this run.</p>")
    parts.append('<h2 id="budgets">Budgets</h2><p class="small">Reported; they decide pass/fail only with '
                 "<code>--strict-time</code>.</p>")
    parts.append('<p class="small">Every scene\'s wall time and budget stand in the summary; here the model '
                 "budgets and the scenes over their budget.</p>")
    budget_rows = [(r.name, "scene wall time", fmt_time(r.wall_time_s), fmt_time(r.budget_s), "over budget")
                   for r in results if r.wall_time_s > r.budget_s]
    for r in results:
        for o in r.outputs_with("within budget") + r.outputs_with("over budget"):
            rr = row(o)
            budget_rows.append((r.name, o.quantity, rr.value_with_unit, rr.reference_with_unit, o.status))
    parts.append(_table(("scene", "what", "measured", "budget", "result"), budget_rows, numeric=(2, 3),
                        status_column=4) if budget_rows else f"<p>{NO_BUDGET_ROWS}</p>")
    if points:
        parts.append('<h2 id="error-vs-time">Which model for an error budget</h2>'
                     "<p>Each point is one (scene, model): its worst error as a multiple of its tolerance at the "
                     "run time of one evaluation; the right panel draws each model family's front.</p>")
        parts.append(_table(("family", "points", "time of one evaluation", "median error / tol", "worst error / tol",
                             "models"), family_table(points), numeric=(1, 3, 4)))
        comparisons = same_scene_comparisons(points)
        if comparisons:
            parts.append("<p>Scenes where models of different families answer the same question:</p>")
            parts.append(_table(("scene", "family", "model", "one evaluation", "worst error / tol"), comparisons,
                                numeric=(3, 4)))
        if (out_dir / "error_vs_time.png").exists():
            parts.append(_image(out_dir / "error_vs_time.png", "error_vs_time.png"))
    for r, s in zip(results, statuses):
        parts.append(f'<section id="{html.escape(r.name)}" data-scene="{html.escape(r.name)}">'
                     f"<h2>{html.escape(r.name)}</h2><p>{html.escape(r.description)}</p>"
                     f'<p>Kind {html.escape(r.kind)}; status <span class="{_status_class(s)}">{status_word(s)}'
                     f"</span>; wall time {fmt_time(r.wall_time_s)} (budget {_scene_budget_text(r)}).</p>")
        if r.error:
            parts.append(f'<p class="error">Error: <code>{html.escape(r.error)}</code></p>')
        for model, t, outputs in model_runs(r):
            parts.append(f"<p><b>{html.escape(model)}</b>, one evaluation {fmt_time(t)}:</p>")
            rows = [row(o) for o in outputs]
            parts.append(_table(("quantity", "value", "reference", "unit", "error", "tolerance", "error / tol",
                                 "status", "source"),
                                [(x.quantity, x.value, x.reference, x.unit or "-", x.error, x.tolerance, x.ratio,
                                  x.status, x.source) for x in rows], numeric=(1, 2, 4, 5, 6), status_column=7))
            notes = [f"{x.quantity}: {x.note}" for x in rows if x.note]
            notes += [f"{o.quantity}: known gap: {o.known_gap.reason} Evidence: {o.known_gap.evidence}"
                      for o in outputs if o.known_gap is not None]
            if notes:
                parts.append('<ul class="small">' + "".join(f"<li>{html.escape(n)}</li>" for n in notes) + "</ul>")
        for note in r.notes:
            parts.append(f"<blockquote>{html.escape(note)}</blockquote>")
        files = []
        for artifact in r.artifacts:
            path = out_dir / artifact
            if artifact.endswith(".png") and path.exists():
                parts.append(_image(path, artifact))
            else:
                files.append(f'<a href="{html.escape(artifact)}">{html.escape(artifact)}</a>')
        if files:
            parts.append(f'<p class="small">Files: {", ".join(files)}</p>')
        parts.append("</section>")
    parts.append("</body></html>")
    return "\n".join(parts)


# ----------------------------------------------------------------------------------------------- JUnit
def to_junit(results: Sequence[SceneResult], *, strict: bool = False, strict_time: bool = False,
             not_run: Sequence[str] = ()) -> bytes:
    """JUnit XML: one test case per scene (classname ``ballbench.<kind>``); known gaps are skipped tests."""
    statuses = [r.status(strict=strict, strict_time=strict_time) for r in results]
    suite = ET.Element("testsuite", name="ballbench", tests=str(len(results) + len(not_run)),
                       failures=str(statuses.count("fail")), errors=str(statuses.count("error")),
                       skipped=str(statuses.count("known gap") + len(not_run)),
                       time=f"{sum(r.wall_time_s for r in results):.3f}")
    for r, s in zip(results, statuses):
        case = ET.SubElement(suite, "testcase", classname=f"ballbench.{r.kind}", name=r.name,
                             time=f"{r.wall_time_s:.3f}")
        lines = failure_lines(r, strict=strict, strict_time=strict_time, limit=50)
        if s == "error":
            ET.SubElement(case, "error", message=r.error or "no checked output").text = r.error
        elif s == "fail":
            ET.SubElement(case, "failure", message=(lines[0].strip() if lines else "failed")).text = "\n".join(lines)
        elif s == "known gap":
            gaps = r.outputs_with("known gap")
            ET.SubElement(case, "skipped", message="known gap: " + "; ".join(
                f"{o.quantity}: {o.known_gap.reason}" for o in gaps))
        budget = f"wall time {fmt_time(r.wall_time_s)}, budget {_scene_budget_text(r)}"
        checks = [f"{check_line(o)}: {o.status}" for o in r.outputs]
        ET.SubElement(case, "system-out").text = "\n".join([budget, *checks])
    for name in not_run:
        case = ET.SubElement(suite, "testcase", classname="ballbench", name=name, time="0")
        ET.SubElement(case, "skipped", message="not run: the run was interrupted")
    return ET.tostring(suite, encoding="utf-8", xml_declaration=True)


# ----------------------------------------------------------------------------------------------- re-render
def results_from_json(data: dict) -> list[SceneResult]:
    """Scene results back from ``results.json`` data (to re-render a report without running the scenes)."""
    from ballbench.validation.scene import KnownGap

    fields = set(Output.__dataclass_fields__) - {"known_gap"}
    results = []
    for s in data["scenes"]:
        outputs = []
        for o in s["outputs"]:
            values = {k: (_float(v) if k in ("value", "reference", "rel_error", "tolerance", "time_s", "scale")
                          else v) for k, v in o.items() if k in fields}
            gap = KnownGap(o["known_gap_reason"], o["known_gap_evidence"]) if o.get("known_gap_reason") else None
            outputs.append(Output(**values, known_gap=gap))
        results.append(SceneResult(s["name"], s["description"], data["fidelity"], tuple(outputs),
                                   tuple(s["artifacts"]), tuple(s["notes"]), s["wall_time_s"], s["error"],
                                   _float(s["budget_s"]), s["kind"], s["interrupted"]))
    return results


# ----------------------------------------------------------------------------------------------- all
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
        "png": out_dir / "error_vs_time.png",
        "points": out_dir / "error_vs_time.csv",
    }
    options = dict(strict=strict, strict_time=strict_time, not_run=not_run)
    data = to_json(results, fidelity, **options)
    paths["json"].write_text(json.dumps(data, indent=2))
    write_csv(results, paths["csv"])
    points = plot_error_vs_time(data, paths["png"], out_dir) if results else []
    if not results:
        paths.pop("png")
        paths.pop("points")
    paths["markdown"].write_text(to_markdown(results, fidelity, points=points, **options))
    paths["html"].write_text(to_html(results, fidelity, out_dir, points=points, **options))
    if junit is not None:
        Path(junit).write_bytes(to_junit(results, **options))
        paths["junit"] = Path(junit)
    return paths
