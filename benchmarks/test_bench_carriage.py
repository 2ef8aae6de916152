"""Speed of the rigid carriage's load distribution (lowmodel.linear_bearing.carriage; docs/carriage.md): a four-row
carriage of 100 balls under a combined load, preloaded, with end relief (target <= 5 ms), and the rows' friction over
one ball pitch (target <= 0.5 s); figures for the speed table (benchmarks/speed_table.py).

Run: python -m pytest benchmarks/test_bench_carriage.py -s
"""
import math

import pytest

from ballbench.lowmodel.bearing import LinearGuide, Material
from ballbench.lowmodel.linear_bearing import carriage
from speed_table import figure


@pytest.mark.parametrize("oversize", [0.0, 2e-6])
def test_four_row_carriage_of_100_balls(benchmark, oversize, record_property):
    guide = LinearGuide(ball_radius=2.381e-3, conformity=0.52, nominal_angle=math.pi / 4,
                        material=Material(210e9, 0.3), friction_coefficient=0.1, groove_velocity=0.1)
    rows = carriage.four_rows(half_width=10e-3, upper=8e-3, lower=2e-3, contact_angle=math.radians(45))
    body = carriage.Carriage(guide, rows, balls_per_row=25, pitch=5e-3, oversize=oversize, relief_length=10e-3,
                             relief_depth=5e-6)
    load = carriage.Load(lateral=1e3, vertical=2e3, pitch=30.0, yaw=10.0, roll=20.0)
    state = benchmark.pedantic(carriage.solve, args=(body, load), rounds=20, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, iterations=state.iterations)
    print(f"\nfour-row carriage, 100 balls, oversize {oversize * 1e6:g} um: {median * 1e3:.2f} ms median, "
          f"{state.iterations} Newton steps, balance {state.balance:.1e}")
    figure(record_property, f"carriage.rigid.{'preloaded' if oversize else 'bare'}",
           f"rigid carriage, 4 rows of 25 balls, combined load, {'2 um oversize' if oversize else 'no preload'} "
           f"({state.iterations} Newton steps), median", median * 1e3, "ms", target="<= 5", clock="wall")


def test_friction_over_one_pitch_of_a_gothic_carriage(benchmark, record_property):
    """The rows' friction over one ball pitch (20 steps; carriage_friction.friction_over_travel with B2B contact
    only): a two-row gothic carriage of 13 balls per row, 2 um oversize, 600 N vertical, every ball by full sliding.
    Target (the whole-bearing issue): <= 0.5 s."""
    from ballbench.lowmodel.linear_bearing import carriage_friction

    guide = LinearGuide(ball_radius=2.381e-3, conformity=0.52, nominal_angle=math.pi / 4,
                        material=Material(210e9, 0.3), friction_coefficient=0.1, groove_velocity=0.1)
    rows = carriage.gothic_rows(half_width=8e-3, height=5e-3, contact_angles=[math.pi / 4] * 4)
    body = carriage.Carriage(guide, rows, balls_per_row=13, pitch=5e-3, oversize=2e-6)
    result = benchmark.pedantic(carriage_friction.friction_over_travel, args=(body, carriage.Load(vertical=600.0)),
                                kwargs=dict(steps=20, alone=False), rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median)
    print(f"\ngothic carriage, 2 x 13 balls, friction over one pitch in 20 steps: {median:.3f} s median, mean force "
          f"{result.mean:.4g} N, ripple {result.ripple:.3g} N, every step complete: {bool(result.complete.all())}")
    figure(record_property, "carriage.travel", "carriage friction over one pitch, 2 gothic rows of 13 balls, 20 "
           "steps, full sliding, median", median, "s", target="<= 0.5", clock="wall")
