"""Mixed lubrication pieces (sun2021 eqs 15, 20-23): WM raceway, one load-shared mixed point, eq 20 torque.

The sun2021 nut contact B at 5.68 deg on the 128 x 32 grid of the sun2021-fig6 scene, G read in pm:
full-film points (500 and 83 mm/s: the smooth and the coupled rough EHL solves) and the decoupled
mixed estimate at 83 mm/s (load sharing: EHL solves plus the asperity half-space contact).
Run: ``.venv/bin/python -m pytest benchmarks/test_bench_mixed.py -s``.
"""
from __future__ import annotations

import numpy as np
import pytest

from ballbench.lowmodel.contact import roughness
from ballbench.lowmodel.screw import friction_torque
from ballbench.validation.cases import sun2021 as case
from ballbench.validation.studies import sun2021 as study


def test_bench_wm_raceway(benchmark):
    grid, _, _ = study.ehl_domain(5.68, "B", 64)
    rough = benchmark(roughness.raceway_roughness, grid, 2.47, 0.41e-12, sample_length=554e-6, cutoff_length=50e-6)
    print(f"\nWM raceway 128 x 32: {benchmark.stats.stats.median * 1e3:.1f} ms, rms {rough.rms * 1e9:.1f} nm")


@pytest.mark.parametrize("surface_speed, coupled", [(0.5, True), (0.083, True), (0.083, False)])
def test_bench_mixed_point(benchmark, surface_speed, coupled):
    grid, gap, _ = study.ehl_domain(5.68, "B", 64)
    heights = study.raceway_heights(grid).heights
    contact, friction, torque, _ = benchmark.pedantic(study.mixed_point, (grid, gap, heights, surface_speed),
                                                      kwargs={"coupled": coupled}, rounds=1, iterations=1)
    print(f"\n{'coupled' if coupled else 'decoupled'} point {surface_speed * 1e3:.0f} mm/s: "
          f"{benchmark.stats.stats.median:.2f} s, "
          f"{contact.iterations} EHL solves, R_s {contact.asperity_share:.4f}, mu "
          f"{friction.friction_coefficient:.4f}, torque {torque:.3f} N m")


def test_bench_friction_torque(benchmark):
    t1 = case.SCREW
    speeds = friction_torque.contact_speeds(np.linspace(0.05, 3.0, 1000), t1.pitch_radius, t1.ball_radius, t1.lead,
                                            t1.nominal_angle)

    def run():
        return friction_torque.friction_torque(0.03, 27.8, speeds.sliding_B, ball_count=t1.ball_count,
                                               lead_angle=case.HELIX_ANGLE, pitch_radius=t1.pitch_radius,
                                               ball_radius=t1.ball_radius, contact_angle_B=t1.nominal_angle)

    torque = benchmark(run)
    print(f"\neq 20 torque, 1000 speeds: {benchmark.stats.stats.median * 1e6:.0f} us, {float(torque[0]):.3f} N m")
