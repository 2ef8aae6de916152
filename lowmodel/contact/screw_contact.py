"""Dry contact of a ball in the helical groove of a ball screw or nut: BEM on the exact gap against Hertz.

sun2021 Sec 2.2 solves the ball-raceway contact by the minimum-excess principle
(eqs 3-12, :mod:`.halfspace`) because the helix makes the contact region rotate
(deflection angle theta_s) and its pressure differ from Hertz.  This module
separates the effects (docs/halfspace.md):

1. **full-tensor Hertz**: the exact curvature tensor of the swept groove surface
   at the contact point (:func:`ballbench.lowmodel.geometry.groove.contact_frame`,
   fundamental forms; the helix adds a twist term in the profile/track frame),
   so the Hertz ellipse is already rotated from the profile frame by the angle of
   the principal directions (``hertz_angle``);
2. **BEM on the exact gap** (:func:`ballbench.lowmodel.geometry.groove.pair_initial_gap`:
   sphere minus exact helical surface, all orders) in the principal frame: what it
   adds to (1) comes from the higher-order terms of the gap only;
3. **profile-frame Hertz** (``forced``): Hertz with the normal curvatures along the
   profile tangent and along the track, the twist dropped, the ellipse forced onto
   the profile/track frame: a "Hertz" that ignores the rotation;
4. **helix-free Hertz** (``flat_helix``): the groove at lead 0 (a bearing raceway
   of the same section), the Hertz a helix-blind model uses.

Angles are measured from the profile tangent (the across-groove direction of the
profile plane, projected on the tangent plane) toward the track direction
(``minor`` of the contact frame), in rad.  The normal loads follow sun2021 eq 1
(:func:`preload_contact_load`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import halfspace, hertz
from ballbench.lowmodel.geometry import groove as groove_geometry

__all__ = ["GrooveContact", "preload_contact_load", "groove_contact", "hertz_pressure"]


def preload_contact_load(preload: float, ball_count: int, lead_angle: float, contact_angle: float) -> float:
    """Normal load Q_A = Q_B [N] of a preloaded double-nut ball screw at rest (sun2021 eq 1).

    ``Q = F_pre / (n_bb / 2 cos(alpha) sin(beta_0))``: the preload [N] shared by
    the ``ball_count / 2`` balls of one nut, projected on the axis through the lead
    angle alpha and the contact angle beta_0 [rad].  Friction and inertia (eq 2)
    are left out: the scenes are static.
    """
    preload = checks.positive("preload", preload, "N")
    ball_count = checks.count("ball_count", ball_count, 2)
    lead_angle = checks.lead_angle("lead_angle", lead_angle)
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    with np.errstate(over="ignore"):
        load = preload / np.float64(ball_count / 2 * math.cos(lead_angle) * math.sin(contact_angle))  # sun2021 eq 1
    return checks.finite_result("preload, contact_angle", load, "N")


def hertz_pressure(grid: halfspace.SurfaceGrid, a: float, b: float, p0: float, angle: float = 0.0,
                   centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """Hertz pressure ``p0 sqrt(1 - x'^2/a^2 - y'^2/b^2)`` [Pa] on the grid (sun2021 eq 13; Johnson eq 4.39).

    ``(x', y')`` the frame rotated by ``angle`` [rad] about ``centre`` [m]; shape ``(nx, ny)``.
    Semi-axes ``a``, ``b`` [m] > 0, ``p0`` [Pa] >= 0.
    """
    a, b = checks.positive("a", a, "m"), checks.positive("b", b, "m")
    p0 = checks.non_negative("p0", p0, "Pa")
    angle = checks.finite("angle", angle, "rad")
    centre = checks.finite("centre", checks.trailing_axis("centre", centre, 2, "(x, y)", "m"), "m")
    X, Y = grid.coordinates()
    X, Y = X - centre[0], Y - centre[1]
    c, s = math.cos(angle), math.sin(angle)
    xr, yr = c * X + s * Y, -s * X + c * Y
    with np.errstate(over="ignore"):  # far outside a tiny ellipse the squares overflow to inf: pressure 0
        return p0 * np.sqrt(np.maximum(1.0 - (xr / a) ** 2 - (yr / b) ** 2, 0.0))


@dataclass(frozen=True)
class GrooveContact:
    """Ball-groove contact by four models (module docstring); lengths [m], pressures [Pa], angles [rad].

    Attributes
    ----------
    force : normal load [N]
    frame : the exact :class:`~ballbench.lowmodel.geometry.groove.ContactFrame` (grid x = ``major``, y = ``minor``)
    profile_direction : angle of the profile tangent in the grid frame
    hertz : full-tensor Hertz (:class:`~ballbench.lowmodel.contact.hertz.HertzContact`)
    hertz_angle : its major axis from the profile tangent
    bem : :class:`~ballbench.lowmodel.contact.halfspace.HalfSpaceContact` on the exact gap
    bem_angle : the BEM ellipse's major axis from the profile tangent (theta_s)
    forced : profile-frame Hertz (twist dropped, axes on the profile/track frame)
    flat_helix : helix-free Hertz (the groove at lead 0)
    """

    force: float
    frame: groove_geometry.ContactFrame
    profile_direction: float
    hertz: hertz.HertzContact
    hertz_angle: float
    bem: halfspace.HalfSpaceContact
    bem_angle: float
    forced: hertz.HertzContact
    flat_helix: hertz.HertzContact

    def hertz_field(self, which: str = "hertz") -> np.ndarray:
        """Pressure [Pa] of ``which`` (``"hertz"``, ``"forced"``, ``"flat_helix"``) on the BEM grid.

        The full-tensor ellipse lies on the grid axes; the two others on the profile frame.
        """
        contact = checks.choice("which", which, ("hertz", "forced", "flat_helix"))
        model = getattr(self, contact)
        angle = 0.0 if contact == "hertz" else self.profile_direction
        return hertz_pressure(self.bem.grid, float(model.a), float(model.b), float(model.p0), angle)


def _wrap_half_turn(angle: float) -> float:
    return (angle + math.pi / 2) % math.pi - math.pi / 2


def groove_contact(ball_radius: float, conformity: float, pitch_radius: float, lead: float, contact_angle: float,
                   force: float, body: str = "screw", flank: str = "left", *, youngs_modulus: float,
                   poisson_ratio: float, n: int = 256, margin: float = 1.3) -> GrooveContact:
    """Ball in a helical groove (:func:`~ballbench.lowmodel.geometry.groove.helical_groove`) under ``force`` [N].

    Geometry inputs as for ``helical_groove`` ([m], [rad]; ``lead`` [m]); both
    bodies of the same steel ``youngs_modulus`` [Pa], ``poisson_ratio``; BEM grid
    of ``n x n`` cells over ``margin`` times the full-tensor Hertz semi-axes.
    """
    force = checks.positive("force", force, "N")
    n = checks.count("n", n, 8)
    margin = checks.bounded("margin", margin, 1.0, 10.0, note="grid half-width over the Hertz semi-axes")
    groove = groove_geometry.helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank)
    frame = groove_geometry.contact_frame(groove)
    ball = (1.0 / groove.ball_radius, 1.0 / groove.ball_radius)
    material = {"youngs_modulus": youngs_modulus, "poisson_ratio": poisson_ratio}
    full_geometry = hertz.from_curvatures(ball, (frame.curvature_major, frame.curvature_minor), **material)
    full = hertz.solve_load(full_geometry, force)
    # profile tangent (d S / d theta at the contact) in the contact frame (x = major, y = minor)
    theta = groove.contact_theta
    tangent = -math.sin(theta) * np.array([1.0, 0.0, 0.0]) + math.cos(theta) * groove.plane_axis
    local = frame.rotation @ tangent
    profile_direction = _wrap_half_turn(math.atan2(local[1], local[0]))
    # Euler: normal curvatures along the profile tangent and the track; the twist term is dropped
    c2, s2 = math.cos(profile_direction) ** 2, math.sin(profile_direction) ** 2
    k_profile = frame.curvature_major * c2 + frame.curvature_minor * s2
    k_track = frame.curvature_major * s2 + frame.curvature_minor * c2
    forced = hertz.solve_load(hertz.from_curvatures(ball, (k_profile, k_track), **material), force)
    flat_frame = groove_geometry.contact_frame(groove_geometry.helical_groove(
        ball_radius, conformity, pitch_radius, 0.0, contact_angle, body, flank))
    flat = hertz.solve_load(hertz.from_curvatures(ball, (flat_frame.curvature_major, flat_frame.curvature_minor),
                                                  **material), force)
    grid = halfspace.hertz_surface_grid(float(full.a), float(full.b), n, margin)
    X, Y = grid.coordinates()
    gap = groove_geometry.pair_initial_gap(ball_radius, conformity, pitch_radius, lead, contact_angle, body,
                                           flank=flank)(X, Y)
    gap -= gap.min()  # first touch at the lowest cell centre (the exact gap is 0 at the origin, >= 0 nearby)
    try:
        bem = halfspace.solve(gap, grid, full_geometry.contact_modulus, force=force)
    except ValueError as error:
        if "edge of the grid" not in str(error):
            raise
        raise ValueError(f"margin: the BEM contact on the exact gap reaches the edge of the grid of {margin!r} times "
                         f"the Hertz semi-axes ({n} x {n} cells); increase margin or n") from None
    return GrooveContact(force=force, frame=frame, profile_direction=profile_direction, hertz=full,
                         hertz_angle=_wrap_half_turn(-profile_direction), bem=bem,
                         bem_angle=_wrap_half_turn(bem.ellipse_angle - profile_direction), forced=forced,
                         flat_helix=flat)
