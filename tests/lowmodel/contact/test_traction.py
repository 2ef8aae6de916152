"""lowmodel.contact.traction: traction patches, their stacking and the free-ball starts, bad input."""
import math

import numpy as np
import pytest
from ballbench.lowmodel.contact import traction
from hypothesis import given
from hypothesis import strategies as st

from tests.property_support import SETTINGS, call, positive, real

# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_stack_patches_reference_force():
    from ballbench.lowmodel.contact import traction

    patch = traction.TractionPatch(np.zeros((2, 3)), np.tile([0.0, 1.0, 0.0], (2, 1)), np.ones(2), False, "BL")
    for reference in (0.0, -1.0, 5e-324):  # were a divide-by-zero warning, negative loads, an overflow warning
        with pytest.raises(ValueError, match="reference_force"):
            traction.stack_patches([[patch]], 1, reference, 1.0)
    assert traction.stack_patches([[patch]], 1, 2.0, 1.0).load.tolist() == [0.5, 0.5]


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


small_cells = st.one_of(st.integers(1, 24), st.sampled_from([0, -2, True]))


@SETTINGS
@given(n_radial=small_cells, n_angular=small_cells, k=st.integers(0, 5), force=real(-1.0, 1e3),
       normal_scale=st.one_of(real(0.0, 2.0), st.just(1.0)), index=st.integers(-1, 3))
def test_traction_patches(n_radial, n_angular, k, force, normal_scale, index):
    samples = call(traction.ellipse_samples, n_radial, n_angular)
    if samples is not None:
        assert abs(float(np.sum(samples[2])) - 1.0) <= 1e-12
    normals = np.tile([0.0, normal_scale, 0.0], (k, 1))
    patch = traction.TractionPatch(np.zeros((k, 3)), normals, np.full(k, force), False, "BL")
    try:  # check_patch names the patch's array (points, normals, forces) in its errors (its docstring)
        checked = call(traction.check_patch, patch, index)
    except AssertionError as error:
        assert any(f": {name} " in str(error) for name in ("points", "normals", "forces")), error
        checked = None
    if checked is not None:
        for reference in (force, 0.0, -1.0, 5e-324):
            stacked = call(traction.stack_patches, [[checked], [checked]], 1, reference, 1.0)
            if stacked is not None:
                assert np.allclose(stacked.load, checked.forces[0] / reference)
                assert stacked.ball.tolist() == [0] * k + [1] * k


@SETTINGS
@given(targets=st.lists(real(-10.0, 10.0), min_size=1, max_size=4), tolerance=st.one_of(positive(1e-14, 1e-6),
       st.sampled_from([0.0, math.inf])), iterations=st.one_of(st.integers(0, 30), st.just(True)))
def test_free_ball_starts(targets, tolerance, iterations):
    """Each ball alone solves x_b^3 = t_b (one real root: Newton converges from 1 unless t_b = 0 stalls it)."""
    target = np.asarray(targets)[:, None]

    def evaluate(states, ball):
        x = states[ball]
        return x**3 - target[ball], np.diag(3.0 * x**2)

    free = call(traction.free_ball_starts, evaluate, np.ones((len(targets), 1)), tolerance=tolerance,
                max_iterations=iterations, what="ball")
    if free is not None:
        assert np.all(np.abs(free[0] ** 3 - target) <= tolerance)
