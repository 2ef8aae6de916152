"""Steady rolling contact with stick and slip: exact half-space solves, FASTSIM throughput.

Targets (docs/rolling_contact.md, 'Costs'): one exact half-space solve on 35 x 35 cells <= 100 ms and on 11 x 11
cells <= 2 ms; FASTSIM >= 1e4 contacts per second; the FE-compliance solve of one patch within 10x the
half-space solve of the same grid (benchmarks/test_bench_fem_rolling.py, it needs a mesh).  CONTACT's own
timing table (perfc_test/get_times.ref_out, 2016): 133 ms (35 x 35) and 1.6 ms (11 x 11) per case, normal and
tangential problem, on grids whose contact spans mx - 4 cells (31 and 7 cells across).

Two grids are timed per size: ``cells=(n, n)`` of :func:`steady_rolling` (n cells across the ellipse, plus one
empty ring: the harder problem) and CONTACT's (the contact across n - 4 cells, ``cells=(n - 4, n - 4)``).
Wall and CPU (process) times are printed with the load average and the cost of one small numpy call in
this run (about 0.5 us on an idle machine): the machine is shared, and a solve of 11 x 11 cells is some
thousand such calls.  Run: ``.venv/bin/python -m pytest benchmarks/test_bench_rolling.py -s``.

The previous path is timed beside the current one in the same run: the rolling modules of commit
:data:`BEFORE` (before ``prepare_rolling``; every call rebuilt the grid, pressure, checks and contact data) are
read with ``git show`` into a temporary package and called with the same inputs (skipped without git).  Three
figures per grid: that code, today's ``steady_rolling`` (which keeps its prepared contacts) and
``prepare_rolling(...).solve`` (the sweep's path), the last on its numpy path and on its compiled one
(:mod:`lowmodel.contact.rolling_kernels`, where numba is installed: prepared grids up to ``DIRECT_CELLS`` contact
cells); median CPU time of alternating blocks of solves.  The kernels' first-use cost is printed too: compiling
into an empty numba cache and loading from it, each in a fresh process.
"""
from __future__ import annotations

import importlib
import importlib.util
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.contact import fastsim, rolling, rolling_newton

from speed_table import figure, number

A, B, FORCE, G, NU, MU = 6.304e-3, 12.61e-3, 106.7e3, 82e9, 0.28, 0.33  # CONTACT's tractcurv contact
CASES = ((0.4e-3, 0.0, 0.0), (1.2e-3, 0.0, 0.0), (2.4e-3, 0.0, 0.0), (0.0, 0.0, 0.1), (1e-3, 0.5e-3, 1.0))


def _call_overhead_us() -> float:
    a = np.ones(200)
    start = time.perf_counter()
    for _ in range(2000):
        np.add(a, a)
    return (time.perf_counter() - start) / 2000 * 1e6


BEFORE = "2ef4ec3764e10dce631759b403a4b8da6e6dc6be"  # the rolling modules before prepare_rolling
_MODULES = ("rolling", "rolling_input", "rolling_operators", "rolling_newton")


def _previous_rolling(tmp_path_factory):
    """``lowmodel.contact.rolling`` as of :data:`BEFORE`, imported from a temporary package (None without git)."""
    root = pathlib.Path(__file__).resolve().parents[1]
    package = tmp_path_factory.mktemp("before") / "ballbench_rolling_before"
    package.mkdir()
    (package / "__init__.py").write_text("")
    for name in _MODULES:
        try:
            text = subprocess.run(["git", "-C", str(root), "show", f"{BEFORE}:lowmodel/contact/{name}.py"],
                                  check=True, capture_output=True, text=True).stdout
        except (OSError, subprocess.CalledProcessError):
            return None
        text = text.replace("from ballbench.lowmodel.contact import rolling_newton",
                            "from ballbench_rolling_before import rolling_newton")
        (package / f"{name}.py").write_text(text.replace("ballbench.lowmodel.contact.rolling",
                                                         "ballbench_rolling_before.rolling"))
    sys.path.insert(0, str(package.parent))
    try:
        return importlib.import_module("ballbench_rolling_before.rolling")
    finally:
        sys.path.remove(str(package.parent))


@pytest.fixture(scope="module")
def previous(tmp_path_factory):
    return _previous_rolling(tmp_path_factory)


def _solve_all(cells, module=rolling):
    return [module.steady_rolling(A, B, FORCE, G, NU, MU, xi, eta, phi, cells) for xi, eta, phi in CASES]


def _with_kernels(enabled, run):
    def switched():
        kernels.use_kernels(enabled)
        try:
            return run()
        finally:
            kernels.use_kernels(None)
    return switched


@pytest.fixture(scope="module")
def compile_seconds(tmp_path_factory):
    """Wall seconds of the rolling kernels' first load in a fresh process: into an empty numba cache (compile), then
    from that cache; None without numba."""
    if importlib.util.find_spec("numba") is None:
        return None
    cache = tmp_path_factory.mktemp("numba_cache")
    code = ("from ballbench.lowmodel import kernels; from ballbench.lowmodel.contact import rolling_newton as r; "
            "m = kernels.load(r.KERNELS); print(kernels.load_seconds(r.KERNELS) if m is not None else 'nan')")
    seconds = []
    for _ in range(2):
        out = subprocess.run([sys.executable, "-c", code], env={**os.environ, "NUMBA_CACHE_DIR": str(cache),
                                                                "BALLBENCH_KERNELS": "1"},
                             capture_output=True, text=True, check=True).stdout
        seconds.append(float(out.split()[-1]))
    return tuple(seconds)


def _cpu_per_solve(paths, rounds):
    """CPU [ms] per solve of each path (name -> callable solving CASES), alternating blocks: ``{name: (median,
    min)}`` over the blocks (the minimum is the figure least disturbed by the other jobs on the machine)."""
    times = {name: [] for name in paths}
    for _ in range(rounds):
        for name, run in paths.items():
            cpu = time.process_time()
            run()
            times[name].append((time.process_time() - cpu) / len(CASES) * 1e3)
    return {name: (float(np.median(values)), float(np.min(values))) for name, values in times.items()}


@pytest.mark.parametrize("n, target_ms", [(11, 2.0), (35, 100.0)])
def test_bench_exact_half_space(benchmark, previous, compile_seconds, n, target_ms, record_property):
    compiled = kernels.load(rolling_newton.KERNELS) is not None
    if compile_seconds is not None and n <= 11:
        print(f"\nrolling kernels' first load in a fresh process: {compile_seconds[0]:.1f} s compiling into an empty "
              f"numba cache, {compile_seconds[1]:.2f} s from the cache (wall; load average {os.getloadavg()[0]:.1f})")
        for key, label, seconds in (("compile", "compiling into an empty numba cache", compile_seconds[0]),
                                    ("cache", "from numba's disk cache", compile_seconds[1])):
            figure(record_property, f"rolling.first_load.{key}", f"rolling kernels' first load in a fresh process, "
                   f"{label}", seconds, "s", target="stated", clock="wall")
    for cells, label in (((n, n), f"{n} x {n} across the contact"), ((n - 4, n - 4), f"CONTACT's {n} x {n}")):
        prepared = rolling.prepare_rolling(A, B, FORCE, G, NU, MU, cells)

        def solve_prepared(prepared=prepared):
            return [prepared.solve(*case) for case in CASES]
        paths = {"steady_rolling": lambda cells=cells: _solve_all(cells),
                 "prepared": _with_kernels(False, solve_prepared)}
        if compiled:
            paths["compiled"] = _with_kernels(True, solve_prepared)
            for numpy_result, kernel_result in zip(paths["prepared"](), paths["compiled"]()):
                assert (np.max(np.abs(numpy_result.traction - kernel_result.traction))
                        <= 1e-12 * MU * np.max(numpy_result.pressure))
                assert numpy_result.iterations == kernel_result.iterations
                assert np.array_equal(numpy_result.stick, kernel_result.stick)
        if previous is not None:
            paths["before"] = lambda cells=cells: _solve_all(cells, previous)
        for run in paths.values():
            results = run()  # the operators (kernels, spectra, dense blocks) are built once per grid
        if previous is not None:  # the same answers as the code before (Woodbury's steps: round-off apart)
            for old, new in zip(_solve_all(cells, previous), _solve_all(cells)):
                assert np.max(np.abs(old.traction - new.traction)) <= 1e-12 * MU * np.max(old.pressure)
                assert old.iterations == new.iterations and np.array_equal(old.stick, new.stick)
        wall = time.perf_counter()
        cpu = _cpu_per_solve(paths, 21 if n <= 11 else 3)
        wall = (time.perf_counter() - wall) / ((21 if n <= 11 else 3) * len(paths) * len(CASES)) * 1e3
        contact = int(results[0].contact.sum())
        newton = sum(r.iterations for r in results) / len(results)
        krylov = sum(r.krylov_iterations for r in results) / len(results)
        shown = {name: f"{median:.2f} ({low:.2f})" for name, (median, low) in cpu.items()}
        before = f"{shown['before']} ms before ({BEFORE[:7]}), " if previous is not None else "(before: no git), "
        state = "on" if compiled else "off"
        print(f"\nexact half-space rolling, {label} ({contact} contact cells): CPU per solve, median (min) of "
              f"the blocks: {before}{shown['steady_rolling']} ms steady_rolling (kernels {state}), "
              f"{shown['prepared']} ms prepared (numpy), {shown.get('compiled', '(no numba)')} ms prepared "
              f"(compiled) (target <= {target_ms} ms); wall {wall:.2f} ms (mean of all paths); Newton "
              f"{newton:.1f}, GMRES {krylov:.1f} per solve; load average {os.getloadavg()[0]:.1f} on "
              f"{os.cpu_count()} cores, numpy call {_call_overhead_us():.2f} us")
        figure(record_property, f"rolling.{n}.{'across' if cells == (n, n) else 'contact'}",
               f"exact rolling solve, {label} ({contact} contact cells), `steady_rolling`, median",
               cpu["steady_rolling"][0], "ms", target=f"<= {target_ms:g}",
               baseline=(f"{BEFORE[:7]}: {number(cpu['before'][0])} ms" if previous is not None else ""))
    benchmark.pedantic(_solve_all, args=((n, n),), rounds=3 if n <= 11 else 1, iterations=1)
    benchmark.extra_info.update({"n": n, "cpu_ms": cpu})


def test_bench_fastsim_throughput(benchmark, record_property):
    rng = np.random.default_rng(0)
    count = 10_000
    xi, eta = rng.uniform(-3e-3, 3e-3, (2, count))
    phi = rng.uniform(-2.0, 2.0, count)

    def run():
        return fastsim.fastsim(A, B, FORCE, G, NU, MU, xi, eta, phi, (20, 20))

    run()
    wall, cpu = time.perf_counter(), time.process_time()
    run()
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    benchmark.pedantic(run, rounds=3, iterations=1)
    rate = count / benchmark.stats.stats.median
    benchmark.extra_info["contacts_per_second"] = rate
    print(f"\nFASTSIM 20 x 20 elements, {count} contacts: {rate:.3g} contacts/s (median of 3; one run wall "
          f"{wall * 1e3:.0f} ms, CPU {cpu * 1e3:.0f} ms; target >= 1e4/s); load average {os.getloadavg()[0]:.1f}")
    figure(record_property, "fastsim", f"FASTSIM, 20 x 20 elements, {count:,} contacts (median of 3)", rate,
           "contacts/s", target=">= 1e4", clock="wall")


def test_bench_fe_compliance_solve(benchmark):
    """One rolling solve on a condensed FE compliance against the half-space solve of the same grid (target: within
    10x); ball R 10 mm on a block, 100 N, 8 x 8 cells, P2, h one cell (the condensation, about a minute, is not
    timed: it is reused by every solve on the grid)."""
    import math

    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    e, nu, radius, force = 2.1e11, 0.28, 10e-3, 100.0
    a = (3.0 * force * radius / (4.0 * e / (2.0 * (1.0 - nu * nu)))) ** (1.0 / 3.0)
    grid = rolling.hertz_grid(a, a, (8, 8))
    path = contact_pairs.ball_on_flat_pair(radius, grid.dx, 1.3, symmetry="full", element_order=2,
                                           fine_ellipse=(1.2 * a + grid.dx, 1.2 * a + grid.dx, 0.5 * a))
    start = time.perf_counter()
    compliance = rolling_compliance.condense(path, (e, nu), grid, order=2)
    condense_s = time.perf_counter() - start
    shear = e / (2 * (1 + nu))
    pressure = rolling.hertz_pressure(grid, a, a, force)
    p0 = 1.5 * force / (math.pi * a * a)
    w = rolling.rigid_slip(grid, 0.3 * MU * p0 / shear, 0.0, 0.5 * MU * p0 / (a * shear))
    fe, half = compliance.operator(), rolling.half_space_operator(grid, shear, nu)
    times = {}
    for name, operator in (("FE", fe), ("half-space", half)):
        rolling.solve(pressure, operator, MU, w)
        cpu = time.process_time()
        for _ in range(20):
            rolling.solve(pressure, operator, MU, w)
        times[name] = (time.process_time() - cpu) / 20
    benchmark.pedantic(rolling.solve, args=(pressure, fe, MU, w), rounds=5, iterations=1)
    print(f"\nFE-compliance rolling solve, 8 x 8 cells ({compliance.ndofs} DOFs, condensation {condense_s:.0f} s "
          f"wall): CPU {times['FE'] * 1e3:.2f} ms per solve against {times['half-space'] * 1e3:.2f} ms on the "
          f"half-space (ratio {times['FE'] / times['half-space']:.2f}, target <= 10); load average "
          f"{os.getloadavg()[0]:.1f}")
