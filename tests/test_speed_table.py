"""benchmarks/speed_table.py, the writer of docs/speed.md's table: correctness only (no timing; the speed targets
live in benchmarks/).  The page keeps its text outside the markers, a figure's target and clock are checked when it
is recorded, and a run's figures are compared with the previous run's by key."""
from __future__ import annotations

import importlib.util
import json
from types import SimpleNamespace

import pytest

from tests import paths

_SPEC = importlib.util.spec_from_file_location("speed_table", paths.ROOT / "benchmarks" / "speed_table.py")
speed_table = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(speed_table)
START, END = speed_table.START, speed_table.END


def _row(key="bearing.2", value=0.05, target="<= 0.2", unit="ms", load=1.0):
    return {"key": key, "label": f"figure {key}", "value": value, "unit": unit, "target": target, "clock": "CPU",
            "baseline": "", "load": load, "test": "test_bench_x.py::test_y"}


def _run(*rows, commit="abc1234"):
    meta = {"date": "2026-12-07 04:00 UTC", "commit": commit, "machine": "a CPU, 2 cores, shared", "tests": 1,
            "seconds": 1.0, "load_start": "1.0, 1.0, 1.0", "load_end": "1.0, 1.0, 1.0", "versions": "Python 3"}
    return {"meta": meta, "figures": list(rows)}


def test_the_table_replaces_only_what_lies_between_the_markers():
    page = f"# Speed\n\nbefore\n{START}\nold table\n| a |\n{END}\nafter, with the page's anchors\n"
    written = speed_table.replace_between(page, "| new |\n")
    assert written == f"# Speed\n\nbefore\n{START}\n| new |\n{END}\nafter, with the page's anchors\n"
    assert speed_table.replace_between(written, "| new |") == written  # a second run changes nothing


@pytest.mark.parametrize("page", ["no markers\n", f"{START}\nonly the start\n", f"{END}\n{START}\n",
                                  f"{START}\n{END}\n{START}\n{END}\n"])
def test_a_page_without_one_pair_of_markers_is_refused(page):
    with pytest.raises(ValueError, match="once"):
        speed_table.replace_between(page, "| table |")


def test_the_rendered_table_lies_between_the_markers_of_the_page():
    page = speed_table.PAGE.read_text()
    table = speed_table.render(_run(_row()))
    written = speed_table.replace_between(page, table)
    head, tail = page.split(START)[0], page.split(END)[1]
    assert written.startswith(head + START) and written.endswith(END + tail)
    assert "| figure bearing.2 | 0.0500 ms | CPU | <= 0.2 ms | met |" in written


@pytest.mark.parametrize("target, value, verdict", [("<= 0.2", 0.2, "met"), ("<= 0.2", 0.21, "short"),
                                                     ("< 500", 500.0, "short"), (">= 2e4", 30801.0, "met"),
                                                     (">= 1e5", 9.9e4, "short"), ("stated", 3.0, ""), (None, 3.0, "")])
def test_a_figure_is_judged_against_its_target(target, value, verdict):
    assert speed_table.verdict(_row(value=value, target=target)) == verdict


def test_a_figure_is_recorded_with_its_target_clock_and_load():
    recorded = []
    speed_table.figure(lambda name, value: recorded.append((name, value)), "screw.whole", "whole screw", 0.73, "s",
                       target="<= 0.5", clock="CPU", baseline="numpy path 4.1 s")
    (name, value), = recorded
    row = json.loads(value)
    assert name == speed_table.PREFIX + "screw.whole"
    assert {k: row[k] for k in ("key", "value", "unit", "target", "clock", "baseline")} == {
        "key": "screw.whole", "value": 0.73, "unit": "s", "target": "<= 0.5", "clock": "CPU",
        "baseline": "numpy path 4.1 s"}
    assert row["load"] >= 0


@pytest.mark.parametrize("target, clock", [("0.5", "CPU"), ("<= half a second", "CPU"), ("=< 0.5", "CPU"),
                                           ("<= 0.5", "process")])
def test_a_figure_with_an_unreadable_target_or_clock_is_refused(target, clock):
    with pytest.raises(ValueError, match="target|clock"):
        speed_table.figure(lambda name, value: None, "k", "label", 1.0, "s", target=target, clock=clock)


def test_the_collector_takes_the_figures_of_the_call_and_the_worst_outcome():
    collector = speed_table.Collector()
    properties = [(speed_table.PREFIX + "k", json.dumps(_row("k"))), ("other", "1")]
    for when, outcome in (("setup", "passed"), ("call", "failed"), ("teardown", "passed")):
        collector.pytest_runtest_logreport(SimpleNamespace(nodeid="benchmarks/test_a.py::test_b", when=when,
                                                           outcome=outcome, user_properties=properties))
    assert [row["key"] for row in collector.figures] == ["k"]  # once, not once per phase
    assert collector.figures[0]["test"] == "test_a.py::test_b"
    assert collector.outcomes == {"benchmarks/test_a.py::test_b": "failed"}


def test_the_figures_are_printed_beside_the_previous_run_by_key():
    previous = _run(_row("bearing.2", 0.085, load=1.4), _row("gone", 1.0), commit="old1234")
    now = _run(_row("bearing.2", 0.0425, load=5.7), _row("new", 2.0, target=None))
    lines = speed_table.beside(previous, now).splitlines()
    assert "| figure bearing.2 | 0.0850 ms | 1.4 | 0.0425 ms | 5.7 | 0.50 | <= 0.2 ms | met |" in lines
    assert "| figure new |  |  | 2.00 ms | 1.0 |  |  |  |" in lines
    assert lines[-1] == "in the previous run only: gone"
    assert "figure bearing.2 |  |  | 0.0425 ms" in speed_table.beside(None, now)


@pytest.mark.parametrize("value, text", [(0.0853, "0.0853"), (2.0, "2.00"), (99.96, "100"), (30801.0, "30,800"),
                                         (1.51e7, "1.51e7"), (1.2e-4, "1.20e-4"), (0.0, "0")])
def test_numbers_keep_three_significant_digits(value, text):
    assert speed_table.number(value) == text
