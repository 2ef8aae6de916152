"""Ball in a helical groove: BEM on the exact gap against full-tensor Hertz (sun2021 Table 1 geometry)."""
import math

import pytest

from ballbench.lowmodel.contact import hertz, screw_contact
from ballbench.lowmodel.geometry import helix

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

    from ballbench.validation.papers import sun2021

    t1 = sun2021.TABLE_1
    assert (t1.ball_radius, t1.groove_radius, t1.pitch_radius, t1.lead) == (2.9765e-3, 3.215e-3, 16e-3, 10e-3)
    # the convention "screw radius r = ball-centre radius" reproduces the printed helix angle 5.68 deg
    assert math.degrees(math.atan(t1.lead / (2 * math.pi * t1.pitch_radius))) == pytest.approx(5.68, abs=0.005)
    assert t1.conformity == pytest.approx(0.54006, abs=1e-5)
    with pytest.raises(dataclasses.FrozenInstanceError):
        t1.lead = 0.0


@pytest.mark.parametrize("n", [9, 11])
def test_groove_contact_on_small_odd_grids(n):
    # the lowest cell of the exact gap is the only start cell on these grids: the BEM used to return it with the
    # whole load (25 and 37 times the Hertz p0); now the central pressure is Hertz's to the discretisation error
    result = screw_contact.groove_contact(R_B, R_G / (2 * R_B), R_P, 0.01, BETA, 27.77, n=n, **STEEL)
    assert result.bem.central_pressure == pytest.approx(float(result.hertz.p0), rel=0.01)
    assert result.bem.iterations > 1
