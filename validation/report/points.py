"""Accuracy against cost as data: the points of ``error_vs_time.png`` and each family's front.

A point is one (scene, model family, model, fidelity level) of ``results.json``:
the model's worst error there as a multiple of its tolerance, at the run time
of one evaluation.  Points are plain dicts (``scene``, ``model``, ``family``,
``level``, ``time_s``, ``error``, ``status``, ``scene_index``) so that the
figure, the tables and ``error_vs_time.csv`` read the same record.
"""
from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Iterable, Sequence

from ballbench.validation.report.records import json_float
from ballbench.validation.report.rows import UNDECLARED
from ballbench.validation.scene import FAMILIES

FLOOR = 1e-8     # error / tolerance drawn at this floor when it is exactly 0 (or below it)
CEILING = 1e4    # ... and at this ceiling when infinite (a missed bound of tolerance 0, a non-finite value)
# the worst status of a point's checks wins
STATUS_ORDER = ("pass", "known gap", "outside accuracy", "unexpected pass", "fail")


def family_order(families: Iterable[str]) -> list[str]:
    """``families`` in the order of :data:`FAMILIES`, then ``undeclared``, then any other name sorted."""
    known = [*FAMILIES, UNDECLARED]
    present = set(families)
    return [f for f in known if f in present] + sorted(present - set(known))


def ratio(rel_error: float, tolerance: float) -> float:
    """Error / tolerance of a ``results.json`` check; a tolerance of 0 gives 0 when met, else inf."""
    if tolerance > 0:
        return rel_error / tolerance
    return 0.0 if rel_error == 0 else math.inf


def plotted(error: float) -> float:
    """Where an error / tolerance is drawn: clipped to the marked floor and ceiling."""
    return min(max(error, FLOOR), CEILING)


def error_points(data: dict) -> list[dict]:
    """One point per (scene, family, model, level) of ``results.json`` data, as the figure draws it.

    ``error`` is the model's worst error as a multiple of its tolerance in
    that scene at that level; ``time_s`` the run time of one evaluation of
    the model: the evaluation that produced that worst error (the longest one
    on a tie); budget rows are not accuracy and are left out, and so are
    checks timed at 0 s (consistency checks of a paper's data, no model run).
    ``status`` is the worst status of the checks (fail > unexpected pass >
    outside accuracy > known gap > pass).  A check without a declared family is ``undeclared``.
    """
    points = []
    for index, s in enumerate(data["scenes"]):
        groups: dict[tuple[str, str, str], list[dict]] = {}
        for o in s["outputs"]:
            if o.get("kind", "accuracy") == "accuracy" and json_float(o["time_s"]) > 0:
                key = (o.get("family") or UNDECLARED, o["model"], o.get("level", ""))
                groups.setdefault(key, []).append(o)
        for (family, model, level), outputs in groups.items():
            ratios = [ratio(json_float(o["rel_error"]), json_float(o["tolerance"])) for o in outputs]
            worst = max(ratios)
            time_s = max(json_float(o["time_s"]) for o, r in zip(outputs, ratios) if r == worst)
            status = max((o["status"] for o in outputs), key=STATUS_ORDER.index)
            points.append({"scene": s["name"], "model": model, "family": family, "level": level, "time_s": time_s,
                           "error": worst, "status": status, "scene_index": index})
    return points


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
    errors = [plotted(p["error"]) for p in front]
    longest = max(p["time_s"] for p in points)
    if longest > times[-1] or len(front) == 1:
        times.append(max(longest, times[-1] * 1.5))  # a lone point at the longest time: a short stub to the right
        errors.append(errors[-1])
    return times, errors


def model_lines(points: Sequence[dict]) -> list[list[dict]]:
    """The points of each (scene, model) sorted by run time: a line through the model's fidelity levels."""
    lines: dict[tuple[str, str, str], list[dict]] = {}
    for p in points:
        lines.setdefault((p["scene"], p["family"], p["model"]), []).append(p)
    return [sorted(members, key=lambda p: p["time_s"]) for members in lines.values()]


def mesh_level_points(data: dict, out_dir: Path) -> list[dict]:
    """Every mesh level of the scenes that saved a ``convergence.csv`` (FE scenes), as accuracy-cost points.

    A level's error is ``max_q |err_q| / tol_q`` over the quantities ``q``
    that the scene checked (columns ``err_<q>``; tolerances from its checks),
    its time the level's ``wall_s``, its family that of those checks; at the
    default fidelity the one level is the checked one, at ``--fine`` the
    convergence study gives a line.
    """
    levels = []
    for s in data["scenes"]:
        path = next((a for a in s["artifacts"] if a.endswith("convergence.csv")), None)
        if path is None:
            continue
        checks = [o for o in s["outputs"] if o.get("kind") == "accuracy"]
        tolerance = {o["quantity"]: json_float(o["tolerance"]) for o in checks}
        try:
            with open(Path(out_dir) / path, newline="") as handle:
                rows = list(csv.DictReader(handle))
        except OSError:
            continue
        columns = set(rows[0]) if rows else set()
        family = next((o.get("family") or UNDECLARED for o in checks if f"err_{o['quantity']}" in columns),
                      UNDECLARED)
        for r in rows:
            ratios = [abs(float(r[f"err_{q}"])) / tol for q, tol in tolerance.items() if f"err_{q}" in r and tol > 0]
            if ratios and "wall_s" in r:
                levels.append({"scene": s["name"], "family": family, "time_s": float(r["wall_s"]),
                               "error": max(ratios), "level": f"n = {r.get('n', '?')}, growth {r.get('growth', '?')}"})
    return levels


POINT_FIELDS = ("number", "scene", "model", "family", "level", "time_s", "error_over_tolerance", "plotted_at",
                "status")


def write_points(points: Sequence[dict], path: Path) -> None:
    """``error_vs_time.csv``: the plotted points (numbered in the order of ``results.json``)."""
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=POINT_FIELDS)
        writer.writeheader()
        for number, p in enumerate(points, start=1):
            writer.writerow({"number": number, "scene": p["scene"], "model": p["model"], "family": p["family"],
                             "level": p["level"], "time_s": repr(p["time_s"]),
                             "error_over_tolerance": repr(p["error"]), "plotted_at": repr(plotted(p["error"])),
                             "status": p["status"]})
