"""The validation harness: error convention, failure handling, report files, CLI exit codes."""
from __future__ import annotations

import json
import math

import pytest

from ballbench.validation import cli
from ballbench.validation.report import write_report
from ballbench.validation.runner import run_scene
from ballbench.validation.scene import Scene, relative_error


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


def _scene(function, name="demo"):
    return Scene(name, "demo scene", function)


def test_checks_pass_and_fail(tmp_path):
    def body(run):
        value, time_s = run.time(lambda: 2.0)
        run.check(model="m", quantity="q", unit="N", value=value, reference=2.0, source="s",
                  tolerance=1e-12, time_s=time_s)
        run.check(model="m", quantity="r", unit="N", value=1.1, reference=1.0, source="s",
                  tolerance=0.05, time_s=time_s)

    result = run_scene(_scene(body), "quick", tmp_path, show_progress=False)
    assert [o.passed for o in result.outputs] == [True, False]
    assert not result.passed
    assert result.outputs[0].time_s > 0


def test_exception_and_empty_scene_fail(tmp_path):
    def boom(run):
        raise ValueError("conformity must be > 0.5")

    result = run_scene(_scene(boom), "quick", tmp_path, show_progress=False)
    assert not result.passed and "conformity" in result.error
    result = run_scene(_scene(lambda run: None), "quick", tmp_path, show_progress=False)
    assert not result.passed and "no checked output" in result.error


def test_report_files_and_schema(tmp_path):
    def body(run):
        run.check(model="m", quantity="q", unit="m", value=1.0, reference=1.0, source="s", tolerance=0.0,
                  time_s=1e-3)

    results = [run_scene(_scene(body), "default", tmp_path, show_progress=False)]
    paths = write_report(results, tmp_path, "default")
    for path in paths.values():
        assert path.exists() and path.stat().st_size > 0
    data = json.loads(paths["json"].read_text())
    output = data["scenes"][0]["outputs"][0]
    for key in ("model", "quantity", "unit", "value", "reference", "source", "rel_error", "tolerance",
                "passed", "time_s"):
        assert key in output
    assert data["scenes"][0]["passed"] is True
    assert "| m | q | m |" in paths["markdown"].read_text()


def test_cli_validate_exit_codes(tmp_path, capsys):
    assert cli.main(["validate", "hertz-sphere-flat", "lin2019-table1-psi", "--out", str(tmp_path),
                     "--quick", "--no-progress"]) == 0
    data = json.loads((tmp_path / "results.json").read_text())
    assert {s["name"] for s in data["scenes"]} == {"hertz-sphere-flat", "lin2019-table1-psi"}
    with pytest.raises(SystemExit, match="no scene matches"):
        cli.main(["validate", "no-such-scene", "--out", str(tmp_path)])


def test_cli_lists_scenes(capsys):
    assert cli.main(["scenes"]) == 0
    assert "hertz-groove-conformity" in capsys.readouterr().out
