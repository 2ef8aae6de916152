"""Ball-screw contact kinematics (wang2022 eqs 1-30): contact-point evaluations per second.

One ball evaluation gives both contacts (nut A, screw B) with every velocity,
U and S, so it counts as two contact-point evaluations.  Target >= 1e6 /s.

Run: python -m pytest benchmarks/test_bench_screw_kinematics.py
"""
import numpy as np

from ballbench.lowmodel.ball_bearing import harris
from ballbench.lowmodel.screw import kinematics as sk

from speed_table import figure

N_BALLS = 200_000


def _inputs(count):
    rng = np.random.default_rng(0)
    return dict(pitch_radius=rng.uniform(10e-3, 40e-3, count), ball_radius=rng.uniform(1.5e-3, 4e-3, count),
                lead=rng.uniform(0.0, 40e-3, count), screw_speed=rng.uniform(50.0, 600.0, count),
                contact_angle_nut=rng.uniform(np.radians(35), np.radians(55), count),
                contact_angle_screw=rng.uniform(np.radians(35), np.radians(55), count))


def test_contact_points_per_second(benchmark, record_property):
    inputs = _inputs(N_BALLS)
    benchmark(sk.kinematics, **inputs)
    rate = 2 * N_BALLS / benchmark.stats.stats.median
    benchmark.extra_info["contact_points_per_second"] = rate
    print(f"\nwang2022 contact-point evaluations per second (vectorised over {N_BALLS} balls x 2 contacts, "
          f"geometries and speeds varied): {rate:.3e} (target >= 1e6)")
    figure(record_property, "screw_kinematics", f"ball-screw contact points (wang2022), vectorised over {N_BALLS:,} "
           "balls x 2 contacts", rate, "points/s", target=">= 1e6", clock="wall")
    assert rate > 0


def test_contact_points_per_second_broadcast_grid(benchmark):
    """Speeds x geometries grid by broadcasting (400 speeds x 500 leads)."""
    speeds = np.linspace(10.0, 600.0, 400)[:, None]
    leads = np.linspace(0.0, 40e-3, 500)[None, :]
    benchmark(sk.kinematics, 20.7e-3, 3.175e-3, leads, speeds, np.radians(45.0))
    rate = 2 * speeds.size * leads.size / benchmark.stats.stats.median
    benchmark.extra_info["contact_points_per_second"] = rate
    print(f"\nwang2022 contact-point evaluations per second (broadcast grid 400 x 500): {rate:.3e}")


def test_harris_bearings_per_second(benchmark):
    inputs = _inputs(N_BALLS)
    benchmark(harris.kinematics, inputs["pitch_radius"], inputs["ball_radius"], inputs["screw_speed"],
              inputs["contact_angle_nut"])
    rate = 2 * N_BALLS / benchmark.stats.stats.median
    benchmark.extra_info["contact_points_per_second"] = rate
    print(f"\nHarris contact-point evaluations per second: {rate:.3e}")
