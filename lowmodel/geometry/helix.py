"""The ball-centre helix of a ball screw and its frames (the geometry core's helix).

One helix, two papers' notations:

* wang2022 eq 10: ``R_OO' = (r_m cos theta, r_m sin theta, h (theta - phi))``,
  ``h = L / (2 pi)``, ``theta`` the ball azimuth, ``phi`` the screw rotation;
* lin2019 eq 35: ``q_B(phi) = (R_P cos phi, R_P sin phi, p phi)`` (the paper
  writes the lead per radian ``p`` as ``r_g`` with a bar), the same helix with
  the screw at rest (lin2019's ``phi`` is wang2022's ``theta``).

**Lead angle**: one name in the code, ``lead_angle`` =
``arctan(L / (2 pi r_m))`` [rad] (:func:`lead_angle`).  The papers' symbols:
``psi`` (wang2022 eq 9), ``alpha`` with a bar (lin2019 eq 42), ``lambda``
(Harris; the earlier hertz module).  A lead ``L = 0`` is a ball bearing: the
helix degenerates to a circle, ``lead_angle = 0`` and every frame stays defined.

Frames (all rotation matrices hold the frame's unit vectors as columns, in
global components, so ``v_global = T @ v_frame``):

* ``CS0`` / lin2019's ``CS`` (global, fixed to the screw): ``i, j, k``, ``k``
  along the screw axis; components ordered ``(i, j, k)`` = ``(x, y, z)``.
* ``CS1`` (wang2022 Sec 2.2, Fig 1; the Frenet frame at the ball centre,
  :func:`frenet_frame`, wang2022 eq 9): ``t`` tangent to the helix (towards
  +k for a positive lead), ``n`` principal normal from the ball centre to the
  screw axis, ``b = t x n``.  Frenet components are ordered ``(t, n, b)``.
* ``CS3`` (lin2019 eq 41, :func:`cs3_frame`): ``T = rot_z(phi) rot_x(lead_angle)``,
  ``x3`` radial (axis -> ball centre), ``y3`` tangent, ``z3 = x3 x y3``; the
  same trihedron as CS1 ordered differently: ``(x3, y3, z3) = (-n, t, b)``.

All functions take SI inputs (m, rad, rad/s) as scalars or numpy arrays that
broadcast together; vectors are returned with a trailing axis of length 3.
Only right-hand screws with ``L >= 0`` are handled (a left-hand screw is the
mirror image).
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError

__all__ = [
    "lead_angle", "lead_from_angle", "helix_parameter", "curvature", "torsion", "ball_centre", "ball_centre_velocity",
    "frenet_frame", "cs3_frame", "rotation_z", "frame_angular_velocity", "to_global", "to_frenet",
    "contact_offset", "contact_point", "axis_in_frenet", "ball_centre_azimuths", "BODIES",
]

BODIES = ("nut", "screw")


def _check_body(body: str) -> str:
    return checks.choice("body", body, BODIES)


# --------------------------------------------------------------------------
# helix scalars
# --------------------------------------------------------------------------
def helix_parameter(lead) -> np.ndarray:
    """Axial advance per radian ``h = L / (2 pi)`` [m/rad] (wang2022 eq 10)."""
    return checks.non_negative("lead", lead, "m") / (2.0 * np.pi)


def lead_angle(lead, pitch_radius) -> np.ndarray:
    """Lead (helix) angle ``arctan(L / (2 pi r_m))`` [rad] of the ball-centre helix.

    wang2022's ``psi``, lin2019 eq 42's ``alpha`` (module docstring).

    ``lead`` L [m] >= 0, ``pitch_radius`` r_m [m] > 0 (wang2022 Table A1:
    L = 20 mm, r_m = 20.7 mm gives psi = 8.74 deg).
    """
    radius = checks.positive("pitch_radius", pitch_radius, "m")
    # wang2022 Sec 2.2, lin2019 eq 42; as atan2(L, 2 pi r_m), the form the mesh builders used:
    # the same angle to 1 ulp, and gmsh meshes (chaotic at the ulp level) stay bit-identical
    return np.arctan2(checks.non_negative("lead", lead, "m"), 2.0 * np.pi * radius)


_lead_angle = lead_angle  # for functions whose argument ``lead_angle`` hides the function


def lead_from_angle(lead_angle, pitch_radius) -> np.ndarray:
    """Lead ``L = 2 pi r_m tan(lead_angle)`` [m], the inverse of :func:`lead_angle`.

    ``lead_angle`` [rad] in [0, pi/2), ``pitch_radius`` r_m [m] > 0.
    """
    angle = checks.lead_angle("lead_angle", lead_angle)
    with np.errstate(over="ignore"):
        lead = 2.0 * np.pi * checks.positive("pitch_radius", pitch_radius, "m") * np.tan(angle)
    return checks.finite_result("lead_angle, pitch_radius", lead, "m")


def curvature(pitch_radius, lead) -> np.ndarray:
    """Curvature ``kappa = r_m / (r_m^2 + h^2)`` [1/m] of the ball-centre helix."""
    return _over_squared_length(checks.positive("pitch_radius", pitch_radius, "m"), pitch_radius, lead)


def torsion(pitch_radius, lead) -> np.ndarray:
    """Torsion ``tau = h / (r_m^2 + h^2)`` [1/m] of the ball-centre helix (> 0: right hand)."""
    return _over_squared_length(helix_parameter(lead), pitch_radius, lead)


def _over_squared_length(numerator, pitch_radius, lead) -> np.ndarray:
    """``numerator / (r_m^2 + h^2)`` [1/m] as ``(numerator / s) / s`` with ``s = hypot(r_m, h)``: no overflow of
    the squares at huge lengths; ValueError if the result itself leaves the float range (r_m, h ~ 1e-308 m)."""
    radius = checks.positive("pitch_radius", pitch_radius, "m")
    size = np.hypot(radius, helix_parameter(lead))
    with np.errstate(over="ignore"):
        return checks.finite_result("pitch_radius, lead", np.float64(numerator) / size / size, "1/m")


# --------------------------------------------------------------------------
# positions, frame, velocities
# --------------------------------------------------------------------------
def ball_centre(theta, pitch_radius, lead, screw_angle=0.0) -> np.ndarray:
    """Ball-centre position [m] in CS0, shape ``(..., 3)`` (wang2022 eq 10).

    ``theta`` azimuth of the ball [rad], ``screw_angle`` phi [rad]:
    ``R_OO' = (r_m cos theta, r_m sin theta, h (theta - phi))``.
    """
    theta = checks.finite("theta", theta)
    radius = checks.positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    phi = checks.finite("screw_angle", screw_angle)
    theta, radius, h, phi = np.broadcast_arrays(theta, radius, h, phi)
    with np.errstate(over="ignore", invalid="ignore"):
        centre = np.stack([radius * np.cos(theta), radius * np.sin(theta), h * (theta - phi)], axis=-1)
    return checks.finite_result("theta, pitch_radius, lead, screw_angle", centre, "m")


def ball_centre_velocity(orbital_speed, screw_speed, pitch_radius, lead, lead_angle=None) -> np.ndarray:
    """Ball-centre velocity [m/s] in Frenet components ``(t, n, b)``, shape ``(..., 3)``.

    Time derivative of wang2022 eq 10 with ``theta' = omega_m`` (orbital speed
    [rad/s]) and ``phi' = omega`` (screw speed [rad/s]), written in CS1:
    ``omega_m r_m (cos psi, 0, -sin psi) + (omega_m - omega) h (sin psi, 0, cos psi)``.
    It does not depend on theta.  ``lead_angle`` psi [rad] defaults to
    ``arctan(h / r_m)``; a value overrides it (wang2022 Table A1 prints 8.74 deg).
    """
    omega_m = checks.finite("orbital_speed", orbital_speed)
    omega = checks.finite("screw_speed", screw_speed)
    radius = checks.positive("pitch_radius", pitch_radius, "m")
    h = helix_parameter(lead)
    psi = _lead_angle(lead, radius) if lead_angle is None else checks.lead_angle("lead_angle", lead_angle)
    cos_psi, sin_psi = np.cos(psi), np.sin(psi)
    with np.errstate(over="ignore", invalid="ignore"):
        tangential = omega_m * radius
        axial = (omega_m - omega) * h
        velocity = np.stack(np.broadcast_arrays(tangential * cos_psi + axial * sin_psi,
                                                np.zeros_like(tangential + axial),
                                                -tangential * sin_psi + axial * cos_psi), axis=-1)
    return checks.finite_result("orbital_speed, screw_speed, pitch_radius, lead", velocity, "m/s")


def frenet_frame(theta, lead_angle) -> np.ndarray:
    """Rotation matrix ``T1`` with columns ``t, n, b`` in CS0, shape ``(..., 3, 3)`` (wang2022 eq 9).

    ``theta`` ball azimuth [rad], ``lead_angle`` psi [rad] in [0, pi/2).
    At ``theta = 0`` this is wang2022 eq 15.
    """
    theta = checks.finite("theta", theta)
    psi = checks.lead_angle("lead_angle", lead_angle)
    theta, psi = np.broadcast_arrays(theta, psi)
    cos_t, sin_t, cos_p, sin_p = np.cos(theta), np.sin(theta), np.cos(psi), np.sin(psi)
    zero = np.zeros_like(theta)
    t = np.stack([-cos_p * sin_t, cos_p * cos_t, sin_p], axis=-1)
    n = np.stack([-cos_t, -sin_t, zero], axis=-1)
    b = np.stack([sin_p * sin_t, -sin_p * cos_t, cos_p], axis=-1)
    return np.stack([t, n, b], axis=-1)


def rotation_z(phi) -> np.ndarray:
    """Rotation matrices ``rot_z(phi)`` about the screw axis, shape ``(..., 3, 3)`` (lin2019 eq 41); ``phi`` [rad]."""
    phi = np.asarray(checks.finite("phi", phi, "rad"), dtype=float)
    c, s = np.cos(phi), np.sin(phi)
    zero, one = np.zeros_like(phi), np.ones_like(phi)
    return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1),
                     np.stack([zero, zero, one], -1)], -2)


def cs3_frame(phi, lead_angle) -> np.ndarray:
    """Rotation matrix ``T_CS-CS3 = rot_z(phi) rot_x(lead_angle)`` with columns ``x3, y3, z3``,
    shape ``(..., 3, 3)`` (lin2019 eq 41).

    ``phi`` azimuth of the ball [rad] (lin2019 eq 35), ``lead_angle`` [rad] in
    [0, pi/2).  ``x3`` is radial (from the axis to the ball centre), ``y3``
    the helix tangent, ``z3 = x3 x y3``: the Frenet frame reordered,
    ``(x3, y3, z3) = (-n, t, b)`` (module docstring).
    """
    frame = frenet_frame(phi, lead_angle)
    return np.stack([-frame[..., :, 1], frame[..., :, 0], frame[..., :, 2]], axis=-1)


def axis_in_frenet(lead_angle) -> np.ndarray:
    """Screw axis ``k`` in Frenet components: ``(sin psi, 0, cos psi)``, shape ``(..., 3)``."""
    psi = checks.lead_angle("lead_angle", lead_angle)
    return np.stack([np.sin(psi), np.zeros_like(psi), np.cos(psi)], axis=-1)


def frame_angular_velocity(orbital_speed, lead_angle) -> np.ndarray:
    """Angular velocity [rad/s] of the Frenet frame in Frenet components, shape ``(..., 3)``.

    The frame turns about the screw axis at the orbital speed omega_m: its
    Darboux vector ``(tau t + kappa b) ds/dt = omega_m k = omega_m (sin psi, 0, cos psi)``.
    """
    omega_m = checks.finite("orbital_speed", orbital_speed)
    return np.asarray(omega_m)[..., None] * axis_in_frenet(lead_angle)


def to_global(frame, vector_frenet) -> np.ndarray:
    """Frenet components ``(t, n, b)`` -> CS0 components, ``frame @ v`` (wang2022 eq 7)."""
    return _rotate("...ij,...j->...i", frame, "vector_frenet", vector_frenet)


def to_frenet(frame, vector_global) -> np.ndarray:
    """CS0 components -> Frenet components, ``frame.T @ v`` (wang2022 eq 8)."""
    return _rotate("...ji,...j->...i", frame, "vector_global", vector_global)


def _rotate(subscripts: str, frame, name: str, vector) -> np.ndarray:
    """``frame`` (..., 3, 3) applied to ``vector`` (..., 3) by ``subscripts``; ValueError naming the bad one."""
    matrix = checks.real("frame", frame)
    if matrix.ndim < 2 or matrix.shape[-2:] != (3, 3):
        raise ValueError(f"frame must have shape (..., 3, 3) (rotation matrices), got shape {matrix.shape}")
    vector = checks.trailing_axis(name, vector, 3, "(t, n, b) or (x, y, z)")
    try:
        return np.einsum(subscripts, matrix, vector)
    except ValueError:
        raise ValueError(f"frame of shape {matrix.shape} and {name} of shape {vector.shape} do not broadcast") from None


def contact_offset(ball_radius, contact_angle, body: str) -> np.ndarray:
    """Vector from the ball centre to the contact point, Frenet components [m], shape ``(..., 3)``.

    wang2022 eqs 11-12: the nut contact A lies away from the axis and towards
    +b, ``(0, -r_b cos alpha, r_b sin alpha)``; the screw contact B is opposite,
    ``(0, r_b cos alpha, -r_b sin alpha)``.  ``ball_radius`` r_b [m] (a radius,
    see docs/screw_kinematics.md), ``contact_angle`` alpha [rad] in (0, pi/2).
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    alpha = checks.contact_angle("contact_angle", contact_angle)
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


def ball_centre_azimuths(pitch_radius: float, lead: float, spacing: float) -> float:
    """Azimuth difference ``dphi`` [rad] of two ball centres on the helix a chord
    ``spacing`` [m] apart: ``(2 R_P sin(dphi/2))^2 + (p dphi)^2 = spacing^2`` (Newton).

    ``pitch_radius`` R_P [m] > 0, ``lead`` [m] >= 0 (``p = lead / 2 pi``),
    ``spacing`` [m] in (0, 2 R_P] (at lead 0 the chord of a circle cannot exceed
    its diameter; the Newton start assumes ``spacing`` well below ``R_P``).
    """
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    p = float(helix_parameter(lead))
    spacing = checks.bounded("spacing", spacing, 0.0, 2.0 * pitch_radius, "m", upper_closed=True,
                             note="the chord between two ball centres, at most the pitch diameter")
    # lengths over a power of two (exact: the same bits wherever the squares below stay in the float range)
    unit = checks.power_of_two_scale(max(pitch_radius, p))
    pitch_radius, p, spacing = pitch_radius / unit, p / unit, spacing / unit
    dphi = spacing / math.hypot(pitch_radius, p)  # arc-length guess
    for iteration in range(50):  # noqa: B007 - the count is reported after the loop
        chord2 = (2 * pitch_radius * math.sin(dphi / 2)) ** 2 + (p * dphi) ** 2
        if chord2 == spacing**2:  # exact root (also where the step would be 0 / 0)
            return dphi
        slope = 2 * pitch_radius**2 * math.sin(dphi) + 2 * p**2 * dphi
        step = (chord2 - spacing**2) / slope
        dphi -= step
        if abs(step) < 1e-15 * dphi:
            return dphi
    raise ConvergenceError("ball_centre_azimuths: Newton did not converge", residual=abs(step),
                           iterations=iteration + 1, tolerance=1e-15 * dphi, reason="iteration limit")
