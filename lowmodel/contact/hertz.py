"""Exact Hertz point contact of two elastic bodies.

Theory: Johnson, *Contact Mechanics* (1985), Sec 4.2 (eqs 4.36-4.41) with
``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``.  The gap between the undeformed
surfaces is ``h = A x^2 + B y^2`` with ``0 < A <= B``; the contact ellipse has
semi-axes ``a`` (along x) ``>= b`` (along y), ratio ``k = b/a`` and
eccentricity ``e = sqrt(1 - k^2)``.

Everything is written with Carlson's symmetric integrals, which removes the
cancellation of ``K(e) - E(e)`` as ``e -> 0`` and the loss of precision of
``K(e)`` as ``e -> 1`` (DLMF 19.25.1)::

    K(e) = R_F(0, k^2, 1)                 K - E       = e^2/3 R_D(0, k^2, 1)
    E(e) = 2 R_G(0, k^2, 1)               E - k^2 K   = e^2 k^2/3 R_D(0, 1, k^2)

so the Hertz relations become

    B/A = R_D(0, 1, k^2) / R_D(0, k^2, 1)                 (shape; load independent)
    a^3 = F R_D(0, k^2, 1) / (2 pi E* A)                  (size)
    p0  = 3 F / (2 pi a b)
    delta = p0 b R_F(0, k^2, 1) / E*                      (approach)

``k`` is found once per geometry by bracketed root finding on ``log k``
(the ratio is monotone in ``k``); loads are then vectorised.  The sphere
(``k = 1``) reduces exactly to ``a^3 = 3 F R / (4 E*)``, ``delta = a^2 / R``.

The papers' constants: lin2019 eq 15 ``a = Psi R_B^(1/3) F^(1/3)``
(:func:`psi_constant`) and lin2019 eq 53 ``delta = C F^(2/3)``
(:func:`hertz_constant`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import elliprd, elliprf, elliprg

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry import groove

__all__ = [
    "HertzGeometry",
    "HertzContact",
    "contact_modulus",
    "from_curvatures",
    "ball_on_flat",
    "ball_on_ball",
    "ball_in_groove",
    "ball_in_screw_groove",
    "groove_geometry",
    "pair_geometry",
    "helical_pair",
    "solve_load",
    "solve_approach",
    "psi_constant",
    "hertz_constant",
]

STEEL_YOUNGS_MODULUS = 2.1e11  # Pa, lin2019 Tables 1 and 4
STEEL_POISSON_RATIO = 0.28  # lin2019 Tables 1 and 4
VALIDITY_RATIO = 0.3  # a / R beyond which a contact is flagged outside Hertz's small-contact assumption


# --------------------------------------------------------------------------
# input checks (lowmodel.checks)
# --------------------------------------------------------------------------
def _material(youngs_modulus: float, poisson_ratio: float, suffix: str = "") -> tuple[float, float]:
    youngs_modulus = checks.positive(f"youngs_modulus{suffix}", youngs_modulus, "Pa")
    poisson_ratio = checks.bounded(f"poisson_ratio{suffix}", poisson_ratio, -1.0, 0.5)
    return youngs_modulus, poisson_ratio


def contact_modulus(youngs_modulus_1: float, poisson_ratio_1: float,
                    youngs_modulus_2: float | None = None, poisson_ratio_2: float | None = None) -> float:
    """Contact modulus E* [Pa]: ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2`` (Johnson eq 4.22).

    Body 2 defaults to the material of body 1.
    """
    e1, n1 = _material(youngs_modulus_1, poisson_ratio_1, "_1")
    e2, n2 = _material(youngs_modulus_1 if youngs_modulus_2 is None else youngs_modulus_2,
                       poisson_ratio_1 if poisson_ratio_2 is None else poisson_ratio_2, "_2")
    return 1.0 / ((1.0 - n1 * n1) / e1 + (1.0 - n2 * n2) / e2)


# --------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class HertzGeometry:
    """Relative curvature and elasticity of a point contact.

    Gap ``h = A x^2 + B y^2`` [m] between the undeformed surfaces.

    Attributes
    ----------
    A, B : float
        Half the principal relative curvatures [1/m], ``0 < A <= B``.  The
        major semi-axis ``a`` lies along x (the direction of ``A``).
    contact_modulus : float
        E* [Pa].
    major_axis_angle : float
        Angle [rad] of x (the ``a`` direction) from the first principal axis
        of body 1, as given to :func:`from_curvatures`.
    axis_ratio : float
        ``k = b/a`` in (0, 1], solved from ``B/A`` (load independent).
    reference_radius : float
        The smallest principal radius of curvature [m] of either surface
        (``1 / max |kappa|``; a ball's radius); Hertz's half-space assumption needs
        ``a`` small against it (:data:`VALIDITY_RATIO`, ``HertzContact.within_validity``).
        ``inf`` when unknown (two flats cannot form a point contact, so never for a
        geometry from :func:`from_curvatures`).
    """

    A: float
    B: float
    contact_modulus: float
    major_axis_angle: float = 0.0
    axis_ratio: float = 1.0
    reference_radius: float = math.inf

    @property
    def equivalent_radius(self) -> float:
        """``R_e = 1 / (2 sqrt(A B))`` [m] (Johnson eq 4.23)."""
        return 0.5 / math.sqrt(self.A * self.B)


def _ratio_of_k(k: float) -> float:
    # B/A as a function of k = b/a (module docstring)
    k2 = k * k
    return float(elliprd(0.0, 1.0, k2) / elliprd(0.0, k2, 1.0))


def _axis_ratio(curvature_ratio: float) -> float:
    """k = b/a for ``B/A = curvature_ratio >= 1``, by brentq on log k."""
    if curvature_ratio <= 1.0 + 1e-15:
        return 1.0
    # B/A ~ k^-3/2 (4 ln(4/k) - ...) grows without bound as k -> 0; bracket in log k
    lo = -1.0
    while _ratio_of_k(math.exp(lo)) < curvature_ratio:
        lo *= 2.0
        if math.exp(2.0 * lo) == 0.0:  # k^2 underflows (B/A beyond ~1e170): the ratio would be inf / inf
            raise ValueError(f"curvatures_1 and curvatures_2 give a curvature ratio B/A = {curvature_ratio:.3e} "
                             "beyond the range of Hertz theory")
    log_k = brentq(lambda t: math.log(_ratio_of_k(math.exp(t)) / curvature_ratio), lo, 0.0,
                   xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    return math.exp(log_k)


def from_curvatures(curvatures_1: tuple[float, float], curvatures_2: tuple[float, float], *,
                    angle: float = 0.0,
                    youngs_modulus: float = STEEL_YOUNGS_MODULUS, poisson_ratio: float = STEEL_POISSON_RATIO,
                    youngs_modulus_2: float | None = None, poisson_ratio_2: float | None = None) -> HertzGeometry:
    """Geometry from the principal curvatures of both bodies (Johnson eq 4.20).

    Parameters
    ----------
    curvatures_1, curvatures_2 : (float, float)
        Principal curvatures [1/m] of each surface at the contact point,
        positive when convex (a ball: ``(1/R, 1/R)``), negative when concave
        (a groove across its profile: ``-1/r_groove``), zero when flat.
    angle : float
        Angle [rad] between the first principal axes of the two bodies.
    youngs_modulus, poisson_ratio : float
        Body 1 [Pa, -]; body 2 defaults to the same unless ``*_2`` is given.

    Raises
    ------
    ValueError
        If a relative curvature is not positive (the bodies conform and Hertz
        theory does not apply) or an input is not finite.
    """
    k1 = np.asarray(checks.finite("curvatures_1", curvatures_1, "1/m"))
    k2 = np.asarray(checks.finite("curvatures_2", curvatures_2, "1/m"))
    if k1.shape != (2,) or k2.shape != (2,):
        raise ValueError("curvatures_1 and curvatures_2 must each be two principal curvatures [1/m]")
    angle = checks.finite("angle", angle, "rad")
    e_star = contact_modulus(youngs_modulus, poisson_ratio, youngs_modulus_2, poisson_ratio_2)
    c, s = math.cos(angle), math.sin(angle)
    rotation = np.array([[c, -s], [s, c]])
    # half the relative curvature tensor: h = x^T (K1 + K2) x / 2
    tensor = 0.5 * (np.diag(k1) + rotation @ np.diag(k2) @ rotation.T)
    eigenvalues, eigenvectors = np.linalg.eigh(tensor)
    A, B = float(eigenvalues[0]), float(eigenvalues[1])
    if not A > 0.0:
        raise ValueError(
            f"curvatures_1 and curvatures_2 give relative curvatures A = {A:.6g} 1/m, B = {B:.6g} 1/m: both must "
            "be > 0 for Hertz point contact (the surfaces conform or do not touch at a point)")
    major_axis_angle = float(math.atan2(eigenvectors[1, 0], eigenvectors[0, 0]))
    reference_radius = 1.0 / float(np.max(np.abs(np.concatenate([k1, k2]))))  # > 0 since A > 0
    geometry = HertzGeometry(A, B, e_star, major_axis_angle, _axis_ratio(B / A), reference_radius)
    try:
        unit = _unit_solution(geometry)
    except (ZeroDivisionError, OverflowError):
        unit = (math.nan,)
    if not all(math.isfinite(v) and v > 0.0 for v in (*unit, unit[-1] ** 1.5)):  # e.g. E* A over-, C^1.5 underflows
        raise ValueError(f"youngs_modulus and curvatures_1, curvatures_2 (E* = {e_star:.6g} Pa, A = {A:.6g} 1/m, "
                         f"B = {B:.6g} 1/m) give a Hertz contact outside the floating-point range")
    return geometry


def _curvature(name: str, radius) -> float:
    """``1 / radius`` [1/m] of a ball, checked: ``radius`` > 0 m with a finite inverse (not subnormal)."""
    radius = checks.positive(name, radius, "m")
    return checks.positive(f"1 / {name}", 1.0 / radius, "1/m")


def ball_on_flat(ball_radius: float, *, youngs_modulus: float = STEEL_YOUNGS_MODULUS,
                 poisson_ratio: float = STEEL_POISSON_RATIO, youngs_modulus_2: float | None = None,
                 poisson_ratio_2: float | None = None) -> HertzGeometry:
    """A ball of radius ``ball_radius`` [m] on a flat."""
    kappa = _curvature("ball_radius", ball_radius)
    return from_curvatures((kappa, kappa), (0.0, 0.0), youngs_modulus=youngs_modulus,
                           poisson_ratio=poisson_ratio, youngs_modulus_2=youngs_modulus_2,
                           poisson_ratio_2=poisson_ratio_2)


def ball_on_ball(ball_radius: float, other_radius: float | None = None, *,
                 youngs_modulus: float = STEEL_YOUNGS_MODULUS, poisson_ratio: float = STEEL_POISSON_RATIO,
                 youngs_modulus_2: float | None = None, poisson_ratio_2: float | None = None) -> HertzGeometry:
    """Two balls in contact (the ball-to-ball, B2B, contact of lin2019); radii [m]."""
    k1 = _curvature("ball_radius", ball_radius)
    k2 = k1 if other_radius is None else _curvature("other_radius", other_radius)
    return from_curvatures((k1, k1), (k2, k2), youngs_modulus=youngs_modulus,
                           poisson_ratio=poisson_ratio, youngs_modulus_2=youngs_modulus_2,
                           poisson_ratio_2=poisson_ratio_2)


def ball_in_groove(ball_radius: float, conformity: float, *, youngs_modulus: float = STEEL_YOUNGS_MODULUS,
                   poisson_ratio: float = STEEL_POISSON_RATIO) -> HertzGeometry:
    """A ball in a straight gothic-arch groove (linear bearing rail; lin2019 Table 1).

    The groove radius is ``conformity * 2 * ball_radius``; the groove is
    straight along its length.  x (major axis ``a``) lies across the groove in
    the cross-section, y along the groove (the rolling direction).  ``ball_radius`` [m] must be a plausible
    ball radius (``checks.PLAUSIBLE``: 0.1 mm to 100 mm), so that a radius in mm is refused, not solved.

    >>> from ballbench.lowmodel.contact import hertz
    >>> contact = hertz.solve_load(hertz.ball_in_groove(3.175e-3, 0.52), 500.0)   # SI: m, -, N
    >>> round(float(contact.a) * 1e3, 3), round(float(contact.b) * 1e3, 3)        # semi-axes [mm]
    (0.954, 0.117)
    """
    kappa = _curvature("ball_radius", ball_radius)
    checks.plausible("ball_radius", ball_radius)
    # body 1 = ball; body 2 = groove: (across, along) = (-1/r_groove, 0) from the geometry core
    return from_curvatures((kappa, kappa), groove.straight_groove_curvatures(ball_radius, conformity),
                           youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)


def ball_in_screw_groove(ball_radius: float, conformity: float, pitch_radius: float, contact_angle: float,
                         lead_angle: float, body: str = "screw", *, profile_plane: str = "normal",
                         youngs_modulus: float = STEEL_YOUNGS_MODULUS,
                         poisson_ratio: float = STEEL_POISSON_RATIO) -> HertzGeometry:
    """A ball in the helical groove of a ball screw (``body='screw'``) or nut (``'nut'``).

    Inputs in [m] and [rad]; the groove and its principal curvatures come from
    the geometry core, :func:`lowmodel.geometry.groove.groove_curvatures_helical`
    (profile in the plane normal to the helix by default, lin2019 eq 41;
    lin2019 Table 4: R_B 2.778 mm, conformity 0.56, pitch radius 16.5 mm,
    contact angle 45 deg, lead 20 mm).  Since the ball is a sphere, the
    ellipse axes follow the groove's principal directions.
    """
    kappa = _curvature("ball_radius", ball_radius)  # first: the geometry core divides by it
    kappa_1, kappa_2, _ = groove.groove_curvatures_helical(ball_radius, conformity, pitch_radius, contact_angle,
                                                           lead_angle, body, profile_plane)
    try:
        return from_curvatures((kappa, kappa), (kappa_1, kappa_2), youngs_modulus=youngs_modulus,
                               poisson_ratio=poisson_ratio)
    except ValueError as error:  # name this function's inputs (e.g. a profile that conforms: A <= 0)
        if "curvatures_1" not in str(error):
            raise
        raise ValueError(f"ball_radius {ball_radius!r} m, conformity {conformity!r}, pitch_radius {pitch_radius!r} m, "
                         f"contact_angle {contact_angle!r} rad, lead_angle {lead_angle!r} rad, {body} groove, "
                         f"profile_plane {profile_plane!r}: {error}") from None


def groove_geometry(guide) -> HertzGeometry:
    """The Hertz geometry of the ball of a :class:`lowmodel.bearing.LinearGuide` in its groove (rail and carriage
    grooves alike: :func:`ball_in_groove` of its ball radius, conformity and material)."""
    return ball_in_groove(guide.ball_radius, guide.conformity, **guide.material.keywords)


def pair_geometry(contact) -> HertzGeometry:
    """The Hertz geometry of a :class:`lowmodel.bearing.ContactLoadCase`: its ball on a flat, on a ball of the same
    radius, in a straight groove of its conformity, or on the flank of its ball screw's helical screw or nut groove
    at the nominal contact angle (the exact helical frame of the geometry core,
    :func:`lowmodel.geometry.groove.contact_frame`), of the contact's material."""
    radius, material = contact.ball_radius, contact.material.keywords
    if contact.pair == "flat":
        return ball_on_flat(radius, **material)
    if contact.pair == "ball":
        return ball_on_ball(radius, **material)
    if contact.pair == "groove":
        return ball_in_groove(radius, contact.conformity, **material)
    frame = groove.contact_frame(groove.helical_groove(*helical_pair(contact)))
    return from_curvatures((1 / radius, 1 / radius), (frame.curvature_major, frame.curvature_minor), **material)


def helical_pair(contact) -> tuple:
    """``(R_B, conformity, R_P, lead, beta_0, pair)`` of a screw or nut :class:`lowmodel.bearing.ContactLoadCase`:
    the arguments of :func:`lowmodel.geometry.groove.helical_groove` (and of the helical pair's mesh builder)."""
    screw = contact.screw
    return (screw.ball_radius, screw.conformity, screw.pitch_radius, screw.lead, screw.nominal_angle, contact.pair)


# --------------------------------------------------------------------------
# solution
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class HertzContact:
    """Hertz solution; array attributes broadcast with the load given.

    Attributes
    ----------
    force : normal load F [N]
    a, b : semi-axes [m], ``a >= b``, ``a`` along x of the geometry
    p0 : peak pressure [Pa], ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)``
    delta : approach of distant points of the two bodies [m]
    stiffness : dF/d(delta) [N/m]
    eccentricity : ``e = sqrt(1 - (b/a)^2)``
    ellip_k, ellip_e : complete elliptic integrals K(e), E(e) (modulus e)
    within_validity : bool array, ``a <= VALIDITY_RATIO * R`` with ``R`` the geometry's
        ``reference_radius`` (the ball radius for the bearing contacts): False flags a
        contact too large for Hertz's half-space assumption; the numbers are still the
        exact solution of the Hertz problem, but no longer of the real contact
        (docs/hertz.md, validity)
    """

    force: np.ndarray
    a: np.ndarray
    b: np.ndarray
    p0: np.ndarray
    delta: np.ndarray
    stiffness: np.ndarray
    eccentricity: float
    ellip_k: float
    ellip_e: float
    within_validity: np.ndarray


def _unit_solution(geometry: HertzGeometry) -> tuple[float, float, float]:
    """(a, delta, C) for F = 1 N: a [m], delta [m], C = delta / F^(2/3) [m N^(-2/3)]."""
    k = geometry.axis_ratio
    k2 = k * k
    a_unit = (float(elliprd(0.0, k2, 1.0)) / (2.0 * math.pi * geometry.contact_modulus * geometry.A)) ** (1.0 / 3.0)
    b_unit = k * a_unit
    p0_unit = 3.0 / (2.0 * math.pi * a_unit * b_unit)
    delta_unit = p0_unit * b_unit * float(elliprf(0.0, k2, 1.0)) / geometry.contact_modulus
    return a_unit, delta_unit, delta_unit


def _as_load(name: str, value, unit: str) -> np.ndarray:
    return np.asarray(checks.non_negative(name, value, unit))


def _build(geometry: HertzGeometry, force: np.ndarray) -> HertzContact:
    k = geometry.axis_ratio
    k2 = k * k
    a_unit, delta_unit, _ = _unit_solution(geometry)
    cube_root = np.cbrt(force)
    a = a_unit * cube_root
    b = k * a
    with np.errstate(invalid="ignore", divide="ignore"):
        p0 = np.where(force > 0.0, 3.0 * force / (2.0 * math.pi * np.where(a > 0, a * b, 1.0)), 0.0)
        if not np.all(np.isfinite(p0)):  # a b underflows (E* ~ 1e300 and F ~ 1e-299): the same in another order
            p0 = np.where(np.isfinite(p0), p0, 3.0 * (force / np.where(a > 0, a, 1.0)) / (2.0 * math.pi * b))
    delta = delta_unit * cube_root**2
    stiffness = 1.5 * np.sqrt(delta) / delta_unit**1.5  # dF/d(delta) of F = (delta/C)^(3/2)
    return HertzContact(force, a, b, p0, delta, stiffness, math.sqrt(max(0.0, 1.0 - k2)),
                        float(elliprf(0.0, k2, 1.0)), float(2.0 * elliprg(0.0, k2, 1.0)),
                        a <= VALIDITY_RATIO * geometry.reference_radius)


def solve_load(geometry: HertzGeometry, force) -> HertzContact:
    """Hertz contact under normal load ``force`` [N] (scalar or array, >= 0)."""
    return _build(geometry, _as_load("force", force, "N"))


def solve_approach(geometry: HertzGeometry, delta) -> HertzContact:
    """Hertz contact for a given approach ``delta`` [m] (scalar or array, >= 0)."""
    delta = _as_load("delta", delta, "m")
    force = (delta / hertz_constant(geometry)) ** 1.5  # lin2019 eq 53 inverted
    return _build(geometry, force)


def psi_constant(geometry: HertzGeometry, ball_radius: float) -> float:
    """Psi of lin2019 eq 15, ``a = Psi R_B^(1/3) F^(1/3)`` [(m^2/N)^(1/3)]."""
    radius = checks.positive("ball_radius", ball_radius, "m")
    a_unit, _, _ = _unit_solution(geometry)
    return a_unit / radius ** (1.0 / 3.0)


def hertz_constant(geometry: HertzGeometry) -> float:
    """Hertz constant C of lin2019 eq 53, ``delta = C F^(2/3)`` [m N^(-2/3)]."""
    return _unit_solution(geometry)[2]
