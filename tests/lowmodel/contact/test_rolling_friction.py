"""The pressure of a rolling grid from sampled fields (lowmodel.contact.rolling_friction; docs/b2b_rolling.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact import rolling_friction as rf


def test_sampled_pressure_of_hertz_samples_is_the_hertz_pressure():
    """Samples on a fine lattice (as FE quadrature points: equal areas) give Hertz's cell averages."""
    a, b, force = 0.1e-3, 0.4e-3, 50.0
    p0 = 1.5 * force / (math.pi * a * b)
    x, y = np.meshgrid((np.arange(100) + 0.5) / 50 - 1.0, (np.arange(400) + 0.5) / 200 - 1.0, indexing="ij")
    pressure = p0 * np.sqrt(np.clip(1.0 - x * x - y * y, 0.0, None))
    weights = np.full(x.shape, (2 * a / 100) * (2 * b / 400))
    grid = rolling.hertz_grid(a, b, (10, 40))
    cells = rf.sampled_pressure(grid, a * x, b * y, pressure, weights)
    assert cells.sum() * grid.cell_area == pytest.approx(float((pressure * weights).sum()), rel=1e-12)
    hertz = rolling.hertz_pressure(grid, a, b, force)
    assert np.max(np.abs(cells - hertz)) < 0.02 * p0  # nearest samples: 1.4e-2 p0 at an edge cell
    assert np.abs(cells - hertz).sum() < 2e-3 * hertz.sum()
    with pytest.raises(ValueError, match="does not cover"):
        rf.sampled_pressure(rolling.hertz_grid(0.5 * a, b, (10, 40)), a * x, b * y, pressure, weights)
