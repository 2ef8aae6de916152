"""Hertz contacts per second, vectorised over loads (target >= 1e5 /s).

Run: python -m pytest benchmarks/test_bench_hertz.py
"""
import numpy as np

from ballbench.lowmodel.contact import hertz

from speed_table import figure

N_LOADS = 100_000


def test_hertz_contacts_per_second(benchmark, record_property):
    geometry = hertz.ball_in_groove(5e-3, 0.56)
    forces = np.linspace(1.0, 1000.0, N_LOADS)
    benchmark(hertz.solve_load, geometry, forces)
    rate = N_LOADS / benchmark.stats.stats.median
    benchmark.extra_info["contacts_per_second"] = rate
    print(f"\nHertz contacts per second (vectorised over {N_LOADS} loads): {rate:.3e} (target >= 1e5)")
    figure(record_property, "hertz", f"Hertz contacts, vectorised over {N_LOADS:,} loads", rate, "contacts/s",
           target=">= 1e5", clock="wall")


def test_hertz_geometry_setups_per_second(benchmark):
    """Geometry + eccentricity root find, one per call (not vectorisable: one root per geometry)."""
    benchmark(hertz.ball_in_groove, 5e-3, 0.52)
    rate = 1.0 / benchmark.stats.stats.median
    benchmark.extra_info["geometries_per_second"] = rate
    print(f"\nHertz geometries (eccentricity root finds) per second: {rate:.3e}")
