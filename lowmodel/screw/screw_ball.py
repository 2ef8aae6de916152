"""Quasi-static motion and friction of balls in a four-point-contact ball screw (lin2019 Sec 3.1).

lin2019 eqs 34-55 and Appendix A9-A11; the friction of each contact ellipse with
its velocity centre offset in both directions comes from
:func:`lowmodel.contact.ellipse_friction_offset.friction_offset`.

Frames (lin2019 Sec 3.1, Figs 12-13; :mod:`lowmodel.geometry.helix`): CS is fixed
to the screw shaft, ``z`` along its axis; the nut turns at ``omega_N`` about
``+z`` and advances ``p omega_N`` (eq 34, ``p = lead / 2 pi``).  CS3 moves with
the ball: ``x3`` radial, ``y3`` tangent to the helix, ``z3 = x3 x y3``
(eq 41, :func:`helix.cs3_frame`); in CS3 the screw axis is
``z_hat = (0, sin alpha, cos alpha)`` (``alpha`` the lead angle, eq 42).

Contacts in the order of lin2019 eq 54, ``(SL, SR, NR, NL)``.  In the
cross-section ``x3-z3`` flank ``i`` is a circular arc of radius
``r_g = 2 conformity R_B`` (gothic arch, :class:`lowmodel.geometry.groove.HelicalGroove`)
with centre ``C_i``; the nut flanks move by the nut's axial shift ``u`` relative
to the screw, ``(0, u cos alpha)`` in ``(x3, z3)`` (eq 48: the shift projected on
the cross-section).  For a ball centre ``p_B`` the contact conditions eqs 49-52
(contact point on the profile, normal through the ball centre) have the closed
form ``e_i = (p_B - C_i)/|p_B - C_i|`` (unit vector from the ball centre to the
contact), the approach is ``delta_i = |p_B - C_i| + R_B + oversize - r_g`` and
``F_i = (delta_i / C_i)^(3/2)`` if ``delta_i > 0`` else 0 (eq 53; ``oversize`` is
the preload: the approach of every contact of a centred ball).  The actual
contact angle follows from ``e_i = (s_u cos beta_i, s_w sin beta_i)``
(``s_u = -1`` screw, ``+1`` nut; ``s_w = -1`` left, ``+1`` right; eq 37).

Kinematics (eqs 36, 40, 43-47): the ball orbits at ``omega_B`` and spins at
``omega`` relative to CS3, so its absolute angular velocity is
``omega_B z_hat + omega``.  Screw (at rest) and nut (``omega_N``) move with the
helical field ``Omega_g H(r)``, ``H(r) = z_hat x r + p z_hat``, and so does the
nominal ball centre (``omega_B H``), hence the slip of the ball on flank ``i`` at
``r = q_B + q_i + xi`` is the rigid field

    dv_i = (omega_B - Omega_i) H(q_B + q_i) + omega x q_i + W_i x xi,   W_i = (omega_B - Omega_i) z_hat + omega

with ``q_i = R_B e_i`` (eq 37) and ``H(q_B + q) = (s q_z, L/(2 pi) + c q_x, -s q_x)``
in CS3 (``s, c = sin, cos alpha``, ``L`` of eq 45).  In the contact plane (minor
axis ``y3`` along the helix, major axis ``n_i x y3`` across the groove,
``n_i = -e_i`` the inward normal) this is lin2019 eq 47: spin ``omega_i = W_i . n_i``
about ``n_i``, slip at the contact centre ``(slip_minor, slip_major) =
(dv . y3, dv . major) = (omega_i c_i, -omega_i d_i)``; tested term by term against
eq 44 and A9-A11.  Friction on the ball: ``mu F_i (f_major major + f_minor y3)``
and the moment ``mu F_i a_i m e_i`` about the contact centre.

Equilibrium of each ball (eq 54): normal forces ``-F_i e_i``, friction forces
and moments, summed about the ball centre (6 equations); unknowns
``p_B = (x_B3, z_B3)``, ``omega_B`` and ``omega = (omega_x, omega_y, omega_z)``
(6; eq 55's 18-vector with the contact points and angles eliminated by the
closed form above).  The axial load: the screw pushes the balls with
``sum_screw contacts (force on the ball) . z_hat = axial_load`` [N], with the
nut shift ``u`` as the extra unknown.

Power: the screw is at rest, so all the friction loss is put in by the nut,
``P_in = omega_N sum_nut (F_f,i . H(r_i) + M_i . z_hat)`` (normal forces do no
work on the helical field: ``n_i . H(r_i) = 0``).  ``P_in = sum_i P_f,i`` holds
to the Newton tolerance in every solve (tests); the friction torque is
``P / omega_N``.

Newton with the analytic Jacobian: every quantity carries its derivatives
with respect to the ball's unknowns and ``u`` (forward-mode chain rule,
:class:`_Dual`), through the Jacobian of ``friction_offset``; globalised by
the Levenberg-Marquardt ``newton`` of :mod:`lowmodel.solvers`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.lowmodel.screw.convergence import row_tolerances, row_weights, stall_reason
from ballbench.lowmodel.geometry import helix

__all__ = [
    "CONTACT_NAMES", "DEVIATION_READINGS", "ScrewModule", "screw_module", "BallContacts", "ball_contacts",
    "ScrewBallState", "solve_balls", "profile_2d", "arc_profile", "N_UNKNOWNS", "ball_terms",
    "free_rolling_guess", "scales_for", "solve_preloaded", "continuation_start", "reference_force",
    "state_from", "Scales", "BallTerms", "hertz_direct", "FRICTION_LEVEL", "GrooveContactLaws", "NUT_SPEED_RANGE",
    "FRICTION_COEFFICIENT_MAX",
]

CONTACT_NAMES = ("SL", "SR", "NR", "NL")  # lin2019 eq 54 order
DEVIATION_READINGS = ("rotated", "tilted")
FRICTION_COEFFICIENT_MAX = 2.0  # mu in (0, 2]: residuals are scaled by mu F (friction would swamp the normal forces)
NUT_SPEED_RANGE = (1e-100, 1e100)  # |omega_N| [rad/s]: quasi-static, any speed; the floats set the range
N_UNKNOWNS = 6  # per ball: x_B3, z_B3, omega_B, omega_x, omega_y, omega_z
# tanh-sinh level of friction_offset: 3 where every b/a >= 0.2 (measured error < 3e-8 there, tests), else 4
FRICTION_LEVEL = {"coarse": 3, "fine": 4, "coarse_min_b_over_a": 0.2}
_BODY = ("screw", "screw", "nut", "nut")
_FLANK = ("left", "right", "right", "left")
_ON_NUT = np.array([0.0, 0.0, 1.0, 1.0])
_SIGN_U = np.array([-1.0, -1.0, 1.0, 1.0])
_SIGN_W = np.array([-1.0, 1.0, 1.0, -1.0])


# --------------------------------------------------------------------------
# module and contacts
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class ScrewModule:
    """Ball-screw parameters (SI; lin2019 Table 4 defaults in :func:`screw_module`).

    ball_radius, pitch_radius, lead [m]; conformity; nominal_angle [rad] (beta_0);
    nut_speed [rad/s] (omega_N about +z); friction_coefficient mu;
    youngs_modulus [Pa], poisson_ratio; oversize [m] (preload: approach of every
    contact of a centred ball, 0 = exact fit).
    """

    ball_radius: float
    conformity: float
    pitch_radius: float
    lead: float
    nominal_angle: float
    nut_speed: float
    friction_coefficient: float
    youngs_modulus: float
    poisson_ratio: float
    oversize: float

    @property
    def lead_angle(self) -> float:
        """``alpha = atan(lead / (2 pi R_P))`` [rad] (lin2019 eq 42, :func:`helix.lead_angle`)."""
        return float(helix.lead_angle(self.lead, self.pitch_radius))

    @property
    def lead_per_radian(self) -> float:
        """``p = lead / (2 pi)`` [m/rad] (lin2019 eq 34's r_g)."""
        return float(helix.helix_parameter(self.lead))

    @property
    def helix_radius(self) -> float:
        """``L / (2 pi) = sqrt(R_P^2 + p^2)`` [m] (lin2019 eq 45)."""
        return math.hypot(self.pitch_radius, self.lead_per_radian)

    @property
    def groove_radius(self) -> float:
        return 2.0 * self.conformity * self.ball_radius


def screw_module(*, ball_radius: float = 2.778e-3, conformity: float = 0.56, pitch_radius: float = 16.5e-3,
                 lead: float = 20e-3, nominal_angle: float = math.radians(45.0), nut_speed: float = 2 * math.pi,
                 friction_coefficient: float = 0.1, youngs_modulus: float = 2.1e11, poisson_ratio: float = 0.28,
                 oversize: float = 0.0) -> ScrewModule:
    """Validated :class:`ScrewModule`; defaults are lin2019 Table 4 (E = 210 GPa, papers/README)."""
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    conformity = checks.conformity("conformity", conformity)
    pitch_radius = checks.positive("pitch_radius", pitch_radius, "m")
    lead = checks.non_negative("lead", lead, "m (right-handed screw)")
    nominal_angle = checks.contact_angle("nominal_angle", nominal_angle)
    nut_speed = checks.finite("nut_speed", nut_speed, "rad/s")
    if not NUT_SPEED_RANGE[0] <= abs(nut_speed) <= NUT_SPEED_RANGE[1]:
        raise ValueError(f"nut_speed must satisfy {NUT_SPEED_RANGE[0]:g} <= |nut_speed| <= {NUT_SPEED_RANGE[1]:g} "
                         f"rad/s (nonzero: the ball motion is undetermined at rest; the friction Jacobian scales "
                         f"like 1 / speed and leaves the float range near 1e-300), got {nut_speed!r}")
    mu = checks.bounded("friction_coefficient", friction_coefficient, 0.0, FRICTION_COEFFICIENT_MAX, upper_closed=True,
                        note="Coulomb friction of steel contacts; equilibrium is solved to a tolerance in mu F")
    youngs_modulus = checks.positive("youngs_modulus", youngs_modulus, "Pa")
    poisson_ratio = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5)
    oversize = checks.bounded("oversize", oversize, 0.0, 0.01 * ball_radius, "m", lower_closed=True,
                              upper_closed=True, note="i.e. [0, 0.01 ball_radius]")
    if pitch_radius <= 2.0 * conformity * ball_radius:
        raise ValueError(f"pitch_radius must exceed the groove radius {2 * conformity * ball_radius!r} m, "
                         f"got {pitch_radius!r}")
    if not helix.lead_angle(lead, pitch_radius) < 0.5 * math.pi:
        raise ValueError(f"lead must give a lead angle below pi/2 rad with pitch_radius {pitch_radius!r} m "
                         f"(atan(lead / (2 pi pitch_radius)) rounds to 90 deg), got {lead!r}")
    return ScrewModule(ball_radius, conformity, pitch_radius, lead, nominal_angle, nut_speed, mu, youngs_modulus,
                       poisson_ratio, oversize)


@dataclass(frozen=True)
class BallContacts:
    """Flank geometry and Hertz constants of ``n`` balls, arrays of shape ``(n, 4)`` in (SL, SR, NR, NL).

    contact_angles : rad, the flank's contact angle with a centred ball (beta_0 + deviation)
    arc_centres : (n, 4, 2) m, ``(x3, z3)`` of the flank arc centres at nut shift 0
    hertz_constant : m N^(-2/3), ``C_i`` of lin2019 eq 53
    semi_major_unit : m N^(-1/3), ``a_i = semi_major_unit F_i^(1/3)``
    b_over_a : Hertz axis ratio
    deviation : (n,) rad, the screw-side contact angle deviation theta of each ball
    bulk_compliance : m/N, ``C_b`` of a calibrated law ``delta = C F^(2/3) + C_b F``; None: Hertz (eq 53)
    """

    module: ScrewModule
    contact_angles: np.ndarray
    arc_centres: np.ndarray
    hertz_constant: np.ndarray
    semi_major_unit: np.ndarray
    b_over_a: np.ndarray
    deviation: np.ndarray
    bulk_compliance: np.ndarray | None = None

    @property
    def n_balls(self) -> int:
        return self.contact_angles.shape[0]


def _hertz_of(module: ScrewModule, angle, body: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(C, a per F^(1/3), b/a) of a ball on a helical flank at contact angles ``angle`` (normal profile).

    Interpolated (cubic spline) from :func:`lowmodel.contact.hertz.ball_in_screw_groove` on a 0.25 deg grid
    of contact angles covering beta_0 +- 15 deg (measured agreement with the direct solution 1e-10 relative,
    tests); exact at the nodes, beta_0 among them.
    """
    table = _hertz_table(module.ball_radius, module.conformity, module.pitch_radius, module.lead_angle,
                         module.nominal_angle, body, module.youngs_modulus, module.poisson_ratio)
    return tuple(spline(angle) for spline in table)


_HERTZ_STEP = math.radians(0.25)


@lru_cache(maxsize=32)
def _hertz_table(ball_radius, conformity, pitch_radius, lead_angle, nominal_angle, body, youngs_modulus,
                 poisson_ratio):
    from scipy.interpolate import CubicSpline

    low = max(nominal_angle - groove_core.MAX_DEVIATION, 1e-3)
    high = min(nominal_angle + groove_core.MAX_DEVIATION, 0.5 * math.pi - 1e-3)
    below = np.arange(nominal_angle, low, -_HERTZ_STEP)[::-1]
    above = np.arange(nominal_angle + _HERTZ_STEP, high, _HERTZ_STEP)
    angles = np.concatenate([below, above])
    values = np.array([hertz_direct(ball_radius, conformity, pitch_radius, lead_angle, float(a), body,
                                    youngs_modulus, poisson_ratio) for a in angles])
    return tuple(CubicSpline(angles, values[:, q]) for q in range(3))


def hertz_direct(ball_radius, conformity, pitch_radius, lead_angle, angle, body, youngs_modulus, poisson_ratio):
    """(C [m N^-2/3], a per F^(1/3) [m N^-1/3], b/a) from :func:`hertz.ball_in_screw_groove` (no table)."""
    from ballbench.lowmodel.contact import hertz

    geometry = hertz.ball_in_screw_groove(ball_radius, conformity, pitch_radius, angle, lead_angle, body,
                                          youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)
    unit = hertz.solve_load(geometry, 1.0)
    return hertz.hertz_constant(geometry), float(unit.a), float(unit.b / unit.a)


def flank_angles(nominal_angle: float, deviation, reading: str = "tilted") -> np.ndarray:
    """Contact angles (n, 4) of (SL, SR, NR, NL) with the screw-side deviation ``theta`` [rad].

    ``reading`` (lin2019 Fig 17 is missing; docs/ball_screw.md):

    * ``"rotated"``: the screw's gothic-arch profile turned by ``theta``
      about the ball centre, ``beta_SL = beta_0 + theta``, ``beta_SR = beta_0 - theta``
      (the linear-bearing deviation of lin2019 Fig 7, Delta beta_BL = -Delta beta_BR);
    * ``"tilted"`` (default): both screw flanks tilted, ``beta_SL = beta_SR = beta_0 + theta``; the
      reading that reproduces lin2019 Table 5 (docs/ball_screw.md).

    The nut flanks keep ``beta_0``.
    """
    shape = checks.real("deviation", deviation).shape
    if len(shape) > 1 or 0 in shape:
        raise ValueError(f"deviation must be one theta [rad] or a 1-D array of one per ball (at least one), got "
                         f"shape {shape}")
    theta = np.atleast_1d(checks.bounded("deviation", deviation, -groove_core.MAX_DEVIATION,
                                         groove_core.MAX_DEVIATION, "rad", lower_closed=True, upper_closed=True,
                                         note="i.e. [-15, 15] deg"))
    reading = checks.choice("reading", reading, DEVIATION_READINGS)
    angles = np.full((theta.size, 4), float(nominal_angle))
    angles[:, 0] += theta
    angles[:, 1] += -theta if reading == "rotated" else theta
    checks.contact_angle("nominal_angle + deviation", angles)
    return angles


@dataclass(frozen=True)
class GrooveContactLaws:
    """Calibrated contact laws of the screw and the nut groove (issue 13, docs/calibration.md).

    ``screw``, ``nut``: :class:`lowmodel.calibration.ContactLaw` of each groove, ``delta = C F^(2/3) + C_b F``
    (lin2019 eq 53 plus the finite-body compliance ``C_b``) and ``a = Psi R_B^(1/3) F^(1/3)`` (eq 15), fitted
    at the nominal contact angle (e.g. FE load sweeps of ``fe-hertz-screw`` / ``fe-hertz-nut``).
    :func:`ball_contacts` scales the Hertz ``C`` and ``a / F^(1/3)`` of every flank by calibrated / Hertz
    of its groove (the ``reference`` stored with each constant, else Hertz of the module at beta_0), so
    the dependence on the contact angle stays Hertz's, and adds ``C_b``.  Hertz's b/a is kept.
    """

    screw: object
    nut: object

    @classmethod
    def from_calibration(cls, calibration, screw_group: str = "screw-groove",
                         nut_group: str = "nut-groove") -> "GrooveContactLaws":
        """The laws of the groups ``screw_group`` and ``nut_group`` of a :class:`lowmodel.calibration.Calibration`."""
        from ballbench.lowmodel.calibration import ContactLaw

        def law(group):
            psi = calibration.constants.get(group, {}).get("psi")
            return ContactLaw(calibration.get(group, "hertz_constant"), calibration.get(group, "bulk_compliance"),
                              psi)

        return cls(law(screw_group), law(nut_group))

    def factors(self, module: ScrewModule, body: str) -> tuple[float, float, float]:
        """(C calibrated / Hertz, a calibrated / Hertz, C_b [m/N]) of the ``body`` groove."""
        law = self.screw if body == "screw" else self.nut
        c_hertz, a_unit, _ = hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                          module.lead_angle, module.nominal_angle, body, module.youngs_modulus,
                                          module.poisson_ratio)
        c_ref = law.hertz_constant.reference or c_hertz
        c_factor = law.hertz_constant.value / c_ref
        a_factor = 1.0
        if law.psi is not None:  # eq 15: a / F^(1/3) = Psi R_B^(1/3)
            a_factor = law.psi.value / (law.psi.reference or a_unit / module.ball_radius ** (1.0 / 3.0))
        for name, factor in (("hertz_constant", c_factor), ("psi", a_factor)):
            if not (0.5 < factor < 2.0):
                raise ValueError(f"the calibrated {name} of the {body} groove must lie within a factor 2 of Hertz's, "
                                 f"got the ratio {factor!r} (a calibration of another geometry?)")
        return c_factor, a_factor, float(law.bulk_compliance.value)


def ball_contacts(module: ScrewModule, deviation=0.0, reading: str = "tilted", *,
                  contact_law: GrooveContactLaws | None = None) -> BallContacts:
    """Contacts of ``n`` balls with screw-side deviations ``deviation`` [rad], shape () or (n,).

    Flank arcs from the geometry core (:class:`groove.HelicalGroove`, normal profile),
    Hertz constants from :func:`lowmodel.contact.hertz.ball_in_screw_groove` with the
    helical groove curvatures at each flank's contact angle (spline on a 0.25 deg grid, :func:`_hertz_of`).
    ``contact_law``: calibrated laws of the screw and nut grooves (:class:`GrooveContactLaws`); None: Hertz.
    """
    angles = flank_angles(module.nominal_angle, deviation, reading)
    n = angles.shape[0]
    centres = np.empty((n, 4, 2))
    constant = np.empty((n, 4))
    unit = np.empty((n, 4))
    ratio = np.empty((n, 4))
    for i in range(4):
        try:
            constant[:, i], unit[:, i], ratio[:, i] = _hertz_of(module, angles[:, i], _BODY[i])
        except ValueError as error:   # e.g. conformity next to 0.5: the flank conforms with the ball
            raise ValueError(f"module: no Hertz point contact on flank {CONTACT_NAMES[i]} with conformity "
                             f"{module.conformity!r} ({error})") from None
        for j in range(n):   # angles validated by flank_angles; the core's flank gives the arc centre
            flank = groove_core.HelicalGroove(module.ball_radius, module.conformity, module.pitch_radius,
                                              module.lead, float(angles[j, i]), _BODY[i], _FLANK[i])
            centres[j, i] = flank.arc_centre  # (u, w) = (x3, z3)
    _check_axis_ratio(module, angles, ratio)
    theta = np.broadcast_to(np.asarray(deviation, dtype=float), (n,)).copy()
    bulk = None
    if contact_law is not None:
        bulk = np.empty((n, 4))
        for body in ("screw", "nut"):
            c_factor, a_factor, c_b = contact_law.factors(module, body)
            columns = [i for i in range(4) if _BODY[i] == body]
            constant[:, columns] *= c_factor
            unit[:, columns] *= a_factor
            bulk[:, columns] = c_b
    return BallContacts(module, angles, centres, constant, unit, ratio, theta, bulk)


def _check_axis_ratio(module: ScrewModule, angles: np.ndarray, ratio: np.ndarray) -> None:
    """ValueError naming the module's conformity where a flank's Hertz b/a leaves the friction map's range."""
    from ballbench.lowmodel.contact.ellipse_friction import B_OVER_A_RANGE

    if np.min(ratio) < B_OVER_A_RANGE[0]:
        worst = np.unravel_index(np.argmin(ratio), ratio.shape)
        raise ValueError(f"module: conformity = {module.conformity!r} gives a Hertz axis ratio b/a = "
                         f"{float(ratio[worst]):.4g} on flank {CONTACT_NAMES[worst[1]]} (contact angle "
                         f"{float(angles[worst]):.4g} rad), below {B_OVER_A_RANGE[0]}, the range of the ellipse "
                         f"friction map (lin2019 eqs A4-A7): raise the conformity (about 0.5007 or more)")


def arc_profile(contacts: BallContacts, gamma, nut_shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Closed form of the flank profiles in ``(x3, z3)``: points and d/d gamma, shapes (n, 4, ..., 2).

    ``A_i(gamma) = C_i + r_g (s_u cos gamma, s_w sin gamma) + (0, u cos alpha)`` for the nut flanks;
    ``gamma`` is lin2019's cross-sectional angular variable (eq 48, Fig 15), equal to
    the contact angle at the contact point.
    """
    module = contacts.module
    gamma = np.asarray(checks.finite("gamma", gamma, "rad"), dtype=float)
    nut_shift = checks.finite("nut_shift", nut_shift, "m")
    r_g = module.groove_radius
    shape = (contacts.n_balls, 4) + (1,) * gamma.ndim
    su, sw = _SIGN_U.reshape((1, 4) + (1,) * gamma.ndim), _SIGN_W.reshape((1, 4) + (1,) * gamma.ndim)
    centre = contacts.arc_centres.reshape(shape + (2,))
    shift = nut_shift * math.cos(module.lead_angle) * _ON_NUT.reshape((1, 4) + (1,) * gamma.ndim)
    points = np.stack([centre[..., 0] + r_g * su * np.cos(gamma), centre[..., 1] + r_g * sw * np.sin(gamma) + shift],
                      axis=-1)
    tangent = np.stack([-r_g * su * np.sin(gamma) * np.ones(shape), r_g * sw * np.cos(gamma) * np.ones(shape)],
                       axis=-1)
    return points, tangent


def profile_2d(contacts: BallContacts, ball: int, contact: int, gamma, azimuth: float = 0.0,
               nut_shift: float = 0.0) -> np.ndarray:
    """lin2019 eq 48 literally: the flank surface ``S(azimuth, gamma)`` (plus the nut's axial shift)
    taken into CS3 at the ball's azimuth and projected on ``(x3, z3)``; shape (..., 2) [m].

    Built from the geometry core's exact helical surface
    (:meth:`groove.HelicalGroove.surface`), not from :func:`arc_profile` (tests compare them).
    """
    module = contacts.module
    ball = checks.count("ball", ball, 0, contacts.n_balls - 1)
    contact = checks.count("contact", contact, 0, 3)
    azimuth = checks.finite("azimuth", azimuth, "rad")
    nut_shift = checks.finite("nut_shift", nut_shift, "m")
    flank = groove_core.helical_groove(module.ball_radius, module.conformity, module.pitch_radius, module.lead,
                                       float(contacts.contact_angles[ball, contact]), _BODY[contact],
                                       _FLANK[contact])
    gamma = np.asarray(checks.finite("gamma", gamma, "rad"), dtype=float)
    direction = np.stack([_SIGN_U[contact] * np.cos(gamma), _SIGN_W[contact] * np.sin(gamma)], axis=-1)
    theta = np.arctan2(direction[..., 1], direction[..., 0])  # the core's arc angle
    surface = flank.surface(theta, azimuth)
    if _ON_NUT[contact]:
        surface = surface + np.array([0.0, 0.0, nut_shift])
    frame = helix.cs3_frame(azimuth, module.lead_angle)
    local = np.einsum("ji,...j->...i", frame, surface - helix.ball_centre(azimuth, module.pitch_radius, module.lead))
    return local[..., [0, 2]]


# --------------------------------------------------------------------------
# forward-mode derivatives
# --------------------------------------------------------------------------
class _Dual:
    """Value ``v`` (shape (m,)) with its gradient ``g`` (shape (m, k)): exact chain rule."""

    __slots__ = ("v", "g")

    def __init__(self, v, g):
        self.v = v
        self.g = g

    def __add__(self, other):
        if isinstance(other, _Dual):
            return _Dual(self.v + other.v, self.g + other.g)
        return _Dual(self.v + other, self.g)

    __radd__ = __add__

    def __sub__(self, other):
        if isinstance(other, _Dual):
            return _Dual(self.v - other.v, self.g - other.g)
        return _Dual(self.v - other, self.g)

    def __rsub__(self, other):
        return _Dual(other - self.v, -self.g)

    def __neg__(self):
        return _Dual(-self.v, -self.g)

    def __mul__(self, other):
        if isinstance(other, _Dual):
            return _Dual(self.v * other.v, self.g * other.v[:, None] + other.g * self.v[:, None])
        other = np.asarray(other, dtype=float)
        return _Dual(self.v * other, self.g * (other[..., None] if other.ndim else other))

    __rmul__ = __mul__

    def __truediv__(self, other):
        if isinstance(other, _Dual):
            inv = 1.0 / other.v
            return _Dual(self.v * inv, (self.g - other.g * (self.v * inv)[:, None]) * inv[:, None])
        return self * (1.0 / np.asarray(other, dtype=float))

    def sqrt(self):
        root = np.sqrt(self.v)
        return _Dual(root, self.g * (0.5 / root)[:, None])


def _const(value, k: int) -> _Dual:
    value = np.asarray(value, dtype=float)
    return _Dual(value, np.zeros(value.shape + (k,)))


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


# --------------------------------------------------------------------------
# residual of eq 54 for every ball, with its Jacobian
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Scales:
    """Units of the scaled unknowns and residuals (per solve)."""

    length: float      # m: x_B3, z_B3, nut shift
    orbit: float       # rad/s: omega_B
    spin: float        # rad/s: omega
    force: float       # N: residual rows (mu F_ref)


def scales_for(contacts: BallContacts, reference_force: float) -> Scales:
    """Scales of one solve: Hertz approach of the reference force, omega_N, omega_N R_P / R_B, mu F_ref."""
    module = contacts.module
    constant = float(np.max(contacts.hertz_constant))
    speed = abs(module.nut_speed)
    return Scales(constant * reference_force ** (2.0 / 3.0), speed, speed * module.pitch_radius / module.ball_radius,
                  module.friction_coefficient * reference_force)


@dataclass(frozen=True)
class BallTerms:
    """Per-ball residual of eq 54 (n, 6) in units ``Scales.force`` (moments / R_B) and Jacobian (n, 6, 7)
    with respect to the 6 scaled ball unknowns and the scaled nut shift; ``axial`` (n,) the scaled axial
    force of the screw on each ball and its gradient (n, 7); contact quantities (n, 4) in SI."""

    residual: np.ndarray
    jacobian: np.ndarray
    axial: np.ndarray
    axial_gradient: np.ndarray
    normal_force: np.ndarray
    contact_direction: np.ndarray   # (n, 4, 2): e_i in (x3, z3)
    approach: np.ndarray
    semi_major: np.ndarray
    spin: np.ndarray                # omega_i [rad/s] about the inward normal
    slip_minor: np.ndarray          # m/s
    slip_major: np.ndarray
    friction_force: np.ndarray      # (n, 4, 3) N in CS3
    friction_moment: np.ndarray     # (n, 4, 3) N m about the contact centre, CS3
    friction_loss: np.ndarray       # (n, 4) W (eq A6 with the offset, friction_offset)
    input_power: np.ndarray         # (n,) W put in by the nut through each ball


def ball_terms(unknowns: np.ndarray, nut_shift: float, contacts: BallContacts, scales: Scales, *,
               oversize: float | None = None) -> BallTerms:
    """lin2019 eqs 36-54 for every ball at scaled ``unknowns`` (n, 6) and scaled ``nut_shift`` (scalar or (n,)).

    Unknowns: ``(x_B3, z_B3)/length``, ``omega_B/orbit``, ``(omega_x, omega_y, omega_z)/spin``.
    ``oversize`` [m] overrides the module's preload (continuation).
    """
    from ballbench.lowmodel.contact.ellipse_friction_offset import friction_offset

    module = contacts.module
    n = unknowns.shape[0]
    m = 4 * n
    k = N_UNKNOWNS + 1
    radius = module.ball_radius
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    z_hat = (0.0, s, c)

    def var(column, scale):
        value = np.repeat(unknowns[:, column] * scale, 4)
        grad = np.zeros((m, k))
        grad[:, column] = scale
        return _Dual(value, grad)

    x_b, z_b = var(0, scales.length), var(1, scales.length)
    orbit = var(2, scales.orbit)
    omega = (var(3, scales.spin), var(4, scales.spin), var(5, scales.spin))
    shift = _Dual(np.repeat(np.broadcast_to(np.asarray(nut_shift, dtype=float), (n,)) * scales.length, 4),
                  np.zeros((m, k)))
    shift.g[:, N_UNKNOWNS] = scales.length
    on_nut = np.tile(_ON_NUT, n)
    centre = contacts.arc_centres.reshape(m, 2)
    # eqs 49-53 in closed form: direction from the arc centre through the ball centre
    dx = x_b - centre[:, 0]
    dz = z_b - (shift * (c * on_nut)) - centre[:, 1]
    distance = (dx * dx + dz * dz).sqrt()
    ex, ez = dx / distance, dz / distance
    preload = module.oversize if oversize is None else oversize
    approach = distance + (radius + preload - module.groove_radius)
    hertz_c = contacts.hertz_constant.reshape(m)
    loaded = approach.v > 0.0
    if contacts.bulk_compliance is None:
        ratio = np.where(loaded, approach.v, 0.0) / hertz_c
        force_v = ratio**1.5
        force = _Dual(force_v, approach.g * (1.5 * np.sqrt(ratio) / hertz_c)[:, None])  # eq 53
    else:  # calibrated law delta = C F^(2/3) + C_b F (eq 53 + finite-body compliance), lowmodel.calibration
        from ballbench.lowmodel.calibration import law_force

        force_v, slope = law_force(approach.v, hertz_c, contacts.bulk_compliance.reshape(m))
        force = _Dual(force_v, approach.g * slope[:, None])
    semi = _Dual(contacts.semi_major_unit.reshape(m) * np.cbrt(force_v), np.zeros((m, k)))
    with np.errstate(divide="ignore", invalid="ignore"):
        da_dF = np.where(loaded, semi.v / (3.0 * np.where(loaded, force_v, 1.0)), 0.0)
    semi.g = force.g * da_dF[:, None]
    # kinematics (module docstring): q = R_B e, W = (omega_B - Omega_g) z_hat + omega
    relative = orbit - module.nut_speed * on_nut
    q = (ex * radius, _const(np.zeros(m), k), ez * radius)
    helical = (q[2] * s, q[0] * c + module.helix_radius, q[0] * (-s))
    spin_vector = tuple(relative * z_hat[j] + omega[j] for j in range(3))
    turn = _cross(omega, q)
    slip = tuple(relative * helical[j] + turn[j] for j in range(3))
    inward = (-ex, _const(np.zeros(m), k), -ez)
    major = (ez, _const(np.zeros(m), k), -ex)          # n_i x y3
    spin = _dot(spin_vector, inward)                    # omega_i about the inward normal
    spin_velocity = spin * semi
    slip_minor = slip[1]
    slip_major = _dot(slip, major)
    mu = module.friction_coefficient
    fr_force_major = _const(np.zeros(m), k)
    fr_force_minor = _const(np.zeros(m), k)
    fr_moment = _const(np.zeros(m), k)
    loss_unit = np.zeros(m)
    idx = np.flatnonzero(loaded)
    if idx.size:
        ratio_ba = contacts.b_over_a.reshape(m)[idx]
        level = FRICTION_LEVEL["coarse" if ratio_ba.min() >= FRICTION_LEVEL["coarse_min_b_over_a"] else "fine"]
        fr = friction_offset(spin_velocity.v[idx], slip_minor.v[idx], slip_major.v[idx], ratio_ba, level=level)
        jac = fr.jacobian
        grads = (spin_velocity.g[idx], slip_minor.g[idx], slip_major.g[idx])
        for target, row in ((fr_force_major, 0), (fr_force_minor, 1), (fr_moment, 2)):
            target.v[idx] = (fr.force_major, fr.force_minor, fr.moment)[row]
            target.g[idx] = sum(jac[:, row, j, None] * grads[j] for j in range(3))
        loss_unit[idx] = fr.loss
    mu_force = force * mu
    f_major, f_minor = fr_force_major * mu_force, fr_force_minor * mu_force
    friction = tuple(major[j] * f_major for j in range(3))
    friction = (friction[0], friction[1] + f_minor, friction[2])
    moment_mag = fr_moment * mu_force * semi              # about major x minor = -n_i = e_i
    contact_moment = (ex * moment_mag, _const(np.zeros(m), k), ez * moment_mag)
    arm_moment = _cross(q, friction)
    normal = (ex * (-1.0) * force, _const(np.zeros(m), k), ez * (-1.0) * force)
    total_force = tuple(normal[j] + friction[j] for j in range(3))
    total_moment = tuple(arm_moment[j] + contact_moment[j] for j in range(3))
    rows = [total_force[0], total_force[1], total_force[2]] + [t * (1.0 / radius) for t in total_moment]
    residual = np.empty((n, 6))
    jacobian = np.empty((n, 6, k))
    for r, quantity in enumerate(rows):
        residual[:, r] = quantity.v.reshape(n, 4).sum(axis=1) / scales.force
        jacobian[:, r] = quantity.g.reshape(n, 4, k).sum(axis=1) / scales.force
    axial_contrib = _dot(total_force, z_hat) * (1.0 - on_nut)
    axial = axial_contrib.v.reshape(n, 4).sum(axis=1) / scales.force
    axial_gradient = axial_contrib.g.reshape(n, 4, k).sum(axis=1) / scales.force
    # power put in by the nut (screw at rest): omega_N sum_nut (F_f . H + M . z_hat)
    nut_power = (_dot(friction, helical).v + _dot(contact_moment, z_hat).v) * module.nut_speed * on_nut
    loss = mu * force_v * loss_unit
    return BallTerms(residual, jacobian, axial, axial_gradient, force_v.reshape(n, 4),
                     np.stack([ex.v, ez.v], axis=-1).reshape(n, 4, 2), approach.v.reshape(n, 4),
                     semi.v.reshape(n, 4), spin.v.reshape(n, 4), slip_minor.v.reshape(n, 4),
                     slip_major.v.reshape(n, 4),
                     np.stack([f.v for f in friction], axis=-1).reshape(n, 4, 3),
                     np.stack([f.v for f in contact_moment], axis=-1).reshape(n, 4, 3),
                     loss.reshape(n, 4), nut_power.reshape(n, 4).sum(axis=1))


# --------------------------------------------------------------------------
# solution
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class ScrewBallState:
    """Quasi-static state of ``n`` balls (leading shape (n,); contacts (SL, SR, NR, NL)).

    centre : (n, 2) m, ball centre ``(x_B3, z_B3)`` from the nominal helix
    orbit_speed : (n,) rad/s, ``omega_B``; omega : (n, 3) rad/s, spin relative to CS3
    nut_shift : m, axial shift of the nut relative to the screw (scalar, or (n,) per ball)
    normal_force : (n, 4) N; contact_angle : (n, 4) rad (actual); approach : (n, 4) m
    semi_major : (n, 4) m; spin : (n, 4) rad/s about the inward normal; slip_minor, slip_major : (n, 4) m/s
    friction_force : (n, 4, 3) N; friction_moment : (n, 4, 3) N m (CS3, on the ball)
    friction_loss : (n, 4) W; input_power : W (by the nut); b2b_force : (n-1,) N;
    b2b_friction_loss : (n-1,) W; iterations; residual (max scaled residual)
    """

    centre: np.ndarray
    orbit_speed: np.ndarray
    omega: np.ndarray
    nut_shift: float
    normal_force: np.ndarray
    contact_angle: np.ndarray
    approach: np.ndarray
    semi_major: np.ndarray
    spin: np.ndarray
    slip_minor: np.ndarray
    slip_major: np.ndarray
    friction_force: np.ndarray
    friction_moment: np.ndarray
    friction_loss: np.ndarray
    input_power: float
    axial_load: float
    b2b_force: np.ndarray
    b2b_friction_loss: np.ndarray
    iterations: int
    residual: float

    @property
    def groove_loss(self) -> float:
        """Ball-to-groove friction loss [W]."""
        return float(self.friction_loss.sum())

    @property
    def total_loss(self) -> float:
        """Ball-to-groove plus ball-to-ball friction loss [W]."""
        return float(self.friction_loss.sum() + self.b2b_friction_loss.sum())


def _contact_angles(direction: np.ndarray) -> np.ndarray:
    return np.arctan2(_SIGN_W * direction[..., 1], _SIGN_U * direction[..., 0])


def free_rolling_guess(contacts: BallContacts) -> np.ndarray:
    """Orbit and spin (n, 4) [rad/s] with least-squares zero slip at the four nominal contact centres."""
    module = contacts.module
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    guess = np.empty((contacts.n_balls, 4))
    for j in range(contacts.n_balls):
        rows, rhs = [], []
        for i in range(4):
            beta = contacts.contact_angles[j, i]
            e = np.array([_SIGN_U[i] * math.cos(beta), 0.0, _SIGN_W[i] * math.sin(beta)])
            q = module.ball_radius * e
            helical = np.array([s * q[2], module.helix_radius + c * q[0], -s * q[0]])
            # slip = (omega_B - Omega) H + omega x q; omega x q = -[q]x omega
            skew = np.array([[0.0, -q[2], q[1]], [q[2], 0.0, -q[0]], [-q[1], q[0], 0.0]])
            block = np.column_stack([helical, -skew])
            rows.append(block)
            rhs.append(module.nut_speed * _ON_NUT[i] * helical)
        solution = np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]
        guess[j] = solution
    return guess


def solve_balls(contacts: BallContacts, axial_load: float, *, tolerance: float = 1e-10,
                max_iterations: int = 80) -> ScrewBallState:
    """Each ball on its own (no ball-to-ball contact) under ``axial_load`` [N] per ball (lin2019 eqs 49-55).

    ``axial_load``: force of the screw on each ball along +z [N], one number (its sign picks the
    loaded diagonal); the nut shift is solved for it, ball by ball: ``nut_shift`` of the result is
    (n,), one per ball (a float for one ball).  ``tolerance``:
    max residual of eq 54 in units of ``mu F_ref`` (F_ref = |axial_load| / (sin beta_0 cos alpha) / 2
    for the loaded pair, forces and moments / R_B) and of the axial balance.
    Raises ConvergenceError with its residual if Newton fails.
    """
    from ballbench.lowmodel.solvers import check_solver_options

    check_solver_options(tolerance, max_iterations)
    load = checks.scalar("axial_load", axial_load, "N", note="the load on each ball")
    states = [_solve_one(contacts, j, load, tolerance, max_iterations) for j in range(contacts.n_balls)]
    return _stack(states, contacts)


def reference_force(contacts: BallContacts, axial_load: float) -> float:
    """Normal force scale [N]: the axial load over one loaded pair, at least the preload force."""
    module = contacts.module
    load = checks.scalar("axial_load", axial_load, "N")
    with np.errstate(over="ignore"):
        pair = abs(load) / np.float64(math.sin(module.nominal_angle) * math.cos(module.lead_angle))
    preload = (module.oversize / float(np.min(contacts.hertz_constant))) ** 1.5 if module.oversize > 0 else 0.0
    force = checks.finite_result("axial_load", max(pair, preload, 1e-3), "N")
    with np.errstate(over="ignore"):
        approach = float(float(np.max(contacts.hertz_constant)) * np.float64(force) ** (2.0 / 3.0))  # lin2019 eq 53
    if not approach < module.ball_radius:
        raise ValueError(f"axial_load: its Hertz approach {approach!r} m (per loaded pair, {float(force)!r} N) "
                         f"exceeds the ball radius {module.ball_radius!r} m: no Hertz contact at this load, "
                         f"got {axial_load!r} N")
    return force


def _solve_one(contacts: BallContacts, index: int, axial_load: float, tolerance: float, max_iterations: int):
    """One ball with its own nut shift (:func:`solve_preloaded`)."""
    single = _single(contacts, index)
    scales = scales_for(single, reference_force(single, axial_load))
    guess = np.zeros(N_UNKNOWNS + 1)
    rates = free_rolling_guess(single)[0]
    guess[2] = rates[0] / scales.orbit
    guess[3:6] = rates[1:] / scales.spin
    target = axial_load / scales.force

    def make_function(oversize):
        def function(z):
            terms = ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales, oversize=oversize)
            residual = np.concatenate([terms.residual[0], [terms.axial[0] - target]])
            jacobian = np.vstack([terms.jacobian[0], terms.axial_gradient[0][None, :]])
            return residual, jacobian
        return function

    rows = row_tolerances(tolerance, friction_coefficient=single.module.friction_coefficient,
                          groove_radius=single.module.groove_radius, ball_radius=single.module.ball_radius,
                          approach=scales.length, balls=1, axial=1)
    z, residual, iterations = solve_preloaded(
        make_function, guess, single, axial_load, tolerance=tolerance, max_iterations=max_iterations,
        what=f"screw ball {index}", row_tolerance=rows,
        row_weight=row_weights(friction_coefficient=single.module.friction_coefficient, balls=1, axial=1),
        contacts_at=lambda z, oversize: ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales,
                                                   oversize=oversize))
    terms = ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales)
    return z, terms, scales, iterations, float(np.max(np.abs(residual))), axial_load


def continuation_start(contacts: BallContacts, axial_load: float) -> float:
    """Oversize [m] where the preload continuation starts: twice the approach of the reference force,
    so that all four contacts stay loaded (well-conditioned four-point state)."""
    with np.errstate(over="ignore"):
        start = 2.0 * float(np.max(contacts.hertz_constant)) * np.float64(reference_force(contacts, axial_load)) ** (
            2.0 / 3.0)
    return checks.finite_result("axial_load", start, "m")


def solve_preloaded(make_function, guess: np.ndarray, contacts: BallContacts, load_per_ball: float, *,
                    tolerance: float, max_iterations: int, what: str, steps: int = 6, max_halvings: int = 10,
                    step_iterations: int = 15, direct_fraction: float = 0.2, direct_iterations: int = 12,
                    row_tolerance=None, row_weight=None, contacts_at=None):
    """Newton (:func:`lowmodel.solvers.newton`) on ``make_function(oversize)`` at the module's preload.

    Between ``direct_fraction`` and half of :func:`continuation_start` Newton is tried
    directly for ``direct_iterations``.  Below (little or no preload: two- and three-point
    contact, where Newton from free rolling wanders) or if that fails, the solve starts at that
    four-point preload and steps the oversize down to the module's value, each step
    from the previous solution (step grown 1.5x after a success, halved after a failure).
    ``row_tolerance``, ``row_weight``: per-row tolerances and step weights for :func:`lowmodel.solvers.newton`
    (:func:`.convergence.row_tolerances`, :func:`.convergence.row_weights`);
    ``contacts_at(z, oversize)``: the :class:`BallTerms` (or any object with ``normal_force``, ``slip_minor``,
    ``spin``, ``semi_major``) at a converged point, from which a stall's reason is read
    (:func:`.convergence.stall_reason`).  Returns ``(z, residual, iterations)``; ConvergenceError if a step keeps
    failing.
    """
    from functools import partial

    from ballbench.lowmodel.solvers import newton

    newton = partial(newton, row_tolerance=row_tolerance, row_weight=row_weight)
    target = contacts.module.oversize
    start = continuation_start(contacts, load_per_ball)
    if target >= 0.5 * start:
        return newton(make_function(target), guess, tolerance=tolerance, max_iterations=max_iterations, what=what)
    if target >= direct_fraction * start:   # some preload: try Newton directly, briefly
        try:
            return newton(make_function(target), guess, tolerance=tolerance,
                          max_iterations=min(direct_iterations, max_iterations), what=what)
        except ConvergenceError:
            pass
    z, residual, total = newton(make_function(start), guess, tolerance=tolerance, max_iterations=max_iterations,
                                what=what)
    current, step, halvings = start, (start - target) / steps, 0
    while current > target:
        trial = max(target, current - step)
        try:
            z_new, residual, iterations = newton(make_function(trial), z, tolerance=tolerance,
                                                 max_iterations=min(step_iterations, max_iterations), what=what)
        except ConvergenceError as error:
            halvings += 1
            if halvings > max_halvings:
                reason, detail = "preload continuation stalled", ""
                if contacts_at is not None:
                    terms = contacts_at(z, current)
                    reason, detail = stall_reason(terms.normal_force, terms.slip_minor, terms.spin, terms.semi_major,
                                                  where=f"(oversize {current:.3e} m)")
                    detail = f": {reason}: {detail}"
                raise ConvergenceError(f"{what}: preload continuation stalled at oversize {current:.3e} m "
                                       f"(target {target:.3e} m){detail}", residual=error.residual,
                                       iterations=total, tolerance=tolerance, reason=reason) from None
            step *= 0.5
            continue
        z, current = z_new, trial
        total += iterations
        step *= 1.5
    return z, residual, total


def _single(contacts: BallContacts, index: int) -> BallContacts:
    sl = slice(index, index + 1)
    return BallContacts(contacts.module, contacts.contact_angles[sl], contacts.arc_centres[sl],
                        contacts.hertz_constant[sl], contacts.semi_major_unit[sl], contacts.b_over_a[sl],
                        contacts.deviation[sl],
                        None if contacts.bulk_compliance is None else contacts.bulk_compliance[sl])


def state_from(z_balls: np.ndarray, shift: float, terms: BallTerms, scales: Scales, *, axial_load: float,
               b2b_force=None, b2b_loss=None, iterations: int, residual: float) -> ScrewBallState:
    """ScrewBallState from scaled unknowns (n, 6), the scaled nut shift and the terms at that point."""
    n = z_balls.shape[0]
    if b2b_force is None:
        b2b_force, b2b_loss = np.zeros(max(n - 1, 0)), np.zeros(max(n - 1, 0))
    shift = np.asarray(shift, dtype=float) * scales.length
    return ScrewBallState(z_balls[:, :2] * scales.length, z_balls[:, 2] * scales.orbit, z_balls[:, 3:6] * scales.spin,
                          float(shift) if shift.ndim == 0 else shift, terms.normal_force,
                          _contact_angles(terms.contact_direction),
                          terms.approach, terms.semi_major, terms.spin, terms.slip_minor, terms.slip_major,
                          terms.friction_force, terms.friction_moment, terms.friction_loss,
                          float(terms.input_power.sum()), axial_load, np.asarray(b2b_force, dtype=float),
                          np.asarray(b2b_loss, dtype=float), iterations, residual)


def _stack(states, contacts: BallContacts) -> ScrewBallState:
    """Join single-ball solutions (each with its own nut shift: ``nut_shift`` (n,)) into one state."""
    if len(states) == 1:
        z, terms, scales, iterations, residual, load = states[0]
        return state_from(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], terms, scales, axial_load=load,
                          iterations=iterations, residual=residual)
    parts = [state_from(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], t, sc, axial_load=ld, iterations=it, residual=r)
             for z, t, sc, it, r, ld in states]

    def cat(name):
        return np.concatenate([getattr(p, name) for p in parts])

    n = len(parts)
    return ScrewBallState(cat("centre"), cat("orbit_speed"), cat("omega"),
                          np.array([p.nut_shift for p in parts]), cat("normal_force"), cat("contact_angle"),
                          cat("approach"), cat("semi_major"), cat("spin"), cat("slip_minor"), cat("slip_major"),
                          cat("friction_force"), cat("friction_moment"), cat("friction_loss"),
                          float(sum(p.input_power for p in parts)), float(sum(p.axial_load for p in parts)),
                          np.zeros(n - 1), np.zeros(n - 1), max(p.iterations for p in parts),
                          max(p.residual for p in parts))
