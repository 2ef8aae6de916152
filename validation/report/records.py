"""The run as data: scene statuses and counts (:class:`Tally`), ``results.json``, ``results.csv``, and back.

JSON and CSV carry SI values; the schema is in the package docstring
(``validation/report/__init__.py``).
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from ballbench.validation.scene import PASSING, KnownGap, Output, SceneResult

CSV_FIELDS = ("scene", "model", "quantity", "unit", "value", "reference", "source", "rel_error", "tolerance",
              "passed", "status", "time_s", "relation", "kind", "scale", "note", "why", "known_gap_reason",
              "known_gap_evidence", "family", "level")
SCENE_STATUSES = ("pass", "known gap", "findings", "not applicable", "inconclusive", "fail", "error")
_NUMBERS = ("value", "reference", "rel_error", "tolerance", "time_s", "scale")


@dataclass(frozen=True)
class Tally:
    """Every scene's status under the run's options, and their counts: computed once, read by every output."""

    statuses: tuple[str, ...]
    counts: dict
    strict: bool = False
    strict_time: bool = False
    not_run: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        """No scene failed or raised and none was left out by an interruption."""
        return all(s in PASSING for s in self.statuses) and not self.not_run


def tally(results: Sequence[SceneResult], *, strict: bool = False, strict_time: bool = False,
          not_run: Sequence[str] = ()) -> Tally:
    """The :class:`Tally` of ``results`` (``strict``: findings, known gaps, inconclusive scenes and scenes that do
    not apply fail;
    ``strict_time``: budget overruns fail)."""
    statuses = tuple(r.status(strict=strict, strict_time=strict_time) for r in results)
    return Tally(statuses, {k: statuses.count(k) for k in SCENE_STATUSES}, strict, strict_time, tuple(not_run))


def json_number(x):
    """A float that JSON can hold: ``inf`` and ``nan`` as the strings ``"inf"``, ``"nan"``."""
    return x if not isinstance(x, float) or math.isfinite(x) else str(x)


def json_float(x) -> float:
    """A number of ``results.json`` back as a float (``"inf"``, ``"Infinity"`` and ``"nan"`` included)."""
    return float(x) if not isinstance(x, str) else float(x.replace("Infinity", "inf"))


def to_json(results: Sequence[SceneResult], fidelity: str, *, strict: bool = False, strict_time: bool = False,
            not_run: Sequence[str] = (), counted: Tally | None = None) -> dict:
    """The ``results.json`` document (``counted``: the run's :class:`Tally`, computed here when not given)."""
    counted = counted or tally(results, strict=strict, strict_time=strict_time, not_run=not_run)
    return {
        "fidelity": fidelity,
        "passed": counted.passed,
        "strict": counted.strict,
        "strict_time": counted.strict_time,
        "complete": not counted.not_run,
        "not_run": list(counted.not_run),
        "counts": counted.counts,
        "scenes": [
            {
                "name": r.name,
                "description": r.description,
                "kind": r.kind,
                "status": status,
                "passed": status in PASSING,
                "error": r.error,
                "not_applicable": r.not_applicable,
                "inconclusive": r.inconclusive,
                "wall_time_s": r.wall_time_s,
                "budget_s": json_number(r.budget_s),
                "over_budget": r.over_budget,
                "interrupted": r.interrupted,
                "peak_memory_gb": r.peak_memory_gb,
                "scene_peak_memory_gb": r.scene_peak_memory_gb,
                "declared_memory_gb": r.declared_memory_gb,
                "over_memory": r.over_memory,
                "artifacts": list(r.artifacts),
                "notes": list(r.notes),
                "outputs": [{k: json_number(v) for k, v in o.as_dict().items()} for o in r.outputs],
                **({"tables": [{"title": t, "header": list(h), "rows": [list(x) for x in rows]}
                               for t, h, rows in r.tables]} if r.tables else {}),
            }
            for r, status in zip(results, counted.statuses)
        ],
    }


def write_csv(results: Sequence[SceneResult], path: Path) -> None:
    """``results.csv``: one row per check (:data:`CSV_FIELDS`), SI units."""
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for r in results:
            for o in r.outputs:
                data = o.as_dict()
                data["scene"] = r.name
                writer.writerow({k: data[k] for k in CSV_FIELDS})


def results_from_json(data: dict) -> list[SceneResult]:
    """Scene results back from ``results.json`` data (to re-render a report without running the scenes).

    Keys an older version did not write (``family``, ``level``, ``peak_memory_gb``, ``not_applicable``,
    ``inconclusive``, ``scene_peak_memory_gb``, ``declared_memory_gb``) take their defaults (0: not measured); a
    finding check that missed is known by its status (``outside accuracy``)."""
    fields = set(Output.__dataclass_fields__) - {"known_gap", "finding"}
    results = []
    for s in data["scenes"]:
        outputs = []
        for o in s["outputs"]:
            values = {k: (json_float(v) if k in _NUMBERS else v) for k, v in o.items() if k in fields}
            gap = KnownGap(o["known_gap_reason"], o["known_gap_evidence"]) if o.get("known_gap_reason") else None
            outputs.append(Output(**values, known_gap=gap, finding=o.get("status") == "outside accuracy"))
        results.append(SceneResult(s["name"], s["description"], data["fidelity"], tuple(outputs),
                                   tuple(s["artifacts"]), tuple(s["notes"]), s["wall_time_s"], s["error"],
                                   json_float(s["budget_s"]), s["kind"], s["interrupted"],
                                   tuple((t["title"], tuple(t["header"]), tuple(tuple(x) for x in t["rows"]))
                                         for t in s.get("tables", ())),
                                   s.get("peak_memory_gb", 0.0), s.get("not_applicable", ""),
                                   s.get("inconclusive", ""), s.get("scene_peak_memory_gb", 0.0),
                                   s.get("declared_memory_gb", 0.0)))
    return results
