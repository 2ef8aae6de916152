"""Harris method: ball kinematics of a ball bearing relative to the cage (wang2022 ref [20]).

Harris & Kotzalas, Rolling Bearing Analysis (2006), Vol 1, ball-bearing
kinematics, with equal inner and outer contact angles alpha and no gyroscopic
spin: with ``gamma = D cos(alpha) / d_m = r_b cos(alpha) / r_m``,

* cage speed ``omega_c = [omega_i (1 - gamma) + omega_o (1 + gamma)] / 2``
* raceway surface speed relative to the cage at the contact
  ``u_i = (omega_i - omega_c) r_m (1 - gamma)`` (inner),
  ``u_o = (omega_c - omega_o) r_m (1 + gamma)`` (outer);
* pure rolling: the ball surface moves with the raceway, so the entrainment
  velocities are ``U_i = |u_i|``, ``U_o = |u_o|`` and the slide-roll ratios are 0.

Both speeds equal ``(omega_i - omega_o) r_m (1 - gamma^2) / 2``; wang2022
Table 1 (61830, 3600 rpm) prints 15.994 m/s.  Names follow the ball screw of
:mod:`lowmodel.screw.kinematics`: the inner ring is the screw (contact B),
the outer ring the nut (contact A).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["HarrisKinematics", "kinematics"]


@dataclass(frozen=True)
class HarrisKinematics:
    """Harris ball-bearing kinematics; arrays of the broadcast input shape.

    cage_speed : omega_c [rad/s]
    ball_spin_speed : ball speed about its own axis relative to the cage [rad/s]
    entrainment_outer, entrainment_inner : U_A (outer/nut), U_B (inner/screw) [m/s]
    slide_roll_outer, slide_roll_inner : S_A, S_B [-] (0: pure rolling)
    """

    cage_speed: np.ndarray
    ball_spin_speed: np.ndarray
    entrainment_outer: np.ndarray
    entrainment_inner: np.ndarray
    slide_roll_outer: np.ndarray
    slide_roll_inner: np.ndarray


def kinematics(pitch_radius, ball_radius, inner_speed, contact_angle, outer_speed=0.0) -> HarrisKinematics:
    """Harris kinematics of a ball bearing, vectorised.

    pitch_radius r_m [m] > ball_radius; ball_radius r_b [m] > 0;
    inner_speed, outer_speed [rad/s]; contact_angle alpha [rad] in (0, pi/2).
    """
    r_m = checks.positive("pitch_radius", pitch_radius, "m")
    r_b = checks.positive("ball_radius", ball_radius, "m")
    if np.any(r_b >= r_m):
        raise ValueError(f"ball_radius must be < pitch_radius, got ball_radius={ball_radius!r}, "
                         f"pitch_radius={pitch_radius!r}")
    omega_i = checks.finite("inner_speed", inner_speed)
    omega_o = checks.finite("outer_speed", outer_speed)
    alpha = checks.contact_angle("contact_angle", contact_angle)
    gamma = r_b * np.cos(alpha) / r_m
    cage = 0.5 * (omega_i * (1.0 - gamma) + omega_o * (1.0 + gamma))  # Harris: cage speed
    inner = np.abs(omega_i - cage) * r_m * (1.0 - gamma)  # inner raceway speed relative to cage
    outer = np.abs(cage - omega_o) * r_m * (1.0 + gamma)  # outer raceway speed relative to cage
    # Harris: omega_R = (d_m / 2D)(1 - gamma^2)(omega_i - omega_o), spin axis normal to the contact line
    spin = outer / r_b
    zero = np.zeros(np.broadcast(inner, outer).shape)
    return HarrisKinematics(cage + zero, spin + zero, outer + zero, inner + zero, zero, zero)
