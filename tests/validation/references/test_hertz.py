"""validation.references.hertz: the subsurface stress on the axis (Boussinesq quadrature) against closed forms."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.validation.references.hertz import axis_stress, axis_von_mises_maximum


def test_axis_stress_of_a_circular_contact_matches_johnson():
    """Johnson (1985) eqs 3.72: sigma_z = -p0 / (1 + z^2/a^2), sigma_r = p0 (-(1 + nu)(1 - z/a atan(a/z))
    + 1 / (2 (1 + z^2/a^2)))."""
    a, p0, nu = 1e-4, 1e9, 0.3
    zeta = np.array([0.05, 0.2, 0.5, 1.0, 3.0])
    sx, sy, sz = axis_stress(a, a, p0, nu, zeta * a)
    sigma_z = -p0 / (1 + zeta**2)
    sigma_r = p0 * (-(1 + nu) * (1 - zeta * np.arctan(1 / zeta)) + 0.5 / (1 + zeta**2))
    assert sz == pytest.approx(sigma_z, rel=1e-9)
    assert sx == pytest.approx(sigma_r, rel=1e-9)
    assert sy == pytest.approx(sigma_r, rel=1e-9)


def test_von_mises_maximum_of_a_circular_contact():
    a, p0, nu = 1e-4, 1e9, 0.3

    def von_mises(z):
        zeta = z / a
        sz = -1 / (1 + zeta**2)
        sr = -(1 + nu) * (1 - zeta * math.atan(1 / zeta)) + 0.5 / (1 + zeta**2)
        return abs(sr - sz) * p0

    grid = np.linspace(0.3, 0.7, 40001) * a
    values = np.array([von_mises(z) for z in grid])
    depth, value = axis_von_mises_maximum(a, a, p0, nu)
    assert value == pytest.approx(values.max(), rel=1e-9)
    assert depth == pytest.approx(grid[values.argmax()], rel=1e-3)
    assert value / p0 == pytest.approx(0.62, abs=0.005)  # the textbook 0.62 p0 near 0.48 a


def test_elongated_ellipse_and_bad_input():
    a, b, p0 = 8e-4, 1e-4, 1e9
    sx, sy, sz = axis_stress(a, b, p0, 0.28, [1e-6])[:, 0]
    assert sz == pytest.approx(-p0, rel=1e-3)  # at the surface sigma_z = -p
    with pytest.raises(ValueError):
        axis_stress(a, b, p0, 0.28, [0.0])
