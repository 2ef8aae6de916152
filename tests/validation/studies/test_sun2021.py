"""sun2021-fe-bem: the rotation estimator shared by FE and BEM, and the scene at its quick level (slow: FE)."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import halfspace as hs
from ballbench.validation.studies import sun2021


@pytest.mark.parametrize("angle_deg", [-0.29, 0.0, 0.1, 30.0])
def test_second_moment_angle_of_a_rotated_hertz_field(angle_deg):
    # a Hertz field rotated by a known angle: the estimator returns it, and agrees with the BEM's pressure_ellipse
    grid = hs.surface_grid(3e-4, 3e-4, 200, 200)
    X, Y = grid.coordinates()
    angle = math.radians(angle_deg)
    c, s = math.cos(angle), math.sin(angle)
    xr, yr = c * X + s * Y, -s * X + c * Y
    pressure = np.sqrt(np.maximum(1.0 - (xr / 2.7e-4) ** 2 - (yr / 0.5e-4) ** 2, 0.0))
    found = sun2021.second_moment_angle(X.ravel(), Y.ravel(), pressure.ravel())
    assert math.degrees(found) == pytest.approx(angle_deg, abs=0.01)  # grid staircase: 0.005 deg at 30 deg
    assert found == pytest.approx(hs.pressure_ellipse(pressure, grid)[2], abs=1e-9)
    with pytest.raises(ValueError, match="weight"):
        sun2021.second_moment_angle(X.ravel(), Y.ravel(), 0.0 * pressure.ravel())


@pytest.mark.slow
def test_scene_passes_quick(tmp_path):
    # FE of the helical pair (~300k P2 DOFs, ~4 GB, 2-4 min)
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import registry

    result = run_scene(registry()["sun2021-fe-bem"], "quick", tmp_path)
    assert not result.error, result.error
    assert result.passed, [(o.quantity, o.rel_error) for o in result.outputs if o.status == "fail"]
