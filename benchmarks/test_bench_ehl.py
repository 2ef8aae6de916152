"""EHL point contact (lowmodel.contact.ehl.solve_reynolds): time of one operating point.

Targets (docs/ehl.md): 129 x 129 under 20 s, 257 x 257 under 2 min on this machine
(here 128 x 128 and 256 x 256: the nested grids need even cell counts).
Circular steel contact, R = 10 mm, 8 N, u_s = 1 m/s, eta0 = 0.05 Pa s (Moes M = 20.5, L = 13.7).
Run: ``.venv/bin/python -m pytest benchmarks/test_bench_ehl.py -s``.
"""
from __future__ import annotations

import time

import pytest

from ballbench.lowmodel.contact import ehl, hertz
from ballbench.lowmodel.contact import halfspace as hs

from speed_table import figure

E, NU, ETA0, R, LOAD, SPEED = 2.1e11, 0.3, 0.05, 0.01, 8.0, 1.0


@pytest.mark.parametrize("n, target_s", [(128, 20.0), (256, 120.0)])
def test_bench_ehl_point(benchmark, n, target_s, record_property):
    geometry = hertz.ball_on_flat(R, youngs_modulus=E, poisson_ratio=NU)
    a = float(hertz.solve_load(geometry, LOAD).a)
    grid = hs.SurfaceGrid(n, n, 5.5 * a / n, 5.0 * a / n, -1.25 * a, 0.0)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    reference = ehl.hamrock_dowson_film(SPEED, LOAD, R, R, 2 * geometry.contact_modulus, ETA0,
                                        ehl.roelands_pressure_viscosity_coefficient(ETA0))

    def run():
        return ehl.solve_reynolds(gap, grid, geometry.contact_modulus, LOAD, SPEED, ETA0, 970.0,
                                  initial_film=reference["h_c"])

    cpu = time.process_time()
    solution = benchmark.pedantic(run, rounds=1, iterations=1)
    cpu = time.process_time() - cpu
    benchmark.extra_info.update({"n": n, "cpu_s": cpu, "newton_iterations": solution.iterations})
    print(f"\nEHL {n} x {n}: wall {benchmark.stats.stats.median:.1f} s, CPU {cpu:.1f} s (target < {target_s:g} s); "
          f"{solution.iterations} Newton steps on the finest grid; h_c / Hamrock-Dowson "
          f"{solution.central_film / reference['h_c']:.3f}, "
          f"h_min / HD {solution.minimum_film / reference['h_min']:.3f}, "
          f"load error {solution.load_error:.1e}, p_max / p_Hertz {solution.max_pressure / geometry_p0(geometry):.3f}")
    figure(record_property, f"ehl.{n}", f"EHL point contact (sun2021 eqs 14-19), {n} x {n} cells, one operating "
           f"point ({cpu:.3g} s CPU)", benchmark.stats.stats.median, "s", target=f"< {target_s:g}", clock="wall")


def geometry_p0(geometry):
    return float(hertz.solve_load(geometry, LOAD).p0)
