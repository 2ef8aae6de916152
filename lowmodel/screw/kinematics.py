"""Ball-screw contact kinematics with the Frenet frame as a virtual cage (wang2022).

Implements wang2022 eqs 1-30: contact-point positions, absolute velocities
of the nut, screw and ball surfaces, convected velocities of the Frenet
frame, relative velocities, entrainment velocity (eqs 1-2), sliding velocity
(eqs 5-6), slide-roll ratio (eq 4), ball orbital and spin speeds (eqs 18-21)
and centrifugal force (eq 22).  The same inputs also give Wei's measures
(:func:`absolute_velocity_measures`, entrainment and slide-roll ratio from
absolute velocities) and the Harris method of a ball bearing
(:mod:`lowmodel.ball_bearing.harris`).

Geometry and frames come from :mod:`lowmodel.geometry.helix`: vectors are Frenet
components ``(t, n, b)`` of the ball at azimuth ``theta = 0`` (wang2022
Sec 2.3: in CS1 the velocities do not depend on theta).  Contact A is the
ball-nut contact, B the ball-screw contact; the screw turns at omega about
+k, the nut translates axially (wang2022 eq 16), nothing else moves.

Everything is vectorised: the inputs broadcast together (balls, speeds,
geometries); scalars give shape ``()`` and vectors ``(..., 3)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.dual import cross
from ballbench.lowmodel.geometry import helix

__all__ = ["ScrewKinematics", "kinematics", "pitch_angle", "orbital_speed", "ball_spin_speed",
           "ball_angular_velocity", "centrifugal_force", "absolute_velocity_measures", "entrainment_velocity",
           "slide_roll_ratio", "slide_roll_ratio_magnitude", "wei_ball_centre_kinematics", "WeiKinematics"]


def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _scale(factor, a):
    return (factor * a[0], factor * a[1], factor * a[2])


def _length(a):
    with np.errstate(over="ignore"):
        squared = a[0] * a[0] + a[1] * a[1] + a[2] * a[2]
    if np.all(np.isfinite(squared)):
        return np.sqrt(squared)
    return np.hypot(np.hypot(a[0], a[1]), a[2])  # huge speeds: no overflow of the squares


def _components(vector: np.ndarray):
    """The three components of ``vector`` (..., 3) as contiguous arrays (fast elementwise arithmetic)."""
    return tuple(np.array(vector[..., i]) for i in range(3))


def _norm(vector: np.ndarray) -> np.ndarray:
    vector = np.asarray(vector)
    return np.hypot(np.hypot(vector[..., 0], vector[..., 1]), vector[..., 2])


# --------------------------------------------------------------------------
# ball motion, wang2022 eqs 18-22: unchecked kernels (shared by kinematics()) and checked public wrappers
# --------------------------------------------------------------------------
def _pitch_angle(cos_o, sin_o, gamma):
    """wang2022 eq 21: ``tan beta = sin alpha_o / (cos alpha_o (1 + gamma'))``."""
    return np.arctan2(sin_o, cos_o * (1.0 + gamma))


def _orbital_speed(omega, gamma, cos_o, sin_o, cos_i, sin_i, tan_beta):
    """wang2022 eq 18: ``omega_m = omega / (1 + ratio)``."""
    ratio = ((1.0 + gamma * cos_o) * (cos_i + tan_beta * sin_i)
             / ((1.0 - gamma * cos_i) * (cos_o + tan_beta * sin_o)))
    return omega / (1.0 + ratio)


def _spin_speed(omega_m, gamma, cos_o, sin_o, cos_psi, cos_beta, sin_beta):
    """wang2022 eq 19: the ball's spin speed omega_R relative to the Frenet frame."""
    return omega_m * (1.0 + gamma * cos_o) * cos_psi / (gamma * (cos_beta * cos_o + sin_beta * sin_o))


def _angular_velocity(spin, cos_beta, sin_beta, yaw):
    """wang2022 eq 20: ``(omega_t, omega_n, omega_b)`` as a component triple."""
    return (spin * cos_beta * np.sin(yaw), -spin * sin_beta, -spin * cos_beta * np.cos(yaw))


def pitch_angle(contact_angle_nut, ball_radius, pitch_radius) -> np.ndarray:
    """Ball pitch angle beta [rad] relative to the Frenet frame (wang2022 eq 21).

    ``tan beta = sin alpha_o / (cos alpha_o + r_b cos alpha_o / r_m)``: the
    spin axis for pure rolling at the nut (outer) contact.
    """
    alpha_o = checks.contact_angle("contact_angle_nut", contact_angle_nut)
    gamma = checks.positive("ball_radius", ball_radius, "m") / checks.positive(
        "pitch_radius", pitch_radius, "m")
    return _pitch_angle(np.cos(alpha_o), np.sin(alpha_o), gamma)


def _radius_ratio(ball_radius, pitch_radius):
    """gamma' = r_b / r_m of wang2022, with r_b, r_m [m] > 0 and r_b < r_m (ball inside the pitch circle)."""
    r_b = checks.positive("ball_radius", ball_radius, "m")
    r_m = checks.positive("pitch_radius", pitch_radius, "m")
    if np.any(r_b >= r_m):
        raise ValueError(f"ball_radius must be < pitch_radius (ball inside the pitch circle), "
                         f"got ball_radius={ball_radius!r}, pitch_radius={pitch_radius!r}")
    return r_b / r_m


def orbital_speed(screw_speed, ball_radius, pitch_radius, contact_angle_nut, contact_angle_screw,
                  pitch_angle_rad) -> np.ndarray:
    """Orbital angular speed omega_m = theta' [rad/s] of the ball (wang2022 eq 18).

    ``screw_speed`` [rad/s]; radii [m] > 0 with ``ball_radius < pitch_radius``; contact angles and the
    pitch angle beta (eq 21) [rad] in (0, pi/2).
    """
    omega = checks.finite("screw_speed", screw_speed, "rad/s")
    gamma = _radius_ratio(ball_radius, pitch_radius)
    alpha_o = checks.contact_angle("contact_angle_nut", contact_angle_nut)
    alpha_i = checks.contact_angle("contact_angle_screw", contact_angle_screw)
    tan_beta = np.tan(checks.contact_angle("pitch_angle_rad", pitch_angle_rad))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        speed = _orbital_speed(omega, gamma, np.cos(alpha_o), np.sin(alpha_o), np.cos(alpha_i), np.sin(alpha_i),
                               tan_beta)  # wang2022 eq 18
    return checks.finite_result("screw_speed, ball_radius, pitch_radius", speed, "rad/s")


def ball_spin_speed(orbital_speed_rad_s, ball_radius, pitch_radius, contact_angle_nut, lead_angle,
                    pitch_angle_rad) -> np.ndarray:
    """Ball spin speed omega_R [rad/s] about its own axis, relative to the Frenet frame (wang2022 eq 19).

    ``orbital_speed_rad_s`` [rad/s]; radii [m] > 0 with ``ball_radius < pitch_radius``; ``contact_angle_nut``
    and the pitch angle [rad] in (0, pi/2), ``lead_angle`` [rad] in [0, pi/2).
    """
    omega_m = checks.finite("orbital_speed_rad_s", orbital_speed_rad_s, "rad/s")
    gamma = _radius_ratio(ball_radius, pitch_radius)
    alpha_o = checks.contact_angle("contact_angle_nut", contact_angle_nut)
    beta = checks.contact_angle("pitch_angle_rad", pitch_angle_rad)
    psi = checks.lead_angle("lead_angle", lead_angle)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        spin = _spin_speed(omega_m, gamma, np.cos(alpha_o), np.sin(alpha_o), np.cos(psi), np.cos(beta),
                           np.sin(beta))  # wang2022 eq 19
    return checks.finite_result("orbital_speed_rad_s, ball_radius, pitch_radius", spin, "rad/s")


def ball_angular_velocity(spin_speed, pitch_angle_rad, yaw_angle=0.0) -> np.ndarray:
    """Ball angular velocity vector (omega_t, omega_n, omega_b) [rad/s] in CS1 (wang2022 eq 20).

    ``spin_speed`` [rad/s], ``pitch_angle_rad`` and ``yaw_angle`` [rad], all finite.
    """
    spin, beta, yaw = np.broadcast_arrays(checks.finite("spin_speed", spin_speed, "rad/s"),
                                          checks.finite("pitch_angle_rad", pitch_angle_rad, "rad"),
                                          checks.finite("yaw_angle", yaw_angle, "rad"))
    return np.stack(_angular_velocity(spin, np.cos(beta), np.sin(beta), yaw), axis=-1)  # wang2022 eq 20


def centrifugal_force(ball_mass, pitch_radius, orbital_speed_rad_s) -> np.ndarray:
    """Centrifugal force F_n = m r_m omega_m^2 [N] on the ball, along -n (wang2022 eq 22)."""
    mass = checks.positive("ball_mass", ball_mass, "kg")
    radius = checks.positive("pitch_radius", pitch_radius, "m")
    omega_m = np.asarray(checks.finite("orbital_speed_rad_s", orbital_speed_rad_s, "rad/s"), dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        force = mass * radius * omega_m ** 2  # wang2022 eq 22
    return checks.finite_result("ball_mass, pitch_radius, orbital_speed_rad_s", force, "N")


# --------------------------------------------------------------------------
# entrainment and slide-roll ratio, wang2022 eqs 1-6
# --------------------------------------------------------------------------
def entrainment_velocity(velocity_1, velocity_2) -> np.ndarray:
    """U = |v_1 + v_2| / 2 [m/s] of two surface velocities ``(..., 3)`` [m/s] (wang2022 eqs 1-2)."""
    v_1 = checks.finite("velocity_1", checks.trailing_axis("velocity_1", velocity_1, 3, "(t, n, b)", "m/s"), "m/s")
    v_2 = checks.finite("velocity_2", checks.trailing_axis("velocity_2", velocity_2, 3, "(t, n, b)", "m/s"), "m/s")
    with np.errstate(over="ignore"):
        return checks.finite_result("velocity_1, velocity_2", 0.5 * _norm(v_1 + v_2), "m/s")


def slide_roll_ratio(sliding_velocity, entrainment) -> np.ndarray:
    """S = |V_S| / U (wang2022 eq 4) of a sliding velocity ``(..., 3)`` [m/s] and the entrainment U [m/s] >= 0;
    0 where both are exactly zero; ValueError where U = 0 < |V_S| (no entrainment: S undefined)."""
    sliding = checks.finite("sliding_velocity", checks.trailing_axis("sliding_velocity", sliding_velocity, 3,
                                                                     "(t, n, b)", "m/s"), "m/s")
    entrainment = checks.non_negative("entrainment", entrainment, "m/s")
    return _slide_roll(_norm(sliding), entrainment, "sliding_velocity, entrainment")


def slide_roll_ratio_magnitude(sliding_speed, entrainment) -> np.ndarray:
    """S = |V_S| / U (wang2022 eq 4) from the sliding speed |V_S| [m/s] >= 0 and the entrainment U [m/s] >= 0;
    0 where both are exactly zero (contact at rest); ValueError where U = 0 < |V_S| (S undefined)."""
    sliding = checks.non_negative("sliding_speed", sliding_speed, "m/s")
    entrainment = checks.non_negative("entrainment", entrainment, "m/s")
    return _slide_roll(sliding, entrainment, "sliding_speed, entrainment")


def _slide_roll(sliding, entrainment, names: str) -> np.ndarray:
    """wang2022 eq 4 on checked magnitudes; ValueError naming ``names`` where S is undefined or overflows."""
    sliding = np.asarray(sliding, dtype=float)
    entrainment = np.asarray(entrainment, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = sliding / entrainment
    ratio = np.where((sliding == 0.0) & (entrainment == 0.0), 0.0, ratio)
    if not np.all(np.isfinite(ratio)):
        raise ValueError(f"{names}: the slide-roll ratio |V_S| / U is undefined or beyond the float range where "
                         f"the entrainment U is 0 (or ~1e-308 times |V_S|) and the sliding is not")
    return ratio


def absolute_velocity_measures(raceway_velocity, ball_velocity, *, raceway_is_driver: bool):
    """Wei's measures: entrainment U, sliding V_S and slide-roll S from velocities ``(..., 3)`` [m/s].

    Applies wang2022 eqs 1-6 to whatever velocities are passed; Wei's model
    passes absolute velocities, the present model relative ones.  The sliding
    velocity is ``ball - raceway`` at the nut (eq 5, ``raceway_is_driver=False``)
    and ``raceway - ball`` at the screw (eq 6, ``raceway_is_driver=True``).
    Returns ``(U, V_S, S)``.
    """
    raceway = checks.finite("raceway_velocity", checks.trailing_axis("raceway_velocity", raceway_velocity, 3,
                                                                     "(t, n, b)", "m/s"), "m/s")
    ball = checks.finite("ball_velocity", checks.trailing_axis("ball_velocity", ball_velocity, 3, "(t, n, b)", "m/s"),
                         "m/s")
    names = "raceway_velocity, ball_velocity"
    with np.errstate(over="ignore", invalid="ignore"):
        entrainment = checks.finite_result(names, 0.5 * _norm(raceway + ball), "m/s")  # wang2022 eqs 1-2
        sliding = checks.finite_result(names, raceway - ball if raceway_is_driver else ball - raceway,
                                       "m/s")  # wang2022 eqs 5-6
        speed = checks.finite_result(names, _norm(sliding), "m/s")
    return entrainment, sliding, _slide_roll(speed, entrainment, names)  # wang2022 eq 4


# --------------------------------------------------------------------------
# the present model
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class ScrewKinematics:
    """Contact kinematics of a ball in a ball screw (wang2022 eqs 1-30).

    Scalars have the broadcast shape ``S`` of the inputs, vectors ``S + (3,)``
    in Frenet components ``(t, n, b)`` [m/s].  A = ball-nut contact,
    B = ball-screw contact; superscripts of the paper: a absolute, e convected,
    r relative to the Frenet frame.

    Attributes
    ----------
    lead_angle : psi [rad]
    pitch_angle : beta [rad], eq 21
    orbital_speed : omega_m [rad/s], eq 18
    spin_speed : omega_R [rad/s], eq 19
    ball_angular_velocity : (omega_t, omega_n, omega_b) [rad/s] relative to CS1, eq 20
    nut_velocity : V_An^a, eq 16
    screw_velocity : V_Bs^a, eq 17
    ball_velocity_nut, ball_velocity_screw : V_Ab^a, V_Bb^a, eqs 23-24
    convected_velocity_nut, convected_velocity_screw : V_A^e, V_B^e, eqs 25-26
    nut_velocity_rel, ball_velocity_nut_rel : V_An^r, V_Ab^r, eqs 27-28
    screw_velocity_rel, ball_velocity_screw_rel : V_Bs^r, V_Bb^r, eqs 29-30
    sliding_velocity_nut, sliding_velocity_screw : V_SA, V_SB, eqs 5-6
    entrainment_nut, entrainment_screw : U_A, U_B [m/s], eqs 1-2
    slide_roll_nut, slide_roll_screw : S_A, S_B [-], eq 4
    """

    lead_angle: np.ndarray
    pitch_angle: np.ndarray
    orbital_speed: np.ndarray
    spin_speed: np.ndarray
    ball_angular_velocity: np.ndarray
    nut_velocity: np.ndarray
    screw_velocity: np.ndarray
    ball_velocity_nut: np.ndarray
    ball_velocity_screw: np.ndarray
    convected_velocity_nut: np.ndarray
    convected_velocity_screw: np.ndarray
    nut_velocity_rel: np.ndarray
    screw_velocity_rel: np.ndarray
    ball_velocity_nut_rel: np.ndarray
    ball_velocity_screw_rel: np.ndarray
    sliding_velocity_nut: np.ndarray
    sliding_velocity_screw: np.ndarray
    entrainment_nut: np.ndarray
    entrainment_screw: np.ndarray
    slide_roll_nut: np.ndarray
    slide_roll_screw: np.ndarray

    def centrifugal_force(self, ball_mass, pitch_radius) -> np.ndarray:
        """F_n = m r_m omega_m^2 [N] (wang2022 eq 22); ``ball_mass`` [kg], ``pitch_radius`` [m]."""
        return centrifugal_force(ball_mass, pitch_radius, self.orbital_speed)


def _check_geometry(pitch_radius, ball_radius, lead, screw_speed, contact_angle_nut, contact_angle_screw,
                    lead_angle):
    r_m = checks.positive("pitch_radius", pitch_radius, "m")
    r_b = checks.positive("ball_radius", ball_radius, "m")
    if np.any(r_b >= r_m):
        raise ValueError(f"ball_radius must be < pitch_radius (ball inside the pitch circle), "
                         f"got ball_radius={ball_radius!r}, pitch_radius={pitch_radius!r}")
    lead_m = checks.non_negative("lead", lead, "m")
    omega = checks.finite("screw_speed", screw_speed)
    alpha_o = checks.contact_angle("contact_angle_nut", contact_angle_nut)
    alpha_i = alpha_o if contact_angle_screw is None else checks.contact_angle(
        "contact_angle_screw", contact_angle_screw)
    psi = helix.lead_angle(lead_m, r_m) if lead_angle is None else checks.lead_angle("lead_angle", lead_angle)
    return r_m, r_b, lead_m, omega, alpha_o, alpha_i, psi


@np.errstate(over="ignore", invalid="ignore")  # overflow at huge speeds is detected and raised below
def kinematics(pitch_radius, ball_radius, lead, screw_speed, contact_angle_nut, contact_angle_screw=None, *,
               lead_angle=None, yaw_angle=0.0) -> ScrewKinematics:
    """Contact kinematics of the present model (wang2022 eqs 1-30), vectorised.

    Parameters (broadcast together)
    ----------
    pitch_radius : r_m [m], nominal (pitch) radius of the ball-centre helix, > ball_radius
    ball_radius : r_b [m] > 0 (wang2022 calls it a diameter; it is a radius)
    lead : L [m] >= 0 (0 is a ball bearing)
    screw_speed : omega [rad/s], screw (inner ring) speed about +k, finite; every velocity is linear
        in it (ValueError if they would overflow double precision, e.g. |omega| ~ 1e308 rad/s)
    contact_angle_nut, contact_angle_screw : alpha_o, alpha_i [rad] in (0, pi/2);
        ``contact_angle_screw=None`` takes alpha_i = alpha_o
    lead_angle : psi [rad]; ``None`` (default) takes ``arctan(L / (2 pi r_m))``,
        a value overrides it (wang2022 Table A1 prints 8.74 deg)
    yaw_angle : beta' [rad]; wang2022 sets it to 0
    """
    r_m, r_b, lead_m, omega, alpha_o, alpha_i, psi = _check_geometry(
        pitch_radius, ball_radius, lead, screw_speed, contact_angle_nut, contact_angle_screw, lead_angle)
    yaw = checks.finite("yaw_angle", yaw_angle)
    r_m, r_b, lead_m, omega, alpha_o, alpha_i, psi, yaw = np.broadcast_arrays(
        r_m, r_b, lead_m, omega, alpha_o, alpha_i, psi, yaw)
    zero = np.zeros(r_m.shape)

    # ball motion, wang2022 eqs 18-21 (the kernels of the public helpers above), trigonometric functions once:
    # beta's sine and cosine from the right triangle of eq 21 rather than from beta
    cos_o, sin_o, cos_i, sin_i = np.cos(alpha_o), np.sin(alpha_o), np.cos(alpha_i), np.sin(alpha_i)
    gamma = r_b / r_m  # gamma' of wang2022
    beta = _pitch_angle(cos_o, sin_o, gamma)  # wang2022 eq 21
    hypotenuse = np.sqrt(sin_o**2 + (cos_o * (1.0 + gamma)) ** 2)
    cos_beta, sin_beta = cos_o * (1.0 + gamma) / hypotenuse, sin_o / hypotenuse
    omega_m = _orbital_speed(omega, gamma, cos_o, sin_o, cos_i, sin_i, sin_beta / cos_beta)  # wang2022 eq 18
    omega_spin = _spin_speed(omega_m, gamma, cos_o, sin_o, np.cos(psi), cos_beta, sin_beta)  # wang2022 eq 19
    # vectors as (t, n, b) component triples inside (contiguous, fast); stacked to (..., 3) on output
    omega_ball = _angular_velocity(omega_spin, cos_beta, sin_beta, yaw)  # wang2022 eq 20
    # geometry and frame from the geometry core (lowmodel.geometry.helix), as component triples
    axis = _components(helix.axis_in_frenet(psi))  # k in CS1 (wang2022 eq 15)
    offset_a = _components(helix.contact_offset(r_b, alpha_o, "nut"))  # wang2022 eq 11
    offset_b = _components(helix.contact_offset(r_b, alpha_i, "screw"))  # wang2022 eq 12
    # ball-centre position at theta = 0 in CS1 (r_m i = -r_m n); its axial part drops out of k x R
    centre_b = (zero, offset_b[1] - r_m, offset_b[2])

    nut = _scale(-omega * helix.helix_parameter(lead_m), axis)  # wang2022 eq 16
    screw = _scale(omega, cross(axis, centre_b))  # wang2022 eq 17
    # convected velocity: ball-centre velocity + frame rotation omega_m k x R (wang2022 eqs 25-26)
    centre_velocity = _components(helix.ball_centre_velocity(omega_m, omega, r_m, lead_m, lead_angle=psi))
    frame_rate = _scale(omega_m, axis)  # helix.frame_angular_velocity: omega_m k
    convected_a = _add(centre_velocity, cross(frame_rate, offset_a))  # wang2022 eq 25
    convected_b = _add(centre_velocity, cross(frame_rate, offset_b))  # wang2022 eq 26
    ball_rel_a = cross(omega_ball, offset_a)  # omega_R x R_O'A, wang2022 eq 23 (= V_Ab^r, eq 28)
    ball_rel_b = cross(omega_ball, offset_b)  # omega_R x R_O'B, wang2022 eq 24 (= V_Bb^r, eq 30)
    ball_a = _add(convected_a, ball_rel_a)  # wang2022 eq 23
    ball_b = _add(convected_b, ball_rel_b)  # wang2022 eq 24
    nut_rel = _sub(nut, convected_a)  # wang2022 eq 27
    screw_rel = _sub(screw, convected_b)  # wang2022 eq 29
    sliding_a = _sub(ball_rel_a, nut_rel)  # wang2022 eq 5
    sliding_b = _sub(screw_rel, ball_rel_b)  # wang2022 eq 6
    u_a = 0.5 * _length(_add(nut_rel, ball_rel_a))  # wang2022 eq 1
    u_b = 0.5 * _length(_add(screw_rel, ball_rel_b))  # wang2022 eq 2
    slip_a, slip_b = _length(sliding_a), _length(sliding_b)
    if not all(np.all(np.isfinite(x)) for x in (slip_a, slip_b, u_a, u_b, _length(ball_a), _length(ball_b))):
        # every velocity is linear in omega: only a speed whose velocities exceed the float range gets here
        raise ValueError("screw_speed: the velocities overflow double precision (|screw_speed| * pitch_radius "
                         "must stay well below 1e308 m/s); got screw_speed up to "
                         f"{float(np.max(np.abs(omega)))!r} rad/s")
    s_a = _slide_roll(slip_a, u_a, "screw_speed")  # wang2022 eq 4
    s_b = _slide_roll(slip_b, u_b, "screw_speed")  # wang2022 eq 4
    (omega_ball, nut, screw, ball_a, ball_b, convected_a, convected_b, nut_rel, screw_rel, ball_rel_a, ball_rel_b,
     sliding_a, sliding_b) = (np.stack(v, axis=-1) for v in (
        omega_ball, nut, screw, ball_a, ball_b, convected_a, convected_b, nut_rel, screw_rel, ball_rel_a,
        ball_rel_b, sliding_a, sliding_b))
    return ScrewKinematics(psi, beta, omega_m, omega_spin, omega_ball, nut, screw, ball_a, ball_b,
                           convected_a, convected_b, nut_rel, screw_rel, ball_rel_a, ball_rel_b,
                           sliding_a, sliding_b, u_a, u_b, s_a, s_b)


# --------------------------------------------------------------------------
# Wei's model (absolute velocities), as far as wang2022 defines it
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class WeiKinematics:
    """Wei's measures from absolute velocities, with the ball surface taken at its centre velocity.

    wang2022 states Wei's raceway velocities (eqs 16-17) but not his ball
    surface velocities.  Every Wei vector printed in wang2022 Table 2 has the
    ball's b-component equal to the ball-centre (= nut) b-velocity, zero
    n-component and mean t-component of the two contacts equal to the
    ball-centre t-velocity; the remaining antisymmetric t-term (about
    -/+0.065 m/s at A/B in Table 2) is not defined by the paper's equations.
    This reconstruction sets it to zero: ``ball_velocity_nut = ball_velocity_screw
    = ball-centre velocity``.  See docs/screw_kinematics.md for the gap.

    Vectors ``(..., 3)`` in CS1 [m/s]; U [m/s]; S [-].
    """

    nut_velocity: np.ndarray
    screw_velocity: np.ndarray
    ball_velocity_nut: np.ndarray
    ball_velocity_screw: np.ndarray
    sliding_velocity_nut: np.ndarray
    sliding_velocity_screw: np.ndarray
    entrainment_nut: np.ndarray
    entrainment_screw: np.ndarray
    slide_roll_nut: np.ndarray
    slide_roll_screw: np.ndarray


def wei_ball_centre_kinematics(pitch_radius, ball_radius, lead, screw_speed, contact_angle_nut,
                               contact_angle_screw=None, *, lead_angle=None) -> WeiKinematics:
    """Wei's model (absolute velocities in eqs 1-6) with ball surfaces moving at the ball-centre velocity.

    Same inputs as :func:`kinematics`.  Raceway velocities are wang2022 eqs
    16-17 (identical in both models, wang2022 Sec 3.2); the ball-centre
    velocity is the time derivative of eq 10 with omega_m from eq 18.
    """
    present = kinematics(pitch_radius, ball_radius, lead, screw_speed, contact_angle_nut, contact_angle_screw,
                         lead_angle=lead_angle)
    centre = helix.ball_centre_velocity(present.orbital_speed, screw_speed, pitch_radius, lead,
                                        lead_angle=present.lead_angle)  # time derivative of wang2022 eq 10
    u_a, sliding_a, s_a = absolute_velocity_measures(present.nut_velocity, centre, raceway_is_driver=False)
    u_b, sliding_b, s_b = absolute_velocity_measures(present.screw_velocity, centre, raceway_is_driver=True)
    return WeiKinematics(present.nut_velocity, present.screw_velocity, centre, centre, sliding_a, sliding_b,
                         u_a, u_b, s_a, s_b)
