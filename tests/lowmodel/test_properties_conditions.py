"""Property tests: every lowmodel solver's answer satisfies the conditions that define it (hypothesis, fixed seeds).

Random *valid* inputs, including small grids, rough gaps and small mu: a solve either returns a state that meets
its defining conditions, checked here apart from the solver (a direct sum for the BEM deflection, the power
balance of the ball models, closed-form least squares for the fits), or raises ValueError / ConvergenceError with
a message and, for a ConvergenceError, a ``reason``; never a warning (property_support.call).  The edge-input
properties (out-of-range inputs) are tests/test_properties*.py.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import event, given
from hypothesis import strategies as st

from ballbench.lowmodel import calibration
from ballbench.lowmodel.contact import ehl, hertz, roughness
from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b as bearing_b2b
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from tests.property_support import CALLS, SETTINGS, SLOW, real


def solved(function, *args, **kwargs):
    """``function(...)``, or None on a ConvergenceError that names its reason (ValueError is not expected here:
    every input is valid)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            result = function(*args, **kwargs)
        except ConvergenceError as error:
            CALLS["ConvergenceError"] += 1
            assert error.reason, f"{function.__name__}: ConvergenceError without a reason: {error}"
            assert str(error)
            event(f"{function.__name__}: ConvergenceError ({error.reason[:40]})")
            return None
    CALLS["returned"] += 1
    event(f"{function.__name__}: solved")
    return result


# --- half-space BEM: complementarity on the full grid, load balance --------------------------------------------
def _deflection_direct(pressure, grid, e_star):
    # the reference: Love's coefficients summed cell by cell (no FFT), as tests/test_halfspace.py
    kernel = hs.influence_coefficients(grid.nx, grid.ny, grid.dx, grid.dy) / e_star
    deflection = np.zeros(pressure.shape)
    for k, m in zip(*np.nonzero(pressure)):
        deflection += pressure[k, m] * kernel[grid.nx - 1 - k:2 * grid.nx - 1 - k, grid.ny - 1 - m:2 * grid.ny - 1 - m]
    return deflection


@SETTINGS
@given(n=st.integers(6, 24), margin=real(1.3, 2.5), ratio=real(1.0, 6.0), angle=real(-1.6, 1.6),
       rough=st.sampled_from([0.0, 0.0, 0.1, 0.5, 1.0]), seed=st.integers(0, 50), load_control=st.booleans(),
       load=real(1.0, 300.0))
def test_bem_complementarity_and_load_balance(n, margin, ratio, angle, rough, seed, load_control, load):
    geometry = hertz.from_curvatures((200.0, 200.0), (0.0, 200.0 * (1.0 - 1.0 / ratio)), youngs_modulus=2.1e11,
                                     poisson_ratio=0.3)
    contact = hertz.solve_load(geometry, load)
    a = float(contact.a)
    grid = hs.surface_grid(margin * a, margin * a, n, n)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B, angle)
    if rough:  # sun2021's fractal raceway (D = 2.47), its peak-to-valley a multiple of the Hertz approach
        heights = roughness.raceway_roughness(grid, 2.47, 1e-9, seed=seed).heights
        gap = gap - rough * float(contact.delta) * heights / max(float(np.ptp(heights)), 1e-300)
    gap -= gap.min()
    control = {"force": load} if load_control else {"approach": float(contact.delta)}
    try:
        result = solved(hs.solve, gap, grid, geometry.contact_modulus, **control)
    except ValueError as error:  # the only valid-input ValueError: a grid too small for the contact
        assert "edge of the grid" in str(error)
        event("halfspace.solve: contact reaches the grid edge")
        return
    if result is None:
        return
    assert np.all(result.pressure >= 0.0)
    loaded = gap + _deflection_direct(result.pressure, grid, geometry.contact_modulus) - result.approach
    interference = result.approach - float(gap.min())
    in_contact = result.pressure > 0.0
    assert np.max(np.abs(loaded[in_contact])) <= 2e-5 * interference  # closed in the contact
    assert np.min(loaded, initial=0.0) >= -2e-5 * interference  # no overlap anywhere
    if load_control:
        assert float(result.pressure.sum()) * grid.cell_area == pytest.approx(load, rel=1e-10)


# --- EHL: load balance, p >= 0, positive film, Reynolds with cavitation ----------------------------------------
@SLOW
@given(n=st.sampled_from([16, 24, 32]), load=real(2.0, 60.0), speed=real(0.05, 3.0), ratio=real(1.0, 4.0))
def test_ehl_load_balance_and_cavitation(n, load, speed, ratio):
    rx = 0.01
    geometry = hertz.from_curvatures((1 / rx, 1 / (ratio * rx)), (0.0, 0.0), youngs_modulus=2.1e11, poisson_ratio=0.3)
    contact = hertz.solve_load(geometry, load)
    along, across = float(contact.b if ratio > 1 else contact.a), float(contact.a)
    grid = hs.SurfaceGrid(n, n, 5.5 * along / n, 5.0 * across / n, -1.25 * along, 0.0)
    X, Y = grid.coordinates()
    gap = X**2 / (2 * rx) + Y**2 / (2 * ratio * rx)
    film = ehl.hamrock_dowson_film(speed, load, rx, ratio * rx, 2 * geometry.contact_modulus, 0.05,
                                   ehl.roelands_pressure_viscosity_coefficient(0.05))["h_c"]
    solution = solved(ehl.solve_reynolds, gap, grid, geometry.contact_modulus, load, speed, 0.05, 870.0,
                      initial_film=film, max_iterations=60)
    if solution is None:
        return
    assert float(solution.pressure.sum()) * grid.cell_area == pytest.approx(load, rel=1e-5)
    assert np.all(solution.pressure >= 0.0) and np.all(solution.film > 0.0)
    assert np.any(solution.pressure[-1] == 0.0) or np.any(solution.pressure == 0.0)  # a cavitated outlet
    ehl.verify(solution, gap, geometry.contact_modulus, load, speed, 0.05, 870.0)  # from its pressure alone


# --- fits: the least-squares optimum (stationarity), in closed form -------------------------------------------
@SETTINGS
@given(n=st.integers(3, 12), mu=real(1e-4, 1.0), slope=real(-0.1, 0.1), noise=real(0.0, 0.05),
       scale=st.sampled_from([1e-150, 1e-3, 1.0, 1e3, 1e150]), seed=st.integers(0, 100), with_speed=st.booleans())
def test_fits_reach_the_least_squares_optimum(n, mu, slope, noise, scale, seed, with_speed):
    rng = np.random.default_rng(seed)
    normal = scale * rng.uniform(1.0, 10.0, n)
    speed = np.linspace(0.0, 2.0, n)
    friction = normal * (mu + (slope * speed if with_speed else 0.0)) * (1.0 + noise * rng.normal(size=n))
    result = solved(calibration.fit_friction_coefficient, normal, friction, speed if with_speed else None)
    if result is None:
        return
    columns = np.column_stack([normal, normal * speed] if with_speed else [normal]) / scale
    optimum = np.linalg.lstsq(columns, friction / scale, rcond=None)[0]
    assert result["mu"].value == pytest.approx(optimum[0], rel=1e-7, abs=1e-10)
    if with_speed:
        assert result["mu_speed_slope"].value == pytest.approx(optimum[1], rel=1e-6, abs=1e-9)
    k = solved(calibration.fit_line_through_origin, normal, -friction)
    if k is not None:
        assert k.value == pytest.approx(float(normal @ friction / (normal @ normal)), rel=1e-7)


# --- ball screw: power balance, contact forces >= 0, complementarity of the B2B contact ------------------------
SCREW = dict(mu=real(-5.0, -1.0), conformity=real(0.52, 0.6), angle=real(40.0, 50.0), lead=real(0.01, 0.04),
             deviation=real(-0.02, 0.02))


@SLOW
@given(oversize=real(1.5e-6, 3e-6), load=real(5.0, 60.0), **SCREW)
def test_screw_balance_at_small_mu(mu, conformity, angle, lead, oversize, load, deviation):
    _screw_balance(mu, conformity, angle, lead, oversize, load, deviation)


@pytest.mark.slow
@SETTINGS
@given(oversize=real(0.0, 3e-6), load=real(5.0, 300.0), **SCREW)
def test_screw_balance_wide(mu, conformity, angle, lead, oversize, load, deviation):
    _screw_balance(mu, conformity, angle, lead, oversize, load, deviation)


def _screw_balance(mu, conformity, angle, lead, oversize, load, deviation):
    module = screw_contacts.screw_module(friction_coefficient=10.0**mu, conformity=conformity,
                                         nominal_angle=math.radians(angle), lead=lead, oversize=oversize)
    state = solved(sb.solve, screw_contacts.ball_contacts(module, deviation), load)
    if state is not None:  # the nut puts in what friction dissipates (lin2019 Sec 3.1), whatever mu
        assert abs(state.input_power - state.groove_loss) <= 1e-8 * state.groove_loss
        assert np.all(state.normal_force >= 0.0) and np.all(state.friction_loss >= 0.0)
    pair = solved(screw_b2b.solve, screw_contacts.ball_contacts(module, [0.0, deviation]), 2.0 * load)
    if pair is not None:
        assert abs(pair.input_power - pair.total_loss) <= 1e-8 * pair.total_loss
        assert np.all(pair.b2b_force >= 0.0)
        closing = pair.orbit_speed[1] - pair.orbit_speed[0]  # eqs 60-61: F >= 0, closing >= 0, F closing = 0
        assert closing >= -1e-9 * abs(module.nut_speed)
        if pair.b2b_force[0] > 1e-9 * load:
            assert abs(closing) <= 1e-8 * abs(module.nut_speed)


# --- linear bearing: two touching balls ----------------------------------------------------------------------
@SETTINGS
@given(theta=real(0.0, 3.0), rho=real(-0.7, 0.7), mu=real(-4.0, -0.3), load=real(0.5, 500.0))
def test_linear_bearing_pair_balance_or_reason(theta, rho, mu, load):
    try:
        contacts = bearing_b2b.module_contacts(math.radians(theta), rho, n_balls=2, vertical_force=load,
                                               friction_coefficient=10.0**mu)
    except ValueError as error:  # rho beyond the four-point range of these angles (lin2017 eq 37)
        assert "side_force" in str(error)
        return
    state = solved(bearing_b2b.solve, contacts)
    if state is None:
        return
    assert abs(state.input_power - state.total_loss) <= 1e-8 * abs(state.input_power)
    assert np.all(state.b2b_force >= 0.0)
