"""Run scenes: time, check, collect; never let one scene's crash hide the others."""
from __future__ import annotations

import ctypes
import gc
import sys
import threading
import time
import traceback
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable

from ballbench.validation.scene import NotApplicable, Run, Scene, SceneResult

GB = 1e9  # bytes


def reset_peak_memory() -> bool:
    """Reset this process's peak resident memory to its current resident memory (Linux:
    ``/proc/self/clear_refs``); False where it cannot."""
    try:
        with open("/proc/self/clear_refs", "w") as handle:
            handle.write("5")
    except OSError:
        return False
    return True


def _status_gb(key: str) -> float:
    """The line ``key`` (e.g. ``VmHWM``) of ``/proc/self/status`` [GB]; 0.0 where the system does not say."""
    try:
        with open("/proc/self/status") as handle:
            for line in handle:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) * 1024 / GB
    except (OSError, ValueError, IndexError):
        pass
    return 0.0


def peak_memory_gb() -> float:
    """This process's peak resident memory since the last :func:`reset_peak_memory` [GB] (Linux ``VmHWM``);
    0.0 where the system does not say."""
    return _status_gb("VmHWM")


def resident_memory_gb() -> float:
    """This process's resident memory now [GB] (Linux ``VmRSS``); 0.0 where the system does not say."""
    return _status_gb("VmRSS")


def _c_library():
    try:
        return ctypes.CDLL(None)
    except OSError:
        return None


_LIBC = _c_library()


def release_free_memory() -> None:
    """Collect Python's garbage and hand the C heap's free pages back to the system (glibc ``malloc_trim``;
    a no-op elsewhere), so that the resident memory is what live objects hold."""
    gc.collect()
    trim = getattr(_LIBC, "malloc_trim", None)
    if trim is not None:
        trim(0)


@dataclass(frozen=True)
class MemoryUse:
    """A scene's memory [GB] (docs/validation.md, "Memory"): ``scene_peak_gb``, the peak resident memory while the
    scene ran above the resident memory at its start (after :func:`release_free_memory`), what the scene itself
    needed; ``process_peak_gb``, the process's peak while the scene ran (what earlier scenes left loaded
    included).  Both 0.0 where not measured (no ``/proc``, or another scene ran in the same process meanwhile)."""

    scene_peak_gb: float = 0.0
    process_peak_gb: float = 0.0


# scenes running now in this process (a dask worker with several threads runs several), each with whether another
# scene ran beside it: the peak resident memory is the process's, so such a scene's own peak is not measured
_RUNNING: dict[int, bool] = {}
_RUNNING_LOCK = threading.Lock()


class SceneMemory:
    """Measures one scene's memory: :meth:`start` before the scene, :meth:`stop` after it (:class:`MemoryUse`)."""

    def start(self) -> None:
        release_free_memory()
        with _RUNNING_LOCK:
            self.key = id(self)
            shared = bool(_RUNNING)
            for other in _RUNNING:
                _RUNNING[other] = True
            _RUNNING[self.key] = shared
            self.measured = not shared and reset_peak_memory()
        self.start_gb = resident_memory_gb()

    def stop(self) -> MemoryUse:
        process_peak = peak_memory_gb()
        with _RUNNING_LOCK:
            shared = _RUNNING.pop(self.key)
        if shared or not self.measured or process_peak <= 0.0 or self.start_gb <= 0.0:
            return MemoryUse()
        return MemoryUse(max(process_peak - self.start_gb, 0.0), process_peak)


def run_scene(scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = False,
              progress_lines: bool = False, should_stop: Callable[[], bool] | None = None) -> SceneResult:
    """Run one scene; an exception becomes a failed result carrying its message.

    The result carries the scene's own peak resident memory (``scene_peak_memory_gb``: the peak while it ran
    above the resident memory at its start, after the garbage of earlier scenes is collected and the C heap's free
    pages are handed back; :class:`SceneMemory`), the process's peak while it ran (``peak_memory_gb``: the
    interpreter and what earlier scenes left loaded included) and the memory the scene declares
    (``declared_memory_gb``, :meth:`Scene.memory_for`).

    The traceback of a failing scene goes to ``<out>/<scene>/error.txt`` (an
    artifact of the report), not to the terminal.  Ctrl-C inside the scene, or a stop request
    (``should_stop()`` true at one of the scene's steps, :meth:`Run.checkpoint`), returns a result marked
    ``interrupted``.  ``progress_lines``: one line per step on stderr when there is no bar.

    :class:`~ballbench.validation.scene.NotApplicable` from a case file's scene (tag ``case``) gives a result
    marked ``not_applicable`` with its reason; from a registered scene it is an error like any exception.
    """
    run = Run(scene, fidelity, out_dir, show_progress=show_progress, progress_lines=progress_lines,
              should_stop=should_stop)
    memory = SceneMemory()
    memory.start()
    start = time.perf_counter()
    error = ""
    not_applicable = ""
    interrupted = False
    try:
        try:
            scene.function(run)
        except NotApplicable as exc:
            if "case" not in scene.tags:
                raise
            not_applicable = exc.reason
    except KeyboardInterrupt:
        interrupted = True
        error = "interrupted by the user (Ctrl-C) before the scene finished"
    except Exception as exc:  # a scene failure is a result, not a crash of the suite
        error = f"{type(exc).__name__}: {exc}"
        try:
            path = run.path("error.txt")
            path.write_text(traceback.format_exc())
            run.add_artifact(path)
        except OSError:
            pass
    wall = time.perf_counter() - start
    used = memory.stop()
    if not error and not not_applicable and not run.outputs and not run.inconclusive_reasons:
        error = "scene recorded no checked output"
    return run.result(wall, error, interrupted, used.process_peak_gb, not_applicable, used.scene_peak_gb)


def run_scenes(scenes: Iterable[Scene], fidelity: str, out_dir: Path, *, show_progress: bool = False,
               on_result: Callable[[SceneResult], None] | None = None,
               should_stop: Callable[[], bool] = lambda: False,
               progress_lines: bool = False) -> tuple[list[SceneResult], bool]:
    """Run ``scenes`` in order; returns ``(results, stopped)``.

    ``on_result`` is called after each scene (e.g. to print its status line);
    a scene stops at its next step and the loop before the next scene when ``should_stop()`` is true or a
    scene was interrupted (``stopped`` is then True, also when the request came during the last scene).
    """
    scenes = list(scenes)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    results: list[SceneResult] = []
    bar = None
    if show_progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(scenes), desc="scenes", unit="scene", file=sys.stderr)
    stopped = False
    try:
        for scene in scenes:
            if should_stop():
                stopped = True
                break
            if bar is not None:
                bar.set_postfix_str(scene.name)
            if progress_lines and bar is None:
                print(f"ballbench: scene {len(results) + 1} of {len(scenes)}: {scene.name}", file=sys.stderr,
                      flush=True)
            result = run_scene(scene, fidelity, out_dir, show_progress=show_progress, progress_lines=progress_lines,
                               should_stop=should_stop)
            results.append(result)
            if bar is not None:
                bar.update()
            if on_result is not None:
                if bar is not None:
                    with bar.external_write_mode():
                        on_result(result)
                else:
                    on_result(result)
            if result.interrupted:
                stopped = True
                break
        if should_stop():  # a stop requested while the last scene ran is still a stop (exit 130)
            stopped = True
    finally:
        if bar is not None:
            bar.close()
    return results, stopped


# dask settings of the LocalCluster that run_scenes_distributed starts: those of the sweep (no statistical profiler);
# worker processes that may start processes of their own (a scene that runs a sweep starts its own LocalCluster; a
# daemonic worker process may not have children); and the BLAS / OpenMP threads of a serial run: dask's nanny sets
# OMP/MKL/OPENBLAS_NUM_THREADS=1 by default, and another thread count sums the FE and BLAS products in another order
# (results equal to round-off, not to the bit; docs/validation.md, "Distributed runs")
LOCAL_CLUSTER_CONFIG = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s",
                        "distributed.worker.daemon": False,
                        "distributed.nanny.pre-spawn-environ": {"MALLOC_TRIM_THRESHOLD_": 65536}}


def run_scenes_distributed(scenes: Iterable[Scene], fidelity: str, out_dir: Path, *, workers: int = 2,
                           scheduler: str | None = None,
                           on_result: Callable[[SceneResult], None] | None = None,
                           should_stop: Callable[[], bool] = lambda: False) -> tuple[list[SceneResult], bool]:
    """Run ``scenes`` as dask.distributed tasks, one task per scene, on a LocalCluster of ``workers``
    single-threaded worker processes or on the cluster of ``scheduler`` (an address such as
    ``tcp://127.0.0.1:8786``; start its workers with ``--nthreads 1``, so that one worker never holds two
    scenes' FE meshes at once); returns ``(results in the order of scenes, stopped)`` like :func:`run_scenes`.

    Each scene runs in a worker exactly as :func:`run_scene` runs it serially (same code, same inputs, writing
    into ``out_dir/<scene>/``, which must be reachable by the workers): the results equal a serial run's,
    timings aside.  The most expensive scenes are submitted first.  A stop request (first Ctrl-C) cancels the
    scenes not yet finished; their results are left out and ``stopped`` is True.

    Memory: each scene reserves the resident memory it declares (:meth:`Scene.memory_for`) as the dask
    resource ``memory`` [bytes], so that a worker never runs scenes whose declared memory together exceeds
    its own.  The local cluster's workers each declare the machine's memory over ``workers``; the workers of
    an external cluster declare theirs at start (``dask worker ADDRESS --nthreads 1 --resources
    memory=24e9``), and where none does, the scenes run unreserved (said on stderr).  A scene that declares
    more than the largest worker has reserves that worker whole (said on stderr).
    """
    import dask
    from dask.distributed import Client, LocalCluster, as_completed

    scenes = list(scenes)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cluster = None
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        if scheduler:
            client = Client(scheduler)
        else:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address="127.0.0.1:0", host="127.0.0.1",
                                   resources={"memory": machine_memory_bytes() / workers})
            client = Client(cluster)
    results: dict[str, SceneResult] = {}
    stopped = False
    try:
        capacity = worker_memory_bytes(client)
        if capacity <= 0:
            print("ballbench: the workers declare no memory resource, the scenes run unreserved (start each "
                  "worker with --resources memory=BYTES)", file=sys.stderr, flush=True)
        order = sorted(scenes, key=lambda s: -s.cost_s)
        futures = {}
        for scene in order:
            reserve = memory_reservation(scene, fidelity, capacity)
            futures[client.submit(run_scene, scene, fidelity, out_dir, pure=False, key=f"scene-{scene.name}",
                                  resources=reserve)] = scene
        running = as_completed(futures)
        for future in running:
            result = future.result()
            results[result.name] = result
            if on_result is not None:
                on_result(result)
            if should_stop():
                stopped = True
                client.cancel([f for f in futures if not f.done()])
                break
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return [results[s.name] for s in scenes if s.name in results], stopped


def machine_memory_bytes() -> float:
    """The machine's physical memory [bytes] (psutil, which dask.distributed installs)."""
    import psutil

    return float(psutil.virtual_memory().total)


def worker_memory_bytes(client) -> float:
    """The largest ``memory`` resource a worker of ``client``'s cluster declares [bytes]; 0 if none does."""
    workers = client.scheduler_info().get("workers", {})
    return max((float(w.get("resources", {}).get("memory", 0.0)) for w in workers.values()), default=0.0)


def memory_reservation(scene: Scene, fidelity: str, capacity: float) -> dict | None:
    """The dask ``resources`` of ``scene``'s task: its declared memory [bytes], at most ``capacity`` (the
    largest worker's, then the scene takes that worker whole); None when no worker declares memory."""
    need = scene.memory_for(fidelity) * GB
    if capacity <= 0:
        return None
    if need > capacity:
        print(f"ballbench: {scene.name} declares {need / GB:.1f} GB, more than the largest worker's "
              f"{capacity / GB:.1f} GB: it takes that worker whole", file=sys.stderr, flush=True)
        need = capacity
    return {"memory": need}
