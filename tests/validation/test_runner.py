"""The validation harness: error convention, guards, known gaps, budgets, report files, CLI exit codes.

Fake scenes (names ``zz-*``) are registered for each test and removed after it,
so the CLI is exercised end to end in seconds without the slow scenes.
"""
from __future__ import annotations

import csv
import html
import json
import math
import os
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

import pytest

from ballbench.validation import cli
from tests.cli_support import one_error_line
from ballbench.validation import scene as scene_module
from ballbench.validation.report import error_points, write_report
from ballbench.validation.runner import run_scene
from ballbench.validation.scene import KnownGap, Scene, relative_error

GAP = KnownGap(reason="the paper's state does not exist in this model", evidence="docs/x.md, section y")


def test_relative_error_conventions():
    assert relative_error(1.01, 1.0) == pytest.approx(0.01)
    assert relative_error(0.2, 0.0, scale=2.0) == pytest.approx(0.1)
    assert relative_error(190.0, 185.2, relation="ge") == 0.0
    assert relative_error(180.0, 185.2, relation="ge") == pytest.approx(5.2 / 185.2)
    assert relative_error(3.0, 2.0, relation="le") == pytest.approx(0.5)
    assert relative_error(float("nan"), 1.0) == math.inf
    with pytest.raises(ValueError, match="scale"):
        relative_error(0.1, 0.0)
    with pytest.raises(ValueError, match="relation"):
        relative_error(1.0, 1.0, relation="approx")


def _scene(function, name="demo", kind="low-order"):
    return Scene(name, "demo scene", function, kind=kind)


def test_checks_pass_and_fail(tmp_path):
    def body(run):
        value, time_s = run.time(lambda: 2.0)
        run.check(model="m", family="analytical", quantity="q", unit="N", value=value, reference=2.0, source="s",
                  tolerance=1e-12, time_s=time_s)
        run.check(model="m", family="analytical", quantity="r", unit="N", value=1.1, reference=1.0, source="s",
                  tolerance=0.05, time_s=time_s)

    result = run_scene(_scene(body), "quick", tmp_path)
    assert [o.status for o in result.outputs] == ["pass", "fail"]
    assert not result.passed and result.status() == "fail"
    assert result.outputs[0].time_s > 0


def test_exception_and_empty_scene_fail(tmp_path):
    def boom(run):
        raise ValueError("conformity must be > 0.5")

    result = run_scene(_scene(boom), "quick", tmp_path)
    assert result.status() == "error" and "conformity" in result.error
    assert "demo/error.txt" in result.artifacts  # the traceback goes to a file, not the terminal
    assert "Traceback" in (tmp_path / "demo" / "error.txt").read_text()
    result = run_scene(_scene(lambda run: None), "quick", tmp_path)
    assert not result.passed and "no checked output" in result.error


@pytest.mark.parametrize("tolerance, scale", [(math.inf, 0.0), (1.0, 0.0), (2.5, 0.0), (0.01, 5.0), (0.01, 1e300)])
def test_guards_reject_checks_that_cannot_fail(tmp_path, tolerance, scale):
    """docs/validation.md: a non-finite or >= 1 tolerance, or a scale above the reference, needs a reason."""
    def body(run, why=""):
        run.check(model="m", family="analytical",
                  quantity="q", unit="1", value=1.0, reference=2.0, source="s", tolerance=tolerance,
                  scale=scale, time_s=1e-3, why=why)

    result = run_scene(_scene(body), "quick", tmp_path)
    assert result.status() == "error" and "why=" in result.error
    result = run_scene(_scene(lambda run: body(run, why="stated reason")), "quick", tmp_path)
    assert result.status() != "error"
    assert result.outputs[0].why == "stated reason"


def test_zero_reference_needs_its_scale_explained(tmp_path):
    def body(run):
        run.check(model="m", family="analytical",
                  quantity="q", unit="N", value=0.0, reference=0.0, scale=4.0, source="s",
                  tolerance=1e-9, time_s=1e-3)

    assert "why=" in run_scene(_scene(body), "quick", tmp_path).error
    with pytest.raises(ValueError, match="reason"):
        KnownGap(reason=" ", evidence="x")


def test_exact_check_needs_no_scale_reason(tmp_path):
    """tolerance 0 demands exact agreement, so a unit scale on a zero reference makes nothing lax."""
    def body(run, value):
        run.check(model="m", family="analytical",
                  quantity="count", unit="count", value=value, reference=0.0, scale=1.0, source="s",
                  tolerance=0.0, time_s=1e-3)

    assert run_scene(_scene(lambda run: body(run, 0.0)), "quick", tmp_path).passed
    failed = run_scene(_scene(lambda run: body(run, 1e-300)), "quick", tmp_path)
    assert not failed.error and not failed.passed


def test_known_gap_statuses(tmp_path):
    def gap(run, value):
        run.check(model="m", family="analytical",
                  quantity="increase", unit="%", value=value, reference=185.2, relation="ge",
                  tolerance=0.0, source="paper", time_s=1e-3, known_gap=GAP)

    missed = run_scene(_scene(lambda run: gap(run, 150.0)), "quick", tmp_path)
    assert missed.outputs[0].status == "known gap"
    assert missed.status() == "known gap" and missed.passed
    assert missed.status(strict=True) == "fail"
    reached = run_scene(_scene(lambda run: gap(run, 190.0)), "quick", tmp_path)
    assert reached.outputs[0].status == "unexpected pass"
    assert reached.status() == "fail" and not reached.passed  # loud: the declaration must go


def test_budgets_never_decide_unless_strict_time(tmp_path):
    def body(run):
        run.check(model="m", family="analytical",
                  quantity="q", unit="N", value=1.0, reference=1.0, source="s", tolerance=1e-9,
                  time_s=1e-3)
        run.budget(quantity="wall time", unit="s", value=61.7, budget=60.0, source="docs/validation.md budget")

    result = run_scene(_scene(body), "quick", tmp_path)
    assert result.outputs[1].status == "over budget"
    assert result.passed and result.over_budget
    assert result.status(strict_time=True) == "fail"


# --------------------------------------------------------------------------------------------- CLI
def _figure_scene(run):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(2, 2))
    axes.plot([0, 1], [0, 1])
    run.save_figure(figure, "line.png")
    run.check(model="lowmodel.contact.hertz", family="analytical",
              quantity="a", unit="m", value=1.2e-4 * (1 + 1e-12), reference=1.2e-4,
              source="closed form", tolerance=1e-10, time_s=1e-3)
    run.check(model="lowmodel.contact.hertz", family="analytical",
              quantity="p0", unit="Pa", value=1.1638e9, reference=1.1638e9 * 1.001,
              source="closed form", tolerance=0.01, time_s=2e-3, note="worst error at the slower evaluation")
    run.note("a note under the table")


def _fail_scene(run):
    run.check(model="fem.contact", family="FE",
              quantity="F_B2B", unit="N", value=4.52, reference=4.01, source="lin2019 Table 3",
              tolerance=0.03, time_s=0.5)


def _gap_scene(run):
    run.check(model="lowmodel.linear_bearing.b2b", family="low-order numerical",
              quantity="largest friction increase", unit="%", value=150.4,
              reference=185.2, relation="ge", tolerance=0.0, source="lin2019 Sec 2.4.1", time_s=0.01, known_gap=GAP)


def _over_budget_scene(run):
    run.check(model="m", family="analytical",
              quantity="q", unit="1", value=1.0, reference=1.0, source="s", tolerance=1e-9, time_s=1e-3)
    run.budget(quantity="wall_time", unit="s", value=2.0, budget=1.0, source="budget")


def _raise_scene(run):
    raise ValueError("conformity must be in (0.5, 1)")


def _interrupt_scene(run):
    raise KeyboardInterrupt


def _sigint_scene(run):
    os.kill(os.getpid(), signal.SIGINT)  # one Ctrl-C: the scene finishes, the next one does not start
    run.check(model="m", family="analytical",
              quantity="q", unit="1", value=1.0, reference=1.0, source="s", tolerance=1e-9, time_s=1e-3)


FAKES = {"zz-a-pass": (_figure_scene, "analytical"), "zz-b-fail": (_fail_scene, "FE"),
         "zz-c-gap": (_gap_scene, "low-order"), "zz-d-budget": (_over_budget_scene, "low-order"),
         "zz-e-raise": (_raise_scene, "low-order"), "zz-f-interrupt": (_interrupt_scene, "low-order"),
         "zz-g-sigint": (_sigint_scene, "low-order"), "zz-h-after": (_figure_scene, "analytical")}


@pytest.fixture
def fakes(monkeypatch):
    scene_module.registry()  # load the real scenes first
    for name, (function, kind) in FAKES.items():
        monkeypatch.setitem(scene_module.REGISTRY, name,
                            Scene(name, f"fake scene {name}", function, default=False, kind=kind, cost_s=0.1))
    return FAKES


def _validate(tmp_path, *names, extra=()):
    out = tmp_path / "report"
    code = cli.main(["validate", *names, "--out", str(out), *extra])
    return code, out


@pytest.mark.parametrize("names, extra, code", [
    (("zz-a-pass",), (), 0),
    (("zz-a-pass", "zz-b-fail"), (), 1),
    (("zz-c-gap",), (), 0),
    (("zz-c-gap",), ("--strict",), 1),
    (("zz-d-budget",), (), 0),
    (("zz-d-budget",), ("--strict-time",), 1),
    (("zz-e-raise",), (), 1),
])
def test_cli_exit_codes(fakes, tmp_path, capsys, names, extra, code):
    assert _validate(tmp_path, *names, extra=extra)[0] == code
    err = capsys.readouterr().err
    assert "Traceback" not in err


def test_fail_line_names_check_value_reference_and_error(fakes, tmp_path, capsys):
    _validate(tmp_path, "zz-b-fail")
    err = capsys.readouterr().err
    line = next(x for x in err.splitlines() if "F_B2B" in x)
    assert "4.52" in line and "4.01" in line and "12.7 %" in line and "tolerance 3 %" in line


@pytest.mark.parametrize("argv, expected", [
    (["validate", "no-such-scene"], "no scene matches"),
    (["validate", "--bogus"], "unrecognized arguments"),
    (["validate", "--quick", "--fine"], "not allowed with"),
    ([], "required"),
    (["frobnicate"], "invalid choice"),
    (["validate", "--fast", "fe-hertz-flat"], "--fast leaves no scene"),
    (["show", "hertz-sphere-flat"], "FE scenes"),
    (["show", "no-such-scene"], "no scene"),
    (["show"], "required"),
])
def test_cli_wrong_use_is_one_line_and_exit_2(fakes, capsys, monkeypatch, argv, expected):
    from ballbench.validation import runner

    monkeypatch.setattr(runner, "run_scenes", lambda *a, **k: pytest.fail("work started before the check"))
    assert expected in one_error_line(capsys, cli.main(argv))


def test_cli_out_checked_before_any_work(fakes, tmp_path, capsys, monkeypatch):
    from ballbench.validation import runner

    monkeypatch.setattr(runner, "run_scenes", lambda *a, **k: pytest.fail("work started before the check"))
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    other = tmp_path / "notes"
    other.mkdir()
    (other / "mine.txt").write_text("keep me")
    cases = [(["--out", str(a_file)], "existing file"),
             (["--out", str(a_file / "sub")], "cannot write"),
             (["--out", "/proc/ballbench-cannot-write-here"], "cannot write"),
             (["--out", str(other)], "not a ballbench report"),
             (["--out", "."], "the current folder"),
             (["--out", str(tmp_path / "r"), "--junit", str(tmp_path)], "--junit"),
             (["--out", str(tmp_path / "r"), "--junit", str(tmp_path / "missing" / "j.xml")], "does not exist")]
    for extra, expected in cases:
        assert expected in one_error_line(capsys, cli.main(["validate", "zz-a-pass", *extra]))
    assert (other / "mine.txt").read_text() == "keep me"
    assert "existing file" in one_error_line(capsys, cli.main(["show", "fe-hertz-flat", "--out", str(a_file)]))


def test_rerun_into_same_out_removes_the_earlier_reports_files_only(fakes, tmp_path, capsys):
    # no stale file of the earlier report survives a re-run; files of one's own put into it do, untouched (the
    # run used to empty the folder: a user's notes.txt and folder were deleted without a word)
    code, out = _validate(tmp_path, "zz-a-pass")
    assert code == 0 and (out / "zz-a-pass" / "line.png").exists()
    (out / "zz-a-pass" / "mine.png").write_bytes(b"mine")
    (out / "notes.txt").write_text("my notes")
    (out / "my-folder" / "deeper").mkdir(parents=True)
    (out / "my-folder" / "deeper" / "data.csv").write_text("1,2")
    (out / "empty-of-mine").mkdir()
    capsys.readouterr()
    code, out = _validate(tmp_path, "zz-h-after")
    assert code == 0
    assert not (out / "zz-a-pass" / "line.png").exists()
    assert (out / "zz-h-after" / "line.png").exists()
    assert (out / "notes.txt").read_text() == "my notes"
    assert (out / "my-folder" / "deeper" / "data.csv").read_text() == "1,2"
    assert (out / "zz-a-pass" / "mine.png").read_bytes() == b"mine" and (out / "empty-of-mine").is_dir()
    err = capsys.readouterr().err
    assert "untouched" in err and "notes.txt" in err and "my-folder" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]  # no temporary or aside folder left
    # a third run: the carried files are still the user's (not in the manifest), the second run's are removed
    assert _validate(tmp_path, "zz-a-pass")[0] == 0
    assert (out / "notes.txt").exists() and not (out / "zz-h-after").exists()


def test_ctrl_c_inside_a_scene_writes_partial_report(fakes, tmp_path, capsys):
    code, out = _validate(tmp_path, "zz-a-pass", "zz-f-interrupt", "zz-h-after")
    assert code == 130
    partial = tmp_path / "report-partial"  # beside the report folder, named so
    data = json.loads((partial / "results.json").read_text())
    assert [s["name"] for s in data["scenes"]] == ["zz-a-pass"]
    assert data["complete"] is False and data["not_run"] == ["zz-f-interrupt", "zz-h-after"]
    assert "interrupted" in capsys.readouterr().err.splitlines()[-1]
    assert "Partial report" in (partial / "report.md").read_text()
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["report-partial"]


def test_an_interrupted_run_leaves_the_earlier_complete_report_intact(fakes, tmp_path, capsys):
    # the run used to empty the report folder first: Ctrl-C left only a partial report where the complete one was
    code, out = _validate(tmp_path, "zz-a-pass", "zz-h-after")
    assert code == 0
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    for scene in ("zz-f-interrupt", "zz-g-sigint"):  # Ctrl-C inside a scene; between two scenes
        capsys.readouterr()
        assert _validate(tmp_path, "zz-a-pass", scene, "zz-h-after")[0] == 130
        assert {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
        assert "untouched" in capsys.readouterr().err.splitlines()[-1]
        data = json.loads((tmp_path / "report-partial" / "results.json").read_text())
        assert data["complete"] is False and data["not_run"][-1] == "zz-h-after"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report", "report-partial"]
    # the next complete run replaces the report; the partial one beside it is left as it is
    assert _validate(tmp_path, "zz-h-after")[0] == 0
    assert not (out / "zz-a-pass").exists() and (tmp_path / "report-partial" / "report.md").exists()


def test_first_ctrl_c_stops_after_the_current_scene(fakes, tmp_path, capsys):
    before = signal.getsignal(signal.SIGINT)  # Python's default handler, or SIG_IGN in a background job
    code, out = _validate(tmp_path, "zz-a-pass", "zz-g-sigint", "zz-h-after")
    assert code == 130
    data = json.loads((tmp_path / "report-partial" / "results.json").read_text())
    assert [s["name"] for s in data["scenes"]] == ["zz-a-pass", "zz-g-sigint"]
    assert data["not_run"] == ["zz-h-after"]
    err = capsys.readouterr().err
    assert "stopping after the current scene" in err and "Traceback" not in err
    assert signal.getsignal(signal.SIGINT) is before  # the run gives back the handler it found


_DRIVER = """
import hashlib, sys
from ballbench.validation import cli, scene as scene_module
from ballbench.validation.scene import Scene


def quick(run):
    run.check(model="m", family="analytical", quantity="q", unit="1", value=1.0, reference=1.0, source="s",
              tolerance=1e-9, time_s=1e-3)


def long(run):
    print("zz-long: inside", file=sys.stderr, flush=True)
    # one C call that releases the GIL and never looks for signals, as a sparse solve does: minutes
    hashlib.pbkdf2_hmac("sha256", b"p", b"s", 2 ** 31 - 1)


scene_module.registry()
for name, function in (("zz-quick", quick), ("zz-long", long)):
    scene_module.REGISTRY[name] = Scene(name, "fake", function, default=False, kind="low-order", cost_s=0.1)
sys.exit(cli.main(["validate", *sys.argv[2:], "--out", sys.argv[1], "--no-progress"]))
"""


def test_a_second_ctrl_c_ends_the_run_at_once_leaving_the_earlier_report(tmp_path):
    # the second Ctrl-C used to raise KeyboardInterrupt only when the solver call returned (minutes), into a
    # report folder the run had emptied first
    driver = tmp_path / "driver.py"
    driver.write_text(_DRIVER)
    out = tmp_path / "report"
    command = [sys.executable, str(driver), str(out)]
    done = subprocess.run([*command, "zz-quick"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    process = subprocess.Popen([*command, "zz-quick", "zz-long"], stderr=subprocess.PIPE, text=True)
    try:
        lines = []
        while not lines or lines[-1] != "zz-long: inside\n":
            lines.append(process.stderr.readline())
            assert lines[-1], "".join(lines)
        time.sleep(0.3)
        process.send_signal(signal.SIGINT)
        time.sleep(0.3)
        assert process.poll() is None  # the first Ctrl-C waits for the scene
        start = time.monotonic()
        process.send_signal(signal.SIGINT)
        code = process.wait(timeout=10)
        elapsed = time.monotonic() - start
        err = process.stderr.read()
    finally:
        process.kill()
        process.wait()
    assert code == 130 and elapsed < 2.0, (code, elapsed, err)
    assert "stopped at once" in err and "untouched" in err
    assert {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()} == before
    partial = tmp_path / "report-partial"
    assert (partial / ".ballbench-report").is_file() and not (partial / "report.md").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", "report", "report-partial"]


def test_broken_pipe_is_quiet():
    command = f"'{sys.executable}' -m ballbench scenes | head -n 1"
    done = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=120)
    assert done.stdout.startswith("scene")
    assert done.stderr == "", done.stderr


def test_version_and_plain_help(capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out.startswith("ballbench ")
    for argv in (["--help"], ["validate", "--help"], ["show", "--help"]):
        with pytest.raises(SystemExit):
            cli.main(argv)
        text = capsys.readouterr().out
        assert "``" not in text and "usage:" in text


def test_scenes_lists_kind_cost_and_level(capsys):
    assert cli.main(["scenes"]) == 0
    out = capsys.readouterr().out
    flat = next(line for line in out.splitlines() if line.startswith("fe-hertz-flat"))
    assert " FE " in flat and "n = b/h" in flat and "s " in flat
    assert any(line.startswith("lin2019-table3-a") and "low-order" in line for line in out.splitlines())
    assert "default run:" in out and "--fast:" in out


def test_progress_bars_only_on_a_terminal(fakes, tmp_path, capsys):
    _validate(tmp_path, "zz-a-pass")
    assert "\r" not in capsys.readouterr().err


# --------------------------------------------------------------------------------------------- reports
class _Collect(HTMLParser):
    def __init__(self):
        super().__init__()
        self.sections, self.images, self.external = [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "section":
            self.sections.append(attrs.get("data-scene"))
        if tag == "img":
            self.images.append((attrs.get("data-artifact"), attrs.get("src", "")))
        for key in ("src", "href"):
            if str(attrs.get(key, "")).startswith(("http:", "https:", "//")):
                self.external.append(attrs[key])
        if tag in ("script", "link"):
            self.external.append(tag)


def test_report_html_is_self_contained_with_every_scene_and_figure(fakes, tmp_path):
    code, out = _validate(tmp_path, "zz-a-pass", "zz-b-fail", "zz-c-gap", "zz-d-budget")
    assert code == 1
    data = json.loads((out / "results.json").read_text())
    parser = _Collect()
    parser.feed((out / "report.html").read_text())
    assert parser.sections == [s["name"] for s in data["scenes"]]
    figures = {a for s in data["scenes"] for a in s["artifacts"] if a.endswith(".png")} | {"error_vs_time.png"}
    assert {name for name, _ in parser.images} == figures
    assert all(src.startswith("data:image/png;base64,") for _, src in parser.images)
    assert parser.external == []
    text = (out / "report.html").read_text()
    assert "Known gaps" in text and html.escape(GAP.reason) in text and html.escape(GAP.evidence) in text


def test_report_markdown_summary_first_engineering_units(fakes, tmp_path):
    _, out = _validate(tmp_path, "zz-a-pass", "zz-c-gap")
    md = (out / "report.md").read_text()
    assert md.index("## Summary") < md.index("## Known gaps") < md.index("## zz-a-pass")
    assert "| a | 120.00 | 120.00 | um |" in md
    assert "| p0 | 1163.8 | 1165.0 | MPa |" in md
    assert md.count("one evaluation 1 ms") == 1 and md.count("one evaluation 2 ms") == 1  # time once per run
    data = json.loads((out / "results.json").read_text())
    assert data["scenes"][0]["outputs"][0]["unit"] == "m"  # JSON stays SI
    with open(out / "results.csv") as handle:
        assert next(csv.DictReader(handle))["unit"] == "m"


def test_plotted_times_are_one_evaluation_per_scene_and_model(fakes, tmp_path):
    """error_vs_time: one point per (scene, model) at the time of the evaluation of its worst error."""
    _, out = _validate(tmp_path, "zz-a-pass", "zz-b-fail", "zz-c-gap", "zz-d-budget", "zz-h-after")
    data = json.loads((out / "results.json").read_text())
    with open(out / "error_vs_time.csv") as handle:
        plotted = {(r["scene"], r["model"]): r for r in csv.DictReader(handle)}
    expected = {}
    for s in data["scenes"]:
        for o in s["outputs"]:
            if o["kind"] != "accuracy":
                continue
            tolerance = float(o["tolerance"])
            ratio = float(o["rel_error"]) / tolerance if tolerance else (0.0 if o["rel_error"] == 0 else math.inf)
            key = (s["name"], o["model"])
            if key not in expected or ratio > expected[key][0]:
                expected[key] = (ratio, float(o["time_s"]))
    assert set(plotted) == set(expected)
    for key, (ratio, time_s) in expected.items():
        assert float(plotted[key]["time_s"]) == time_s
        assert float(plotted[key]["error_over_tolerance"]) == pytest.approx(ratio)
    assert float(plotted[("zz-a-pass", "lowmodel.contact.hertz")]["time_s"]) == 2e-3  # not the 3e-3 sum
    assert plotted[("zz-c-gap", "lowmodel.linear_bearing.b2b")]["status"] == "known gap"
    assert [p["time_s"] for p in error_points(data)] == [float(r["time_s"]) for r in plotted.values()]


def test_junit_xml_has_a_test_case_per_scene(fakes, tmp_path):
    junit = tmp_path / "junit.xml"
    code, _ = _validate(tmp_path, "zz-a-pass", "zz-b-fail", "zz-c-gap", "zz-e-raise", extra=("--junit", str(junit)))
    assert code == 1
    suite = ET.parse(junit).getroot()
    cases = {c.get("name"): c for c in suite.iter("testcase")}
    assert set(cases) == {"zz-a-pass", "zz-b-fail", "zz-c-gap", "zz-e-raise"}
    assert cases["zz-a-pass"].find("failure") is None and cases["zz-a-pass"].find("skipped") is None
    assert "F_B2B" in cases["zz-b-fail"].find("failure").get("message")
    assert cases["zz-c-gap"].find("skipped").get("message").startswith("known gap")
    assert cases["zz-e-raise"].find("error") is not None
    counts = (suite.get("tests"), suite.get("failures"), suite.get("errors"), suite.get("skipped"))
    assert counts == ("4", "1", "1", "1")


def test_report_files_and_schema(tmp_path):
    def body(run):
        run.check(model="m", family="analytical",
                  quantity="q", unit="m", value=1.0, reference=1.0, source="s", tolerance=0.0,
                  time_s=1e-3)

    results = [run_scene(_scene(body), "default", tmp_path)]
    paths = write_report(results, tmp_path, "default")
    for path in paths.values():
        assert path.exists() and path.stat().st_size > 0
    data = json.loads(paths["json"].read_text())
    output = data["scenes"][0]["outputs"][0]
    for key in ("model", "quantity", "unit", "value", "reference", "source", "rel_error", "tolerance",
                "passed", "time_s", "status", "kind", "known_gap_reason"):
        assert key in output
    assert data["scenes"][0]["passed"] is True and data["scenes"][0]["status"] == "pass"


def test_cli_real_scenes_quick(tmp_path):
    assert cli.main(["validate", "hertz-sphere-flat", "lin2019-table1-psi", "--out", str(tmp_path),
                     "--quick", "--no-progress"]) == 0
    data = json.loads((tmp_path / "results.json").read_text())
    assert {s["name"] for s in data["scenes"]} == {"hertz-sphere-flat", "lin2019-table1-psi"}


def test_fig9_worst_is_a_declared_known_gap():
    import inspect

    function = scene_module.registry()["lin2019-fig9-worst"].function  # through the registry, not an import
    gap = function.__globals__["FIG9_GAP"]
    assert isinstance(gap, KnownGap)
    # the gap stands on both laws: full sliding has no state near the limit, the stick/slip law has one there
    assert "stick/slip" in gap.reason and "Neither law reaches" in gap.reason
    assert "docs/b2b_rolling.md" in gap.evidence
    # both Fig 9 scenes (the worst row, and every point: not in the default run) run one function that declares it
    module = inspect.getsource(inspect.getmodule(function))
    assert "known_gap=FIG9_GAP" in module and module.count("known_gap=") == 1 + module.count("known_gap=None")
    assert "whole_grid=False" in inspect.getsource(function)
    whole = scene_module.registry()["lin2019-fig9-stick-slip"]
    assert not whole.default and "whole_grid=True" in inspect.getsource(whole.function)


def test_results_json_round_trip(fakes, tmp_path):
    from ballbench.validation.report import results_from_json, to_json

    _, out = _validate(tmp_path, "zz-a-pass", "zz-c-gap", "zz-d-budget")
    data = json.loads((out / "results.json").read_text())
    again = to_json(results_from_json(data), data["fidelity"])
    assert json.loads(json.dumps(again)) == data


def test_report_folder_of_an_older_version_is_reused(fakes, tmp_path):
    out = tmp_path / "report"
    out.mkdir()
    for name in ("report.md", "results.json", "error_vs_time.png"):
        (out / name).write_text("old")
    assert cli.main(["validate", "zz-a-pass", "--out", str(out)]) == 0
    assert (out / ".ballbench-report").exists() and (out / "zz-a-pass").is_dir()
    assert json.loads((out / "results.json").read_text())["scenes"][0]["name"] == "zz-a-pass"


def test_pictures_added_to_a_report_of_an_older_version_keep_its_files_its_own(fakes, tmp_path, capsys):
    # a report without a manifest: 'show' listing only its pictures made the next run keep the old report.md
    from ballbench.validation import report_folder

    out = tmp_path / "report"
    assert cli.main(["validate", "zz-a-pass", "--out", str(out)]) == 0
    (out / ".ballbench-report").unlink()  # as an earlier version wrote it: report.md and results.json
    (out / "zz-a-pass" / "picture.png").write_bytes(b"png")
    report_folder.add_to_manifest(out, [out / "zz-a-pass" / "picture.png"])
    assert {"report.md", "results.json", "zz-a-pass/picture.png", "zz-a-pass/line.png"} <= report_folder.owned(out)
    capsys.readouterr()
    assert cli.main(["validate", "zz-h-after", "--out", str(out)]) == 0
    assert "untouched" not in capsys.readouterr().err and not (out / "zz-a-pass").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]


def test_a_link_to_a_report_folder_stays_a_link(fakes, tmp_path):
    target = tmp_path / "reports" / "mine"
    assert cli.main(["validate", "zz-a-pass", "--out", str(target)]) == 0
    link = tmp_path / "link"
    link.symlink_to(target)
    assert cli.main(["validate", "zz-h-after", "--out", str(link)]) == 0
    assert link.is_symlink() and (target / "zz-h-after").is_dir() and not (target / "zz-a-pass").exists()


def test_fig9_known_gap_passes_the_run_and_fails_strict(tmp_path, capsys):
    """Declared known gaps at the quick level: the gap is listed, the run passes; --strict fails it."""
    out = tmp_path / "report"
    assert cli.main(["validate", "lin2019-fig9-worst", "--quick", "--out", str(out)]) == 0
    scene_data = json.loads((out / "results.json").read_text())["scenes"][0]
    assert scene_data["status"] == "known gap"
    assert scene_data["outputs"][0]["known_gap_reason"]
    assert "known gap" in capsys.readouterr().err
    assert "lin2019-fig9-worst" in (out / "report.md").read_text().split("## Known gaps")[1].split("## Budgets")[0]
    assert cli.main(["validate", "lin2019-fig9-worst", "--quick", "--strict", "--out", str(out)]) == 1


def test_mesh_levels_join_the_accuracy_cost_front(tmp_path):
    from ballbench.validation.report import mesh_level_points, to_json

    def body(run):
        path = run.path("convergence.csv")
        path.write_text("n,growth,wall_s,err_a,err_p0\n5.5,1.4,10.0,0.02,-0.03\n8.0,1.2,80.0,0.001,0.002\n")
        run.add_artifact(path)
        run.check(model="fem.contact", family="FE", quantity="a", unit="m", value=1.001, reference=1.0, source="Hertz",
                  tolerance=0.003, time_s=80.0)
        run.check(model="fem.contact", family="FE",
                  quantity="p0", unit="Pa", value=1.002, reference=1.0, source="Hertz",
                  tolerance=0.005, time_s=80.0)

    result = run_scene(_scene(body, kind="FE"), "fine", tmp_path)
    levels = mesh_level_points(to_json([result], "fine"), tmp_path)
    assert [p["time_s"] for p in levels] == [10.0, 80.0]
    assert [p["error"] for p in levels] == pytest.approx([max(0.02 / 0.003, 0.03 / 0.005), 0.4])


def test_a_scene_that_raises_points_to_its_traceback(tmp_path, capsys, monkeypatch):
    from ballbench.validation import scene as scene_module
    from ballbench.validation.scene import Scene

    def raises(run):
        raise ValueError("conformity must lie in (0.5, 1); got 0.49")

    scene_module.registry()
    monkeypatch.setitem(scene_module.REGISTRY, "zz-raises",
                        Scene("zz-raises", "raises", raises, default=False, kind="low-order", cost_s=0.1))
    assert cli.main(["validate", "zz-raises", "--out", str(tmp_path / "r")]) == 1
    err = capsys.readouterr().err
    # the terminal said only "ERROR zz-raises (0.0 s): ValueError: ..." and the traceback sat in a file it never named
    assert f"traceback: {tmp_path / 'r' / 'zz-raises' / 'error.txt'}" in err
    assert (tmp_path / "r" / "zz-raises" / "error.txt").read_text().startswith("Traceback")


def test_a_table_is_written_as_csv_and_listed_as_an_artifact(tmp_path):
    rows = [{"h_um": 30, "F_N": 4.1}, {"h_um": 20, "F_N": 4.05}]

    def table_scene(run):
        assert run.write_csv("empty.csv", []) is None  # no rows: no file
        run.write_csv("levels.csv", rows)
        run.check(model="m", family="analytical", quantity="q", unit="1", value=1.0, reference=1.0, tolerance=0.1,
                  source="s", time_s=0.0)

    result = run_scene(Scene("zz-table", "table", table_scene, default=False, kind="low-order", cost_s=0.1),
                       "default", tmp_path)
    written = [name for name in result.artifacts if name.endswith(".csv")]
    assert len(written) == 1 and written[0].endswith("levels.csv")
    with open(tmp_path / written[0], newline="") as handle:
        assert list(csv.DictReader(handle)) == [{"h_um": "30", "F_N": "4.1"}, {"h_um": "20", "F_N": "4.05"}]
    assert not any(name.endswith("empty.csv") for name in result.artifacts)
