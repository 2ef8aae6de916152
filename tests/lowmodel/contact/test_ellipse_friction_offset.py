"""Friction over a Hertz ellipse with a velocity centre offset in both directions (lin2019 eqs 44-47, A9-A11)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate
from scipy.special import ellipe

from ballbench.lowmodel.contact import (ellipse_friction as ef, ellipse_friction_offset as eo,
                                        ellipse_friction_offset as offset)
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, call, real

QUANTITIES = ("force_major", "force_minor", "moment", "loss")


# --------------------------------------------------------------------------
# independent reference: adaptive Cartesian quadrature of the slip field of eq 47
# --------------------------------------------------------------------------
def _cartesian(kappa: float, lam: float, beta: float, which: str) -> float:
    """iint (3/(2 pi)) sqrt(1 - t^2 - s^2) (...) over the unit disc, centre (kappa, lam), omega > 0."""

    def integrand(s: float, t: float) -> float:
        pressure = math.sqrt(max(1.0 - t * t - s * s, 0.0))
        dv_major = beta * (s - lam)  # omega (Y - d) / (omega a)
        dv_minor = -(t - kappa)      # omega (c - X) / (omega a)
        norm = math.hypot(dv_major, dv_minor)
        if norm == 0.0:
            return 0.0
        if which == "force_major":
            return -pressure * dv_major / norm
        if which == "force_minor":
            return -pressure * dv_minor / norm
        if which == "moment":   # X tau_minor - Y tau_major, tau = -p dv/|dv|
            return -pressure * (t * dv_minor - beta * s * dv_major) / norm
        return pressure * norm

    def inner(t: float) -> float:
        half = math.sqrt(max(1.0 - t * t, 0.0))
        points = [lam] if abs(lam) < half else None
        return integrate.quad(integrand, -half, half, args=(t,), points=points, epsabs=1e-12, epsrel=1e-12,
                              limit=200)[0]

    points = [kappa] if abs(kappa) < 1.0 else None
    return 1.5 / math.pi * integrate.quad(inner, -1.0, 1.0, points=points, epsabs=1e-11, epsrel=1e-11,
                                          limit=200)[0]


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("kappa, lam, beta", [
    (0.3, 0.4, 0.23),      # inside
    (-0.5, 0.6, 0.1),      # inside, slender ellipse
    (0.99, 0.1, 0.2),      # inside, next to the rim
    (0.0, 1.0, 0.1),       # on the rim, along the minor axis
    (0.2, 1.2, 0.23),      # outside
    (1.5, -2.0, 0.05),     # outside, very slender
    (50.0, 80.0, 0.2),     # outside, far
    (200.0, -300.0, 0.23),  # disc quadrature of the velocities
])
def test_against_independent_cartesian_quadrature(kappa, lam, beta):
    result = eo.friction_centre(kappa, lam, beta)
    for name in QUANTITIES:
        reference = _cartesian(kappa, lam, beta, name)
        assert abs(float(getattr(result, name)) - reference) < 1e-8, name


def test_reduces_to_major_axis_maps_when_d_is_zero():
    kappa = np.array([-3.0, -1.0, -0.7, 0.0, 0.3, 0.999, 1.0, 1.5, 40.0, 500.0])
    for beta in (0.05, 0.23, 1.0):
        offset = eo.friction_centre(kappa, 0.0, beta)
        exact = ef.friction_exact(kappa, beta)
        np.testing.assert_allclose(offset.force_major, 0.0, atol=1e-15)
        np.testing.assert_allclose(offset.force_minor, exact.force, atol=1e-9)   # friction_exact: 3e-10 at |c/a| = 1
        np.testing.assert_allclose(offset.moment, exact.moment, atol=1e-9)
        np.testing.assert_allclose(offset.loss, exact.loss, rtol=1e-9)
        # derivative in c/a: column slip_minor of the Jacobian at unit spin
        np.testing.assert_allclose(offset.jacobian[:, 1, 1], exact.dforce_dc, atol=1e-8)
        np.testing.assert_allclose(offset.jacobian[:, 2, 1], exact.dmoment_dc, atol=1e-8)
    # the tabulated velocity form of the linear bearing (map accuracy 3e-7)
    rng = np.random.default_rng(3)
    spin, slide = rng.normal(size=(2, 40))
    table = ef.friction_velocity(spin, slide, 0.23)
    offset = eo.friction_offset(spin, slide, 0.0, 0.23)
    np.testing.assert_allclose(offset.force_minor, table.force, atol=1e-6)
    np.testing.assert_allclose(offset.moment, table.moment, atol=1e-6)
    np.testing.assert_allclose(offset.loss / np.hypot(spin, slide), table.loss / np.hypot(spin, slide), atol=1e-6)


def _finite_difference(velocities: np.ndarray, beta: float, step: float = 1e-6) -> np.ndarray:
    fd = np.zeros((4, 3))
    for j in range(3):
        up, down = velocities.copy(), velocities.copy()
        up[j] += step
        down[j] -= step
        plus, minus = eo.friction_offset(*up, beta), eo.friction_offset(*down, beta)
        fd[:, j] = [(float(getattr(plus, q)) - float(getattr(minus, q))) / (2 * step) for q in QUANTITIES]
    return fd


@pytest.mark.parametrize("velocities", [
    (1.0, 0.3, -0.05),     # inside
    (-0.8, 0.2, 0.1),      # omega < 0
    (0.5, 1.3, 0.3),       # outside
    (0.004, 1.0, 0.5),     # far: disc quadrature
    (1.0, 0.0, 0.0),       # pure spin
])
def test_jacobian_against_finite_differences(velocities):
    velocities = np.array(velocities, dtype=float)
    result = eo.friction_offset(*velocities, 0.23)
    np.testing.assert_allclose(result.jacobian, _finite_difference(velocities, 0.23), atol=2e-8)


def test_power_identity_and_switch_continuity(monkeypatch):
    """loss = spin moment - slip . force (both quadratures); the two agree where they switch (R_c = 100)."""
    beta = 0.23
    rng = np.random.default_rng(7)
    direction = rng.normal(size=(20, 2))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    kappa, lam = 1.5 * eo.FAR_CENTRE * direction[:, 0], 1.5 * eo.FAR_CENTRE * direction[:, 1]
    far = eo.friction_centre(kappa, lam, beta)                  # disc quadrature of the velocities
    monkeypatch.setattr(eo, "FAR_CENTRE", 1e9)
    near = eo.friction_centre(kappa, lam, beta)                 # centred quadrature at the same points
    for result in (far, near):
        identity = result.moment - kappa * result.force_minor + beta * lam * result.force_major
        np.testing.assert_allclose(result.loss, identity, rtol=1e-11)
    for name in QUANTITIES:
        np.testing.assert_allclose(getattr(far, name), getattr(near, name), rtol=1e-10, atol=1e-11)
    np.testing.assert_allclose(far.jacobian, near.jacobian, rtol=1e-6, atol=1e-9)


def test_symmetries_and_homogeneity():
    rng = np.random.default_rng(11)
    w, un, um = rng.normal(size=(3, 30))
    beta = 0.3
    base = eo.friction_offset(w, un, um, beta)
    reversed_ = eo.friction_offset(-w, -un, -um, beta)
    scaled = eo.friction_offset(3.0 * w, 3.0 * un, 3.0 * um, beta)
    np.testing.assert_allclose(reversed_.force_major, -base.force_major, atol=1e-13)
    np.testing.assert_allclose(reversed_.force_minor, -base.force_minor, atol=1e-13)
    np.testing.assert_allclose(reversed_.moment, -base.moment, atol=1e-13)
    np.testing.assert_allclose(reversed_.loss, base.loss, rtol=1e-13)
    np.testing.assert_allclose(scaled.force_minor, base.force_minor, atol=1e-13)
    np.testing.assert_allclose(scaled.loss, 3.0 * base.loss, rtol=1e-13)
    # mirror image across the major axis (Y -> -Y, minor components flip): the field of (-w, -un, um);
    # forces mirror (major kept, minor flipped), the moment (a pseudo-scalar) flips, the loss is kept
    reflected = eo.friction_offset(-w, -un, um, beta)
    np.testing.assert_allclose(reflected.force_major, base.force_major, atol=1e-13)
    np.testing.assert_allclose(reflected.force_minor, -base.force_minor, atol=1e-13)
    np.testing.assert_allclose(reflected.moment, -base.moment, atol=1e-13)
    np.testing.assert_allclose(reflected.loss, base.loss, rtol=1e-12)


def test_pure_sliding_and_rest_limits():
    beta = 0.23
    slide = eo.friction_offset(0.0, np.array([0.6, 0.0, -1.0]), np.array([0.8, -2.0, 0.0]), beta)
    np.testing.assert_allclose(slide.force_major, [-0.8, 1.0, 0.0], atol=1e-14)
    np.testing.assert_allclose(slide.force_minor, [-0.6, 0.0, 1.0], atol=1e-14)
    np.testing.assert_allclose(slide.moment, 0.0, atol=1e-14)
    np.testing.assert_allclose(slide.loss, [1.0, 2.0, 1.0], rtol=1e-14)
    # d moment / d spin at pure sliding: (e_major^2 beta^2 + e_minor^2) / (5 |u|), e normal to the slip
    # (int (3/(2 pi)) sqrt(1 - r^2) t^2 over the disc = 1/5)
    expected = np.array([(0.6**2 * beta**2 + 0.8**2) / 5.0, 1.0 / 10.0, beta**2 / 5.0])
    np.testing.assert_allclose(slide.jacobian[:, 2, 0], expected, rtol=1e-12)
    rest = eo.friction_offset(0.0, 0.0, 0.0, beta)
    assert float(rest.moment) == pytest.approx(0.375 * ellipe(1 - beta**2))   # lin2019 eq 11
    assert float(rest.force_major) == 0.0 and float(rest.loss) == 0.0


def test_bad_input():
    with pytest.raises(ValueError, match="spin_velocity"):
        eo.friction_offset(np.nan, 0.0, 0.0, 0.2)
    with pytest.raises(ValueError, match="slip_major"):
        eo.friction_offset(1.0, 0.0, np.inf, 0.2)
    with pytest.raises(ValueError, match="b_over_a"):
        eo.friction_offset(1.0, 0.0, 0.0, 1.5)
    with pytest.raises(ValueError, match="b_over_a"):
        eo.friction_offset(1.0, 0.0, 0.0, 0.01)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_friction_offset_of_a_subnormal_spin():
    from ballbench.lowmodel.contact import ellipse_friction_offset as offset

    with pytest.raises(ValueError, match="spin_velocity"):  # Jacobian ~ 1/|slip| overflowed (RuntimeWarning)
        offset.friction_offset(-2.2e-311, 0.0, -2.2e-311, 0.02)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


speed = st.one_of(real(-10.0, 10.0), st.sampled_from([0.0, 1e-300, 1e300, -1e300]))


@SETTINGS
@given(spin=speed, minor=speed, major=speed, beta=st.one_of(real(-0.1, 1.2), st.sampled_from([0.02, 1.0, 0.0])),
       level=st.one_of(st.integers(-1, 6), st.just(True)), c=real(-1e3, 1e3), d=real(-1e3, 1e3))
def test_friction_offset(spin, minor, major, beta, level, c, d):
    call(offset.friction_offset, spin, minor, major, beta, level=level)
    call(offset.friction_offset, [spin, 0.0], [minor, 0.0], [major, 0.0], beta)
    call(offset.friction_centre, c, d, beta, level=level)
