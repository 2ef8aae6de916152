"""Half-space contact (BEM) speed, and side by side with tamaas on the same Hertz problem and grid.

Targets (docs/halfspace.md): 256 x 256 under 0.5 s, 1024 x 1024 under 10 s; our time at
most 1.5 x tamaas's at 512 x 512 (tamaas with its non-periodic DC-FFT operator,
the same Polonsky-Keer algorithm, the same grid and the same tolerance).
Run: ``.venv/bin/python -m pytest benchmarks/test_bench_halfspace.py -s``.
Wall and CPU (process) times are both printed: the machine is shared, and CPU
time is the steadier figure when other jobs compete for the cores.
"""
from __future__ import annotations

import os

import numpy as np
import pytest
from speed_table import figure
from tamaas_support import tamaas_pressure, timed

from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.contact import hertz

LOAD = 100.0
TOLERANCE = 1e-8
GEOMETRY = hertz.ball_in_groove(5e-3, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28)


def _problem(n):
    contact = hertz.solve_load(GEOMETRY, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), float(contact.b), n)
    return contact, grid, hs.quadratic_gap(grid, GEOMETRY.A, GEOMETRY.B)


def _errors(contact, pressure, grid, approach=None):
    a, b, _, _ = hs.pressure_ellipse(pressure, grid)
    text = (f"p_max {pressure.max() / float(contact.p0) - 1:+.2e}, a {a / float(contact.a) - 1:+.2e}, "
            f"b {b / float(contact.b) - 1:+.2e}")
    if approach is not None:
        text += f", approach {approach / float(contact.delta) - 1:+.2e}"
    return text


@pytest.mark.parametrize("n, target_s", [(256, 0.5), (1024, 10.0)])
def test_bench_bem_hertz(benchmark, n, target_s, record_property):
    contact, grid, gap = _problem(n)
    hs.solve(gap, grid, GEOMETRY.contact_modulus, force=LOAD, tolerance=1e-3)  # kernel spectrum cached

    def run():
        return hs.solve(gap, grid, GEOMETRY.contact_modulus, force=LOAD, tolerance=TOLERANCE)

    result, wall, cpu = timed(run)
    benchmark.pedantic(run, rounds=3 if n <= 256 else 1, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update({"n": n, "iterations": result.iterations, "cpu_s": cpu})
    print(f"\nBEM {n} x {n}: median wall {median:.3f} s (one run: wall {wall:.3f} s, CPU {cpu:.3f} s; "
          f"target < {target_s} s), {result.iterations} CG iterations; error vs Hertz "
          + _errors(contact, result.pressure, grid, result.approach)
          + f"; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    figure(record_property, f"bem.{n}", f"half-space BEM, {n} x {n} cells, Hertz (tolerance 1e-8; one run "
           f"{cpu:.3g} s CPU), median", median, "s", target=f"< {target_s:g}", clock="wall")


def test_bench_bem_vs_tamaas_512(benchmark):
    tm = pytest.importorskip("tamaas")
    contact, grid, gap = _problem(512)

    def tamaas_solve():
        return tamaas_pressure(gap, grid, GEOMETRY.contact_modulus, LOAD, TOLERANCE)

    def ours():
        return hs.solve(gap, grid, GEOMETRY.contact_modulus, force=LOAD, tolerance=TOLERANCE)

    ours()  # kernel spectrum cached, as tamaas builds its operator once per model
    theirs, tamaas_wall, tamaas_cpu = timed(tamaas_solve)
    result, our_wall, our_cpu = timed(ours)
    benchmark.pedantic(ours, rounds=1, iterations=1)
    difference = np.max(np.abs(result.pressure - theirs)) / float(contact.p0)
    benchmark.extra_info.update({"tamaas_wall_s": tamaas_wall, "tamaas_cpu_s": tamaas_cpu, "ours_wall_s": our_wall,
                                 "ours_cpu_s": our_cpu})
    print(f"\n512 x 512 Hertz (groove 0.56, 100 N), tolerance {TOLERANCE:g}:\n"
          f"  tamaas {tm.__version__} (PolonskyKeerRey, dcfft): wall {tamaas_wall:.2f} s, CPU {tamaas_cpu:.2f} s; "
          f"error vs Hertz {_errors(contact, theirs, grid)}\n"
          f"  ballbench halfspace: wall {our_wall:.2f} s, CPU {our_cpu:.2f} s; error vs Hertz "
          f"{_errors(contact, result.pressure, grid, result.approach)}\n"
          f"  time ratio ours/tamaas: wall {our_wall / tamaas_wall:.2f}, CPU {our_cpu / tamaas_cpu:.2f} "
          f"(target <= 1.5); max |p_ours - p_tamaas| / p0 = {difference:.1e}; "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
