"""fem.rolling_compliance: the FE compliance of a coarse flat-like contact agrees with the half-space in a steady
rolling solve (lowmodel.contact.rolling), its shift operator is positive definite, and the condensation's disk cache
returns the same compliance (docs/rolling_contact.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import rolling


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


def test_condensation_disk_cache_returns_the_same_compliance(tmp_path, monkeypatch):
    """fem.rolling_compliance.condense(cache=True): the second call loads W (bit-identical) instead of condensing."""
    from ballbench.fem import rolling_compliance
    from ballbench.meshes.assemblies import contact_pairs

    e, nu, radius, force = 2.1e11, 0.28, 10e-3, 100.0
    a = (3.0 * force * radius / (4.0 * e / (2.0 * (1.0 - nu * nu)))) ** (1.0 / 3.0)
    grid = rolling.hertz_grid(a, a, (4, 4))
    path = contact_pairs.ball_on_flat_pair(radius, 2 * grid.dx, 1.5, symmetry="full", element_order=1,
                                           fine_ellipse=(1.2 * a + grid.dx, 1.2 * a + grid.dx, 0.5 * a))
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))
    first = rolling_compliance.condense(path, (e, nu), grid, order=1, cache=True)
    second = rolling_compliance.condense(path, (e, nu), grid, order=1, cache=True)
    assert "condense_s" in first.timings and "cached_s" in second.timings
    assert np.array_equal(first.W, second.W) and first.ndofs == second.ndofs
    other = rolling.hertz_grid(a, a, (4, 6))  # another grid: another entry, condensed anew
    assert "condense_s" in rolling_compliance.condense(path, (e, nu), other, order=1, cache=True).timings
