"""Contact ellipse truncation: does a ball's contact ellipse reach the shoulder of its groove?

The classic design check of a ball raceway (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., Vol. 2,
"Contact ellipse truncation"): the end of the major semi-axis ``a`` of a contact ellipse, seen from the ball centre,
lies at the angle ``beta + theta_a`` from the load axis, ``beta`` the loaded contact angle and ``sin theta_a =
a / R_B`` (``a`` is measured in the contact's tangent plane, docs/hertz.md); the ellipse is truncated when that
angle reaches the shoulder angle ``theta_s``, where the groove's flank meets its land.  A truncated contact carries
an edge pressure Hertz's ellipse does not have: every model of the workbench (Hertz, the BEM on the groove's
exact gap, lin2019's friction models, the FE modules, whose flanks end at a land) is outside its assumptions.

Where the shoulder is (a convention, docs/truncation.md): a case description gives no shoulder height, so the
groove's land lies ``SHOULDER_DEPTH R_B = 0.25 R_B`` from the ball centre towards the groove's body, measured
along the load axis: for a linear guide's rail and carriage grooves below/above the ball centre (the land of the
FE four-point module since lin2017's cross-section, meshes.parts.rail), for a screw's and a nut's groove radially
(the lands ``R_P -+ 0.25 R_B`` of the FE screw module, meshes.assemblies.ball_screw_module).  A flank of
conformity ``f`` and contact angle ``beta_r`` (the ball centred, deviation included) then ends at the shoulder
angle of :func:`shoulder_angle`: ``acos 0.25`` = 75.5 deg at ``f -> 0.5``, 75.5-76.3 deg at f 0.5-0.6 and
30-60 deg (docs/truncation.md, table).  The FE modules keep that land where the contact's zone fits on the
flank; a heavy contact short of the shoulder gets a longer flank (:func:`land_depth`, ladder.rungs.module_fe).

Only the shoulder end is checked: the other end reaches the groove's bottom (the other flank of a gothic arch)
only where ``theta_a`` passes the contact angle itself, ``a / R_B > sin beta`` (0.64 at 40 deg), far past the
static limit of real bearings (docs/truncation.md).  All lengths in metres, angles in radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.groove import groove_radius

__all__ = ["SHOULDER_DEPTH", "Truncation", "shoulder_angle", "land_depth", "end_angle", "truncation", "words"]

SHOULDER_DEPTH = 0.25  # the groove's land: 0.25 R_B from the ball centre towards the groove's body (convention)


def shoulder_angle(ball_radius: float, conformity: float, contact_angle: float,
                   depth: float = SHOULDER_DEPTH) -> float:
    """The shoulder angle ``theta_s`` [rad] of a gothic-arch flank: seen from the centred ball's centre, the angle
    from the load axis of the point where the flank meets the land ``depth R_B`` from the ball centre.

    In the flank's cross-section, ``u`` along the load axis towards the groove's body and ``v`` across it towards
    the shoulder, the flank is the arc of radius ``r_g = 2 f R_B`` about ``C = -(r_g - R_B) (sin beta_r, cos beta_r)``
    (lowmodel.geometry.groove, the arc centre opposite the contact point); it meets the land ``u = d`` at
    ``v_e = C_v + sqrt(r_g^2 - (d - C_u)^2)`` and ``theta_s = atan2(v_e, d)``.  ``contact_angle`` ``beta_r`` [rad] in
    (0, pi/2); ``depth`` in [0, 1)."""
    radius = checks.positive("ball_radius", ball_radius, "m")
    beta = checks.contact_angle("contact_angle", contact_angle)
    depth = checks.bounded("depth", depth, 0.0, 1.0, lower_closed=True)
    r_g = float(groove_radius(radius, conformity))
    d = depth * radius
    c_v, c_u = -(r_g - radius) * math.sin(beta), -(r_g - radius) * math.cos(beta)
    v_e = c_v + math.sqrt(r_g * r_g - (d - c_u) ** 2)
    return math.atan2(v_e, d)


def land_depth(ball_radius: float, conformity: float, contact_angle: float, angle: float) -> float:
    """The inverse of :func:`shoulder_angle`: the land depth (in units of ``R_B``, from the ball centre towards the
    groove's body) at which the flank of ``contact_angle`` [rad] ends at ``angle`` [rad] from the load axis.

    The flank point seen at ``angle`` ``theta`` lies at ``rho (sin theta, cos theta)`` with ``|rho u - C| = r_g``:
    ``rho = u.C + sqrt((u.C)^2 - |C|^2 + r_g^2)``, ``u.C = -(r_g - R_B) cos(theta - beta_r)``; the depth is
    ``rho cos theta / R_B`` (negative past ``theta = pi/2``: the flank would have to rise above the ball centre)."""
    radius = checks.positive("ball_radius", ball_radius, "m")
    beta = checks.contact_angle("contact_angle", contact_angle)
    theta = checks.bounded("angle", angle, 0.0, math.pi, "rad")
    r_g = float(groove_radius(radius, conformity))
    offset = r_g - radius
    u_c = -offset * math.cos(theta - beta)
    rho = u_c + math.sqrt(u_c * u_c - offset * offset + r_g * r_g)
    return rho * math.cos(theta) / radius


def end_angle(ball_radius: float, contact_angle: float, a: float) -> float:
    """``beta + asin(a / R_B)`` [rad]: the end of the major semi-axis ``a`` [m] of a contact ellipse at the loaded
    contact angle ``beta`` [rad], seen from the ball centre (``a >= R_B``: ``beta + pi/2``)."""
    radius = checks.positive("ball_radius", ball_radius, "m")
    a = checks.non_negative("a", a, "m")
    return float(contact_angle) + math.asin(min(a / radius, 1.0))


@dataclass(frozen=True)
class Truncation:
    """One contact's truncation check: ``contact`` (``"ball 1 BR"``), ``contact_angle`` (loaded) [rad], ``a`` [m],
    ``end_angle`` and ``shoulder_angle`` [rad], ``rigid_angle`` [rad] the flank's; ``margin`` [rad] what is left
    between the ellipse's end and the shoulder."""

    contact: str
    contact_angle: float
    a: float
    end_angle: float
    shoulder_angle: float
    rigid_angle: float  # the flank's contact angle with the ball centred [rad] (it places the shoulder)

    @property
    def margin(self) -> float:
        return self.shoulder_angle - self.end_angle

    @property
    def truncated(self) -> bool:
        return self.end_angle >= self.shoulder_angle

    def text(self) -> str:
        """The numbers in words (degrees)."""
        return (f"{self.contact}: contact angle {math.degrees(self.contact_angle):.1f} deg + "
                f"asin(a/R_B) {math.degrees(self.end_angle - self.contact_angle):.1f} deg (a = {self.a * 1e3:.4g} mm) "
                f"= {math.degrees(self.end_angle):.1f} deg against the shoulder at "
                f"{math.degrees(self.shoulder_angle):.1f} deg")


def truncation(contact: str, ball_radius: float, conformity: float, rigid_angle: float, loaded_angle: float,
               a: float, depth: float = SHOULDER_DEPTH) -> Truncation:
    """The :class:`Truncation` of one contact: its flank's ``rigid_angle`` (the ball centred, deviation included)
    places the shoulder (:func:`shoulder_angle`), the ``loaded_angle`` [rad] and semi-axis ``a`` [m] of the touching
    state the ellipse's end (:func:`end_angle`)."""
    return Truncation(contact, float(loaded_angle), float(a), end_angle(ball_radius, loaded_angle, a),
                      shoulder_angle(ball_radius, conformity, rigid_angle, depth), float(rigid_angle))


def words(found: list[Truncation] | tuple[Truncation, ...]) -> str:
    """Why the truncated contacts of ``found`` put a case outside the models (empty when none is truncated)."""
    cut = [t for t in found if t.truncated]
    if not cut:
        return ""
    worst = max(cut, key=lambda t: t.end_angle - t.shoulder_angle)
    names = ", ".join(t.contact for t in cut)
    return (f"contact ellipse truncated by the groove's shoulder on {len(cut)} contact(s) ({names}); "
            f"worst {worst.text()} (the land {SHOULDER_DEPTH:g} R_B from the ball centre, the shoulder convention of "
            "docs/truncation.md): the contact carries an edge pressure that Hertz's ellipse, lin2019's friction "
            "models and the FE modules (their contacts on the flank) do not represent; lower the load or use a "
            "closer conformity / higher shoulder")
