"""The current speed figures as one table, written into docs/speed.md by the benchmarks that measure them.

Each benchmark of :data:`SUBSET` hands its figures over with :func:`figure` (pytest's ``record_property``: the
figure travels in the test's report, so a benchmark run by hand prints as before and records nothing anywhere).
This script runs the subset in one pytest session (a few minutes on the shared 2-core machine once numba's disk
cache holds the kernels; the first run of a checkout compiles them), reads the figures from the reports, and

* prints them beside the previous run's figures (:data:`DATA`), each with its target and the load average at the
  moment it was taken;
* writes the table between :data:`START` and :data:`END` in docs/speed.md (the rest of the page is left as it is)
  and the figures to :data:`DATA`, the previous figures of the next run.

A benchmark of the subset that fails, is skipped or records nothing leaves the page and the data as they were
(exit status 1): the table is always one complete run at one commit.

Run (repository root, the project's venv):
    python benchmarks/speed_table.py             # run, print beside the previous figures, write the table
    python benchmarks/speed_table.py --dry-run   # run and print only
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "speed.md"
DATA = ROOT / "docs" / "speed_table.json"
START, END = "<!-- speed-table:start -->", "<!-- speed-table:end -->"
PREFIX = "speed-figure:"  # the name of a figure's record_property, followed by its key
# the benchmarks whose figures make the table, in the table's order (pytest node ids, relative to the root)
SUBSET = (
    "benchmarks/test_bench_kernels.py::test_import_is_light",
    "benchmarks/test_bench_kernels.py::test_one_case_solves",
    "benchmarks/test_bench_kernels.py::test_monte_carlo",
    "benchmarks/test_bench_screw.py::test_two_ball_b2b_solve",
    "benchmarks/test_bench_screw.py::test_whole_screw_simulation",
    "benchmarks/test_bench_screw.py::test_ring_pieces",
    "benchmarks/test_bench_carriage.py::test_four_row_carriage_of_100_balls",
    "benchmarks/test_bench_carriage.py::test_friction_over_one_pitch_of_a_gothic_carriage",
    "benchmarks/test_bench_rolling.py::test_bench_exact_half_space",
    "benchmarks/test_bench_rolling.py::test_bench_fastsim_throughput",
    "benchmarks/test_bench_hertz.py::test_hertz_contacts_per_second",
    "benchmarks/test_bench_fourpoint.py::test_fourpoint_solve_per_second",
    "benchmarks/test_bench_b2b_analytical.py::test_two_ball_cases_per_second",
    "benchmarks/test_bench_screw_kinematics.py::test_contact_points_per_second",
    "benchmarks/test_bench_ellipse_friction.py::test_map_build_cold",
    "benchmarks/test_bench_halfspace.py::test_bench_bem_hertz",
    "benchmarks/test_bench_ehl.py::test_bench_ehl_point",
)
TARGET = re.compile(r"^(<=|>=|<|>) ?([0-9][0-9.e+-]*)$")
CLOCKS = ("CPU", "wall")


def parse_target(text: str | None) -> tuple[str, float] | None:
    """``"<= 0.2"`` -> ``("<=", 0.2)``; None (no bound: the figure is stated) for None or ``"stated"``."""
    if text is None or text == "stated":
        return None
    match = TARGET.match(text)
    if match is None:
        raise ValueError(f"target must read like '<= 0.2', '>= 2e4' or 'stated', got {text!r}")
    return match.group(1), float(match.group(2))


def figure(record_property, key: str, label: str, value: float, unit: str, *, target: str | None = None,
           clock: str = "CPU", baseline: str = "") -> None:
    """Hand one figure to the speed table: ``key`` names it from run to run, ``label`` says what was measured,
    ``value`` in ``unit`` on the ``clock`` ("CPU": ``time.process_time``, or "wall"), ``target`` in the same unit
    (``"<= 0.2"``; None where none is set), ``baseline`` what the code before gave in the same run ("numpy path
    2.03 ms").  ``record_property`` is pytest's fixture of that name; the load average is taken now."""
    parse_target(target)
    if clock not in CLOCKS:
        raise ValueError(f"clock must be one of {CLOCKS}, got {clock!r}")
    record_property(PREFIX + key, json.dumps({
        "key": key, "label": label, "value": float(value), "unit": unit, "target": target, "clock": clock,
        "baseline": baseline, "load": round(os.getloadavg()[0], 2)}))


def verdict(row: dict) -> str:
    """"met", "short" or "" (no target) for a figure."""
    target = parse_target(row["target"])
    if target is None:
        return ""
    operator, bound = target
    value = row["value"]
    met = {"<=": value <= bound, "<": value < bound, ">=": value >= bound, ">": value > bound}[operator]
    return "met" if met else "short"


def number(value: float) -> str:
    """Three significant digits: ``0.0853``, ``30,800``, large and small ones as ``1.23e6``."""
    rounded = float(f"{value:.3g}")
    if rounded == 0:
        return "0"
    if not 1e-3 <= abs(rounded) < 1e5:
        mantissa, exponent = f"{rounded:.2e}".split("e")
        return f"{mantissa}e{int(exponent)}"
    return f"{rounded:,.{max(0, 2 - math.floor(math.log10(abs(rounded))))}f}"


def quantity(row: dict) -> str:
    return f"{number(row['value'])} {row['unit']}"


def bound(row: dict) -> str:
    if row["target"] in (None, "stated"):
        return row["target"] or ""
    return f"{row['target']} {row['unit']}"


def render(run: dict) -> str:
    """The table of one run (``{"meta": ..., "figures": [...]}``) as Markdown: a sentence on the run, the table."""
    meta = run["meta"]
    lines = [
        f"Run {meta['date']} at commit `{meta['commit']}` by `python benchmarks/speed_table.py` ({meta['tests']} "
        f"benchmarks, {meta['seconds']:.0f} s); {meta['machine']}; load average {meta['load_start']} at the start, "
        f"{meta['load_end']} at the end (1, 5, 15 min); {meta['versions']}.",
        "",
        "| figure | now | clock | target | | the code before, same run | load | benchmark |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for row in run["figures"]:
        lines.append(f"| {row['label']} | {quantity(row)} | {row['clock']} | {bound(row)} | {verdict(row)} | "
                     f"{row['baseline']} | {row['load']:.1f} | `{row['test']}` |")
    return "\n".join(lines) + "\n"


def beside(previous: dict | None, run: dict) -> str:
    """The figures of ``run`` beside those of ``previous`` (same key), as a Markdown table for the terminal."""
    old = {row["key"]: row for row in (previous or {}).get("figures", [])}
    when = (f"{previous['meta']['date']}, `{previous['meta']['commit']}`" if previous else "none")
    lines = [f"previous: {when}; now: {run['meta']['date']}, `{run['meta']['commit']}`", "",
             "| figure | previous | load | now | load | now / previous | target | |",
             "|---|---|---|---|---|---|---|---|"]
    for row in run["figures"]:
        before = old.get(row["key"])
        if before is None or before["unit"] != row["unit"]:
            then, load, ratio = "", "", ""
        else:
            then, load = quantity(before), f"{before['load']:.1f}"
            ratio = f"{row['value'] / before['value']:.2f}" if before["value"] else ""
        lines.append(f"| {row['label']} | {then} | {load} | {quantity(row)} | {row['load']:.1f} | {ratio} | "
                     f"{bound(row)} | {verdict(row)} |")
    gone = [key for key in old if key not in {row["key"] for row in run["figures"]}]
    if gone:
        lines += ["", "in the previous run only: " + ", ".join(gone)]
    return "\n".join(lines) + "\n"


def replace_between(text: str, block: str) -> str:
    """``text`` with what lies between :data:`START` and :data:`END` replaced by ``block``; each marker must occur
    once, the start before the end."""
    if text.count(START) != 1 or text.count(END) != 1 or text.index(START) > text.index(END):
        raise ValueError(f"the page must hold {START} once and, after it, {END} once")
    head, rest = text.split(START)
    tail = rest.split(END)[1]
    return f"{head}{START}\n{block.strip()}\n{END}{tail}"


class Collector:
    """pytest plugin: the figures of every test's call (:func:`figure`), and each test's worst outcome."""

    def __init__(self):
        self.figures: list[dict] = []
        self.outcomes: dict[str, str] = {}

    def pytest_runtest_logreport(self, report):
        rank = ("passed", "skipped", "failed")
        now = self.outcomes.get(report.nodeid, "passed")
        self.outcomes[report.nodeid] = max(now, report.outcome, key=rank.index)
        if report.when == "call":
            for name, value in report.user_properties:
                if name.startswith(PREFIX):
                    self.figures.append({**json.loads(value), "test": report.nodeid.removeprefix("benchmarks/")})


def _git(*arguments: str) -> str:
    return subprocess.run(["git", "-C", str(ROOT), *arguments], capture_output=True, text=True,
                          check=True).stdout.strip()


def _machine() -> str:
    model = platform.processor() or platform.machine()
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        names = [line.split(":", 1)[1].strip() for line in cpuinfo.read_text().splitlines()
                 if line.startswith("model name")]
        model = names[0] if names else model
    return f"{model}, {os.cpu_count()} cores, shared"


def _versions() -> str:
    from importlib.metadata import PackageNotFoundError, version

    found = [f"Python {platform.python_version()}"]
    for name in ("numpy", "scipy", "numba"):
        try:
            found.append(f"{name} {version(name)}")
        except PackageNotFoundError:
            found.append(f"no {name}")
    return ", ".join(found)


def _load() -> str:
    return ", ".join(f"{value:.1f}" for value in os.getloadavg())


def run_subset(subset=SUBSET) -> tuple[dict, list[str]]:
    """Run the benchmarks of ``subset`` in this process; the run (meta and figures) and what went wrong."""
    import pytest

    commit = _git("rev-parse", "--short", "HEAD")
    if _git("status", "--porcelain", "--untracked-files=no"):
        commit += " + uncommitted changes"
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), "commit": commit,
            "machine": _machine(), "versions": _versions(), "load_start": _load()}
    collector, began = Collector(), time.perf_counter()
    status = pytest.main(["-s", "-p", "no:cacheprovider", *(f"{ROOT}/{test}" for test in subset)], plugins=[collector])
    meta.update(seconds=time.perf_counter() - began, load_end=_load(), tests=len(collector.outcomes))
    problems = [f"{test}: {outcome}" for test, outcome in collector.outcomes.items() if outcome != "passed"]
    recorded = {row["test"] for row in collector.figures}
    problems += [f"{test}: no figure recorded" for test in collector.outcomes
                 if test.removeprefix("benchmarks/") not in recorded and collector.outcomes[test] == "passed"]
    if status != 0 and not problems:
        problems.append(f"pytest exit status {int(status)}")
    return {"meta": meta, "figures": collector.figures}, problems


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--dry-run", action="store_true", help="print the figures, write neither page nor data")
    options = parser.parse_args(argv)
    os.chdir(ROOT)
    previous = json.loads(DATA.read_text()) if DATA.exists() else None
    run, problems = run_subset()
    print("\n" + beside(previous, run))
    if problems:
        print("not written (the table is one complete run):\n  " + "\n  ".join(problems))
        return 1
    if options.dry_run:
        return 0
    PAGE.write_text(replace_between(PAGE.read_text(), render(run)))
    DATA.write_text(json.dumps(run, indent=1) + "\n")
    print(f"written: {PAGE.relative_to(ROOT)} (between its markers), {DATA.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
