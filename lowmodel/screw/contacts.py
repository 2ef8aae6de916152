"""The ball-screw module and the contacts of its balls (lin2019 Sec 3.1, eqs 34-53, Table 4): the inputs
of the ball model :mod:`lowmodel.screw.ball`.

:class:`ScrewModule` holds the parameters (lin2019 Table 4 defaults in :func:`screw_module`);
:class:`BallContacts` the flank geometry and Hertz constants of the four contacts of ``n`` balls
(:func:`ball_contacts`, from the geometry core and :mod:`lowmodel.contact.hertz`, or calibrated contact
laws, :class:`GrooveContactLaws`); :func:`arc_profile` and :func:`profile_2d` the flank profiles.

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
Signs per contact: :data:`SIGN_U`, :data:`SIGN_W` and :data:`ON_NUT` (1 on the nut's flanks).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from ballbench.lowmodel import checks, model_inputs
from ballbench.lowmodel.bearing import BallScrew, Material
from ballbench.lowmodel.calibration import ContactLaw
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.cubic_pieces import cubic_pieces
from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.model_inputs import FRICTION_COEFFICIENT_MAX, NUT_SPEED_RANGE  # their home; named here too

__all__ = [
    "CONTACT_NAMES", "DEVIATION_READINGS", "ScrewModule", "module", "screw_module", "BallContacts", "ball_contacts",
    "flank_angles", "profile_2d", "arc_profile", "hertz_direct", "GrooveContactLaws", "NUT_SPEED_RANGE",
    "FRICTION_COEFFICIENT_MAX", "SIGN_U", "SIGN_W", "ON_NUT",
]

CONTACT_NAMES = ("SL", "SR", "NR", "NL")  # lin2019 eq 54 order
DEVIATION_READINGS = ("rotated", "tilted")
_BODY = ("screw", "screw", "nut", "nut")
_FLANK = ("left", "right", "right", "left")
ON_NUT = np.array([0.0, 0.0, 1.0, 1.0])  # 1 on the nut flanks (NR, NL)
SIGN_U = np.array([-1.0, -1.0, 1.0, 1.0])  # e_i = (s_u cos beta_i, s_w sin beta_i) in (x3, z3), eq 37
SIGN_W = np.array([-1.0, 1.0, 1.0, -1.0])
for _array in (ON_NUT, SIGN_U, SIGN_W):
    _array.setflags(write=False)


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

    @cached_property   # the derived lengths and angles: computed once per module (they sit in every solve's loops)
    def lead_angle(self) -> float:
        """``alpha = atan(lead / (2 pi R_P))`` [rad] (lin2019 eq 42, :func:`helix.lead_angle`)."""
        return float(helix.lead_angle(self.lead, self.pitch_radius))

    @cached_property
    def lead_per_radian(self) -> float:
        """``p = lead / (2 pi)`` [m/rad] (lin2019 eq 34's r_g)."""
        return float(helix.helix_parameter(self.lead))

    @cached_property
    def helix_radius(self) -> float:
        """``L / (2 pi) = sqrt(R_P^2 + p^2)`` [m] (lin2019 eq 45)."""
        return math.hypot(self.pitch_radius, self.lead_per_radian)

    @cached_property
    def groove_radius(self) -> float:
        """``r_g = conformity * 2 R_B`` [m] (:func:`lowmodel.geometry.groove.groove_radius`)."""
        return float(groove_core.groove_radius(self.ball_radius, self.conformity))


def module(screw, oversize: float | None = None) -> ScrewModule:
    """The module of the lin2019 Sec 3 models (:class:`ScrewModule`) of a :class:`lowmodel.bearing.BallScrew`, with
    the preload ``oversize`` [m] (default: the screw's own).  The screw must give its conformity, material, friction
    coefficient and nut speed (the nut drives, the screw is at rest); the module's own ranges are checked here:
    ``mu`` in [0, 2], a nonzero nut speed, the groove inside the pitch radius, a lead angle below 90 deg."""
    screw.need("conformity", "material", "friction_coefficient", "nut_speed",
               by="the ball-screw module (lowmodel.screw.ball)")
    # the screw's fields are checked by BallScrew (lowmodel.bearing.check_field); the module's own ranges here
    ball_radius, conformity, pitch_radius, lead, nominal_angle, nut_speed = (float(x) for x in (
        screw.ball_radius, screw.conformity, screw.pitch_radius, screw.lead, screw.nominal_angle, screw.nut_speed))
    youngs_modulus, poisson_ratio = float(screw.material.youngs_modulus), float(screw.material.poisson_ratio)
    oversize = screw.oversize if oversize is None else oversize
    nut_speed = model_inputs.nut_speed(nut_speed)
    mu = model_inputs.screw_friction_coefficient(screw.friction_coefficient)
    oversize = checks.bounded("oversize", oversize, 0.0, 0.01 * ball_radius, "m", lower_closed=True,
                              upper_closed=True, note="i.e. [0, 0.01 ball_radius]")
    checks.plausible("oversize", oversize)  # a module's own oversize (the screw's is checked by BallScrew)
    model_inputs.screw_pitch_radius(pitch_radius, ball_radius, conformity)
    if not helix.lead_angle(lead, pitch_radius) < 0.5 * math.pi:
        raise ValueError(f"lead must give a lead angle below pi/2 rad with pitch_radius {pitch_radius!r} m "
                         f"(atan(lead / (2 pi pitch_radius)) rounds to 90 deg), got {screw.lead!r}")
    return ScrewModule(ball_radius, conformity, pitch_radius, lead, nominal_angle, nut_speed, mu, youngs_modulus,
                       poisson_ratio, oversize)


def screw_module(*, ball_radius: float = 2.778e-3, conformity: float = 0.56, pitch_radius: float = 16.5e-3,
                 lead: float = 20e-3, nominal_angle: float = math.radians(45.0), nut_speed: float = 2 * math.pi,
                 friction_coefficient: float = 0.1, youngs_modulus: float = 2.1e11, poisson_ratio: float = 0.28,
                 oversize: float = 0.0) -> ScrewModule:
    """:func:`module` by keywords, for the paper figures that sweep one parameter; defaults are lin2019 Table 4
    (E = 210 GPa, papers/README).  Builds the :class:`lowmodel.bearing.BallScrew` (its checks, the plausible ranges
    among them: a length in mm or a modulus in GPa is refused here, not in a solve) and its module."""
    screw = BallScrew(ball_radius=ball_radius, pitch_radius=pitch_radius, lead=lead, nominal_angle=nominal_angle,
                      conformity=conformity, material=Material(youngs_modulus, poisson_ratio),
                      friction_coefficient=friction_coefficient, nut_speed=nut_speed, oversize=oversize)
    return module(screw)


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

    @cached_property
    def kernel_geometry(self) -> np.ndarray:
        """(n, 4, 6), read-only, cached: per contact the arc centre ``(x3, z3)`` [m], Hertz ``C``, ``a / F^(1/3)``,
        b/a and 1 on the nut (the layout of :mod:`lowmodel.screw.ball_kernels`)."""
        data = np.empty(self.contact_angles.shape + (6,))
        data[..., 0:2] = self.arc_centres
        data[..., 2] = self.hertz_constant
        data[..., 3] = self.semi_major_unit
        data[..., 4] = self.b_over_a
        data[..., 5] = ON_NUT
        return checks.read_only(data)

    @cached_property
    def solver_memo(self) -> dict:
        """The load-independent constants of the solves on these contacts, filled by :mod:`lowmodel.screw.ball` and
        :mod:`lowmodel.screw.b2b` at their first use (the free-rolling start, the reference forces by load, the
        chain's scales, layout and row tolerances by load and gaps): a solve repeated on the same contacts skips
        that Python (docs/speed.md).  Computed once per instance like :attr:`kernel_geometry`: a BallContacts is
        not changed after it is built."""
        return {}

    def ball(self, index: int) -> "BallContacts":
        """The contacts of ball ``index`` alone (shape (1, 4))."""
        sl = slice(index, index + 1)
        return BallContacts(self.module, self.contact_angles[sl], self.arc_centres[sl], self.hertz_constant[sl],
                            self.semi_major_unit[sl], self.b_over_a[sl], self.deviation[sl],
                            None if self.bulk_compliance is None else self.bulk_compliance[sl])


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
    # scipy's splines evaluated without its call overhead, the same numbers (lowmodel.cubic_pieces)
    return tuple(cubic_pieces(CubicSpline(angles, values[:, q])) for q in range(3))


def hertz_direct(ball_radius, conformity, pitch_radius, lead_angle, angle, body, youngs_modulus, poisson_ratio):
    """(C [m N^-2/3], a per F^(1/3) [m N^-1/3], b/a) from :func:`hertz.ball_in_screw_groove` (no table)."""
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
    """Calibrated contact laws of the screw and the nut groove (docs/calibration.md).

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
    for i in range(2):   # the screw flanks, at beta_0 + theta
        if i == 1 and np.array_equal(angles[:, 1], angles[:, 0]):   # SR at SL's angles (tilted): SL's numbers
            constant[:, 1], unit[:, 1], ratio[:, 1] = constant[:, 0], unit[:, 0], ratio[:, 0]
        else:
            constant[:, i], unit[:, i], ratio[:, i] = _flank_hertz(module, angles[:, i], i)
        centres[:, i] = _flank_centres(module, angles[:, i], i)
    # the nut flanks keep beta_0 whatever the deviation: their numbers depend on the module and n alone
    nut_constant, nut_unit, nut_ratio, nut_centres = _nut_flanks(module, n)
    constant[:, 2:], unit[:, 2:], ratio[:, 2:], centres[:, 2:] = nut_constant, nut_unit, nut_ratio, nut_centres
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


def _flank_hertz(module: ScrewModule, angles: np.ndarray, i: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(C, a per F^(1/3), b/a) of flank ``i`` at ``angles`` (:func:`_hertz_of`); ValueError naming the flank."""
    try:
        return _hertz_of(module, angles, _BODY[i])
    except ValueError as error:   # e.g. conformity next to 0.5: the flank conforms with the ball
        raise ValueError(f"module: no Hertz point contact on flank {CONTACT_NAMES[i]} with conformity "
                         f"{module.conformity!r} ({error})") from None


def _flank_centres(module: ScrewModule, angles: np.ndarray, i: int) -> np.ndarray:
    """(n, 2) arc centres ``(u, w) = (x3, z3)`` of flank ``i`` at the balls' contact ``angles`` (validated by
    :func:`flank_angles`): the core's :func:`groove.flank_arc_centre`."""
    radius, sign_u, sign_w = _flank_arc(module.ball_radius, module.conformity, module.pitch_radius, module.lead,
                                        float(module.nominal_angle), _BODY[i], _FLANK[i])
    return groove_core.flank_arc_centre(module.ball_radius, radius, angles, sign_u, sign_w)


@lru_cache(maxsize=64)
def _nut_flanks(module: ScrewModule, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """C, a per F^(1/3), b/a (n, 2) and arc centres (n, 2, 2) of the nut flanks (NR, NL) of ``n`` balls, read-only,
    cached: the nut keeps ``beta_0`` (:func:`flank_angles`), so :func:`ball_contacts` computes them once per module and
    ``n`` on the same column of angles; every number is that of its own angle alone (:func:`_hertz_of`,
    :func:`groove.flank_arc_centre`), so each step of the whole screw gets the numbers it would compute."""
    angles = np.full(n, float(module.nominal_angle))
    constant, unit, ratio = (np.empty((n, 2)) for _ in range(3))
    centres = np.empty((n, 2, 2))
    for column, i in enumerate((2, 3)):
        constant[:, column], unit[:, column], ratio[:, column] = _flank_hertz(module, angles, i)
        centres[:, column] = _flank_centres(module, angles, i)
    return tuple(checks.read_only(array) for array in (constant, unit, ratio, centres))


@lru_cache(maxsize=256)
def _flank_arc(ball_radius, conformity, pitch_radius, lead, angle, body, flank) -> tuple[float, float, float]:
    """``(r_g, sign_u, sign_w)`` of the core's flank (:class:`groove.HelicalGroove`) of a module's groove at the
    nominal angle, cached (the flank's ``groove_radius`` checks its inputs at every read): the inputs of
    :func:`groove.flank_arc_centre` at each ball's contact angle."""
    core = groove_core.HelicalGroove(ball_radius, conformity, pitch_radius, lead, angle, body, flank)
    return core.groove_radius, core.sign_u, core.sign_w


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
    su, sw = SIGN_U.reshape((1, 4) + (1,) * gamma.ndim), SIGN_W.reshape((1, 4) + (1,) * gamma.ndim)
    centre = contacts.arc_centres.reshape(shape + (2,))
    shift = nut_shift * math.cos(module.lead_angle) * ON_NUT.reshape((1, 4) + (1,) * gamma.ndim)
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
    direction = np.stack([SIGN_U[contact] * np.cos(gamma), SIGN_W[contact] * np.sin(gamma)], axis=-1)
    theta = np.arctan2(direction[..., 1], direction[..., 0])  # the core's arc angle
    surface = flank.surface(theta, azimuth)
    if ON_NUT[contact]:
        surface = surface + np.array([0.0, 0.0, nut_shift])
    frame = helix.cs3_frame(azimuth, module.lead_angle)
    local = np.einsum("ji,...j->...i", frame, surface - helix.ball_centre(azimuth, module.pitch_radius, module.lead))
    return local[..., [0, 2]]
