"""Contact ellipse truncation (lowmodel.truncation) against hand computations (docs/truncation.md)."""
import math

import pytest

from ballbench.lowmodel import truncation

R_B = 1.5875e-3  # a 1/8-inch ball


def test_shoulder_angle_by_hand():
    # f 0.52, beta_r 47 deg, land 0.25 R_B (units of R_B): r_g = 1.04, the arc centre
    # C = -0.04 (sin 47, cos 47) = (-0.029254, -0.027280); the flank meets u = 0.25 at
    # v = -0.029254 + sqrt(1.04^2 - (0.25 + 0.027280)^2) = -0.029254 + sqrt(1.0816 - 0.076884) = 0.973097,
    # theta_s = atan2(0.973097, 0.25) = 75.592 deg
    theta = truncation.shoulder_angle(R_B, 0.52, math.radians(47.0))
    assert math.degrees(theta) == pytest.approx(75.592, abs=2e-3)
    # f -> 0.5: the flank is the ball's own circle, cos theta_s = 0.25 (75.52 deg)
    assert math.degrees(truncation.shoulder_angle(R_B, 0.5 + 1e-9, math.radians(40.0))) == pytest.approx(
        math.degrees(math.acos(0.25)), abs=1e-4)


def test_land_depth_inverts_the_shoulder_angle():
    # by hand: theta 80 deg on the same flank, u.C = -0.04 cos 33 deg = -0.033547,
    # rho = -0.033547 + sqrt(0.033547^2 - 0.04^2 + 1.04^2) = 1.006225, depth = rho cos 80 deg = 0.174729
    depth = truncation.land_depth(R_B, 0.52, math.radians(47.0), math.radians(80.0))
    assert depth == pytest.approx(0.174729, abs=2e-6)
    assert truncation.shoulder_angle(R_B, 0.52, math.radians(47.0), depth) == pytest.approx(math.radians(80.0),
                                                                                            abs=1e-12)


def test_the_heavy_template_guide_is_truncated_on_one_contact():
    # ballbench init linear-guide at N_y = 500 N, ball 2 BR: beta 47 deg, a = 0.783 mm;
    # asin(0.783 / 1.5875) = asin(0.49323) = 29.553 deg, the end at 76.553 deg > 75.592 deg
    t = truncation.truncation("ball 2 BR", R_B, 0.52, math.radians(47.0), math.radians(47.0), 0.783e-3)
    assert math.degrees(t.end_angle) == pytest.approx(76.553, abs=2e-3)
    assert t.truncated and math.degrees(t.margin) == pytest.approx(-0.961, abs=3e-3)
    assert "ball 2 BR" in truncation.words([t]) and "76.6 deg" in truncation.words([t])
    # its lighter contact (a = 0.4705 mm at 47 deg: 47 + 17.240 = 64.240 deg) keeps 11.352 deg
    light = truncation.truncation("ball 1 BR", R_B, 0.52, math.radians(47.0), math.radians(47.0), 0.4705e-3)
    assert not light.truncated and math.degrees(light.margin) == pytest.approx(11.352, abs=3e-3)
    assert truncation.words([light]) == ""


def test_bad_input_names_the_parameter():
    with pytest.raises(ValueError, match="depth"):
        truncation.shoulder_angle(R_B, 0.52, math.radians(45.0), depth=1.2)
    with pytest.raises(ValueError, match="a"):
        truncation.end_angle(R_B, math.radians(45.0), -1e-3)
