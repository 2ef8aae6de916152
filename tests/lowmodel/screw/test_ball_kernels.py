"""The compiled ball-screw kernels (lowmodel.screw.ball_kernels) against the numpy code they mirror.

Both paths run in every test: the numpy path with the kernels switched off, the compiled one with them on.
Tolerances: the friction integrals and the ball terms agree to 1e-10 relative to each field's largest value (round-off
of sums taken in another order; observed up to 8e-12, in the friction moment of contacts whose velocity centre lies
far out, where the moment is a difference of terms R_c times larger); converged states to 1e-10 relative with the
same iteration count (observed 1e-14, docs/speed.md).
"""
import math

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
