"""Long B2B chains: the block-tridiagonal Jacobian of lowmodel.b2b_chain built directly, as block diagonals (banded
Cholesky of J^T J) from SPARSE_BALLS balls, dense below; rings and global unknowns as CSR blocks."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import b2b_chain
from ballbench.lowmodel.linear_bearing import b2b
from hypothesis import given
from tests.property_support import EXTREME, SETTINGS, call, mostly, real


def _chain(n_balls, seed=3):
    rng = np.random.default_rng(seed)
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=n_balls)
    gaps = np.where(rng.random(n_balls - 1) < 0.7, 0.0, rng.uniform(0.0, 5e-4, n_balls - 1))
    return contacts, gaps


def test_sparse_and_dense_assembly_agree(monkeypatch):
    """The same chain with the block (banded Cholesky of J^T J) and the dense route: the same state."""
    contacts, gaps = _chain(45)
    sparse = b2b.solve(contacts, gaps)
    monkeypatch.setattr(b2b_chain, "SPARSE_BALLS", 10_000)
    dense = b2b.solve(contacts, gaps)
    assert sparse.iterations == dense.iterations
    np.testing.assert_allclose(sparse.ball_velocity, dense.ball_velocity, rtol=1e-12)
    np.testing.assert_allclose(sparse.b2b_force, dense.b2b_force, rtol=1e-9, atol=1e-12)


def test_small_chain_through_the_sparse_route(monkeypatch):
    """Force the block route for a 3-ball chain (one open gap): same state as the dense route."""
    contacts, _ = _chain(3)
    gaps = np.array([0.0, 1e-4])
    dense = b2b.solve(contacts, gaps)
    monkeypatch.setattr(b2b_chain, "SPARSE_BALLS", 1)
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


def _finite_differences(function, z, step=1e-6):
    numeric = np.empty((z.size, z.size))
    for column in range(z.size):
        shift = np.zeros(z.size)
        shift[column] = step
        numeric[:, column] = (function(z + shift)[0] - function(z - shift)[0]) / (2 * step)
    return numeric


def _dense(jacobian):
    return jacobian if isinstance(jacobian, np.ndarray) else jacobian.toarray()


def test_coupled_jacobian_equals_finite_differences():
    """The block Jacobian of b2b.coupled_system (7 balls, two open pairs) against central differences of its
    residual: catches a wrong coupling block (B2B moment, force columns, complementarity rows)."""
    from ballbench.lowmodel.linear_bearing import ball as bearing_ball

    contacts, _ = _chain(7)
    touching = np.array([0, 1, 3, 5])
    reference_force = float(contacts.normal_forces.max())
    rng = np.random.default_rng(1)

    def ball_function(balls, _extra=None):
        terms = bearing_ball.ball_terms(balls, contacts, reference_force)
        return b2b_chain.BallBlocks(terms.residual, terms.jacobian)

    layout = b2b_chain.ChainLayout(7, bearing_ball.N_UNKNOWNS, touching)
    function = b2b.coupled_system(ball_function, layout, 0.1)
    balls = bearing_ball.initial_guess(contacts) + 0.01 * rng.normal(size=(7, bearing_ball.N_UNKNOWNS))
    z = layout.pack(balls)
    z[8 * touching[:2] + 7] = 0.5  # forces on the F > 0 branch (pairs 0, 1) ...
    z[8 * touching[2:] + 7] = -1.0  # ... and on the F = 0 branch (pairs 3, 5): away from the kink of min()
    residual, jacobian = function(z)
    np.testing.assert_allclose(_dense(jacobian), _finite_differences(function, z), rtol=1e-6, atol=1e-7)
    got_balls, forces, extra = layout.unpack(z)
    np.testing.assert_array_equal(got_balls, balls)
    np.testing.assert_array_equal(forces, [0.5, 0.5, 0.0, -1.0, 0.0, -1.0])
    assert extra.size == 0


def _toy_chain(n, k, g, rng):
    """A ball function with dense random couplings to g global unknowns, and a smooth pair law coupling
    both balls of a pair to each other and to the pair force (every block of the chain nonzero)."""
    weights = rng.normal(size=(k, k))
    coupling = rng.normal(size=(n, k, g))
    rows = rng.normal(size=(g, n, k))

    def ball_function(balls, extra):
        residual = np.sin(balls) @ weights.T + np.einsum("jkg,g->jk", coupling, extra)
        jacobian = weights[None, :, :] * np.cos(balls)[:, None, :]
        if not g:
            return b2b_chain.BallBlocks(residual, jacobian)
        return b2b_chain.BallBlocks(residual, jacobian, coupling, np.einsum("gjk,jk->g", rows, balls) + extra ** 3,
                                    rows, np.diag(3 * extra ** 2))

    def pair_function(pairs):
        def function(balls, forces):
            behind, ahead = pairs[:, 0], pairs[:, 1]
            mix = balls[behind, 0] * balls[ahead, 1]  # (p,)
            load = np.zeros((n, k))
            np.add.at(load[:, 0], behind, forces * mix)
            np.add.at(load[:, 1], ahead, -forces * mix)
            d_balls = np.zeros((len(pairs), 2, 2, k, k))
            d_balls[:, 0, 0, 0, 0] = forces * balls[ahead, 1]
            d_balls[:, 0, 1, 0, 1] = forces * balls[behind, 0]
            d_balls[:, 1, 0, 1, 0] = -forces * balls[ahead, 1]
            d_balls[:, 1, 1, 1, 1] = -forces * balls[behind, 0]
            d_force = np.zeros((len(pairs), 2, k))
            d_force[:, 0, 0], d_force[:, 1, 1] = mix, -mix
            return b2b_chain.PairBlocks(load, d_balls, d_force, np.abs(mix))
        return function

    return ball_function, pair_function


@pytest.mark.parametrize("n, ring, g, complementarity", [(4, True, 0, "min"), (7, True, 1, "fischer-burmeister"),
                                                          (7, False, 2, "min"), (2, True, 1, "fischer-burmeister"),
                                                          (3, False, 0, "fischer-burmeister")])
def test_chain_jacobian_of_rings_and_global_unknowns(n, ring, g, complementarity):
    """lowmodel.b2b_chain.chain_system for rings (corner blocks), global unknowns (the bordered Jacobian) and both
    complementarity functions, dense and CSR, against central differences."""
    rng = np.random.default_rng(n + g)
    k = 3
    pairs_count = n if ring else n - 1
    touching = np.flatnonzero(rng.random(pairs_count) < 0.7)
    layout = b2b_chain.ChainLayout(n, k, touching, ring=ring, n_global=g)
    ball_function, pair_function = _toy_chain(n, k, g, rng)
    function = b2b_chain.chain_system(ball_function, pair_function(layout.pairs), layout, rate_index=2,
                                      rate_scale=10.0, complementarity=complementarity)
    z = layout.pack(rng.normal(size=(n, k)), np.where(rng.random(pairs_count) < 0.5, 2.0, -3.0),
                    rng.normal(size=g) + 1.5)
    residual, jacobian = function(z)
    assert residual.shape == (layout.size,)
    np.testing.assert_allclose(_dense(jacobian), _finite_differences(function, z), rtol=1e-6, atol=1e-7)
    if n >= b2b_chain.SPARSE_BALLS:
        assert not isinstance(jacobian, np.ndarray)


def test_chain_forces_checks_complementarity():
    """The one violation check: a negative force or a negative separation rate beyond 10 tolerance raises, a pair
    on the F = 0 branch gets exactly 0."""
    from ballbench.lowmodel.errors import ConvergenceError

    layout = b2b_chain.ChainLayout(3, 1, np.array([0, 1]))
    z = layout.pack(np.array([[0.0], [0.0], [1e-3]]), np.array([2.0, 1e-19]))
    balls, forces, _ = b2b_chain.chain_forces(z, layout, rate_index=0, rate_scale=10.0, tolerance=1e-10,
                                              iterations=1, what="toy")
    np.testing.assert_array_equal(forces, [2.0, 0.0])  # pair 1 separates: its round-off force is zeroed
    for bad in (layout.pack(np.zeros((3, 1)), np.array([-1e-8, 0.0])),
                layout.pack(np.array([[0.0], [-1e-8], [0.0]]), np.array([0.0, 0.0]))):
        with pytest.raises(ConvergenceError, match="complementarity violated"):
            b2b_chain.chain_forces(bad, layout, rate_index=0, rate_scale=10.0, tolerance=1e-10, iterations=1,
                                   what="toy")
    with pytest.raises(ValueError, match="complementarity"):
        b2b_chain.chain_system(None, None, layout, rate_index=0, rate_scale=1.0, complementarity="max")


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_fischer_burmeister_at_huge_arguments():
    """phi(0, 1e300) was -inf with an overflow warning; it is 0 (the complementarity holds)."""
    phi, d_a, d_b = b2b_chain.fischer_burmeister(0.0, 1e300)
    assert float(phi) == 0.0 and float(d_a) == 1.0 and float(d_b) == 0.0
    assert float(b2b_chain.fischer_burmeister(-1e300, -1e300)[0]) < 0.0
    with pytest.raises(ValueError, match="a must be finite"):
        b2b_chain.fischer_burmeister(math.nan, 1.0)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(a=mostly(real(-1e3, 1e3), *EXTREME, -1e300), b=mostly(real(-1e3, 1e3), *EXTREME, -1e300))
def test_fischer_burmeister(a, b):
    result = call(b2b_chain.fischer_burmeister, a, b)
    if result is not None:   # phi = 0 only on the complementarity set (eqs 60-61): < 0 outside, > 0 inside
        phi = float(result[0])
        scale = 1e-13 * max(abs(a), abs(b), 1.0)
        if min(a, b) < -scale:
            assert phi < 0.0
        elif min(a, b) > scale:
            assert phi > 0.0


def test_layout_keeps_its_touching_pairs():
    """A ChainLayout caches its live slots from ``touching``, so it holds ``touching`` read-only (a copy of a writable
    array: the caller's array stays writable and its later edits do not reach the layout); ``live`` is a new writable
    array at every read, as before the cache; pickle and deepcopy rebuild the layout through ``__init__``."""
    import copy
    import pickle

    touching = np.array([0, 2])
    layout = b2b_chain.ChainLayout(4, 3, touching, ring=True)
    assert np.array_equal(layout.live, [True, False, True, False])
    touching[1] = 3
    assert touching.flags.writeable and not layout.touching.flags.writeable
    assert np.array_equal(layout.touching, [0, 2]) and np.array_equal(layout.live, [True, False, True, False])
    live = layout.live
    live[1] = True   # the caller's array: the layout's slots stay
    assert np.array_equal(layout.live, [True, False, True, False])
    balls, forces, _ = layout.unpack(np.arange(layout.size, dtype=float))
    assert np.array_equal(forces, [3.0, 0.0, 11.0, 0.0])
    for rebuilt in (pickle.loads(pickle.dumps(layout)), copy.deepcopy(layout)):
        assert not rebuilt.touching.flags.writeable
        assert np.array_equal(rebuilt.live, layout.live) and np.array_equal(rebuilt.pairs, layout.pairs)
    listed = b2b_chain.ChainLayout(3, 2, [1])   # a list, as before
    assert np.array_equal(listed.live, [False, True, False])
