"""The compiled steps of the load distribution (lowmodel.screw.distribution_kernels) against the numpy code.

Every comparison is exact (0 difference): the kernels repeat the numpy code's operations in its order and hand the
callback to the C routine behind scipy.optimize.brentq (the module's docstring).  A sum taken in another order
(e.g. one running sum over the balls) differs in the last bits for most arrays of 8 or more values, so the tests
reject it.
"""
import math

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from ballbench.lowmodel import kernels
from ballbench.lowmodel.cubic_pieces import cubic_pieces
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import load_distribution as ld
from tests.kernel_support import both, kernels_on

RTOL = 4 * np.finfo(float).eps
OVERSIZE = 1.6848e-6  # m, the lin2019 Table 5 preload fit (docs/ball_screw.md)


@pytest.fixture(scope="module")
def module():
    return screw_contacts.screw_module(oversize=OVERSIZE)


@pytest.fixture(scope="module")
def stiffness(module):
    """A 9-point table up to 80 N (every random total below is at most 60 N per ball)."""
    return ld.axial_stiffness(module, 80.0, points=9)


@pytest.fixture(scope="module")
def pieces(stiffness):
    """The pchip of AxialStiffness.load as lowmodel.cubic_pieces holds it."""
    order = np.argsort(stiffness.shifts)
    return cubic_pieces(PchipInterpolator(stiffness.shifts[order], stiffness.loads[order]))


@pytest.fixture
def compiled():
    yield from kernels_on(ld.KERNELS)


def _random_data(compiled, stiffness, pieces, rng, n):
    low, high = stiffness.shifts.min(), stiffness.shifts.max()
    shifted = rng.uniform(-0.5, 1.5, n) * (high - low)
    data = compiled.pack(n, low, high, rng.uniform(0.05, 0.95) * n * 60.0, pieces)
    compiled.shifted(data)[:] = shifted
    return data, shifted, low, high


def test_trial_loads_and_their_sum_are_the_numpy_codes(compiled, stiffness, pieces):
    rng = np.random.default_rng(7)
    for n in range(1, compiled.MAX_BALLS + 1):
        data, shifted, low, high = _random_data(compiled, stiffness, pieces, rng, n)
        for u0 in rng.uniform(low - (high - low), high + (high - low), 3):
            expected = stiffness.load(np.minimum(np.maximum(u0 - shifted, low), high))
            loads = np.empty(n)
            total = compiled.loads_at(u0, data, loads)
            assert np.array_equal(loads, expected), n
            assert total == expected.sum(), n          # numpy's pairwise order, bit for bit
            assert compiled.mismatch.ctypes(u0, data.ctypes.data) == float(expected.sum() - data[4]), n


def test_root_is_scipys_brentq_bit_for_bit(compiled, stiffness, pieces):
    rng = np.random.default_rng(8)
    for n in (1, 7, 8, 9, 37, 64, 128):
        for _ in range(5):
            data, shifted, low, high = _random_data(compiled, stiffness, pieces, rng, n)
            total = data[4]

            def mismatch(u0, shifted=shifted, low=low, high=high, total=total):
                return float(stiffness.load(np.minimum(np.maximum(u0 - shifted, low), high)).sum() - total)

            start, end = low - np.abs(shifted).max(), high + np.abs(shifted).max()
            root, status, iterations = compiled.nut_shift(data, start, end, 1e-16, RTOL, 2000)
            assert status == compiled.CONVERGED and iterations > 0
            assert root == brentq(mismatch, start, end, xtol=1e-16, rtol=RTOL, maxiter=2000)
            _, status, _ = compiled.nut_shift(data, start, end, 1e-16, RTOL, 2)   # iteration limit
            assert status == compiled.NOT_CONVERGED
            _, status, _ = compiled.nut_shift(data, high + 2 * np.abs(shifted).max(), high + 3 * np.abs(shifted).max(),
                                              1e-16, RTOL, 2000)
            assert status == compiled.NOT_BRACKETED


def test_distribute_is_the_numpy_paths_bit_for_bit(compiled, module, stiffness):
    sections = ld.bar_sections(module)
    rng = np.random.default_rng(9)
    for n in (1, 2, 5, 8, 12, 37, 100, 128, 129, 150):   # 129 and 150: beyond MAX_BALLS, the numpy path on both
        for lead_error, flange in ((0.0, "loaded end"), (2e-7, "loaded end"), (-2e-7, "far end"), (0.0, "far end")):
            psi = rng.uniform(0.0, 4 * math.pi, n)
            total = rng.uniform(0.1, 0.9) * n * 60.0
            reference, fast = both(ld.distribute, psi, total, stiffness, sections, module.lead,
                                   module.youngs_modulus, lead_error=lead_error, flange=flange)
            assert np.array_equal(reference, fast), (n, lead_error, flange)
            assert fast.sum() == pytest.approx(total, rel=1e-10)


def test_distribute_fails_alike_on_both_paths(compiled, module, stiffness):
    """The numpy path's errors, with the same messages: offsets that swamp the table, and the iteration limit."""
    sections = ld.bar_sections(module)
    psi = np.linspace(0.0, 4 * math.pi, 12)
    for total, kwargs in ((700.0, dict(youngs_modulus=1e-3)), (400.0, dict(youngs_modulus=2.1e11, max_iterations=1))):
        messages = []
        for enabled in (False, True):
            kernels.use_kernels(enabled)
            with pytest.raises((ValueError, RuntimeError)) as caught:
                ld.distribute(psi, total, stiffness, sections, module.lead, lead_error=0.0, **kwargs)
            messages.append((type(caught.value), str(caught.value)))
        assert messages[0] == messages[1], kwargs


def test_pack_names_the_limit(compiled, pieces):
    with pytest.raises(ValueError, match="n must be 1 to 128 balls"):
        compiled.pack(compiled.MAX_BALLS + 1, 0.0, 1.0, 1.0, pieces)
