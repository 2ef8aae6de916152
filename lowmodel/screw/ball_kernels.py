"""Compiled (numba) kernel of the ball-screw ball equilibrium: :func:`lowmodel.screw.ball.ball_terms` as loops.

The same equations in the same order of operations as the numpy code, one contact at a time, so that
nothing allocates per array operation (loaded by :func:`lowmodel.kernels.load`; never imported by
``import ballbench.lowmodel``):

* :func:`friction_offset`: the friction of a Hertz ellipse with its velocity centre offset along both axes
  and its Jacobian (lin2019 eqs 44-47, A4-A7, A9-A11), the quadratures of
  :func:`lowmodel.contact.ellipse_friction_offset.friction_offset` (tanh-sinh on the panels about the velocity
  centre inside and outside the ellipse, the disc rule of a far centre) for one contact.
* :func:`ball_terms`: lin2019 eqs 36-54 of every ball (closed-form contact geometry, Hertz eq 53, the helical
  kinematics, friction forces and moments summed about the ball centre) with the forward-mode derivatives of
  :class:`lowmodel.dual.Dual`, written out: every quantity is a tuple of 8 floats ``(value, d/d 7 unknowns)``
  (registers, no allocation per operation), each operation in the component order of ``Dual``.

A status other than :data:`CONVERGED` (a contact at rest, a slip outside the float range of the friction
Jacobian, a non-finite input) hands the evaluation back to the numpy code, which names the problem.
The caller is :func:`lowmodel.screw.ball.ball_terms`; the data layout (``geometry`` (n, 4, FIELDS),
``scalars``, the ``contact`` fields) is built and read there.  :func:`chain_residual` is the residual of the B2B
chain of :mod:`lowmodel.screw.b2b` (eqs 54-61) in the layouts of both compiled chains, :func:`chain_function` it with
its dense Jacobian, and :func:`newton` :func:`lowmodel.solvers.newton` on it (the loop of
:func:`lowmodel.newton_kernels.levenberg_marquardt`) for chains of fewer than
:data:`lowmodel.b2b_chain.SPARSE_BALLS` balls, called by ``b2b.solve`` (longer: :mod:`lowmodel.screw.ring_kernels`).

One concept in one file (about 750 lines): the compiled twin of the screw ball and its small chains.  The kernels
call one another and numba compiles and caches them per module, so one module keeps one compile cache.
"""
from __future__ import annotations

import math
import sys

import numba
import numpy as np

from ballbench.lowmodel.newton_kernels import (CONVERGED, NO_DESCENT, NON_FINITE, NOT_CONVERGED, STATIONARY, blas_dot,
                                               levenberg_marquardt)
from ballbench.lowmodel.screw import b2b, ball

__all__ = ["ball_terms", "friction_offset", "pair_loads", "chain_residual", "chain_function", "newton",
           "ball_outputs", "copy_outputs", "warm_up", "FIELDS", "SCALARS", "CONTACT_FIELDS", "CONVERGED", "FALLBACK",
           "NOT_CONVERGED", "NON_FINITE", "STATIONARY", "NO_DESCENT"]

# geometry fields per contact: arc centre (x3, z3) [m], Hertz C [m N^-2/3], a / F^(1/3) [m N^-1/3], b/a, on nut
CENTRE_X, CENTRE_Z, HERTZ, SEMI_UNIT, B_OVER_A, ON_NUT = range(6)
FIELDS = 6
# scalars: Scales (length, orbit, spin, force), R_B, sin/cos alpha, omega_N, L/(2 pi), oversize, r_g, mu
SCALARS = 12
# contact outputs: F, e_x, e_z, delta, a, spin, slip_minor, slip_major, friction force (3), moment (3), loss
CONTACT_FIELDS = 15
FALLBACK = 1  # an evaluation handed back to the numpy code (CONVERGED: evaluated)
_K = 7  # unknowns of one ball: x_B3, z_B3, omega_B, omega (3), nut shift
_D = _K + 1  # a dual number: value and 7 derivatives
_PREFACTOR = 3.0 / (2.0 * math.pi)  # lin2019 eq A7: p0 a b / F

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")
_inline = numba.njit(inline="always", nogil=True, error_model="numpy")   # the steps of newton, inlined into it


# --------------------------------------------------------------------------
# dual numbers (value, gradient) as tuples of 8 floats: lowmodel.dual.Dual's arithmetic, written out per
# component (numba keeps a tuple in registers: nothing allocates per operation) in the order of operations
# of lowmodel.dual.Dual
# --------------------------------------------------------------------------
@_jit
def _mul(a, b):
    """``a * b``."""
    a0, b0 = a[0], b[0]
    return (a0 * b0, a[1] * b0 + b[1] * a0, a[2] * b0 + b[2] * a0, a[3] * b0 + b[3] * a0, a[4] * b0 + b[4] * a0,
            a[5] * b0 + b[5] * a0, a[6] * b0 + b[6] * a0, a[7] * b0 + b[7] * a0)


@_jit
def _scale(a, s):
    """``a * s`` of a float ``s``."""
    return (a[0] * s, a[1] * s, a[2] * s, a[3] * s, a[4] * s, a[5] * s, a[6] * s, a[7] * s)


@_jit
def _add(a, b):
    """``a + b``."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4], a[5] + b[5], a[6] + b[6], a[7] + b[7])


@_jit
def _sub(a, b):
    """``a - b``."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3], a[4] - b[4], a[5] - b[5], a[6] - b[6], a[7] - b[7])


@_jit
def _shift(a, s):
    """``a + s`` of a float ``s``."""
    return (a[0] + s, a[1], a[2], a[3], a[4], a[5], a[6], a[7])


@_jit
def _div(a, b):
    """``a / b``: value ``a0 / b0``, derivatives ``(a' - b' (a0 / b0)) / b0``."""
    inv = 1.0 / b[0]
    ratio = a[0] * inv
    return (ratio, (a[1] - b[1] * ratio) * inv, (a[2] - b[2] * ratio) * inv, (a[3] - b[3] * ratio) * inv,
            (a[4] - b[4] * ratio) * inv, (a[5] - b[5] * ratio) * inv, (a[6] - b[6] * ratio) * inv,
            (a[7] - b[7] * ratio) * inv)


@_jit
def _sqrt(a):
    """``sqrt(a)``."""
    root = math.sqrt(a[0])
    half = 0.5 / root
    return (root, a[1] * half, a[2] * half, a[3] * half, a[4] * half, a[5] * half, a[6] * half, a[7] * half)


@_jit
def _with_value(a, value):
    """``a`` with its value replaced by ``value`` (the derivatives kept)."""
    return (value, a[1], a[2], a[3], a[4], a[5], a[6], a[7])


@_jit
def _variable(value, column, scale):
    """The unknown ``column`` (0-6) of value ``value * scale`` and derivative ``scale``."""
    return (value * scale, scale if column == 0 else 0.0, scale if column == 1 else 0.0,
            scale if column == 2 else 0.0, scale if column == 3 else 0.0, scale if column == 4 else 0.0,
            scale if column == 5 else 0.0, scale if column == 6 else 0.0)


@_jit
def _chain(value, jac, row, a, b, c):
    """Value ``value``, derivatives ``jac[row] . (a', b', c')`` (the friction of one contact through its velocities)."""
    j0, j1, j2 = jac[row, 0], jac[row, 1], jac[row, 2]
    return (value, ((0.0 + j0 * a[1]) + j1 * b[1]) + j2 * c[1], ((0.0 + j0 * a[2]) + j1 * b[2]) + j2 * c[2],
            ((0.0 + j0 * a[3]) + j1 * b[3]) + j2 * c[3], ((0.0 + j0 * a[4]) + j1 * b[4]) + j2 * c[4],
            ((0.0 + j0 * a[5]) + j1 * b[5]) + j2 * c[5], ((0.0 + j0 * a[6]) + j1 * b[6]) + j2 * c[6],
            ((0.0 + j0 * a[7]) + j1 * b[7]) + j2 * c[7])


_ZERO = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@_jit
def _accumulate(target, row, a):
    """``target[row] += a`` of a (D,) row of a 2-d array."""
    target[row, 0] += a[0]
    target[row, 1] += a[1]
    target[row, 2] += a[2]
    target[row, 3] += a[3]
    target[row, 4] += a[4]
    target[row, 5] += a[5]
    target[row, 6] += a[6]
    target[row, 7] += a[7]


# --------------------------------------------------------------------------
# friction of one offset ellipse (lowmodel.contact.ellipse_friction_offset)
# --------------------------------------------------------------------------
@_jit
def _poles(cos_psi, sin_psi):
    psi = math.atan2(sin_psi, cos_psi)
    p0 = np.remainder(-0.5 * math.pi - psi + 0.5 * math.pi, 2.0 * math.pi) - 0.5 * math.pi
    p1 = np.remainder(-1.5 * math.pi - psi + 0.5 * math.pi, 2.0 * math.pi) - 0.5 * math.pi
    return p0, p1


@_jit
def _angular(acc, cos_psi, sin_psi, cos_p, sin_p, j0, j1, j2, weight, beta):
    """The angular sums (f_major, f_minor, loss, c_ss, c_sc, c_cc) with one node added: the node's direction
    ``theta`` from the ray's ``(cos_p, sin_p)`` turned by the velocity centre's ``psi``, its radial integrals
    ``j0 .. j2`` and weight."""
    cos_t = -(cos_psi * cos_p - sin_psi * sin_p)
    sin_t = -(sin_psi * cos_p + cos_psi * sin_p)
    bsin = beta * sin_t
    g2 = cos_t * cos_t + bsin * bsin
    g = math.sqrt(g2)
    w1 = weight * j1 / g
    w0 = weight * j0 / (g2 * g)
    w0_bsin = w0 * bsin
    w0_cos = w0 * cos_t
    s0, s1, s2, s3, s4, s5 = acc
    return (s0 - w1 * bsin, s1 + w1 * cos_t, s2 + weight * g * j2, s3 + w0_bsin * bsin, s4 + w0_bsin * cos_t,
            s5 + w0_cos * cos_t)


@_jit
def _sort4(a, b, c, d):
    """Four floats in ascending order (a sorting network: exact)."""
    if b < a:
        a, b = b, a
    if d < c:
        c, d = d, c
    if c < a:
        a, c = c, a
    if d < b:
        b, d = d, b
    if c < b:
        b, c = c, b
    return a, b, c, d


@_jit
def _centred(kappa, lam, beta, nodes, weights, sums):  # noqa: C901 - the two quadratures of lowmodel.contact.ellipse_friction_offset
    """The integrals about the velocity centre (omega > 0) into ``sums`` (6,).  The node sums run in local
    variables, node after node in the order of the numpy code's sums."""
    acc = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    rc = math.hypot(kappa, lam)
    cos_psi = kappa / rc if rc > 0.0 else 1.0
    sin_psi = lam / rc if rc > 0.0 else 0.0
    p0, p1 = _poles(cos_psi, sin_psi)
    if rc < 1.0:
        e0, e1, e2, e3 = _sort4(-0.5 * math.pi, 0.5 * math.pi, p0, p1)
        h = math.sqrt(max(1.0 - rc * rc, 0.0))
        k1 = h ** 3 / 3.0
        for panel in range(4):
            start = e0 if panel == 0 else (e1 if panel == 1 else (e2 if panel == 2 else e3))
            end = e1 if panel == 0 else (e2 if panel == 1 else (e3 if panel == 2 else 1.5 * math.pi))
            width = end - start
            for node in range(nodes.size):
                angle = start + width * nodes[node]
                weight = width * weights[node]
                cos_p, sin_p = math.cos(angle), math.sin(angle)
                b = -rc * cos_p
                big_r2 = 1.0 - (rc * sin_p) ** 2
                asin = math.atan2(b, h)
                k0 = 0.25 * math.pi * big_r2 - 0.5 * (b * h + big_r2 * asin)
                k2 = 0.0625 * math.pi * big_r2 ** 2 - 0.125 * (b * (2.0 * b * b - big_r2) * h + big_r2 ** 2 * asin)
                j1 = k1 - b * k0
                j2 = k2 - 2.0 * b * k1 + b * b * k0
                acc = _angular(acc, cos_psi, sin_psi, cos_p, sin_p, k0, j1, j2, weight, beta)
    else:
        if p0 > math.pi:
            p0 -= 2.0 * math.pi
        if p1 > math.pi:
            p1 -= 2.0 * math.pi
        half = math.asin(min(1.0, 1.0 / rc))
        split = -math.inf
        found = False
        for pole in (p0, p1):
            if abs(pole) < half:
                found = True
                split = max(split, math.asin(min(max(rc * math.sin(pole), -1.0), 1.0)))
        if not found:
            split = 0.0
        for panel in range(2):
            start = -0.5 * math.pi if panel == 0 else split
            width = (split + 0.5 * math.pi) if panel == 0 else (0.5 * math.pi - split)
            for node in range(nodes.size):
                x = start + width * nodes[node]
                weight = width * weights[node]
                sin_x, cos_x = math.sin(x), math.cos(x)
                chord = math.sqrt((rc - 1.0) * (rc + 1.0) + cos_x ** 2)
                c3 = cos_x ** 3
                ratio = c3 / chord if chord > 0.0 else 0.0
                j0 = 0.5 * math.pi * ratio
                j1 = 0.5 * math.pi * c3
                j2 = 0.125 * math.pi * ratio * cos_x ** 2 + 0.5 * math.pi * chord * c3
                sin_p = sin_x / rc
                cos_p = chord / rc
                acc = _angular(acc, cos_psi, sin_psi, cos_p, sin_p, j0, j1, j2, weight, beta)
    s0, s1, s2, s3, s4, s5 = acc
    sums[0], sums[1], sums[2] = s0 * _PREFACTOR, s1 * _PREFACTOR, s2 * _PREFACTOR
    sums[3], sums[4], sums[5] = s3 * _PREFACTOR, s4 * _PREFACTOR, s5 * _PREFACTOR


@_jit
def _disc(w, un, um, beta, disc_t, disc_s, disc_w, out, jac):
    """Far centre or pure sliding: Gauss quadrature over the disc in the velocities."""
    force_major = force_minor = moment = loss = 0.0
    for r in range(3):
        for k in range(3):
            jac[r, k] = 0.0
    for node in range(disc_t.size):
        t, s, weight = disc_t[node], disc_s[node], disc_w[node]
        dv_major = w * beta * s + um
        dv_minor = un - w * t
        norm = math.hypot(dv_major, dv_minor)
        e_major, e_minor = dv_major / norm, dv_minor / norm
        arm = beta * s * e_major - t * e_minor
        force_major -= e_major * weight
        force_minor -= e_minor * weight
        moment += arm * weight
        loss += norm * weight
        perp_major, perp_minor = -e_minor, e_major
        lever = beta * s * perp_major - t * perp_minor
        for k in range(3):
            along = lever if k == 0 else (perp_minor if k == 1 else perp_major)
            scale = along / norm
            jac[0, k] -= perp_major * scale * weight
            jac[1, k] -= perp_minor * scale * weight
            jac[2, k] += lever * scale * weight
    out[0], out[1], out[2], out[3] = force_major, force_minor, moment, loss
    jac[3, 0], jac[3, 1], jac[3, 2] = moment, -force_minor, -force_major


@_jit
def friction_offset(w, un, um, beta, nodes, weights, disc_t, disc_s, disc_w, far_centre, out, jac, sums):
    """(force_major, force_minor, moment, loss) into ``out`` (4,) and their Jacobian ``jac`` (4, 3) of one contact
    (the normalisation of :class:`lowmodel.contact.ellipse_friction_offset.OffsetFriction`); False at rest
    (all three velocities 0: the numpy code's pure-spin value)."""
    slip = math.hypot(un, um)
    scaled = math.hypot(un, um / beta)
    if w == 0.0 and slip == 0.0:
        return False
    if scaled >= far_centre * abs(w):
        _disc(w, un, um, beta, disc_t, disc_s, disc_w, out, jac)
        return True
    kappa = un / w
    lam = -um / (w * beta)
    _centred(kappa, lam, beta, nodes, weights, sums)
    f_major, f_minor, loss_hat, c_ss, c_sc, c_cc = sums[0], sums[1], sums[2], sums[3], sums[4], sums[5]
    sign = 1.0 if w > 0.0 else -1.0
    absw = abs(w)
    mom = kappa * f_minor - beta * lam * f_major + loss_hat
    d = ((-c_sc, beta * c_cc), (-c_ss, beta * c_sc),
         (-kappa * c_ss + beta * lam * c_sc, beta * (kappa * c_sc - beta * lam * c_cc)))
    for row in range(3):
        d0, d1 = d[row]
        jac[row, 0] = -(kappa * d0 + lam * d1) / absw
        jac[row, 1] = d0 / absw
        jac[row, 2] = -d1 / (beta * absw)
    out[0], out[1], out[2], out[3] = sign * f_major, sign * f_minor, sign * mom, absw * loss_hat
    jac[3, 0], jac[3, 1], jac[3, 2] = sign * mom, -sign * f_minor, -sign * f_major
    return True


# --------------------------------------------------------------------------
# lin2019 eqs 36-54 of every ball (lowmodel.screw.ball.ball_terms)
# --------------------------------------------------------------------------
@_jit
def ball_terms(unknowns, shift, geometry, scalars, level_coarse, nodes_coarse, weights_coarse, nodes_fine,  # noqa: C901 - one contact loop of eqs 36-54
               weights_fine, disc_t, disc_s, disc_w, far_centre, smallest_slip, residual, jacobian, axial,
               axial_gradient, contact, input_power):
    """Residual (n, 6), Jacobian (n, 6, 7), axial (n,), its gradient (n, 7), contact fields (n, 4, CONTACT_FIELDS)
    and nut input power (n,) at scaled ``unknowns`` (n, 6) and scaled nut ``shift`` (n,); returns
    :data:`CONVERGED`, or :data:`FALLBACK` where the numpy code must evaluate (outputs then undefined)."""
    n = unknowns.shape[0]
    length, orbit_scale, spin_scale, force_scale = scalars[0], scalars[1], scalars[2], scalars[3]
    radius, s, c, nut_speed, helix_radius = scalars[4], scalars[5], scalars[6], scalars[7], scalars[8]
    preload, groove_radius, mu = scalars[9], scalars[10], scalars[11]
    gap = radius + preload - groove_radius
    # first pass: the loaded contacts decide the quadrature level (FRICTION_LEVEL of lowmodel.screw.ball)
    smallest_ratio = math.inf
    for j in range(n):
        x_b, z_b, u = unknowns[j, 0] * length, unknowns[j, 1] * length, shift[j] * length
        for i in range(4):
            dx = x_b - geometry[j, i, CENTRE_X]
            dz = z_b - u * (c * geometry[j, i, ON_NUT]) - geometry[j, i, CENTRE_Z]
            if math.sqrt(dx * dx + dz * dz) + gap > 0.0:
                smallest_ratio = min(smallest_ratio, geometry[j, i, B_OVER_A])
    nodes, weights = nodes_fine, weights_fine
    if smallest_ratio >= level_coarse:
        nodes, weights = nodes_coarse, weights_coarse
    fr = np.empty(4)
    fr_jac = np.empty((4, 3))
    sums = np.empty(6)
    rows = np.empty((6, _D))
    axial_sum = np.empty((1, _D))
    for j in range(n):
        x_b = _variable(unknowns[j, 0], 0, length)
        z_b = _variable(unknowns[j, 1], 1, length)
        orbit = _variable(unknowns[j, 2], 2, orbit_scale)
        o0 = _variable(unknowns[j, 3], 3, spin_scale)
        o1 = _variable(unknowns[j, 4], 4, spin_scale)
        o2 = _variable(unknowns[j, 5], 5, spin_scale)
        u = _variable(shift[j], 6, length)
        rows[:] = 0.0
        axial_sum[:] = 0.0
        power = 0.0
        for i in range(4):
            on_nut = geometry[j, i, ON_NUT]
            hertz_c = geometry[j, i, HERTZ]
            dx = _shift(x_b, -geometry[j, i, CENTRE_X])
            dz = _shift(_sub(z_b, _scale(u, c * on_nut)), -geometry[j, i, CENTRE_Z])
            distance = _sqrt(_add(_mul(dx, dx), _mul(dz, dz)))
            ex, ez = _div(dx, distance), _div(dz, distance)
            approach = _shift(distance, gap)
            loaded = approach[0] > 0.0
            ratio = (approach[0] if loaded else 0.0) / hertz_c
            force_v = ratio ** 1.5
            force = _with_value(_scale(approach, 1.5 * math.sqrt(ratio) / hertz_c), force_v)
            semi = _with_value(_scale(force, (geometry[j, i, SEMI_UNIT] * np.cbrt(force_v)) / (3.0 * force_v)
                                      if loaded else 0.0), geometry[j, i, SEMI_UNIT] * np.cbrt(force_v))
            relative = _shift(orbit, -nut_speed * on_nut)
            q0, q2 = _scale(ex, radius), _scale(ez, radius)
            h0, h1, h2 = _scale(q2, s), _shift(_scale(q0, c), helix_radius), _scale(q0, -s)
            sv0 = _add(_scale(relative, 0.0), o0)
            sv2 = _add(_scale(relative, c), o2)
            turn0 = _mul(o1, q2)
            turn1 = _sub(_mul(o2, q0), _mul(o0, q2))
            turn2 = _scale(_mul(o1, q0), -1.0)
            slip0 = _add(_mul(relative, h0), turn0)
            slip1 = _add(_mul(relative, h1), turn1)
            slip2 = _add(_mul(relative, h2), turn2)
            in0, in2 = _scale(ex, -1.0), _scale(ez, -1.0)
            spin = _add(_mul(sv0, in0), _mul(sv2, in2))
            spin_velocity = _mul(spin, semi)
            slip_major = _add(_mul(slip0, ez), _mul(slip2, in0))   # major = (e_z, 0, -e_x)
            fm, fn, fo = _ZERO, _ZERO, _ZERO
            loss_unit = 0.0
            if loaded:
                w, un, um = spin_velocity[0], slip1[0], slip_major[0]
                if not (math.isfinite(w) and math.isfinite(un) and math.isfinite(um)):
                    return FALLBACK
                largest = max(abs(w), abs(un), abs(um))
                if 0.0 < largest < smallest_slip:
                    return FALLBACK
                if not friction_offset(w, un, um, geometry[j, i, B_OVER_A], nodes, weights, disc_t, disc_s, disc_w,
                                       far_centre, fr, fr_jac, sums):
                    return FALLBACK
                fm = _chain(fr[0], fr_jac, 0, spin_velocity, slip1, slip_major)
                fn = _chain(fr[1], fr_jac, 1, spin_velocity, slip1, slip_major)
                fo = _chain(fr[2], fr_jac, 2, spin_velocity, slip1, slip_major)
                loss_unit = fr[3]
            mu_force = _scale(force, mu)
            f_major, f_minor = _mul(fm, mu_force), _mul(fn, mu_force)
            fr0, fr1, fr2 = _mul(ez, f_major), f_minor, _mul(in0, f_major)
            moment_mag = _mul(_mul(fo, mu_force), semi)
            cm0, cm2 = _mul(ex, moment_mag), _mul(ez, moment_mag)
            am0 = _scale(_mul(q2, fr1), -1.0)
            am1 = _sub(_mul(q2, fr0), _mul(q0, fr2))
            am2 = _mul(q0, fr1)
            tf0 = _add(_mul(_scale(ex, -1.0), force), fr0)
            tf1 = fr1
            tf2 = _add(_mul(_scale(ez, -1.0), force), fr2)
            inv = 1.0 / radius
            _accumulate(rows, 0, tf0)
            _accumulate(rows, 1, tf1)
            _accumulate(rows, 2, tf2)
            _accumulate(rows, 3, _scale(_add(am0, cm0), inv))
            _accumulate(rows, 4, _scale(am1, inv))
            _accumulate(rows, 5, _scale(_add(am2, cm2), inv))
            if on_nut == 0.0:
                _accumulate(axial_sum, 0, _add(_scale(tf1, s), _scale(tf2, c)))
            else:
                power += ((fr0[0] * h0[0] + fr1[0] * h1[0]) + fr2[0] * h2[0] + cm2[0] * c) * nut_speed
            out = contact[j, i]
            out[0], out[1], out[2], out[3], out[4] = force_v, ex[0], ez[0], approach[0], semi[0]
            out[5], out[6], out[7] = spin[0], slip1[0], slip_major[0]
            out[8], out[9], out[10] = fr0[0], fr1[0], fr2[0]
            out[11], out[12], out[13] = cm0[0], 0.0, cm2[0]
            out[14] = mu * force_v * loss_unit
        for row in range(6):
            residual[j, row] = rows[row, 0] / force_scale
            for col in range(_K):
                jacobian[j, row, col] = rows[row, 1 + col] / force_scale
        axial[j] = axial_sum[0, 0] / force_scale
        for col in range(_K):
            axial_gradient[j, col] = axial_sum[0, 1 + col] / force_scale
        input_power[j] = power
    return CONVERGED


# --------------------------------------------------------------------------
# the B2B chain of a few balls (lowmodel.screw.b2b, lowmodel.b2b_chain) and its damped Newton
# --------------------------------------------------------------------------
_FB_SMOOTHING = 1e-14  # as lowmodel.b2b_chain: the Fischer-Burmeister smoothing
_B2B_REGULARISATION = 1e-14  # as lowmodel.screw.b2b: |s| floor in units of R_B * speed


@_jit
def pair_loads(spins, forces, chord, rot, radius, mu, speed, n, ring, load, d_spin, d_force):
    """lin2019 eqs 57-59 (:func:`lowmodel.screw.b2b.b2b_loads`) for the chain's pairs: loads (n, 6) [N, N m],
    d_spin (p, 2, 2, 6, 3), d_force (p, 2, 6).  The matrix products go to BLAS as numpy's ``@`` does (``np.dot``
    into scratch arrays: the same routine, so the same bits), the element-wise steps are loops in numpy's order, so
    a pair allocates nothing; ``rot^T B`` and ``-rot^T`` are the same for every pair."""
    pairs = n if ring else n - 1
    a_mat = np.zeros((3, 3))
    a_mat[0, 1], a_mat[0, 2], a_mat[1, 0] = chord[2], -chord[1], -chord[2]
    a_mat[1, 2], a_mat[2, 0], a_mat[2, 1] = chord[0], chord[1], -chord[0]   # -R [chord]x
    for r in range(3):
        for q in range(3):
            a_mat[r, q] *= radius
    b_mat = -a_mat
    rot_t = np.ascontiguousarray(rot.T)
    minus_rot_t = -rot_t
    rot_t_b = rot_t @ b_mat
    load[:] = 0.0
    floor = (_B2B_REGULARISATION * radius * speed) ** 2
    rotated, total, slip, direction = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    friction, force_behind, moment, vector = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    product, dfd, b_dfd = np.empty(3), np.empty(3), np.empty(3)
    scaled, d_behind, d_rotated, block = np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3)), np.empty((3, 3))
    for p in range(pairs):
        behind, ahead = p, (p + 1) % n
        np.dot(rot, spins[ahead], rotated)
        for i in range(3):
            total[i] = spins[behind, i] + rotated[i]
        np.dot(a_mat, total, slip)
        speeds = math.sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2])
        norm = math.sqrt(speeds ** 2 + floor)
        scale = -mu * forces[p]
        for i in range(3):
            direction[i] = slip[i] / norm
            friction[i] = scale * direction[i]
            force_behind[i] = -forces[p] * chord[i] + friction[i]
        np.dot(b_mat, friction, moment)
        for i in range(3):
            load[behind, i] += force_behind[i]
            load[behind, 3 + i] += moment[i]
            vector[i] = -force_behind[i]
        np.dot(rot_t, vector, product)
        load[ahead, :3] += product
        np.dot(rot_t, moment, product)
        load[ahead, 3:] += product
        factor = -mu * forces[p] / norm
        for r in range(3):   # factor (I - d d^T)
            for c in range(3):
                scaled[r, c] = factor * ((1.0 if r == c else 0.0) - direction[r] * direction[c])
        np.dot(scaled, a_mat, d_behind)
        np.dot(d_behind, rot, d_rotated)
        for side in range(2):
            d_fric = d_behind if side == 0 else d_rotated
            d_spin[p, 0, side, :3] = d_fric
            np.dot(b_mat, d_fric, block)
            d_spin[p, 0, side, 3:] = block
            np.dot(minus_rot_t, d_fric, block)
            d_spin[p, 1, side, :3] = block
            np.dot(rot_t_b, d_fric, block)
            d_spin[p, 1, side, 3:] = block
        for i in range(3):
            dfd[i] = -mu * direction[i]
            d_force[p, 0, i] = -chord[i] + dfd[i]
            vector[i] = chord[i] - dfd[i]
        np.dot(b_mat, dfd, b_dfd)
        d_force[p, 0, 3:] = b_dfd
        np.dot(rot_t, vector, product)
        d_force[p, 1, :3] = product
        np.dot(rot_t, b_dfd, product)
        d_force[p, 1, 3:] = product


@_jit
def ball_outputs(n):
    """The output arrays of :func:`ball_terms` for ``n`` balls: residual (n, 6), Jacobian (n, 6, 7), axial (n,), its
    gradient (n, 7), contact fields (n, 4, CONTACT_FIELDS), nut input power (n,)."""
    return (np.empty((n, 6)), np.empty((n, 6, _K)), np.empty(n), np.empty((n, _K)), np.empty((n, 4, CONTACT_FIELDS)),
            np.empty(n))


@_jit
def copy_outputs(source, target):
    """Copy the :func:`ball_outputs` ``source`` into ``target``."""
    target[0][:] = source[0]
    target[1][:] = source[1]
    target[2][:] = source[2]
    target[3][:] = source[3]
    target[4][:] = source[4]
    target[5][:] = source[5]


@_jit
def chain_residual(z, n, big_k, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars,
                   residual, terms):
    """The residual of the screw chain (:func:`lowmodel.b2b_chain.chain_system` of
    :func:`lowmodel.screw.b2b._solve_attempt`) at ``z`` into ``residual`` (the ball terms into ``terms``,
    :func:`ball_outputs`), in either layout of the unknowns: ``big_k`` per ball, the ball's 6, its nut shift at ``j
    big_k + 6`` where ``per_ball`` (else one at ``n big_k``, the last row the axial balance), the force slot of the
    pair ``(j, j + 1)`` last.  Rows: lin2019 eq 54 of each ball with the B2B loads of eqs 57-59 (moments / R_B, in
    units of the force scale), the axial balance, eqs 60-61 by Fischer-Burmeister (``slot = 0`` where the pair does
    not touch or past the chain's end).  Returns ``(status, d_spin, d_force, d_phi)`` for the Jacobian: the
    derivatives of :func:`pair_loads` and, per pair, ``d phi / d F`` and ``d phi / d omega_B`` of the ball ahead
    (that of the ball behind its negative; ``(1, 0)`` for a placeholder); status that of :func:`ball_terms` (the rest
    undefined unless :data:`CONVERGED`)."""
    (level_coarse, nodes_coarse, weights_coarse, nodes_fine, weights_fine, disc_t, disc_s, disc_w, far_centre,
     smallest_slip) = tables
    radius, mu, speed, rate_scale = pair_scalars[0], pair_scalars[1], pair_scalars[2], pair_scalars[3]
    spin_scale, force_scale = scalars[2], scalars[3]
    k = big_k - 1
    pairs = n if ring else n - 1
    unknowns = np.empty((n, 6))
    shift = np.empty(n)
    slots = np.empty(n)
    for j in range(n):
        for q in range(6):
            unknowns[j, q] = z[j * big_k + q]
        shift[j] = z[j * big_k + 6] if per_ball else z[n * big_k]
        slots[j] = z[j * big_k + k]
    d_spin = np.zeros((max(pairs, 1), 2, 2, 6, 3))
    d_force = np.zeros((max(pairs, 1), 2, 6))
    d_phi = np.empty((n, 2))
    ball_res, ball_jac, axial, axial_gradient, contact, power = terms
    status = ball_terms(unknowns, shift, geometry, scalars, level_coarse, nodes_coarse, weights_coarse, nodes_fine,
                        weights_fine, disc_t, disc_s, disc_w, far_centre, smallest_slip, ball_res, ball_jac, axial,
                        axial_gradient, contact, power)
    if status != CONVERGED:
        return status, d_spin, d_force, d_phi
    lam = np.zeros(n)
    for j in range(n):
        if live[j]:
            lam[j] = slots[j]
    forces = np.zeros(max(pairs, 1))
    for p in range(pairs):
        forces[p] = lam[p]
    load = np.empty((n, 6))
    pair_loads(unknowns[:, 3:6] * spin_scale, forces * force_scale, chord, rot, radius, mu, speed, n, ring, load,
               d_spin, d_force)   # no pairs (one ball): no loads
    for j in range(n):
        base = j * big_k
        for r in range(6):
            residual[base + r] = ball_res[j, r]
        if per_ball:
            residual[base + 6] = axial[j] - targets[j]
        for r in range(6):   # the B2B loads (eqs 57-59), moments / R_B, in units of the force scale
            residual[base + r] += (load[j, r] / radius if r >= 3 else load[j, r]) / force_scale
    if not per_ball:
        total = 0.0
        for j in range(n):
            total += axial[j]
        residual[n * big_k] = total - targets[0]
    for j in range(n):   # eqs 60-61: phi(F, gamma rate) = 0, Fischer-Burmeister; placeholders: slot = 0
        row = j * big_k + k
        if not live[j]:
            residual[row] = slots[j]
            d_phi[j, 0], d_phi[j, 1] = 1.0, 0.0
            continue
        ahead = (j + 1) % n
        rate = (unknowns[ahead, 2] - unknowns[j, 2]) * rate_scale if j < pairs else 0.0
        a = lam[j]
        root = math.sqrt(a * a + rate * rate + _FB_SMOOTHING ** 2)
        residual[row] = a + rate - root
        d_phi[j, 0] = 1.0 - a / root
        d_phi[j, 1] = (1.0 - rate / root) * rate_scale
    return status, d_spin, d_force, d_phi


@_jit
def chain_function(z, n, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars,  # noqa: C901 - the Jacobian of lowmodel.b2b_chain.chain_system, dense
                   residual, jacobian, terms):
    """Residual (:func:`chain_residual`) and dense Jacobian of the screw chain (:func:`lowmodel.b2b_chain.chain_system`
    of :func:`lowmodel.screw.b2b._solve_attempt`, Fischer-Burmeister complementarity of eqs 60-61), the ball terms
    into ``terms`` (:func:`ball_outputs`); returns the status of :func:`ball_terms`."""
    radius = pair_scalars[0]
    spin_scale, force_scale = scalars[2], scalars[3]
    k = 7 if per_ball else 6
    big_k = k + 1
    pairs = n if ring else n - 1
    status, d_spin, d_force, d_phi = chain_residual(z, n, big_k, per_ball, ring, live, targets, geometry, scalars,
                                                    tables, chord, rot, pair_scalars, residual, terms)
    if status != CONVERGED:
        return status
    ball_jac, axial_gradient = terms[1], terms[3]
    jacobian[:] = 0.0
    for j in range(n):
        base = j * big_k
        for r in range(6):
            for q in range(6):
                jacobian[base + r, base + q] = ball_jac[j, r, q]
            if per_ball:
                jacobian[base + r, base + 6] = ball_jac[j, r, 6]
            else:
                jacobian[base + r, n * big_k] = ball_jac[j, r, 6]
        if per_ball:
            for q in range(7):
                jacobian[base + 6, base + q] = axial_gradient[j, q]
    if not per_ball:
        block = 0.0
        for j in range(n):
            block += axial_gradient[j, 6]
            for q in range(6):
                jacobian[n * big_k, j * big_k + q] = axial_gradient[j, q]
        jacobian[n * big_k, n * big_k] = block
    spin_factor = spin_scale / force_scale
    for p in range(pairs):
        behind, ahead = p, (p + 1) % n
        for side_row in range(2):
            row_ball = behind if side_row == 0 else ahead
            for side_col in range(2):
                col_ball = behind if side_col == 0 else ahead
                for r in range(6):
                    for q in range(3):
                        value = d_spin[p, side_row, side_col, r, q]
                        value = (value / radius if r >= 3 else value) * spin_factor
                        jacobian[row_ball * big_k + r, col_ball * big_k + 3 + q] += value
            if live[p]:
                for r in range(6):
                    value = d_force[p, side_row, r] / radius if r >= 3 else d_force[p, side_row, r]
                    jacobian[row_ball * big_k + r, behind * big_k + k] += value
    for j in range(n):   # eqs 60-61
        row = j * big_k + k
        jacobian[row, row] = d_phi[j, 0]
        if live[j]:
            if j < pairs:
                jacobian[row, ((j + 1) % n) * big_k + 2] += d_phi[j, 1]
            jacobian[row, j * big_k + 2] += -d_phi[j, 1]
    return CONVERGED


@_inline
def _evaluate(evaluation, z, state):
    """:func:`chain_function` at ``z`` into ``state`` (residual, Jacobian, ball terms), its rows weighted: the
    evaluation of :func:`lowmodel.newton_kernels.levenberg_marquardt`."""
    n, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, row_weight = evaluation
    residual, jacobian, terms = state
    status = chain_function(z, n, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot,
                            pair_scalars, residual, jacobian, terms)
    if status == CONVERGED:
        for r in range(residual.size):
            residual[r] *= row_weight[r]
            jacobian[r] *= row_weight[r]
    return status


@_inline
def _prepare(steps, state, _first):
    """The dense normal equations ``J^T J`` and ``J^T r`` (BLAS, as numpy's ``@``); no plain Newton step."""
    normal, gradient = steps[0], steps[1]
    residual, jacobian = state[0], state[1]
    normal[:] = jacobian.T @ jacobian
    gradient[:] = jacobian.T @ residual
    return np.max(np.diag(normal)), False


@_inline
def _step(steps, _state, damping, _plain, step):
    """``(J^T J + damping I) dx = -J^T r`` (:func:`_damped_solve`); False where it is singular."""
    normal, gradient, identity = steps
    return _damped_solve(normal, gradient, identity, damping, step)


@_jit
def _damped_solve(normal, gradient, identity, damping, step):
    """``step = (normal + damping I)^-1 (-gradient)`` by LAPACK's LU (``np.linalg.solve``); False where singular."""
    try:
        step[:] = np.linalg.solve(normal + damping * identity, -gradient)
    except Exception:  # noqa: BLE001 - numba raises a generic error for a singular matrix
        return False
    return True


@_inline
def _multiply(_steps, state, step, _plain, change):
    """``change = J step`` (BLAS, as numpy's ``@``)."""
    change[:] = state[1] @ step


@_jit
def newton(z0, n, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars,
           max_iterations, row_tolerance, row_weight, z, result, terms):
    """:func:`lowmodel.solvers.newton` (Levenberg-Marquardt, Nielsen's update, dense normal equations: the loop of
    :func:`lowmodel.newton_kernels.levenberg_marquardt`) on :func:`chain_function`; ``z`` the solution, ``result``
    (residual (size,) unweighted), ``terms`` the ball terms at ``z`` (:func:`ball_outputs`); returns ``(status,
    iterations, norm)`` with status :data:`CONVERGED`, :data:`NOT_CONVERGED`, :data:`NON_FINITE`,
    :data:`STATIONARY`, :data:`NO_DESCENT` or :data:`FALLBACK`."""
    size = z0.size
    evaluation = (n, per_ball, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, row_weight)
    steps = (np.empty((size, size)), np.empty(size), np.eye(size))   # J^T J, J^T r, I
    state = (np.empty(size), np.empty((size, size)), terms)
    trial_state = (np.empty(size), np.empty((size, size)), ball_outputs(n))
    z[:] = z0
    status, iterations, norm, state = levenberg_marquardt(_evaluate, _prepare, _step, _multiply, blas_dot, evaluation,
                                                          steps, z, state, trial_state, row_tolerance * row_weight,
                                                          row_weight, max_iterations, result)
    copy_outputs(state[2], terms)   # the terms at z (a no-op where they are there already)
    return status, iterations, norm


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernel with the argument types the model passes."""
    ball.warm_up_kernel(sys.modules[__name__])
    b2b.warm_up_kernel(sys.modules[__name__])
