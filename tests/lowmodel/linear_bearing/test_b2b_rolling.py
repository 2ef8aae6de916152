"""lin2019's linear-bearing B2B solve with stick/slip ball-to-groove contacts (lowmodel.linear_bearing.b2b_rolling
over lowmodel.contact.rolling_friction; docs/b2b_rolling.md)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact import rolling_friction as rf
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling, b2b_traction

CELLS = (8, 32)
R_B, MU, V = 5e-3, 0.1, 0.01
COMMON = dict(ball_radius=R_B, friction_coefficient=MU, groove_velocity=V)


THETA = math.radians(2.0)  # lin2019 Tables 2-3


def linear_balls(theta=THETA, rho=-0.6, top=(0.0, 0.0), cells=CELLS, mu=MU, **options):
    contacts = b2b.module_contacts(theta, rho, top_deviations=top, friction_coefficient=mu)
    return contacts, [b2b_rolling.hertz_contacts(contacts, j, cells=cells, **options) for j in range(2)]


@pytest.fixture(scope="module")
def case_a():
    contacts, balls = linear_balls()
    return contacts, balls, b2b_rolling.module_b2b(balls, **COMMON)


def test_linear_case_a_power_balance_and_the_full_slip_limit_on_the_same_cells(case_a):
    contacts, balls, result = case_a
    for state in (result.touching, result.free, result.full_slip, result.full_slip_free):
        assert state.power_balance < 1e-6
    low = b2b.solve(contacts, [0.0])
    # near full slip (Lambda ~ 60, no stick): the stick/slip force is within 1 % of full slip on the same cells,
    # which is within 1 % of lin2019's low-order model (Heathcote's slip and the grid)
    assert result.b2b_force[0] == pytest.approx(result.full_slip.b2b_force[0], rel=0.01)
    assert result.full_slip.b2b_force[0] == pytest.approx(low.b2b_force[0], rel=0.01)
    assert result.b2b_force[0] != result.full_slip.b2b_force[0]
    lam = [c.spin_parameter for row in result.touching.contacts for c in row]
    assert 40.0 < min(lam) and max(lam) < 90.0
    # the slower ball behind is pushed: complementarity, equal velocities
    assert result.touching.ball_velocity[0] == pytest.approx(result.touching.ball_velocity[1], rel=1e-9)
    assert result.free.ball_velocity[0] > result.free.ball_velocity[1]


def test_full_slip_law_of_the_evaluator_is_the_sampled_coulomb_model(case_a):
    """The evaluator with the full-slip law has zero residual at the b2b_traction solution of the same cells."""
    _, balls, result = case_a
    patches = [[c.patch() for c in row] for row in balls]
    free = b2b_traction.solve(patches, gaps=[R_B], **COMMON)
    reference = max(p.normal_force for row in patches for p in row)
    friction = rf.StickSlipFriction(balls, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, reference, 1.0, V,
                                    law="full-slip")
    states = np.column_stack([free.ball_velocity / V, free.omega * R_B / V])
    residual = friction.evaluate(states, jacobian=False)[0]
    assert np.max(np.abs(residual)) < 1e-8
    # and the stick/slip law is not: the two differ by stick/slip and elastic creep
    stick = rf.StickSlipFriction(balls, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, reference, 1.0, V)
    assert np.max(np.abs(stick.evaluate(states, jacobian=False)[0])) > 1e-4


def test_finite_difference_jacobian_matches_central_differences(case_a):
    _, balls, result = case_a
    reference = max(c.normal_force for row in balls for c in row)
    friction = rf.StickSlipFriction(balls, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, reference, 1.0, V)
    x = np.column_stack([result.free.ball_velocity / V, result.free.omega * R_B / V])
    _, jac, _, _ = friction.evaluate(x, ball=0)
    h = 1e-5
    for j in range(3):
        up, down = x.copy(), x.copy()
        up[0, j] += h
        down[0, j] -= h
        central = (friction.evaluate(up, jacobian=False, ball=0)[0] - friction.evaluate(down, jacobian=False,
                                                                                           ball=0)[0]) / (2 * h)
        assert jac[:, j] == pytest.approx(central, rel=1e-3, abs=1e-4 * np.abs(jac).max())


def test_theta_zero_gives_no_b2b_force():
    _, balls = linear_balls(theta=0.0)
    result = b2b_rolling.module_b2b(balls, **COMMON)
    assert result.b2b_force[0] == 0.0 and result.full_slip.b2b_force[0] == 0.0
    assert result.free.velocity_deviation == pytest.approx([0.0, 0.0], abs=1e-10)
    assert result.power_balance < 1e-6


def test_case_b_mitigating_top_groove_gives_no_b2b_force():
    _, balls = linear_balls(top=(-math.radians(2.0), math.radians(2.0)))
    result = b2b_rolling.module_b2b(balls, **COMMON)
    assert result.b2b_force[0] < 1e-9 * MU * 100.0  # round-off: the two balls roll at v/2 exactly
    assert abs(result.free.velocity_deviation).max() < 1e-9


def test_stick_slip_tends_to_full_slip_as_lambda_grows():
    """Lambda = |phi| b G / (mu p0) ~ 1 / mu: each contact's friction approaches full slip on the same cells, and
    so does the B2B force (whose difference to full slip is below 0.3 % already at Lambda ~ 14 for this case:
    measured -0.2 .. +0.2 % over grids of 8 x 32 to 20 x 80 cells, docs/b2b_rolling.md)."""
    lambdas, forces, contacts_ = [], [], []
    for mu in (0.4, 0.1, 0.025, 0.00625):
        contacts, balls = linear_balls(mu=mu)
        result = b2b_rolling.module_b2b(balls, ball_radius=R_B, friction_coefficient=mu, groove_velocity=V)
        lambdas.append(min(c.spin_parameter for row in result.touching.contacts for c in row))
        forces.append(abs(result.b2b_force[0] / result.full_slip.b2b_force[0] - 1.0))
        contacts_.append(max(abs(s.along_groove - f.along_groove) / (mu * s.normal_force)
                             for row, full_row in zip(result.free.contacts, result.full_slip_free.contacts)
                             for s, f in zip(row, full_row)))
    assert lambdas == sorted(lambdas) and lambdas[-1] > 60 * lambdas[0]
    # over the decades of Lambda (between Lambda 14 and 58 the light contacts' creepage moves too)
    assert contacts_[2] < 0.5 * min(contacts_[:2]) and contacts_[3] < 0.5 * contacts_[2]
    assert min(contacts_[:2]) > 3e-3 and contacts_[-1] < 3e-4
    assert max(forces) < 3e-3 and forces[-1] < 5e-4


def test_reversed_groove_velocity_mirrors_the_state(case_a):
    _, balls, result = case_a
    reverse = b2b_rolling.solve(balls, ball_radius=R_B, friction_coefficient=MU, groove_velocity=-V, gaps=[R_B])
    assert reverse.ball_velocity == pytest.approx(-result.free.ball_velocity, rel=1e-7)
    assert reverse.total_loss == pytest.approx(result.free.total_loss, rel=1e-7)


def test_a_dense_operator_gives_the_half_space_result():
    """The MatrixOperator path (an FE compliance) with the half-space's own matrix: the same state."""
    contacts, _ = linear_balls(cells=(6, 24))

    def dense(grid):
        operator = rolling.half_space_operator(grid, 2.1e11 / (2 * 1.28), 0.28)
        cells = np.arange(grid.nx * grid.ny)
        return rolling.MatrixOperator(grid, operator.dense(cells))

    balls = [b2b_rolling.hertz_contacts(contacts, j, cells=(6, 24)) for j in range(2)]
    matrix = [b2b_rolling.hertz_contacts(contacts, j, cells=(6, 24), operator_for=dense) for j in range(2)]
    first = b2b_rolling.solve(balls, **COMMON)
    second = b2b_rolling.solve(matrix, **COMMON)
    assert second.b2b_force[0] == pytest.approx(first.b2b_force[0], rel=1e-8)


def test_b2b_contact_slides_fully(case_a):
    ratio, creepage = b2b_rolling.b2b_contact_check(case_a[2].touching, ball_radius=R_B, friction_coefficient=MU)
    assert ratio == pytest.approx(1.0, abs=1e-4)
    assert creepage > 1e3


def test_sampled_contact_rebuilds_a_hertz_contact():
    """Hertz samples on the sphere as an FE pressure would come: the stick/slip module reproduces the Hertz grid's."""
    contacts, balls = linear_balls(cells=(12, 48))
    sampled = []
    for j in range(2):
        rows = []
        for patch in b2b_traction.hertz_patches(contacts, j, n_radial=48, n_angular=192, planar=False):
            normal = patch.centre / np.linalg.norm(patch.centre)
            local = patch.points - patch.centre
            # the area of a sample: its force over Hertz's pressure at it
            i = ["BL", "BR", "TR", "TL"].index(patch.name)
            a, b_ = contacts.semi_major[j, i], contacts.semi_major[j, i] * contacts.b_over_a[j, i]
            e1 = np.cross(normal, [0.0, 0.0, 1.0])
            rho2 = (local @ e1 / a) ** 2 + (local[:, 2] / b_) ** 2
            p = 1.5 * patch.normal_force / (math.pi * a * b_) * np.sqrt(np.clip(1.0 - rho2, 1e-12, None))
            rows.append((patch.name, patch.top, patch.points, p, patch.forces / p))
        sampled.append(b2b_rolling.sampled_contacts(rows, ball_radius=R_B, conformity=0.56, cells=(12, 48)))
    first = b2b_rolling.solve(balls, **COMMON)
    second = b2b_rolling.solve(sampled, **COMMON)
    assert second.b2b_force[0] == pytest.approx(first.b2b_force[0], rel=0.01)


def test_bad_input_names_the_parameter(case_a):
    contacts, balls, _ = case_a
    with pytest.raises(ValueError, match="law"):
        b2b_rolling.solve(balls, law="partial", **COMMON)
    with pytest.raises(ValueError, match="groove_velocity"):
        b2b_rolling.solve(balls, ball_radius=R_B, friction_coefficient=MU, groove_velocity=0.0)
    with pytest.raises(ValueError, match="friction_coefficient"):
        b2b_rolling.solve(balls, ball_radius=R_B, friction_coefficient=-0.1, groove_velocity=V)
    contact = balls[0][0]
    with pytest.raises(ValueError, match="does not cover"):
        rf.grid_contact("BL", False, contact.grid, np.ones((contact.grid.nx, contact.grid.ny)), contact.centre,
                        contact.normal, contact.axis, lateral_curvature=0.0, shear_modulus=8e10, poisson_ratio=0.28)
    other = rolling.hertz_grid(1e-4, 4e-4, (4, 8))
    with pytest.raises(ValueError, match="operator's grid"):
        rf.grid_contact("BL", False, contact.grid, contact.pressure, contact.centre, contact.normal, contact.axis,
                        lateral_curvature=0.0, shear_modulus=8e10, poisson_ratio=0.28,
                        operator=rolling.half_space_operator(other, 8e10, 0.28))
    with pytest.raises(ValueError, match="axis"):
        rf.contact_frame([0.0, 0.0, 1.0], [0.0, 0.0, 2.0])


def test_a_non_converged_solve_raises_with_its_residual(case_a):
    _, balls, _ = case_a
    with pytest.raises(ConvergenceError) as info:
        b2b_rolling.solve(balls, max_iterations=1, tolerance=1e-14, **COMMON)
    assert info.value.residual > info.value.tolerance


def test_power_balance_check_rejects_a_wrong_loss(case_a, monkeypatch):
    """A contact loss off by 1e-4 (a wrong rigid power) is caught by the solve's own check."""
    _, balls, _ = case_a
    original = rf.StickSlipFriction._summary

    def off(self, *args):
        summary = original(self, *args)
        return dataclasses.replace(summary, rigid_power=summary.rigid_power * (1 + 1e-4))

    monkeypatch.setattr(rf.StickSlipFriction, "_summary", off)
    with pytest.raises(ConvergenceError, match="power balance"):
        b2b_rolling.solve(balls, **COMMON)


def test_grid_contacts_reproduce_the_rolling_contacts_of_a_ball_state():
    """The engine's frames, rolling direction and slip field against lowmodel.linear_bearing.rolling_contacts, which
    derives each contact's Kalker frame, creepages and spin on its own (docs/rolling_contact.md): at the low-order
    free-ball state both solve the same rolling problems."""
    from ballbench.lowmodel.linear_bearing import ball, rolling_contacts

    contacts = b2b.module_contacts(math.radians(2.0), -0.6).ball(0)
    state = ball.solve(contacts)
    reference = rolling_contacts.solve_contacts(contacts, state, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28,
                                                cells=(10, 40), tolerance=1e-12)
    grid_contacts = [b2b_rolling.hertz_contacts(contacts, 0, cells=(10, 40))]
    friction = rf.StickSlipFriction(grid_contacts, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, 100.0, 1.0, V)
    x = np.array([[state.ball_velocity[0] / V, *(state.omega[0] * R_B / V)]])
    for mine, theirs in zip(friction.summaries(x)[0], reference):
        scale = MU * theirs.motion.normal_force
        assert mine.along_groove == pytest.approx(theirs.friction_force, abs=1e-9 * scale)
        assert mine.lateral == pytest.approx(theirs.lateral_force, abs=1e-9 * scale)
        assert mine.spin_moment == pytest.approx(theirs.spin_moment, abs=1e-9 * scale * 1e-3)
        assert mine.spin_parameter == pytest.approx(theirs.spin_parameter, rel=0.02)  # moment axes vs Hertz's


def test_the_rolling_start_of_a_symmetric_ball_is_rolling_at_half_the_groove_speed():
    """The rolling start (StickSlipFriction.rolling_start) of a ball whose four contacts are alike (theta 0, rho 0):
    by symmetry the centre moves at v/2 (the bottom groove at rest, the top at v) and the ball does not yaw
    (omega_y = 0); the least-squares slip is then orthogonal to every column (its normal equations)."""
    contacts, balls = linear_balls(theta=0.0, rho=0.0)
    state = b2b_rolling.solve(balls[:1], start="rolling", **COMMON)
    start = rf.StickSlipFriction([balls[0]], lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, 1.0, 1.0,
                                 V).rolling_start()[0]
    assert start[0] == pytest.approx(0.5, abs=1e-12) and abs(start[2]) < 1e-12
    assert state.ball_velocity[0] == pytest.approx(0.5 * V, rel=1e-9)  # the solved ball: v/2 by the same symmetry


def test_the_stick_slip_state_from_rolling_is_the_state_from_full_slip(case_a):
    """Where full slip has a state, the stick/slip solve reaches the same state from the rolling start as from full
    slip (touching and free balls): the start does not choose the answer."""
    contacts, balls, result = case_a
    for gaps, reference in ((None, result.touching), ([R_B], result.free)):
        state = b2b_rolling.solve(balls, gaps=gaps, start="rolling", **COMMON)
        assert state.b2b_force == pytest.approx(reference.b2b_force, rel=1e-7, abs=1e-9)
        assert state.ball_velocity == pytest.approx(reference.ball_velocity, rel=1e-9)
        assert state.omega == pytest.approx(reference.omega, rel=1e-6, abs=1e-9 * V / R_B)
    auto = b2b_rolling.solve(balls, start="auto", **COMMON)
    assert auto.b2b_force == pytest.approx(result.touching.b2b_force, rel=1e-7)
    with pytest.raises(ValueError, match="start"):
        b2b_rolling.solve(balls, start="rolling", law="full-slip", **COMMON)


def test_a_warm_start_reaches_the_same_state(case_a):
    """A state of the balls at a nearby deviation (2.1 deg) starts the solve at 2 deg: the same state as from full
    slip (B2B force 1e-7, velocities 1e-9); with ``start="auto"`` full slip, which has a state here, goes first and
    the result is bit for bit the one without ``warm``; a warm state far off (the balls spinning, a huge B2B force)
    falls back to the cold start; a warm state of another number of balls is refused."""
    contacts, balls, result = case_a
    _, near = linear_balls(theta=math.radians(2.1))
    warm = b2b_rolling.solve(near, **COMMON)
    state = b2b_rolling.solve(balls, warm=warm, **COMMON)
    assert state.b2b_force == pytest.approx(result.touching.b2b_force, rel=1e-7, abs=1e-9)
    assert state.ball_velocity == pytest.approx(result.touching.ball_velocity, rel=1e-9)
    assert state.omega == pytest.approx(result.touching.omega, rel=1e-6, abs=1e-9 * V / R_B)
    auto = b2b_rolling.solve(balls, start="auto", warm=warm, **COMMON)
    cold = b2b_rolling.solve(balls, start="auto", **COMMON)
    assert np.array_equal(auto.b2b_force, cold.b2b_force) and np.array_equal(auto.omega, cold.omega)
    far = dataclasses.replace(warm, ball_velocity=np.zeros(2), omega=np.full((2, 2), 1e3), b2b_force=np.array([1e6]))
    fallback = b2b_rolling.solve(balls, warm=far, **COMMON)
    assert fallback.b2b_force == pytest.approx(result.touching.b2b_force, rel=1e-7, abs=1e-9)
    with pytest.raises(ValueError, match="warm"):
        b2b_rolling.solve(balls[:1], warm=warm, **COMMON)


def test_the_spin_to_roll_ratio_is_the_ball_s_rotation_against_the_contact_normal():
    """A ball whose four contacts are alike (theta 0, rho 0) rolls about the lateral axis: at every 45 deg contact its
    rotation has equal parts about the contact normal (spin) and in the tangent plane (roll), a spin-to-roll ratio
    of tan 45 deg = 1 from the ball's own omega (the curved contact surface's rolling radius moves it by 1e-3)."""
    contacts, balls = linear_balls(theta=0.0, rho=0.0, cells=(12, 48))
    state = b2b_rolling.solve(balls[:1], **COMMON)
    omega = np.array([*state.omega[0], 0.0])
    for contact, summary in zip(balls[0], state.contacts[0]):
        spin = float(omega @ contact.normal)
        roll = float(np.linalg.norm(omega - spin * contact.normal))
        assert abs(spin) / roll == pytest.approx(1.0, rel=1e-12)
        assert summary.spin_to_roll == pytest.approx(abs(spin) / roll, rel=1e-3)


def test_a_chain_from_its_balls_alone_reaches_the_state_from_full_slip(case_a):
    """``start="alone"``: each ball solved alone, then the touching balls from those states with the B2B force from
    zero: the state from full slip (B2B force 1e-7, velocities 1e-9); refused for balls that do not touch."""
    contacts, balls, result = case_a
    state = b2b_rolling.solve(balls, start="alone", **COMMON)
    assert state.b2b_force == pytest.approx(result.touching.b2b_force, rel=1e-7, abs=1e-9)
    assert state.ball_velocity == pytest.approx(result.touching.ball_velocity, rel=1e-9)
    assert state.omega == pytest.approx(result.touching.omega, rel=1e-6, abs=1e-9 * V / R_B)
    with pytest.raises(ValueError, match="alone"):
        b2b_rolling.solve(balls, start="alone", gaps=[1e-3], **COMMON)


def test_a_chain_of_balls_with_different_numbers_of_contacts():
    """Balls of one chain need not carry as many contacts (a carriage's ball in its end relief beside four-point
    ones): three touching balls whose middle one carries a contact of 1e-6 of its load equal, within that share of
    the friction, the chain whose middle ball has that contact left out (the law's loads are the given normal forces,
    so a vanishing contact is a vanishing friction); the full-slip law and start, which take as many contacts per
    ball, are refused by name."""
    contacts = b2b.module_contacts(THETA, -0.6, friction_coefficient=MU)
    rows = [contacts.contact_angles[0], contacts.normal_forces[0], contacts.semi_major[0], contacts.b_over_a[0]]
    angles, forces, semi, ratio = (np.stack([row, row, row]) for row in rows)
    forces = forces.copy()
    semi = semi.copy()
    forces[1, 3] = 1e-6 * forces[1].max()  # TL of the middle ball: nearly unloaded (Hertz: a ~ F^(1/3))
    semi[1, 3] = semi[1, 2] * (forces[1, 3] / forces[1, 2]) ** (1.0 / 3.0)

    def chain(drop: bool):
        balls = []
        for k in range(3):
            f = forces[k].copy()
            if drop and k == 1:
                f[3] = 0.0  # left out by loaded_contacts
            balls.append(b2b_rolling.loaded_contacts(angles[k], f, semi[k], ratio[k], ball_radius=R_B, cells=CELLS))
        return balls

    full, three = chain(False), chain(True)
    assert [len(b) for b in three] == [4, 3, 4]
    with_light = b2b_rolling.solve(full, start="auto", **COMMON)
    without = b2b_rolling.solve(three, start="auto", **COMMON)
    scale = MU * forces.max()
    assert np.max(np.abs(without.b2b_force - with_light.b2b_force)) < 1e-5 * scale
    assert without.ball_velocity == pytest.approx(with_light.ball_velocity, rel=1e-5)
    assert without.friction_loss.shape == (3, 4) and without.friction_loss[1, 3] == 0.0
    assert without.power_balance < 1e-8 and without.b2b_force.max() > 0.01 * scale  # a pair carries B2B force
    with pytest.raises(ValueError, match="different numbers of contacts"):
        b2b_rolling.solve(three, **COMMON)  # the default start: full slip on the cells
    with pytest.raises(ValueError, match="different numbers of contacts"):
        b2b_rolling.solve(three, law="full-slip", start="auto", **COMMON)
