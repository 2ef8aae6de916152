"""Exact geometry of a helical gothic-arch groove flank of a ball screw (screw shaft or nut).

(Temporary home: moves to the geometry core ``ballbench.lowmodel.geometry``.)

Geometry (lin2019 Sec 3.1, eqs 37-42, Fig 13; Table 4 gives the case R_B =
2.778 mm, conformity 0.56, R_P = 16.5 mm, lead 20 mm, beta_0 = 45 deg):

* the nominal ball-centre path is the right-handed helix
  ``H(phi) = (R_P cos phi, R_P sin phi, p phi)`` with ``p = lead / (2 pi)``;
  lead angle ``alpha = atan(p / R_P)`` (lin2019 eq 42);
* the moving frame CS3 (lin2019 eq 41, ``T = rot_z(phi) rot_x(alpha)``):
  ``x3`` radial (from the axis to the ball centre), ``y3`` tangent to the helix,
  ``z3 = x3 x y3``;
* the groove cross-section is a gothic arch: two circular arcs of radius
  ``r_g = conformity * 2 R_B`` whose centres are offset from the ball centre by
  ``r_g - R_B`` so that a ball on the helix touches each arc at the contact
  angle ``beta`` measured from ``-x3`` (screw) or ``+x3`` (nut) (lin2019 eq 37);
* the groove surface is the screw motion of that cross-section
  ``S(theta, phi) = rot_z(phi) [(R_P, 0, 0) + u(theta) e_1 + w(theta) c] + (0, 0, p phi)``
  with ``(u, w)`` the arc and ``c`` the profile-plane "axial" direction.

Two profile planes are offered (``profile_plane``):

``"normal"`` (default, lin2019): the profile is drawn in the plane x3-z3, normal
    to the helix, ``c = (0, -sin alpha, cos alpha)``.  A ball centred on the
    helix then touches the swept surface exactly at the profile contact point
    and the surface normal there passes through the ball centre (the helix
    velocity of the contact point is orthogonal to the contact normal).
``"axial"``: the profile is drawn in the axial plane (``c = (0, 0, 1)``), the
    convention of :func:`lowmodel.contact.hertz.groove_curvatures_helical`.  The surface
    normal at the profile contact point is then tilted out of the axial plane
    (by 8.8 deg for lin2019 Table 4), so a ball tangent there has its centre
    ``R_B`` along the true normal, slightly off the helix.

All lengths in metres, angles in radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.meshes import inputs as checks

__all__ = [
    "HelicalGroove",
    "ContactFrame",
    "helical_groove",
    "contact_frame",
    "surface_residual",
    "profile_coordinates",
    "pair_initial_gap",
    "counter_height",
]

_BODIES = ("screw", "nut")
_FLANKS = ("left", "right")
_PLANES = ("normal", "axial")


# --------------------------------------------------------------------------
# exact geometry
# --------------------------------------------------------------------------
def _rot_z(phi) -> np.ndarray:
    """Rotation matrices about z, shape (..., 3, 3)."""
    phi = np.asarray(phi, dtype=float)
    c, s = np.cos(phi), np.sin(phi)
    zero, one = np.zeros_like(phi), np.ones_like(phi)
    return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1),
                     np.stack([zero, zero, one], -1)], -2)


@dataclass(frozen=True)
class HelicalGroove:
    """One flank of a helical gothic-arch groove (build with :func:`helical_groove`).

    Profile coordinates ``(u, w)``: ``u`` along ``e_1 = x3`` (radially outward from
    the ball centre), ``w`` along ``c`` (``z3`` for the normal profile, the screw
    axis for the axial profile); origin at the ball centre on the helix.
    """

    ball_radius: float
    conformity: float
    pitch_radius: float
    lead: float
    contact_angle: float
    body: str = "screw"
    flank: str = "left"
    profile_plane: str = "normal"

    @property
    def groove_radius(self) -> float:
        """``r_g = conformity * 2 R_B`` [m] (lin2019 Sec 2.3.1: conf = R_G / 2 R_B)."""
        return self.conformity * 2.0 * self.ball_radius

    @property
    def lead_per_radian(self) -> float:
        """``p = lead / (2 pi)`` [m/rad]."""
        return self.lead / (2.0 * math.pi)

    @property
    def lead_angle(self) -> float:
        """Nominal lead angle ``atan(lead / (2 pi R_P))`` [rad] (lin2019 eq 42)."""
        return math.atan2(self.lead, 2.0 * math.pi * self.pitch_radius)

    @property
    def sign_u(self) -> float:
        """-1 on the screw (contact toward the axis), +1 on the nut."""
        return -1.0 if self.body == "screw" else 1.0

    @property
    def sign_w(self) -> float:
        """-1 on the left flank (lin2019 eq 37: q_SL has -R_B sin beta along z3), +1 on the right."""
        return -1.0 if self.flank == "left" else 1.0

    @property
    def plane_axis(self) -> np.ndarray:
        """``c`` at phi = 0: the profile-plane direction other than ``e_1`` (unit)."""
        if self.profile_plane == "axial":
            return np.array([0.0, 0.0, 1.0])
        lam = self.lead_angle
        return np.array([0.0, -math.sin(lam), math.cos(lam)])  # z3 of lin2019 eq 41 at phi = 0

    @property
    def contact_direction(self) -> np.ndarray:
        """Unit vector (u, w) from the ball centre to the contact point in the profile plane."""
        return np.array([self.sign_u * math.cos(self.contact_angle), self.sign_w * math.sin(self.contact_angle)])

    @property
    def arc_centre(self) -> np.ndarray:
        """(u, w) of this flank's arc centre: ``-(r_g - R_B)`` along the contact direction."""
        return -(self.groove_radius - self.ball_radius) * self.contact_direction

    @property
    def contact_theta(self) -> float:
        """Arc angle of the contact point, ``(u, w) = centre + r_g (cos theta, sin theta)``."""
        d = self.contact_direction
        return math.atan2(d[1], d[0])

    @property
    def bottom_theta(self) -> float:
        """Arc angle of the groove bottom (the gothic-arch apex, w = 0, where the flanks meet)."""
        centre = self.arc_centre
        r_g = self.groove_radius
        # the arc point with w = 0 on the side of the contact: u - u_c = sign_u sqrt(r_g^2 - w_c^2)
        du = self.sign_u * math.sqrt(r_g**2 - centre[1] ** 2)
        return math.atan2(-centre[1], du)

    def profile(self, theta, radius=None) -> np.ndarray:
        """Profile points ``(u, w)`` at arc angle ``theta`` [rad], shape (..., 2).

        ``radius`` defaults to ``r_g`` (the groove surface); larger values give the
        concentric arcs inside the groove body.
        """
        theta = np.asarray(theta, dtype=float)
        r = self.groove_radius if radius is None else np.asarray(radius, dtype=float)
        centre = self.arc_centre
        return np.stack([centre[0] + r * np.cos(theta), centre[1] + r * np.sin(theta)], -1)

    def to_world(self, u, w, phi) -> np.ndarray:
        """World points of profile coordinates ``(u, w)`` in the plane at azimuth ``phi``, shape (..., 3)."""
        u, w, phi = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (u, w, phi)))
        local = (self.pitch_radius + u)[..., None] * np.array([1.0, 0.0, 0.0]) + w[..., None] * self.plane_axis
        world = np.einsum("...ij,...j->...i", _rot_z(phi), local)
        world[..., 2] += self.lead_per_radian * phi
        return world

    def surface(self, theta, phi) -> np.ndarray:
        """Groove surface points ``S(theta, phi)`` [m], shape (..., 3)."""
        uw = self.profile(theta)
        return self.to_world(uw[..., 0], uw[..., 1], phi)

    def helix(self, phi) -> np.ndarray:
        """Ball-centre helix ``H(phi)`` [m], shape (..., 3)."""
        return self.to_world(0.0, 0.0, phi)


def helical_groove(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                   contact_angle: float, body: str = "screw", flank: str = "left",
                   profile_plane: str = "normal") -> HelicalGroove:
    """Validated :class:`HelicalGroove`.

    ``ball_radius``, ``pitch_radius`` [m] > 0, ``lead`` [m] >= 0 (0: a bearing
    raceway), ``conformity`` > 0.5, ``contact_angle`` in (0, pi/2) rad.
    """
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    conformity = checks.conformity("conformity", conformity)
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    lead = checks.non_negative("lead", lead, "m")
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    body = checks.choice("body", body, _BODIES)
    flank = checks.choice("flank", flank, _FLANKS)
    profile_plane = checks.choice("profile_plane", profile_plane, _PLANES)
    if body == "screw" and pitch_radius <= 2.0 * conformity * ball_radius:
        raise ValueError(f"pitch_radius must exceed the groove radius 2 conformity ball_radius "
                         f"= {2 * conformity * ball_radius!r} m for a screw groove, got {pitch_radius!r}")
    return HelicalGroove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)


@dataclass(frozen=True)
class ContactFrame:
    """Contact point, normal and principal directions of a groove flank (world frame, [m]).

    ``normal`` points out of the groove material into the ball; ``major`` is the
    principal direction nearest the profile (across the groove; the major axis
    ``a`` of the Hertz ellipse of a ball), ``minor`` the one nearest the helix
    (along the groove, the rolling direction, oriented with increasing azimuth);
    ``major = minor x normal`` so (major, minor, normal) is right-handed.
    Curvatures are positive convex as seen from the ball (the concave groove
    cross-section has ``curvature_major ~ -1/r_g``), as in :mod:`lowmodel.contact.hertz`.
    """

    point: np.ndarray
    normal: np.ndarray
    major: np.ndarray
    minor: np.ndarray
    curvature_major: float
    curvature_minor: float
    ball_centre: np.ndarray
    profile_angle: float  # angle [rad] between ``major`` and the profile tangent

    @property
    def rotation(self) -> np.ndarray:
        """Rows (major, minor, normal): maps world vectors to contact-frame (x, y, z)."""
        return np.stack([self.major, self.minor, self.normal])


def contact_frame(groove: HelicalGroove) -> ContactFrame:
    """Exact contact frame at the profile contact point (phi = 0) from the first and
    second fundamental forms of ``S(theta, phi)``."""
    theta = groove.contact_theta
    r_g = groove.groove_radius
    p = groove.lead_per_radian
    e1 = np.array([1.0, 0.0, 0.0])
    c = groove.plane_axis
    z_hat = np.array([0.0, 0.0, 1.0])
    u, w = groove.profile(theta)
    u_t, w_t = -r_g * math.sin(theta), r_g * math.cos(theta)
    u_tt, w_tt = -r_g * math.cos(theta), -r_g * math.sin(theta)
    point = (groove.pitch_radius + u) * e1 + w * c
    s_t = u_t * e1 + w_t * c
    s_tt = u_tt * e1 + w_tt * c
    s_p = np.cross(z_hat, point) + p * z_hat  # d/dphi rot_z(phi) v = z x v at phi = 0
    s_tp = np.cross(z_hat, s_t)
    s_pp = np.cross(z_hat, np.cross(z_hat, point))
    normal = np.cross(s_t, s_p)
    normal /= np.linalg.norm(normal)
    to_ball = -(groove.contact_direction[0] * e1 + groove.contact_direction[1] * c)
    if normal @ to_ball < 0.0:
        normal = -normal
    first = np.array([[s_t @ s_t, s_t @ s_p], [s_t @ s_p, s_p @ s_p]])
    second = np.array([[s_tt @ normal, s_tp @ normal], [s_tp @ normal, s_pp @ normal]])
    # convex-positive curvature (seen from the ball) = -eigenvalues of I^-1 II
    values, vectors = np.linalg.eig(-np.linalg.solve(first, second))
    values, vectors = values.real, vectors.real
    tangents = [vectors[0, i] * s_t + vectors[1, i] * s_p for i in range(2)]
    tangents = [t / np.linalg.norm(t) for t in tangents]
    profile_dir = s_t / np.linalg.norm(s_t)
    i_major = int(np.argmax([abs(t @ profile_dir) for t in tangents]))
    minor = tangents[1 - i_major]
    minor = minor - (minor @ normal) * normal
    minor /= np.linalg.norm(minor)
    if minor @ s_p < 0.0:
        minor = -minor
    major = np.cross(minor, normal)
    angle = math.acos(min(1.0, abs(major @ profile_dir)))
    return ContactFrame(point=point, normal=normal, major=major, minor=minor,
                        curvature_major=float(values[i_major]), curvature_minor=float(values[1 - i_major]),
                        ball_centre=point + groove.ball_radius * normal, profile_angle=angle)


def counter_height(groove: HelicalGroove, x, y, iterations: int = 40) -> np.ndarray:
    """Height ``z`` [m] of the exact groove surface above the point ``(x, y)`` of the
    contact frame (:func:`contact_frame`; the pair's frame), arrays of any shape.

    Solves ``Q (S(theta, phi) - P) = (x, y, z)`` for ``(theta, phi, z)`` by Newton
    from the contact (theta_c, 0); valid over the groove flank around the contact.
    """
    frame = contact_frame(groove)
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    shape = x.shape
    target = np.stack([x.ravel(), y.ravel()], 1)
    rotation = frame.rotation
    r_g = groove.groove_radius
    theta = np.full(target.shape[0], groove.contact_theta)
    phi = np.zeros(target.shape[0])
    z_hat = np.array([0.0, 0.0, 1.0])
    e1, c = np.array([1.0, 0.0, 0.0]), groove.plane_axis
    for _ in range(iterations):
        local = (groove.surface(theta, phi) - frame.point) @ rotation.T
        residual = local[:, :2] - target
        uw_t = np.stack([-r_g * np.sin(theta), r_g * np.cos(theta)], 1)
        s_t = np.einsum("nij,nj->ni", _rot_z(phi), uw_t[:, :1] * e1 + uw_t[:, 1:] * c)
        world = groove.surface(theta, phi)
        s_p = np.cross(z_hat, world) + groove.lead_per_radian * z_hat
        jac = np.stack([s_t @ rotation[:2].T, s_p @ rotation[:2].T], 2)  # (n, 2 xy, 2 (theta, phi))
        step = np.linalg.solve(jac, residual[..., None])[..., 0]
        theta -= step[:, 0]
        phi -= step[:, 1]
        if np.max(np.abs(step[:, 0]) * r_g + np.abs(step[:, 1]) * groove.pitch_radius) < 1e-16:
            break
    local = (groove.surface(theta, phi) - frame.point) @ rotation.T
    return local[:, 2].reshape(shape)


def pair_initial_gap(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                     contact_angle: float, body: str = "screw", *, flank: str = "left",
                     profile_plane: str = "normal"):
    """Exact initial gap ``g0(x, y)`` [m] between the undeformed ball and groove of
    :func:`ball_in_screw_groove_pair` (same arguments), measured along z at the point
    ``(x, y)`` of the ball surface: ``R_B - sqrt(R_B^2 - x^2 - y^2) - counter_height``.

    Node-to-facet gaps of P1 meshes of these conforming surfaces err by up to
    ``~ kappa_groove h^2 / 8`` (chords of the concave groove lie inside the ball:
    an apparent initial penetration of some nm); this callable gives the FE contact
    the gap of the exact geometry instead (``fem.contact.build_model(initial_gap=...)``).
    For small ``(x, y)`` it tends to Hertz's ``A x^2 + B y^2``.
    """
    groove = helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)
    radius = groove.ball_radius

    def initial_gap(x, y):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        ball = radius - np.sqrt(np.maximum(radius**2 - x * x - y * y, 0.0))
        return ball - counter_height(groove, x, y)

    return initial_gap


def profile_coordinates(groove: HelicalGroove, points, iterations: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """Azimuth ``phi`` [rad] of the profile plane through each world point and the
    point's profile coordinates ``(u, w)`` [m] in it; ``points`` shape (n, 3).

    Solves ``(X - H(phi)) . m(phi) = 0`` (m: the profile-plane normal) by Newton.
    """
    points = np.atleast_2d(np.asarray(points, dtype=float))
    e1 = np.array([1.0, 0.0, 0.0])
    c = groove.plane_axis
    m0 = np.cross(e1, c)
    z_hat = np.array([0.0, 0.0, 1.0])
    phi = np.arctan2(points[:, 1], points[:, 0])
    for _ in range(iterations):
        rot = _rot_z(phi)
        m = rot @ m0
        offset = points - groove.helix(phi)
        g = np.einsum("ij,ij->i", offset, m)
        h_p = np.stack([-groove.pitch_radius * np.sin(phi), groove.pitch_radius * np.cos(phi),
                        np.full_like(phi, groove.lead_per_radian)], -1)
        dg = -np.einsum("ij,ij->i", h_p, m) + np.einsum("ij,ij->i", offset, np.cross(z_hat, m))
        step = g / dg
        phi = phi - step
        if np.max(np.abs(step)) < 1e-15:
            break
    rot = _rot_z(phi)
    offset = points - groove.helix(phi)
    u = np.einsum("ij,ij->i", offset, rot @ e1)
    w = np.einsum("ij,ij->i", offset, rot @ c)
    return phi, np.stack([u, w], -1)


def surface_residual(groove: HelicalGroove, points, radius: float | None = None) -> np.ndarray:
    """Signed in-plane distance [m] of world ``points`` (n, 3) from the helical arc
    surface of radius ``radius`` (default ``r_g``) about this flank's arc centre."""
    _, uw = profile_coordinates(groove, points)
    r = groove.groove_radius if radius is None else radius
    return np.linalg.norm(uw - groove.arc_centre, axis=1) - r
