"""The command line (validation/cli.py): what a new user trips over (misspelt names, help, the README's commands);
each test fails on the behaviour it guards."""
from __future__ import annotations

import json

import pytest

from ballbench.validation import cli
from tests import paths
from tests.cli_support import one_error_line


@pytest.fixture
def no_work(monkeypatch):
    from ballbench.validation import runner, show

    monkeypatch.setattr(runner, "run_scenes", lambda *a, **k: pytest.fail("work started before the check"))
    monkeypatch.setattr(show, "show", lambda *a, **k: pytest.fail("show started on a scene it cannot draw"))


def test_misspelt_scene_name_suggests_the_close_ones(capsys, no_work, tmp_path):
    line = one_error_line(capsys, cli.main(["validate", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line
    line = one_error_line(capsys, cli.main(["show", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line


def test_show_of_a_scene_without_saved_fields_says_to_validate_first(capsys, tmp_path):
    # sun2021-fe-bem saves only its BEM surfaces (no fields.vtu): 'show' on a folder without them used to advise
    # deleting a fields.vtu that never existed
    line = one_error_line(capsys, cli.main(["show", "sun2021-fe-bem", "--out", str(tmp_path / "r")]))
    assert "no ballbench report" in line and "ballbench validate sun2021-fe-bem" in line and "delete" not in line
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("record, words", [
    ({"status": "error", "error": "ValueError: conformity"}, ["ended in an error: ValueError: conformity",
                                                             "error.txt"]),
    ({"status": "pass"}, ["saved no fields", "ballbench validate"]),
])
def test_show_of_a_scene_with_nothing_saved_says_why_and_exits_0(capsys, tmp_path, record, words):
    # a scene that errored in the validate run: 'show' used to exit 1 (or solve it again, minutes)
    out = tmp_path / "r"
    (out / "sun2021-fe-bem").mkdir(parents=True)
    (out / "sun2021-fe-bem" / "error.txt").write_text("Traceback")
    (out / ".ballbench-report").write_text("{}")
    (out / "results.json").write_text(json.dumps({"fidelity": "default", "scenes": [
        {"name": "sun2021-fe-bem", **record}]}))
    assert cli.main(["show", "sun2021-fe-bem", "--out", str(out)]) == 0
    captured = capsys.readouterr()
    lines = [x for x in captured.err.splitlines() if x.strip()]
    assert captured.out == "" and len(lines) == 1 and "nothing saved to draw" in lines[0]
    assert all(w in lines[0] for w in words) and "--solve" not in lines[0], lines[0]


def test_show_names_the_kind_with_the_right_article(capsys, no_work, tmp_path):
    line = one_error_line(capsys, cli.main(["show", "hertz-sphere-flat", "--out", str(tmp_path / "r")]))
    assert "is an analytical scene" in line


# ---------------------------------------------------------------------------------------------- sweep


# ---------------------------------------------------------------------------------------------- report figure


# ---------------------------------------------------------------------------------------------- calibrate


# ---------------------------------------------------------------------------------------------- README, help
README = paths.ROOT / "README.md"


def test_readme_calibrate_writes_the_file_the_next_command_reads():
    # the calibrate spec's output is relative to the spec's folder (examples/), so without --out the README's
    # 'validate --calibration calibration.json' found no file (and examples/ got the output files)
    lines = [x.split("#")[0].split() for x in README.read_text().splitlines() if x.startswith("ballbench ")]
    calibrate = next(x for x in lines if x[1] == "calibrate")
    validate = next(x for x in lines if x[1] == "validate" and "--calibration" in x)
    written = calibrate[calibrate.index("--out") + 1] if "--out" in calibrate else None
    assert written == validate[validate.index("--calibration") + 1]


def test_help_states_no_run_time_of_its_own(capsys):
    # the epilog said "about 5 minutes" for the default run while 'ballbench scenes' states ~27 min
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    text = capsys.readouterr().out
    assert "minute" not in text and "'ballbench scenes' states the cost" in text


def test_one_scene_is_not_one_scenes(tmp_path, capsys):
    from ballbench.validation.report import count

    assert count(1, "scene") == "1 scene" and count(35, "scene") == "35 scenes" and count(0, "point") == "0 points"
    assert cli.main(["validate", "hertz-sphere-flat", "--out", str(tmp_path / "r")]) == 0
    assert "ballbench: 1 scene at fidelity default" in capsys.readouterr().err
    assert "mode default. 1 scene: 1 passed" in (tmp_path / "r" / "report.md").read_text()
