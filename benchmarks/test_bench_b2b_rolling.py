"""Speed of the B2B solve with stick/slip ball-to-groove contacts (lowmodel.linear_bearing.b2b_rolling,
lowmodel.screw.b2b_rolling; docs/b2b_rolling.md).

Touching two-ball solve of lin2019 Table 3 case (a) and Table 5 case (a) (fitted preload) on Hertz contacts and two
half-spaces: the full-slip start and the stick/slip Newton (the analytic Jacobian from the rolling solve's sensitivity);
the number of rolling solves beside the time.  The FE rungs are timed by the rolling-b2b-* scenes (ladder.csv).

Run: python -m pytest benchmarks/test_bench_b2b_rolling.py
"""
import math

import numpy as np
import pytest

from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts


@pytest.mark.parametrize("cells", [(12, 48), (16, 64), (20, 80)])  # 16 x 64: the quick cells of the case ladder
def test_linear_two_ball_stick_slip_solve(benchmark, cells):
    contacts = b2b.module_contacts(math.radians(2.0), -0.6)
    balls = [b2b_rolling.hertz_contacts(contacts, j, cells=cells) for j in range(2)]

    def solve():
        return b2b_rolling.solve(balls, ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)

    state = benchmark.pedantic(solve, rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, rolling_solves=state.rolling_solves, f_b2b=float(state.b2b_force[0]))
    print(f"\nlinear stick/slip two-ball solve, {cells[0]} x {cells[1]} cells per contact: {median:.2f} s median, "
          f"{state.iterations} Newton iterations, {state.rolling_solves} rolling solves, "
          f"F_B2B {state.b2b_force[0]:.4f} N")


@pytest.mark.parametrize("cells", [(12, 48), (20, 80)])
def test_screw_two_ball_stick_slip_solve(benchmark, cells):
    module = screw_contacts.screw_module(oversize=1.6848e-6)
    contacts = screw_contacts.ball_contacts(module, np.radians([0.0, 2.0]), reading="tilted")
    low = screw_b2b.solve(contacts, 50.0)
    balls = [screw_rolling.hertz_contacts(low, contacts, j, cells=cells) for j in range(2)]

    def solve():
        return screw_rolling.solve(balls, module)

    state = benchmark.pedantic(solve, rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, rolling_solves=state.rolling_solves, f_b2b=float(state.b2b_force[0]))
    print(f"\nscrew stick/slip two-ball solve, {cells[0]} x {cells[1]} cells per contact: {median:.2f} s median, "
          f"{state.iterations} Newton iterations, {state.rolling_solves} rolling solves, "
          f"F_B2B {state.b2b_force[0]:.4f} N")


# where full sliding has no state (docs/b2b_rolling.md, "Where full sliding has no state"): the guide's and the
# screw's friction of record by the stick/slip law, beside lin2019's full-sliding solve of a case that has one
GUIDES = {"full sliding (Table 3 a)": (2.0, -0.6, 100.0, 0.1), "spin capacity 0.738 (1.5 deg, 300 N, mu 0.2)":
          (1.5, -0.9, 300.0, 0.2), "branch ends (2.87 deg, 128 N, mu 0.604)": (2.87, -0.83, 128.0, 0.604)}


@pytest.mark.parametrize("name", list(GUIDES))
def test_guide_friction_of_record(benchmark, name):
    from ballbench.lowmodel import bearing_results
    from ballbench.lowmodel.bearing import GuideLoadCase, LinearGuide, Material

    theta, rho, vertical, mu = GUIDES[name]
    guide = LinearGuide(ball_radius=5e-3, conformity=0.56, nominal_angle=math.pi / 4, material=Material(210e9, 0.28),
                        friction_coefficient=mu, groove_velocity=0.01)
    case = GuideLoadCase(guide, vertical_force=vertical, side_force_ratio=rho,
                         deviations=(-math.radians(theta), math.radians(theta), 0.0, 0.0))
    states = benchmark.pedantic(bearing_results.guide_states, args=(case,), kwargs=dict(cells=(12, 48)), rounds=3,
                                iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, law=states.law)
    print(f"\nguide friction of record, {name}: {states.law}, {median:.3f} s median (touching and free; stick/slip "
          "on 12 x 48 cells)")


def test_screw_friction_of_record_past_the_preload_loss(benchmark):
    from ballbench.lowmodel import bearing_results
    from ballbench.lowmodel.bearing import BallScrew, Material, ScrewLoadCase

    screw = BallScrew(ball_radius=2.381e-3, pitch_radius=12.5e-3, lead=5e-3, nominal_angle=math.pi / 4,
                      conformity=0.54, material=Material(210e9, 0.3), friction_coefficient=0.05,
                      nut_speed=2 * math.pi, oversize=1.5e-6)
    case = ScrewLoadCase(screw, axial_load=300.0, deviations=(0.0, math.radians(2.0)), reading="tilted")
    states = benchmark.pedantic(bearing_results.screw_law_states, args=(case,), kwargs=dict(cells=(12, 48)),
                                rounds=3, iterations=1)
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(median_s=median, law=states.law)
    print(f"\nscrew friction of record past the preload loss (300 N, loss 111 N): {states.law}, {median:.3f} s median "
          "(lin2019's ramp first, then the stick/slip law on 12 x 48 cells)")
