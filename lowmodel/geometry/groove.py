"""Gothic-arch grooves: the straight rail groove and the helical ball-screw groove, their
profiles, exact surfaces and principal curvatures (the geometry core's groove).

Gothic arch (lin2019 Sec 2.3.1, eq 37, Figs 2 and 13): each flank of the groove
cross-section is a circular arc of radius ``r_g = conformity * 2 R_B``
(``conf = R_G / 2 R_B``) whose centre lies ``r_g - R_B`` from the ball centre,
opposite the contact point, so that the ball touches the flank at its contact
angle with the normal through the ball centre.  A contact angle deviation
(lin2017 Sec 4 / lin2019 eq 17: ``b_i = b_0 + db_i``, "manufacturing error
and/or misalignment") turns that arc centre about the ball centre by
``db_i``: the ball keeps its centre and touches the flank at ``b_0 + db_i``.

**Straight groove** (:class:`GothicArch`, linear-bearing rail; frame of lin2017
Fig 2 / lin2019 Fig 2): ball centre at the origin, ``z`` along the rail,
``x``-``y`` the cross-section, the bottom rail below (``y < 0``); contact angles
from ``-y`` towards ``-x`` (left, BL) and ``+x`` (right, BR), contact points from
:mod:`lowmodel.geometry.fourpoint` (lin2017 eq 1).  The groove is the lens
``disc(C_left) & disc(C_right)`` below the land.

**Helical groove** (:class:`HelicalGroove`, ball screw; lin2019 Sec 3.1, eqs
35-42, Fig 13; Table 4: R_B = 2.778 mm, conformity 0.56, R_P = 16.5 mm,
lead 20 mm, beta_0 = 45 deg):

* the nominal ball-centre path is the right-handed helix of
  :mod:`lowmodel.geometry.helix`, ``H(phi) = (R_P cos phi, R_P sin phi, p phi)``,
  ``p = lead / (2 pi)`` (lin2019 eq 35), lead angle
  ``lead_angle = atan(p / R_P)`` (lin2019 eq 42's alpha);
* the moving frame CS3 (lin2019 eq 41, :func:`helix.cs3_frame`): ``x3`` radial,
  ``y3`` tangent to the helix, ``z3 = x3 x y3``;
* the flank touches a ball on the helix at the contact angle ``beta`` measured
  from ``-x3`` (screw) or ``+x3`` (nut) (lin2019 eq 37), on the ``-z3`` side for
  the left flank and ``+z3`` for the right;
* the groove surface is the screw motion of that cross-section
  ``S(theta, phi) = rot_z(phi) [(R_P, 0, 0) + u(theta) e_1 + w(theta) c] + (0, 0, p phi)``
  with ``(u, w)`` the arc and ``c`` the profile plane's second direction.

Two profile planes (``profile_plane``):

``"normal"`` (the default everywhere, lin2019 eq 41): the profile is drawn in
    the plane x3-z3, normal to the helix, ``c = z3 = (0, -sin lead_angle, cos lead_angle)``.
    A ball centred on the helix then touches the swept surface exactly at the
    profile contact point and the surface normal there passes through the ball
    centre (the helix velocity of the contact point is orthogonal to the
    contact normal); the only profile for which a ball on the helix touches
    all four flanks.
``"axial"``: the profile is drawn in the axial plane (``c = (0, 0, 1)``, a
    manufacturing convention, offered for comparison).  The surface normal at
    the profile contact point then tilts out of the axial plane (by 8.8 deg for
    lin2019 Table 4), so a ball tangent there has its centre ``R_B`` along the
    true normal, slightly off the helix.

Principal curvatures (:func:`contact_frame`, :func:`groove_curvatures_helical`):
the first and second fundamental forms of ``S`` are exact, the curvatures are
the eigenvalues of the shape operator, positive convex as seen from the ball
(the concave cross-section has ``~ -1/r_g``).  At ``lead = 0`` both planes
reduce to the bearing raceway ``(-1/r_g, +-cos(beta)/(R_P -+ R_B cos(beta)))``
(Harris).

All lengths in metres, angles in radians; numpy only.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import fourpoint, helix

__all__ = [
    "BODIES", "FLANKS", "PROFILE_PLANES", "MAX_DEVIATION",
    "groove_radius", "straight_groove_curvatures", "GothicArch", "gothic_arch",
    "HelicalGroove", "helical_groove", "flank_arc_centre", "ContactFrame", "contact_frame", "groove_curvatures_helical",
    "counter_height", "pair_initial_gap", "straight_pair_initial_gap", "profile_coordinates", "surface_residual",
]

BODIES = helix.BODIES  # ("nut", "screw"), one tuple for the geometry core
FLANKS = ("left", "right")
PROFILE_PLANES = ("normal", "axial")
MAX_DEVIATION = math.radians(15.0)  # largest contact angle deviation of a flank [rad]


def groove_radius(ball_radius, conformity):
    """Flank radius ``r_g = conformity * 2 R_B`` [m] (lin2019 Sec 2.3.1: ``conf = R_G / 2 R_B``).

    ``ball_radius`` [m] > 0, ``conformity`` in (0.5, 1) (:func:`lowmodel.checks.conformity`).
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    with np.errstate(over="ignore"):
        return checks.finite_result("ball_radius", checks.conformity("conformity", conformity) * 2.0 * radius, "m")


# --------------------------------------------------------------------------
# straight gothic arch (linear-bearing rail)
# --------------------------------------------------------------------------
def straight_groove_curvatures(ball_radius: float, conformity: float) -> tuple[float, float]:
    """Principal curvatures [1/m] of a straight groove flank, ``(across, along) = (-1/r_g, 0)``.

    Positive convex as seen from the ball; ``across`` lies in the cross-section
    (the major axis ``a`` of a ball's Hertz ellipse), ``along`` the groove.
    ``ball_radius`` [m] > 0, ``conformity`` in (0.5, 1).
    """
    with np.errstate(over="ignore", divide="ignore"):
        across = checks.finite_result("ball_radius", -1.0 / np.float64(groove_radius(ball_radius, conformity)), "1/m")
    return across, 0.0


@dataclass(frozen=True)
class GothicArch:
    """Cross-section of a bottom gothic-arch groove (build with :func:`gothic_arch`).

    ``contact_angle_left/right`` [rad] are the actual contact angles (nominal plus
    deviation) of the left (-x) and right (+x) flanks; ``land_height`` [m] is the
    ``y`` of the rail's top face (negative: below the ball centre).
    """

    ball_radius: float
    conformity: float
    contact_angle_left: float
    contact_angle_right: float
    land_height: float

    @property
    def groove_radius(self) -> float:
        return groove_radius(self.ball_radius, self.conformity)

    def contact_point(self, side: str) -> np.ndarray:
        """(x, y) of the contact point of flank ``side`` ('left' or 'right') [m]: BL or BR of lin2017 eq 1."""
        beta = self.contact_angle_left if side == "left" else self.contact_angle_right
        return self.ball_radius * fourpoint.contact_normal("BL" if side == "left" else "BR", beta)

    def arc_centre(self, side: str) -> np.ndarray:
        """(x, y) of the centre of flank ``side``: ``-(r_g - R_B)`` along its contact direction [m]."""
        return -(self.groove_radius - self.ball_radius) * self.contact_point(side) / self.ball_radius

    @property
    def bottom(self) -> np.ndarray:
        """(x, y) of the groove bottom, the lower intersection of the two flank circles [m]."""
        c_l, c_r = self.arc_centre("left"), self.arc_centre("right")
        mid = (c_l + c_r) / 2
        half = np.linalg.norm(c_r - c_l) / 2
        along = (c_r - c_l) / max(2 * half, 1e-300)
        normal = np.array([along[1], -along[0]])
        if normal[1] > 0:
            normal = -normal
        return mid + math.sqrt(self.groove_radius**2 - half**2) * normal

    def edge(self, side: str) -> np.ndarray:
        """(x, y) where flank ``side`` meets the land [m]."""
        centre = self.arc_centre(side)
        sign = -1.0 if side == "left" else 1.0
        dy = self.land_height - centre[1]
        return np.array([centre[0] + sign * math.sqrt(self.groove_radius**2 - dy**2), self.land_height])


def gothic_arch(ball_radius: float, conformity: float, contact_angle: float, deviation_left: float = 0.0,
                deviation_right: float = 0.0, land_height: float | None = None) -> GothicArch:
    """Validated bottom gothic-arch groove.

    ``contact_angle`` [rad] the nominal angle ``b_0`` in (0, pi/2); deviations
    [rad] in [-15, 15] deg; ``land_height`` [m] (default ``-0.25 R_B``) in
    ``(-R_B, 0]``.  Raises ``ValueError`` if a contact point does not lie on the
    groove boundary between its bottom and the land (loss of four-point contact).
    """
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    conformity = checks.conformity("conformity", conformity)
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    for name, value in (("deviation_left", deviation_left), ("deviation_right", deviation_right)):
        checks.bounded(name, value, -MAX_DEVIATION, MAX_DEVIATION, "rad", lower_closed=True, upper_closed=True,
                       note="i.e. [-15, 15] deg")
    left = checks.contact_angle("contact_angle + deviation_left", contact_angle + float(deviation_left))
    right = checks.contact_angle("contact_angle + deviation_right", contact_angle + float(deviation_right))
    land = -0.25 * ball_radius if land_height is None else checks.finite("land_height", land_height, "m")
    if not -ball_radius < land <= 0.0:
        raise ValueError(f"land_height must lie in (-ball_radius, 0] = ({-ball_radius!r}, 0] m, got {land!r}")
    arch = GothicArch(ball_radius, conformity, left, right, land)
    # Each contact point lies inside the other flank's disc, hence on the groove boundary:
    # |P_right - C_left|^2 = r_g^2 - 2 R_B (r_g - R_B) (1 - cos(b_left + b_right)) < r_g^2.
    # Four-point contact is lost only where a contact point rises above the land.
    for side in ("left", "right"):
        point = arch.contact_point(side)
        if point[1] > land - 0.05 * ball_radius:
            raise ValueError(f"loss of four-point contact: the {side} contact point lies above the land "
                             f"(land_height must be above {point[1] + 0.05 * ball_radius!r} m)")
    return arch


# --------------------------------------------------------------------------
# helical gothic arch (ball screw and nut)
# --------------------------------------------------------------------------
def flank_arc_centre(ball_radius: float, groove_radius: float, contact_angle, sign_u: float,
                     sign_w: float) -> np.ndarray:
    """(u, w) of a helical flank's arc centre [m]: ``-(r_g - R_B)`` along the contact direction
    ``(sign_u cos beta, sign_w sin beta)`` (:attr:`HelicalGroove.arc_centre`, whose fields give the signs and ``r_g``;
    no input checks: for many contact angles of one validated groove).  One angle: shape (2,); a 1-D array of n:
    (n, 2), each row the numbers of its angle alone (``math.cos`` per angle: numpy's may round otherwise)."""
    angles = np.asarray(contact_angle, dtype=float).reshape(-1).tolist()
    direction = np.array([[sign_u * math.cos(a) for a in angles], [sign_w * math.sin(a) for a in angles]])
    centres = (-(groove_radius - ball_radius) * direction).T
    return centres[0] if np.ndim(contact_angle) == 0 else centres


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
        return groove_radius(self.ball_radius, self.conformity)

    @property
    def lead_per_radian(self) -> float:
        """``p = lead / (2 pi)`` [m/rad] (lin2019 eq 35, wang2022's ``h``)."""
        return float(helix.helix_parameter(self.lead))

    @property
    def lead_angle(self) -> float:
        """Nominal lead angle ``atan(lead / (2 pi R_P))`` [rad] (lin2019 eq 42's alpha; :func:`helix.lead_angle`)."""
        return float(helix.lead_angle(self.lead, self.pitch_radius))

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
        return helix.cs3_frame(0.0, self.lead_angle)[:, 2]  # z3 of lin2019 eq 41 at phi = 0: (0, -sin, cos)

    @property
    def contact_direction(self) -> np.ndarray:
        """Unit vector (u, w) from the ball centre to the contact point in the profile plane."""
        return np.array([self.sign_u * math.cos(self.contact_angle), self.sign_w * math.sin(self.contact_angle)])

    @property
    def arc_centre(self) -> np.ndarray:
        """(u, w) of this flank's arc centre: ``-(r_g - R_B)`` along the contact direction
        (:func:`flank_arc_centre`)."""
        return flank_arc_centre(self.ball_radius, self.groove_radius, self.contact_angle, self.sign_u, self.sign_w)

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
        world = np.einsum("...ij,...j->...i", helix.rotation_z(phi), local)
        world[..., 2] += self.lead_per_radian * phi
        return world

    def surface(self, theta, phi) -> np.ndarray:
        """Groove surface points ``S(theta, phi)`` [m], shape (..., 3)."""
        uw = self.profile(theta)
        return self.to_world(uw[..., 0], uw[..., 1], phi)

    def helix(self, phi) -> np.ndarray:
        """Ball-centre helix ``H(phi)`` [m], shape (..., 3) (lin2019 eq 35; :func:`helix.ball_centre`)."""
        return helix.ball_centre(phi, self.pitch_radius, self.lead)

    def surface_normal(self, theta, phi) -> np.ndarray:
        """Unit normal of ``S`` at ``(theta, phi)``, shape (..., 3), pointing from the groove's arc centre
        side into the groove opening (towards the ball): ``S_theta x S_phi`` oriented along the profile's
        inward radius ``-(cos theta, sin theta)``; ``S_phi = z x S + p z``."""
        theta, phi = np.broadcast_arrays(np.asarray(theta, dtype=float), np.asarray(phi, dtype=float))
        e1, c = np.array([1.0, 0.0, 0.0]), self.plane_axis
        rot = helix.rotation_z(phi)
        s_t = np.einsum("...ij,...j->...i", rot, (-np.sin(theta))[..., None] * e1 + np.cos(theta)[..., None] * c)
        s_p = np.cross(np.array([0.0, 0.0, 1.0]), self.surface(theta, phi)) + self.lead_per_radian * np.array(
            [0.0, 0.0, 1.0])
        normal = np.cross(s_t, s_p)
        inward = -np.einsum("...ij,...j->...i", rot, np.cos(theta)[..., None] * e1 + np.sin(theta)[..., None] * c)
        normal *= np.sign(np.einsum("...i,...i->...", normal, inward))[..., None]
        return normal / np.linalg.norm(normal, axis=-1, keepdims=True)


def helical_groove(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                   contact_angle: float, body: str = "screw", flank: str = "left",
                   profile_plane: str = "normal") -> HelicalGroove:
    """Validated :class:`HelicalGroove`.

    ``ball_radius``, ``pitch_radius`` [m] > 0, ``lead`` [m] >= 0 (0: a bearing
    raceway; a right-handed screw), ``conformity`` in (0.5, 1)
    (:func:`lowmodel.checks.conformity`), ``contact_angle`` in (0, pi/2) rad.
    """
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    conformity = checks.conformity("conformity", conformity)
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    lead = checks.non_negative("lead", lead, "m (right-handed screw)")
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    body = checks.choice("body", body, BODIES)
    flank = checks.choice("flank", flank, FLANKS)
    profile_plane = checks.choice("profile_plane", profile_plane, PROFILE_PLANES)
    if pitch_radius <= groove_radius(ball_radius, conformity):
        raise ValueError(f"pitch_radius must exceed the groove radius 2 conformity ball_radius "
                         f"= {groove_radius(ball_radius, conformity)!r} m (the screw groove must not reach the axis; "
                         f"a nut groove needs that screw), got {pitch_radius!r}")
    if not helix.lead_angle(lead, pitch_radius) < 0.5 * math.pi:
        raise ValueError(f"lead must give a lead angle below pi/2 rad with pitch_radius {pitch_radius!r} m "
                         f"(atan(lead / (2 pi pitch_radius)) rounds to 90 deg), got {lead!r}")
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
    cross-section has ``curvature_major ~ -1/r_g``), as :mod:`lowmodel.contact.hertz` takes them.
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


@np.errstate(over="ignore", invalid="ignore", divide="ignore")  # overflow is detected and raised below
def contact_frame(groove: HelicalGroove) -> ContactFrame:
    """Exact contact frame at the profile contact point (phi = 0) from the first and
    second fundamental forms of ``S(theta, phi)`` (module docstring): the one
    place the project computes the principal curvatures of a groove."""
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
    if not (np.all(np.isfinite(first)) and np.all(np.isfinite(second)) and np.linalg.det(first) > 0.0):
        _out_of_range(groove)
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
    if not all(np.all(np.isfinite(v)) for v in (values, normal, major, minor, point)):
        _out_of_range(groove)
    angle = math.acos(min(1.0, abs(major @ profile_dir)))
    return ContactFrame(point=point, normal=normal, major=major, minor=minor,
                        curvature_major=float(values[i_major]), curvature_minor=float(values[1 - i_major]),
                        ball_centre=point + groove.ball_radius * normal, profile_angle=angle)


def _out_of_range(groove: HelicalGroove):
    raise ValueError(f"groove: the fundamental forms of this groove leave the float range (pitch_radius "
                     f"{groove.pitch_radius!r} m, ball_radius {groove.ball_radius!r} m, lead {groove.lead!r} m); "
                     f"use lengths of a physical size")


def groove_curvatures_helical(ball_radius: float, conformity: float, pitch_radius: float, contact_angle: float,
                              lead_angle: float, body: str = "screw",
                              profile_plane: str = "normal") -> tuple[float, float, float]:
    """Principal curvatures of a helical ball-screw groove at the contact point.

    The groove of :func:`helical_groove` with the lead given by its angle:
    ``lead = 2 pi pitch_radius tan(lead_angle)``; ``ball_radius``,
    ``pitch_radius`` [m], ``contact_angle`` [rad] in (0, pi/2), ``lead_angle``
    [rad] in [0, pi/2), ``body`` ``"screw"`` or ``"nut"``, ``profile_plane``
    ``"normal"`` (default, lin2019 eq 41) or ``"axial"`` (module docstring).
    Evaluated on the right (``+z3``) flank; the left flank is its image under
    the half-turn about ``x3`` and has the same curvatures.

    Returns ``(kappa_1, kappa_2, angle)``: principal curvatures [1/m] (positive
    convex, seen from the ball), ``kappa_1`` the one closer to the profile
    (across-groove) direction, and ``angle`` [rad] between that principal
    direction and the profile tangent (:func:`contact_frame`).
    """
    checks.positive("ball_radius", ball_radius, "m")
    checks.conformity("conformity", conformity)
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    checks.contact_angle("contact_angle", contact_angle)
    lead_angle = checks.lead_angle("lead_angle", lead_angle)
    checks.choice("body", body, BODIES)
    checks.choice("profile_plane", profile_plane, PROFILE_PLANES)
    lead = float(helix.lead_from_angle(lead_angle, pitch_radius))
    frame = contact_frame(helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, "right",
                                         profile_plane))
    return frame.curvature_major, frame.curvature_minor, frame.profile_angle

def counter_height(groove: HelicalGroove, x, y, iterations: int = 40) -> np.ndarray:
    """Height ``z`` [m] of the exact groove surface above the point ``(x, y)`` of the
    contact frame (:func:`contact_frame`; the pair's frame), arrays of any shape.

    Solves ``Q (S(theta, phi) - P) = (x, y, z)`` for ``(theta, phi, z)`` by Newton
    from the contact (theta_c, 0); valid over the groove flank around the contact.  ConvergenceError
    (with the residual [m]) if a point is not matched to ``1e-9 r_g`` after ``iterations`` steps.
    """
    iterations = checks.count("iterations", iterations, 1)
    frame = contact_frame(groove)
    x, y = np.broadcast_arrays(np.asarray(checks.finite("x", x, "m"), dtype=float),
                               np.asarray(checks.finite("y", y, "m"), dtype=float))
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
        s_t = np.einsum("nij,nj->ni", helix.rotation_z(phi), uw_t[:, :1] * e1 + uw_t[:, 1:] * c)
        world = groove.surface(theta, phi)
        s_p = np.cross(z_hat, world) + groove.lead_per_radian * z_hat
        jac = np.stack([s_t @ rotation[:2].T, s_p @ rotation[:2].T], 2)  # (n, 2 xy, 2 (theta, phi))
        step = np.linalg.solve(jac, residual[..., None])[..., 0]
        theta -= step[:, 0]
        phi -= step[:, 1]
        if np.max(np.abs(step[:, 0]) * r_g + np.abs(step[:, 1]) * groove.pitch_radius, initial=0.0) < 1e-16:
            break
    local = (groove.surface(theta, phi) - frame.point) @ rotation.T
    miss = float(np.max(np.abs(local[:, :2] - target), initial=0.0)) if target.size else 0.0
    if not miss <= 1e-9 * r_g:  # also NaN: the point lies off the flank that Newton can reach from the contact
        raise ConvergenceError("counter_height: Newton did not reach the groove surface above (x, y)", residual=miss,
                               iterations=iterations, tolerance=1e-9 * r_g, reason="iteration limit")
    return local[:, 2].reshape(shape)


def pair_initial_gap(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                     contact_angle: float, body: str = "screw", *, flank: str = "left",
                     profile_plane: str = "normal"):
    """Exact initial gap ``g0(x, y)`` [m] between the undeformed ball and groove of the
    ball-in-screw-groove contact pair meshed by ``meshes`` (same arguments; contact frame of
    :func:`contact_frame`), measured along z at the point ``(x, y)`` of the ball surface:
    ``R_B - sqrt(R_B^2 - x^2 - y^2) - counter_height``.

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


def straight_pair_initial_gap(ball_radius: float, pair: str, conformity: float | None = None):
    """Exact initial gap ``g0(x, y)`` [m] of a ball of radius ``ball_radius`` [m] touching a flat (``pair``
    ``"flat"``), a ball of the same radius (``"ball"``) or a straight groove of ``conformity`` (``"groove"``), at the
    point ``(x, y)`` of the contact plane: the ball's cap ``R_B - sqrt(R_B^2 - x^2 - y^2)``, plus the other ball's
    cap, or minus the groove arc's depth across it, ``r_g - sqrt(r_g^2 - x^2)`` (x across the groove, the major
    axis of :func:`straight_groove_curvatures`; y along it).  For small ``(x, y)`` it tends to Hertz's
    ``A x^2 + B y^2``; beyond ``|x| = R_B`` the caps are continued flat at their rim (the BEM grid stays inside).
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    checks.choice("pair", pair, ("flat", "ball", "groove"))
    r_g = groove_radius(radius, conformity) if pair == "groove" else None

    def initial_gap(x, y):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        cap = radius - np.sqrt(np.maximum(radius**2 - x * x - y * y, 0.0))
        if pair == "flat":
            return cap
        if pair == "ball":
            return 2.0 * cap
        return cap - (r_g - np.sqrt(np.maximum(r_g**2 - x * x, 0.0)))

    return initial_gap


def profile_coordinates(groove: HelicalGroove, points, iterations: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """Azimuth ``phi`` [rad] of the profile plane through each world point and the
    point's profile coordinates ``(u, w)`` [m] in it; ``points`` shape (n, 3).

    Solves ``(X - H(phi)) . m(phi) = 0`` (m: the profile-plane normal) by Newton; ConvergenceError (with the
    residual [m]) if a point is not on its plane to ``1e-9 R_P`` after ``iterations`` steps.
    """
    iterations = checks.count("iterations", iterations, 1)
    points = np.atleast_2d(np.asarray(checks.finite("points", checks.trailing_axis("points", points, 3, "(x, y, z)"),
                                                    "m"), dtype=float))
    e1 = np.array([1.0, 0.0, 0.0])
    c = groove.plane_axis
    m0 = np.cross(e1, c)
    z_hat = np.array([0.0, 0.0, 1.0])
    phi = np.arctan2(points[:, 1], points[:, 0])
    for _ in range(iterations):
        rot = helix.rotation_z(phi)
        m = rot @ m0
        offset = points - groove.helix(phi)
        g = np.einsum("ij,ij->i", offset, m)
        h_p = np.stack([-groove.pitch_radius * np.sin(phi), groove.pitch_radius * np.cos(phi),
                        np.full_like(phi, groove.lead_per_radian)], -1)
        dg = -np.einsum("ij,ij->i", h_p, m) + np.einsum("ij,ij->i", offset, np.cross(z_hat, m))
        step = g / dg
        phi = phi - step
        if np.max(np.abs(step), initial=0.0) < 1e-15:
            break
    rot = helix.rotation_z(phi)
    offset = points - groove.helix(phi)
    miss = float(np.max(np.abs(np.einsum("ij,ij->i", offset, rot @ m0)), initial=0.0))
    if not miss <= 1e-9 * groove.pitch_radius:  # also NaN
        raise ConvergenceError("profile_coordinates: Newton did not reach the profile plane of a point",
                               residual=miss, iterations=iterations, tolerance=1e-9 * groove.pitch_radius,
                               reason="iteration limit")
    u = np.einsum("ij,ij->i", offset, rot @ e1)
    w = np.einsum("ij,ij->i", offset, rot @ c)
    return phi, np.stack([u, w], -1)


def surface_residual(groove: HelicalGroove, points, radius: float | None = None) -> np.ndarray:
    """Signed in-plane distance [m] of world ``points`` (n, 3) from the helical arc
    surface of radius ``radius`` (default ``r_g``) about this flank's arc centre."""
    r = groove.groove_radius if radius is None else checks.positive("radius", radius, "m")
    _, uw = profile_coordinates(groove, points)
    return np.linalg.norm(uw - groove.arc_centre, axis=1) - r
