"""The compiled ball-screw kernels (lowmodel.screw.ball_kernels) against the numpy code they mirror.

Both paths run in every test: the numpy path with the kernels switched off, the compiled one with them on.
Tolerances: the friction integrals and the ball terms agree to 1e-10 relative to each field's largest value (round-off
of sums taken in another order; observed up to 8e-12, in the friction moment of contacts whose velocity centre lies
far out, where the moment is a difference of terms R_c times larger); converged states to 1e-10 relative with the
same iteration count (observed 1e-14, docs/speed.md).
"""
import math
import platform
from pathlib import Path

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.contact.ellipse_friction_offset import FAR_CENTRE, disc_rule, friction_offset
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.quadrature import tanh_sinh
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as sc
from tests.kernel_support import both, kernels_on

TOLERANCE = 1e-10
OVERSIZE = 1.6848e-6  # m, the lin2019 Table 5 preload fit (docs/ball_screw.md)


@pytest.fixture
def compiled():
    yield from kernels_on(sb.KERNELS)


def _assert_close(a, b, name, tolerance=TOLERANCE):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape, name
    scale = max(float(np.max(np.abs(a), initial=0.0)), 1e-300)
    assert float(np.max(np.abs(a - b), initial=0.0)) <= tolerance * scale, name


def test_friction_offset_kernel_equals_numpy(compiled):
    # centre inside the ellipse, outside it (cone of rays), far out (disc rule), negative spin, slip only
    rng = np.random.default_rng(7)
    spin = np.concatenate([rng.normal(size=30), [0.0, 1e-3, -2.0]])
    slip_minor = np.concatenate([rng.normal(size=30) * rng.choice([0.1, 1.0, 300.0], size=30), [1.0, 0.5, 0.0]])
    slip_major = np.concatenate([rng.normal(size=30) * rng.choice([0.05, 1.0, 200.0], size=30), [0.3, 0.0, 0.7]])
    beta = rng.uniform(0.1, 1.0, size=33)
    out, jac, sums = np.empty(4), np.empty((4, 3)), np.empty(6)
    for level in (3, 4):
        nodes, weights = tanh_sinh(level)
        reference = friction_offset(spin, slip_minor, slip_major, beta, level=level)
        values, jacobians = np.empty((33, 4)), np.empty((33, 4, 3))
        for q in range(33):
            assert compiled.friction_offset(spin[q], slip_minor[q], slip_major[q], beta[q], nodes, weights,
                                            *disc_rule(), FAR_CENTRE, out, jac, sums)
            values[q], jacobians[q] = out, jac
        for k, name in enumerate(("force_major", "force_minor", "moment", "loss")):
            _assert_close(getattr(reference, name), values[:, k], name)
        _assert_close(reference.jacobian, jacobians, "jacobian")


@pytest.mark.parametrize("oversize, deviations", [(OVERSIZE, [0.0, 2.0, -1.5]), (0.0, [3.0, 0.0, 1.0])])
def test_ball_terms_kernel_equals_numpy(compiled, oversize, deviations):
    module = sc.screw_module(oversize=oversize)
    contacts = sc.ball_contacts(module, np.radians(deviations))
    scales = sb.scales_for(contacts, 50.0)
    rates = sb.free_rolling_guess(contacts)
    rng = np.random.default_rng(3)
    for trial in range(40):
        unknowns = np.zeros((3, 6))
        unknowns[:, 2] = rates[:, 0] / scales.orbit
        unknowns[:, 3:] = rates[:, 1:] / scales.spin
        unknowns += rng.normal(size=(3, 6)) * (0.3 if trial % 2 else 1e-3)
        shift = rng.normal(size=3) * 0.3 if trial % 3 else float(rng.normal())
        reference, terms = both(sb.ball_terms, unknowns, shift, contacts, scales, oversize=2.0 * oversize)
        for name in reference.__dataclass_fields__:
            _assert_close(getattr(reference, name), getattr(terms, name), name)


def _assert_same_state(reference, state):
    for name in reference.__dataclass_fields__:
        if name in ("iterations", "residual"):
            continue
        _assert_close(getattr(reference, name), getattr(state, name), name)
    assert reference.iterations == state.iterations
    assert math.isclose(reference.total_loss, state.total_loss, rel_tol=TOLERANCE)


@pytest.mark.parametrize("oversize, load", [(OVERSIZE, 50.0), (0.0, 50.0), (OVERSIZE, 1500.0 / 37)])
def test_two_ball_solve_kernel_equals_numpy(compiled, oversize, load):
    # lin2019 Table 5 a (preload fit), the literal no-preload reading (preload continuation of solve_preloaded)
    contacts = sc.ball_contacts(sc.screw_module(oversize=oversize), np.radians([0.0, 2.0]))
    _assert_same_state(*both(screw_b2b.solve, contacts, load))


def test_ring_with_per_ball_loads_and_warm_start_equal_numpy(compiled):
    # the whole-screw form (ring, one nut shift per ball, warm start from a previous state), on 4 balls
    contacts = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), np.radians([0.0, 2.0, -1.0, 0.5]))
    loads = np.array([40.0, 45.0, 35.0, 50.0])
    reference, state = both(screw_b2b.solve, contacts, loads, np.array([0.0, 0.0, 1e-3, 0.0]), ring=True)
    _assert_same_state(reference, state)
    moved = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), np.radians([0.2, 1.8, -0.8, 0.4]))
    _assert_same_state(*both(screw_b2b.solve, moved, loads * 1.05, np.array([0.0, 0.0, 5e-4, 0.0]), ring=True,
                              initial=reference))


@pytest.fixture
def ring_compiled():
    yield from kernels_on(screw_b2b.RING_KERNELS)


@pytest.mark.parametrize("ring", [True, False])
def test_long_chain_with_per_ball_loads_equals_numpy(ring_compiled, ring):
    # the whole screw's ring (lowmodel.screw.ring_kernels: banded-bordered Cholesky of the damped normal equations)
    # and an open chain, 7 balls, per-ball loads, touching and open pairs; then a warm start from the state
    deviations = np.radians([0.0, 2.0, -1.0, 0.5, 1.5, -2.0, 0.8])
    contacts = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), deviations)
    loads = np.array([40.0, 45.0, 35.0, 50.0, 42.0, 38.0, 47.0])
    gaps = np.array([0.0, 0.0, 1e-3, 0.0, 0.0, 0.0, 0.0])[:7 if ring else 6]
    reference, state = both(screw_b2b.solve, contacts, loads, gaps, ring=ring)
    _assert_same_state(reference, state)
    assert np.count_nonzero(reference.b2b_force > 0.0) >= 2   # the B2B coupling is exercised
    moved = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), deviations * 0.9 + 0.002)
    _assert_same_state(*both(screw_b2b.solve, moved, loads * 1.05, gaps, ring=ring, initial=reference))


def test_long_chain_failure_is_the_numpy_failure(ring_compiled):
    contacts = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), np.radians(np.linspace(-2.0, 2.0, 7)))
    loads = np.full(7, 40.0)
    errors = []
    for enabled in (False, True):
        kernels.use_kernels(enabled)
        with pytest.raises(ConvergenceError) as error:
            screw_b2b._solve_attempt(contacts, loads, np.zeros(7), ring=True, max_iterations=2)
        errors.append(error.value)
    assert str(errors[0]) == str(errors[1])
    assert errors[0].reason == errors[1].reason
    assert errors[0].iterations == errors[1].iterations


def test_failure_is_the_numpy_failure(compiled):
    contacts = sc.ball_contacts(sc.screw_module(oversize=OVERSIZE), np.radians([0.0, 2.0]))
    errors = []
    for enabled in (False, True):
        kernels.use_kernels(enabled)
        with pytest.raises(ConvergenceError) as error:
            screw_b2b.solve(contacts, 50.0, max_iterations=2)
        errors.append(error.value)
    assert str(errors[0]) == str(errors[1])
    assert errors[0].reason == errors[1].reason
    assert errors[0].iterations == errors[1].iterations


def test_calibrated_laws_keep_the_numpy_path(compiled):
    # C_b of a calibrated law is not in the kernel: ball_terms hands back (None), the numpy code runs
    module = sc.screw_module(oversize=OVERSIZE)
    contacts = sc.ball_contacts(module, np.radians([0.0, 2.0]))
    calibrated = sc.BallContacts(module, contacts.contact_angles, contacts.arc_centres, contacts.hertz_constant,
                                 contacts.semi_major_unit, contacts.b_over_a, contacts.deviation,
                                 np.full((2, 4), 1e-10))
    scales = sb.scales_for(contacts, 50.0)
    unknowns = np.zeros((2, 6))
    unknowns[:, 2] = 0.45
    reference, terms = both(sb.ball_terms, unknowns, 0.1, calibrated, scales)
    for name in reference.__dataclass_fields__:   # the kernel would drop C_b: the numpy code ran both times
        assert np.array_equal(getattr(reference, name), getattr(terms, name)), name


_REFERENCE = Path(__file__).parents[2] / "data" / "screw_kernels" / "ball_terms_f01e0a3.npz"


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64") or platform.libc_ver()[0] != "glibc",
                    reason="reference bits from x86-64 glibc (cos, sin, atan2, cbrt of another libm may differ)")
def test_ball_terms_kernel_bits_equal_stored_reference(compiled):
    # the dual numbers as tuples (no allocation per operation) do the same arithmetic in the same order as the arrays
    # of commit f01e0a3: its outputs on three 37-ball ring states (whole-screw size; the third with 37 of 148 contacts
    # unloaded), stored with their inputs, reproduced to the last bit (docs/speed.md, "Dual numbers without allocation")
    data = np.load(_REFERENCE)
    tables = tuple(float(data[f"table{k}"]) if data[f"table{k}"].ndim == 0 else data[f"table{k}"] for k in range(10))
    for state in range(3):
        outputs = sb.kernel_outputs(37)
        assert compiled.ball_terms(data[f"unknowns{state}"], data[f"shift{state}"], data[f"geometry{state}"],
                                   data[f"scalars{state}"], *tables, *outputs) == compiled.CONVERGED
        for name, value in zip(("residual", "jacobian", "axial", "axial_gradient", "contact", "power"), outputs):
            expected = data[f"{name}{state}"]
            assert np.array_equal(value.view(np.int64), expected.view(np.int64)), (state, name)
    assert np.count_nonzero(data["contact2"][..., 0] == 0.0) == 37   # unloaded contacts are in the reference


def _reference_cholesky(matrix):
    """Textbook left-looking Cholesky, each entry ``(A[i, j] - L[i, 0] L[j, 0] - L[i, 1] L[j, 1] - ...) / L[j, j]``
    in that order, in Python floats (terms outside the band are exact zeros)."""
    size = matrix.shape[0]
    factor = [[0.0] * size for _ in range(size)]
    for j in range(size):
        total = float(matrix[j, j])
        for t in range(j):
            total -= factor[j][t] * factor[j][t]
        factor[j][j] = math.sqrt(total)
        for i in range(j + 1, size):
            total = float(matrix[i, j])
            for t in range(j):
                total -= factor[i][t] * factor[j][t]
            factor[i][j] = total / factor[j][j]
    return np.array(factor)


def test_ring_normal_equations_factor_is_the_textbook_cholesky(ring_compiled):
    # lowmodel.screw.ring_kernels: the normal matrix J^T J of a cyclic block-tridiagonal J in band (by columns),
    # border and corner storage, against numpy's J^T J; its Cholesky (sums advanced together, t outermost) equal to
    # the textbook order's value for value; the solve against numpy's
    rng = np.random.default_rng(5)
    n, k = 6, 8
    m = (n - 2) * k
    diagonal, upper, lower = (rng.normal(size=(n, k, k)) for _ in range(3))
    dense_j = np.zeros((n * k, n * k))
    for j in range(n):
        rows = slice(j * k, (j + 1) * k)
        dense_j[rows, j * k:(j + 1) * k] = diagonal[j]
        dense_j[rows, ((j + 1) % n) * k:((j + 1) % n + 1) * k] += upper[j]
        dense_j[rows, ((j - 1) % n) * k:((j - 1) % n + 1) * k] += lower[j]
    band, border, corner = np.zeros((m, 3 * k)), np.zeros((m, 2 * k)), np.zeros((2 * k, 2 * k))
    ring_compiled._normal(diagonal, upper, lower, band, border, corner)
    normal = np.zeros((n * k, n * k))
    for j in range(m):
        for d in range(min(3 * k, m - j)):
            normal[j + d, j] = normal[j, j + d] = band[j, d]
    normal[m:, :m], normal[:m, m:] = border.T, border
    normal[m:, m:] = np.tril(corner) + np.tril(corner, -1).T
    _assert_close(dense_j.T @ dense_j, normal, "normal", 1e-14)
    damping = 0.3
    l_band, l_border, l_corner = np.zeros_like(band), np.zeros_like(border), np.zeros_like(corner)
    assert ring_compiled._factor(band, border, corner, damping, l_band, l_border, l_corner)
    reference = _reference_cholesky(normal + damping * np.eye(n * k))
    for j in range(m):
        for d in range(min(3 * k, m - j)):
            assert l_band[j, d] == reference[j + d, j], (j, d)
    assert np.array_equal(l_border, reference[m:, :m].T)
    assert np.array_equal(np.tril(l_corner), reference[m:, m:])
    rhs, step = rng.normal(size=n * k), np.empty(n * k)
    ring_compiled._solve(l_band, l_border, l_corner, rhs, step)
    _assert_close(np.linalg.solve(normal + damping * np.eye(n * k), rhs), step, "step", 1e-12)
    assert not ring_compiled._factor(band, border, corner, -1e3 * np.max(band[:, 0]), l_band, l_border, l_corner)


def _matrix_form_pair_loads():
    """lin2019 eqs 57-59 for every pair written with matrix products (``@``, numpy's operators): the reference of
    :func:`ball_kernels.pair_loads`, whose products go to the same BLAS routines into scratch arrays."""
    import numba

    @numba.njit(cache=False)
    def reference(spins, forces, chord, rot, radius, mu, speed, n, ring, load, d_spin, d_force):
        pairs = n if ring else n - 1
        cross = np.array([[0.0, chord[2], -chord[1]], [-chord[2], 0.0, chord[0]], [chord[1], -chord[0], 0.0]])
        a_mat = cross * radius
        b_mat = -a_mat
        rot_t = np.ascontiguousarray(rot.T)
        load[:] = 0.0
        floor = (1e-14 * radius * speed) ** 2
        for p in range(pairs):
            behind, ahead = p, (p + 1) % n
            slip = a_mat @ (spins[behind] + rot @ spins[ahead])
            norm = math.sqrt(math.sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]) ** 2 + floor)
            direction = slip / norm
            friction = -mu * forces[p] * direction
            force_behind = -forces[p] * chord + friction
            moment = b_mat @ friction
            load[behind, :3] += force_behind
            load[behind, 3:] += moment
            load[ahead, :3] += rot_t @ (-force_behind)
            load[ahead, 3:] += rot_t @ moment
            d_behind = (-mu * forces[p] / norm) * (np.eye(3) - np.outer(direction, direction)) @ a_mat
            for side in range(2):
                d_fric = d_behind if side == 0 else d_behind @ rot
                d_spin[p, 0, side, :3] = d_fric
                d_spin[p, 0, side, 3:] = b_mat @ d_fric
                d_spin[p, 1, side, :3] = -rot_t @ d_fric
                d_spin[p, 1, side, 3:] = rot_t @ b_mat @ d_fric
            dfd = -mu * direction
            d_force[p, 0, :3] = -chord + dfd
            d_force[p, 0, 3:] = b_mat @ dfd
            d_force[p, 1, :3] = rot_t @ (chord - dfd)
            d_force[p, 1, 3:] = rot_t @ (b_mat @ dfd)

    return reference


def test_pair_loads_are_the_matrix_form_bit_for_bit(compiled):
    """The B2B loads of random chains (open and ring, 2-40 balls, some pairs unloaded) equal the matrix form to the
    last bit (a product regrouped or summed in loops instead of BLAS differs in most chains)."""
    reference = _matrix_form_pair_loads()
    rng = np.random.default_rng(11)
    for _ in range(200):
        n, ring = int(rng.integers(2, 41)), bool(rng.integers(0, 2))
        spins = rng.standard_normal((n, 3)) * 10 ** rng.uniform(-2, 3)
        forces = np.abs(rng.standard_normal(n)) * 10 * (rng.uniform(size=n) > 0.1)
        chord = rng.standard_normal(3)
        chord /= np.linalg.norm(chord)
        rot = np.ascontiguousarray(np.linalg.qr(rng.standard_normal((3, 3)))[0])
        args = (spins, forces, chord, rot, 3.175e-3, rng.uniform(0.01, 0.3), rng.uniform(1.0, 100.0), n, ring)
        outputs = []
        for function in (reference, compiled.pair_loads):
            out = (np.zeros((n, 6)), np.zeros((n, 2, 2, 6, 3)), np.zeros((n, 2, 6)))
            function(*args, *out)
            outputs.append(out)
        for name, a, b in zip(("load", "d_spin", "d_force"), *outputs):
            assert np.array_equal(a, b), (name, n, ring)
