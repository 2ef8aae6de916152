"""Sweep engine (validation/sweep/): spec checks, reproducible draws, failures, kill and resume, equivalence."""
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from ballbench.validation import sweep
from tests.cli_support import one_error_line
from tests.cli_support import helper_module
from tests import paths
from ballbench.validation import cli

HELPERS = textwrap.dedent('''
    import math, os, time

    def square(x, y=0.0, offset=0.0, delay=0.0):
        """x^2 + y + offset; logs every call to $SWEEP_LOG; x < 0 raises; x == 0 gives inf."""
        log = os.environ.get("SWEEP_LOG")
        if log:
            with open(log, "a") as handle:
                handle.write(f"{x!r}\\n")
        time.sleep(delay or float(os.environ.get("SWEEP_DELAY", "0")))
        if x < 0:
            raise ValueError(f"x must be >= 0, got {x}")
        if x == 0:
            return {"value": math.inf, "pair": (x, y)}
        return {"value": x * x + y + offset, "pair": (x, y)}

    def worker_profiling(x):
        """1.0 where the process that computes it runs dask's statistical profiler, else 0.0."""
        import dask
        return {"value": float(dask.config.get("distributed.worker.profile.enabled"))}

    def vector_square(x, y=0.0):
        import numpy as np
        x = np.asarray(x)
        if np.any(x < 0):
            raise ValueError("x must be >= 0")
        return {"value": x * x + y}
''')


@pytest.fixture
def helpers(tmp_path, monkeypatch):
    return helper_module(tmp_path, monkeypatch, "sweep_helpers", HELPERS)


def _spec(**overrides):
    raw = {"name": "t", "function": "sweep_helpers:square", "chunk_size": 4, "outputs": ["value", "pair[1]"],
           "fixed": {"offset": 1.0},
           "grid": {"x": {"values": [-1.0, 0.0, 1.0, 2.0, 3.0]}},
           "random": {"draws": 3, "seed": 7, "inputs": {"y": {"distribution": "normal", "mean": 0.0, "sigma": 1.0}}}}
    raw.update(overrides)
    return raw


def test_cases_and_units():
    spec = sweep.spec_from_dict({"name": "u", "function": "math:hypot", "outputs": ["x"],
                                 "grid": {"a": {"linspace": [0.0, 2.0, 3], "unit": "deg"}, "b": [1.0, 2.0]}})
    assert spec.n_cases == 6
    inputs = sweep.case_inputs(spec, 0, 6)
    np.testing.assert_allclose(inputs["a"], np.radians([0, 0, 1, 1, 2, 2]), rtol=0, atol=1e-18)  # C order
    np.testing.assert_array_equal(inputs["b"], [1, 2, 1, 2, 1, 2])


def test_draws_do_not_depend_on_chunking():
    spec = sweep.spec_from_dict({"name": "r", "function": "math:hypot", "outputs": ["x"], "random": {
        "draws": 10000, "seed": 3, "inputs": {"a": {"distribution": "normal", "mean": 1.0, "sigma": 2.0},
                                              "b": {"distribution": "uniform", "low": -1.0, "high": 1.0}}}})
    whole = sweep.case_inputs(spec, 0, 10000)
    pieces = [sweep.case_inputs(spec, s, min(s + 997, 10000)) for s in range(0, 10000, 997)]  # crosses blocks
    for name in ("a", "b"):
        np.testing.assert_array_equal(whole[name], np.concatenate([p[name] for p in pieces]))
    assert abs(whole["a"].mean() - 1.0) < 0.1 and abs(whole["a"].std() - 2.0) < 0.1
    assert whole["b"].min() >= -1.0 and whole["b"].max() < 1.0
    other = sweep.spec_from_dict({**spec.source, "random": {**spec.source["random"], "seed": 4}})
    assert not np.array_equal(sweep.case_inputs(other, 0, 10)["a"], whole["a"][:10])


@pytest.mark.parametrize("change, message", [
    ({"function": "nomodule"}, "package.module:function"),
    ({"outputs": []}, "outputs"),
    ({"chunk_size": 0}, "chunk_size"),
    ({"grid": {"x": {"linspace": [0, 1]}}}, "linspace"),
    ({"grid": {"x": {"values": [1.0], "unit": "furlong"}}}, "unit"),
    ({"random": {"draws": 3, "inputs": {"y": {"distribution": "normal", "mean": 0, "sigma": 1}}}}, "seed"),
    ({"random": {"draws": 3, "seed": 1, "inputs": {"y": {"distribution": "cauchy"}}}}, "distribution"),
    ({"random": {"draws": 3, "seed": 1, "inputs": {"y": {"distribution": "normal", "mean": 0, "sigma": -1}}}},
     "sigma"),
    ({"fixed": {"x": 1.0}}, "more than one"),
    ({"colour": "red"}, "unknown spec key"),
    ({"outputs": ["value", "x"]}, "share a name with a swept input"),
])
def test_bad_specs_are_named(change, message):
    with pytest.raises(ValueError, match=message):
        sweep.spec_from_dict(_spec(**change))


def test_unimportable_function_fails_before_running(tmp_path):
    spec = sweep.spec_from_dict(_spec(function="no_such_module_xyz:f"))
    with pytest.raises(ValueError, match="cannot import"):
        sweep.run_sweep(spec, tmp_path / "out", serial=True, progress=False)


def test_failures_are_recorded_with_their_reason(helpers, tmp_path):
    spec = sweep.spec_from_dict(_spec())
    summary = sweep.run_sweep(spec, tmp_path / "out", serial=True, progress=False)
    result = sweep.read_results(tmp_path / "out")
    assert summary.computed == 15 and summary.failed == 6 and result["case"].tolist() == list(range(15))
    negative = result["x"] < 0
    assert all(e.startswith("ValueError: x must be >= 0") for e in result["error"][negative])
    assert all("not finite" in e for e in result["error"][result["x"] == 0])
    ok = result["x"] > 0
    assert all(e == "" for e in result["error"][ok])
    np.testing.assert_array_equal(result["value"][ok], result["x"][ok] ** 2 + result["y"][ok] + 1.0)
    np.testing.assert_array_equal(result["pair[1]"][ok], result["y"][ok])
    assert np.all(np.isnan(result["value"][~ok]))  # stored as null


def test_vectorised_falls_back_to_single_calls(helpers, tmp_path):
    spec = sweep.spec_from_dict(_spec(function="sweep_helpers:vector_square", vectorised=True, fixed={},
                                      outputs=["value"], chunk_size=10))
    sweep.run_sweep(spec, tmp_path / "out", serial=True, progress=False)
    result = sweep.read_results(tmp_path / "out")
    assert sum(bool(e) for e in result["error"]) == 3  # x = -1 only, named per case
    ok = result["x"] >= 0
    np.testing.assert_array_equal(result["value"][ok], result["x"][ok] ** 2 + result["y"][ok])


def test_another_spec_in_the_same_directory_is_refused(helpers, tmp_path):
    sweep.run_sweep(sweep.spec_from_dict(_spec()), tmp_path / "out", serial=True, progress=False)
    with pytest.raises(ValueError, match="another sweep"):
        sweep.run_sweep(sweep.spec_from_dict(_spec(fixed={"offset": 2.0})), tmp_path / "out", serial=True,
                        progress=False)
    # the chunk size is not part of the identity: a resume with other chunks is fine
    summary = sweep.run_sweep(sweep.spec_from_dict(_spec(chunk_size=2)), tmp_path / "out", serial=True,
                              progress=False)
    assert summary.computed == 0 and summary.skipped == 15


def test_killed_sweep_restarts_with_the_missing_cases_only(helpers, tmp_path):
    spec_path = tmp_path / "spec.toml"
    spec_path.write_text(textwrap.dedent('''
        name = "kill"
        function = "sweep_helpers:square"
        chunk_size = 5
        outputs = ["value"]
        [grid]
        x = { linspace = [1.0, 2.0, 200] }
    '''))
    out = tmp_path / "out"
    env = {**os.environ, "PYTHONPATH": f"{helpers}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
           "SWEEP_LOG": str(tmp_path / "first.log"), "SWEEP_DELAY": "0.05"}  # 10 s in all: killed long before
    process = subprocess.Popen([sys.executable, "-m", "ballbench", "sweep", str(spec_path), "--serial", "--out",
                                str(out), "--no-progress"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and len(list(out.glob("part-*.parquet"))) < 4:
        time.sleep(0.05)
    process.send_signal(signal.SIGKILL)
    process.wait()
    parts = list(out.glob("part-*.parquet"))
    assert 4 <= len(parts) < 40, "the sweep must be killed halfway"
    done = set(sweep.read_results(out)["case"].tolist())
    os.environ["SWEEP_LOG"] = str(tmp_path / "second.log")
    try:
        summary = sweep.run_sweep(sweep.load_spec(spec_path), out, serial=True, progress=False)
    finally:
        del os.environ["SWEEP_LOG"]
    x_all = np.linspace(1.0, 2.0, 200)
    recomputed = [float(line) for line in (tmp_path / "second.log").read_text().split()]
    expected = sorted(x_all[sorted(set(range(200)) - done)].tolist())
    assert sorted(recomputed) == expected  # exactly the missing cases, each once
    assert summary.computed == 200 - len(done) and summary.skipped == len(done)
    result = sweep.read_results(out)
    np.testing.assert_array_equal(result["case"], np.arange(200))
    np.testing.assert_array_equal(result["value"], x_all ** 2)


def test_example_specs_parse_and_match_the_scene():
    from ballbench.validation.sweep.functions import EQUIVALENCE_SPEC

    from ballbench.validation.cases.case_file import kind_of

    root = paths.ROOT / "examples"  # sweep specs beside calibrate specs and case files (a top-level kind)
    specs = {p.stem: sweep.load_spec(p) for p in sorted(root.glob("*.toml"))
             if not p.stem.startswith("calibrate") and kind_of(p) is None}
    assert specs["two_ball_monte_carlo"].n_cases == 100_000
    assert specs["lin2019_fig8_9"].grid_shape == (101, 101)
    assert specs["sweep_equivalence"].identity() == sweep.spec_from_dict(EQUIVALENCE_SPEC).identity()


def test_many_chunks_through_a_bounded_window(helpers, tmp_path):
    # an in-process dask client (threads, no worker processes: cheap); 100 chunks > the 16 tasks in flight
    from dask.distributed import Client

    spec = sweep.spec_from_dict(_spec(chunk_size=2, grid={"x": {"linspace": [1.0, 2.0, 40]}}))
    with Client(processes=False, n_workers=1, threads_per_worker=2,
                dashboard_address="127.0.0.1:0") as client:
        summary = sweep.run_sweep(spec, tmp_path / "dask", client=client, progress=False)
    sweep.run_sweep(spec, tmp_path / "serial", serial=True, progress=False)
    assert summary.computed == spec.n_cases == 120
    dask_result, serial_result = sweep.read_results(tmp_path / "dask"), sweep.read_results(tmp_path / "serial")
    for name in ("case", "x", "y", "value", "pair[1]"):
        np.testing.assert_array_equal(dask_result[name], serial_result[name])
    assert list(dask_result["error"]) == list(serial_result["error"])


def test_cli_reports_spec_errors_as_messages(tmp_path, capsys):
    from ballbench.validation import cli
    from tests.cli_support import one_error_line

    assert "no such file" in one_error_line(capsys, cli.main(["sweep", str(tmp_path / "missing.toml"), "--serial"]))
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "b"\nfunction = "math:hypot"\noutputs = ["x"]\nchunk_size = 0\n')
    assert "chunk_size must be an integer >= 1" in one_error_line(capsys, cli.main(["sweep", str(bad), "--serial"]))


def test_a_spec_naming_the_old_module_of_the_case_functions_is_told_the_new_one(tmp_path, capsys):
    """The case functions moved from validation/sweep_cases.py to validation/sweep/functions.py: a spec that still
    names the old module is a wrong use whose message gives the new path (no alias module)."""
    from ballbench.validation import cli
    from tests.cli_support import one_error_line

    old = tmp_path / "old.toml"
    old.write_text('name = "o"\nfunction = "ballbench.validation.sweep_cases:two_ball_numerical"\n'
                   'outputs = ["b2b_force"]\n')
    line = one_error_line(capsys, cli.main(["sweep", str(old), "--serial", "--out", str(tmp_path / "out")]))
    assert 'function = "ballbench.validation.sweep.functions:two_ball_numerical"' in line
    assert not (tmp_path / "out").exists()


def test_gridded_sweep_lands_in_a_zarr_dataset_and_resumes_the_missing_cases(helpers, tmp_path, monkeypatch):
    """A partial run writes the Dataset with done = False where cases are missing; the restart computes only
    those (counted by the function's call log) and the final Dataset equals that of one uninterrupted run."""
    import xarray as xr

    log = tmp_path / "calls.log"
    monkeypatch.setenv("SWEEP_LOG", str(log))
    raw = _spec(grid={"x": {"values": [-1.0, 0.0, 1.0, 2.0, 3.0]}, "y": {"linspace": [0.0, 1.0, 2]}})
    raw.pop("random")
    spec = sweep.spec_from_dict(raw)
    out = tmp_path / "partial"
    first = sweep.run_sweep(spec, out, serial=True, progress=False, max_chunks=1)
    assert first.computed == 4
    partial = xr.open_zarr(out / sweep.DATASET_NAME, consolidated=False).load()
    assert partial.sizes == {"x": 5, "y": 2} and int(partial["done"].sum()) == 4
    assert np.isnan(partial["value"].values.reshape(-1)[4:]).all()
    log.write_text("")
    second = sweep.run_sweep(spec, out, serial=True, progress=False)
    assert second.skipped == 4 and second.computed == 6 and len(log.read_text().split()) == 6
    whole = sweep.run_sweep(spec, tmp_path / "whole", serial=True, progress=False)
    assert whole.computed == 10
    resumed = xr.open_zarr(out / sweep.DATASET_NAME, consolidated=False).load()
    once = xr.open_zarr(tmp_path / "whole" / sweep.DATASET_NAME, consolidated=False).load()
    xr.testing.assert_identical(resumed.drop_attrs(), once.drop_attrs())
    assert bool(resumed["done"].all())
    np.testing.assert_array_equal(resumed["x"].values, [-1.0, 0.0, 1.0, 2.0, 3.0])
    np.testing.assert_array_equal(resumed["y"].values, [0.0, 1.0])
    # x = 1, y = 1: 1 + 1 + offset 1; x = -1 fails with its reason, x = 0 gives inf (a failure too)
    assert float(resumed["value"].sel(x=1.0, y=1.0)) == 3.0
    assert str(resumed["error"].sel(x=-1.0, y=0.0).values).startswith("ValueError: x must be >= 0")
    assert "not finite" in str(resumed["error"].sel(x=0.0, y=1.0).values)
    assert np.isnan(float(resumed["value"].sel(x=-1.0, y=0.0)))
    xr.testing.assert_identical(sweep.read_dataset(out).drop_attrs(), resumed.drop_attrs())


def test_dataset_has_a_draw_dimension_and_needs_a_grid(helpers, tmp_path):
    spec = sweep.spec_from_dict(_spec())
    sweep.run_sweep(spec, tmp_path / "o", serial=True, progress=False)
    dataset = sweep.read_dataset(tmp_path / "o")
    assert dataset.sizes == {"x": 5, "draw": 3} and "y" in dataset
    result = sweep.read_results(tmp_path / "o")
    np.testing.assert_array_equal(dataset["y"].values.reshape(-1), result["y"])  # case = point * draws + draw
    flat = sweep.spec_from_dict({**_spec(), "grid": {}})
    with pytest.raises(ValueError, match="no grid"):
        sweep.to_dataset(flat, result)


def test_summary_counts_compute_time_and_overhead(helpers, tmp_path, monkeypatch):
    monkeypatch.setenv("SWEEP_DELAY", "0.01")
    spec = sweep.spec_from_dict(_spec(chunk_size=5))
    summary = sweep.run_sweep(spec, tmp_path / "o", serial=True, progress=False)
    assert summary.workers == 1 and summary.computed == 15
    assert 15 * 0.01 <= summary.compute_s <= summary.wall_time_s  # every case sleeps 10 ms inside run_chunk
    assert 0.0 < summary.utilisation <= 1.0
    assert summary.overhead_per_case == pytest.approx((summary.wall_time_s - summary.compute_s) / 15)


def test_local_cluster_workers_run_without_the_profiler(helpers, tmp_path):
    """run_sweep's own LocalCluster hands LOCAL_CLUSTER_CONFIG to its worker processes (the profiler's 10 ms
    stack samples and the 20 ms tick cost the cases CPU; docs/sweeps.md run 9).  Catches: the settings applied
    in the client only, or dask keys that no longer exist (dask.config.get raises on an unknown key)."""
    import dask

    for key in sweep.LOCAL_CLUSTER_CONFIG:
        dask.config.get(key)
    spec = sweep.spec_from_dict({"name": "p", "function": "sweep_helpers:worker_profiling", "outputs": ["value"],
                                 "grid": {"x": {"values": [1.0]}}})
    summary = sweep.run_sweep(spec, tmp_path / "o", workers=1, progress=False)
    assert summary.where == "local:1" and summary.computed == 1
    assert sweep.read_results(tmp_path / "o")["value"].tolist() == [0.0]
    assert dask.config.get("distributed.worker.profile.enabled")  # the client's own config is left alone


@pytest.mark.parametrize("flag, lines", [([], ["#SBATCH --cpus-per-task=1", "#SBATCH --mem=2G", "#SBATCH -t 02:00:00"]),
                                         (["--pbs"], ["#PBS -l select=1:ncpus=1", "#PBS -l walltime=02:00:00"])])
def test_jobqueue_example_builds_its_job_script(flag, lines):
    """The documented dask-jobqueue configuration (examples/jobqueue_sweep.py) builds and writes its batch job
    script without a batch system (--dry-run); submitting to Slurm/PBS is not tested (none here)."""
    pytest.importorskip("dask_jobqueue")
    root = paths.ROOT
    result = subprocess.run([sys.executable, str(root / "examples" / "jobqueue_sweep.py"),
                             str(root / "examples" / "two_ball_monte_carlo.toml"), "--dry-run", *flag],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    for line in lines:
        assert line in result.stdout
    assert "dask_worker" in result.stdout and "--nthreads 1" in result.stdout


def test_the_spec_units_live_in_one_module():
    """Spec parsing, execution and storage are separate modules, and no module of the sweep turns a unit into a
    factor: the one units parser, shared with the case files and calibrate specs, is validation/cases/units.py."""
    folder = Path(sweep.__file__).parent
    for path in folder.glob("*.py"):
        text = path.read_text()
        assert len(text.splitlines()) <= 600, path.name
        assert "math.pi / 180" not in text and "1e-3" not in text and "UNITS[" not in text, path.name
    spec = sweep.spec_from_dict({"name": "u", "function": "math:hypot", "outputs": ["real"],
                                 "grid": {"x": {"values": [1.0, 2.0], "unit": "mm"}}})
    np.testing.assert_allclose(spec.grid["x"], [1e-3, 2e-3])


SWEEP_HELPERS = '''
def square(x, offset=0.0):
    """x^2 + offset [-]; x < 0 raises."""
    if x < 0:
        raise ValueError(f"x must be >= 0, got {x}")
    return {"value": x * x + offset}
'''


@pytest.fixture
def sweep_helpers(tmp_path, monkeypatch):
    return helper_module(tmp_path, monkeypatch, "audit_sweep_helpers", SWEEP_HELPERS)


def _sweep_spec(tmp_path, fixed: str, values: str) -> str:
    path = tmp_path / "spec.toml"
    path.write_text(f'name = "audit"\nfunction = "audit_sweep_helpers:square"\nchunk_size = 2\noutputs = ["value"]\n'
                    f'[fixed]\n{fixed}\n[grid]\nx = {{ values = {values} }}\n')
    return str(path)


VECTOR_HELPERS = '''
import numpy as np

CALLS = []


def vector_square(x):
    """x^2 [-]; raises for the whole batch when any x < 0 (as b2b_analytical does outside four-point contact)."""
    x = np.asarray(x, dtype=float)
    CALLS.append(x.size)
    if np.any(x < 0):
        raise ValueError("x must be >= 0")
    return {"value": x * x}
'''


@pytest.mark.parametrize("fixed, expected", [
    ("ofset = 1.0", "unexpected keyword argument 'ofset'"),  # a misspelt input
    ("", None),                                               # fine: offset has a default
])
def test_sweep_input_names_are_checked_before_any_case_runs(sweep_helpers, tmp_path, capsys, fixed, expected):
    spec = _sweep_spec(tmp_path, fixed, "[1.0, 2.0]")
    out = tmp_path / "out"
    if expected is None:
        assert cli.main(["sweep", spec, "--serial", "--out", str(out), "--no-progress"]) == 0
        return
    # used to run every case, record a TypeError each and exit 0; a wrong use: exit 2, one line
    line = one_error_line(capsys, cli.main(["sweep", spec, "--serial", "--out", str(out), "--no-progress"]))
    assert expected in line and "square(x, offset=0.0)" in line
    assert not out.exists()


def test_sweep_names_the_failure_reasons_and_fails_when_every_case_fails(sweep_helpers, tmp_path, capsys):
    out = tmp_path / "out"
    assert cli.main(["sweep", _sweep_spec(tmp_path, "", "[-2.0, -1.0, 3.0]"), "--serial", "--out", str(out),
                     "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "2 failed with ValueError; the first, case 0: ValueError: x must be >= 0, got -2.0" in printed
    everything_fails = _sweep_spec(tmp_path, "", "[-2.0, -1.0]")
    assert cli.main(["sweep", everything_fails, "--serial", "--out", str(tmp_path / "out2"), "--no-progress"]) == 1
    assert "every case failed" in capsys.readouterr().err


def test_a_vectorised_chunk_with_one_failing_case_stays_vectorised(tmp_path, monkeypatch):
    import importlib

    import numpy as np

    from ballbench.validation import sweep

    helper_module(tmp_path, monkeypatch, "audit_vector_helpers", VECTOR_HELPERS)
    helpers = importlib.import_module("audit_vector_helpers")
    values = [float(v) for v in range(1, 1025)]
    values[700] = -1.0
    spec = sweep.spec_from_dict({"name": "v", "function": "audit_vector_helpers:vector_square", "vectorised": True,
                                 "chunk_size": 1024, "outputs": ["value"], "grid": {"x": {"values": values}}})
    columns = sweep.run_chunk(spec.source, 0, 1024)
    assert [bool(e) for e in columns["error"]].count(True) == 1 and columns["error"][700].startswith("ValueError")
    ok = np.arange(1024) != 700
    np.testing.assert_array_equal(columns["value"][ok], np.asarray(values)[ok] ** 2)
    singles = [size for size in helpers.CALLS if size == 1]
    # the whole chunk used to be recomputed one case at a time: 1 + 1024 calls
    assert len(singles) <= sweep.VECTOR_LEAF and len(helpers.CALLS) <= 2 * 10 + sweep.VECTOR_LEAF


def test_sweep_summary_of_a_serial_or_finished_run_names_no_workers(sweep_helpers, tmp_path, capsys):
    spec = _sweep_spec(tmp_path, "", "[1.0, 2.0]")
    argv = ["sweep", spec, "--serial", "--out", str(tmp_path / "out"), "--no-progress"]
    assert cli.main(argv) == 0
    first = capsys.readouterr().out
    # "--serial" printed "workers computing 0 % of the time"; a resumed run with nothing left printed it too
    assert "workers" not in first and "this process computing" in first
    assert cli.main(argv) == 0
    assert "computing" not in capsys.readouterr().out
