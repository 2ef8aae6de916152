"""FASTSIM: Kalker's simplified theory of steady rolling contact, vectorised over many contacts.

Kalker (1982) 'A fast algorithm for the simplified theory of rolling contact', Vehicle System Dynamics 11,
1-13; Kalker (1990) Ch 3.  Each surface point deforms like a spring, ``u = L p`` (no interaction between
points), so the steady-state slip ``s = w - L dp/dx`` (rolling along ``+x``, material entering at the
leading edge ``x = a(y)``) integrates along each strip ``y = const`` from the leading edge, where ``p = 0``::

    p(x - dx) = Proj_g( p(x) - dx (xi - phi y,  eta + phi x) / L )

(stick while ``|p| < g``, else on the bound and opposite to the slip).  Three flexibilities make the no-slip
limit of each creepage reproduce Kalker's linear theory (:func:`flexibilities`)::

    L1 = 8 a / (3 C11 G),   L2 = 8 a / (3 C22 G),   L3 = pi a sqrt(a/b) / (4 C23 G)

and FASTSIM uses their mean weighted by the creepages (Kalker 1982), ``L = (|xi| L1 + |eta| L2 + c |phi| L3)
/ sqrt(xi^2 + eta^2 + c^2 phi^2)``, ``c = sqrt(a b)``: one flexibility keeps the slip direction of full slip
that of the rigid slip.

with the creepage coefficients ``C11, C22, C23`` of Kalker (1990) Table E.3 (:func:`kalker_coefficients`).
The traction bound is Kalker's parabolic one, ``g = mu p0' (1 - x^2/a^2 - y^2/b^2)`` with ``p0'`` such that the
elements' bounds sum to ``mu F`` (``2 F / (pi a b)`` in the continuum; with the parabola the simplified
theory's creep curves come closer to the exact theory's), or the Hertz ellipse (``bound="elliptic"``).
Conventions (axes, signs) are those of :mod:`lowmodel.contact.rolling`: ``x`` rolling, ``y`` lateral,
``z`` into body 1, forces on body 1.

Grid: ``n_y`` strips of equal width across ``[-b, b]``, each cut into ``n_x`` elements of equal length
across its chord ``[-a(y), a(y)]`` (Kalker 1982).  Cost ``O(n_x n_y)`` per contact; all contacts and strips
march together (numpy), so a batch of ``N`` contacts costs ``n_x`` vector steps of length ``N n_y``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["KALKER_TABLE_E3", "kalker_coefficients", "flexibilities", "FastsimResult", "fastsim"]

# Kalker (1990) Table E.3 (the same numbers are in CONTACT, src/m_hertz.f90): rows g = 0.1, 0.2, ..., 1.0;
# per row (C11, C22, C23) at Poisson's ratio (0, 0.25, 0.5).  "a_le_b": a (along rolling) <= b, g = a/b;
# "a_gt_b": a > b, g = b/a.
KALKER_TABLE_E3 = {
    "a_le_b": np.array([
        [[2.51, 3.31, 4.85], [2.51, 2.52, 2.53], [0.334, 0.473, 0.731]],
        [[2.59, 3.37, 4.81], [2.59, 2.63, 2.66], [0.483, 0.603, 0.809]],
        [[2.68, 3.44, 4.80], [2.68, 2.75, 2.81], [0.607, 0.715, 0.889]],
        [[2.78, 3.53, 4.82], [2.78, 2.88, 2.98], [0.720, 0.823, 0.977]],
        [[2.88, 3.62, 4.83], [2.88, 3.01, 3.14], [0.827, 0.929, 1.07]],
        [[2.98, 3.72, 4.91], [2.98, 3.14, 3.31], [0.930, 1.03, 1.18]],
        [[3.09, 3.81, 4.97], [3.09, 3.28, 3.48], [1.03, 1.14, 1.29]],
        [[3.19, 3.91, 5.05], [3.19, 3.41, 3.65], [1.13, 1.25, 1.40]],
        [[3.29, 4.01, 5.12], [3.29, 3.54, 3.82], [1.23, 1.36, 1.51]],
        [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]],
    ]),
    "a_gt_b": np.array([
        [[10.7, 11.7, 12.9], [10.7, 12.8, 16.0], [12.2, 14.6, 18.0]],
        [[6.96, 7.78, 8.82], [6.96, 8.14, 9.79], [5.72, 6.63, 7.89]],
        [[5.57, 6.34, 7.34], [5.57, 6.40, 7.51], [3.79, 4.32, 5.01]],
        [[4.84, 5.57, 6.57], [4.84, 5.48, 6.31], [2.88, 3.24, 3.70]],
        [[4.37, 5.10, 6.11], [4.37, 4.90, 5.56], [2.35, 2.62, 2.96]],
        [[4.06, 4.78, 5.80], [4.06, 4.50, 5.04], [2.01, 2.23, 2.50]],
        [[3.82, 4.54, 5.58], [3.82, 4.21, 4.67], [1.76, 1.95, 2.18]],
        [[3.65, 4.36, 5.42], [3.65, 3.99, 4.39], [1.58, 1.75, 1.94]],
        [[3.51, 4.22, 5.30], [3.51, 3.81, 4.16], [1.44, 1.59, 1.77]],
        [[3.40, 4.12, 5.20], [3.40, 3.67, 3.98], [1.33, 1.47, 1.63]],
    ]),
}
_NU = np.array([0.0, 0.25, 0.5])


def _asymptote_a_le_b(g: np.ndarray, nu: np.ndarray) -> np.ndarray:
    # Kalker (1990) eq (E.3 asymptotes), a << b (g = a/b -> 0): C11 = pi^2/(4 (1 - nu)), C22 = pi^2/4,
    # C23 = pi sqrt(g) / (3 (1 - nu)) (1 + nu (ln(16/g) - 5))
    c11 = math.pi**2 / (4.0 * (1.0 - nu))
    c22 = np.full_like(g, math.pi**2 / 4.0)
    c23 = math.pi * np.sqrt(g) / (3.0 * (1.0 - nu)) * (1.0 + nu * (np.log(16.0 / g) - 5.0))
    return np.stack(np.broadcast_arrays(c11, c22, c23), axis=-1)


def _asymptote_a_gt_b(g: np.ndarray, nu: np.ndarray) -> np.ndarray:
    # Kalker (1990), a >> b (g = b/a -> 0), with Lambda = ln(16/g^2)
    lam = np.log(16.0 / g**2)
    c11 = 2.0 * math.pi / ((lam - 2.0 * nu) * g) * (1.0 + (3.0 - math.log(4.0)) / (lam - 2.0 * nu))
    c22 = (2.0 * math.pi / g * (1.0 + (1.0 - nu) * (3.0 - math.log(4.0)) / ((1.0 - nu) * lam + 2.0 * nu))
           / ((1.0 - nu) * lam + 2.0 * nu))
    c23 = 2.0 * math.pi / (3.0 * g**1.5 * ((1.0 - nu) * lam - 2.0 + 4.0 * nu))
    return np.stack([c11, c22, c23], axis=-1)


def kalker_coefficients(a_over_b, poisson_ratio) -> np.ndarray:
    """Kalker's creepage coefficients ``(C11, C22, C23)`` of an ellipse, shape ``broadcast + (3,)``.

    ``a_over_b``: semi-axis along rolling over the lateral one, in ``(0, inf)``; ``poisson_ratio`` in
    ``[0, 0.5]``.  Inside Table E.3 (``g = min(a/b, b/a) >= 0.1``): linear in ``g`` between the rows and, at
    each row, ``1/C`` quadratic in ``nu`` through the table's three values (the coefficients are closer to
    linear in ``nu`` as ``1/C``); below ``g = 0.1`` Kalker's asymptotes (continuous to 1-5 %).
    """
    ratio = np.asarray(checks.positive("a_over_b", a_over_b), dtype=float)
    nu = np.asarray(checks.bounded("poisson_ratio", poisson_ratio, 0.0, 0.5, lower_closed=True,
                                   upper_closed=True), dtype=float)
    ratio, nu = np.broadcast_arrays(ratio, nu)
    out = np.empty(ratio.shape + (3,))
    wide = ratio <= 1.0
    g = np.where(wide, ratio, 1.0 / ratio)
    inside = g >= 0.1
    # interpolation in the table
    position = np.clip(10.0 * g - 1.0, 0.0, 9.0)
    row = np.minimum(position.astype(int), 8)
    frac = position - row
    for key, mask in (("a_le_b", wide & inside), ("a_gt_b", ~wide & inside)):
        if not np.any(mask):
            continue
        rows = KALKER_TABLE_E3[key]
        r, f, n = row[mask], frac[mask], nu[mask]
        values = (1.0 - f)[:, None, None] * rows[r] + f[:, None, None] * rows[r + 1]  # (m, 3 coeffs, 3 nu)
        inverse = 1.0 / values
        # Lagrange through nu = 0, 0.25, 0.5 of 1/C
        basis = np.stack([(n - 0.25) * (n - 0.5) / ((0.0 - 0.25) * (0.0 - 0.5)),
                          (n - 0.0) * (n - 0.5) / ((0.25 - 0.0) * (0.25 - 0.5)),
                          (n - 0.0) * (n - 0.25) / ((0.5 - 0.0) * (0.5 - 0.25))], axis=-1)  # (m, 3 nu)
        out[mask] = 1.0 / np.einsum("mcn,mn->mc", inverse, basis)
    small = ~inside
    if np.any(small & wide):
        out[small & wide] = _asymptote_a_le_b(g[small & wide], nu[small & wide])
    if np.any(small & ~wide):
        out[small & ~wide] = _asymptote_a_gt_b(g[small & ~wide], nu[small & ~wide])
    return out


def flexibilities(semi_axis_rolling, semi_axis_lateral, shear_modulus, poisson_ratio) -> np.ndarray:
    """FASTSIM's ``(L1, L2, L3)`` [m/Pa] (module docstring), shape ``broadcast + (3,)``."""
    a = np.asarray(checks.positive("semi_axis_rolling", semi_axis_rolling, "m"), dtype=float)
    b = np.asarray(checks.positive("semi_axis_lateral", semi_axis_lateral, "m"), dtype=float)
    shear = np.asarray(checks.positive("shear_modulus", shear_modulus, "Pa"), dtype=float)
    c = kalker_coefficients(a / b, poisson_ratio)
    l1 = 8.0 * a / (3.0 * c[..., 0] * shear)
    l2 = 8.0 * a / (3.0 * c[..., 1] * shear)
    l3 = math.pi * a * np.sqrt(a / b) / (4.0 * c[..., 2] * shear)
    return np.stack([l1, l2, l3], axis=-1)


@dataclass(frozen=True)
class FastsimResult:
    """FASTSIM forces of a batch of contacts (arrays of the inputs' broadcast shape).

    ``force_rolling``, ``force_lateral`` [N] and ``spin_moment`` [N m] (about ``+z`` through the contact
    centre) on body 1; ``stick_fraction`` (of the elements); ``frictional_power`` [W] at ``rolling_speed``.
    """

    force_rolling: np.ndarray
    force_lateral: np.ndarray
    spin_moment: np.ndarray
    stick_fraction: np.ndarray
    frictional_power: np.ndarray


def fastsim(semi_axis_rolling, semi_axis_lateral, normal_force, shear_modulus, poisson_ratio, friction_coefficient,
            creepage_rolling, creepage_lateral, spin, cells=(20, 20), *, rolling_speed=1.0,
            bound: str = "parabolic") -> FastsimResult:
    """Kalker's FASTSIM for a batch of Hertz contacts; every argument broadcasts (one contact per element).

    Arguments as :func:`lowmodel.contact.rolling.steady_rolling` (SI; ``spin`` in rad/m); ``cells`` =
    ``(n_x, n_y)`` elements per strip and strips.  ``bound``: ``"parabolic"`` (Kalker's FASTSIM) or
    ``"elliptic"`` (the Hertz pressure: the full-slip limit is then lin2019's eqs A4-A7, the ellipse-friction
    maps; with the parabola it is not, 10-16 % lower in the spin moment of a ball-groove contact).
    Returns :class:`FastsimResult`.
    """
    checks.choice("bound", bound, ("parabolic", "elliptic"))
    a = np.asarray(checks.positive("semi_axis_rolling", semi_axis_rolling, "m"), dtype=float)
    b = np.asarray(checks.positive("semi_axis_lateral", semi_axis_lateral, "m"), dtype=float)
    force = np.asarray(checks.positive("normal_force", normal_force, "N"), dtype=float)
    mu = np.asarray(checks.positive("friction_coefficient", friction_coefficient), dtype=float)
    xi = np.asarray(checks.finite("creepage_rolling", creepage_rolling), dtype=float)
    eta = np.asarray(checks.finite("creepage_lateral", creepage_lateral), dtype=float)
    phi = np.asarray(checks.finite("spin", spin, "rad/m"), dtype=float)
    speed = np.asarray(checks.positive("rolling_speed", rolling_speed, "m/s"), dtype=float)
    try:
        nx, ny = cells
    except (TypeError, ValueError):
        raise ValueError(f"cells must be (n_x, n_y), got {cells!r}") from None
    nx = checks.count("cells[0] (n_x)", nx, 1, 10000)
    ny = checks.count("cells[1] (n_y)", ny, 1, 10000)
    flex = flexibilities(a, b, shear_modulus, poisson_ratio)
    a, b, force, mu, xi, eta, phi, speed, l1, l2, l3 = np.broadcast_arrays(
        a, b, force, mu, xi, eta, phi, speed, flex[..., 0], flex[..., 1], flex[..., 2])
    shape = a.shape
    col = (slice(None), None)
    a, b, force, mu, xi, eta, phi, speed, l1, l2, l3 = (v.reshape(-1)[col] for v in
                                                         (a, b, force, mu, xi, eta, phi, speed, l1, l2, l3))
    t = -1.0 + (2.0 * np.arange(ny) + 1.0) / ny  # strip centres y/b
    y = b * t[None, :]
    half = a * np.sqrt(1.0 - t * t)[None, :]  # a(y)
    dx = 2.0 * half / nx
    area = dx * (2.0 * b / ny)
    # Kalker's parabolic bound mu p0' (1 - x^2/a^2 - y^2/b^2), p0' scaled so that the elements' bound sums to
    # mu F exactly (the midpoint sum of the parabola, 2 F/(pi a b), is 0.15 % off at 20 x 20)
    u = 1.0 - (2.0 * np.arange(nx) + 1.0) / nx
    if bound == "parabolic":
        across, along = 1.0 - t * t, 1.0 - u * u
    else:  # elliptic: sqrt(1 - x^2/a^2 - y^2/b^2) = sqrt(1 - y^2/b^2) sqrt(1 - u^2)
        across, along = np.sqrt(1.0 - t * t), np.sqrt(1.0 - u * u)
    total = 4.0 / (nx * ny) * float(np.sum(np.sqrt(1.0 - t * t) * across)) * float(np.sum(along))
    bound_0 = mu * force / (a * b * total) * across[None, :]
    # Kalker's (1982) single flexibility, weighted by the creepages: L = (|xi| L1 + |eta| L2 + c |phi| L3) /
    # sqrt(xi^2 + eta^2 + c^2 phi^2), c = sqrt(a b) (L1 without creepage); the slip direction in full slip is
    # then the rigid slip's (w = (xi - phi y, eta + phi x))
    c = np.sqrt(a * b)
    weight = np.sqrt(xi * xi + eta * eta + (c * phi) ** 2)
    flexibility = np.where(weight > 0.0, (np.abs(xi) * l1 + np.abs(eta) * l2 + c * np.abs(phi) * l3)
                           / np.where(weight > 0.0, weight, 1.0), l1)
    # the increments over one element: dx (xi - phi y) / L and dx (eta + phi x) / L, x = a(y) u_i
    step_x = dx * (xi - phi * y) / flexibility
    step_y = dx * eta / flexibility
    step_spin = dx * phi / flexibility * half
    px = np.zeros_like(y)
    py = np.zeros_like(y)
    sum_x = np.zeros_like(y)
    sum_y = np.zeros_like(y)
    sum_xy = np.zeros_like(y)
    slipping = np.zeros_like(y)
    dissipation = np.zeros_like(y)
    for i in range(nx):
        u = 1.0 - (2.0 * i + 1.0) / nx  # x / a(y) at the element centre
        px -= step_x
        py -= step_y + u * step_spin
        g = bound_0 * along[i]
        norm = np.hypot(px, py)
        sliding = norm > g
        scale = np.where(sliding, g / np.where(sliding, norm, 1.0), 1.0)
        # slip per unit rolling distance s = (L/dx)(p - p_trial), nonzero in slip elements only
        dissipation += (1.0 - scale) * scale * (px * px + py * py)
        px *= scale
        py *= scale
        sum_x += px
        sum_y += py
        sum_xy += u * py
        slipping += sliding
    fx = np.sum(sum_x * area, axis=1)
    fy = np.sum(sum_y * area, axis=1)
    mz = np.sum((half * sum_xy - y * sum_x) * area, axis=1)
    stick = nx * ny - np.sum(slipping, axis=1)
    power = np.sum(dissipation * flexibility * area / dx, axis=1)
    return FastsimResult(fx.reshape(shape), fy.reshape(shape), mz.reshape(shape), (stick / (nx * ny)).reshape(shape),
                         (power * speed[:, 0]).reshape(shape))
