"""Speed of the FE-informed B2B model (lowmodel.linear_bearing.b2b_traction; docs/b2b_traction.md).

Two-ball solve of lin2019 Table 3 case (a) from Hertz samples (the size of the FE input at the
default level is about 4000 points per ball); the FE module itself is timed by the scenes
fe-b2b-linear-a/-b (levels.csv: mesh, assembly, condensation, contact solves, B2B).

Run: python -m pytest benchmarks/test_bench_b2b_traction.py
"""
import math

import pytest

from ballbench.lowmodel.linear_bearing import b2b, b2b_traction


@pytest.mark.parametrize("n_radial, n_angular", [(8, 32), (16, 64)])
def test_two_ball_traction_solve(benchmark, n_radial, n_angular):
    contacts = b2b.module_contacts(math.radians(2.0), -0.6)
    patches = [b2b_traction.hertz_patches(contacts, j, n_radial=n_radial, n_angular=n_angular) for j in range(2)]

    def solve():
        return b2b_traction.solve(patches, ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)

    state = benchmark.pedantic(solve, rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, points_per_ball=4 * n_radial * n_angular,
                                f_b2b=float(state.b2b_force[0]))
    print(f"\nFE-informed two-ball solve, {4 * n_radial * n_angular} points per ball: {median:.3f} s median, "
          f"{state.iterations} Newton iterations, F_B2B = {state.b2b_force[0]:.4f} N")
