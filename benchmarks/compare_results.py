"""Compare two ``results.json`` of ``ballbench validate`` (or of a case file's ladder): every number of every scene's
outputs and tables at a relative tolerance, timings and memory aside.  The evidence of a change that keeps the
results ("the same numbers as the code before", docs/speed.md "Running the benchmarks").

    python benchmarks/compare_results.py OLD/results.json NEW/results.json [--rtol 1e-12] [--subset]

Compared per scene (matched by name): its status and the number of its outputs; per output (matched by model,
quantity, family, level and its place among equals) ``value``, ``reference``, ``rel_error``, ``tolerance``,
``status``; the numbers inside the scene's notes.  ``--subset``: scenes of NEW missing from OLD (or the reverse) are
listed, not counted as differences.  Exit 0 when nothing differs beyond ``--rtol``, 1 otherwise; the differences are
printed, the largest first.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import sys
from pathlib import Path

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
COMPARED = ("value", "reference", "rel_error", "tolerance", "scale")
# a number followed by one of these units measures the run (time, memory), not the model
RUN_UNIT = re.compile(r"\s?(?:s|ms|us|min|h|GB|MB|kB)\b")


def _key(output: dict) -> tuple:
    return (output.get("model"), output.get("quantity"), output.get("family"), output.get("level"))


def _differs(a, b, rtol: float) -> float:
    """The relative difference of two JSON values (0 when equal within ``rtol``, NaN-aware), or inf for a type or
    text change."""
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)):
            return 0.0
        if not (math.isfinite(a) and math.isfinite(b)):
            return math.inf
        scale = max(abs(a), abs(b))
        relative = abs(a - b) / scale
        return relative if relative > rtol else 0.0
    return 0.0 if a == b else math.inf


def _note_numbers(notes: list[str]) -> list[float]:
    """The numbers of a scene's notes but those that measure the run: a number followed by a unit of time or
    memory (``17.2 s``, ``3 ms``, ``1.4 GB``), a rate (``cases/s``, ``it/s``) or inside a sentence about run time."""
    numbers = []
    for note in notes:
        for sentence in re.split(r"(?<=[.;])\s", note):
            if any(word in sentence for word in ("wall", "run time", "seconds", "it/s", "cases/s", "per s")):
                continue
            for match in NUMBER.finditer(sentence):
                if not RUN_UNIT.match(sentence, match.end()):
                    numbers.append(float(match.group()))
    return numbers


def compare(old: dict, new: dict, rtol: float, subset: bool) -> tuple[list[tuple[float, str]], list[str], int]:
    """(differences as (relative size, where), scenes present on one side only, numbers compared)."""
    old_scenes = {s["name"]: s for s in old["scenes"]}
    new_scenes = {s["name"]: s for s in new["scenes"]}
    differences, alone, counted = [], [], 0
    for name in sorted(set(old_scenes) ^ set(new_scenes)):
        side = "old" if name in old_scenes else "new"
        alone.append(f"{name} only in {side}")
        if not subset:
            differences.append((math.inf, f"{name}: only in {side}"))
    for name in sorted(set(old_scenes) & set(new_scenes)):
        a, b = old_scenes[name], new_scenes[name]
        if a["status"] != b["status"]:
            differences.append((math.inf, f"{name}: status {a['status']} -> {b['status']}"))
        seen: dict[tuple, int] = {}
        old_outputs = {}
        for output in a["outputs"]:
            key = _key(output)
            seen[key] = seen.get(key, 0) + 1
            old_outputs[key + (seen[key],)] = output
        seen = {}
        for output in b["outputs"]:
            key = _key(output)
            seen[key] = seen.get(key, 0) + 1
            before = old_outputs.pop(key + (seen[key],), None)
            if before is None:
                differences.append((math.inf, f"{name}: new output {key}"))
                continue
            if output.get("kind") == "budget":
                continue  # a wall-time or throughput budget measures the run
            for field in COMPARED + ("status",):
                counted += 1
                size = _differs(before.get(field), output.get(field), rtol)
                if size:
                    differences.append((size, f"{name}: {key[1]!r} ({key[0]}, {key[2]}, {key[3]!r}) {field}: "
                                              f"{before.get(field)!r} -> {output.get(field)!r}"))
        for key in old_outputs:
            differences.append((math.inf, f"{name}: output gone {key[:4]}"))
        numbers_a, numbers_b = _note_numbers(a.get("notes", [])), _note_numbers(b.get("notes", []))
        if len(numbers_a) != len(numbers_b):
            differences.append((math.inf, f"{name}: the notes hold {len(numbers_a)} -> {len(numbers_b)} numbers"))
        else:
            for k, (x, y) in enumerate(zip(numbers_a, numbers_b)):
                counted += 1
                size = _differs(x, y, rtol)
                if size:
                    differences.append((size, f"{name}: note number {k}: {x!r} -> {y!r}"))
    return sorted(differences, key=lambda d: -d[0]), alone, counted


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--rtol", type=float, default=1e-12)
    parser.add_argument("--subset", action="store_true", help="scenes on one side only are listed, not differences")
    parser.add_argument("--most", type=int, default=40, help="print at most this many differences")
    args = parser.parse_args(argv)
    old, new = (json.loads(path.read_text()) for path in (args.old, args.new))
    differences, alone, counted = compare(old, new, args.rtol, args.subset)
    for line in alone:
        print(f"  {line}")
    for size, where in differences[:args.most]:
        print(f"  {size:.3g}  {where}")
    print(f"{len(differences)} differences at rtol {args.rtol:g} among {counted} numbers of "
          f"{len({s['name'] for s in new['scenes']})} scenes")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
