"""Mixed lubrication (lowmodel.contact.mixed) and the eq 20 friction torque (lowmodel.screw.friction_torque)."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ehl, halfspace, hertz, mixed
from ballbench.lowmodel.screw import friction_torque, kinematics
from ballbench.lowmodel.contact import halfspace as hs
from hypothesis import given, strategies as st
from tests.property_support import SLOW, call, one_bad, real
from tests.lowmodel.contact.ehl_support import EHL_BAD, EHL_VALID, ehl_case_rx

E, NU, ETA0 = 2.1e11, 0.3, 0.05
E_STAR = E / (2 * (1 - NU**2))
INITIAL = 2.5e-7


RX = 0.01  # as tests/lowmodel/contact/test_ehl.py (a point that converges at 64 x 64): R_x = R_y = 10 mm, 20 N, 1 m/s


def case(n=48):
    geometry = hertz.from_curvatures((1 / RX, 1 / RX), (0.0, 0.0), youngs_modulus=E, poisson_ratio=NU)
    a = float(hertz.solve_load(geometry, 20.0).a)
    grid = halfspace.SurfaceGrid(n, n, 5.5 * a / n, 5.0 * a / n, -1.25 * a, 0.0)
    X, Y = grid.coordinates()
    return grid, (X**2 + Y**2) / (2 * RX)


def test_smooth_raceway_is_full_film_and_equals_the_ehl_solve():
    grid, gap = case(64)
    contact = mixed.solve(gap, np.zeros_like(gap), grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL)
    direct = ehl.solve_reynolds(gap, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL, coarsest=16)
    assert contact.coupled and contact.asperity_load == 0.0 and contact.asperity_share == 0.0
    assert contact.central_asperity_pressure == 0.0
    assert np.allclose(contact.film.pressure, direct.pressure, rtol=0, atol=1e-9 * direct.max_pressure)
    friction = mixed.mixed_friction(contact, 0.02, ETA0, 5e6)
    assert friction.asperity_friction == 0.0
    assert friction.friction_coefficient == pytest.approx(friction.film_friction / 20.0, rel=1e-12)


def test_rough_raceway_shares_the_load():
    grid, gap = case(64)
    smooth = ehl.solve_reynolds(gap, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL, coarsest=16)
    X, Y = grid.coordinates()
    # a ridge across the track as high as the film: it must reach through and carry load
    heights = 1.5 * smooth.central_film * np.exp(-((X / (4 * grid.dx)) ** 2))
    contact = mixed.solve(gap, heights, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL, coupled=False)
    assert not contact.coupled and contact.clearance < 0.0
    assert 0.0 < contact.asperity_share < 1.0
    # load sharing, sun2021 eq 21: film load + asperity load = Q to the share tolerance
    assert contact.film.force + contact.asperity_load == pytest.approx(20.0, rel=1e-2)
    # the rough film is the separation of the asperity contact: zero exactly where asperities carry pressure
    assert np.all(contact.rough_film[contact.asperity_pressure > 0.0] == 0.0)
    assert np.all(contact.rough_film >= 0.0)
    friction = mixed.mixed_friction(contact, 0.02, ETA0, 5e6, dry_friction=0.1)
    assert friction.asperity_friction == pytest.approx(0.1 * contact.asperity_load)
    assert friction.friction_coefficient > friction.film_friction / 20.0


def test_coupled_rough_film_flattens_long_waves():
    grid, gap = case(64)
    smooth = ehl.solve_reynolds(gap, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL, coarsest=16)
    X, Y = grid.coordinates()
    # a wave along the track, longer than the contact, as high as the smooth film: the rigid (decoupled)
    # film touches, the coupled film pressure flattens it and stays open
    heights = 1.2 * smooth.minimum_film * np.cos(2 * np.pi * X / (grid.nx * grid.dx))
    decoupled = mixed.solve(gap, heights, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL, coupled=False)
    contact = mixed.solve(gap, heights, grid, E_STAR, 20.0, 1.0, ETA0, initial_film=INITIAL)
    assert decoupled.clearance < 0.0 < contact.clearance
    assert contact.coupled and contact.asperity_share == 0.0
    assert contact.film.force == pytest.approx(20.0, rel=1e-4)


def test_asperity_contact_is_zero_without_interference_and_rejects_bad_shapes():
    grid, gap = case(16)
    pressure, load, rough = mixed.asperity_contact(gap + 1e-7, np.zeros_like(gap), grid, E_STAR)
    assert load == 0.0 and not pressure.any() and np.array_equal(rough, gap + 1e-7)
    with pytest.raises(ValueError, match="heights"):
        mixed.solve(gap, np.zeros((3, 3)), grid, E_STAR, 20.0, 1.0, ETA0)


def test_friction_torque_eq20_by_hand_and_speeds_follow_wang2022():
    r, r_b, lead, beta = 16e-3, 2.9765e-3, 10e-3, math.radians(40.26)
    speeds = friction_torque.contact_speeds(0.50265, r, r_b, lead, beta)
    state = kinematics.kinematics(r, r_b, lead, 0.50265 / r, beta)
    # sun2021 A = screw = wang2022 B, sun2021 B = nut = wang2022 A
    assert speeds.entrainment_B == state.entrainment_nut and speeds.entrainment_A == state.entrainment_screw
    assert 0.45 < float(speeds.entrainment_B) / 0.50265 < 0.5  # about half the pitch-circle speed
    alpha = math.atan(lead / (2 * math.pi * r))
    torque = friction_torque.friction_torque(0.05, 27.0, speeds.sliding_B, ball_count=168, lead_angle=alpha,
                                             pitch_radius=r, ball_radius=r_b, contact_angle_B=beta)
    direction = np.asarray(speeds.sliding_B) / np.linalg.norm(speeds.sliding_B)
    by_hand = 168 * 0.05 * 27.0 * (direction[0] * math.cos(alpha) + direction[2] * math.sin(alpha)) * (
        r + r_b * math.cos(beta))
    assert torque == pytest.approx(abs(by_hand), rel=1e-12)
    # the torque is linear in mu and in the load, and independent of the sliding speed's magnitude
    assert friction_torque.friction_torque(0.1, 27.0, 3 * np.asarray(speeds.sliding_B), ball_count=168,
                                           lead_angle=alpha, pitch_radius=r, ball_radius=r_b,
                                           contact_angle_B=beta) == pytest.approx(2 * torque, rel=1e-12)
    with pytest.raises(ValueError, match="sliding_B"):
        friction_torque.friction_torque(0.05, 27.0, [0.0, 0.0, 0.0], ball_count=168, lead_angle=alpha,
                                        pitch_radius=r, ball_radius=r_b, contact_angle_B=beta)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_asperity_contact_names_heights():
    grid = hs.surface_grid(1e-4, 1e-4, 8, 8)
    with pytest.raises(ValueError, match="heights"):  # named gap, not a parameter of asperity_contact
        mixed.asperity_contact(np.full((8, 8), 1e-7), np.full((8, 8), 1e300), grid, 1e11)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SLOW
@given(kw=one_bad(dict(EHL_VALID, rough=real(0.0, 1e-6), coupled=st.booleans(), mu_a=real(0.0, 0.3)),
                  dict(EHL_BAD, rough=st.sampled_from([1e300, -1.0]), mu_a=st.sampled_from([-0.1, 1e300]))))
def test_mixed(kw):
    e_star, grid, gap = ehl_case_rx(kw["n"])
    heights = kw["rough"] * np.cos(np.arange(grid.nx * grid.ny).reshape(grid.nx, grid.ny))
    call(mixed.asperity_contact, gap * 0.0 + 1e-7, heights, grid, e_star)
    contact = call(mixed.solve, gap, heights, grid, e_star, kw["load"], kw["u"], kw["eta0"],
                   initial_film=kw["film"], coupled=kw["coupled"], max_iterations=4, ehl_iterations=30)
    if contact is not None:
        assert contact.film_load + contact.asperity_load == pytest.approx(kw["load"], rel=0.02)
        call(mixed.mixed_friction, contact, kw["du"], kw["eta0"], kw["tau0"], kw["mu_a"])
