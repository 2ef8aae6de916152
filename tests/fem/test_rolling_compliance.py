"""fem.rolling_compliance: the condensation's disk cache (docs/rolling_contact.md)."""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.contact import rolling


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
