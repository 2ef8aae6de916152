"""lowmodel.screw.friction_torque: the eq 20 friction torque of a ball screw (sun2021) over its input range."""
import math

import pytest
from ballbench.lowmodel.screw import friction_torque as ft
from hypothesis import given
from hypothesis import strategies as st

from tests.property_support import SETTINGS, call, mostly, real
from tests.property_support import length, speed, force, lead_angle, contact_angle, ball_fraction, count

# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


TINY = 5e-324  # the smallest float


@pytest.mark.filterwarnings("error")
def test_friction_torque_at_extreme_sliding_speeds():
    """sliding_B = (-1, 0, 1e300) m/s gave |sliding_B| = inf (overflow warning) and a torque of 0; only the
    direction counts, so it must equal the torque of (0, 0, 1).  mu = Q = 1e300 gave NaN."""
    common = dict(ball_count=10, lead_angle=0.1, pitch_radius=0.016, ball_radius=3e-3, contact_angle_B=0.7)
    along_b = ft.friction_torque(0.1, 100.0, [0.0, 0.0, 1.0], **common)
    assert along_b > 0.0
    assert ft.friction_torque(0.1, 100.0, [-1.0, 0.0, 1e300], **common) == pytest.approx(along_b, rel=1e-15)
    assert ft.friction_torque(0.1, 100.0, [0.0, 0.0, TINY], **common) == along_b
    with pytest.raises(ValueError, match="friction_coefficient, load_B"):
        ft.friction_torque(1e300, 1e300, [1.0, 0.0, 0.0], **common)
    with pytest.raises(ValueError, match="surface_speed, pitch_radius"):
        ft.screw_angular_speed(-1.0, TINY)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(surface=speed, pitch_radius=length, fraction=ball_fraction, lead=length, alpha=contact_angle,
       mu=mostly(real(0.0, 0.5), -0.1, 1e300), load=force, sliding=st.tuples(speed, speed, speed), balls=count,
       psi=lead_angle)
def test_friction_torque(surface, pitch_radius, fraction, lead, alpha, mu, load, sliding, balls, psi):
    ball_radius = pitch_radius * fraction
    call(ft.screw_angular_speed, surface, pitch_radius)
    call(ft.contact_speeds, surface, pitch_radius, ball_radius, lead, alpha)
    torque = call(ft.friction_torque, mu, load, sliding, ball_count=balls, lead_angle=psi, pitch_radius=pitch_radius,
                  ball_radius=ball_radius, contact_angle_B=alpha)
    if torque is not None:   # |M| <= n mu Q (r + r_b cos beta): the friction force mu Q_B has no larger lever
        assert torque <= balls * mu * load * (pitch_radius + ball_radius * math.cos(alpha)) * (1.0 + 1e-12)
