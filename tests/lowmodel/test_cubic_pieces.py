"""lowmodel.cubic_pieces: scipy's cubic splines evaluated without its call overhead, the same numbers to the bit."""
import pickle

import numpy as np
import pytest
from scipy.interpolate import CubicSpline, PchipInterpolator

from ballbench.lowmodel.cubic_pieces import cubic_pieces


def _points(x, rng):
    """Inside every piece, at and next to every breakpoint, and beyond both ends."""
    span = x[-1] - x[0]
    return np.concatenate([rng.uniform(x[0], x[-1], 20000), x, np.nextafter(x, -np.inf), np.nextafter(x, np.inf),
                           rng.uniform(x[0] - span, x[-1] + span, 2000)])


@pytest.mark.parametrize("build", [PchipInterpolator, CubicSpline,
                                   lambda x, y: CubicSpline(x, y, bc_type="natural"),
                                   lambda x, y: CubicSpline(x, y, bc_type="clamped")])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_equal_to_scipy_to_the_last_bit(build, seed):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(1e-3, 1.0, 4 + 9 * seed)) * 10.0 ** (3 * seed - 6)
    y = rng.normal(size=x.size) * 10.0 ** (2 - seed)
    spline = build(x, y)
    pieces = cubic_pieces(spline)
    u = _points(x, rng)
    assert np.array_equal(pieces(u), spline(u))
    assert np.array_equal(pieces(u[:20000].reshape(-1, 4)), spline(u[:20000].reshape(-1, 4)))
    assert isinstance(pieces(u[0]), np.ndarray) and pieces(u[0]).shape == () and pieces(u[0]) == spline(u[0])
    assert np.isnan(pieces(np.nan)) and np.isnan(spline(np.nan))


def test_read_only_and_pickled():
    pieces = cubic_pieces(PchipInterpolator([0.0, 1.0, 3.0], [0.0, 2.0, 3.0]))
    with pytest.raises(ValueError):
        pieces.c0[0] = 1.0
    again = pickle.loads(pickle.dumps(pieces))
    assert np.array_equal(again(np.linspace(-1, 4, 11)), pieces(np.linspace(-1, 4, 11)))


def test_refuses_what_it_does_not_evaluate():
    with pytest.raises(ValueError, match="cubic PPoly"):
        cubic_pieces(CubicSpline([0.0, 1.0, 2.0], np.ones((3, 2))))
    with pytest.raises(ValueError, match="extrapolate"):
        cubic_pieces(PchipInterpolator([0.0, 1.0, 2.0], [0.0, 1.0, 3.0], extrapolate=False))
