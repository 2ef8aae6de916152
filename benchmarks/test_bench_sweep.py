"""Sweep throughput on dask.distributed against the serial speed, and the scheduler overhead per case.

Issue 13 target: LocalCluster throughput (cases/s) >= 80 % of the serial speed times the number of workers
for the linear-bearing two-ball Monte Carlo (examples/two_ball_monte_carlo.toml, low-order numerical model,
about 8 ms per case).  The overhead per case is ``(workers x wall - serial compute) / cases``; for a
no-op model (``builtins:dict``) it is the pure cost of tasks, transfer and Parquet writing.

The machine is shared (2 cores); the load average at the start is printed with every figure, and `cpu_scaling`
(two spinning processes against one, measured just before) says how much of the second core was ours;
`two_process_rate` (two plain processes running the serial loop on the two halves at once, no dask) is what
this machine gives two single-threaded workers at that moment.  The cluster is started with
`sweep.LOCAL_CLUSTER_CONFIG`, as `ballbench sweep` starts it.

Run: python -m pytest benchmarks/test_bench_sweep.py -s
"""
import os
import time
from pathlib import Path

import pytest

from ballbench.validation import sweep

ROOT = Path(__file__).resolve().parents[1]
WORKERS = 2


@pytest.fixture(scope="module")
def client():
    import dask
    from dask.distributed import Client, LocalCluster

    with dask.config.set(sweep.LOCAL_CLUSTER_CONFIG):  # the settings of run_sweep's own LocalCluster
        cluster = LocalCluster(n_workers=WORKERS, threads_per_worker=1, processes=True,
                               dashboard_address="127.0.0.1:0", host="127.0.0.1")
    with Client(cluster) as c:
        yield c
    cluster.close()


def _monte_carlo(cases: int, chunk: int) -> sweep.SweepSpec:
    raw = dict(sweep.load_spec(ROOT / "examples" / "two_ball_monte_carlo.toml").source)
    raw["random"] = {**raw["random"], "draws": cases}
    raw["chunk_size"] = chunk
    return sweep.spec_from_dict(raw)


def _spin(seconds: float) -> int:
    count, end = 0, time.perf_counter() + seconds
    while time.perf_counter() < end:
        for _ in range(10000):
            count += 1
    return count


def cpu_scaling(seconds: float = 3.0) -> float:
    """Work of two spinning processes together over that of one alone, now: 2.0 when two idle cores are ours,
    1.0 when other jobs leave the equivalent of one.  No LocalCluster(2) can beat this factor x serial."""
    import multiprocessing

    one = _spin(seconds)
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        two = sum(pool.map(_spin, [seconds, seconds]))
    return two / (0.5 * (one + _spin(seconds)))


def _serial_half(args) -> float:
    raw, first, stop, chunk = args
    sweep.run_chunk(raw, first, first + 1)  # warm-up, as _serial_seconds
    start = time.perf_counter()
    for begin in range(first, stop, chunk):
        sweep.run_chunk(raw, begin, min(begin + chunk, stop))
    return time.perf_counter() - start


def two_process_rate(spec: sweep.SweepSpec) -> float:
    """Cases/s of two plain processes (no dask) each running the serial loop over one half of the cases at the
    same time: what this machine gives two single-threaded workers now, the ceiling of any LocalCluster(2)."""
    import multiprocessing

    half = spec.n_cases // 2
    jobs = [(spec.source, 0, half, spec.chunk_size), (spec.source, half, spec.n_cases, spec.chunk_size)]
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        seconds = pool.map(_serial_half, jobs)
    return spec.n_cases / max(seconds)


def _serial_seconds(spec: sweep.SweepSpec) -> float:
    chunks = sweep.missing_chunks(spec.n_cases, [], spec.chunk_size)
    sweep.run_chunk(spec.source, 0, 1)  # warm-up: friction map and imports
    start = time.perf_counter()
    for first, stop in chunks:
        sweep.run_chunk(spec.source, first, stop)
    return time.perf_counter() - start


def _report(benchmark, name, spec, serial_s, wall_s, target=""):
    serial_rate = spec.n_cases / serial_s
    rate = spec.n_cases / wall_s
    efficiency = rate / (WORKERS * serial_rate)
    overhead = (WORKERS * wall_s - serial_s) / spec.n_cases
    load = os.getloadavg()[0]
    benchmark.extra_info.update(cases=spec.n_cases, chunk_size=spec.chunk_size, serial_cases_per_s=serial_rate,
                                cluster_cases_per_s=rate, efficiency=efficiency, overhead_per_case_s=overhead,
                                load_average=load)
    print(f"\n{name}: {spec.n_cases} cases, chunks of {spec.chunk_size}: serial {serial_rate:.1f} cases/s, "
          f"LocalCluster({WORKERS}) {rate:.1f} cases/s = {100 * efficiency:.0f} % of {WORKERS} x serial"
          f"{target}; overhead {overhead * 1e3:.3f} ms per case; load average {load:.2f}")
    return efficiency


@pytest.mark.parametrize("chunk", [100, 250])
def test_monte_carlo_throughput(benchmark, client, tmp_path, chunk):
    """Serial before and after the LocalCluster run, on the same cases, in the same run: the ratio uses their mean,
    and the drift between the two serial runs shows how much the machine's load moved meanwhile.  The workers'
    own compute time (SweepSummary.compute_s) splits the cluster's loss into slower computing (load: the
    scheduler and the client share the 2 cores with the workers) and time not computing (overhead)."""
    spec = _monte_carlo(2000, chunk)
    scaling = cpu_scaling()
    before_s = _serial_seconds(spec)
    client.run(sweep.run_chunk, spec.source, 0, 1)  # warm the workers the same way
    runs = iter(range(100))

    def cluster_run():
        return sweep.run_sweep(spec, tmp_path / f"run{next(runs)}", client=client, progress=False)

    summary = benchmark.pedantic(cluster_run, rounds=1, iterations=1)
    after_s = _serial_seconds(spec)
    pair_rate = two_process_rate(spec)
    of_pair = spec.n_cases / summary.wall_time_s / pair_rate
    assert summary.computed == spec.n_cases
    serial_s = 0.5 * (before_s + after_s)
    _report(benchmark, "two-ball Monte Carlo", spec, serial_s, summary.wall_time_s, " (target >= 80 %)")
    slowdown = summary.compute_s / serial_s  # worker compute time over serial compute time, same cases
    benchmark.extra_info.update(cpu_scaling=scaling, serial_before_s=before_s, serial_after_s=after_s,
                                two_process_cases_per_s=pair_rate,
                                of_two_processes=of_pair,
                                worker_compute_s=summary.compute_s,
                                utilisation=summary.utilisation, compute_slowdown=slowdown,
                                overhead_not_computing_per_case_s=summary.overhead_per_case)
    print(f"  serial {before_s:.2f} s before, {after_s:.2f} s after; workers computed {summary.compute_s:.2f} s "
          f"({slowdown:.3f} x serial: CPU shared with scheduler, client and other jobs), busy "
          f"{100 * summary.utilisation:.1f} % of {WORKERS} x {summary.wall_time_s:.2f} s; not computing "
          f"{1e3 * summary.overhead_per_case:.3f} ms per case; two spinning processes did {scaling:.2f} x the work "
          f"of one just before (a rough reading of the CPU left to us: the load moves within seconds); two plain "
          f"processes (no dask) {pair_rate:.1f} cases/s, the cluster {of_pair:.0%} of that")


@pytest.mark.parametrize("chunk", [1, 250])
def test_scheduler_overhead_per_case(benchmark, client, tmp_path, chunk):
    cases = 200 if chunk == 1 else 20000
    spec = sweep.spec_from_dict({"name": "null", "function": "builtins:dict", "outputs": ["y"], "chunk_size": chunk,
                                 "fixed": {"y": 0.0}, "grid": {"x": {"linspace": [0.0, 1.0, cases]}}})
    serial_s = _serial_seconds(spec)
    runs = iter(range(100))

    def cluster_run():
        return sweep.run_sweep(spec, tmp_path / f"run{next(runs)}", client=client, progress=False)

    summary = benchmark.pedantic(cluster_run, rounds=1, iterations=1)
    assert summary.computed == cases
    _report(benchmark, "no-op model (scheduler, transfer, Parquet)", spec, serial_s, summary.wall_time_s)
