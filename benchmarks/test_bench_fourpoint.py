"""Four-point evaluations per second, vectorised over cases (target >= 1e5 /s).

One evaluation = normal forces (lin2017 eq 36), K (eq 23), sliding state, ball
motion, friction forces and loss of one ball.  Run:
python -m pytest benchmarks/test_bench_fourpoint.py
"""
import numpy as np

from ballbench.lowmodel.linear_bearing import fourpoint

from speed_table import figure

N_CASES = 100_000


def _cases():
    rng = np.random.default_rng(0)
    angles = np.radians(rng.uniform(35.0, 55.0, (N_CASES, 4)))
    lower, upper = fourpoint.contact_limits(angles)
    rho = lower + (upper - lower) * rng.uniform(0.05, 0.95, N_CASES)
    return angles, rho


def test_fourpoint_solve_per_second(benchmark, record_property):
    angles, rho = _cases()
    state = benchmark(fourpoint.solve, angles, 100.0 * rho, 100.0, ball_radius=5e-3, friction_coefficient=0.1,
                      groove_velocity=0.01)
    assert state.friction_loss.shape == (N_CASES,)
    rate = N_CASES / benchmark.stats.stats.median
    benchmark.extra_info["evaluations_per_second"] = rate
    print(f"\nfour-point evaluations per second (solve, vectorised over {N_CASES} cases): {rate:.3e} "
          f"(target >= 1e5)")
    figure(record_property, "fourpoint", f"four-point evaluations (lin2017), vectorised over {N_CASES:,} cases", rate,
           "evaluations/s", target=">= 1e5", clock="wall")


def test_fourpoint_normal_forces_per_second(benchmark):
    angles, rho = _cases()
    benchmark(fourpoint.normal_forces, 100.0 * rho, 100.0, angles)
    rate = N_CASES / benchmark.stats.stats.median
    benchmark.extra_info["evaluations_per_second"] = rate
    print(f"\nfour-point normal forces per second (eq 36, vectorised over {N_CASES} cases): {rate:.3e}")
