"""Steady rolling contact with stick and slip (lowmodel.contact.rolling, .influence, .fastsim).

References are independent of the solver: Carter's and Cattaneo-Mindlin's closed forms, Kalker's Table E.3,
CONTACT's stored tractcurv output (validation.references.rolling), numerical quadrature of the point-force
solutions, the ellipse-friction maps for the full-slip limit.
"""
from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest
from scipy import integrate

from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import fastsim as fs
from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.contact import influence, rolling, rolling_newton
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.validation.references import rolling as ref

pytestmark = pytest.mark.filterwarnings("error")

G, NU, MU = 82e9, 0.28, 0.3


# --- influence coefficients ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("offset", [(0.0, 0.0), (1.0, 0.0), (0.0, 2.0), (1.5, -2.0), (-3.0, 1.0)])
def test_rectangle_coefficients_equal_the_quadrature_of_cerrutis_point_force(offset):
    dx, dy = 1.0, 0.7
    X, Y = offset[0] * dx, offset[1] * dy
    xx, xy, yy = (k[0, 0] for k in influence.tangential_coefficients([X], [Y], dx, dy, G, NU))

    def quad(f):  # over the source cell, split at the field point's lines so the 1/r singularity is at a corner
        xs = sorted({X - dx / 2, X + dx / 2} | ({0.0} if abs(X) < dx / 2 else set()))
        ys = sorted({Y - dy / 2, Y + dy / 2} | ({0.0} if abs(Y) < dy / 2 else set()))
        total = 0.0
        for x0, x1 in zip(xs, xs[1:]):
            for y0, y1 in zip(ys, ys[1:]):
                total += integrate.dblquad(lambda v, u: f(u, v), x0, x1, y0, y1, epsabs=1e-12, epsrel=1e-10)[0]
        return total / (math.pi * G)

    def r(u, v):
        return math.hypot(u, v)

    assert xx == pytest.approx(quad(lambda u, v: (1 - NU) / r(u, v) + NU * u * u / r(u, v) ** 3), rel=1e-7)
    assert yy == pytest.approx(quad(lambda u, v: (1 - NU) / r(u, v) + NU * v * v / r(u, v) ** 3), rel=1e-7)
    assert xy == pytest.approx(quad(lambda u, v: NU * u * v / r(u, v) ** 3), abs=1e-9 * abs(xx))


def test_coupling_coefficients_equal_the_quadrature_and_vanish_for_identical_bodies():
    shear, nu, k = influence.combined_material(80e9, 0.3, 40e9, 0.45)
    assert k != 0.0
    assert influence.combined_material(80e9, 0.3)[2] == 0.0
    xn, yn = influence.coupling_coefficients([1.3e-3], [0.4e-3], 1e-3, 1e-3, shear, k)
    value = integrate.dblquad(lambda v, u: u / (u * u + v * v), 0.8e-3, 1.8e-3, -0.1e-3, 0.9e-3,
                              epsabs=1e-14)[0]
    assert xn[0, 0] == pytest.approx(-k / (math.pi * shear) * value, rel=1e-8)


def test_half_space_compliance_is_symmetric_positive_definite():
    grid = hs.SurfaceGrid(6, 5, 1e-4, 1.3e-4)
    shift = rolling.half_space_operator(grid, G, NU, steady=False)
    matrix = shift.dense(np.arange(30))
    assert np.allclose(matrix, matrix.T, rtol=0, atol=1e-12 * np.max(matrix))
    assert np.min(np.linalg.eigvalsh(matrix)) > 0.0


def test_fft_products_equal_the_dense_ones():
    grid = hs.SurfaceGrid(9, 7, 1e-4, 1.3e-4)
    operator = rolling.half_space_operator(grid, G, NU)
    field = np.random.default_rng(3).standard_normal((9, 7, 2))
    dense = (operator.dense(np.arange(63)) @ field.reshape(-1)).reshape(9, 7, 2)
    assert np.max(np.abs(operator.apply(field) - dense)) < 1e-12 * np.max(np.abs(dense))


# --- the ladder ------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kappa", [0.15, 0.45, 0.75])
def test_carter_creep_force_and_traction(kappa):
    a, load = 1e-3, 2e5
    p0 = 2 * load / (math.pi * a)
    creepage = kappa * 2 * (1 - NU) * MU * p0 / G
    result = rolling.steady_rolling_line(a, load, G, NU, MU, creepage, 400)
    reference = ref.carter_force(creepage, p0, G, NU, MU)
    assert result.force_rolling / (MU * load) == pytest.approx(reference, rel=2e-3)
    x = result.grid.x
    exact = ref.carter_traction(x, a, creepage, p0, G, NU, MU)
    assert np.max(np.abs(result.traction[:, 0, 0] - exact)) < 0.03 * MU * p0
    width = np.count_nonzero(result.stick) * result.grid.dx
    assert width == pytest.approx(ref.carter_stick_width(creepage, a, p0, G, NU, MU), abs=2.5 * result.grid.dx)


@pytest.mark.parametrize("ratio", [0.3, 0.7])
def test_cattaneo_mindlin_shift(ratio):
    a, force = 1e-3, 1000.0
    delta = ref.mindlin_shift(ratio, force, a, G, 0.0, MU)
    grid = rolling.hertz_grid(a, a, (40, 40))
    result = rolling.shift(rolling.hertz_pressure(grid, a, a, force), grid, G, 0.0, MU, (delta, 0.0))
    assert -result.force_rolling / (MU * force) == pytest.approx(ratio, rel=3e-3)
    radius = math.sqrt(np.count_nonzero(result.stick) * grid.cell_area / math.pi)
    assert radius == pytest.approx(ref.mindlin_stick_radius(ratio, a), rel=0.02)
    assert abs(result.force_lateral) < 1e-9 * force


def test_tractcurv_on_contacts_grid_and_pressure():
    d = ref.TRACTCURV_INPUT
    grid = hs.SurfaceGrid(*d["grid"], *d["cell"])
    gap = hs.quadratic_gap(grid, d["curvature_rolling"], d["curvature_lateral"])
    normal = hs.solve(gap, grid, d["shear_modulus"] / (1 - d["poisson_ratio"]), force=d["normal_force"],
                      tolerance=1e-10)
    operator = rolling.half_space_operator(grid, d["shear_modulus"], d["poisson_ratio"])
    for creepage, reference in list(zip(ref.TRACTCURV_CREEPAGES, ref.TRACTCURV_FX_OVER_MU_FN))[::2]:
        result = rolling.solve(normal.pressure, operator, d["friction_coefficient"],
                               rolling.rigid_slip(grid, creepage, 0.0, 0.0))
        value = -result.force_rolling / (d["friction_coefficient"] * d["normal_force"])
        assert value == pytest.approx(reference, rel=1e-3)


def test_full_slip_limit_is_the_ellipse_friction_map():
    a, b, force = 0.1e-3, 0.6e-3, 50.0
    p0 = 1.5 * force / (math.pi * a * b)
    kappa = 0.3
    mapped = ef.friction(kappa, a / b)
    phi = 1e5 * MU * p0 / (b * G)  # spin parameter 1e5
    result = rolling.steady_rolling(a, b, force, G, NU, MU, kappa * phi * b, 0.0, phi, (64, 64))
    assert result.stick_fraction == 0.0
    assert result.force_rolling / (MU * force) == pytest.approx(float(mapped.force), abs=1e-3)
    assert -result.spin_moment / (MU * force * b) == pytest.approx(float(mapped.moment), abs=1e-3)
    # the lateral force full slip lacks falls off as 1/Lambda
    weaker = rolling.steady_rolling(a, b, force, G, NU, MU, kappa * phi * b / 100, 0.0, phi / 100, (32, 32))
    assert 1e-4 < abs(weaker.force_lateral) / (MU * force) < 1e-2


def test_steady_rolling_signs_follow_kalker():
    a, b, force = 0.5e-3, 1e-3, 100.0
    result = rolling.steady_rolling(a, b, force, G, NU, MU, 1e-4, 1e-4, 10.0, 16)
    assert result.force_rolling < 0 and result.force_lateral < 0
    assert result.frictional_power > 0
    mirrored = rolling.steady_rolling(a, b, force, G, NU, MU, -1e-4, -1e-4, -10.0, 16)
    assert mirrored.force_rolling == pytest.approx(-result.force_rolling, rel=1e-8)
    assert mirrored.spin_moment == pytest.approx(-result.spin_moment, rel=1e-8)
    # stick at the leading edge (x > 0), slip at the trailing edge (Kalker: material enters at x = +a)
    creep = rolling.steady_rolling(a, b, force, G, NU, MU, 1e-4, 0.0, 0.0, 16)
    x = creep.grid.x
    leading = creep.stick[x > 0].sum() / creep.contact[x > 0].sum()
    trailing = creep.stick[x < 0].sum() / creep.contact[x < 0].sum()
    assert leading > 0.9 and trailing < 0.5


def test_dense_and_fft_paths_agree():
    args = (0.5e-3, 1e-3, 100.0, G, NU, MU, 2e-4, -1e-4, 20.0)
    grid = rolling.hertz_grid(*args[:2], (14, 14))
    pressure = rolling.hertz_pressure(grid, *args[:3])
    operator = rolling.half_space_operator(grid, G, NU)
    w = rolling.rigid_slip(grid, *args[6:])
    dense = rolling.solve(pressure, operator, MU, w, dense=True)
    fft = rolling.solve(pressure, operator, MU, w, dense=False)
    assert np.max(np.abs(dense.traction - fft.traction)) < 1e-8 * MU * pressure.max()


# --- input checks and failures ----------------------------------------------------------------------------------------
def test_bad_inputs_name_the_parameter():
    args = dict(semi_axis_rolling=0.5e-3, semi_axis_lateral=1e-3, normal_force=100.0, shear_modulus=G,
                poisson_ratio=NU, friction_coefficient=MU, creepage_rolling=1e-4, creepage_lateral=0.0, spin=0.0,
                cells=(8, 8))
    for name, value in (("friction_coefficient", 0.0), ("friction_coefficient", -0.1),
                        ("creepage_rolling", math.nan), ("spin", math.inf), ("normal_force", -1.0)):
        with pytest.raises(ValueError, match=name):
            rolling.steady_rolling(**{**args, name: value})
    grid = rolling.hertz_grid(0.5e-3, 1e-3, (8, 8))
    pressure = rolling.hertz_pressure(grid, 0.5e-3, 1e-3, 100.0)
    operator = rolling.half_space_operator(grid, G, NU)
    w = rolling.rigid_slip(grid, 1e-4, 0.0, 0.0)
    negative = pressure.copy()
    negative[4, 4] = -1.0
    with pytest.raises(ValueError, match="pressure must be >= 0"):
        rolling.solve(negative, operator, MU, w)
    wide = rolling.hertz_pressure(grid, 0.6e-3, 1.2e-3, 100.0)  # an ellipse larger than the grid
    with pytest.raises(ValueError, match="does not cover the contact"):
        rolling.solve(wide, operator, MU, w)
    with pytest.raises(ValueError, match="rigid slip"):
        rolling.solve(pressure, operator, MU, np.full_like(w, np.nan))


@pytest.mark.parametrize("cells, name", [((8, 1), r"cells\[1\] \(n_lateral\)"), ((1, 8), r"cells\[0\] \(n_rolling\)"),
                                         (1, r"cells\[0\] \(n_rolling\)")])
def test_too_few_cells_are_refused_by_the_documented_check(cells, name):
    # (n, 1) passed the check of cells and failed inside the grid on "ny ... got 3"
    with pytest.raises(ValueError, match=name + r" must be an integer in \[2, 4096\]"):
        rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 1e-4, 0.0, 0.0, cells)
    assert rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 1e-4, 0.0, 0.0, (8, 2)).stick_fraction > 0


@pytest.mark.parametrize("value, words", [([1.0, 2.0, 3.0], r"rigid_shift must have shape \(2,\) or \(10, 10, 2\)"),
                                          ([math.nan, 0.0], "rigid_shift must be finite"),
                                          ("x", "rigid_shift must be a real number")])
def test_a_bad_rigid_shift_names_the_parameter(value, words):
    # the shape and finiteness checks named the internal "rigid (the rigid slip)"
    grid = rolling.hertz_grid(0.5e-3, 0.5e-3, (8, 8))
    pressure = rolling.hertz_pressure(grid, 0.5e-3, 0.5e-3, 100.0)
    with pytest.raises(ValueError, match=words):
        rolling.shift(pressure, grid, G, NU, MU, value)


@pytest.mark.parametrize("creepages", [(5e-324, 0.0, 0.0), (0.0, 5e-324, 0.0), (0.0, 0.0, 5e-324),
                                       (-5e-324, 5e-324, 5e-324), (1e-310, 0.0, 0.0)])
def test_a_subnormal_creepage_rolls_in_full_stick_without_warnings(creepages):
    # a creepage of 5e-324 overflowed in the marching start's bound / |trial| (a RuntimeWarning; the module's
    # warnings are errors); in full stick the forces are linear in the creepages: at most Kalker's C11 G ab xi
    a, b, force = 0.5e-3, 1e-3, 100.0
    for solve in (rolling.steady_rolling, fs.fastsim):
        result = solve(a, b, force, G, NU, MU, *creepages)
        assert float(np.asarray(result.stick_fraction)) == 1.0
        for value in (result.force_rolling, result.force_lateral):
            assert abs(float(np.asarray(value))) <= 10.0 * G * a * b * max(map(abs, creepages)) + 1e-300


def test_non_convergence_raises_with_the_residual():
    with pytest.raises(ConvergenceError) as info:
        rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 3e-4, 0.0, 0.0, 16, max_iterations=1)
    assert info.value.residual > info.value.tolerance


def test_a_wrong_traction_fails_its_defining_check(monkeypatch):
    original = rolling_newton.semismooth_newton

    def off(problem, tolerance, max_iterations, start):
        p, iterations, krylov, residual = original(problem, tolerance, max_iterations, start)
        return p * 1.01, iterations, krylov, residual  # a slightly wrong answer claiming convergence

    monkeypatch.setenv("BALLBENCH_KERNELS", "numpy")  # the numpy path; the compiled one: the test below
    monkeypatch.setattr(rolling_newton, "semismooth_newton", off)
    with pytest.raises(ConvergenceError, match="check failed"):
        rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 3e-4, 0.0, 0.0, 12)


def test_a_wrong_traction_fails_its_defining_check_on_the_compiled_path(monkeypatch):
    if importlib.util.find_spec("numba") is None:  # not imported here: lowmodel.kernels sets its cache first
        pytest.skip("numba is not installed")
    from ballbench.lowmodel import kernels

    monkeypatch.setenv("BALLBENCH_KERNELS", "1")
    module = kernels.load(rolling_newton.KERNELS)
    assert module is not None, kernels.load_errors
    original = module.newton

    def off(*args):
        p, iterations, residual, status = original(*args)
        return p * 1.01, iterations, residual, status  # a slightly wrong answer claiming convergence

    monkeypatch.setattr(module, "newton", off)
    with pytest.raises(ConvergenceError, match="check failed"):
        rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 3e-4, 0.0, 0.0, 12)
    monkeypatch.setattr(module, "newton", original)  # and the right answer passes the same checks
    assert rolling.steady_rolling(0.5e-3, 1e-3, 100.0, G, NU, MU, 3e-4, 0.0, 0.0, 12).iterations >= 1


# --- FASTSIM ----------------------------------------------------------------------------------------------------------
def test_kalker_table_agrees_with_the_reference_entries():
    for aob, values in ref.KALKER_TABLE_E3_NU_025.items():
        assert fs.kalker_coefficients(aob, 0.25) == pytest.approx(values, rel=1e-12)
    # a > b mirrors: the a_le_b and a_gt_b tables meet at a = b
    assert fs.kalker_coefficients(1.0, 0.28) == pytest.approx(fs.kalker_coefficients(1.0 + 1e-12, 0.28), rel=1e-6)


def test_fastsim_linear_and_full_slip_limits():
    a, b, force = 6.304e-3, 12.61e-3, 106.7e3
    c = math.sqrt(a * b)
    coefficients = fs.kalker_coefficients(a / b, NU)
    linear = fs.fastsim(a, b, force, G, NU, MU, 1e-9, 0.0, 0.0, (80, 80))
    assert -linear.force_rolling / (G * c * c * 1e-9) == pytest.approx(coefficients[0], rel=0.02)
    spin = fs.fastsim(a, b, force, G, NU, MU, 0.0, 0.0, 1e-9 / c, (80, 80))
    assert -spin.force_lateral / (G * c * c * 1e-9) == pytest.approx(coefficients[2], rel=0.03)
    slide = fs.fastsim(a, b, force, G, NU, MU, [0.1, -0.1], 0.0, 0.0)
    assert slide.force_rolling == pytest.approx([-MU * force, MU * force], rel=1e-9)
    assert np.all(slide.stick_fraction < 0.1)


def test_fastsim_is_close_to_the_exact_creep_curve_and_batches():
    a, b, force, mu = 6.304e-3, 12.61e-3, 106.7e3, 0.33
    creepages = np.array(ref.TRACTCURV_CREEPAGES)
    batch = fs.fastsim(a, b, force, G, NU, mu, creepages, 0.0, 0.0)
    assert batch.force_rolling.shape == creepages.shape
    ratio = -batch.force_rolling / (mu * force)
    assert np.max(np.abs(ratio - np.array(ref.TRACTCURV_FX_OVER_MU_FN))) < 0.03
    one = fs.fastsim(a, b, force, G, NU, mu, creepages[2], 0.0, 0.0)
    assert float(one.force_rolling) == pytest.approx(batch.force_rolling[2], rel=1e-12)
    assert np.all(batch.frictional_power >= 0.0)


def test_fastsim_with_the_hertz_bound_reaches_the_full_slip_maps():
    a, b, force = 0.1e-3, 0.5e-3, 50.0
    p0 = 1.5 * force / (math.pi * a * b)
    for kappa in (0.0, 0.3, 1.0):
        mapped = ef.friction(kappa, a / b)
        phi = 1e4 * MU * p0 / (b * G)
        result = fs.fastsim(a, b, force, G, NU, MU, kappa * phi * b, 0.0, phi, (20, 40), bound="elliptic")
        assert float(result.force_rolling) / (MU * force) == pytest.approx(float(mapped.force), abs=2e-3)
        assert -float(result.spin_moment) / (MU * force * b) == pytest.approx(float(mapped.moment), abs=2e-3)


def test_dissimilar_coupling_enters_the_slip_and_flips_with_the_bodies():
    shear, nu, k = influence.combined_material(80e9, 0.3, 40e9, 0.45)
    grid = rolling.hertz_grid(0.5e-3, 0.5e-3, (12, 12))
    pressure = rolling.hertz_pressure(grid, 0.5e-3, 0.5e-3, 200.0)
    w = np.zeros((grid.nx, grid.ny, 2))
    plain = rolling.solve(pressure, rolling.half_space_operator(grid, shear, nu), MU, w)
    assert np.max(np.abs(plain.traction)) == 0.0
    one = rolling.solve(pressure, rolling.half_space_operator(grid, shear, nu, coupling=k), MU, w)
    other = rolling.solve(pressure, rolling.half_space_operator(grid, shear, nu, coupling=-k), MU, w)
    assert np.max(np.abs(one.traction)) > 1e-3 * MU * pressure.max()
    assert np.allclose(other.traction, -one.traction, rtol=0, atol=1e-9 * MU * pressure.max())
    assert abs(one.force_lateral) < 1e-9 * 200.0  # symmetric about y = 0
