"""Ball-screw solves at small friction coefficients (lin2019 Table 4 module): scale-aware tolerances and reasons.

The residual rows are in units of mu F_ref; the rows that sum normal contact forces carry a round-off of
~eps lever / mu in those units (lowmodel.solvers.equilibrium_tolerance), which passed the fixed tolerance of
1e-10 below mu ~ 1e-4: every solve failed with "no descent step".  docs/ball_screw.md.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import solvers
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import convergence
from ballbench.lowmodel.screw import b2b
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts

TABLE4_PRELOAD = 1.6848e-6  # m, the oversize fitted on lin2019 Table 3 case (a) (docs/ball_screw.md)


@pytest.mark.parametrize("mu", [1e-5, 1e-4])
def test_single_ball_converges_at_small_mu(mu):
    module = screw_contacts.screw_module(friction_coefficient=mu, oversize=TABLE4_PRELOAD)
    state = sb.solve(screw_contacts.ball_contacts(module, 0.02), 25.0)
    # the physics of the converged state, checked apart from the solver's residual: power balance (the losses
    # shrink with mu, the balance is relative), every contact dissipates, and the contact forces tend to the
    # frictionless ones (the state at mu differs from the one at mu / 10 by O(mu) in the forces)
    assert abs(state.input_power - state.groove_loss) < 1e-8 * state.groove_loss
    assert np.all(state.friction_loss >= 0.0)
    tenth_module = screw_contacts.screw_module(friction_coefficient=mu / 10, oversize=TABLE4_PRELOAD)
    tenth = sb.solve(screw_contacts.ball_contacts(tenth_module, 0.02), 25.0)
    assert np.max(np.abs(state.normal_force - tenth.normal_force)) < 10 * mu * np.max(state.normal_force)
    assert state.orbit_speed == pytest.approx(tenth.orbit_speed, rel=10 * mu)


def test_chain_with_ball_to_ball_contact_converges_at_small_mu():
    module = screw_contacts.screw_module(friction_coefficient=1e-5, oversize=TABLE4_PRELOAD)
    state = b2b.solve(screw_contacts.ball_contacts(module, [0.0, 0.01, -0.01]), 75.0)
    assert np.all(state.b2b_force >= 0.0)
    assert abs(state.input_power - state.total_loss) < 1e-8 * state.total_loss


def test_no_state_without_preload_is_named_with_its_evidence():
    # without preload at small mu the light contact slides fully where the continuation stops (the same state
    # a continuation in mu reaches): a reason from that state, not "stalled"
    module = screw_contacts.screw_module(friction_coefficient=1e-3)
    with pytest.raises(ConvergenceError, match=r"\|c/a\| up to") as caught:
        sb.solve(screw_contacts.ball_contacts(module, 0.0), 25.0)
    assert caught.value.reason == "a contact slides fully"
    with pytest.raises(ConvergenceError) as chained:
        b2b.solve(screw_contacts.ball_contacts(module, [0.0, 0.01]), 50.0)
    assert chained.value.reason == "a contact slides fully"


def test_every_screw_convergence_error_has_a_reason():
    module = screw_contacts.screw_module(oversize=1e-6)
    with pytest.raises(ConvergenceError) as caught:
        sb.solve(screw_contacts.ball_contacts(module), 25.0, max_iterations=1)
    assert caught.value.reason
    with pytest.raises(ConvergenceError) as caught:
        b2b.solve(screw_contacts.ball_contacts(module, [0.0, 0.01]), 50.0, max_iterations=1)
    assert caught.value.reason


def test_equilibrium_tolerance_floor():
    eps = np.finfo(float).eps
    assert solvers.equilibrium_tolerance(1e-10, 0.1, 100.0) == 1e-10  # the floor (1.4e-12) below: unchanged
    assert solvers.equilibrium_tolerance(1e-10, 1e-5, 100.0) == pytest.approx(64 * eps * 100.0 / 1e-5)
    rows = convergence.row_tolerances(1e-10, friction_coefficient=1e-5, groove_radius=3e-3, ball_radius=2.7e-3,
                                      approach=3e-6, balls=2, axial=1, extra=1)
    normal = 64 * eps * 100.0 / 1e-5
    expected = [normal, 1e-10, normal, 1e-10, 1e-10, 1e-10] * 2 + [normal, 1e-10]
    np.testing.assert_allclose(rows, expected, rtol=1e-12)
    weights = convergence.row_weights(friction_coefficient=1e-5, balls=1, axial=1)
    np.testing.assert_allclose(weights, [1e-4, 1, 1e-4, 1, 1, 1, 1e-4])
    assert np.all(convergence.row_weights(friction_coefficient=0.3, balls=1, axial=1) == 1.0)


def test_newton_never_passes_a_nan_residual_as_converged():
    # max(|r|) of a NaN residual is NaN, and NaN > tolerance is False: newton returned at once
    def function(x):
        return np.array([math.nan]), np.eye(1)

    with pytest.raises(ConvergenceError) as caught:
        solvers.newton(function, np.zeros(1), tolerance=1e-10, max_iterations=5, what="nan")
    assert caught.value.reason == "non-finite residual"
