"""Friction over a Hertz ellipse whose velocity centre is offset along both axes (ball screws).

lin2019 Sec 3.1, eqs 44-47 and Appendix A9-A11 (Fig 14): in the contact plane
of a ball-screw contact the slip of the ball relative to the groove is a rigid
rotation with angular velocity ``omega`` about the *velocity centre* ``(c, d)``,
``c`` along the major semi-axis ``a`` (across the groove), ``d`` along the minor
semi-axis ``b`` (along the helix, the rolling direction).  With ``X`` the major
and ``Y`` the minor coordinate (lin2019 eq 47: ``X = z_i``, ``Y = y_i``)::

    dv_major = omega (Y - d),     dv_minor = omega (c - X)

The linear bearing (lin2019 eq 3, :mod:`lowmodel.contact.ellipse_friction`) is
the case ``d = 0``.  With the Hertz pressure ``p = p0 sqrt(1 - X^2/a^2 -
Y^2/b^2)``, ``p0 = 3 F / (2 pi a b)`` (eq A7) and Coulomb friction ``mu p``
opposing the slip, the friction on the ball is (eqs A4-A6 with the offset)::

    F_major = -mu iint p dv_major/|dv|,     F_minor = -mu iint p dv_minor/|dv|
    M       =  iint (X tau_minor - Y tau_major)    (about major x minor; the
                                                   lin2019 -y_i axis of eq 4 for d = 0)
    P       =  mu iint p |dv|

Inputs are the slip velocities, which stay finite as ``omega -> 0``::

    spin_velocity = omega a            [m/s]
    slip_minor    = omega c            [m/s]  slip at the contact centre along the minor axis
    slip_major    = -omega d           [m/s]  slip at the contact centre along the major axis

so that ``dv_major = omega Y + slip_major`` and ``dv_minor = slip_minor - omega X``.
Returned, normalised as :func:`ellipse_friction.friction_velocity`::

    F_major = mu F force_major,  F_minor = mu F force_minor  [N]
    M       = mu F a moment                                  [N m]
    P       = mu F loss                                      [W]  (loss in m/s)

Exact identities (differentiate under the integral; ``loss`` is homogeneous of
degree 1 in the three velocities)::

    loss = spin moment - slip_minor force_minor - slip_major force_major   (power of the tractions)
    d loss / d(spin, slip_minor, slip_major) = (moment, -force_minor, -force_major)

Quadrature, in the unit disc ``t = X/a``, ``s = Y/b`` (``beta = b/a``), with the
velocity centre at ``(kappa, lam) = (c/a, d/b)`` and its distance
``R_c = hypot(kappa, lam)``:

* ``R_c < 1`` (centre inside): polar coordinates about the velocity centre,
  ``t = kappa + rho cos th``, ``s = lam + rho sin th``; then ``|dv| = |omega| a rho g(th)``,
  ``g = sqrt(cos^2 + beta^2 sin^2)``, the slip direction depends on ``th`` only and the
  radial integrals ``J_n = int rho^n sqrt(1 - t^2 - s^2) d rho`` are closed forms (the
  kink of the slip direction and the ``1/rho`` of the derivatives are integrated
  exactly).  Angular rule: tanh-sinh on four panels whose ends are the two
  directions where the rays graze the rim as ``R_c -> 1`` and the two minor-axis
  directions, where ``g`` has its complex zeros (``tan = +-i/beta``) closest to the
  real axis: every near-singularity sits at a panel end, where tanh-sinh clusters its nodes.
* ``1 <= R_c < 100``: the same, over the cone of rays that meet the disc,
  parametrised by ``sin(th') = sin(x)/R_c`` so that the chord integrals are smooth in ``x``
  (two panels, split at a minor-axis direction inside the cone).
* ``R_c >= 100`` and ``omega = 0`` (near pure sliding): Gauss quadrature over the disc
  of the smooth integrand in the velocities themselves (the centred form would
  cancel ``O(R_c)`` terms in the moment).

Agreement with an independent adaptive Cartesian quadrature: tests assert 1e-8
(observed 1e-17 .. 2e-12); level 4 (default, 516 nodes inside, 258 outside) agrees
with level 7 to 1e-13 for ``b/a`` in [0.1, 0.25], level 3 to 3e-8.  Derivatives with respect to the three velocities are
returned (``jacobian``); they come from exact derivative integrals, not finite
differences.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.special import ellipe

from ballbench.lowmodel import checks
from ballbench.lowmodel.quadrature import tanh_sinh

__all__ = ["OffsetFriction", "friction_offset", "friction_centre", "FAR_CENTRE", "disc_rule"]

_PREFACTOR = 3.0 / (2.0 * math.pi)  # lin2019 eq A7: p0 a b / F
FAR_CENTRE = 100.0  # R_c above which the disc quadrature of the velocities is used
_LEVEL = 4  # tanh-sinh level of the centred quadrature (step 2^-4 per panel; 1e-13 against level 7, tests)


@dataclass(frozen=True)
class OffsetFriction:
    """Friction of a Hertz ellipse with a velocity centre ``(c, d)`` (module docstring).

    Arrays of the broadcast input shape ``S``:

    force_major, force_minor : friction force on the ball along +major / +minor, in units ``mu F``
    moment : friction moment about the contact centre, about ``major x minor``, units ``mu F a``
    loss : dissipated power in units ``mu F`` [m/s]
    jacobian : shape ``S + (4, 3)``, rows (force_major, force_minor, moment, loss),
        columns d/d(spin_velocity, slip_minor, slip_major) [1/(m/s)] (loss row: dimensionless)
    """

    force_major: np.ndarray
    force_minor: np.ndarray
    moment: np.ndarray
    loss: np.ndarray
    jacobian: np.ndarray


# --------------------------------------------------------------------------
# quadrature rules
# --------------------------------------------------------------------------
def _g_poles(cos_psi: np.ndarray, sin_psi: np.ndarray) -> np.ndarray:
    """th' (m, 2) of the ray angles theta = psi + pi + th' = +-pi/2 (the minor-axis directions, where
    ``g = sqrt(cos^2 + beta^2 sin^2)`` has its complex zeros closest to the real axis), in [-pi/2, 3 pi/2)."""
    psi = np.arctan2(sin_psi, cos_psi)
    poles = np.stack([-0.5 * math.pi - psi, -1.5 * math.pi - psi], axis=1)
    return np.mod(poles + 0.5 * math.pi, 2.0 * math.pi) - 0.5 * math.pi


def _inside_panels(cos_psi: np.ndarray, sin_psi: np.ndarray, level: int):
    """Angles th' (m, 4 N) and weights of tanh-sinh rules on the panels of [-pi/2, 3 pi/2) split where
    the rays graze the rim as R_c -> 1 (th' = +-pi/2) and at the two minor-axis directions (``_g_poles``):
    every near-singularity of the angular integrand sits at a panel end, where tanh-sinh clusters its nodes."""
    x, w = tanh_sinh(level)
    m = cos_psi.size
    ends = np.concatenate([np.full((m, 1), -0.5 * math.pi), np.full((m, 1), 0.5 * math.pi),
                           _g_poles(cos_psi, sin_psi)], axis=1)
    ends = np.sort(ends, axis=1)
    ends = np.concatenate([ends, np.full((m, 1), 1.5 * math.pi)], axis=1)
    start, width = ends[:, :4, None], np.diff(ends, axis=1)[:, :, None]
    return (start + width * x).reshape(m, -1), (width * w).reshape(m, -1)


def _outside_panels(cos_psi: np.ndarray, sin_psi: np.ndarray, rc: np.ndarray, level: int):
    """x (m, 2 N) in (-pi/2, pi/2) (``sin th' = sin x / R_c``) and weights: two tanh-sinh panels split at the
    minor-axis direction if it lies inside the cone of rays that meet the disc, else at x = 0."""
    t, w = tanh_sinh(level)
    poles = _g_poles(cos_psi, sin_psi)
    poles = np.where(poles > math.pi, poles - 2.0 * math.pi, poles)          # th' in (-pi, pi]
    half = np.arcsin(np.minimum(1.0, 1.0 / rc))                             # cone half-angle
    inside = np.abs(poles) < half[:, None]
    split_x = np.arcsin(np.clip(rc[:, None] * np.sin(poles), -1.0, 1.0))
    split = np.where(np.any(inside, axis=1), np.where(inside, split_x, -math.inf).max(axis=1), 0.0)
    ends = np.stack([np.full(rc.size, -0.5 * math.pi), split, np.full(rc.size, 0.5 * math.pi)], axis=1)
    start, width = ends[:, :2, None], np.diff(ends, axis=1)[:, :, None]
    return (start + width * t).reshape(rc.size, -1), (width * w).reshape(rc.size, -1)


@lru_cache(maxsize=4)
def _disc_rule(n_radial: int = 16, n_angular: int = 32):
    """Nodes (t, s) and weights of int_disc (3/(2 pi)) sqrt(1 - t^2 - s^2) f dt ds (weights sum to 1)."""
    x, w = np.polynomial.legendre.leggauss(n_radial)
    gamma = 0.25 * math.pi * (x + 1.0)  # r = sin(gamma): r sqrt(1 - r^2) dr = sin cos^2 d gamma
    weight_r = 0.25 * math.pi * w * np.sin(gamma) * np.cos(gamma) ** 2
    radius = np.sin(gamma)
    alpha = 2.0 * math.pi * (np.arange(n_angular) + 0.5) / n_angular
    t = (radius[:, None] * np.cos(alpha)[None, :]).ravel()
    s = (radius[:, None] * np.sin(alpha)[None, :]).ravel()
    weights = (_PREFACTOR * weight_r[:, None] * (2.0 * math.pi / n_angular) * np.ones(n_angular)[None, :]).ravel()
    return checks.read_only(t), checks.read_only(s), checks.read_only(weights)  # cached: shared by every caller


def disc_rule() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The disc rule of the far-centre quadrature: nodes ``t``, ``s`` and weights (read-only; the compiled
    twin :mod:`lowmodel.screw.ball_kernels` sums over the same nodes)."""
    return _disc_rule()


# --------------------------------------------------------------------------
# centred quadrature: functions of (kappa, lam) for omega > 0
# --------------------------------------------------------------------------
def _centred(kappa: np.ndarray, lam: np.ndarray, beta: np.ndarray, level: int = _LEVEL):
    """Integrals about the velocity centre for omega > 0; 1-D arrays of equal length.

    Returns ``(f_major, f_minor, loss_hat, c_ss, c_sc, c_cc)`` with
    ``loss_hat = iint P D`` (loss per unit ``omega a``) and the derivative integrals
    ``c_ss = iint P beta^2 (s - lam)^2 / D^3``, ``c_sc = iint P beta (t - kappa)(s - lam) / D^3``,
    ``c_cc = iint P (t - kappa)^2 / D^3`` (``D = sqrt((t - kappa)^2 + beta^2 (s - lam)^2)``,
    ``P = (3/(2 pi)) sqrt(1 - t^2 - s^2) dt ds``).
    """
    rc = np.hypot(kappa, lam)
    safe = np.where(rc > 0.0, rc, 1.0)
    # direction of the centre from the disc centre; the ray angle is theta = psi + pi + th'
    cos_psi, sin_psi = np.where(rc > 0.0, kappa / safe, 1.0), np.where(rc > 0.0, lam / safe, 0.0)
    out = np.empty((6, kappa.size))
    inside = rc < 1.0
    if np.any(inside):
        r = rc[inside, None]
        angle, weight = _inside_panels(cos_psi[inside], sin_psi[inside], level)
        cos_p, sin_p = np.cos(angle), np.sin(angle)
        b = -r * cos_p                       # w = rho + b along the ray; q = R^2 - w^2
        big_r2 = 1.0 - (r * sin_p) ** 2
        h = np.sqrt(np.maximum(1.0 - r * r, 0.0))    # sqrt(R^2 - b^2) = sqrt(1 - R_c^2), one per contact
        asin = np.arctan2(b, h)                      # asin(b / R), without the division
        k0 = 0.25 * math.pi * big_r2 - 0.5 * (b * h + big_r2 * asin)
        k1 = h**3 / 3.0
        k2 = 0.0625 * math.pi * big_r2**2 - 0.125 * (b * (2.0 * b * b - big_r2) * h + big_r2**2 * asin)
        j0 = k0
        j1 = k1 - b * k0
        j2 = k2 - 2.0 * b * k1 + b * b * k0
        cos_t = -(cos_psi[inside, None] * cos_p - sin_psi[inside, None] * sin_p)   # cos(psi + pi + th')
        sin_t = -(sin_psi[inside, None] * cos_p + cos_psi[inside, None] * sin_p)
        out[:, inside] = _angular(cos_t, sin_t, j0, j1, j2, weight, beta[inside, None])
    outside = ~inside
    if np.any(outside):
        r = rc[outside, None]
        x, weight = _outside_panels(cos_psi[outside], sin_psi[outside], rc[outside], level)
        sin_x, cos_x = np.sin(x), np.cos(x)
        chord = np.sqrt((r - 1.0) * (r + 1.0) + cos_x**2)   # R_c cos(th') = -b
        # J_n d th' with d th' = cos x dx / chord, R^2 = cos^2 x (full chord); c3/chord -> cos^2 x at R_c = 1
        c3 = cos_x**3
        ratio = np.divide(c3, chord, out=np.zeros_like(chord), where=chord > 0.0)
        j0 = 0.5 * math.pi * ratio
        j1 = 0.5 * math.pi * c3
        j2 = 0.125 * math.pi * ratio * cos_x**2 + 0.5 * math.pi * chord * c3
        sin_p = sin_x / r                 # th' = asin(sin x / R_c), cos th' = chord / R_c
        cos_p = chord / r
        cos_t = -(cos_psi[outside, None] * cos_p - sin_psi[outside, None] * sin_p)
        sin_t = -(sin_psi[outside, None] * cos_p + cos_psi[outside, None] * sin_p)
        out[:, outside] = _angular(cos_t, sin_t, j0, j1, j2, weight, beta[outside, None])
    return out


def _angular(cos, sin, j0, j1, j2, weight, beta):
    """Angular sums over rays of direction (cos, sin) (arrays (m, nodes)) with the radial integrals J_n."""
    bsin = beta * sin
    g2 = cos * cos + bsin * bsin
    g = np.sqrt(g2)
    w1 = weight * j1 / g
    w0 = weight * j0 / (g2 * g)
    w0_bsin = w0 * bsin
    w0_cos = w0 * cos
    f_minor = np.einsum("ij,ij->i", w1, cos)
    f_major = -np.einsum("ij,ij->i", w1, bsin)
    loss = np.einsum("ij,ij->i", weight * g, j2)
    c_ss = np.einsum("ij,ij->i", w0_bsin, bsin)
    c_sc = np.einsum("ij,ij->i", w0_bsin, cos)
    c_cc = np.einsum("ij,ij->i", w0_cos, cos)
    return _PREFACTOR * np.stack([f_major, f_minor, loss, c_ss, c_sc, c_cc])


# --------------------------------------------------------------------------
# disc quadrature in the velocities (far centre, pure sliding)
# --------------------------------------------------------------------------
def _disc(spin, slip_minor, slip_major, beta):
    """(force_major, force_minor, moment, loss, jacobian (n, 4, 3)) by Gauss quadrature over the disc."""
    t, s, weight = _disc_rule()
    w, un, um, b = (v[:, None] for v in (spin, slip_minor, slip_major, beta))
    dv_major = w * b * s + um            # in units of a: omega Y + slip_major, Y = b s
    dv_minor = un - w * t
    norm = np.hypot(dv_major, dv_minor)
    e_major, e_minor = dv_major / norm, dv_minor / norm
    arm = b * s * e_major - t * e_minor   # (beta s, -t) . e
    force_major = -(e_major @ weight)
    force_minor = -(e_minor @ weight)
    moment = arm @ weight                 # int (t tau_minor - beta s tau_major), tau = -e
    loss = norm @ weight
    # d e / d q = (I - e e^T) d dv / d q / |dv|; d dv/d(spin, slip_minor, slip_major) = (beta s, -t), (0, 1), (1, 0)
    perp_major, perp_minor = -e_minor, e_major   # unit vector normal to e
    components = (b * s * perp_major - t * perp_minor,  # perp . d dv/d spin
                  perp_minor * np.ones_like(t),        # perp . (0, 1)
                  perp_major * np.ones_like(t))        # perp . (1, 0)
    jac = np.empty((spin.size, 4, 3))
    for k, along in enumerate(components):
        scale = along / norm   # d e = perp (perp . d dv) / |dv|
        jac[:, 0, k] = -((perp_major * scale) @ weight)
        jac[:, 1, k] = -((perp_minor * scale) @ weight)
        jac[:, 2, k] = ((b * s * perp_major - t * perp_minor) * scale) @ weight
    jac[:, 3, 0] = moment
    jac[:, 3, 1] = -force_minor
    jac[:, 3, 2] = -force_major
    return force_major, force_minor, moment, loss, jac


# --------------------------------------------------------------------------
# public API
# --------------------------------------------------------------------------
def _check(name, value) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must be finite (m/s), got a NaN or inf")
    return array


SMALLEST_SLIP = 1e-300  # m/s: below, the Jacobian (~ 1/|slip| x 1/b_over_a x |centre|) leaves the float range


def friction_offset(spin_velocity, slip_minor, slip_major, b_over_a, *, level: int = _LEVEL) -> OffsetFriction:
    """Friction of a Hertz ellipse with its velocity centre at ``(c, d)``, from the slip velocities.

    Parameters
    ----------
    spin_velocity : array_like [m/s], ``omega_i a_i`` (``omega_i`` of lin2019 eq 46)
    slip_minor : array_like [m/s], ``omega_i c_i``: slip of the ball at the contact centre
        along the minor axis (the rolling direction; ``(dv)_y`` of eq 44 at the centre)
    slip_major : array_like [m/s], ``-omega_i d_i``: slip at the contact centre along the
        major axis (``(dv)_z`` of eq 44 at the centre)
    b_over_a : array_like in ``[0.02, 1]``.  All four broadcast.
    level : tanh-sinh level of the centred quadrature (``2^level`` steps per unit on each panel; default 4)

    Returns
    -------
    OffsetFriction (normalisation in its docstring).  Nonzero slips below ``SMALLEST_SLIP`` (1e-300 m/s)
    are a ValueError (the Jacobian ~ 1/|slip| leaves the float range).  At zero slip
    (all three velocities 0) the friction is undefined; the pure-spin value
    (forces 0, moment ``(3/8) E(e)``, loss 0) is returned with a zero Jacobian.
    """
    w = _check("spin_velocity", spin_velocity)
    un = _check("slip_minor", slip_minor)
    um = _check("slip_major", slip_major)
    beta = np.asarray(b_over_a, dtype=float)
    if not np.all(np.isfinite(beta)) or np.any(beta < 0.02) or np.any(beta > 1.0):
        raise ValueError("b_over_a must lie in [0.02, 1] (a is the semi-major axis)")
    w, un, um, beta = np.broadcast_arrays(w, un, um, beta)
    shape = w.shape
    w, un, um, beta = (np.ravel(v).astype(float) for v in (w, un, um, beta))
    largest = np.maximum(np.maximum(np.abs(w), np.abs(un)), np.abs(um))
    if np.any((largest > 0.0) & (largest < SMALLEST_SLIP)):  # the Jacobian ~ 1 / |slip| overflows
        smallest = float(np.min(largest[largest > 0.0]))
        raise ValueError(f"spin_velocity, slip_minor and slip_major must be 0 or at least {SMALLEST_SLIP:g} m/s in "
                         f"magnitude (the Jacobian ~ 1/|slip| overflows below), got {smallest:.3g}")
    n = w.size
    force_major = np.zeros(n)
    force_minor = np.zeros(n)
    moment = np.zeros(n)
    loss = np.zeros(n)
    jac = np.zeros((n, 4, 3))
    slip = np.hypot(un, um)
    # centre distance R_c = hypot(kappa, lam) with kappa = c/a = un/w, lam = d/b = -um/(w beta)
    scaled = np.hypot(un, um / beta)
    far = scaled >= FAR_CENTRE * np.abs(w)          # includes w = 0 with slip
    rest = (w == 0.0) & (slip == 0.0)
    near = ~far & ~rest
    if np.any(rest):
        moment[rest] = 0.375 * ellipe(1.0 - beta[rest] ** 2)   # lin2019 eq 11
    far &= ~rest
    if np.any(far):
        fm, fn, mo, lo, jj = _disc(w[far], un[far], um[far], beta[far])
        force_major[far], force_minor[far], moment[far], loss[far], jac[far] = fm, fn, mo, lo, jj
    if np.any(near):
        wn, bn = w[near], beta[near]
        kappa = un[near] / wn
        lam = -um[near] / (wn * bn)
        f_major, f_minor, loss_hat, c_ss, c_sc, c_cc = _centred(kappa, lam, bn, level)
        sign = np.sign(wn)
        absw = np.abs(wn)
        mom = kappa * f_minor - bn * lam * f_major + loss_hat
        # derivatives in (kappa, lam) for omega > 0 (module docs, docs/ball_screw.md)
        dfn = np.stack([-c_ss, bn * c_sc])             # d f_minor / d(kappa, lam)
        dfm = np.stack([-c_sc, bn * c_cc])             # d f_major / d(kappa, lam)
        dmo = np.stack([-kappa * c_ss + bn * lam * c_sc, bn * (kappa * c_sc - bn * lam * c_cc)])
        # chain rule: kappa = un/w, lam = -um/(beta w); F = sgn(w) f(kappa, lam)
        def to_velocity(d):
            return np.stack([-(kappa * d[0] + lam * d[1]) / absw, d[0] / absw, -d[1] / (bn * absw)], axis=-1)

        force_major[near] = sign * f_major
        force_minor[near] = sign * f_minor
        moment[near] = sign * mom
        loss[near] = absw * loss_hat
        jac_near = np.empty((wn.size, 4, 3))
        jac_near[:, 0] = to_velocity(dfm)
        jac_near[:, 1] = to_velocity(dfn)
        jac_near[:, 2] = to_velocity(dmo)
        jac_near[:, 3, 0] = sign * mom
        jac_near[:, 3, 1] = -sign * f_minor
        jac_near[:, 3, 2] = -sign * f_major
        jac[near] = jac_near
    return OffsetFriction(force_major.reshape(shape), force_minor.reshape(shape), moment.reshape(shape),
                          loss.reshape(shape), jac.reshape(shape + (4, 3)))


def friction_centre(c_over_a, d_over_b, b_over_a, *, level: int = _LEVEL) -> OffsetFriction:
    """Friction as a function of the velocity centre ``(c/a, d/b)`` for ``omega > 0`` (lin2019 Fig 14).

    Same as :func:`friction_offset` with ``spin_velocity = 1``,
    ``slip_minor = c/a``, ``slip_major = -(b/a)(d/b)``: forces in units ``mu F``, moment in
    units ``mu F a``, loss in units ``|omega| a mu F`` (lin2019 eq A6 form).  For ``d = 0``
    ``force_minor``, ``moment`` and ``loss`` are ``force``, ``moment`` and ``loss`` of
    :func:`ellipse_friction.friction_exact`.
    """
    kappa = np.asarray(c_over_a, dtype=float)
    lam = np.asarray(d_over_b, dtype=float)
    beta = np.asarray(b_over_a, dtype=float)
    return friction_offset(np.ones_like(kappa), kappa, -beta * lam, beta, level=level)
