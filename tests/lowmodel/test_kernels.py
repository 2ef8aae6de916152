"""The compiled kernels (lowmodel.kernels) against the numpy path they mirror: same states, same failures."""
import math
import subprocess
import sys

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from tests.kernel_support import both, kernels_on

FIELDS = ("ball_velocity", "omega", "velocity_deviation", "spin", "slide", "c_over_a", "friction_force",
          "friction_moment", "friction_loss", "friction_loss_table", "b2b_force", "b2b_friction_loss", "b2b_slip")
# the B2B fields are judged on the scale of the ball-groove field they balance (lin2019 eqs 7-8): where the B2B force
# vanishes (a symmetric pair, theta = rho = 0) its round-off is that of the friction forces, not a fraction of zero
SCALE_OF = {"b2b_force": "friction_force", "b2b_friction_loss": "friction_loss", "b2b_slip": "slide"}


@pytest.fixture
def compiled():
    yield from kernels_on("linear_bearing.ball_kernels")


def _assert_same(reference, state, tolerance=1e-12):
    # round-off of the converged unknowns (an ulp) is all that may differ: epsilon = 2 v_B / v - 1 is compared on
    # the scale of 2 v_B / v (1), c/a = tan(phi) through phi
    for name in FIELDS:
        a, b = np.asarray(getattr(reference, name)), np.asarray(getattr(state, name))
        if name == "velocity_deviation":
            a, b = a + 1.0, b + 1.0
        elif name == "c_over_a":
            a, b = np.arctan(a), np.arctan(b)
        assert a.shape == b.shape, name
        finite = np.isfinite(a)
        assert np.array_equal(finite, np.isfinite(b)), name
        assert np.array_equal(a[~finite], b[~finite]), name  # +-inf c/a at pure sliding
        scale = max(float(np.max(np.abs(a[finite]), initial=0.0)), 1e-300)
        if name in SCALE_OF:
            scale = max(scale, float(np.max(np.abs(getattr(reference, SCALE_OF[name])))))
        assert np.max(np.abs(a[finite] - b[finite]), initial=0.0) <= tolerance * scale, name
    assert math.isclose(reference.input_power, state.input_power, rel_tol=tolerance)
    assert math.isclose(reference.total_loss, state.total_loss, rel_tol=tolerance)
    assert reference.iterations == state.iterations


CASES = [(2.0, -0.6), (2.87, -0.5), (1.0, 0.3), (0.0, 0.0), (3.5, -0.2), (0.5, -0.9)]


@pytest.mark.parametrize("theta_deg, rho", CASES)
def test_two_ball_kernel_equals_numpy(compiled, theta_deg, rho):
    contacts = b2b.module_contacts(math.radians(theta_deg), rho)
    _assert_same(*both(b2b.solve, contacts, [0.0]))
    _assert_same(*both(bearing_ball.solve, contacts))


@pytest.mark.parametrize("n_balls, gaps", [(3, [0.0, 1e-4]), (7, None), (12, [0.0] * 5 + [1e-5] + [0.0] * 5)])
def test_chain_kernel_equals_numpy(compiled, n_balls, gaps):
    # 7 and 12 balls: the band path (banded Cholesky of the permuted normal equations)
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=n_balls)
    _assert_same(*both(b2b.solve, contacts, gaps))


def _block_solve_and_dense(compiled, diagonal, upper, lower, rng):
    """The block LU (ball_kernels._block_factor, which must succeed) and its solve of a random right-hand side, with
    the dense solve of the same block-tridiagonal matrix: (pivots, reach, block solution, dense solution)."""
    n, k = diagonal.shape[:2]
    dense = np.zeros((n * k, n * k))
    compiled._dense(diagonal, upper, lower, dense)
    factor, coupling = np.empty((n, k, k)), np.empty((n, k, k))
    pivots, reach = np.empty((n, k), dtype=np.int64), np.empty((n, 2), dtype=np.int64)
    assert compiled._block_factor(diagonal, upper, lower, factor, pivots, coupling, reach)
    rhs, out = rng.normal(size=n * k), np.empty(n * k)
    compiled._block_solve(factor, pivots, coupling, reach, lower, rhs, out, np.empty(k))
    return pivots, reach, out, np.linalg.solve(dense, rhs)


def test_block_lu_of_a_chain_jacobian(compiled):
    # the block LU of the Newton step (ball_kernels._block_factor/_block_solve) against a dense solve, on the pattern
    # of a chain's Jacobian (couplings through rows and columns 0-2 and the force slot) with random values; a zero
    # pivot is refused (then the kernel takes the normal equations)
    rng = np.random.default_rng(3)
    n, k = 9, 8
    diagonal = rng.normal(size=(n, k, k)) + 4.0 * np.eye(k)
    upper, lower = np.zeros((n, k, k)), np.zeros((n, k, k))
    upper[:-1, 1:3, 1:3] = rng.normal(size=(n - 1, 2, 2))
    upper[:-1, 7, 0] = rng.normal(size=n - 1)
    lower[1:, 0:3, 7] = rng.normal(size=(n - 1, 3))
    lower[1:, 1:3, 1:3] = rng.normal(size=(n - 1, 2, 2))
    pivots, reach, out, expected = _block_solve_and_dense(compiled, diagonal, upper, lower, rng)
    assert reach[1:].tolist() == [[3, 3]] * (n - 2) + [[3, 0]]
    assert np.max(np.abs(out - expected)) <= 1e-12 * np.max(np.abs(expected))
    diagonal[4] = 0.0
    assert not compiled._block_factor(diagonal, upper, lower, np.empty((n, k, k)), pivots, np.empty((n, k, k)), reach)


def test_block_lu_eliminates_the_slip_angles_first(compiled):
    # pivot blocks with a chain ball's pattern (slip kinematics rows 3-6: columns 0-2 and their own angle only) take
    # the 4 x 4 Schur complement (ball_kernels._slip_factor, marked by pivots[j, 7] = -1); a slip-angle pivot near 0
    # (a contact near sticking) takes the full 8 x 8 LU; both against a dense solve
    rng = np.random.default_rng(5)
    n, k = 9, 8
    diagonal = np.zeros((n, k, k))
    diagonal[:, 0:3, 3:7] = rng.normal(size=(n, 3, 4))
    diagonal[:, 3:7, 0:3] = rng.normal(size=(n, 4, 3))
    diagonal[:, 1:3, 1:3] = rng.normal(size=(n, 2, 2))
    diagonal[:, 0:3, 7] = rng.normal(size=(n, 3))
    diagonal[:, 7, 7] = 1.0
    diagonal[::2, 7, 0], diagonal[::2, 7, 7] = -2.0, 0.0
    for s in range(3, 7):
        diagonal[:, s, s] = rng.uniform(0.5, 1.5, size=n) * rng.choice([-1.0, 1.0], size=n)
    diagonal[6, 5, 5] = 1e-9
    upper, lower = np.zeros((n, k, k)), np.zeros((n, k, k))
    upper[:-1, 1:3, 1:3] = rng.normal(size=(n - 1, 2, 2))
    upper[::2, 7, 0] = 2.0
    upper[-1] = 0.0
    lower[1:, 0:3, 7] = rng.normal(size=(n - 1, 3))
    lower[1:, 1:3, 1:3] = rng.normal(size=(n - 1, 2, 2))
    pivots, _, out, expected = _block_solve_and_dense(compiled, diagonal, upper, lower, rng)
    assert [bool(p < 0) for p in pivots[:, 7]] == [j != 6 for j in range(n)]
    assert np.max(np.abs(out - expected)) <= 1e-10 * np.max(np.abs(expected))


def test_failure_is_the_numpy_failure(compiled):
    # beyond the spin-capacity limit the kernels fail and the numpy path names the failure, the same either way
    contacts = b2b.module_contacts(math.radians(2.87), -0.9, vertical_force=128.0, friction_coefficient=0.6)
    messages = []
    for enabled in (False, True):
        kernels.use_kernels(enabled)
        with pytest.raises(ConvergenceError) as error:
            b2b.solve(contacts, [0.0])
        messages.append((str(error.value), error.value.reason))
    assert messages[0] == messages[1]


def test_switched_off_by_environment(monkeypatch):
    monkeypatch.setenv(kernels.ENVIRONMENT_VARIABLE, "numpy")
    kernels.use_kernels(None)
    assert not kernels.kernels_enabled()
    assert kernels.load("linear_bearing.ball_kernels") is None


def test_numpy_path_without_numba():
    # numba missing (an import that fails): the kernels are not loaded and the solve runs the numpy path
    code = ("import sys, math\n"
            "sys.modules['numba'] = None\n"
            "from ballbench.lowmodel import kernels\n"
            "from ballbench.lowmodel.linear_bearing import b2b\n"
            "state = b2b.solve(b2b.module_contacts(math.radians(2.0), -0.6), [0.0])\n"
            "print(kernels.load('linear_bearing.ball_kernels'), repr(float(state.b2b_force[0])),"
            " 'numba' in kernels.load_errors.get('linear_bearing.ball_kernels', ''))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded, force, numba_missing = out.stdout.split()
    assert loaded == "None" and numba_missing == "True"
    kernels.use_kernels(False)
    try:
        reference = b2b.solve(b2b.module_contacts(math.radians(2.0), -0.6), [0.0])
    finally:
        kernels.use_kernels(None)
    assert float(force) == float(reference.b2b_force[0])


def test_use_kernels_checks_its_argument():
    with pytest.raises(ValueError, match="enabled"):
        kernels.use_kernels("yes")


@pytest.mark.parametrize("enabled", [True, False])
def test_batched_cases_equal_one_case_solves(enabled):
    # the vectorised Monte Carlo case function (one batch per chunk) gives each case's scalar call to the last bit,
    # with the kernels and without them (then the batch is the one-case solves)
    from ballbench.validation.sweep import functions

    if enabled:
        pytest.importorskip("numba")
    kernels.use_kernels(enabled)
    try:
        draws = np.random.default_rng(5).normal(0.0, math.radians(1.0), (8, 12))
        rho = np.linspace(-0.5, 0.5, 12)
        batch = functions.two_ball_deviations(*draws, rho=rho)
        for case in range(12):
            one = functions.two_ball_deviations(*draws[:, case], rho=float(rho[case]))
            for name, value in one.items():
                assert batch[name][case] == value, (case, name)
    finally:
        kernels.use_kernels(None)


def test_case_batches_check_their_size():
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=3)
    with pytest.raises(ValueError, match="balls_per_case"):
        b2b.solve_cases(contacts, 2)


def test_the_disk_cache_is_kept_per_version_of_all_kernel_sources(tmp_path):
    # a kernel inlines another module's loop (lowmodel.newton_kernels): an edit of that module alone must not load
    # its callers' stale code, so the cache folder changes with any kernel source
    for name, text in (("a_kernels.py", "x = 1\n"), ("sub/b_kernels.py", "y = 2\n"), ("other.py", "z = 3\n")):
        (tmp_path / name).parent.mkdir(exist_ok=True)
        (tmp_path / name).write_text(text)
    key = kernels.sources_key(tmp_path)
    assert kernels.sources_key(tmp_path) == key and len(key) == 16
    (tmp_path / "other.py").write_text("z = 4\n")   # not a kernel: the same key
    assert kernels.sources_key(tmp_path) == key
    (tmp_path / "sub" / "b_kernels.py").write_text("y = 3\n")
    assert kernels.sources_key(tmp_path) != key
    assert kernels.sources_key() != kernels.sources_key(tmp_path)  # the package's own kernels
