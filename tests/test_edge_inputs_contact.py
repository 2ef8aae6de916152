"""Regression tests of the edge inputs tests/test_properties_contact.py found (issue 10 item 8).

Each test failed before its fix: a NaN/inf or a warning, an error not naming the parameter, an
IndexError/ZeroDivisionError/UnboundLocalError instead of a ValueError, an accepted nonsense input, or a
silently wrong result.  Every warning is an error here (``pytestmark``).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import calibration, solvers
from ballbench.lowmodel.contact import ehl, hertz, mixed, roughness
from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import b2b_traction as bt


pytestmark = pytest.mark.filterwarnings("error")  # every warning, also numpy's and scipy's, fails a test


# --- hertz ------------------------------------------------------------------------------------------------------
def test_flat_on_flat_names_the_curvatures():
    with pytest.raises(ValueError, match="curvatures_1 and curvatures_2"):
        hertz.from_curvatures((0.0, 0.0), (0.0, 0.0))


def test_geometry_outside_the_float_range_is_refused_when_built():
    # E* A overflows: the unit solution was 0 and solve_approach divided by it (ZeroDivisionError)
    with pytest.raises(ValueError, match="youngs_modulus"):
        hertz.ball_on_ball(1e-9, youngs_modulus=1e300, poisson_ratio=0.0)


@pytest.mark.parametrize("build", [hertz.ball_on_flat, hertz.ball_on_ball,
                                   lambda r: hertz.ball_in_groove(r, 0.56),
                                   lambda r: hertz.ball_in_screw_groove(r, 0.56, 16.5e-3, 0.785, 0.19)])
def test_subnormal_ball_radius_is_named(build):
    # 1 / 5e-324 = inf: the error named curvatures_1 (or the geometry core warned)
    with pytest.raises(ValueError, match="ball_radius"):
        build(5e-324)


# --- ehl and roughness ------------------------------------------------------------------------------------------
def test_wm_top_level_checks_its_inputs():
    with pytest.raises(ValueError, match="sample_length"):  # was "math domain error"
        ehl.wm_top_level(-1e-3, 0.46, 1.94)
    with pytest.raises(ValueError, match="cutoff_length"):  # was OverflowError (L / L_s = inf)
        ehl.wm_top_level(0.55, 5e-324, 1.26)
    with pytest.raises(ValueError, match="gamma"):  # was ZeroDivisionError (log 1 = 0)
        ehl.wm_top_level(1.0, 0.1, 1.0)
    assert ehl.wm_top_level(1.0, 0.1, 1.5) == math.floor(math.log(10.0) / math.log(1.5))


def test_wm_amplitude_names_sample_length():
    with pytest.raises(ValueError, match="sample_length"):  # named cutoff_length, not a parameter
        roughness.wm_amplitude(2.5, 0.55, 5e-324)


def test_roelands_overflow_is_an_error_not_inf():
    assert math.isfinite(float(ehl.roelands_viscosity(5e9, 0.05)))
    with pytest.raises(ValueError, match="pressure"):  # was inf with a RuntimeWarning
        ehl.roelands_viscosity(1e300, 48.1)


def test_hamrock_dowson_groups_out_of_float_range():
    with pytest.raises(ValueError, match="radius_x"):  # was ZeroDivisionError
        ehl.hamrock_dowson_film(1.0, 1e-313, 5e-324, 0.9, 8.5e12, 0.56, 3.3e-8)


def test_eyring_shear_with_overflowing_shear_rate():
    # tau0 h underflows: was inf with a RuntimeWarning; asinh(x) = ln(2x) there
    tau = ehl.eyring_shear_stress(0.05, np.array([1.0, -1.0, 0.0]), 1e-12, 1e-300)  # shear rate 5e310
    expected = 1e-300 * (math.log(2.0) + math.log(0.05) + 312.0 * math.log(10.0))
    assert tau == pytest.approx([expected, -expected, 0.0], rel=1e-12)
    assert ehl.eyring_shear_stress(0.05, 1.0, 1e-7, 5e6) == 5e6 * np.arcsinh(0.05 / (5e6 * 1e-7))  # unchanged


def _ehl_case(n=16):
    geometry = hertz.from_curvatures((100.0, 100.0), (0.0, 0.0), youngs_modulus=2.1e11, poisson_ratio=0.3)
    a = float(hertz.solve_load(geometry, 20.0).a)
    grid = hs.SurfaceGrid(n, n, 5.5 * a / n, 5.0 * a / n, -1.25 * a, 0.0)
    X, Y = grid.coordinates()
    return geometry.contact_modulus, grid, (X**2 + Y**2) * 50.0


def test_ehl_floating_point_failure_is_a_convergence_error():
    e_star, grid, gap = _ehl_case(8 * 2)
    for load, speed in ((7.9e-18, 1.0), (20.0, 1e-300)):  # were RuntimeWarnings (invalid divide, overflow)
        with pytest.raises(ConvergenceError, match="floating-point"):
            ehl.solve_reynolds(gap, grid, e_star, load, speed, 0.05, initial_film=2.5e-7, max_iterations=30)


def test_ehl_iteration_options_are_checked():
    e_star, grid, gap = _ehl_case()
    with pytest.raises(ValueError, match="max_iterations"):  # was UnboundLocalError
        ehl.solve_reynolds(gap, grid, e_star, 20.0, 1.0, 0.05, max_iterations=0)
    with pytest.raises(ValueError, match="coarsest"):  # coarse grids of 2 cells failed naming nx
        ehl.solve_reynolds(gap, grid, e_star, 20.0, 1.0, 0.05, coarsest=1)
    with pytest.raises(ValueError, match="max_iterations"):
        mixed.solve_mixed(gap, np.zeros_like(gap), grid, e_star, 20.0, 1.0, 0.05, max_iterations=True)


# --- half-space grids and solve ----------------------------------------------------------------------------------
def test_surface_grid_refuses_nonsense_cells():
    for nx in (2, True, 8.0):  # 2 failed later naming nx in asperity_contact; 8.0 was accepted
        with pytest.raises(ValueError, match="nx"):
            hs.SurfaceGrid(nx, 8, 1e-6, 1e-6)
    with pytest.raises(ValueError, match="dx"):
        hs.SurfaceGrid(8, 8, 0.0, 1e-6)
    with pytest.raises(ValueError, match="nx"):
        hs.surface_grid(1e-3, nx=8.0)
    with pytest.raises(ValueError, match="half_width_x"):  # the cell size underflowed to 0
        hs.surface_grid(5e-324, nx=4)
    with pytest.raises(ValueError, match="margin"):  # was ZeroDivisionError
        hs.hertz_surface_grid(5e-324, n=4, square_cells=True)


def test_halfspace_float_range():
    grid = hs.surface_grid(2e-4, 2e-4, 16, 16)
    with pytest.raises(ValueError, match="contact_modulus"):  # was inf with a RuntimeWarning
        hs.deformation(np.full((16, 16), 1e9), grid, 5e-324)
    gap = hs.quadratic_gap(grid, 1e300, 5e3)
    with pytest.raises(ValueError, match="gap"):  # overflowed the float32 CG increments (RuntimeWarning)
        hs.solve(gap, grid, 1e11, force=1.0)
    with pytest.raises(ValueError, match="force"):
        hs.solve(hs.quadratic_gap(grid, 5e3, 5e3), grid, 5e-324, force=1.0)
    with pytest.raises(ValueError, match="A = "):
        hs.quadratic_gap(hs.surface_grid(1e200, 1e200, 4, 4), 1e300, 1.0)


# --- calibration ----------------------------------------------------------------------------------------------
def test_fit_errors_name_their_parameters():
    with pytest.raises(ValueError, match="forces"):
        calibration.fit_contact_law([1.0, 1.0, 2.0], [1e-6, 1e-6, 1.6e-6])
    with pytest.raises(ValueError, match="n_points"):
        calibration.fit_least_squares(lambda p: p, [1.0, 2.0, 3.0], n_points=3)
    with pytest.raises(ValueError, match="normal_force"):  # was RuntimeWarning "Mean of empty slice"
        calibration.fit_friction_coefficient([], [])
    with pytest.raises(ValueError, match="x must"):  # was a 0/0 RuntimeWarning
        calibration.fit_line_through_origin([0.0, 0.0, 0.0], [1.0, 2.0, 3.0])


def test_fit_from_a_start_decades_off_is_not_returned_as_the_fit():
    t = np.linspace(0.0, 1.0, 8)

    def residual(p):
        return p[0] - np.exp(t)

    with pytest.raises(ConvergenceError, match="away from a minimum"):  # returned p0 = -3.56e-127 as the fit
        calibration.fit_least_squares(residual, [-3.56e-127], n_points=8)
    fit = calibration.fit_least_squares(residual, [1.0], n_points=8)
    assert fit.params[0] == pytest.approx(np.mean(np.exp(t)), rel=1e-12)


def test_law_force_options():
    with pytest.raises(ValueError, match="max_iterations"):  # was UnboundLocalError
        calibration.law_force([1e-6], 1e-6, 0.0, max_iterations=0)
    with pytest.raises(ValueError, match="max_iterations"):  # True was taken as 1
        calibration.law_force([1e-6], 1e-6, 0.0, max_iterations=True)
    with pytest.raises(ValueError, match="approach"):  # overflow and NaN with RuntimeWarnings
        calibration.law_force([1e300], 1e-9, 1e-6)


# --- solvers --------------------------------------------------------------------------------------------------
def _square(c):
    return lambda x: (x * x - c, np.diag(2.0 * x))


def test_newton_refuses_an_infinite_tolerance_and_bool_iterations():
    with pytest.raises(ValueError, match="tolerance"):  # returned the start x0 = 1 of x^2 = 4 as converged
        solvers.newton(_square(4.0), np.array([1.0]), tolerance=math.inf, max_iterations=20, what="x^2 = 4")
    with pytest.raises(ValueError, match="max_iterations"):
        solvers.newton(_square(4.0), np.array([1.0]), tolerance=1e-12, max_iterations=True, what="x^2 = 4")


def test_continuation_options_and_max_steps():
    def solve_at(s, x0):
        return solvers.newton(_square(1.0 + s), x0, tolerance=1e-12, max_iterations=30, what="x^2 = 1 + s")

    with pytest.raises(ValueError, match="max_steps"):  # was ConvergenceError with an infinite residual
        solvers.continuation(solve_at, np.array([1.0]), what="path", max_steps=0)
    with pytest.raises(ValueError, match="initial_step"):
        solvers.continuation(solve_at, np.array([1.0]), what="path", initial_step=math.nan)
    with pytest.raises(ConvergenceError) as stopped:  # a path with no fold that runs out of steps
        solvers.continuation(solve_at, np.array([1.0]), what="path", max_steps=1)
    assert stopped.value.reason == "max_steps reached"  # was "continuation stopped (fold or no state beyond)"
    assert math.isfinite(stopped.value.residual) and stopped.value.last_converged == ("s", 0.25)
    x, _, _ = solvers.continuation(solve_at, np.array([1.0]), what="path")
    assert x[0] == pytest.approx(math.sqrt(2.0), rel=1e-12)


def test_solve_with_restarts_needs_an_attempt():
    with pytest.raises(ValueError, match="attempts"):  # was ConvergenceError with an infinite residual
        solvers.solve_with_restarts(_square(4.0), np.array([1.0]), lambda x: None, tolerance=1e-12,
                                    max_iterations=20, what="x^2 = 4", attempts=0)


# --- counts ---------------------------------------------------------------------------------------------------
def test_bool_counts_are_refused():
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=2)
    with pytest.raises(ValueError, match="ball"):  # was "setting an array element with a sequence"
        bt.hertz_patches(contacts, True)
    with pytest.raises(ValueError, match="ball"):
        bt.hertz_patches(contacts, 2)
    with pytest.raises(ValueError, match="n_cluster"):  # True was taken as 1
        ef.friction_map(9, True, 4, use_cache=False)


def test_stack_patches_reference_force():
    from ballbench.lowmodel.contact import traction

    patch = traction.TractionPatch(np.zeros((2, 3)), np.tile([0.0, 1.0, 0.0], (2, 1)), np.ones(2), False, "BL")
    for reference in (0.0, -1.0, 5e-324):  # were a divide-by-zero warning, negative loads, an overflow warning
        with pytest.raises(ValueError, match="reference_force"):
            traction.stack_patches([[patch]], 1, reference, 1.0)
    assert traction.stack_patches([[patch]], 1, 2.0, 1.0).load.tolist() == [0.5, 0.5]


@pytest.mark.parametrize("change", [
    lambda d: d["constants"]["g"].update(C=None),          # was TypeError: 'NoneType' object is not iterable
    lambda d: d["constants"]["g"]["C"].update(value="1"),  # was TypeError in math.isfinite
    lambda d: d["constants"]["g"]["C"].update(unit=5),     # was accepted
    lambda d: d["constants"]["g"]["C"].update(n_points=True),  # was accepted
    lambda d: d.update(version=True),                      # was accepted as version 1
    lambda d: d.update(notes=3),                           # was TypeError: 'int' object is not iterable
    lambda d: d.update(constants=[]),                      # was AttributeError
])
def test_calibration_file_fields_of_the_wrong_type(tmp_path, change):
    import json

    constant = calibration.Constant(2.5e-7, 1e-9, 2.4e-7, 2.6e-7, "m N^-2/3", "fe")
    path = calibration.save(calibration.Calibration({"g": {"C": constant}}), tmp_path / "c.json")
    assert calibration.load(path).constants["g"]["C"] == constant
    document = json.loads(path.read_text())
    change(document)
    path.write_text(json.dumps(document))
    with pytest.raises(ValueError, match="c.json"):
        calibration.load(path)


def test_screw_groove_that_conforms_names_its_inputs():
    # lead 0.5 rad, axial profile: A = -0.63 1/m; the error named curvatures_1 and curvatures_2 only
    with pytest.raises(ValueError, match="lead_angle 0.5 rad.*A = -0.634"):
        hertz.ball_in_screw_groove(0.015625, 0.5625, 3 * 0.015625, 0.5, 0.5, "screw", profile_plane="axial")


# --- found by a 300-example random run of the property tests ----------------------------------------------------
def test_hertz_float_range_of_the_constant_and_p0():
    # E* ~ 1e300 with R = 1e300: C^1.5 underflowed, the stiffness was 0/0 (RuntimeWarning)
    with pytest.raises(ValueError, match="youngs_modulus"):
        hertz.ball_on_ball(1e300, youngs_modulus=1e300, poisson_ratio=0.4)
    # a b underflows at E* = 1e300, F = 2e-299: p0 was inf (RuntimeWarning); now F / a / b in that order
    geometry = hertz.from_curvatures((1.1, 1.1), (0.02, 0.02), youngs_modulus=1e300, poisson_ratio=0.4)
    contact = hertz.solve_load(geometry, 2.2e-299)
    expected = 3.0 * (2.2e-299 / float(contact.a)) / (2.0 * math.pi * float(contact.b))
    assert math.isfinite(float(contact.p0)) and float(contact.p0) == pytest.approx(expected, rel=1e-12)
    # B/A ~ 2e285: k^2 underflowed in the bracket of b/a, inf / inf (RuntimeWarning)
    with pytest.raises(ValueError, match="curvatures_1"):
        hertz.from_curvatures((5e-324, 1.1754943508222875e-38), (5e-324, 1.1754943508222875e-38))


def test_more_float_range_edges():
    with pytest.raises(ValueError, match="load"):  # mu = inf
        ehl.friction_coefficient(0.0, -338.2, 2.225073858507203e-309, 0.2)
    with pytest.raises(ValueError, match="dx"):  # dy / dx = inf: 0 * inf in the kernel (RuntimeWarning)
        hs.influence_coefficients(8, 8, 5e-324, 1e-3)
    force, _ = calibration.law_force([8.5e-4], 5.96e-8, -3.3e-186)  # s* overflowed (RuntimeWarning)
    assert force[0] == pytest.approx((8.5e-4 / 5.96e-8) ** 1.5, rel=1e-12)
    from ballbench.lowmodel.contact import ellipse_friction_offset as offset

    with pytest.raises(ValueError, match="spin_velocity"):  # Jacobian ~ 1/|slip| overflowed (RuntimeWarning)
        offset.friction_offset(-2.2e-311, 0.0, -2.2e-311, 0.02)


def test_more_named_errors():
    normal = np.array([1.0, 2.0])
    with pytest.raises(ValueError, match="normal_force"):  # 2 rows for 2 parameters: named n_points, p0
        calibration.fit_friction_coefficient(normal, 0.1 * normal, [0.0, 1.0])
    tiny = np.array([8.6e-210, 1.7e-209, 3.1e-209])
    # the singular value^2 underflowed (a divide by zero, then a ValueError naming normal_force); forces outside
    # 1e-100..1e100 are now fitted divided by a power of two: the mu of the same data in N
    scaled = tiny * 1e209
    friction = np.array([0.1, 0.2, 0.31]) * scaled
    fitted = calibration.fit_friction_coefficient(tiny, friction * 1e-209)["mu"]
    assert fitted.value == pytest.approx(float(scaled @ friction / (scaled @ scaled)), rel=1e-9)  # least squares
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=2)
    patches = [bt.hertz_patches(contacts, j, n_radial=2, n_angular=8) for j in range(2)]
    with pytest.raises(ValueError, match="ball_radius"):  # r / 5e-324 overflowed (RuntimeWarning)
        bt.solve(patches, ball_radius=5e-324, friction_coefficient=0.1, groove_velocity=0.01)
    grid = hs.surface_grid(1e-4, 1e-4, 8, 8)
    with pytest.raises(ValueError, match="heights"):  # named gap, not a parameter of asperity_contact
        mixed.asperity_contact(np.full((8, 8), 1e-7), np.full((8, 8), 1e300), grid, 1e11)


def test_newton_huge_trial_step_is_rejected_without_a_warning():
    """x^2 = 2 from x0 = -2.7e-112: the first Levenberg-Marquardt trial step is ~1e111 and its merit |r|^2
    overflows (it was a RuntimeWarning).  newton rejects it and raises damping; x0 is a stationary point of |r|^2
    to double precision (predicted decrease 1e-111 against a merit of 16), so it ends in a ConvergenceError
    naming that, with no warning on the way."""
    import warnings

    import numpy as np

    from ballbench.lowmodel import solvers

    def quadratic(x):
        return x * x - 2.0, np.diag(2.0 * x)

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ConvergenceError, match="no descent step"):
            solvers.newton(quadratic, np.full(4, -2.7e-112), tolerance=1e-12, max_iterations=200, what="x^2 = 2")


def test_restarts_that_use_up_the_iteration_budget_end_in_a_convergence_error():
    """solve_with_restarts shares max_iterations among its runs; when a restart came after the budget was used
    up it called newton(max_iterations=0), which the input check refuses with a ValueError (the default
    lin2019-stability run errored on it).  Now: ConvergenceError, or the restart point if it already solves."""
    import numpy as np

    from ballbench.lowmodel import solvers

    def quadratic(x):
        return x * x - 4.0, np.diag(2.0 * x)

    _, _, needed = solvers.newton(quadratic, np.array([3.0]), tolerance=1e-12, max_iterations=50, what="x^2 = 4")

    def away(x):  # reject the root +2 and restart from 3 (converges again, needing the same iterations)
        return None if x[0] < 0 else (np.array([3.0]), 1.0)

    with pytest.raises(ConvergenceError, match="did not converge"):
        solvers.solve_with_restarts(quadratic, np.array([3.0]), away, tolerance=1e-12, max_iterations=needed,
                                    what="x^2 = 4")

    def to_the_other_root(x):  # reject +2 and restart at the root -2 itself: accepted with no further step
        return None if x[0] < 0 else (np.array([-2.0]), 1.0)

    x, _, total = solvers.solve_with_restarts(quadratic, np.array([3.0]), to_the_other_root, tolerance=1e-12,
                                              max_iterations=needed, what="x^2 = 4")
    assert x[0] == -2.0 and total == needed


def test_k_f_exact_at_axis_ratios_whose_square_is_subnormal():
    """b/a = 7.5e-156 (found by the property tests at 5x their examples): R_D(0, 1, beta^2) overflowed and k_f was
    inf; the limit b/a -> 0 is 3/2, reached to double precision long before."""
    from ballbench.lowmodel.contact import ellipse_friction as ef

    for ratio in (1e-154, 7.5e-156, 1e-160):
        assert float(ef.k_f_exact(ratio)) == 1.5
    assert float(ef.k_f_exact(1e-150)) == pytest.approx(1.5, rel=1e-15)
