"""``validate --workers N`` / ``--scheduler ADDRESS``: scenes as dask.distributed tasks give the results of a serial
run (timings aside)."""
from __future__ import annotations

import json
import math

import pytest

from ballbench.validation import cli
from tests.cli_support import one_error_line

SCENES = ["hertz-ball-ball", "hertz-sphere-flat", "lin2019-table3-a"]


def _numbers(path):
    """Every check of results.json without its timings."""
    data = json.loads(path.read_text())
    return {(s["name"], o["model"], o["quantity"]): (o["value"], o["reference"], o["passed"])
            for s in data["scenes"] for o in s["outputs"]}


def test_two_workers_give_the_serial_results(tmp_path, capsys):
    assert cli.main(["validate", *SCENES, "--quick", "--out", str(tmp_path / "serial")]) == 0
    assert cli.main(["validate", *SCENES, "--quick", "--out", str(tmp_path / "dask"), "--workers", "2"]) == 0
    serial, distributed = _numbers(tmp_path / "serial" / "results.json"), _numbers(tmp_path / "dask" / "results.json")
    assert serial.keys() == distributed.keys() and len(serial) > 3
    for key, (value, _reference, passed) in serial.items():
        other = distributed[key]
        assert other[2] == passed and (value == other[0] or math.isclose(value, other[0], rel_tol=1e-12)), key
    assert "local cluster of 2 workers" in capsys.readouterr().err


@pytest.mark.parametrize("args, words", [
    (["--workers", "0"], "--workers must be at least 1"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "not both"),
])
def test_wrong_use_of_workers(args, words, tmp_path, capsys):
    code = cli.main(["validate", "hertz-ball-ball", "--out", str(tmp_path / "r"), *args])
    assert words in one_error_line(capsys, code)
