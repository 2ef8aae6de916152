"""Shared ball-screw geometry: the helix of the ball centre and its Frenet frame.

Frames (wang2022 Sec 2.2, Fig 1):

* ``CS0`` (global, fixed to the base): unit vectors ``i, j, k``; ``k`` along
  the screw axis.  Global components are ordered ``(i, j, k)``.
* ``CS1`` (Frenet frame, origin at the ball centre): ``t`` tangent to the
  helix (pointing to +k for a positive lead), ``n`` principal normal pointing
  from the ball centre to the screw axis, ``b = t x n``.  Frenet components are
  ordered ``(t, n, b)``.

The ball centre lies on the helix ``r_m (cos theta, sin theta) , h theta``
with ``h = L / (2 pi)`` (wang2022 eq 10, written for a screw at rest; the
screw rotation angle ``phi`` shifts the axial coordinate by ``-h phi``).  The
lead angle is ``psi = arctan(h / r_m)``.  A lead ``L = 0`` is a ball bearing:
the helix degenerates to a circle, ``psi = 0`` and the frame stays defined.

The rotation matrix :func:`frenet_frame` holds ``t, n, b`` as its columns
(wang2022 eq 9), so ``v_global = T @ v_frenet`` and ``v_frenet = T.T @ v_global``
(:func:`to_global`, :func:`to_frenet`).

All functions take SI inputs (m, rad, rad/s) as scalars or numpy arrays that
broadcast together; vectors are returned with a trailing axis of length 3.
Only right-hand screws with ``L >= 0`` are handled (a left-hand screw is the
mirror image).
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "lead_angle", "helix_parameter", "curvature", "torsion", "ball_centre", "ball_centre_velocity",
    "frenet_frame", "frame_angular_velocity", "to_global", "to_frenet", "contact_offset", "contact_point",
    "axis_in_frenet", "BODIES",
]

BODIES = ("nut", "screw")


# --------------------------------------------------------------------------
# input checks (ValueError naming the parameter and the allowed range)
# --------------------------------------------------------------------------
def _array(name: str, value) -> np.ndarray:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a real number or array, got {value!r}") from exc
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite (no NaN or inf), got {value!r}")
    return array


def check_positive(name: str, value, unit: str) -> np.ndarray:
    """``value`` as a float array; ValueError unless finite and > 0."""
    array = _array(name, value)
    if np.any(array <= 0.0):
        raise ValueError(f"{name} must be > 0 {unit}, got {value!r}")
    return array


def check_non_negative(name: str, value, unit: str) -> np.ndarray:
    """``value`` as a float array; ValueError unless finite and >= 0."""
    array = _array(name, value)
    if np.any(array < 0.0):
        raise ValueError(f"{name} must be >= 0 {unit}, got {value!r}")
    return array


def check_finite(name: str, value) -> np.ndarray:
    """``value`` as a float array; ValueError unless finite."""
    return _array(name, value)


def check_contact_angle(name: str, value) -> np.ndarray:
    """Contact angle [rad] in the open range (0, pi/2)."""
    array = _array(name, value)
    if np.any(array <= 0.0) or np.any(array >= 0.5 * np.pi):
        raise ValueError(f"{name} must lie in (0, pi/2) rad, i.e. (0, 90) deg, got {value!r}")
    return array


def check_lead_angle(name: str, value) -> np.ndarray:
    """Lead (helix) angle [rad] in [0, pi/2)."""
    array = _array(name, value)
    if np.any(array < 0.0) or np.any(array >= 0.5 * np.pi):
        raise ValueError(f"{name} must lie in [0, pi/2) rad, got {value!r}")
    return array


def _check_body(body: str) -> str:
    if body not in BODIES:
        raise ValueError(f"body must be one of {BODIES}, got {body!r}")
    return body


# --------------------------------------------------------------------------
# helix scalars
# --------------------------------------------------------------------------
def helix_parameter(lead) -> np.ndarray:
    """Axial advance per radian ``h = L / (2 pi)`` [m/rad] (wang2022 eq 10)."""
    return check_non_negative("lead", lead, "m") / (2.0 * np.pi)


def lead_angle(lead, pitch_radius) -> np.ndarray:
    """Lead (helix) angle ``psi = arctan(L / (2 pi r_m))`` [rad] of the ball-centre helix.

    ``lead`` L [m] >= 0, ``pitch_radius`` r_m [m] > 0 (wang2022 Table A1:
    L = 20 mm, r_m = 20.7 mm gives psi = 8.74 deg).
    """
    radius = check_positive("pitch_radius", pitch_radius, "m")
    return np.arctan(helix_parameter(lead) / radius)


def curvature(pitch_radius, lead) -> np.ndarray:
    """Curvature ``kappa = r_m / (r_m^2 + h^2)`` [1/m] of the ball-centre helix."""
    radius = check_positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    return radius / (radius**2 + h**2)


def torsion(pitch_radius, lead) -> np.ndarray:
    """Torsion ``tau = h / (r_m^2 + h^2)`` [1/m] of the ball-centre helix (> 0: right hand)."""
    radius = check_positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    return h / (radius**2 + h**2)


# --------------------------------------------------------------------------
# positions, frame, velocities
# --------------------------------------------------------------------------
def ball_centre(theta, pitch_radius, lead, screw_angle=0.0) -> np.ndarray:
    """Ball-centre position [m] in CS0, shape ``(..., 3)`` (wang2022 eq 10).

    ``theta`` azimuth of the ball [rad], ``screw_angle`` phi [rad]:
    ``R_OO' = (r_m cos theta, r_m sin theta, h (theta - phi))``.
    """
    theta = check_finite("theta", theta)
    radius = check_positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    phi = check_finite("screw_angle", screw_angle)
    theta, radius, h, phi = np.broadcast_arrays(theta, radius, h, phi)
    return np.stack([radius * np.cos(theta), radius * np.sin(theta), h * (theta - phi)], axis=-1)


def ball_centre_velocity(orbital_speed, screw_speed, pitch_radius, lead) -> np.ndarray:
    """Ball-centre velocity [m/s] in Frenet components ``(t, n, b)``, shape ``(..., 3)``.

    Time derivative of wang2022 eq 10 with ``theta' = omega_m`` (orbital speed
    [rad/s]) and ``phi' = omega`` (screw speed [rad/s]), written in CS1:
    ``omega_m r_m (cos psi, 0, -sin psi) + (omega_m - omega) h (sin psi, 0, cos psi)``.
    It does not depend on theta.
    """
    omega_m = check_finite("orbital_speed", orbital_speed)
    omega = check_finite("screw_speed", screw_speed)
    radius = check_positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    psi = np.arctan(h / radius)
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)
    tangential = omega_m * radius
    axial = (omega_m - omega) * h
    return np.stack(np.broadcast_arrays(tangential * cos_psi + axial * sin_psi,
                                        np.zeros_like(tangential + axial),
                                        -tangential * sin_psi + axial * cos_psi), axis=-1)


def frenet_frame(theta, lead_angle) -> np.ndarray:
    """Rotation matrix ``T1`` with columns ``t, n, b`` in CS0, shape ``(..., 3, 3)`` (wang2022 eq 9).

    ``theta`` ball azimuth [rad], ``lead_angle`` psi [rad] in [0, pi/2).
    At ``theta = 0`` this is wang2022 eq 15.
    """
    theta = check_finite("theta", theta)
    psi = check_lead_angle("lead_angle", lead_angle)
    theta, psi = np.broadcast_arrays(theta, psi)
    cos_t, sin_t, cos_p, sin_p = np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    zero = np.zeros_like(theta)
    t = np.stack([-cos_p * sin_t, cos_p * cos_t, sin_p], axis=-1)
    n = np.stack([-cos_t, -sin_t, zero], axis=-1)
    b = np.stack([sin_p * sin_t, -sin_p * cos_t, cos_p], axis=-1)
    return np.stack([t, n, b], axis=-1)


def axis_in_frenet(lead_angle) -> np.ndarray:
    """Screw axis ``k`` in Frenet components: ``(sin psi, 0, cos psi)``, shape ``(..., 3)``."""
    psi = check_lead_angle("lead_angle", lead_angle)
    return np.stack([np.sin(psi), np.zeros_like(psi), np.cos(psi)], axis=-1)


def frame_angular_velocity(orbital_speed, lead_angle) -> np.ndarray:
    """Angular velocity [rad/s] of the Frenet frame in Frenet components, shape ``(..., 3)``.

    The frame turns about the screw axis at the orbital speed omega_m: its
    Darboux vector ``(tau t + kappa b) ds/dt = omega_m k = omega_m (sin psi, 0, cos psi)``.
    """
    omega_m, psi = np.broadcast_arrays(check_finite("orbital_speed", orbital_speed),
                                       check_lead_angle("lead_angle", lead_angle))
    return np.stack([omega_m * np.sin(psi), np.zeros_like(omega_m), omega_m * np.cos(psi)], axis=-1)


def to_global(frame, vector_frenet) -> np.ndarray:
    """Frenet components ``(t, n, b)`` -> CS0 components, ``frame @ v`` (wang2022 eq 7)."""
    return np.einsum("...ij,...j->...i", frame, vector_frenet)


def to_frenet(frame, vector_global) -> np.ndarray:
    """CS0 components -> Frenet components, ``frame.T @ v`` (wang2022 eq 8)."""
    return np.einsum("...ji,...j->...i", frame, vector_global)


def contact_offset(ball_radius, contact_angle, body: str) -> np.ndarray:
    """Vector from the ball centre to the contact point, Frenet components [m], shape ``(..., 3)``.

    wang2022 eqs 11-12: the nut contact A lies away from the axis and towards
    +b, ``(0, -r_b cos alpha, r_b sin alpha)``; the screw contact B is opposite,
    ``(0, r_b cos alpha, -r_b sin alpha)``.  ``ball_radius`` r_b [m] (a radius,
    see docs/screw_kinematics.md), ``contact_angle`` alpha [rad] in (0, pi/2).
    """
    radius = check_positive("ball_radius", ball_radius, "m")
    alpha = check_contact_angle("contact_angle", contact_angle)
    sign = -1.0 if _check_body(body) == "nut" else 1.0
    radius, alpha = np.broadcast_arrays(radius, alpha)
    return np.stack([np.zeros_like(radius), sign * radius * np.cos(alpha), -sign * radius * np.sin(alpha)],
                    axis=-1)


def contact_point(theta, pitch_radius, lead, ball_radius, contact_angle, body: str,
                  screw_angle=0.0) -> np.ndarray:
    """Absolute contact-point position [m] in CS0, shape ``(..., 3)`` (wang2022 eqs 13-14).

    ``R_OA = R_OO' + T1 R_O'A`` for ``body='nut'`` and ``R_OB`` for ``'screw'``.
    """
    centre = ball_centre(theta, pitch_radius, lead, screw_angle)
    psi = lead_angle(lead, pitch_radius)
    frame = frenet_frame(theta, psi)
    offset = contact_offset(ball_radius, contact_angle, body)
    return centre + to_global(frame, offset)
