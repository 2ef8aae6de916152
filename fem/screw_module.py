"""FE four-point contact module of a ball screw: one ball between a clamped screw groove segment and a
nut groove segment that carries the ball's axial load, P2 elasticity, mortar contact at the four
ball-to-groove contacts (lin2019 Sec 3, Table 4; docs/fe_b2b.md).

The implementation is :mod:`fem.fourpoint`'s (assembly, condensation ``W = B K^-1 B^T``, the QP of
Goldfarb-Idnani with polishing, the geometric update of the gap, the ellipse fit): this module gives it
the screw's geometry (:class:`ScrewModuleGeometry`, the module protocol of ``fourpoint.ModuleGeometry``).

Mesh: :func:`meshes.assemblies.ball_screw_module.ball_screw_module` with one ball at azimuth 0 (screw
frame: ``z`` the screw axis, ball centre ``H(0) = (R_P, 0, 0)``), the grooves' profile in the plane normal
to the helix (lin2019 eq 41).  Contacts in the order of lin2019 eq 54, ``(SL, SR, NR, NL)``.

Frames.  CS3 of lin2019 eq 41 at the ball (``helix.cs3_frame(0, alpha)``): ``x3 = (1, 0, 0)`` radial,
``y3 = (0, cos alpha, sin alpha)`` along the helix, ``z3 = (0, -sin alpha, cos alpha)``.  Contact ``i``: the
geometry core's exact frame at the flank's contact point (:func:`lowmodel.geometry.groove.contact_frame`):
``e1`` = major axis (across the groove), ``e2`` = minor axis (along the groove), ``e3`` = the flank normal
into the ball; for the normal profile the normal passes through the ball centre and lies in the x3-z3
plane.  **The initial gap is that of the exact surfaces**: sphere height ``R_B - sqrt(R_B^2 - x^2 - y^2)``
minus the height of the exact helical flank above the tangent plane
(:func:`lowmodel.geometry.groove.counter_height`, Newton on ``S(theta, phi)``), not Hertz's
``A x^2 + B y^2``.

Preload (docs/ball_screw.md): the low-order model's ``oversize`` (1.6848 um, fitted on Table 5 case (a))
is the approach of every contact of a centred ball, i.e. a ball larger by ``oversize`` in radius.  It
enters here as the same interference fit: ``g0 -> g0 - oversize`` at every point (a ball of radius
``R_B + oversize`` to ``O(oversize x^2 / R_B^2)``, below 2e-3 of the oversize over the contact patches).
An interference rather than a preload force because the low-order model's preload is a geometric
quantity: with it both models see the same unloaded geometry, and the FE's bulk compliance of the
truncated segments (which Hertz does not have) shows as a difference in the forces, not as a refit.

Rigid unknowns ``q = (X3, Z3, U)``: the ball's translation along ``x3`` and ``z3`` (the contact normals
lie in that plane, so the ball is free along ``y3``: its 3-2-1 nodes carry the residual, reported) and
the nut's axial translation ``U`` along ``z`` (its load face ``nut_load`` moves rigidly; the screw's core
``screw_support`` is clamped).  Loads ``r = (0, 0, F_a)``: ball equilibrium in x3 and z3, and the nut
carries ``F_a`` [N], the ball's axial share: the screw pushes the ball along ``+z`` with ``F_a``
(lowmodel.screw.ball's sign: ``sum_screw (force on ball) . z_hat = axial_load``).  As in the low-order model the nut
does not move radially (it is held by the other balls).  Four contact forces, three equations: unlike the
linear module the forces are statically indeterminate and follow from the FE's compliance and the preload.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ballbench.fem import fourpoint
from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.screw.contacts import flank_angles

__all__ = ["CONTACTS", "ScrewModuleGeometry", "screw_module_geometry", "build_screw_model", "solve",
           "flank_angles_tilted", "with_oversize"]

CONTACTS = ("SL", "SR", "NR", "NL")  # lin2019 eq 54
_BODY = ("screw", "screw", "nut", "nut")
_FLANK = ("left", "right", "right", "left")
_SIGN_U = (-1.0, -1.0, 1.0, 1.0)  # contact direction from the ball centre: -x3 on the screw, +x3 on the nut
_SIGN_W = (-1.0, 1.0, 1.0, -1.0)  # -z3 on the left flanks, +z3 on the right (lin2019 eq 37)


@dataclass(frozen=True)
class ScrewModuleGeometry:
    """Ball and groove geometry of one ball in a ball screw: ``ball_radius``, ``pitch_radius``, ``lead`` [m],
    ``conformity``, ``contact_angles`` (4,) [rad] of (SL, SR, NR, NL) with a centred ball, ``oversize`` [m]
    (preload as an interference fit, module docstring)."""

    ball_radius: float
    conformity: float
    pitch_radius: float
    lead: float
    contact_angles: tuple
    oversize: float = 0.0

    contact_names = CONTACTS
    volumes = {"ball1": 0, "screw": 1, "nut": 2}
    clamped = ("screw_support", "nut_load")
    load_face = "nut_load"
    rigid_names = ("X3", "Z3", "U")
    all_contacts = True

    @property
    def lead_angle(self) -> float:
        return float(helix.lead_angle(self.lead, self.pitch_radius))

    @property
    def cs3(self) -> np.ndarray:
        """(3, 3) columns ``x3, y3, z3`` of CS3 at the ball (lin2019 eq 41, :func:`helix.cs3_frame`)."""
        return helix.cs3_frame(0.0, self.lead_angle)

    @property
    def ball_centre(self) -> np.ndarray:
        """(3,) ball centre on the helix at azimuth 0 [m]."""
        return np.asarray(helix.ball_centre(0.0, self.pitch_radius, self.lead), dtype=float)

    @property
    def free_axis(self) -> np.ndarray:
        """``y3``: the ball translation no contact holds."""
        return self.cs3[:, 1]

    @property
    def groove_radius(self) -> float:
        return float(groove_core.groove_radius(self.ball_radius, self.conformity))

    def flank(self, i: int) -> groove_core.HelicalGroove:
        return _flank(self, i)

    def frame(self, i: int) -> np.ndarray:
        """(3, 3) rows ``e1, e2, e3`` (major, minor, normal into the ball) of contact ``i``."""
        return _contact_frame(self, i).rotation

    @property
    def normals(self) -> np.ndarray:
        """(4, 3) outward unit contact normals (ball centre -> contact) of the centred ball, screw frame."""
        return np.array([-_contact_frame(self, i).normal for i in range(4)])

    def contact_point(self, i: int) -> np.ndarray:
        return _contact_frame(self, i).point

    def gap(self, i: int, local: np.ndarray, shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Exact gap [m] along ``e3`` between the sphere and the helical flank of contact ``i`` at the
        tangent-plane points ``local`` (k, 2) [m], minus the oversize; also the sphere points (k, 3) relative
        to the ball centre [m].  ``shift``: the ball moved by ``shift e1`` relative to the flank (its point
        ``local`` faces the flank at ``local + shift e1``)."""
        radius = self.ball_radius
        frame = _contact_frame(self, i)
        x, y = local[:, 0], local[:, 1]
        rho2 = x * x + y * y
        if np.any(rho2 >= radius * radius):
            raise ValueError("gap: a point lies outside the ball's silhouette (candidate zone too large)")
        ball = rho2 / (radius + np.sqrt(radius * radius - rho2))  # R - sqrt(R^2 - rho^2) without cancellation
        flank = groove_core.counter_height(self.flank(i), x + shift, y)
        points = (frame.point - self.ball_centre) + x[:, None] * frame.major + y[:, None] * frame.minor \
            + ball[:, None] * frame.normal
        return ball - flank - self.oversize, points

    def rigid_modes(self, i: int) -> np.ndarray:
        """(3, 3): displacement of the ball relative to the flank of contact ``i`` per unit ``(X3, Z3, U)``."""
        cs3 = self.cs3
        nut = -1.0 if i >= 2 else 0.0
        return np.array([cs3[:, 0], cs3[:, 2], [0.0, 0.0, nut]])

    def load_face_motion(self, rigid: np.ndarray) -> np.ndarray:
        return np.array([0.0, 0.0, rigid[2]])

    def moving(self, i: int) -> bool:
        """True for the nut's contacts (NR, NL)."""
        return i >= 2

    def loaded_angle(self, i: int, centre: np.ndarray) -> float:
        """Contact angle [rad] of the point ``centre`` (3,) (relative to the ball centre, screw frame) as lin2019
        eq 37 measures it: from ``-x3`` (screw) or ``+x3`` (nut) towards ``-+z3``."""
        local = centre @ self.cs3
        return math.atan2(_SIGN_W[i] * local[2], _SIGN_U[i] * local[0])

    def flank_normals(self, i: int, points: np.ndarray) -> np.ndarray:
        """(k, 3) unit normals of the exact helical flank at the points facing ``points`` (k, 3) (relative to
        the ball centre), pointing from the flank into the ball
        (:meth:`lowmodel.geometry.groove.HelicalGroove.surface_normal`)."""
        flank = self.flank(i)
        phi, uw = groove_core.profile_coordinates(flank, points + self.ball_centre)
        d = uw - flank.arc_centre
        theta = np.arctan2(d[:, 1], d[:, 0])
        return -flank.surface_normal(theta, phi)  # outward from the ball, as the sphere's normal

    def to_ball_frame(self, vectors: np.ndarray) -> np.ndarray:
        """Screw-frame vectors (k, 3) -> CS3 components (x3, y3, z3) (the frame of lowmodel.screw)."""
        return vectors @ self.cs3


@lru_cache(maxsize=64)
def _flank(geometry: ScrewModuleGeometry, i: int) -> groove_core.HelicalGroove:
    return groove_core.helical_groove(geometry.ball_radius, geometry.conformity, geometry.pitch_radius,
                                      geometry.lead, float(geometry.contact_angles[i]), _BODY[i], _FLANK[i])


@lru_cache(maxsize=64)
def _contact_frame(geometry: ScrewModuleGeometry, i: int) -> groove_core.ContactFrame:
    return groove_core.contact_frame(_flank(geometry, i))


def flank_angles_tilted(nominal_angle: float, theta: float) -> tuple:
    """Contact angles (SL, SR, NR, NL) [rad] of lin2019 Fig 17 as the low-order model reads it (docs/ball_screw.md,
    ``reading="tilted"``): both screw flanks at ``beta_0 + theta``, the nut's at ``beta_0``
    (:func:`lowmodel.screw.ball.flank_angles`)."""
    return tuple(float(a) for a in flank_angles(nominal_angle, theta, "tilted")[0])


def screw_module_geometry(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                          contact_angles, oversize: float = 0.0) -> ScrewModuleGeometry:
    """Validated :class:`ScrewModuleGeometry` (lengths [m] > 0, ``lead`` >= 0, ``contact_angles`` four angles in
    (0, pi/2) rad, ``oversize`` in [0, 0.01 ball_radius] m)."""
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    checks.conformity("conformity", conformity)
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    lead = checks.non_negative("lead", lead, "m")
    try:
        angles = tuple(float(a) for a in contact_angles)
    except (TypeError, ValueError):
        raise ValueError(f"contact_angles must be four angles (SL, SR, NR, NL) [rad], got {contact_angles!r}") from None
    if len(angles) != 4:
        raise ValueError(f"contact_angles must be four angles (SL, SR, NR, NL) [rad], got {contact_angles!r}")
    checks.contact_angle("contact_angles", np.array(angles))
    oversize = checks.bounded("oversize", oversize, 0.0, 0.01 * ball_radius, "m", lower_closed=True,
                              upper_closed=True, note="i.e. [0, 0.01 ball_radius]")
    return ScrewModuleGeometry(float(ball_radius), float(conformity), float(pitch_radius), float(lead), angles,
                               float(oversize))


def build_screw_model(mesh, geometry: ScrewModuleGeometry, *, materials=(2.1e11, 0.28), gap_limit: float,
                      method: str = "augmented") -> fourpoint.ModuleModel:
    """Assemble, constrain and condense the screw module (:func:`fem.fourpoint.build_module_model` with the
    screw's geometry); ``mesh`` a path of a one-ball :func:`meshes.assemblies.ball_screw_module.ball_screw_module`
    mesh (its default bodies, screw core and nut outside at ``R_P -+ 5.25 R_B``, are the validated depth:
    docs/fe_b2b.md "Depth of the FE bodies"); ``gap_limit`` [m] as there (on the gap with the oversize subtracted)."""
    if not isinstance(geometry, ScrewModuleGeometry):
        raise ValueError(f"geometry must be a ScrewModuleGeometry, got {type(geometry).__name__}")
    return fourpoint.build_module_model(mesh, geometry, materials=materials, gap_limit=gap_limit, method=method)


def solve(model: fourpoint.ModuleModel, axial_load: float, *, tol: float = 1e-9, fit: bool = True,
                       geometric_update: bool = True, max_updates: int = 20) -> fourpoint.ModuleResult:
    """Solve the screw module with the nut carrying ``axial_load`` [N] > 0 (the screw pushes the ball along
    ``+z``); contacts (SL, SR, NR, NL) with normal force, loaded contact angle (lin2019 eq 37 convention),
    approach, fitted ellipse (``a`` along the major axis e1), pressure (:class:`fem.fourpoint.ContactResult`)."""
    if not (math.isfinite(axial_load) and axial_load > 0.0):
        raise ValueError(f"axial_load must be a finite number > 0 N, got {axial_load!r}")
    return fourpoint.solve_loaded(model, np.array([0.0, 0.0, float(axial_load)]), tol=tol, fit=fit,
                                  geometric_update=geometric_update, max_updates=max_updates)


def with_oversize(model: fourpoint.ModuleModel, oversize: float) -> fourpoint.ModuleModel:
    """The condensed ``model`` with another preload ``oversize`` [m] (no new condensation: ``W`` does not depend on
    it).  A uniform interference shifts every weighted gap by ``-oversize int phi_k dA = -oversize m_k``."""
    geometry = model.geometry
    if not isinstance(geometry, ScrewModuleGeometry):
        raise ValueError(f"model must be a screw module, got a {type(geometry).__name__}")
    new = screw_module_geometry(geometry.ball_radius, geometry.conformity, geometry.pitch_radius, geometry.lead,
                                geometry.contact_angles, oversize)
    return dataclasses.replace(model, geometry=new, g0=model.g0 - (new.oversize - geometry.oversize) * model.weights)
