"""Long B2B chains (issue 10 item 7): the block-tridiagonal Jacobian built directly, as block diagonals (banded
Cholesky of J^T J) from SPARSE_BALLS balls, dense below."""
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
    """The same chain with the block (banded Cholesky of J^T J) and the dense route: the same state."""
    contacts, gaps = _chain(45)
    sparse = b2b.solve(contacts, gaps)
    monkeypatch.setattr(b2b, "SPARSE_BALLS", 10_000)
    dense = b2b.solve(contacts, gaps)
    assert sparse.iterations == dense.iterations
    np.testing.assert_allclose(sparse.ball_velocity, dense.ball_velocity, rtol=1e-12)
    np.testing.assert_allclose(sparse.b2b_force, dense.b2b_force, rtol=1e-9, atol=1e-12)


def test_small_chain_through_the_sparse_route(monkeypatch):
    """Force the block route for a 3-ball chain (one open gap): same state as the dense route."""
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


def test_block_tridiagonal_products_equal_dense():
    """matvec, rmatvec and the banded normal matrix J^T J of lowmodel.solvers.BlockTridiagonal against the dense
    matrix (catches a block put on the wrong side of the diagonal, a missing U^T U / L^T L term, a transposed
    block in the band storage)."""
    from ballbench.lowmodel.solvers import BlockTridiagonal

    rng = np.random.default_rng(7)
    for n, k in ((1, 3), (2, 8), (3, 4), (9, 8)):
        blocks = [rng.normal(size=(n, k, k)) for _ in range(3)]
        matrix = BlockTridiagonal(*blocks)
        dense = matrix.toarray()
        # the dense matrix from its definition, block by block
        expected = np.zeros((n * k, n * k))
        for i in range(n):
            for j, part in ((i - 1, blocks[0]), (i, blocks[1]), (i + 1, blocks[2])):
                if 0 <= j < n:
                    expected[i * k:(i + 1) * k, j * k:(j + 1) * k] = part[i]
        np.testing.assert_array_equal(dense, expected)
        x = rng.normal(size=n * k)
        np.testing.assert_allclose(matrix.matvec(x), expected @ x, rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(matrix.rmatvec(x), expected.T @ x, rtol=1e-13, atol=1e-13)
        band = matrix.normal_band().storage
        normal = expected.T @ expected
        rows, cols = np.tril_indices(n * k)
        keep = rows - cols < band.shape[0]
        np.testing.assert_allclose(band[rows[keep] - cols[keep], cols[keep]], normal[rows[keep], cols[keep]],
                                   rtol=1e-12, atol=1e-12)
        assert np.all(normal[rows[~keep], cols[~keep]] == 0.0)  # nothing outside the band


def test_coupled_jacobian_equals_finite_differences():
    """The block Jacobian of b2b.coupled_system (7 balls, two open pairs) against central differences of its
    residual: catches a wrong coupling block (B2B moment, force columns, complementarity rows)."""
    from ballbench.lowmodel.linear_bearing import ball as bearing_ball

    contacts, _ = _chain(7)
    touching = np.array([0, 1, 3, 5])
    reference_force = float(contacts.normal_forces.max())
    rng = np.random.default_rng(1)

    def ball_function(balls):
        terms = bearing_ball.ball_terms(balls, contacts, reference_force)
        return terms.residual, terms.jacobian

    function, unpack, pack = b2b.coupled_system(ball_function, 7, bearing_ball.N_UNKNOWNS, touching, 0.1)
    balls = bearing_ball.initial_guess(contacts) + 0.01 * rng.normal(size=(7, bearing_ball.N_UNKNOWNS))
    z = pack(balls)
    z[8 * touching[:2] + 7] = 0.5  # forces on the F > 0 branch (pairs 0, 1) ...
    z[8 * touching[2:] + 7] = -1.0  # ... and on the F = 0 branch (pairs 3, 5): away from the kink of min()
    residual, jacobian = function(z)
    dense = jacobian if isinstance(jacobian, np.ndarray) else jacobian.toarray()
    step = 1e-6
    numeric = np.empty_like(dense)
    for column in range(z.size):
        shift = np.zeros(z.size)
        shift[column] = step
        numeric[:, column] = (function(z + shift)[0] - function(z - shift)[0]) / (2 * step)
    np.testing.assert_allclose(dense, numeric, rtol=1e-6, atol=1e-7)
    got_balls, forces = unpack(z)
    np.testing.assert_array_equal(got_balls, balls)
    np.testing.assert_array_equal(forces, [0.5, 0.5, 0.0, -1.0, 0.0, -1.0])
