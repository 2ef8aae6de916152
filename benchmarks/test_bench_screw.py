"""Speed of the ball-screw models (lin2019 Sec 3): two-ball B2B solve and the whole-screw simulation.

Targets (docs/speed.md): two-ball solve <= 1 ms median (first target 30 ms; paper: 15.3 s in MATLAB); whole
screw (37 balls, 200 steps) <= 0.5 s (first target 10 s).  Table 4 parameters, the Table 5 preload fit
(oversize 1.6848 um, tilted reading).

Every figure is printed beside the code before the compiled path, timed in the same run: the numpy path
(``lowmodel.kernels.use_kernels(False)``), interleaved with the compiled one (CPU time, ``time.process_time``, the
machine is shared; the load average beside it).  The two-ball solve is also set against its arithmetic: the flops
of the kernel's loops (:func:`arithmetic`) at the rate of compiled loops on this machine now
(``test_bench_kernels.scalar_rate``); the kernels' first-call cost (compile with an empty numba cache, load from
the disk cache) is printed, and the pieces of one Newton iteration of the whole screw's ring (one evaluation of the
chain, the normal matrix, its banded-bordered Cholesky, the two triangular solves).

Run: python -m pytest benchmarks/test_bench_screw.py -s
"""
import math
import os
import time

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.quadrature import tanh_sinh
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import ball as screw_ball
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import load_distribution, whole_screw

from kernel_support import compiled_module, first_call_seconds, interleaved
from speed_table import figure, number

OVERSIZE = 1.6848e-6  # m, fitted on lin2019 Table 5 case a (scene lin2019-table5-a)
# flops of lowmodel/screw/ball_kernels.py: one tanh-sinh node of the friction integrals (cos, sin, atan2 and sqrt
# counted as 20 each, ~45 arithmetic), the dual-number algebra of one contact (~65 operations on 8 numbers), and
# per pair the B2B loads with their derivatives
NODE, CONTACT, PAIR = 125, 520, 400


def arithmetic(n_balls: int, evaluations: int, iterations: int, size: int) -> float:
    """Floating-point operations of a compiled screw chain solve: ``evaluations`` of the chain (four contacts per
    ball on the 4-panel tanh-sinh rule of level 3, every pair) and per Newton iteration the dense normal equations
    (``2 size^3``) and the LU (``2/3 size^3``)."""
    nodes = 4 * tanh_sinh(screw_ball.FRICTION_LEVEL["coarse"])[0].size
    evaluation = n_balls * 4 * (nodes * NODE + CONTACT) + (n_balls - 1) * PAIR
    return evaluations * evaluation + iterations * (2.0 + 2.0 / 3.0) * size ** 3


@pytest.fixture(scope="module")
def compiled():
    compiled_module(screw_b2b.RING_KERNELS)   # the whole screw's ring (loaded here, not inside a timed run)
    return compiled_module(screw_ball.KERNELS)


@pytest.mark.parametrize("name", [screw_ball.KERNELS, screw_b2b.RING_KERNELS])
def test_first_call_cost(compiled, name):
    """Cold: a fresh numba cache (every screw kernel compiled); warm: the cache of this run (loaded from disk)."""
    cold, warm = first_call_seconds(name)
    print(f"\n{name}: first call in a process: compile {cold:.1f} s with an empty numba cache, {warm:.2f} s "
          f"from the disk cache; load average {os.getloadavg()[0]:.2f}")


def test_two_ball_b2b_solve(compiled, record_property):
    from test_bench_kernels import scalar_rate

    module = screw_contacts.screw_module(oversize=OVERSIZE)
    contacts = screw_contacts.ball_contacts(module, np.radians([0.0, 2.0]), reading="tilted")

    def solve():
        return screw_b2b.solve(contacts, 50.0)

    state = solve()
    new, old = interleaved(solve, 31, 10)
    rate = scalar_rate()
    size = 2 * (screw_ball.N_UNKNOWNS + 1) + 1
    flops = arithmetic(2, state.iterations + 1, state.iterations, size)
    print(f"\nscrew two-ball B2B solve: compiled {new * 1e3:.2f} ms (target 1 ms), numpy path {old * 1e3:.2f} ms "
          f"(x {old / new:.1f}); {state.iterations} iterations, F_B2B = {state.b2b_force[0]:.3f} N; "
          f"{flops:.3g} flop = {flops / rate * 1e3:.3f} ms at the measured {rate / 1e9:.2f} Gflop/s of compiled "
          f"loops: figure of merit {flops / rate / new:.2f} (1 = pure arithmetic); load average "
          f"{os.getloadavg()[0]:.2f}")
    figure(record_property, "screw.two_ball", "screw two-ball B2B solve (Table 5 a), compiled, median", 1e3 * new,
           "ms", target="<= 1", baseline=f"numpy path {number(1e3 * old)} ms")


def test_whole_screw_simulation(compiled, record_property):
    module = screw_contacts.screw_module(oversize=OVERSIZE)
    stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37)

    def run():
        return whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness)

    seconds = {}
    for enabled in (True, False):
        kernels.use_kernels(enabled)
        start = time.process_time()
        history = run()
        seconds[enabled] = time.process_time() - start
    kernels.use_kernels(None)
    steps = history.iterations.size
    print(f"\nwhole screw, 37 balls, 200 steps: with the kernels {seconds[True]:.2f} s CPU (target 1 s; "
          f"{seconds[True] / steps * 1e3:.1f} ms per step), numpy path {seconds[False]:.1f} s "
          f"(x {seconds[False] / seconds[True]:.1f}); {int(history.iterations.sum())} Newton iterations "
          f"({history.iterations.mean():.2f} per step, the first from rest); load average {os.getloadavg()[0]:.2f}")
    figure(record_property, "screw.whole", f"whole screw, 37 balls, 200 steps ({int(history.iterations.sum())} "
           "Newton iterations), compiled, one run", seconds[True], "s", target="<= 1",
           baseline=f"numpy path {number(seconds[False])} s")


def test_ring_pieces(compiled, record_property):
    """One state of the whole screw's ring (the third step's start): the compiled pieces of a Newton iteration."""
    ring = kernels.load(screw_b2b.RING_KERNELS)
    module = screw_contacts.screw_module(oversize=OVERSIZE)
    stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37)
    captured, newton = [], ring.newton

    def spy(*args):
        captured.append([value.copy() if isinstance(value, np.ndarray) else value for value in args])
        return newton(*args)

    ring.newton = spy
    try:
        whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness, steps=3)
    finally:
        ring.newton = newton
    z, n, closed, live, targets, geometry, scalars, tables, chord, rot, pair_scalars = captured[2][:11]
    weights, terms, k = captured[2][13], captured[2][16], 8
    m = (n - 2) * k
    residual, blocks = np.empty(n * k), [np.empty((n, k, k)) for _ in range(3)]
    band, border, corner = np.zeros((m, 3 * k)), np.zeros((m, 2 * k)), np.zeros((2 * k, 2 * k))
    factor = (np.zeros((m, 3 * k)), np.zeros((m, 2 * k)), np.zeros((2 * k, 2 * k)))
    step, gradient = np.empty(n * k), np.empty(n * k)

    def evaluate():
        ring.chain_blocks(z, n, closed, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, residual,
                          *blocks, terms)

    def timed(function, repeats):
        function()
        start = time.process_time()
        for _ in range(repeats):
            function()
        return (time.process_time() - start) / repeats

    seconds = {"evaluation": timed(evaluate, 30)}
    ring._weigh(residual, *blocks, weights)
    ring._rmatvec(*blocks, residual, gradient)
    seconds["normal matrix"] = timed(lambda: ring._normal(*blocks, band, border, corner), 300)
    damping = 1e-8 * max(float(band[:, 0].max()), float(np.diag(corner).max()))
    seconds["Cholesky"] = timed(lambda: ring._factor(band, border, corner, damping, *factor), 300)
    seconds["two solves"] = timed(lambda: ring._solve(*factor, gradient, step), 300)
    print(f"\nwhole screw's ring ({n} balls, {n * k} unknowns), compiled, CPU time: "
          + ", ".join(f"{name} {value * 1e3:.3f} ms" for name, value in seconds.items())
          + f"; load average {os.getloadavg()[0]:.2f}")
    figure(record_property, "screw.ring_evaluation", f"whole screw's ring: one evaluation of the chain ({4 * n} "
           "contacts' friction integrals, the pairs, the blocks)", 1e3 * seconds["evaluation"], "ms")
    figure(record_property, "screw.ring_step", "whole screw's ring: normal matrix, its Cholesky and the two solves "
           "of one step", 1e3 * (seconds["normal matrix"] + seconds["Cholesky"] + seconds["two solves"]), "ms")
