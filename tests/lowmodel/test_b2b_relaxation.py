"""The existence oracle of B2B states (lowmodel.b2b_relaxation): relaxation in time under the same friction laws."""
import math

import numpy as np
import pytest

from ballbench.lowmodel import b2b_relaxation as relaxation
from ballbench.lowmodel.b2b_chain import ChainLayout
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing.ball import N_UNKNOWNS, with_slip_angles
from ballbench.lowmodel.solvers import newton


@pytest.mark.parametrize("theta_deg, rho, mu, n_balls", [(2.0, -0.6, 0.1, 2), (2.0, -0.6, 1.0, 2),
                                                         (3.0, -0.7, 0.3, 2), (2.0, -0.6, 0.1, 5)])
def test_settles_where_newton_converges(theta_deg, rho, mu, n_balls):
    # a state exists: the relaxation settles on it (velocities and pair forces of the Newton solution)
    contacts = b2b.module_contacts(math.radians(theta_deg), rho, n_balls=n_balls, friction_coefficient=mu)
    state = b2b.solve(contacts)
    relaxed = b2b.relax_state(contacts)
    assert relaxed.settled and relaxed.reason == "" and relaxed.kind == ""
    reference = mu * float(contacts.normal_forces.max())
    np.testing.assert_allclose(relaxed.forces * reference, state.b2b_force, atol=1e-7 * reference)
    np.testing.assert_allclose(relaxed.velocities[:, 0] * contacts.groove_velocity, state.ball_velocity,
                               atol=1e-8 * contacts.groove_velocity)


def test_settled_state_is_a_newton_start():
    contacts = b2b.module_contacts(math.radians(3.0), -0.7, n_balls=2, friction_coefficient=0.3)
    relaxed = b2b.relax_state(contacts, [0.0])
    layout = ChainLayout(2, N_UNKNOWNS, np.array([0]))
    balls = np.zeros((2, N_UNKNOWNS))
    balls[:, :3] = relaxed.velocities
    start = layout.pack(with_slip_angles(balls, contacts), relaxed.forces)
    at = {}

    def ball_function(x, _extra=None):
        from ballbench.lowmodel.b2b_chain import BallBlocks
        from ballbench.lowmodel.linear_bearing.ball import ball_terms

        terms = ball_terms(x, contacts, float(contacts.normal_forces.max()))
        at["terms"] = terms
        return BallBlocks(terms.residual, terms.jacobian)

    system = b2b.coupled_system(ball_function, layout, contacts.friction_coefficient)
    _, residual, iterations = newton(system, start, tolerance=1e-12, max_iterations=10, what="from the relaxation")
    assert iterations <= 3 and np.max(np.abs(residual)) <= 1e-12


def test_quoted_case_is_a_contact_that_stops_sliding():
    # theta 2.87 deg, rho -0.83, N_y 128 N, mu 0.6 (spin-capacity ratio 1.70): Newton and continuation fail; the
    # relaxation shows the balls rolling on a diagonal with two contacts stalled (their friction chatters)
    contacts = b2b.module_contacts(math.radians(2.87), -0.83, n_balls=2, vertical_force=128.0,
                                   friction_coefficient=0.6)
    relaxed = b2b.relax_state(contacts, [0.0])
    assert not relaxed.settled and relaxed.kind == relaxation.STALL_REASON and relaxed.stalled is not None
    with pytest.raises(ConvergenceError) as error:
        b2b.solve(contacts, [0.0])
    assert error.value.reason.startswith("a contact stops sliding")  # the walks' account or the relaxation's
    assert "ball 0 contact BL" in str(error.value)
    assert error.value.relaxation.kind == relaxation.STALL_REASON


def _toy(drive):
    """Balls with a linear friction-like load pulling each velocity to ``drive`` (rates 1), no rotation."""
    def ball_loads(x):
        load = np.zeros_like(x)
        load[:, 0] = drive - x[:, 0]
        load[:, 1:] = -x[:, 1:]
        jacobian = np.broadcast_to(-np.eye(3), (x.shape[0], 3, 3)).copy()
        slip = np.stack([np.ones((x.shape[0], 4)), np.ones((x.shape[0], 4))], axis=-1)
        return load, jacobian, slip

    def pair_loads(x):
        direction = np.zeros((x.shape[0] - 1, 2, 3))
        direction[:, 0, 0], direction[:, 1, 0] = -1.0, 1.0
        return direction

    return ball_loads, pair_loads


def test_touching_pair_carries_the_force_that_keeps_it_together():
    # ball 0 driven to 1, ball 1 to 0.5: together they settle at 0.75 with the force 0.25 between them
    ball_loads, pair_loads = _toy(np.array([1.0, 0.5]))
    relaxed = relaxation.relax(ball_loads, pair_loads, np.zeros((2, 3)), touching=[True])
    assert relaxed.settled
    np.testing.assert_allclose(relaxed.velocities[:, 0], 0.75, atol=1e-9)
    np.testing.assert_allclose(relaxed.forces, [0.25], atol=1e-9)
    # driven apart: the pair opens, no force
    ball_loads, pair_loads = _toy(np.array([0.5, 1.0]))
    relaxed = relaxation.relax(ball_loads, pair_loads, np.zeros((2, 3)), touching=[True])
    assert relaxed.settled and relaxed.forces[0] == 0.0


def test_an_open_gap_that_closes_is_a_third_contact():
    ball_loads, pair_loads = _toy(np.array([1.0, 0.5, 0.5]))
    relaxed = relaxation.relax(ball_loads, pair_loads, np.zeros((3, 3)), touching=[False, True], gaps=[0.1, 0.0],
                               gap_scale=1.0)
    assert not relaxed.settled and relaxed.kind == relaxation.CONTACT_REASON
    assert "pair (0, 1)" in relaxed.reason
