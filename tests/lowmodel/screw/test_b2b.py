"""Ball-to-ball contact in a ball screw (lin2019 Sec 3.2, eqs 56-61)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.screw import b2b as b2, ball as sb, contacts as screw_contacts, b2b as b2b

DEG = math.pi / 180.0


@pytest.fixture(scope="module")
def module():
    return screw_contacts.screw_module(oversize=1e-6)


def test_pair_geometry_is_the_helix_chord(module):
    pair = b2.pair_geometry(module)
    p = module.lead / (2 * math.pi)
    step = pair.azimuth_step
    chord = math.hypot(2 * module.pitch_radius * math.sin(step / 2), p * step)
    assert chord == pytest.approx(2 * module.ball_radius, rel=1e-12)
    assert np.linalg.norm(pair.chord) == pytest.approx(1.0)
    np.testing.assert_allclose(pair.rotation @ pair.rotation.T, np.eye(3), atol=1e-15)
    # the chord lies (nearly) in the x3-y3 plane and is tilted towards the axis by ~dphi/2 (eq 56's picture)
    assert abs(pair.chord[2]) < 5e-3    # p (dphi - sin dphi) cos(alpha) / (2 R_B): 0.0034 for Table 4
    assert pair.angle == pytest.approx(b2.b2b_angle_eq56(module), rel=0.03)
    assert pair.angle != pytest.approx(b2.b2b_angle_eq56(module), rel=0.01)   # eq 56 is an approximation (1.9 %)


def test_theta_zero_gives_no_b2b_and_equal_orbit_speeds(module):
    contacts = screw_contacts.ball_contacts(module, np.zeros(2))
    state = b2.solve(contacts, 50.0)
    assert state.b2b_force[0] < 1e-9     # identical balls: force and separation rate both zero (to the tolerance)
    assert state.orbit_speed[0] == pytest.approx(state.orbit_speed[1], rel=1e-10)
    free = sb.solve(screw_contacts.ball_contacts(module, 0.0), 25.0)
    assert state.orbit_speed[0] == pytest.approx(free.orbit_speed[0], rel=1e-9)
    assert abs(state.input_power - state.total_loss) < 1e-8 * state.total_loss


@pytest.mark.parametrize("oversize, thetas", [(1e-6, (0.0, 2.0)), (0.0, (0.0, 3.0)), (1.7e-6, (0.0, 3.0, -1.0, 2.0))])
def test_b2b_power_balance_and_complementarity(oversize, thetas):
    module = screw_contacts.screw_module(oversize=oversize)
    contacts = screw_contacts.ball_contacts(module, np.array(thetas) * DEG, reading="tilted")
    state = b2.solve(contacts, 25.0 * len(thetas))
    free = b2.solve(contacts, 25.0 * len(thetas), with_b2b=False)
    for result in (state, free):
        assert abs(result.input_power - result.total_loss) < 1e-8 * result.total_loss
    assert np.all(state.b2b_force >= 0.0)
    separation = np.diff(state.orbit_speed)
    assert np.all(separation >= -1e-9 * abs(module.nut_speed))
    assert np.all(np.abs(state.b2b_force * separation) < 1e-8 * abs(module.nut_speed))
    # the ball behind (ball 0, theta = 0) is faster on its own, so the first pair is pressed together
    assert free.orbit_speed[0] > free.orbit_speed[1]
    assert state.b2b_force[0] > 0.0
    assert state.total_loss > free.total_loss
    assert np.all(state.b2b_friction_loss >= 0.0)


def test_open_gap_carries_no_force(module):
    contacts = screw_contacts.ball_contacts(module, np.array([0.0, 2.0]) * DEG)
    state = b2.solve(contacts, 50.0, gaps=[0.01])
    assert state.b2b_force[0] == 0.0
    assert state.orbit_speed[0] > state.orbit_speed[1]


def test_b2b_loads_derivatives_and_balance(module):
    pair = b2.pair_geometry(module)
    rng = np.random.default_rng(2)
    spins = rng.normal(size=(3, 3)) * 20.0
    forces = np.array([1.5, 0.7])
    load, d_pairs, d_pair_force, speeds = b2.b2b_loads(spins, forces, pair, module.ball_radius, 0.1)
    # the pair blocks (p, 2, 2, 6, 3) and (p, 2, 6) summed into d load / d spins (n, 6, n, 3) and d load / d F
    d_spin, d_force = np.zeros((3, 6, 3, 3)), np.zeros((3, 6, 2))
    for j, (behind, ahead) in enumerate(((0, 1), (1, 2))):
        for row, ball_row in enumerate((behind, ahead)):
            d_force[ball_row, :, j] += d_pair_force[j, row]
            for col, ball_col in enumerate((behind, ahead)):
                d_spin[ball_row, :, ball_col] += d_pairs[j, row, col]
    step = 1e-6
    for ball in range(3):
        for axis in range(3):
            up, down = spins.copy(), spins.copy()
            up[ball, axis] += step
            down[ball, axis] -= step
            fd = (b2.b2b_loads(up, forces, pair, module.ball_radius, 0.1)[0]
                  - b2.b2b_loads(down, forces, pair, module.ball_radius, 0.1)[0]) / (2 * step)
            np.testing.assert_allclose(d_spin[:, :, ball, axis], fd, atol=1e-8)
    for j in range(2):
        up, down = forces.copy(), forces.copy()
        up[j] += step
        down[j] -= step
        fd = (b2.b2b_loads(spins, up, pair, module.ball_radius, 0.1)[0]
              - b2.b2b_loads(spins, down, pair, module.ball_radius, 0.1)[0]) / (2 * step)
        np.testing.assert_allclose(d_force[:, :, j], fd, atol=1e-8)
    # action = reaction for a single pair: the forces cancel in a common frame, the friction moments are equal
    single, _, _, _ = b2.b2b_loads(spins[:2], forces[:1], pair, module.ball_radius, 0.1)
    np.testing.assert_allclose(single[0, :3] + pair.rotation @ single[1, :3], 0.0, atol=1e-12)
    np.testing.assert_allclose(single[0, 3:], pair.rotation @ single[1, 3:], atol=1e-15)
    assert np.all(speeds > 0.0)


def test_bad_input(module):
    contacts = screw_contacts.ball_contacts(module, np.zeros(2))
    with pytest.raises(ValueError, match="gaps"):
        b2.solve(contacts, 50.0, gaps=[-0.1])
    with pytest.raises(ValueError, match="gaps"):
        b2.solve(contacts, 50.0, gaps=[0.0, 0.0])
    with pytest.raises(ValueError, match="axial_load"):
        b2.solve(contacts, float("inf"))


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_b2b_solution_does_not_depend_on_the_speed_scale():
    """Quasi-static: scaling the nut speed scales every velocity and leaves the forces.  At 2e-13 rad/s the B2B
    slip floor (1e-14 R_B in m/s, absolute) bent the friction direction: the power balance was off by 1.3e-5;
    the floor is now 1e-14 R_B |omega_N|."""
    states = []
    for speed in (2 * math.pi, 2e-13):
        module = screw_contacts.screw_module(oversize=1e-6, nut_speed=speed)
        states.append(b2b.solve(screw_contacts.ball_contacts(module, np.radians([0.0, 2.0])), 50.0))
    for state in states:
        assert abs(state.input_power - state.total_loss) <= 1e-8 * state.total_loss
    assert states[1].b2b_force[0] == pytest.approx(states[0].b2b_force[0], rel=1e-6)
    assert states[1].total_loss / 2e-13 == pytest.approx(states[0].total_loss / (2 * math.pi), rel=1e-6)


def test_chain_setups_of_touching_patterns_in_turn(module):
    """The chain layouts and step weights of b2b's solves are kept per touching pattern (and ball count, mu, nut
    shifts): patterns in turn each get the layout built for them, equal to a ChainLayout built directly, and the
    solves of each pattern repeated after the others equal the first, at 0 difference."""
    from ballbench.lowmodel.b2b_chain import ChainLayout
    from ballbench.lowmodel.screw.convergence import row_weights

    contacts = screw_contacts.ball_contacts(module, np.radians([0.0, 2.0, -1.0, 3.0, 1.0, 0.5]))
    loads = np.array([40.0, 60.0, 50.0, 45.0, 70.0, 55.0])
    patterns = (np.zeros(6), np.array([0.0, 1e-3, 0.0, 0.0, 2e-3, 0.0]), np.array([1e-3, 0.0, 0.0, 1e-3, 0.0, 0.0]))
    first = [b2b.solve(contacts, loads, gaps, ring=True) for gaps in patterns]
    again = [b2b.solve(contacts, loads, gaps, ring=True) for gaps in patterns[::-1]][::-1]
    for gaps, one, two in zip(patterns, first, again):
        assert np.array_equal(one.b2b_force, two.b2b_force) and np.array_equal(one.orbit_speed, two.orbit_speed)
        assert np.all(one.b2b_force[gaps > 0.0] == 0.0)
        touching = np.flatnonzero(gaps <= 1e-12)
        layout, live = b2b._chain_layout(6, sb.N_UNKNOWNS + 1, touching.tobytes(), True, 0)
        direct = ChainLayout(6, sb.N_UNKNOWNS + 1, touching, ring=True)
        assert np.array_equal(layout.touching, touching) and np.array_equal(live, direct.live)
        assert np.array_equal(layout.pairs, direct.pairs) and not live.flags.writeable
    weights = b2b._chain_weights(module.friction_coefficient, 6, True, 0)
    assert np.array_equal(weights, np.tile(row_weights(friction_coefficient=module.friction_coefficient, balls=1,
                                                       axial=1, extra=1), 6))


def test_kernel_warm_ups_compile_the_types_the_solves_pass():
    """numba compiles a read-only array type apart from a writable one: the warm-ups (run when a kernel module is
    loaded) pass the chain's constant arrays read-only as a solve's _ChainSetup holds them, so a fresh process's
    two-ball solve and whole screw run on the warmed-up specialisation (one signature each) and do not compile or
    load another (the warm-ups passed writable arrays: two signatures each); the ball terms' nut shift is always a
    writable copy (a per-ball shift used to reach the kernel read-only, a scalar one writable)."""
    import subprocess
    import sys

    pytest.importorskip("numba")
    code = """
from ballbench.lowmodel import kernels
from ballbench.lowmodel.screw import b2b, ball, contacts, whole_screw
kernels.use_kernels(True)
compiled = [kernels.load(name) for name in (b2b.RING_KERNELS, ball.KERNELS)]
module = contacts.screw_module(oversize=1.7e-6)
whole_screw.simulate(module, n_balls=8, axial_load=200.0, steps=2)
b2b.solve(contacts.ball_contacts(module, [0.0, 0.03]), 50.0)
ball.solve(contacts.ball_contacts(module, 0.0), 30.0)
print(*(len(kernel.newton.signatures) for kernel in compiled), len(compiled[1].ball_terms.signatures))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["1", "1", "1"], out.stdout
