"""The prepared path of steady rolling (lowmodel.contact.rolling.prepare_rolling, PreparedRolling.solve).

Reference: the general entry ``rolling.solve`` on a pressure, operator and rigid slip built here, which
prepares nothing (full LU per Newton step, no kept inverse, no cache): the prepared path must give the same
answer to round-off, with the same Newton steps and stick set, on its numpy path and on its compiled one
(lowmodel.contact.rolling_kernels; skipped without numba).
"""
from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.contact import rolling, rolling_newton

pytestmark = pytest.mark.filterwarnings("error")

A, B, FORCE, G, NU, MU = 6.304e-3, 12.61e-3, 106.7e3, 82e9, 0.28, 0.33  # CONTACT's tractcurv contact
CASES = ((0.4e-3, 0.0, 0.0), (1.2e-3, 0.0, 0.0), (2.4e-3, 0.0, 0.0), (0.0, 0.0, 0.1), (1e-3, 0.5e-3, 1.0),
         (1e-9, 0.0, 0.0), (-2e-4, 1e-4, -0.3))


def _unprepared(cells, xi, eta, phi):
    grid = rolling.hertz_grid(A, B, cells)
    pressure = rolling.hertz_pressure(grid, A, B, FORCE)
    operator = rolling.half_space_operator(grid, G, NU)
    return rolling.solve(pressure, operator, MU, rolling.rigid_slip(grid, xi, eta, phi))


@pytest.fixture(params=["numpy", "compiled"])
def path(request):
    """The numpy path (kernels off) or the compiled one (skipped without numba); kernels back to the environment."""
    if request.param == "compiled":
        if importlib.util.find_spec("numba") is None:  # not imported here: lowmodel.kernels sets its cache first
            pytest.skip("numba is not installed")
    kernels.use_kernels(request.param == "compiled")
    if request.param == "compiled" and kernels.load(rolling_newton.KERNELS) is None:
        pytest.fail(f"the rolling kernels did not load: {kernels.load_errors}")
    yield request.param
    kernels.use_kernels(None)


@pytest.mark.parametrize("cells", [(7, 7), (11, 11), (14, 16)])  # dense LU and Woodbury; 14 x 16: GMRES
def test_prepared_solves_equal_the_unprepared_solver(cells, path, monkeypatch):
    low_rank = {"woodbury_step": 0, "identity_step": 0}  # the two low-rank forms of the Newton step
    compiled = []
    original_compiled = rolling_newton.compiled_solve

    def counted_compiled(*args):
        answer = original_compiled(*args)
        compiled.append(answer is not None)
        return answer
    monkeypatch.setattr(rolling_newton, "compiled_solve", counted_compiled)

    def counted(name):
        original = getattr(rolling_newton, name)

        def step(*args):
            low_rank[name] += 1
            return original(*args)
        return step

    for name in low_rank:
        monkeypatch.setattr(rolling_newton, name, counted(name))
    prepared = rolling.prepare_rolling(A, B, FORCE, G, NU, MU, cells)
    for xi, eta, phi in CASES:
        reference = _unprepared(cells, xi, eta, phi)
        result = prepared.solve(xi, eta, phi)
        scale = MU * float(reference.pressure.max())
        assert np.max(np.abs(result.traction - reference.traction)) <= 1e-12 * scale
        assert np.max(np.abs(result.slip - reference.slip)) <= 1e-12 * float(np.abs(reference.rigid_slip).max())
        assert np.array_equal(result.stick, reference.stick)
        assert result.iterations == reference.iterations
        for name in ("force_rolling", "force_lateral"):
            assert getattr(result, name) == pytest.approx(getattr(reference, name), rel=1e-12, abs=1e-12 * MU * FORCE)
        assert result.spin_moment == pytest.approx(reference.spin_moment, rel=1e-12, abs=1e-12 * MU * FORCE * B)
        assert result.normal_force == reference.normal_force
        # steady_rolling goes through the same prepared contact: to the last bit
        again = rolling.steady_rolling(A, B, FORCE, G, NU, MU, xi, eta, phi, cells)
        assert np.array_equal(again.traction, result.traction)
    dense = int(result.contact.sum()) <= rolling.DIRECT_CELLS  # the dense LU grids take both low-rank forms
    if path == "compiled":  # the kernel solves every prepared dense case (the reference runs numpy: no inverse)
        assert sum(compiled) == (2 * len(CASES) if dense else 0) and not any(low_rank.values()), (compiled, low_rank)
    else:
        assert not any(compiled)
        assert all(bool(count) == dense for count in low_rank.values()), low_rank


def test_prepared_contact_is_frozen_and_carries_the_speed():
    prepared = rolling.prepare_rolling(A, B, FORCE, G, NU, MU, (9, 9))
    with pytest.raises(ValueError, match="read-only"):
        prepared.pressure[3, 3] = 0.0
    with pytest.raises(AttributeError):
        prepared.friction_coefficient = 0.5
    slow, fast = prepared.solve(1e-3, 0.0, 0.2), prepared.solve(1e-3, 0.0, 0.2, rolling_speed=3.0)
    assert fast.frictional_power == pytest.approx(3.0 * slow.frictional_power, rel=1e-14)
    assert np.array_equal(fast.traction, slow.traction)


def test_bad_input_to_the_prepared_path_names_the_parameter():
    good = dict(semi_axis_rolling=A, semi_axis_lateral=B, normal_force=FORCE, shear_modulus=G, poisson_ratio=NU,
                friction_coefficient=MU, cells=(8, 8))
    for name, value in (("friction_coefficient", 0.0), ("friction_coefficient", True), ("normal_force", math.nan),
                        ("semi_axis_rolling", -1e-3), ("poisson_ratio", 0.7), ("cells", (8, 0))):
        with pytest.raises(ValueError, match=name):
            rolling.prepare_rolling(**{**good, name: value})
    prepared = rolling.prepare_rolling(**good)
    for args, name in (((math.nan, 0.0, 0.0), "creepage_rolling"), ((0.0, math.inf, 0.0), "creepage_lateral"),
                       ((0.0, 0.0, -math.inf), "spin"), (([1e-3, 2e-3], 0.0, 0.0), "creepage_rolling"),
                       ((True, 0.0, 0.0), "creepage_rolling")):
        with pytest.raises(ValueError, match=name):
            prepared.solve(*args)
    for speed in (0.0, -1.0, math.nan, True):
        with pytest.raises(ValueError, match="rolling_speed"):
            prepared.solve(1e-3, 0.0, 0.0, rolling_speed=speed)


def test_steady_rolling_cache_does_not_let_bad_input_through():
    args = (0.5e-3, 1e-3, 100.0, G, NU)
    rolling.steady_rolling(*args, 1, 1e-4, 0.0, 0.0, (8, 8))  # mu = 1 (an int) is prepared and kept
    with pytest.raises(ValueError, match="friction_coefficient"):
        rolling.steady_rolling(*args, True, 1e-4, 0.0, 0.0, (8, 8))  # True == 1, but a boolean is refused
    with pytest.raises(ValueError, match="cells"):
        rolling.steady_rolling(*args, 1, 1e-4, 0.0, 0.0, (True, 8))
    # unhashable inputs are prepared for the call alone, with the same answer
    kept = rolling.steady_rolling(*args, 0.3, 1e-4, 0.0, 0.0, (8, 8))
    listed = rolling.steady_rolling(*args, np.array(0.3), 1e-4, 0.0, 0.0, [8, 8])
    assert np.array_equal(kept.traction, listed.traction)


def test_prepared_solve_without_numba_runs_the_numpy_path():
    # numba missing (an import that fails): the rolling kernels are not loaded, the answer is the numpy path's
    import os
    import subprocess
    import sys

    code = ("import sys\n"
            "sys.modules['numba'] = None\n"
            "from ballbench.lowmodel import kernels\n"
            "from ballbench.lowmodel.contact import rolling, rolling_newton\n"
            f"result = rolling.prepare_rolling({A!r}, {B!r}, {FORCE!r}, {G!r}, {NU!r}, {MU!r}, (7, 7))"
            ".solve(1.2e-3, 0.0, 0.1)\n"
            "print(kernels.load(rolling_newton.KERNELS), repr(result.force_rolling),"
            " 'numba' in kernels.load_errors.get(rolling_newton.KERNELS, ''))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "BALLBENCH_KERNELS": "1"})
    loaded, force, numba_missing = out.stdout.split()
    assert loaded == "None" and numba_missing == "True"
    kernels.use_kernels(False)
    try:
        reference = rolling.prepare_rolling(A, B, FORCE, G, NU, MU, (7, 7)).solve(1.2e-3, 0.0, 0.1)
    finally:
        kernels.use_kernels(None)
    assert float(force) == reference.force_rolling
