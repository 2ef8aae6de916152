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


_SPANS: dict[str, tuple[float, float]] = {}


def _sleeping_scene(run):
    import time

    start = time.perf_counter()
    time.sleep(1.5)  # long against dask's start of the next task on a loaded machine (0.7 s seen under the CI run)
    _SPANS[run.scene.name] = (start, time.perf_counter())
    run.check(model="probe", family="analytical", quantity="one", unit="1", value=1.0, reference=1.0, source="probe",
              tolerance=0.0, time_s=0.0)


def _probe(name, memory_gb):
    from ballbench.validation.scene import Scene

    return Scene(name, "probe", _sleeping_scene, default=False, kind="low-order", cost_s=0.1, memory_gb=memory_gb)


def test_declared_memory_keeps_scenes_apart_on_one_worker(tmp_path, capsys):
    # one worker with two threads and 10 GB declared: two scenes of 6 GB each must not overlap in time, two of
    # 4 GB may; the reservation is the dask resource "memory" (docs/validation.md, "Memory")
    from dask.distributed import LocalCluster

    from ballbench.validation.runner import run_scenes_distributed

    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address="127.0.0.1:0",
                      resources={"memory": 10e9}) as cluster:
        heavy = [_probe("zz-heavy-1", 6.0), _probe("zz-heavy-2", 6.0)]
        results, stopped = run_scenes_distributed(heavy, "default", tmp_path, scheduler=cluster.scheduler_address)
        assert not stopped and [r.status() for r in results] == ["pass", "pass"]
        (a0, a1), (b0, b1) = _SPANS["zz-heavy-1"], _SPANS["zz-heavy-2"]
        assert a1 <= b0 or b1 <= a0, "two scenes of 6 GB ran at once on a worker of 10 GB"
        light = [_probe("zz-light-1", 4.0), _probe("zz-light-2", 4.0)]
        run_scenes_distributed(light, "default", tmp_path, scheduler=cluster.scheduler_address)
        (a0, a1), (b0, b1) = _SPANS["zz-light-1"], _SPANS["zz-light-2"]
        assert a0 < b1 and b0 < a1, "two scenes of 4 GB waited for each other on a worker of 10 GB"
    assert "more than the largest worker" not in capsys.readouterr().err


def test_memory_reservation_of_a_scene(capsys):
    from ballbench.validation.runner import GB, memory_reservation

    fe = _probe("zz-fe", None)
    fe = type(fe)(**{**fe.__dict__, "kind": "FE"})
    assert fe.memory_for("default") == 12.0 and fe.memory_for("fine") == 24.0
    assert memory_reservation(fe, "default", 0.0) is None  # no worker declares memory: unreserved
    assert memory_reservation(fe, "default", 16 * GB) == {"memory": 12 * GB}
    assert memory_reservation(fe, "fine", 16 * GB) == {"memory": 16 * GB}  # takes the largest worker whole
    assert "zz-fe declares 24.0 GB, more than the largest worker's 16.0 GB" in capsys.readouterr().err
    with pytest.raises(ValueError, match="memory_gb"):
        from ballbench.validation.scene import scene

        scene("zz-bad", "bad", memory_gb=3e6)


def test_a_scene_reports_its_peak_memory(tmp_path):
    import numpy as np

    from ballbench.validation.runner import run_scene

    def allocating(run):
        block = np.ones(40_000_000)  # 320 MB touched
        run.check(model="probe", family="analytical", quantity="sum", unit="1", value=float(block.sum()), reference=4e7,
                  source="probe", tolerance=0.0, time_s=0.0)

    from ballbench.validation.scene import Scene

    small = run_scene(_probe("zz-small", None), "quick", tmp_path)
    large = run_scene(Scene("zz-large", "probe", allocating, default=False, cost_s=0.1), "quick", tmp_path)
    assert large.peak_memory_gb - small.peak_memory_gb > 0.3


def test_a_scene_that_starts_its_own_cluster_runs_on_a_worker(tmp_path):
    # sweep-equivalence starts a LocalCluster of two processes; a daemonic dask worker may not have children, so
    # the local cluster's workers are started non-daemonic (runner.LOCAL_CLUSTER_CONFIG)
    out = tmp_path / "dask"
    assert cli.main(["validate", "sweep-equivalence", "--quick", "--out", str(out), "--workers", "2"]) == 0
    scene = json.loads((out / "results.json").read_text())["scenes"][0]
    assert scene["status"] == "pass" and not scene["error"]
