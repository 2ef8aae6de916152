"""Running a sweep: chunks of cases on dask.distributed (or in this process), each written as it arrives.

Chunks of ``chunk_size`` consecutive cases, one task each, run on a
``LocalCluster`` (default), an existing scheduler (``--scheduler ADDRESS``) or
in this process (``--serial``); a bounded window of tasks is in flight, so a
sweep of millions of chunks does not flood the scheduler.  Every finished
chunk is written at once (:mod:`.storage`); the Dataset of a gridded sweep is
rebuilt every :data:`DATASET_EVERY_S` seconds while it runs and when it stops
(also when interrupted).
"""
from __future__ import annotations

import itertools
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from ballbench.validation.sweep.cases import check_inputs, resolve_function, run_chunk
from ballbench.validation.sweep.spec import SweepSpec
from ballbench.validation.sweep.storage import (DATASET_NAME, done_ranges, missing_chunks, prepare, read_results,
                                                write_dataset, write_part)

IN_FLIGHT_MIN, IN_FLIGHT_PER_THREAD = 16, 4  # tasks submitted ahead of the results
DATASET_EVERY_S = 30.0  # rebuild the Dataset from the parts at most this often while a sweep runs [s]
# dask settings of the LocalCluster that run_sweep starts: the workers' statistical profiler (a stack sample of
# every thread each 10 ms, for the dashboard) and the 20 ms event-loop tick cost CPU that the cases need on a
# small machine (docs/sweeps.md, "Throughput and overhead").
# An external cluster keeps its own settings (DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False, docs).
LOCAL_CLUSTER_CONFIG = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s"}


@dataclass(frozen=True)
class SweepSummary:
    """What a call of :func:`run_sweep` did: cases in the sweep, already done before, computed now,
    failed (in the whole directory), wall time [s] of this call, and where ("serial", "local:N" or the address)."""

    n_cases: int
    skipped: int
    computed: int
    failed: int
    wall_time_s: float
    where: str
    out_dir: Path
    compute_s: float = 0.0   # sum over the chunks of the time spent computing them, where they ran [s]
    workers: int = 1         # worker threads that computed (1 for serial)
    reasons: tuple = ()      # failed cases by exception type: (type, count, first case, its error), see failure_reasons

    @property
    def throughput(self) -> float:
        """Cases per second computed by this call."""
        return self.computed / self.wall_time_s if self.wall_time_s > 0 else math.inf

    @property
    def utilisation(self) -> float:
        """Share of the workers' time spent computing cases: ``compute_s / (workers wall)``."""
        return self.compute_s / (self.workers * self.wall_time_s) if self.wall_time_s > 0 else 0.0

    @property
    def overhead_per_case(self) -> float:
        """Worker time not spent computing, per case [s]: ``(workers wall - compute_s) / computed``
        (scheduling, transfer, writing parts, idle workers at the start and end, other jobs on the machine)."""
        return (self.workers * self.wall_time_s - self.compute_s) / self.computed if self.computed else 0.0


def _progress_bar(total: int, initial: int, enabled: bool | None, name: str):
    if enabled is None:
        enabled = sys.stderr.isatty()  # only on a terminal: logs and CI stay clean
    if not enabled:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, initial=initial, desc=name, unit="case", file=sys.stderr)


def run_sweep(spec: SweepSpec, out_dir: str | Path, *, scheduler: str | None = None, workers: int = 2,  # noqa: C901 - the serial and the dask paths share resume, progress and storage
              serial: bool = False, client=None, progress: bool | None = None,
              max_chunks: int | None = None) -> SweepSummary:
    """Run the cases of ``spec`` that ``out_dir`` does not hold yet.

    ``serial`` computes in this process (no dask); otherwise ``client`` (a
    ``dask.distributed.Client``), else a new client of ``scheduler`` (an
    address such as ``tcp://127.0.0.1:8786``), else a ``LocalCluster`` of
    ``workers`` single-threaded worker processes.  ``max_chunks`` stops after
    that many chunks (a partial run; the rest is computed by the next call).
    ``progress``: None shows a bar only when stderr is a terminal.
    """
    out_dir = Path(out_dir)
    check_inputs(spec, resolve_function(spec.function))  # fail early, in the client, before the directory is made
    prepare(out_dir, spec)
    done = done_ranges(out_dir)
    chunks = missing_chunks(spec.n_cases, done, spec.chunk_size)
    skipped = spec.n_cases - sum(stop - start for start, stop in chunks)
    if max_chunks is not None:
        chunks = chunks[:max_chunks]
    bar = _progress_bar(spec.n_cases, skipped, progress, spec.name)
    start_time = time.perf_counter()
    computed = 0
    raw = spec.source
    own_client = None
    last_dataset = [time.perf_counter()]

    compute_s, threads = 0.0, 1

    def written(chunk_cases: int, chunk_compute_s: float) -> None:
        nonlocal computed, compute_s
        computed += chunk_cases
        compute_s += chunk_compute_s
        if bar is not None:
            bar.update(chunk_cases)
        if spec.grid and time.perf_counter() - last_dataset[0] >= DATASET_EVERY_S:
            write_dataset(out_dir, spec)
            last_dataset[0] = time.perf_counter()

    where = "serial" if serial else "nothing left to compute" if not chunks else ""
    try:
        if serial:
            for start, stop in chunks:
                chunk = run_chunk(raw, start, stop)
                write_part(out_dir, spec, chunk)
                written(stop - start, chunk["compute_s"])
        elif chunks:
            import dask
            from dask.distributed import Client, LocalCluster, as_completed

            if client is None:
                if scheduler:
                    own_client = Client(scheduler)
                    where = scheduler
                else:
                    with dask.config.set(LOCAL_CLUSTER_CONFIG):
                        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                               dashboard_address="127.0.0.1:0", host="127.0.0.1")
                    own_client = Client(cluster)
                    where = f"local:{workers}"
                client = own_client
            else:
                where = str(client.scheduler.address)
            # a bounded window of tasks in flight: a sweep of millions of chunks does not flood the scheduler
            threads = sum(client.nthreads().values())
            window = max(IN_FLIGHT_MIN, IN_FLIGHT_PER_THREAD * threads)
            pending = iter(chunks)
            running = as_completed()
            for start, stop in itertools.islice(pending, window):
                running.add(client.submit(run_chunk, raw, start, stop, pure=False))
            for future in running:
                chunk = future.result()  # a task that itself fails (not a case) stops the sweep; parts stay
                write_part(out_dir, spec, chunk)
                written(len(chunk["case"]), chunk["compute_s"])
                future.release()
                following = next(pending, None)
                if following is not None:
                    running.add(client.submit(run_chunk, raw, *following, pure=False))
    finally:
        if bar is not None:
            bar.close()
        if computed or (spec.grid and not (out_dir / DATASET_NAME).exists()):
            write_dataset(out_dir, spec)  # also after an interruption: the Dataset holds what the parts hold
        if own_client is not None:
            cluster = own_client.cluster
            own_client.close()
            if cluster is not None:
                cluster.close()
    wall = time.perf_counter() - start_time
    failed, reasons = 0, ()
    if done_ranges(out_dir):
        columns = read_results(out_dir)
        failed = int(sum(bool(e) for e in columns["error"]))
        reasons = failure_reasons(columns)
    return SweepSummary(spec.n_cases, skipped, computed, failed, wall, where, out_dir, compute_s, threads, reasons)


def failure_reasons(columns: dict) -> tuple[tuple[str, int, int, str], ...]:
    """The failed cases of :func:`read_results` columns grouped by exception type, most frequent first:
    ``(type, count, first case, its error text)``."""
    groups: dict[str, list] = {}
    for case, error in zip(columns["case"], columns["error"]):
        if error:
            kind = error.split(":", 1)[0]
            groups.setdefault(kind, [0, int(case), error])[0] += 1
    return tuple((kind, count, case, text) for kind, (count, case, text)
                 in sorted(groups.items(), key=lambda item: (-item[1][0], item[1][1])))
