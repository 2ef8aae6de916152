"""Speed of the low-order numerical B2B model (lin2019 Sec 2.2).

Two-ball B2B solve of Table 3 case (a) (paper: 0.74 s in MATLAB; target <= 5 ms median),
the single-ball solve (eq 4) and a 50-ball chain.

Run: python -m pytest benchmarks/test_bench_b2b.py
"""
import math

import numpy as np

from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts

from ballbench.lowmodel.contact import hertz

RADIUS = 5e-3  # lin2019 Table 1


def _contacts(n_balls=2, theta_deg=2.0, rho=-0.6):
    """Table 1 / Sec 2.4 module with lin2017 eq 36 normal forces (written out: no dependency on fourpoint)."""
    theta = math.radians(theta_deg)
    angles = np.tile(math.pi / 4 + np.array([-theta, theta, 0.0, 0.0]), (n_balls, 1))
    side = np.where(np.arange(n_balls) % 2 == 0, 1.0, -1.0) * rho * 100.0
    bl, br, tr, tl = angles.T
    forces = np.stack([-(side * np.cos(br) - 100.0 * np.sin(br)) / np.sin(bl + br),
                       (side * np.cos(bl) + 100.0 * np.sin(bl)) / np.sin(bl + br),
                       -(side * np.cos(tl) - 100.0 * np.sin(tl)) / np.sin(tl + tr),
                       (side * np.cos(tr) + 100.0 * np.sin(tr)) / np.sin(tl + tr)], axis=-1)  # lin2017 eq 36
    contact = hertz.solve_load(hertz.ball_in_groove(RADIUS, 0.56), forces)
    return bearing_contacts.contacts_from_forces(angles, forces, contact.a, contact.b / contact.a, ball_radius=RADIUS,
                                             friction_coefficient=0.1, groove_velocity=0.01)


def test_two_ball_b2b_solve(benchmark):
    contacts = _contacts()
    b2b.solve(contacts, [0.0])  # warm-up: friction map loaded once
    state = benchmark(b2b.solve, contacts, [0.0])
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_ms=median * 1e3, iterations=state.iterations, f_b2b=float(state.b2b_force[0]))
    print(f"\ntwo-ball B2B solve: {median * 1e3:.2f} ms median, {state.iterations} Newton iterations, "
          f"F_B2B = {state.b2b_force[0]:.3f} N (paper: 0.74 s in MATLAB; target <= 5 ms)")


def test_single_ball_solve(benchmark):
    contacts = _contacts(n_balls=1)
    bearing_ball.solve(contacts)
    state = benchmark(bearing_ball.solve, contacts)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_ms=median * 1e3, iterations=state.iterations)
    print(f"\nsingle-ball solve (eq 4): {median * 1e3:.2f} ms median, {state.iterations} Newton iterations")


def test_fifty_ball_chain(benchmark):
    contacts = _contacts(n_balls=50)
    gaps = np.zeros(49)
    b2b.solve(contacts, gaps)
    state = benchmark.pedantic(b2b.solve, args=(contacts, gaps), rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_ms=median * 1e3, iterations=state.iterations)
    print(f"\n50-ball chain, all touching: {median * 1e3:.1f} ms median, {state.iterations} Newton iterations")


def test_chain_cost_per_ball(benchmark):
    """Chains of 50 to 1000 touching balls: targets 200 balls <= 40 ms, 1000 balls <= 250 ms, time per ball
    constant within 30 % from 50 to 1000 balls (docs/b2b_bearing.md; sparse block-tridiagonal Jacobian, banded
    Cholesky).

    The machine is shared: median CPU time (``time.process_time``) and median wall time of many solves, the
    least CPU time beside them, and the least-squares line ``time = fixed + n * per_ball`` through the median
    CPU times.  Spread = max/min of time per ball - 1; 30 % needs ``fixed <= 0.3 * 50 * per_ball``.
    """
    import time

    sizes, repeats = (50, 100, 200, 400, 1000), {50: 41, 100: 31, 200: 21, 400: 15, 1000: 9}
    wall, cpu, cpu_least = {}, {}, {}
    for n_balls in sizes:
        contacts = _contacts(n_balls=n_balls)
        gaps = np.zeros(n_balls - 1)
        b2b.solve(contacts, gaps)
        times, cpu_times = [], []
        for _ in range(repeats[n_balls]):
            start, start_cpu = time.perf_counter(), time.process_time()
            b2b.solve(contacts, gaps)
            times.append(time.perf_counter() - start)
            cpu_times.append(time.process_time() - start_cpu)
        wall[n_balls] = float(np.median(times))
        cpu[n_balls] = float(np.median(cpu_times))
        cpu_least[n_balls] = float(np.min(cpu_times))
    contacts = _contacts(n_balls=200)
    benchmark.pedantic(b2b.solve, args=(contacts, np.zeros(199)), rounds=5, iterations=1)

    def spread(values):
        return max(t / n for n, t in values.items()) / min(t / n for n, t in values.items()) - 1

    per_ball, fixed = np.polyfit(np.array(sizes, dtype=float), np.array([cpu[n] for n in sizes]), 1)
    # marginal cost per added ball between neighbouring sizes: constant if the cost is linear (affine) in n
    marginal = {f"{a}-{b}": (cpu[b] - cpu[a]) / (b - a) for a, b in zip(sizes[:-1], sizes[1:])}
    marginal_spread = max(marginal.values()) / min(marginal.values()) - 1
    benchmark.extra_info.update({f"median_cpu_ms_{n}": 1e3 * t for n, t in cpu.items()},
                                **{f"median_wall_ms_{n}": 1e3 * t for n, t in wall.items()},
                                per_ball_spread_cpu=spread(cpu), per_ball_spread_wall=spread(wall),
                                per_ball_spread_least_cpu=spread(cpu_least), fixed_ms=1e3 * fixed,
                                per_ball_ms=1e3 * per_ball, marginal_spread_cpu=marginal_spread,
                                **{f"marginal_cpu_ms_{k}": 1e3 * v for k, v in marginal.items()})

    def row(values):
        return ", ".join(f"{n} {1e3 * t:.1f} ms ({1e3 * t / n:.4f} ms/ball)" for n, t in values.items())

    print(f"\nchain solve, median CPU: {row(cpu)}; spread {100 * spread(cpu):.0f} %"
          f"\nchain solve, median wall: {row(wall)}; spread {100 * spread(wall):.0f} %"
          f"\nchain solve, least CPU: {row(cpu_least)}; spread {100 * spread(cpu_least):.0f} %"
          f"\nline through the median CPU times: {1e3 * fixed:.2f} ms fixed + {1e3 * per_ball:.4f} ms per ball "
          f"(30 % spread needs fixed <= {1e3 * 0.3 * 50 * per_ball:.2f} ms); targets: 200 balls <= 40 ms, "
          "1000 <= 250 ms, spread <= 30 %"
          "\nmarginal CPU time per added ball: "
          + ", ".join(f"{k} {1e3 * v:.4f} ms" for k, v in marginal.items())
          + f"; spread {100 * marginal_spread:.0f} % (linear cost: the same slope at every size)"
          "\nbefore the fixed-cost cuts (e566c4d, same protocol, docs/b2b_bearing.md): median CPU 4.7, 6.5, 11.5, "
          "17.4, 39.0 ms, spread 140 %; 3.28 ms fixed + 0.0358 ms per ball")
