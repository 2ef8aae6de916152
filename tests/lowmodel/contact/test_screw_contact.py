"""Ball in a helical groove: BEM on the exact gap against full-tensor Hertz (sun2021 Table 1 geometry)."""
import math

import pytest

from ballbench.lowmodel.contact import hertz, screw_contact
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.contact import halfspace, screw_contact as sc
import numpy as np
from hypothesis import given, strategies as st
from tests.property_support import EXTREME, SETTINGS, angle_limits, call, mostly, positive, real
from tests.property_support import length, force, lead_angle, contact_angle, count

R_B, R_G, R_P, BETA = 2.9765e-3, 3.215e-3, 16e-3, math.radians(40.26)  # sun2021 Table 1
STEEL = {"youngs_modulus": 200e9, "poisson_ratio": 0.3}


def test_eq1_load():
    # 1500 / (84 cos 5.68 deg sin 40.26 deg), evaluated independently
    expected = 1500.0 / (84 * 0.99509 * 0.646266)
    assert screw_contact.preload_contact_load(1500.0, 168, math.radians(5.68), BETA) == pytest.approx(expected,
                                                                                                        rel=1e-4)
    with pytest.raises(ValueError, match="preload"):
        screw_contact.preload_contact_load(-1.0, 168, 0.1, BETA)


@pytest.mark.parametrize("helix_deg, body, flank", [(0.0, "screw", "left"), (21.71, "screw", "left"),
                                                    (21.71, "nut", "right")])
def test_bem_on_exact_gap_matches_full_tensor_hertz(helix_deg, body, flank):
    lead = float(helix.lead_from_angle(math.radians(helix_deg), R_P))
    result = screw_contact.groove_contact(R_B, R_G / (2 * R_B), R_P, lead, BETA, 27.8, body, flank, n=128, **STEEL)
    assert result.bem.central_pressure == pytest.approx(float(result.hertz.p0), rel=5e-3)
    assert result.bem.force == pytest.approx(27.8, rel=1e-12)
    assert math.degrees(result.bem_angle) == pytest.approx(math.degrees(result.hertz_angle), abs=0.01)
    if helix_deg == 0.0:
        # a bearing raceway: no rotation, and all four models coincide
        assert abs(result.hertz_angle) < 1e-9
        assert float(result.forced.p0) == pytest.approx(float(result.hertz.p0), rel=1e-12)
        assert float(result.flat_helix.p0) == pytest.approx(float(result.hertz.p0), rel=1e-12)
        # and the full tensor is the bearing raceway of Harris (independent closed form)
        raceway = hertz.from_curvatures((1 / R_B, 1 / R_B), (-1 / R_G, math.cos(BETA) / (R_P - R_B * math.cos(BETA))),
                                        **STEEL)
        assert float(result.hertz.p0) == pytest.approx(float(hertz.solve_load(raceway, 27.8).p0), rel=1e-9)
    else:
        assert abs(math.degrees(result.hertz_angle)) > 0.1  # the helix rotates the principal axes


def test_sun2021_table1_as_data():
    import dataclasses

    from ballbench.validation.cases import sun2021

    t1 = sun2021.SCREW
    assert (t1.ball_radius, sun2021.GROOVE_RADIUS, t1.pitch_radius, t1.lead) == (2.9765e-3, 3.215e-3, 16e-3, 10e-3)
    # the convention "screw radius r = ball-centre radius" reproduces the printed helix angle 5.68 deg
    assert math.degrees(math.atan(t1.lead / (2 * math.pi * t1.pitch_radius))) == pytest.approx(5.68, abs=0.005)
    assert t1.conformity == pytest.approx(0.54006, abs=1e-5)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t1.lead = 0.0


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_preload_load_and_hertz_pressure_check_their_inputs():
    """preload_contact_load(1e300 N at 1e-16 rad) returned inf; hertz_pressure(a = 0) warned (0 / 0) and a
    negative semi-axis or pressure was accepted."""
    with pytest.raises(ValueError, match="preload"):
        sc.preload_contact_load(1e300, 2, 0.0, 1e-16)
    grid = halfspace.hertz_surface_grid(1e-4, 5e-5, 8, 1.3)
    for a, b, p0, name in ((0.0, 5e-5, 1e9, "a"), (-1e-4, 5e-5, 1e9, "a"), (1e-4, 5e-5, -1.0, "p0")):
        with pytest.raises(ValueError, match=name):
            sc.hertz_pressure(grid, a, b, p0)
    field = sc.hertz_pressure(grid, 1e-300, 5e-5, 1e9)   # a needle: zero pressure off its axis, no warning
    assert np.all(np.isfinite(field)) and field.max() <= 1e9


@pytest.mark.filterwarnings("error")
def test_groove_contact_names_the_grid_margin():
    """A coarse BEM grid whose contact reaches the grid edge: halfspace's error named its own 'half_width'."""
    with pytest.raises(ValueError, match="margin"):
        sc.groove_contact(2.778e-3, 0.56, 16.5e-3, 20e-3, 0.785, 100.0, youngs_modulus=2.1e11, poisson_ratio=0.3,
                          n=16, margin=1.0001)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(preload=force, balls=count, psi=lead_angle, alpha=contact_angle, a=length, b=length, p0=force,
       rotation=mostly(real(-4.0, 4.0), *EXTREME))
def test_screw_contact(preload, balls, psi, alpha, a, b, p0, rotation):
    call(sc.preload_contact_load, preload, balls, psi, alpha)
    grid = halfspace.hertz_surface_grid(1e-4, 5e-5, 8, 1.3)
    field = call(sc.hertz_pressure, grid, a, b, p0, rotation, (0.1 * a, 0.0))
    if field is not None:
        assert np.all(field >= 0.0) and np.all(field <= p0)


@SETTINGS
@given(ball_radius=mostly(positive(1e-4, 1e-2), *EXTREME), conf=mostly(real(0.51, 0.6), 0.5, 1.0),
       lead=mostly(real(0.0, 0.05), *EXTREME), alpha=mostly(real(0.3, 1.2), *angle_limits),
       load=mostly(real(1.0, 1e3), *EXTREME), body=st.sampled_from(["screw", "nut"]))
def test_groove_contact(ball_radius, conf, lead, alpha, load, body):
    call(sc.groove_contact, ball_radius, conf, 6.0 * ball_radius, lead, alpha, load, body, youngs_modulus=2.1e11,
         poisson_ratio=0.3, n=16)


@pytest.mark.parametrize("n", [9, 11])
def test_groove_contact_on_small_odd_grids(n):
    # the lowest cell of the exact gap is the only start cell on these grids: the BEM used to return it with the
    # whole load (25 and 37 times the Hertz p0); now the central pressure is Hertz's to the discretisation error
    result = screw_contact.groove_contact(R_B, R_G / (2 * R_B), R_P, 0.01, BETA, 27.77, n=n, **STEEL)
    assert result.bem.central_pressure == pytest.approx(float(result.hertz.p0), rel=0.01)
    assert result.bem.iterations > 1
