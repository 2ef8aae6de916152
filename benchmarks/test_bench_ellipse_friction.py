"""Friction map over a Hertz ellipse: build once (target <= 10 s), load from cache, evaluation speed.

Run: python -m pytest benchmarks/test_bench_ellipse_friction.py
"""
import numpy as np

from ballbench.lowmodel.contact import ellipse_friction as ef

from speed_table import figure


def test_map_build_cold(benchmark, tmp_path, monkeypatch, record_property):
    """Tabulate the integrals of lin2019 eqs A4-A6 on the default grid, no cache (target <= 10 s)."""
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))
    build = ef.friction_map.__wrapped__
    table = benchmark.pedantic(build, kwargs={"use_cache": False}, rounds=3, iterations=1)
    seconds = benchmark.stats.stats.median
    benchmark.extra_info["build_s"] = seconds
    print(f"\nfriction map build (cold, {table.phi.size} x {table.log_b_over_a.size} nodes): {seconds:.3f} s "
          "(target <= 10 s)")
    figure(record_property, "friction_map", f"friction map over a Hertz ellipse (lin2019 A4-A6), built without cache "
           f"({table.phi.size} x {table.log_b_over_a.size} nodes, median of 3)", seconds, "s", target="<= 10",
           clock="wall")
    assert seconds <= 10.0


def test_map_load_from_cache_and_patches(benchmark, tmp_path, monkeypatch):
    """Disk-cache hit plus the bicubic patch set built on first use."""
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))
    build = ef.friction_map.__wrapped__
    build()  # fill the cache

    def load():
        table = build()
        assert table.from_cache
        return ef._patches(table)

    benchmark.pedantic(load, rounds=3, iterations=1)
    print(f"\nfriction map load from cache + patch set: {benchmark.stats.stats.median * 1e3:.1f} ms")


def test_friction_call_eight_contacts(benchmark):
    """One Newton iteration's worth of look-ups: 8 contacts (two balls), values and d/d(c/a)."""
    ef.friction(0.0, 0.23)
    kappa = np.linspace(-0.4, 0.4, 8)
    benchmark(ef.friction, kappa, 0.23)
    print(f"\nfriction(8 contacts): {benchmark.stats.stats.median * 1e6:.1f} us per call")


def test_friction_velocity_call_eight_contacts(benchmark):
    ef.friction(0.0, 0.23)
    spin = np.linspace(-1e-3, 1e-3, 8)
    slide = np.linspace(1e-4, -2e-4, 8)
    benchmark(ef.friction_velocity, spin, slide, 0.23)
    print(f"\nfriction_velocity(8 contacts): {benchmark.stats.stats.median * 1e6:.1f} us per call")


def test_friction_points_per_second(benchmark):
    ef.friction(0.0, 0.23)
    rng = np.random.default_rng(0)
    kappa = np.tan(rng.uniform(-1.57, 1.57, 100_000))
    beta = rng.uniform(0.05, 1.0, kappa.size)
    benchmark(ef.friction, kappa, beta)
    rate = kappa.size / benchmark.stats.stats.median
    benchmark.extra_info["points_per_second"] = rate
    print(f"\nfriction map evaluations per second (vectorised, 1e5 points): {rate:.3e}")


def test_exact_quadrature_points_per_second(benchmark):
    rng = np.random.default_rng(1)
    kappa = rng.uniform(-3.0, 3.0, 1000)
    benchmark.pedantic(ef.friction_exact, args=(kappa, 0.23), rounds=3, iterations=1)
    rate = kappa.size / benchmark.stats.stats.median
    print(f"\nexact quadrature evaluations per second (vectorised): {rate:.3e}")
