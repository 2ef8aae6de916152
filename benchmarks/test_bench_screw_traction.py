"""Speed of the FE-informed screw B2B model (lowmodel.screw.b2b_traction; docs/b2b_traction.md).

Two-ball module of lin2019 Table 5 case (a) (Table 4 geometry, preload 1.6848 um, tilted deviation
reading) from Hertz samples of the low-order state: 20 x 100 = 2000 points per contact (8000 per
ball, the size of an FE patch set), the touching solve alone and the module (touching + free balls,
:func:`lowmodel.screw.b2b_traction.module_b2b`).  The FE module itself is timed by the scenes fe-b2b-screw-a/-b.

Run: python -m pytest benchmarks/test_bench_screw_traction.py
"""
import math

import numpy as np
import pytest

from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import b2b_traction as sbt

N_RADIAL, N_ANGULAR = 20, 100  # 2000 samples per contact


@pytest.fixture(scope="module")
def case_a():
    module = screw_contacts.screw_module(oversize=1.6848e-6)
    contacts = screw_contacts.ball_contacts(module, np.array([0.0, math.radians(2.0)]), reading="tilted")
    low = screw_b2b.solve(contacts, 50.0)
    patches = [sbt.hertz_patches(low, contacts, j, n_radial=N_RADIAL, n_angular=N_ANGULAR) for j in range(2)]
    return module, patches, low


@pytest.mark.parametrize("what", ["touching", "module"])
def test_two_ball_screw_traction_solve(benchmark, case_a, what):
    module, patches, low = case_a

    def run():
        return sbt.solve(patches, module) if what == "touching" else sbt.module_b2b(patches, module)

    result = benchmark.pedantic(run, rounds=5, iterations=1)
    state = result if what == "touching" else result.touching
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, points_per_contact=N_RADIAL * N_ANGULAR,
                                f_b2b=float(state.b2b_force[0]))
    print(f"\nFE-informed screw, two balls, {N_RADIAL * N_ANGULAR} points per contact ({what}): {median:.3f} s "
          f"median, {state.iterations} Newton iterations, F_B2B = {state.b2b_force[0]:.5f} N "
          f"(low-order {low.b2b_force[0]:.5f} N), power balance {state.power_balance:.1e}")
