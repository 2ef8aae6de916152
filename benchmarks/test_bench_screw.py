"""Speed of the ball-screw models (lin2019 Sec 3): two-ball B2B solve and the whole-screw simulation.

Targets (docs/speed.md): two-ball solve <= 1 ms median (first target 30 ms; paper: 15.3 s in MATLAB); whole
screw (37 balls, 200 steps) <= 0.5 s (first target 10 s).  The screw has no compiled path yet: these are the numpy
path's times, printed with the load average (the machine is shared).  Table 4 parameters, the Table 5 preload
fit (oversize 1.6848 um, tilted reading).

Run: python -m pytest benchmarks/test_bench_screw.py
"""
import math
import os
import time

import numpy as np

from ballbench.lowmodel.screw import load_distribution, whole_screw
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts

OVERSIZE = 1.6848e-6  # m, fitted on lin2019 Table 5 case a (scene lin2019-table5-a)


def test_two_ball_b2b_solve(benchmark):
    module = screw_contacts.screw_module(oversize=OVERSIZE)
    contacts = screw_contacts.ball_contacts(module, np.radians([0.0, 2.0]), reading="tilted")
    screw_b2b.solve(contacts, 50.0)  # warm-up (Hertz tables)
    state = benchmark(screw_b2b.solve, contacts, 50.0)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_ms=median * 1e3, iterations=state.iterations, f_b2b=float(state.b2b_force[0]))
    print(f"\nscrew two-ball B2B solve: {median * 1e3:.1f} ms median (target 1 ms), {state.iterations} iterations, "
          f"F_B2B = {state.b2b_force[0]:.3f} N; load average {os.getloadavg()[0]:.2f}")


def test_whole_screw_simulation(benchmark):
    module = screw_contacts.screw_module(oversize=OVERSIZE)
    stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37)

    def run():
        return whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness)

    start = time.perf_counter()
    history = benchmark.pedantic(run, rounds=1, iterations=1)
    elapsed = time.perf_counter() - start
    benchmark.extra_info.update(seconds=elapsed, iterations=int(history.iterations.sum()))
    print(f"\nwhole screw, 37 balls, 200 steps: {elapsed:.1f} s (target 0.5 s), "
          f"{int(history.iterations.sum())} Newton iterations; load average {os.getloadavg()[0]:.2f}")
