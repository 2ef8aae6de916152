"""Friction integrals over a Hertz ellipse (lin2019 eqs A4-A7, 11, 12, 14)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate
from scipy.special import ellipe, ellipk

from ballbench.lowmodel.contact import ellipse_friction as ef
from hypothesis import given
from tests.property_support import SETTINGS, SLOW, call, real
from ballbench.lowmodel import quadrature
from hypothesis import strategies as st
from tests.property_support import one_bad


# --------------------------------------------------------------------------
# independent reference: adaptive Cartesian quadrature of the paper's (t, s) form
# --------------------------------------------------------------------------
def _cartesian(kappa: float, beta: float, which: str) -> float:
    """lin2019 eqs A4 (force) and A6 (loss), second lines, by nested adaptive quad."""

    def integrand(s: float, t: float) -> float:
        pressure = math.sqrt(max(1.0 - t * t - s * s, 0.0))
        distance = math.hypot(t - kappa, beta * s)
        if which == "force":
            return pressure * (t - kappa) / distance if distance > 0.0 else 0.0
        return pressure * distance

    def inner(t: float) -> float:
        half = math.sqrt(max(1.0 - t * t, 0.0))
        return integrate.quad(integrand, -half, half, args=(t,), points=[0.0], epsabs=1e-12, epsrel=1e-12,
                              limit=200)[0]

    points = [kappa] if abs(kappa) < 1.0 else None
    value = integrate.quad(inner, -1.0, 1.0, points=points, epsabs=1e-11, epsrel=1e-11, limit=200)[0]
    return 1.5 / math.pi * value


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("kappa, beta", [(0.0, 0.23), (0.3, 0.23), (-0.7, 0.5), (1.0, 0.3), (1.5, 0.1), (6.0, 1.0)])
def test_exact_quadrature_against_independent_cartesian(kappa, beta):
    result = ef.friction_exact(kappa, beta)
    assert abs(float(result.force) - _cartesian(kappa, beta, "force")) < 1e-8
    assert abs(float(result.loss) - _cartesian(kappa, beta, "loss")) < 1e-8


def test_limit_pure_spin_eq11():
    beta = np.array([0.05, 0.23, 0.6, 1.0])
    result = ef.friction_exact(0.0, beta)
    np.testing.assert_allclose(result.force, 0.0, atol=1e-14)
    expected = 0.375 * ellipe(1.0 - beta**2)  # (3/8) Ellip(sqrt(a^2 - b^2)/a), lin2019 eq 11
    np.testing.assert_allclose(result.moment, expected, rtol=1e-12)
    np.testing.assert_allclose(ef.spin_moment(beta), expected, rtol=1e-15)
    np.testing.assert_allclose(ef.friction(0.0, beta).moment, expected, rtol=1e-6)
    assert ef.spin_moment(1.0) == pytest.approx(3 * math.pi / 16)  # circle: (3/8)(pi/2)


def test_limit_pure_sliding_eq12():
    beta = 0.23
    for method in (ef.friction_exact, ef.friction):
        big = method(np.array([1e8, -1e8, np.inf, -np.inf]), beta)
        np.testing.assert_allclose(big.force, [-1.0, 1.0, -1.0, 1.0], atol=1e-9)
        np.testing.assert_allclose(big.moment, 0.0, atol=1e-6)
        np.testing.assert_allclose(big.dforce_dc, 0.0, atol=1e-9)
        assert np.all(np.isinf(big.loss[2:]))
    # loss -> |c/a| (sliding at speed |omega c|): loss - |kappa| -> 0 like 1/kappa
    far = ef.friction_exact(np.array([1e3, 1e4]), beta)
    gap = far.loss - np.array([1e3, 1e4])
    assert 0.0 < gap[1] < gap[0] < 1e-2
    assert gap[0] / gap[1] == pytest.approx(10.0, rel=1e-3)


def test_k_f_exact_closed_forms():
    beta = np.array([0.02, 0.1, 0.23, 0.5, 0.99])
    e2 = 1.0 - beta**2
    legendre = 1.5 * (ellipe(e2) - beta**2 * ellipk(e2)) / e2   # 3 (E - beta^2 K) / (2 e^2)
    np.testing.assert_allclose(ef.k_f_exact(beta), legendre, rtol=1e-12)
    assert ef.k_f_exact(1.0) == pytest.approx(3 * math.pi / 8, rel=1e-14)
    assert ef.k_f_exact(0.0) == 1.5
    # the slope of the quadrature and the returned derivative at c/a = 0
    step = 1e-4
    slope = (ef.friction_exact(-step, beta).force - ef.friction_exact(step, beta).force) / (2 * step)
    np.testing.assert_allclose(slope, ef.k_f_exact(beta), rtol=1e-7)
    np.testing.assert_allclose(-ef.friction_exact(0.0, beta).dforce_dc, ef.k_f_exact(beta), rtol=1e-10)


def test_force_is_an_odd_cubic_inside_the_ellipse():
    """For |c/a| <= 1 the curvature is exactly k_f - 3 g3 (c/a)^2 (polar integration about the velocity
    centre), so force = -k_f kappa + g3 kappa^3 and the least-squares slope is k_f - (3/5) c_max^2 g3."""
    for beta in (0.02, 0.23, 0.7, 1.0):
        kappa = np.linspace(-0.99, 0.99, 23)
        exact = ef.friction_exact(kappa, beta)
        closed = ef.friction_inside(kappa, beta)
        for name in ("force", "moment", "loss", "dforce_dc", "dmoment_dc", "dloss_dc"):
            np.testing.assert_allclose(getattr(closed, name), getattr(exact, name), atol=1e-12, err_msg=name)
        rim = ef.friction_exact(np.array([-1.0, 1.0]), beta)
        np.testing.assert_allclose(ef.friction_inside(np.array([-1.0, 1.0]), beta).force, rim.force, atol=1e-9)
        assert ef.k_f_least_squares(beta, 0.5) == pytest.approx(
            ef.k_f_exact(beta) - 0.15 * ef.cubic_coefficient(beta), rel=1e-12)
    assert ef.cubic_coefficient(1.0) == pytest.approx(3 * math.pi / 32, rel=1e-14)
    # both branches of cubic_coefficient agree where they meet
    assert ef.cubic_coefficient(0.5) == pytest.approx(float(ef.cubic_coefficient(0.5 + 1e-12)), rel=1e-10)
    with pytest.raises(ValueError, match="c_over_a"):
        ef.friction_inside(1.5, 0.3)


def test_identities_power_balance_and_derivatives():
    rng = np.random.default_rng(3)
    kappa = np.concatenate([rng.uniform(-3.0, 3.0, 40), [-1.0, 1.0, 0.999, 1.001]])
    beta = rng.uniform(0.05, 1.0, kappa.size)
    result = ef.friction_exact(kappa, beta)
    np.testing.assert_allclose(result.moment, result.loss + kappa * result.force, atol=1e-13)
    step = 1e-6
    plus, minus = ef.friction_exact(kappa + step, beta), ef.friction_exact(kappa - step, beta)
    np.testing.assert_allclose((plus.force - minus.force) / (2 * step), result.dforce_dc, atol=2e-6)
    np.testing.assert_allclose((plus.moment - minus.moment) / (2 * step), result.dmoment_dc, atol=2e-6)
    np.testing.assert_allclose((plus.loss - minus.loss) / (2 * step), result.dloss_dc, atol=2e-6)
    assert np.all(result.dforce_dc < 0.0)  # force decreases monotonically with c/a


def test_symmetries():
    kappa = np.array([0.0, 0.2, 0.9, 1.0, 1.7, 40.0])
    for method in (ef.friction_exact, ef.friction):
        plus, minus = method(kappa, 0.3), method(-kappa, 0.3)
        np.testing.assert_allclose(plus.force, -minus.force, atol=1e-12)
        np.testing.assert_allclose(plus.moment, minus.moment, atol=1e-12)
        np.testing.assert_allclose(plus.loss, minus.loss, atol=1e-12)


def test_map_against_exact():
    rng = np.random.default_rng(7)
    kappa = np.concatenate([np.tan(rng.uniform(-1.5707, 1.5707, 3000)), 1.0 + rng.uniform(-0.05, 0.05, 1000),
                            [0.0, 1.0, -1.0, 0.5]])
    beta = np.exp(rng.uniform(math.log(ef.B_OVER_A_RANGE[0]), 0.0, kappa.size))
    beta[-4:] = [0.02, 1.0, 0.23, 0.23]
    exact, table = ef.friction_exact(kappa, beta), ef.friction(kappa, beta)
    assert np.max(np.abs(table.force - exact.force)) < 1e-6
    assert np.max(np.abs(table.moment - exact.moment)) < 1e-6
    assert np.max(np.abs(table.loss - exact.loss) / np.hypot(1.0, kappa)) < 1e-6
    for name in ("dforce_dc", "dmoment_dc", "dloss_dc"):
        assert np.max(np.abs(getattr(table, name) - getattr(exact, name))) < 1e-4, name


def test_map_derivatives_are_those_of_the_map():
    rng = np.random.default_rng(11)
    kappa = np.concatenate([rng.uniform(-4.0, 4.0, 200), [0.0, 0.999, 1.001]])
    beta = rng.uniform(0.1, 1.0, kappa.size)
    step = 1e-6
    result = ef.friction(kappa, beta)
    plus, minus = ef.friction(kappa + step, beta), ef.friction(kappa - step, beta)
    for name, deriv in (("force", "dforce_dc"), ("moment", "dmoment_dc"), ("loss", "dloss_dc")):
        difference = (getattr(plus, name) - getattr(minus, name)) / (2 * step)
        np.testing.assert_allclose(difference, getattr(result, deriv), atol=1e-7, err_msg=name)


def test_newton_on_the_map_converges_quadratically():
    beta = 0.23
    for target in (-0.5, 0.9, 0.995):
        kappa, errors = 0.0, []
        for _ in range(30):
            result = ef.friction(kappa, beta)
            residual = float(result.force) - target
            errors.append(abs(residual))
            if abs(residual) < 1e-14:
                break
            kappa -= residual / float(result.dforce_dc)
        exact_root = kappa
        assert errors[-1] < 1e-13
        assert abs(float(ef.friction_exact(exact_root, beta).force) - target) < 1e-6
        # order of convergence p = log(e_{n+1}/e_n) / log(e_n/e_{n-1}) over the last steps above round-off
        tail = [e for e in errors if e > 1e-14]
        orders = [math.log(c / b) / math.log(b / a)
                  for a, b, c in zip(tail, tail[1:], tail[2:]) if a < 0.05 and c < 1e-6]
        assert orders and min(orders) > 1.8, (target, errors)


def test_velocity_form_is_finite_and_continuous_through_zero_spin():
    beta = 0.23
    spin = np.array([1e-3, 1e-12, 0.0, -1e-12, -1e-3])
    result = ef.friction_velocity(spin, 0.01, beta)
    np.testing.assert_allclose(result.force[1:4], -1.0, atol=1e-9)  # pure sliding: f = -mu F sign(V)
    np.testing.assert_allclose(result.moment[1:4], 0.0, atol=1e-9)
    np.testing.assert_allclose(result.loss[1:4], 0.01, rtol=1e-9)
    for name in ("dforce_dspin", "dforce_dslide", "dmoment_dspin", "dloss_dslide"):
        assert np.all(np.isfinite(getattr(result, name)))
    # same as the c/a form for omega > 0 and with the sgn(omega) factor for omega < 0
    by_ratio = ef.friction(0.01 / 1e-3, beta)
    assert result.force[0] == pytest.approx(float(by_ratio.force), abs=1e-12)
    assert result.loss[0] == pytest.approx(1e-3 * float(by_ratio.loss), rel=1e-12)
    negative_spin = ef.friction(0.01 / -1e-3, beta)  # c/a = -10, sgn(omega) = -1
    assert result.force[-1] == pytest.approx(-float(negative_spin.force), abs=1e-12)
    assert result.moment[-1] == pytest.approx(-float(negative_spin.moment), abs=1e-12)
    assert result.loss[-1] == pytest.approx(1e-3 * float(negative_spin.loss), rel=1e-12)


def test_velocity_form_power_balance_and_derivatives():
    rng = np.random.default_rng(5)
    spin = rng.normal(size=50) * 1e-3
    slide = rng.normal(size=50) * 1e-3
    beta = rng.uniform(0.05, 1.0, 50)
    result = ef.friction_velocity(spin, slide, beta)
    # P = omega M_O - (omega c) f_z: loss = spin * moment - slide * force (to map accuracy)
    np.testing.assert_allclose(result.loss, spin * result.moment - slide * result.force,
                               atol=1e-6 * np.hypot(spin, slide).max())
    step = 1e-10
    for which, delta in (("spin", (step, 0.0)), ("slide", (0.0, step))):
        plus = ef.friction_velocity(spin + delta[0], slide + delta[1], beta)
        minus = ef.friction_velocity(spin - delta[0], slide - delta[1], beta)
        for name in ("force", "moment", "loss"):
            difference = (getattr(plus, name) - getattr(minus, name)) / (2 * step)
            analytic = getattr(result, f"d{name}_d{which}")
            np.testing.assert_allclose(difference, analytic, rtol=1e-4, atol=1e-3, err_msg=f"{name} {which}")


def test_disk_cache_roundtrip(tmp_path, monkeypatch):
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))
    build = ef.friction_map.__wrapped__
    first = build(n_uniform=21, n_cluster=4, n_beta=5)
    assert not first.from_cache
    assert list((tmp_path / "ellipse_friction").glob("map-*.npz"))
    second = build(n_uniform=21, n_cluster=4, n_beta=5)
    assert second.from_cache
    np.testing.assert_array_equal(first.force, second.force)
    np.testing.assert_array_equal(first.loss_direction, second.loss_direction)


@pytest.mark.parametrize("bad", [0.0, -0.2, 1.2, float("nan"), float("inf")])
def test_bad_axis_ratio(bad):
    with pytest.raises(ValueError, match="b_over_a"):
        ef.friction(0.1, bad)
    with pytest.raises(ValueError, match="b_over_a"):
        ef.friction_velocity(1.0, 0.1, bad)


def test_below_table_range_and_nan_inputs():
    with pytest.raises(ValueError, match=r"b_over_a must lie in \[0.02, 1\]"):
        ef.friction(0.1, 0.01)
    ef.friction_exact(0.1, 0.01)  # the direct quadrature has no table
    with pytest.raises(ValueError, match="c_over_a"):
        ef.friction(float("nan"), 0.3)
    with pytest.raises(ValueError, match="c_over_a"):
        ef.friction_exact(float("nan"), 0.3)
    with pytest.raises(ValueError, match="spin_velocity"):
        ef.friction_velocity(float("nan"), 0.0, 0.3)
    with pytest.raises(ValueError, match="c_max"):
        ef.k_f_least_squares(0.3, c_max=-1.0)


def test_force_is_concave_for_positive_c_so_fitted_slopes_lie_below_the_tangent():
    """-force is concave on c/a >= 0 (the curvature decreases), which backs the scene's bound k_f_exact >= 1.38."""
    kappa = np.linspace(0.0, 20.0, 2001)
    for beta in (0.02, 0.23, 1.0):
        curvature = -ef.friction_exact(kappa, beta).dforce_dc
        assert np.all(np.diff(curvature) <= 1e-14)
        assert ef.k_f_least_squares(beta, 0.5) < ef.k_f_exact(beta)


def test_angle_form_matches_the_other_forms_and_its_derivatives():
    rng = np.random.default_rng(9)
    phi = rng.uniform(-3 * math.pi, 3 * math.pi, 300)
    beta = rng.uniform(0.05, 1.0, phi.size)
    result = ef.friction_angle(phi, beta)
    by_velocity = ef.friction_velocity(np.cos(phi), np.sin(phi), beta)
    np.testing.assert_allclose(result.force, by_velocity.force, atol=1e-12)
    np.testing.assert_allclose(result.moment, by_velocity.moment, atol=1e-12)
    np.testing.assert_allclose(result.loss, by_velocity.loss, atol=1e-12)
    np.testing.assert_allclose(result.loss, np.cos(phi) * result.moment - np.sin(phi) * result.force, atol=1e-6)
    step = 1e-6
    plus, minus = ef.friction_angle(phi + step, beta), ef.friction_angle(phi - step, beta)
    for name in ("force", "moment", "loss"):
        difference = (getattr(plus, name) - getattr(minus, name)) / (2 * step)
        np.testing.assert_allclose(difference, getattr(result, f"d{name}_dphi"), atol=1e-6, err_msg=name)
    shifted = ef.friction_angle(phi + math.pi, beta)
    np.testing.assert_allclose(shifted.force, -result.force, atol=1e-12)
    with pytest.raises(ValueError, match="slip_angle"):
        ef.friction_angle(float("nan"), 0.3)


def test_bad_grid():
    with pytest.raises(ValueError, match="n_beta"):
        ef.friction_map.__wrapped__(n_beta=2, use_cache=False)
    with pytest.raises(ValueError, match="n_uniform"):
        ef.friction_map.__wrapped__(n_uniform=4.5, use_cache=False)


def test_friction_angle_at_equals_friction_angle():
    """The fixed-b/a evaluator of the Newton solvers gives the values of friction_angle (same spline)."""
    from ballbench.lowmodel.contact import ellipse_friction as ef

    rng = np.random.default_rng(5)
    beta = rng.uniform(0.02, 1.0, size=(40, 4))
    phi = rng.uniform(-12.0, 12.0, size=(40, 4))  # any real angle: periodic
    phi[0] = [-np.pi, np.pi, 0.5 * np.pi, -0.5 * np.pi]
    got = ef.friction_angle_at(beta)(phi)
    want = ef.friction_angle(phi, beta)
    for value, reference in zip(got, (want.force, want.dforce_dphi, want.moment, want.dmoment_dphi, want.loss)):
        np.testing.assert_allclose(value, reference, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="b_over_a"):
        ef.friction_angle_at(np.array([0.5, 1.5]))


def test_friction_angle_at_stacked_slopes_are_derivatives():
    """The stacked evaluator of the chain solves (one batched product per call) gives the 5-tuple's values, and
    its slopes are the phi-derivatives of its values, d loss/d phi included (catches a basis built from the
    wrong powers of dphi or with the (phi, log b/a) indices swapped, which the solvers' Newton would only see
    as slow convergence)."""
    from ballbench.lowmodel.contact import ellipse_friction as ef

    rng = np.random.default_rng(11)
    beta = rng.uniform(0.02, 1.0, size=(30, 4))
    phi = rng.uniform(-4.0, 4.0, size=(30, 4))
    table = ef.friction_angle_at(beta, stacked=True)(phi)
    assert table.shape == (30, 4, 3, 2)
    for value, reference in zip(ef.friction_angle_at(beta)(phi), (table[..., 0, 0], table[..., 0, 1],
                                                                  table[..., 1, 0], table[..., 1, 1],
                                                                  table[..., 2, 0])):
        np.testing.assert_array_equal(value, reference)
    step = 1e-6
    evaluate = ef.friction_angle_at(beta, stacked=True)
    numeric = (evaluate(phi + step)[..., 0] - evaluate(phi - step)[..., 0]) / (2 * step)
    np.testing.assert_allclose(table[..., 1], numeric, rtol=1e-6, atol=1e-6)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("c_over_a", [1e300, -1e300, 1e200, 1e8, 300.0, -250.0])
def test_friction_exact_far_velocity_centre(c_over_a):
    """c/a = 1e300 gave NaN (overflow); far out the identity moment = loss + (c/a) force cancels."""
    beta = 0.3
    result = ef.friction_exact(c_over_a, beta)
    for name in ("force", "moment", "loss", "dforce_dc", "dmoment_dc", "dloss_dc"):
        assert np.isfinite(getattr(result, name)), name
    assert float(result.force) == pytest.approx(-math.copysign(1.0, c_over_a), rel=1e-6)
    assert float(result.moment) == pytest.approx(beta**2 / (5 * abs(c_over_a)), rel=1e-4)  # leading term
    assert float(result.loss) >= abs(c_over_a)


@pytest.mark.filterwarnings("error")
def test_friction_exact_series_meets_quadrature():
    """Both sides of the switch at |c/a| = 200 (quadrature below, series above) against the two leading
    terms of the far field, ``force = -1 + (b/a)^2 / (10 (c/a)^2)``, ``loss = c/a + (b/a)^2 / (10 c/a)``."""
    beta = np.array([0.02, 0.3, 1.0])[:, None]
    kappa = np.array([150.0, 199.0, 201.0, 250.0])[None, :]
    exact = ef.friction_exact(kappa, beta)
    np.testing.assert_allclose(exact.force, -1.0 + beta**2 / (10 * kappa**2), rtol=0, atol=5e-11)  # next: 0.011/k^4
    np.testing.assert_allclose(exact.loss, kappa + beta**2 / (10 * kappa), rtol=1e-15, atol=5e-9)  # next: 0.004/k^3
    np.testing.assert_allclose(-exact.dforce_dc, beta**2 / (5 * kappa**3), rtol=2e-4)


@pytest.mark.filterwarnings("error")
def test_cubic_coefficient_at_zero_ratio():
    """b/a = 0 is inside the documented range; NaN before (0 * inf), the limit is E(1)/2 = 1/2."""
    values = ef.cubic_coefficient([0.0, 1e-8, 1e-4])
    assert np.all(np.isfinite(values))
    np.testing.assert_allclose(values, 0.5, rtol=1e-6)


@pytest.mark.filterwarnings("error")
def test_friction_velocity_at_huge_velocities():
    result = ef.friction_velocity(1e300, 3e300, 0.5)
    reference = ef.friction_velocity(1.0, 3.0, 0.5)
    assert float(result.force) == pytest.approx(float(reference.force), rel=1e-12)
    assert float(result.loss) == pytest.approx(1e300 * float(reference.loss), rel=1e-12)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_bool_cluster_count_is_refused():
    with pytest.raises(ValueError, match="n_cluster"):  # True was taken as 1
        ef.friction_map(9, True, 4, use_cache=False)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(kappa=real(-1e300, 1e300), small=real(-3.0, 3.0), beta=real(-0.1, 1.2))
def test_ellipse_friction(kappa, small, beta):
    for c_over_a in (kappa, small):
        call(ef.friction, c_over_a, beta, allow_inf=("loss",))
        call(ef.friction_exact, c_over_a, beta, allow_inf=("loss",))
        call(ef.friction_angle, c_over_a, beta)
        call(ef.friction_inside, c_over_a, beta)
    call(ef.friction_velocity, small, kappa, beta)
    call(ef.k_f_exact, beta)
    call(ef.cubic_coefficient, beta)
    call(ef.spin_moment, beta)


@SLOW
@given(beta=real(0.0, 1.0), c_max=real(-0.5, 3.0))
def test_k_f_least_squares(beta, c_max):
    call(ef.k_f_least_squares, beta, c_max)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(beta=st.one_of(real(-0.1, 1.2), st.sampled_from([0.0, 0.02, 1.0, 5e-324])), stacked=st.booleans(),
       level=st.one_of(st.integers(-1, 7), st.just(True)))
def test_ellipse_friction_rest(beta, stacked, level):
    if 0.0 < beta <= 1.0:  # a closure over the tabulated map; it is evaluated at slip angles
        at = call(ef.friction_angle_at, beta, stacked=stacked)
        if at is not None:
            call(at, np.full(np.shape(beta), 2.5))  # phi of the shape of b_over_a (its docstring)
    else:
        call(ef.friction_angle_at, beta, stacked=stacked)
    call(quadrature.tanh_sinh, level)


@SLOW
@given(kw=one_bad(dict(n_uniform=st.integers(9, 13), n_cluster=st.integers(1, 3), n_beta=st.integers(4, 6)),
                  dict(n_uniform=st.sampled_from([8, -1, True, 9.0]), n_cluster=st.sampled_from([0, True]),
                       n_beta=st.sampled_from([3, 4.0]))))
def test_friction_map_small(kw):
    call(ef.friction_map, kw["n_uniform"], kw["n_cluster"], kw["n_beta"], use_cache=False)
