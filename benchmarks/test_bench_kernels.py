"""The compiled kernels against today's numpy path, in the same run: the targets of the speed work.

Targets (docs/speed.md): two-ball linear-bearing solve <= 0.2 ms median; 1,000-ball chain <= 10 ms; the
two-ball Monte Carlo (examples/two_ball_monte_carlo.toml, 100,000 draws, case setup included) >= 20,000 cases/s
on this 2-core machine; ``import ballbench.lowmodel`` < 0.5 s without numba, gmsh, pyvista, vtk, matplotlib;
the kernels' first-call cost (compile, or load from numba's disk cache) stated.  The screw targets are in
benchmarks/test_bench_screw.py.

The machine is shared: every figure is a median of CPU time (``time.process_time``) with the baseline (the numpy
path, ``lowmodel.kernels.use_kernels(False)``: the code before the kernels) timed interleaved in the same run,
and the load average printed beside it.  Time per solve is set against its arithmetic: the floating-point
operations the kernel executes (:func:`arithmetic`, counted from the loops of
lowmodel/linear_bearing/ball_kernels.py for the iterations the solve took) divided by the scalar rate this
machine gives such loops now (:func:`scalar_rate`, a dense LU in the same compiled style): the ratio is the
roofline-style figure of merit (1 = the solve is pure arithmetic at that rate).

The chains are also timed against the compiled kernels of commit :data:`BEFORE` (the Levenberg-Marquardt step on
the banded normal equations in every iteration; today's kernel tries the Newton step by a block LU of ``J`` first):
that module is read with ``git show``, kept under the numba cache directory (so it compiles once per machine) and
given to ``ball_fast`` in alternating blocks with today's (skipped without git).

Run: python -m pytest benchmarks/test_bench_kernels.py -s
"""
import importlib.util
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import ball_fast

from kernel_support import compiled_module, first_call_seconds, interleaved
from speed_table import figure, number

ROOT = Path(__file__).resolve().parents[1]
KERNELS = "linear_bearing.ball_kernels"
# flops per ball of the kernels' loops (ball_kernels.py): one evaluation of the chain (4 friction patches of 3 x 44
# flops, slip kinematics, eq 4 rows, Jacobian entries, sin/cos counted as 20 each; the pair loads); below 6 balls
# the normal equations summed over J's nonzeros, J x and J^T r and a dense LU (2/3 size^3); from 6 balls the Newton
# step by the block LU of J (LU of the 8 x 8 pivot block, 2/3 8^3, three columns of M^-1 U, the update of rows 0-2),
# its two sweeps and J x (the Levenberg-Marquardt fallback on the normal equations is not counted)
EVALUATION, NORMAL, PRODUCTS, BLOCK_LU, BLOCK_SOLVE, MATVEC = 900, 640, 240, 780, 220, 120


def arithmetic(n_balls: int, iterations: int, unknowns: int = 8) -> float:
    """Floating-point operations of a kernel solve of ``n_balls`` balls in ``iterations`` Newton iterations (one
    trial evaluation each; rejected steps are not counted, so this is a lower bound)."""
    size = n_balls * unknowns
    if n_balls < 6:
        per_iteration = (EVALUATION + NORMAL + PRODUCTS) * n_balls + (2.0 / 3.0) * size ** 3
    else:
        per_iteration = (EVALUATION + BLOCK_LU + BLOCK_SOLVE + MATVEC) * n_balls
    return EVALUATION * n_balls + iterations * per_iteration


def scalar_rate() -> float:
    """flop/s of the kernels' compiled loop style on this machine now: the dense LU of ball_kernels on 48 x 48."""
    module = kernels.load(KERNELS)
    rng = np.random.default_rng(0)
    matrix = rng.normal(size=(48, 48)) + 48 * np.eye(48)
    rhs, out = rng.normal(size=48), np.empty(48)
    module._lu_solve(matrix.copy(), rhs, out)
    times = []
    for _ in range(200):
        work = matrix.copy()
        start = time.process_time()
        for _ in range(20):
            work[:] = matrix
            module._lu_solve(work, rhs, out)
        times.append((time.process_time() - start) / 20)
    return (2.0 / 3.0 * 48 ** 3 + 2 * 48 ** 2) / float(np.median(times))


@pytest.fixture(scope="module")
def compiled():
    return compiled_module(KERNELS)


BEFORE = "a925e57"  # the chain kernels before the slip angles were eliminated from the pivot blocks


@pytest.fixture(scope="module")
def previous(compiled):
    """lowmodel/linear_bearing/ball_kernels.py as of :data:`BEFORE`, compiled (or loaded from numba's cache) under
    another module name; None without git."""
    try:
        text = subprocess.run(["git", "-C", str(ROOT), "show", f"{BEFORE}:lowmodel/linear_bearing/ball_kernels.py"],
                              check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    folder = Path(os.environ["NUMBA_CACHE_DIR"]).parent / "benchmark_sources"
    path = folder / f"ball_kernels_{BEFORE}.py"
    if not path.exists() or path.read_text() != text:  # a fixed file: numba's cache keys on its path and time stamp
        folder.mkdir(parents=True, exist_ok=True)
        part = path.with_suffix(f".{os.getpid()}.part")
        part.write_text(text)
        part.replace(path)
    spec = importlib.util.spec_from_file_location(f"ball_kernels_{BEFORE}", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    before = _Before(module)
    ball_fast.warm_up(before)
    return before


class _Before:
    """The kernel module of :data:`BEFORE` as ``ball_fast`` calls today's: its ``solve_chain_cases`` takes no scratch
    ``work`` (it allocates its own per solve)."""

    def __init__(self, module):
        self.module = module

    def __getattr__(self, name):
        return getattr(self.module, name)

    def workspace_size(self, n_balls):
        return 0

    def solve_chain_cases(self, *arguments):
        return self.module.solve_chain_cases(*arguments[:-1])


@pytest.mark.parametrize("n_balls", [50, 200, 1000])
def test_chain_against_previous_kernels(compiled, previous, n_balls, monkeypatch):
    if previous is None:
        pytest.skip("no git: the kernels before cannot be read")
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=n_balls)
    gaps = np.zeros(n_balls - 1)
    states = {}
    for name, module in (("now", compiled), ("before", previous)):
        monkeypatch.setattr(ball_fast, "compiled", lambda module=module: module)
        states[name] = b2b.solve(contacts, gaps)
    difference = max(float(np.max(np.abs(getattr(states["now"], field) - getattr(states["before"], field))
                                  / max(np.max(np.abs(getattr(states["before"], field))), 1e-300)))
                     for field in ("ball_velocity", "omega", "friction_force", "b2b_force"))
    repeats, block = {50: (31, 4), 200: (21, 2), 1000: (15, 1)}[n_balls]
    times = {"now": [], "before": []}
    for _ in range(repeats):
        for name, module in (("now", compiled), ("before", previous)):
            monkeypatch.setattr(ball_fast, "compiled", lambda module=module: module)
            b2b.solve(contacts, gaps)
            start = time.process_time()
            for _ in range(block):
                b2b.solve(contacts, gaps)
            times[name].append((time.process_time() - start) / block)
    now, before = (1e3 * float(np.median(times[name])) for name in ("now", "before"))
    target = " (target <= 10 ms)" if n_balls == 1000 else ""
    print(f"\n{n_balls}-ball B2B chain, compiled: {now:.3f} ms now{target}, {before:.3f} ms with the kernels of "
          f"{BEFORE} (x {before / now:.2f}); minimum {1e3 * min(times['now']):.3f} / {1e3 * min(times['before']):.3f} "
          f"ms; {states['now'].iterations} / {states['before'].iterations} iterations; states apart by "
          f"{difference:.1e} (largest relative); load average {os.getloadavg()[0]:.2f}")


def test_import_is_light(record_property):
    code = ("import sys, time\nstart = time.perf_counter()\nimport ballbench.lowmodel\n"
            "print(time.perf_counter() - start, sorted({n.split('.')[0] for n in sys.modules} & "
            "{'numba', 'llvmlite', 'gmsh', 'pyvista', 'vtk', 'matplotlib'}))")
    seconds = []
    for _ in range(5):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
        value, heavy = out.split(" ", 1)
        seconds.append(float(value))
    print(f"\nimport ballbench.lowmodel: {1e3 * float(np.median(seconds)):.0f} ms median of 5 fresh processes "
          f"(target < 500 ms), heavy modules loaded: {heavy.strip()}; load average {os.getloadavg()[0]:.2f}")
    assert heavy.strip() == "[]"
    figure(record_property, "import", "`import ballbench.lowmodel` in a fresh process, median of 5 (numba, gmsh, "
           "pyvista, vtk, matplotlib not loaded)", 1e3 * float(np.median(seconds)), "ms", target="< 500", clock="wall")


def test_first_call_cost(compiled):
    """Cold: a fresh numba cache (every kernel compiled); warm: the cache of this run (loaded from disk)."""
    cold, warm = first_call_seconds(KERNELS)
    print(f"\nkernels' first call in a process: compile {cold:.1f} s with an empty numba cache, {warm:.2f} s from "
          f"the disk cache (NUMBA_CACHE_DIR, default ~/.cache/ballbench/numba); load average "
          f"{os.getloadavg()[0]:.2f}")


def _two_ball():
    return b2b.module_contacts(math.radians(2.0), -0.6)


@pytest.mark.parametrize("n_balls", [1, 2, 50, 200, 1000])
def test_one_case_solves(compiled, n_balls, record_property):
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=n_balls)
    gaps = np.zeros(n_balls - 1)
    if n_balls == 1:
        def solve():
            return bearing_ball.solve(contacts)
    else:
        def solve():
            return b2b.solve(contacts, gaps)
    state = solve()
    repeats, block = {1: (41, 20), 2: (41, 20), 50: (31, 4), 200: (21, 2), 1000: (15, 1)}[n_balls]
    new, old = interleaved(solve, repeats, block)
    rate = scalar_rate()
    flops = arithmetic(n_balls, state.iterations, 7 if n_balls == 1 else 8)
    target = {2: " (target <= 0.2 ms)", 1000: " (target <= 10 ms)"}.get(n_balls, "")
    name = "single ball" if n_balls == 1 else f"{n_balls}-ball B2B chain"
    print(f"\n{name}: compiled {1e3 * new:.3f} ms{target}, numpy path {1e3 * old:.3f} ms (x {old / new:.1f}); "
          f"{state.iterations} iterations, {flops:.3g} flop = {flops / rate * 1e3:.3f} ms at the measured "
          f"{rate / 1e9:.2f} Gflop/s of compiled loops: figure of merit {flops / rate / new:.2f} (1 = pure "
          f"arithmetic); load average {os.getloadavg()[0]:.2f}")
    label = {1: "single-ball solve", 2: "two-ball B2B solve"}.get(n_balls, f"{n_balls:,}-ball B2B chain")
    figure(record_property, f"bearing.{n_balls}", f"{label} (linear bearing), compiled, median", 1e3 * new, "ms",
           target={2: "<= 0.2", 1000: "<= 10"}.get(n_balls), baseline=f"numpy path {number(1e3 * old)} ms")


def _spec(draws: int, vectorised: bool, chunk: int):
    from ballbench.validation import sweep

    raw = dict(sweep.load_spec(ROOT / "examples" / "two_ball_monte_carlo.toml").source)
    raw["random"] = {**raw["random"], "draws": draws}
    raw["vectorised"] = vectorised
    raw["chunk_size"] = chunk
    return sweep.spec_from_dict(raw)


def test_monte_carlo(compiled, tmp_path, record_property):
    """Serial chunk rates of the new vectorised chunk (kernels, one batch per chunk) and of today's code (numpy
    path, one case per call, chunks of 250) on the same draws; then the whole 100,000-draw example on a
    LocalCluster of two workers (started before the clock; its start time printed)."""
    from dask.distributed import Client, LocalCluster

    from ballbench.validation import sweep

    new_spec, old_spec = _spec(20000, True, 5000), _spec(20000, False, 250)
    sweep.run_chunk(new_spec.source, 0, 8)  # imports, friction map, kernels
    kernels.use_kernels(False)
    sweep.run_chunk(old_spec.source, 0, 2)
    start = time.process_time()
    sweep.run_chunk(old_spec.source, 0, 300)
    old_rate = 300 / (time.process_time() - start)
    kernels.use_kernels(None)
    start = time.process_time()
    result = sweep.run_chunk(new_spec.source, 0, 20000)
    new_rate = 20000 / (time.process_time() - start)
    failed = sum(1 for error in result["error"] if error)
    load = os.getloadavg()[0]
    print(f"\ntwo-ball Monte Carlo, one process: vectorised chunk with kernels {new_rate:.0f} cases/s (20,000 "
          f"draws, {failed} failed), today's code {old_rate:.0f} cases/s (300 draws, numpy path, one case per "
          f"call): x {new_rate / old_rate:.0f}; load average {load:.2f}")
    figure(record_property, "monte_carlo.process", "two-ball Monte Carlo in one process (vectorised chunk of 20,000 "
           "draws, setup included)", new_rate, "cases/s",
           baseline=f"numpy path, one case per call: {number(old_rate)} cases/s")
    spec = sweep.load_spec(ROOT / "examples" / "two_ball_monte_carlo.toml")
    began = time.perf_counter()
    import dask

    with dask.config.set(sweep.LOCAL_CLUSTER_CONFIG):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address="127.0.0.1:0",
                               host="127.0.0.1")
    with Client(cluster) as client:
        client.run(sweep.run_chunk, spec.source, 0, 8)  # warm the workers: imports, friction map, kernels
        started = time.perf_counter() - began
        summary = sweep.run_sweep(spec, tmp_path / "mc", client=client, progress=False)
    cluster.close()
    print(f"two-ball Monte Carlo, the example ({spec.n_cases} draws, chunks of {spec.chunk_size}) on "
          f"LocalCluster(2): {summary.throughput:.0f} cases/s (target >= 20,000), wall {summary.wall_time_s:.1f} s, "
          f"{summary.failed} failed; cluster start and warm-up {started:.1f} s before the clock; today's "
          f"code: {old_rate:.0f} cases/s per core (260 cases/s on two idle workers, measured before the kernels); "
          f"load average {os.getloadavg()[0]:.2f}")
    assert summary.computed == spec.n_cases
    figure(record_property, "monte_carlo.cluster", f"two-ball Monte Carlo, the example's {spec.n_cases:,} draws on "
           "LocalCluster(2)", summary.throughput, "cases/s", target=">= 20000", clock="wall")
