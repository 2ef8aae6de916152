"""The rolling-contact scenes at the quick level (validation/scenes/rolling.py): every check passes and the
FE-compliance machinery agrees with the half-space on a coarse flat-like contact (slow)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import rolling


@pytest.mark.parametrize("name", ["rolling-carter", "rolling-cattaneo", "rolling-kalker", "rolling-tractcurv",
                                  "rolling-full-slip", "rolling-lin2019-contacts"])
def test_rolling_scene_quick(quick_scene, name):
    result = quick_scene(name)
    assert all(o.family for o in result.outputs if o.kind == "accuracy")


@pytest.mark.slow
def test_fe_compliance_matches_the_half_space_on_a_flat_like_contact():
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    e, nu, radius, force, mu = 2.1e11, 0.28, 10e-3, 100.0, 0.3
    a = (3.0 * force * radius / (4.0 * e / (2.0 * (1.0 - nu * nu)))) ** (1.0 / 3.0)
    grid = rolling.hertz_grid(a, a, (6, 6))
    path = contact_pairs.ball_on_flat_pair(radius, grid.dx, 1.3, symmetry="full", element_order=2,
                                           fine_ellipse=(1.2 * a + grid.dx, 1.2 * a + grid.dx, 0.5 * a))
    compliance = rolling_compliance.condense(path, (e, nu), grid, order=2)
    shear = e / (2 * (1 + nu))
    pressure = rolling.hertz_pressure(grid, a, a, force)
    p0 = 1.5 * force / (math.pi * a * a)
    w = rolling.rigid_slip(grid, 0.3 * mu * p0 / shear, 0.0, 0.0)
    half = rolling.solve(pressure, rolling.half_space_operator(grid, shear, nu), mu, w)
    fe = rolling.solve(pressure, compliance.operator(coupling=False), mu, w)
    assert fe.force_rolling == pytest.approx(half.force_rolling, rel=0.03)
    # the shift operator is the compliance itself: symmetric to the FE's accuracy, positive definite
    shift = compliance.operator(steady=False, coupling=False).matrix
    assert np.min(np.linalg.eigvalsh(0.5 * (shift + shift.T))) > 0.0
