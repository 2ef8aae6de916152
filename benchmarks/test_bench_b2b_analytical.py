"""Analytical B2B model (lin2019 eqs 22, 30, 32): cases per second, vectorised (target >= 1e6 /s).

Run: python -m pytest benchmarks/test_bench_b2b_analytical.py
"""
import math

import numpy as np

from ballbench.lowmodel.linear_bearing import b2b_analytical as b2b

from speed_table import figure

N_CASES = 1_000_000
COMMON = dict(normal_load=100.0, groove_velocity=0.01, friction_coefficient=0.1, psi=5.3073e-4, ball_radius=5e-3)


def test_two_ball_cases_per_second(benchmark, record_property):
    rng = np.random.default_rng(0)
    theta = rng.uniform(-math.radians(3), math.radians(3), N_CASES)
    rho = rng.uniform(-0.9, 0.9, N_CASES)  # |rho| < tan(42 deg): four-point contact (lin2017 eq 37)
    benchmark.pedantic(b2b.two_ball_case, args=(theta, rho), kwargs=COMMON, rounds=5, iterations=1)
    rate = N_CASES / benchmark.stats.stats.median
    benchmark.extra_info["cases_per_second"] = rate
    print(f"\nanalytical two-ball cases per second (vectorised over {N_CASES}): {rate:.3e} (target >= 1e6)")
    figure(record_property, "b2b_analytical", f"analytical B2B two-ball cases (lin2019 eqs 22, 30, 32), vectorised "
           f"over {N_CASES:,}", rate, "cases/s", target=">= 1e6", clock="wall")


def test_two_ball_single_case(benchmark):
    """One case (paper, Table 3: 6.67 ms in MATLAB)."""
    benchmark(b2b.two_ball_case, math.radians(2.0), -0.6, **COMMON)
    print(f"\nanalytical single case: {benchmark.stats.stats.median * 1e6:.1f} us (paper: 6.67 ms)")
