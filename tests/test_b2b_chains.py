"""Long B2B chains (issue 10 item 7): the block-tridiagonal Jacobian built directly, sparse for long chains."""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel.linear_bearing import b2b


def _chain(n_balls, seed=3):
    rng = np.random.default_rng(seed)
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=n_balls)
    gaps = np.where(rng.random(n_balls - 1) < 0.7, 0.0, rng.uniform(0.0, 5e-4, n_balls - 1))
    return contacts, gaps


def test_sparse_and_dense_assembly_agree(monkeypatch):
    """The same chain with the sparse (CSR, banded Cholesky) and the dense route: the same state."""
    contacts, gaps = _chain(45)
    sparse = b2b.solve(contacts, gaps)
    monkeypatch.setattr(b2b, "SPARSE_BALLS", 10_000)
    dense = b2b.solve(contacts, gaps)
    assert sparse.iterations == dense.iterations
    np.testing.assert_allclose(sparse.ball_velocity, dense.ball_velocity, rtol=1e-12)
    np.testing.assert_allclose(sparse.b2b_force, dense.b2b_force, rtol=1e-9, atol=1e-12)


def test_small_chain_through_the_sparse_route(monkeypatch):
    """Force the sparse route for a 3-ball chain (one open gap): same state as the dense route."""
    contacts, _ = _chain(3)
    gaps = np.array([0.0, 1e-4])
    dense = b2b.solve(contacts, gaps)
    monkeypatch.setattr(b2b, "SPARSE_BALLS", 1)
    sparse = b2b.solve(contacts, gaps)
    np.testing.assert_allclose(sparse.ball_velocity, dense.ball_velocity, rtol=1e-12)
    np.testing.assert_allclose(sparse.b2b_force, dense.b2b_force, rtol=1e-9, atol=1e-12)


def test_thousand_ball_chain():
    contacts, gaps = _chain(1000)
    state = b2b.solve(contacts, gaps)
    assert state.residual <= 1e-12
    assert abs(state.input_power - state.total_loss) / abs(state.input_power) < 1e-8
    touching = gaps == 0.0
    assert np.all(state.b2b_force[~touching] == 0.0)
    assert np.all(np.diff(state.ball_velocity)[state.b2b_force > 0] < 1e-12 * 0.01)  # pressed pairs move together
