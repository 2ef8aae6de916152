"""Friction torque of a preloaded double-nut ball screw (sun2021 eq 20) with wang2022 contact kinematics.

sun2021 eq 20::

    M = n_bb (F_SBt cos(alpha) + F_SBb sin(alpha)) (r + r_b cos(beta_B))

with ``F_SBt``, ``F_SBb`` the friction force at the ball-nut contact B along
the Frenet directions t and b (its ref [31]), ``alpha`` the helix (lead) angle,
``r`` the pitch radius, ``r_b`` the ball radius, ``beta_B`` the nut contact angle
and ``n_bb`` the number of working balls.  sun2021 leaves the direction of
``F_SB`` unstated; here it is the direction of the sliding velocity at the nut
contact of wang2022 (eq 5, :mod:`ballbench.lowmodel.screw.kinematics`), of
magnitude ``mu Q_B``.

Labels: sun2021 calls the screw contact A and the nut contact B; wang2022 calls
the nut contact A and the screw contact B.  :func:`contact_speeds` returns
sun2021's labels.  sun2021's "screw speed" ``Omega'`` [mm/s] is the surface
speed of the pitch circle, ``omega r`` (its 502.65 mm/s is 300 rpm at r = 16 mm,
Table 1's 83 mm/s 50 rpm, Sec 4.3's 1005.3 mm/s 600 rpm): :func:`screw_angular_speed`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.screw import kinematics

__all__ = ["screw_angular_speed", "ContactSpeeds", "contact_speeds", "friction_torque"]


def screw_angular_speed(surface_speed, pitch_radius: float):
    """Screw angular speed omega [rad/s] from sun2021's screw speed ``Omega' = omega r`` [m/s]."""
    r = checks.positive("pitch_radius", pitch_radius, "m")
    speed = checks.finite("surface_speed", surface_speed, "m/s")
    with np.errstate(over="ignore"):
        return checks.finite_result("surface_speed, pitch_radius", np.divide(speed, r), "rad/s")


@dataclass(frozen=True)
class ContactSpeeds:
    """Entrainment and sliding at sun2021's contacts A (screw) and B (nut), wang2022 eqs 1-6 [m/s].

    entrainment_A, entrainment_B : u_s = |v_1 + v_2| / 2 (wang2022 eqs 1-2)
    sliding_A, sliding_B : (..., 3) sliding velocity in Frenet components (t, n, b) (wang2022 eqs 5-6)
    """

    entrainment_A: np.ndarray
    entrainment_B: np.ndarray
    sliding_A: np.ndarray
    sliding_B: np.ndarray


def contact_speeds(surface_speed, pitch_radius: float, ball_radius: float, lead: float,
                   contact_angle: float) -> ContactSpeeds:
    """Entrainment and sliding velocities at A (screw) and B (nut) for sun2021's screw speed ``Omega'`` [m/s].

    wang2022's present model (:func:`ballbench.lowmodel.screw.kinematics.kinematics`)
    with the screw turning at ``Omega' / r`` and equal contact angles [rad];
    lengths [m].
    """
    state = kinematics.kinematics(pitch_radius, ball_radius, lead, screw_angular_speed(surface_speed, pitch_radius),
                                  contact_angle)
    # wang2022 A = nut = sun2021 B; wang2022 B = screw = sun2021 A
    return ContactSpeeds(entrainment_A=state.entrainment_screw, entrainment_B=state.entrainment_nut,
                         sliding_A=state.sliding_velocity_screw, sliding_B=state.sliding_velocity_nut)


def friction_torque(friction_coefficient, load_B, sliding_B, *, ball_count: int, lead_angle: float,
                    pitch_radius: float, ball_radius: float, contact_angle_B: float):
    """Friction torque M [N m] of sun2021 eq 20.

    ``friction_coefficient`` mu at B (eq 21), ``load_B`` Q_B [N], ``sliding_B``
    (..., 3) the sliding velocity at B in Frenet components (t, n, b) [m/s] (its
    direction only: the friction force is ``mu Q_B`` along it), ``ball_count``
    n_bb, ``lead_angle`` alpha [rad], ``pitch_radius`` r and ``ball_radius`` r_b
    [m], ``contact_angle_B`` beta_B [rad].  Returns ``|M|``.
    """
    mu = checks.non_negative("friction_coefficient", friction_coefficient)
    q = checks.non_negative("load_B", load_B, "N")
    n_bb = checks.count("ball_count", ball_count, 1)
    alpha = checks.lead_angle("lead_angle", lead_angle)
    r = checks.positive("pitch_radius", pitch_radius, "m")
    r_b = checks.positive("ball_radius", ball_radius, "m")
    beta = checks.contact_angle("contact_angle_B", contact_angle_B)
    sliding = checks.finite("sliding_B", checks.trailing_axis("sliding_B", sliding_B, 3, "tnb", "m/s"), "m/s")
    # only its direction counts: each row over a power of two near its largest component (exact, the same
    # direction to the bit) so that |sliding_B| neither overflows nor underflows
    sliding = np.ldexp(sliding, -np.frexp(np.max(np.abs(sliding), axis=-1, keepdims=True))[1])
    speed = np.linalg.norm(sliding, axis=-1)
    if np.any(speed == 0.0):
        raise ValueError("sliding_B must be non-zero (it sets the direction of the friction force)")
    with np.errstate(over="ignore", invalid="ignore"):
        force = (mu * q / speed)[..., None] * sliding  # friction force mu Q_B along the sliding velocity
        lever = r + r_b * math.cos(beta)
        torque = n_bb * (force[..., 0] * math.cos(alpha) + force[..., 2] * math.sin(alpha)) * lever  # sun2021 eq 20
    torque = checks.finite_result("friction_coefficient, load_B, pitch_radius, ball_radius", torque, "N m")
    return np.abs(torque) if np.ndim(torque) else abs(float(torque))
