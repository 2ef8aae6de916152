"""Helical gothic-arch groove segments of a ball screw (screw shaft and nut) and the
ball-in-groove contact pair.

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
from pathlib import Path

import numpy as np

from ballbench.meshes.gmsh_tools import cached_msh, contact_refinement, physical, session, size_threshold, write_msh

__all__ = [
    "HelicalGroove",
    "ContactFrame",
    "helical_groove",
    "contact_frame",
    "surface_residual",
    "profile_coordinates",
    "pair_hertz_geometry",
    "pair_initial_gap",
    "counter_height",
    "screw_groove_segment",
    "ball_in_screw_groove_pair",
]

_BODIES = ("screw", "nut")
_FLANKS = ("left", "right")
_PLANES = ("normal", "axial")


# --------------------------------------------------------------------------
# input checks
# --------------------------------------------------------------------------
def _finite(name: str, value, allowed: str) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number in {allowed}, got {value!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a real number in {allowed}, got {value!r}")
    return value


def _positive(name: str, value, unit: str) -> float:
    value = _finite(name, value, f"(0, inf) {unit}")
    if value <= 0.0:
        raise ValueError(f"{name} must lie in (0, inf) {unit}, got {value!r}")
    return value


def _conformity(value) -> float:
    value = _finite("conformity", value, "(0.5, inf)")
    if value <= 0.5:
        raise ValueError(f"conformity (groove radius / ball diameter) must lie in (0.5, inf), got {value!r}")
    return value


def _contact_angle(value, name: str = "contact_angle") -> float:
    value = _finite(name, value, "(0, pi/2) rad")
    if not 0.0 < value < math.pi / 2:
        raise ValueError(f"{name} must lie in (0, pi/2) rad (0-90 deg exclusive), got {value!r}")
    return value


def _choice(name: str, value, allowed: tuple[str, ...]) -> str:
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


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
    ball_radius = _positive("ball_radius", ball_radius, "m")
    conformity = _conformity(conformity)
    pitch_radius = _positive("pitch_radius", pitch_radius, "m")
    lead = _finite("lead", lead, "[0, inf) m")
    if lead < 0.0:
        raise ValueError(f"lead must lie in [0, inf) m (right-handed screw), got {lead!r}")
    contact_angle = _contact_angle(contact_angle)
    body = _choice("body", body, _BODIES)
    flank = _choice("flank", flank, _FLANKS)
    profile_plane = _choice("profile_plane", profile_plane, _PLANES)
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


def pair_hertz_geometry(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                        contact_angle: float, body: str = "screw", *, flank: str = "left",
                        profile_plane: str = "normal", youngs_modulus: float = 2.1e11,
                        poisson_ratio: float = 0.28):
    """Hertz geometry (:class:`lowmodel.contact.hertz.HertzGeometry`) of the contact meshed by
    :func:`ball_in_screw_groove_pair` with the same arguments: the ball's curvature
    ``1/R_B`` and the groove's exact principal curvatures at the contact; ``A``
    belongs to the contact-frame x axis.  For ``profile_plane="axial"`` it equals
    :func:`lowmodel.contact.hertz.ball_in_screw_groove` (tested)."""
    from ballbench.lowmodel.contact import hertz

    frame = contact_frame(helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank,
                                         profile_plane))
    curvature = 1.0 / float(ball_radius)
    return hertz.from_curvatures((curvature, curvature), (frame.curvature_major, frame.curvature_minor),
                                 youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)


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


# --------------------------------------------------------------------------
# gmsh construction
# --------------------------------------------------------------------------
MESH_FORMAT_VERSION = "helical-1"


def _section_loop(occ, groove: HelicalGroove, phi: float, theta_range: tuple[float, float],
                  depth: float) -> int:
    """Curve loop of the annular-sector block cross-section at azimuth ``phi``:
    arc angles ``theta_range`` around the flank's arc centre, radii ``r_g`` .. ``r_g + depth``."""
    r_g = groove.groove_radius
    corners = [(theta_range[0], r_g), (theta_range[1], r_g), (theta_range[1], r_g + depth),
               (theta_range[0], r_g + depth)]
    tags = []
    for theta, radius in corners:
        u, w = groove.profile(theta, radius)
        tags.append(occ.addPoint(*groove.to_world(u, w, phi)))
    centre = occ.addPoint(*groove.to_world(groove.arc_centre[0], groove.arc_centre[1], phi))
    curves = [occ.addCircleArc(tags[0], centre, tags[1]), occ.addLine(tags[1], tags[2]),
              occ.addCircleArc(tags[2], centre, tags[3]), occ.addLine(tags[3], tags[0])]
    loop = occ.addCurveLoop(curves)
    occ.remove([(0, centre)])
    return loop


def _sweep_along_helix(occ, groove: HelicalGroove, face: int, phi_range: tuple[float, float],
                       path_points: int = 17) -> list[tuple[int, int]]:
    """Sweep ``face`` (lying in the profile plane at ``phi_range[0]``) along the helix.

    The helix is an interpolating spline through ``path_points`` exact points;
    the Frenet trihedron of a helix is carried by the screw motion, so the swept
    surface is the screw motion of the section (OCC approximation ~1e-8 m,
    removed afterwards by :func:`_snap_to_groove`).
    """
    phis = np.linspace(phi_range[0], phi_range[1], path_points)
    points = [occ.addPoint(*xyz) for xyz in groove.helix(phis)]
    spline = occ.addSpline(points)
    wire = occ.addWire([spline])
    volumes = occ.addPipe([(2, face)], wire, "Frenet")
    occ.remove([(1, wire)], recursive=True)
    return volumes


def _face_point(gmsh, tag: int) -> np.ndarray:
    """A point on surface ``tag`` (value at the middle of its parametric box)."""
    lo, hi = gmsh.model.getParametrizationBounds(2, tag)
    return np.asarray(gmsh.model.getValue(2, tag, [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]))


def _snap_to_groove(gmsh, groove: HelicalGroove, surface_tags: list[int], to_world: np.ndarray,
                    origin: np.ndarray) -> float:
    """Move the mesh nodes of the groove surfaces onto the exact helical surface.

    Nodes are given in the contact frame; ``to_world`` (3x3) and ``origin`` map them
    back (``X = origin + to_world @ x``).  Each node keeps its azimuth phi and its
    angle about the arc centre; only its distance from the centre is set to r_g.
    Returns the largest correction [m].
    """
    worst = 0.0
    for tag in surface_tags:
        node_tags, coords, _ = gmsh.model.mesh.getNodes(2, tag, includeBoundary=True)
        local = coords.reshape(-1, 3)
        world = origin + local @ to_world.T
        phi, uw = profile_coordinates(groove, world)
        rel = uw - groove.arc_centre
        dist = np.linalg.norm(rel, axis=1)
        snapped = groove.arc_centre + rel * (groove.groove_radius / dist)[:, None]
        new_world = groove.to_world(snapped[:, 0], snapped[:, 1], phi)
        new_local = (new_world - origin) @ to_world
        worst = max(worst, float(np.max(np.linalg.norm(new_local - local, axis=1))))
        for node, xyz in zip(node_tags, new_local):
            gmsh.model.mesh.setNode(int(node), xyz.tolist(), [])
    return worst


def _check_refinement(ball_radius: float, h_contact, growth, h_max, fine_radius) -> tuple[float, float, float, float]:
    h_contact = _positive("h_contact", h_contact, "m")
    growth = _finite("growth", growth, "[1, 3]")
    if not 1.0 <= growth <= 3.0:
        raise ValueError(f"growth (size ratio of neighbouring elements) must lie in [1, 3], got {growth!r}")
    h_max = ball_radius / 3.0 if h_max is None else _positive("h_max", h_max, "m")
    if h_contact > ball_radius / 4.0:
        raise ValueError(f"h_contact must lie in (0, ball_radius/4] = (0, {ball_radius / 4!r}] m, got {h_contact!r}")
    if h_max < h_contact:
        raise ValueError(f"h_max must be >= h_contact = {h_contact!r} m, got {h_max!r}")
    fine_radius = 0.0 if fine_radius is None else _finite("fine_radius", fine_radius, "[0, inf) m")
    if fine_radius < 0.0:
        raise ValueError(f"fine_radius must lie in [0, inf) m, got {fine_radius!r}")
    return h_contact, growth, h_max, fine_radius


def _patch_refinement(gmsh, h_contact: float, growth: float, h_max: float, half_lengths) -> int:
    """Background size field ``h = min(h_max, h_contact + (growth - 1) d)`` with ``d`` the
    distance [m] from the box ``|x| <= l_x, |y| <= l_y, |z| <= l_z`` about the contact
    (``half_lengths = (l_x, l_y[, l_z])``, ``l_z`` default 0: the rectangle of the contact
    plane).  The same law as :func:`meshes.gmsh_tools.contact_refinement`, whose fine
    zone is a ball; a box fits an elongated Hertz ellipse and its subsurface field."""
    lengths = [float(v) for v in half_lengths] + [0.0] * (3 - len(half_lengths))
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    beyond = [f"((Abs({axis}) - ({length!r}) + Abs(Abs({axis}) - ({length!r}))) / 2)"  # max(0, |x| - l_x)
              for axis, length in zip("xyz", lengths)]
    field.setString(distance, "F", f"Sqrt({beyond[0]}^2 + {beyond[1]}^2 + {beyond[2]}^2)")
    return size_threshold(gmsh, distance, h_contact, growth, h_max)


def ball_in_screw_groove_pair(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                              contact_angle: float, body: str = "screw", h_contact: float = 2e-5,
                              growth: float = 1.3, *, flank: str = "left", profile_plane: str = "normal",
                              h_max: float | None = None, fine_radius: float | None = None,
                              fine_half_length: float = 0.0, fine_patch: tuple[float, float] | None = None,
                              block_half_width: float | None = None, block_half_length: float | None = None,
                              block_depth: float | None = None, cap_height: float | None = None,
                              element_order: int = 1, cache: bool = True) -> Path:
    """Contact pair of a ball in a helical screw or nut groove, as a cached gmsh 4.1 ``.msh`` [m].

    Frame (docs/developing.md, contact-pair meshes): the undeformed contact point
    at the origin, ``+z`` the groove normal pointing into the ball (ball centre at
    ``(0, 0, R_B)``), ``x`` the principal direction of the groove nearest its
    cross-section profile (across the groove: the major axis ``a`` of the Hertz
    ellipse), ``y`` the principal direction nearest the helix (along the groove,
    towards increasing azimuth).  x and y are the exact principal directions at
    the contact point (:func:`contact_frame`).

    Bodies: the ball truncated to the cap ``z <= cap_height`` (default ``R_B``: a
    hemisphere, load on its flat face), the groove truncated to a helical block:
    the annular sector ``r_g <= r <= r_g + block_depth`` about the flank's arc
    centre spanning the arc length ``+-block_half_width`` around the contact,
    swept along the helix for ``+-block_half_length`` of the contact point's path.
    Defaults ``0.6 R_B`` each, the width limited to 90 % of the way to the groove
    bottom so the other flank is never meshed.

    Physical groups: volumes ``ball``, ``counter``; surfaces ``ball_contact``
    (spherical cap), ``ball_load`` (flat face of the cap), ``counter_contact``
    (groove face; its nodes lie exactly on the helical surface), ``counter_support``
    (the back face of the block).  Mesh size: :func:`meshes.gmsh_tools.contact_refinement`,
    ``h(r) = min(h_max, h_contact + (growth - 1) max(0, r - fine_radius))``, ``r`` the
    distance from the contact point, or from the segment ``|x| <= fine_half_length`` of
    the x axis (as :func:`meshes.contact_pairs.ball_in_groove_pair`: ``fine_radius ~ b``,
    ``fine_half_length ~ a``); or, with ``fine_patch = (l_x, l_y[, l_z])`` [m], ``r`` the
    distance from the box ``|x| <= l_x, |y| <= l_y, |z| <= l_z`` (``l_z`` default 0:
    the rectangle of the contact plane), e.g. ``(1.15 a, 1.4 b, 0.6 a)``.

    ``h_contact`` [m] size at the contact, ``growth`` the size ratio of
    neighbouring elements away from the fine zone of radius ``fine_radius`` [m]
    (default 0), ``h_max`` [m] (default ``R_B/3``), ``element_order`` 1 or 2.
    """
    groove = helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)
    radius = groove.ball_radius
    h_contact, growth, h_max, fine_radius = _check_refinement(radius, h_contact, growth, h_max, fine_radius)
    r_g = groove.groove_radius
    to_bottom = abs(groove.bottom_theta - groove.contact_theta)
    half_width = 0.6 * radius if block_half_width is None else _positive("block_half_width", block_half_width, "m")
    if half_width / r_g > 0.9 * to_bottom:
        half_width = 0.9 * to_bottom * r_g if block_half_width is None else half_width
        if block_half_width is not None:
            raise ValueError(f"block_half_width must lie in (0, {0.9 * to_bottom * r_g!r}] m (90 % of the arc "
                             f"to the groove bottom), got {block_half_width!r}")
    half_length = 0.6 * radius if block_half_length is None else _positive("block_half_length", block_half_length, "m")
    depth = 0.6 * radius if block_depth is None else _positive("block_depth", block_depth, "m")
    cap = radius if cap_height is None else _positive("cap_height", cap_height, "m")
    if cap >= 2.0 * radius:
        raise ValueError(f"cap_height must lie in (0, 2 ball_radius) = (0, {2 * radius!r}) m (the cap needs its "
                         f"flat loaded face), got {cap!r}")
    if element_order not in (1, 2):
        raise ValueError(f"element_order must be 1 or 2, got {element_order!r}")
    fine_half_length = _finite("fine_half_length", fine_half_length, "[0, inf) m")
    if fine_half_length < 0.0:
        raise ValueError(f"fine_half_length must lie in [0, inf) m, got {fine_half_length!r}")
    if fine_patch is not None and fine_half_length > 0.0:
        raise ValueError("fine_patch and fine_half_length exclude each other: give one fine zone")
    if fine_patch is not None:
        try:
            fine_patch = tuple(_positive("fine_patch", v, "m") for v in fine_patch)
        except TypeError:
            raise ValueError(f"fine_patch must be half-lengths (l_x, l_y[, l_z]) [m], got {fine_patch!r}") from None
        if len(fine_patch) not in (2, 3):
            raise ValueError(f"fine_patch must be half-lengths (l_x, l_y[, l_z]) [m], got {fine_patch!r}")
    if groove.body == "screw" and depth >= groove.pitch_radius - radius:
        raise ValueError(f"block_depth must be smaller than pitch_radius - ball_radius, got {depth!r}")

    params = dict(builder="ball_in_screw_groove_pair", groove=[radius, groove.conformity, groove.pitch_radius,
                  groove.lead, groove.contact_angle, groove.body, groove.flank, groove.profile_plane],
                  h_contact=h_contact, growth=growth, h_max=h_max, fine_radius=fine_radius, half_width=half_width,
                  half_length=half_length, depth=depth, cap=cap, order=element_order, fine_patch=fine_patch,
                  fine_half_length=fine_half_length)
    path, build = cached_msh("screw-pair", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path

    frame = contact_frame(groove)
    with session("screw_pair") as gmsh:
        occ = gmsh.model.occ
        theta_c = groove.contact_theta
        gamma = half_width / r_g
        speed = float(np.linalg.norm(np.cross([0.0, 0.0, 1.0], frame.point) + [0.0, 0.0, groove.lead_per_radian]))
        dphi = half_length / speed  # |dS/dphi| of the contact point
        loop = _section_loop(occ, groove, -dphi, (theta_c - gamma, theta_c + gamma), depth)
        face = occ.addPlaneSurface([loop])
        counter = _sweep_along_helix(occ, groove, face, (-dphi, dphi))
        occ.synchronize()
        (_, counter_tag), = [vt for vt in counter if vt[0] == 3]
        groove_faces, support_faces = [], []
        for _, tag in gmsh.model.getBoundary([(3, counter_tag)], oriented=False):
            xyz = _face_point(gmsh, tag)[None, :]
            if abs(surface_residual(groove, xyz)[0]) < 0.01 * depth:
                groove_faces.append(tag)
            elif abs(surface_residual(groove, xyz, r_g + depth)[0]) < 0.01 * depth:
                support_faces.append(tag)
        if len(groove_faces) != 1 or len(support_faces) != 1:
            raise RuntimeError(f"helical block faces not identified: groove {groove_faces}, support {support_faces}")
        # world -> contact frame: x = Q (X - P)
        rotation = frame.rotation
        shift = -rotation @ frame.point
        affine = np.hstack([rotation, shift[:, None]]).ravel().tolist() + [0.0, 0.0, 0.0, 1.0]
        occ.affineTransform([(3, counter_tag)], affine)
        sphere = occ.addSphere(0.0, 0.0, radius, radius)
        box = occ.addBox(-2 * radius, -2 * radius, -radius, 4 * radius, 4 * radius, radius + cap)
        ball, _ = occ.intersect([(3, sphere)], [(3, box)])
        occ.synchronize()
        (_, ball_tag), = ball
        ball_faces = [tag for _, tag in gmsh.model.getBoundary(ball, oriented=False)]
        ball_contact = [tag for tag in ball_faces if gmsh.model.getType(2, tag) == "Sphere"]
        ball_load = [tag for tag in ball_faces if gmsh.model.getType(2, tag) == "Plane"]
        physical(gmsh, 3, [ball_tag], "ball")
        physical(gmsh, 3, [counter_tag], "counter")
        physical(gmsh, 2, ball_contact, "ball_contact")
        physical(gmsh, 2, ball_load, "ball_load")
        physical(gmsh, 2, groove_faces, "counter_contact")
        physical(gmsh, 2, support_faces, "counter_support")
        if fine_patch is None:
            threshold = contact_refinement(gmsh, h_contact, growth, h_max, fine_radius=fine_radius)
            if fine_half_length > 0.0:  # distance from the segment |x| <= fine_half_length instead of the point
                distance = gmsh.model.mesh.field.add("MathEval")
                gmsh.model.mesh.field.setString(
                    distance, "F", f"Sqrt(((Abs(x) - ({fine_half_length!r}) + Abs(Abs(x) - ({fine_half_length!r})))"
                                   f" / 2)^2 + y^2 + z^2)")
                gmsh.model.mesh.field.setNumber(threshold, "InField", distance)
                gmsh.model.mesh.field.setAsBackgroundMesh(threshold)
        else:
            _patch_refinement(gmsh, h_contact, growth, h_max, fine_patch)
        gmsh.model.mesh.generate(3)
        if element_order == 2:
            gmsh.model.mesh.setOrder(2)
        _snap_to_groove(gmsh, groove, groove_faces, rotation.T, frame.point)
        write_msh(gmsh, path)
    return path


def _flank_intersections(left: HelicalGroove, right: HelicalGroove) -> tuple[np.ndarray, np.ndarray]:
    """(u, w) of the two intersections of the flank circles: (groove bottom, top of the lens)."""
    c_l, c_r = left.arc_centre, right.arc_centre
    r_g = left.groove_radius
    mid = (c_l + c_r) / 2
    half = float(np.linalg.norm(c_r - c_l)) / 2
    along = (c_r - c_l) / (2 * half)
    perp = np.array([along[1], -along[0]])
    points = [mid + s * math.sqrt(r_g**2 - half**2) * perp for s in (-1.0, 1.0)]
    points.sort(key=lambda uw: -left.sign_u * uw[0])  # the bottom lies deepest in the body
    return points[0], points[1]


def _lens_loop(occ, grooves: tuple[HelicalGroove, HelicalGroove], phi: float) -> int:
    """Curve loop of the gothic-arch lens (inside both flank circles) in the profile plane at ``phi``."""
    left, right = grooves
    apexes = _flank_intersections(left, right)
    tags = [occ.addPoint(*left.to_world(a[0], a[1], phi)) for a in apexes]
    centres = [occ.addPoint(*left.to_world(c[0], c[1], phi)) for c in (left.arc_centre, right.arc_centre)]
    # each flank circle bounds the lens on the side away from its centre; both arcs are
    # shorter than pi (the centres lie inside the lens), so OCC's arc is the right one
    arcs = [occ.addCircleArc(tags[0], centres[1], tags[1]), occ.addCircleArc(tags[1], centres[0], tags[0])]
    loop = occ.addCurveLoop(arcs)
    occ.remove([(0, c) for c in centres])
    return loop


def _snap_to_bottom(gmsh, grooves: tuple[HelicalGroove, HelicalGroove], left_faces: list[int],
                    right_faces: list[int]) -> None:
    """Put the nodes shared by both flanks (the groove-bottom edge) on the exact bottom helix."""
    def node_set(faces):
        tags = [gmsh.model.mesh.getNodes(2, f, includeBoundary=True)[0] for f in faces]
        return set(np.concatenate(tags).tolist()) if tags else set()

    shared = sorted(node_set(left_faces) & node_set(right_faces))
    if not shared:
        return
    coords = np.array([gmsh.model.mesh.getNode(int(tag))[0] for tag in shared])
    phi, _ = profile_coordinates(grooves[0], coords)
    bottom, _ = _flank_intersections(*grooves)
    exact = grooves[0].to_world(np.full_like(phi, bottom[0]), np.full_like(phi, bottom[1]), phi)
    for tag, xyz in zip(shared, exact):
        gmsh.model.mesh.setNode(int(tag), xyz.tolist(), [])


def _segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, body, deviations,
                     profile_plane) -> tuple[HelicalGroove, HelicalGroove]:
    """The (left, right) flanks of a groove with contact angle deviations (left, right) [rad]."""
    try:
        deviations = [float(d) for d in deviations]
    except (TypeError, ValueError):
        raise ValueError(f"deviations must be two angles (left, right) [rad], got {deviations!r}") from None
    if len(deviations) != 2 or not all(math.isfinite(d) and abs(d) <= math.radians(15) for d in deviations):
        raise ValueError(f"deviations must be two angles (left, right) in [-15, 15] deg [rad], got {deviations!r}")
    contact_angle = _contact_angle(contact_angle)
    return tuple(helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle + deviation, body,
                                flank, profile_plane) for flank, deviation in zip(("left", "right"), deviations))


def _segment_dimensions(grooves, land_radius, back_radius, half_angle, axial_half_width,
                        prefix: str = "") -> tuple[float, float, float, float]:
    """Validated (land radius, back radius, half angle, axial half width) of a groove segment."""
    left = grooves[0]
    radius, r_p, p = left.ball_radius, left.pitch_radius, left.lead_per_radian
    sign = left.sign_u
    land = r_p + sign * 0.25 * radius if land_radius is None else _positive(f"{prefix}land_radius", land_radius, "m")
    back = r_p + sign * 2.0 * radius if back_radius is None else _positive(f"{prefix}back_radius", back_radius, "m")
    contact_u = sign * radius * min(math.cos(g.contact_angle) for g in grooves)
    if not sign * (land - r_p) < sign * contact_u - 0.05 * radius:
        raise ValueError(f"{prefix}land_radius must leave the contact points (at radius {r_p + contact_u!r} m) "
                         f"in the groove (loss of four-point contact), got {land!r}")
    bottom_u = _flank_intersections(*grooves)[0][0]
    if not sign * (back - r_p) > sign * bottom_u + 0.05 * radius:
        raise ValueError(f"{prefix}back_radius must lie beyond the groove bottom (radius {r_p + bottom_u!r} m), "
                         f"got {back!r}")
    half_angle = 2.0 * radius / r_p if half_angle is None else _positive("half_angle", half_angle, "rad")
    if half_angle > math.pi / 2:
        raise ValueError(f"half_angle must lie in (0, pi/2] rad, got {half_angle!r}")
    limit = p * math.pi if p > 0 else math.inf  # lead / 2
    width = min(p * half_angle + 1.5 * radius, limit) if axial_half_width is None else \
        _positive("axial_half_width", axial_half_width, "m")
    if width > limit:
        raise ValueError(f"axial_half_width must lie in (0, lead/2] = (0, {limit!r}] m, got {width!r}")
    return land, back, half_angle, width


def _add_segment(gmsh, grooves, land: float, back: float, half_angle: float,
                 width: float) -> tuple[list[int], dict[str, list[int]]]:
    """OCC groove segment (annular wedge minus the lens lofted along the helix); returns its
    volume tags and faces by role ('flank_left', 'flank_right', 'land', 'back', 'free')."""
    occ = gmsh.model.occ
    left = grooves[0]
    radius, r_p = left.ball_radius, left.pitch_radius
    r_in, r_out = min(land, back), max(land, back)
    outer = occ.addCylinder(0.0, 0.0, -width, 0.0, 0.0, 2 * width, r_out, angle=2 * half_angle)
    inner = occ.addCylinder(0.0, 0.0, -2 * width, 0.0, 0.0, 4 * width, r_in)
    wedge, _ = occ.cut([(3, outer)], [(3, inner)])
    occ.rotate(wedge, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, -half_angle)
    # the cutter runs past the wedge's end planes (a profile plane spans azimuths within
    # ~ 2 R_B sin(lambda) / rho of its own); loft through exact lens sections (OCC: 1e-7 m
    # from the exact surface, against 1e-6 m for a pipe over this reach; flank nodes are
    # snapped afterwards)
    reach = 1.1 * half_angle + 0.02 + 3 * radius * math.sin(left.lead_angle) / (r_p - 2 * radius * (left.sign_u < 0))
    sections = [_lens_loop(occ, grooves, phi) for phi in np.linspace(-reach, reach, 9)]
    cutter = occ.addThruSections(sections, makeSolid=True, makeRuled=False)
    result, _ = occ.cut(wedge, [vt for vt in cutter if vt[0] == 3])
    occ.synchronize()
    volumes = [tag for dim, tag in result if dim == 3]
    roles: dict[str, list[int]] = {"flank_left": [], "flank_right": [], "land": [], "back": [], "free": []}
    for _, tag in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True, oriented=False):
        xyz = _face_point(gmsh, tag)
        rho = math.hypot(xyz[0], xyz[1])
        kind = gmsh.model.getType(2, tag)
        residuals = [abs(surface_residual(g, xyz[None, :])[0]) for g in grooves]
        if kind == "Cylinder" and abs(rho - land) < 1e-6 * radius:
            roles["land"].append(tag)
        elif kind == "Cylinder" and abs(rho - back) < 1e-6 * radius:
            roles["back"].append(tag)
        elif kind not in ("Plane", "Cylinder") and min(residuals) < 0.01 * radius:
            roles["flank_left" if residuals[0] < residuals[1] else "flank_right"].append(tag)
        else:
            roles["free"].append(tag)
    if not roles["flank_left"] or not roles["flank_right"]:
        raise RuntimeError(f"groove flanks not identified: {roles}")
    return volumes, roles


def _snap_segment(gmsh, grooves, roles: dict[str, list[int]]) -> None:
    for groove, name in zip(grooves, ("flank_left", "flank_right")):
        _snap_to_groove(gmsh, groove, roles[name], np.eye(3), np.zeros(3))
    _snap_to_bottom(gmsh, grooves, roles["flank_left"], roles["flank_right"])


def screw_groove_segment(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                         contact_angle: float, body: str = "screw", *, deviations=(0.0, 0.0),
                         profile_plane: str = "normal", land_radius: float | None = None,
                         back_radius: float | None = None, half_angle: float | None = None,
                         axial_half_width: float | None = None, h_contact: float | None = None,
                         growth: float = 1.3, h_max: float | None = None, fine_radius: float | None = None,
                         cache: bool = True) -> Path:
    """A screw-shaft (``body="screw"``) or nut segment with its helical gothic-arch groove,
    as a cached gmsh 4.1 ``.msh`` in the screw frame [m] (axis z, ball-centre helix
    ``H(phi)``, the groove's nominal contacts at phi = 0).

    The body is the annular wedge ``|phi| <= half_angle`` between ``land_radius``
    (the land: default ``R_P -+ 0.25 R_B``) and ``back_radius`` (core of the screw /
    outside of the nut, default ``R_P -+ 2 R_B``), within ``|z| <= axial_half_width``
    (default ``p half_angle + 1.5 R_B``, at most ``lead/2`` so no other turn of the
    groove enters), minus the gothic-arch lens swept along the helix (both flanks;
    lin2019 Fig 13).  Default ``half_angle``: ``2 R_B / R_P``.  With ``h_contact``
    the mesh is refined around the two contact points of a ball at phi = 0.
    ``deviations`` [rad]: contact angle deviations (left, right) of the two flanks
    (lin2019 Fig 17, eq 17 ``b = b_0 + db``): a flank's arc centre turns about the
    ball centre so a ball on the helix touches it at ``contact_angle + db``.

    Physical groups: volume ``screw`` or ``nut``; surfaces ``flank_left``,
    ``flank_right`` (nodes on the exact helical surface), ``land``, ``back``,
    ``segment_free`` (the cut faces).
    """
    grooves = _segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, body, deviations,
                               profile_plane)
    left = grooves[0]
    land, back, half_angle, width = _segment_dimensions(grooves, land_radius, back_radius, half_angle,
                                                        axial_half_width)
    refine = h_contact is not None
    h_contact, growth, h_max, fine_radius = _check_refinement(left.ball_radius, left.ball_radius / 4 if h_contact
                                                              is None else h_contact, growth, h_max, fine_radius)
    params = dict(builder="screw_groove_segment", groove=[left.ball_radius, left.conformity, left.pitch_radius,
                  left.lead, left.contact_angle, grooves[1].contact_angle, left.body, left.profile_plane],
                  land=land, back=back, half_angle=half_angle, width=width, refine=refine, h_contact=h_contact,
                  growth=growth, h_max=h_max, fine_radius=fine_radius)
    path, build = cached_msh(f"{left.body}-segment", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    with session("groove_segment") as gmsh:
        volumes, roles = _add_segment(gmsh, grooves, land, back, half_angle, width)
        physical(gmsh, 3, volumes, left.body)
        for name, tags in roles.items():
            if tags:
                physical(gmsh, 2, tags, "segment_free" if name == "free" else name)
        if refine:
            from ballbench.meshes.rail import _refine_at_points

            contacts = [g.surface(g.contact_theta, 0.0) for g in grooves]
            _refine_at_points(gmsh, contacts, h_contact, growth, h_max, fine_radius)
        else:
            gmsh.option.setNumber("Mesh.MeshSizeMax", h_max)
            gmsh.option.setNumber("Mesh.MeshSizeMin", h_max / 2)
        gmsh.model.mesh.generate(3)
        _snap_segment(gmsh, grooves, roles)
        write_msh(gmsh, path)
    return path
