"""Post-processing of FE contact states: Hertz ellipse estimators and the approach convention.

* :func:`moment_ellipse` - the estimator of every FE scene (mortar multipliers, a piecewise-linear
  pressure): the Hertz ellipse with the same force and the same second moments as the FE pressure.
  For Hertz's ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)`` (Johnson 1985 eq 4.29 form),
  ``int p dA = 2 pi a b p0 / 3``, ``int p x^2 dA / int p dA = a^2 / 5`` and
  ``int p y^2 dA / int p dA = b^2 / 5``, so ``a = sqrt(5 <x^2>)``, ``b = sqrt(5 <y^2>)``,
  ``p0 = 3 F / (2 pi a b)``.  These are integrals of the pressure against smooth weights, the
  quantities a mortar multiplier converges in; a pointwise fit is pulled by the edge ring of the
  multipliers, which depends on which edge nodes are kept; the moments do not (measured in
  docs/fem.md, the mesh-convergence study of groove f = 0.56).
* :func:`fit_ellipse` - least-squares fit of the Hertz pressure field
  ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)`` (Johnson 1985 eq 4.29 form) to the
  nodal pressures of all candidate nodes (zeros included).  Single nodal
  pressures of node-to-surface contact scatter (docs/fem.md), the fitted
  ``a, b, p0`` do not.
* :func:`approach_fit` - the bulk-compliance convention for the approach:
  the FE approach ``U(F)`` of the two reference faces (the ball's load face and
  the counter's support) is ``U = C_H F^(2/3) + C_b F``: the Hertz approach of
  distant points (``C_H F^(2/3)``, lin2019 eq 53) plus the linear compliance
  ``C_b`` of the finite bodies outside the contact zone (their deviation from
  half-spaces; negative when the bodies are stiffer than half-spaces, as a
  hemisphere loaded on its flat face is).  ``C_H`` and ``C_b`` are fitted by
  least squares to a load sweep solved with the same condensed compliance;
  the FE contact approach is ``delta = C_H F^(2/3)``.  The next term of the
  expansion is of relative order ``(a / L)^3`` (L the body size).
* :func:`nodal_stress` - von Mises stress and the normal stress along the contact normal at the
  nodes, from Hooke's law of :mod:`fem.elasticity` (the fields of ``show``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.optimize import least_squares

from ballbench.fem.elasticity import lame, stress, von_mises

__all__ = ["EllipseFit", "moment_ellipse", "fit_ellipse", "ApproachFit", "approach_fit", "mesh_check", "nodal_stress"]


@dataclass(frozen=True)
class EllipseFit:
    """Fitted Hertz pressure field: semi-axes ``a`` (along x), ``b`` (along y) [m],
    peak ``p0`` [Pa], centre ``(x0, y0)`` [m], rms residual [Pa], ``force`` of the
    fitted field ``2 pi p0 a b / 3`` [N] (full model)."""

    a: float
    b: float
    p0: float
    x0: float
    y0: float
    rms: float
    force: float


# Dunavant's 6-point rule (degree 4, positive weights): exact for a linear pressure times a quadratic weight
_DUNAVANT_A = (0.445948490915965, 0.091576213509771)
_DUNAVANT_W = (0.223381589678011, 0.109951743655322)


def _degree4_rule() -> tuple[np.ndarray, np.ndarray]:
    bary, weights = [], []
    for a, w in zip(_DUNAVANT_A, _DUNAVANT_W):
        c = 1.0 - 2.0 * a
        bary += [(c, a, a), (a, c, a), (a, a, c)]
        weights += [w, w, w]
    return np.array(bary), np.array(weights)


def moment_ellipse(xy: np.ndarray, triangles: np.ndarray, nodal: np.ndarray, *, symmetric_x: bool = True,
                   symmetric_y: bool = True, symmetry_factor: int = 1, check_sign: bool = True) -> EllipseFit:
    """Hertz ellipse with the force and second moments of a piecewise-linear pressure field.

    ``xy`` (n, 2) [m] node positions in the contact frame (a along x, b along y), ``triangles`` (k, 3)
    indices into ``xy`` (the pressure's support), ``nodal`` (n,) [Pa] the nodal pressures (mortar
    multipliers).  The integrals are exact (a degree-4 rule on each triangle).  The centre is the
    pressure centroid along an axis that is not ``symmetric_*`` (0 along a symmetric one: a symmetry
    cut or a patch centred on that axis).  ``symmetry_factor`` (1, 2 or 4) turns the force of the
    meshed cut into the full model's.  ``check_sign=False`` admits negative nodal values (a projected
    field rather than contact multipliers).  Returns :class:`EllipseFit` with ``a = sqrt(5 <(x - x0)^2>)``,
    ``b = sqrt(5 <(y - y0)^2>)``, ``p0 = 3 F / (2 pi a b)`` (Johnson 1985 eq 4.29 form integrated),
    ``rms`` the rms difference [Pa] of that Hertz field and the FE pressure over the triangles'
    quadrature points, ``force`` the full model's force [N].
    """
    xy = np.asarray(xy, float)
    triangles = np.asarray(triangles, dtype=np.int64)
    nodal = np.asarray(nodal, float)
    if xy.ndim != 2 or xy.shape[1] != 2 or nodal.shape != (len(xy),):
        raise ValueError(f"xy must be (n, 2) and nodal (n,), got {xy.shape} and {nodal.shape}")
    if triangles.ndim != 2 or triangles.shape[1] != 3 or triangles.size == 0:
        raise ValueError(f"triangles must be a non-empty (k, 3) index array, got shape {triangles.shape}")
    if symmetry_factor not in (1, 2, 4):
        raise ValueError(f"symmetry_factor must be 1, 2 or 4, got {symmetry_factor!r}")
    if not np.all(np.isfinite(nodal)) or (check_sign and np.any(nodal < 0)):
        raise ValueError("nodal pressures must be finite and >= 0 Pa")
    if np.count_nonzero(nodal > 0) < 5:
        raise ValueError(f"only {int(np.count_nonzero(nodal > 0))} nodes in contact: cannot fit an ellipse "
                         "(need >= 5)")
    bary, weight = _degree4_rule()
    corners = xy[triangles]  # (k, 3, 2)
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    points = np.einsum("qv,kvd->kqd", bary, corners)  # (k, 6, 2)
    values = np.einsum("qv,kv->kq", bary, nodal[triangles])  # the linear pressure there (k, 6)
    dA = area[:, None] * weight[None, :]
    force = float(np.sum(values * dA))
    if not force > 0:
        raise ValueError("the pressure field carries no force: cannot fit an ellipse")

    def mean(f):
        return float(np.sum(values * dA * f)) / force

    x, y = points[..., 0], points[..., 1]
    x0 = 0.0 if symmetric_x else mean(x)
    y0 = 0.0 if symmetric_y else mean(y)
    a = float(np.sqrt(5.0 * mean((x - x0) ** 2)))
    b = float(np.sqrt(5.0 * mean((y - y0) ** 2)))
    full = symmetry_factor * force
    p0 = 3.0 * full / (2.0 * np.pi * a * b)
    hertz = _hertz_field((p0, a, b, x0, y0), points.reshape(-1, 2), False, False).reshape(values.shape)
    rms = float(np.sqrt(np.sum((hertz - values) ** 2 * dA) / np.sum(dA)))
    return EllipseFit(a, b, float(p0), float(x0), float(y0), rms, float(full))


def _hertz_field(params, xy, fix_x: bool, fix_y: bool):
    p0, a, b, x0, y0 = params
    x = xy[:, 0] - (0.0 if fix_x else x0)
    y = xy[:, 1] - (0.0 if fix_y else y0)
    s = 1.0 - (x / a) ** 2 - (y / b) ** 2
    return p0 * np.sqrt(np.clip(s, 0.0, None))


def fit_ellipse(xy: np.ndarray, pressure: np.ndarray, *, symmetric_x: bool = True,
                symmetric_y: bool = True) -> EllipseFit:
    """Fit ``p0, a, b`` (and the centre along a non-symmetric axis) to nodal pressures (least squares).

    Kept for node-to-surface forces and as a start; the FE scenes use :func:`moment_ellipse`.

    ``xy`` (n, 2) [m] node positions in the contact frame, ``pressure`` (n,) [Pa].
    """
    xy = np.asarray(xy, float)
    pressure = np.asarray(pressure, float)
    active = pressure > 0
    if active.sum() < 5:
        raise ValueError(f"only {int(active.sum())} nodes in contact: cannot fit an ellipse (need >= 5)")
    # moments of the active set as a starting point
    p_max = float(np.max(pressure))
    a0 = max(float(np.max(np.abs(xy[active, 0]))), 1e-12)
    b0 = max(float(np.max(np.abs(xy[active, 1]))), 1e-12)
    start = np.array([p_max, a0, b0, 0.0, 0.0])
    scale = np.array([p_max, a0, b0, a0, b0])

    def residual(z):
        return (_hertz_field(z * scale, xy, symmetric_x, symmetric_y) - pressure) / p_max

    sol = least_squares(residual, start / scale, method="lm", xtol=1e-12, ftol=1e-12, gtol=1e-12)
    p0, a, b, x0, y0 = sol.x * scale
    a, b = abs(a), abs(b)
    rms = float(np.sqrt(np.mean((residual(sol.x) * p_max) ** 2)))
    return EllipseFit(float(a), float(b), float(p0), 0.0 if symmetric_x else float(x0),
                      0.0 if symmetric_y else float(y0), rms, float(2.0 * np.pi * p0 * a * b / 3.0))


@dataclass(frozen=True)
class ApproachFit:
    """``U(F) = hertz_constant F^(2/3) + bulk_compliance F``: ``hertz_constant``
    [m/N^(2/3)], ``bulk_compliance`` [m/N], rms fit residual [m]."""

    hertz_constant: float
    bulk_compliance: float
    rms: float

    def contact_approach(self, force: float) -> float:
        """FE contact approach ``C_H F^(2/3)`` [m] at ``force`` [N]."""
        return self.hertz_constant * force ** (2.0 / 3.0)


def approach_fit(forces, approaches) -> ApproachFit:
    """Least-squares ``U = C_H F^(2/3) + C_b F`` over a load sweep (>= 3 loads [N], approaches [m])."""
    forces = np.asarray(forces, float)
    approaches = np.asarray(approaches, float)
    if forces.size < 3 or forces.size != approaches.size:
        raise ValueError(f"need >= 3 (force, approach) pairs of equal length, got {forces.size} and {approaches.size}")
    matrix = np.column_stack([forces ** (2.0 / 3.0), forces])
    coef, *_ = np.linalg.lstsq(matrix, approaches, rcond=None)
    rms = float(np.sqrt(np.mean((matrix @ coef - approaches) ** 2)))
    return ApproachFit(float(coef[0]), float(coef[1]), rms)


def mesh_check(h_contact: float, b: float, min_elements: float = 5.0) -> None:
    """Refuse a mesh with fewer than ``min_elements`` elements across the minor semi-axis ``b`` [m]."""
    if not (np.isfinite(h_contact) and h_contact > 0):
        raise ValueError(f"h_contact must be a finite length > 0 m, got {h_contact!r}")
    if b / h_contact < min_elements:
        raise ValueError(f"mesh too coarse for the contact patch: h_contact = {h_contact:.3e} m gives "
                         f"{b / h_contact:.2f} elements across b = {b:.3e} m; use h_contact <= "
                         f"{b / min_elements:.3e} m (at least {min_elements:g} elements across b)")


def force_operator(points: np.ndarray, triangles: np.ndarray, nodes: np.ndarray, subdivisions: int = 6):
    """Quadrature of consistent nodal forces ``f_j = int p N_j dA`` over the xy-projection
    of the surface ``triangles`` (k, 3) whose nodes are all in ``nodes`` (n,).

    Returns ``(xq (q, 2) [m], M (n, q) sparse [m^2])`` with ``f = M @ p(xq)``: each
    triangle is split into ``subdivisions^2`` sub-triangles, one centroid point each.
    Hertz pressure acts on the projected area (half-space theory), hence xy areas.
    """
    index = -np.ones(len(points), dtype=np.int64)
    index[nodes] = np.arange(len(nodes))
    tris = triangles[(index[triangles] >= 0).all(axis=1)]
    s = int(subdivisions)
    bary = []
    for i in range(s):
        for j in range(s - i):
            bary.append(((i + 1 / 3) / s, (j + 1 / 3) / s))  # upward sub-triangle centroid
            if i + j < s - 1:
                bary.append(((i + 2 / 3) / s, (j + 2 / 3) / s))  # downward one
    bary = np.array(bary)  # (s^2, 2): (l1, l2)
    lam = np.column_stack([1.0 - bary.sum(axis=1), bary])  # (s^2, 3)
    p = points[tris][:, :, :2]  # (k, 3, 2)
    area = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                        - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    xq = np.einsum("qv,kvd->kqd", lam, p).reshape(-1, 2)
    weight = (area[:, None] / len(bary)) * np.ones((1, len(bary)))  # (k, s^2)
    rows = index[tris][:, None, :].repeat(len(bary), axis=1)  # (k, s^2, 3)
    cols = np.arange(len(tris) * len(bary)).reshape(len(tris), len(bary))[:, :, None].repeat(3, axis=2)
    vals = weight[:, :, None] * lam[None, :, :]
    M = sp.csr_matrix((vals.ravel(), (rows.ravel(), cols.ravel())), shape=(len(nodes), xq.shape[0]))
    return xq, M


def fit_ellipse_forces(xq: np.ndarray, operator, forces: np.ndarray, *, symmetric_x: bool = True,
                       symmetric_y: bool = True) -> EllipseFit:
    """Fit the Hertz field to nodal contact forces ``forces`` (n,) [N] through their
    consistent-force ``operator`` (:func:`force_operator`): ``forces ~ M p(xq)``.

    This removes the bias of dividing forces by lumped areas near the edge of the
    patch, where the pressure falls as a square root.  The node-to-surface (P1) model's
    estimator; the mortar scenes use :func:`moment_ellipse` (the least-squares fit of a mortar
    pressure is pulled by its edge ring: module docstring).  The fitted ``a, b, p0`` are the whole
    ellipse's also on a symmetry cut, so ``force = 2 pi p0 a b / 3`` is the full model's without a
    symmetry factor (unlike :func:`moment_ellipse`, which integrates the meshed cut).
    """
    forces = np.asarray(forces, float)
    f_max = float(np.max(forces))
    if np.count_nonzero(forces > 0) < 5:
        raise ValueError(f"only {int(np.count_nonzero(forces > 0))} nodes in contact: cannot fit an ellipse")
    lumped = np.asarray(operator.sum(axis=1)).ravel()
    pressure = np.where(lumped > 0, forces / np.where(lumped > 0, lumped, 1.0), 0.0)
    xy_nodes = (operator @ xq) / np.where(lumped > 0, lumped, 1.0)[:, None]
    start_fit = fit_ellipse(xy_nodes, pressure, symmetric_x=symmetric_x, symmetric_y=symmetric_y)
    scale = np.array([start_fit.p0, start_fit.a, start_fit.b, start_fit.a, start_fit.b])
    start = np.array([1.0, 1.0, 1.0, start_fit.x0 / start_fit.a, start_fit.y0 / start_fit.b])

    def residual(z):
        return (operator @ _hertz_field(z * scale, xq, symmetric_x, symmetric_y) - forces) / f_max

    sol = least_squares(residual, start, method="trf", xtol=1e-13, ftol=1e-13, gtol=1e-13, x_scale="jac")
    p0, a, b, x0, y0 = sol.x * scale
    a, b = abs(a), abs(b)
    rms = float(np.sqrt(np.mean(residual(sol.x) ** 2))) * f_max
    return EllipseFit(float(a), float(b), float(p0), 0.0 if symmetric_x else float(x0),
                      0.0 if symmetric_y else float(y0), rms, float(2.0 * np.pi * p0 * a * b / 3.0))


def nodal_stress(basis, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, node_of: np.ndarray):
    """Von Mises stress and sigma_zz [Pa] at the nodes ``node_of`` (k, n_elements) from the P2 solution ``u``.

    Hooke's law (:func:`fem.elasticity.stress`) on the gradient of ``u`` at the quadrature points, the
    volume-weighted mean over each element, then the volume-weighted mean of the elements that share a node;
    von Mises (:func:`fem.elasticity.von_mises`) of the element-mean stress.
    """
    lam, mu = lame(youngs_modulus, poisson_ratio)
    sigma = stress(basis.interpolate(u).grad, lam, mu)    # (3, 3, n_elements, n_qp)
    dx = basis.dx                                          # (n_elements, n_qp) [m^3]
    volume = dx.sum(axis=1)
    mean = (sigma * dx).sum(axis=-1) / volume              # (3, 3, n_elements)
    count = int(node_of.max()) + 1
    weight = np.zeros(count)
    np.add.at(weight, node_of.ravel(), np.tile(volume, node_of.shape[0]))
    out = []
    for value in (von_mises(mean), mean[2, 2]):
        total = np.zeros(count)
        np.add.at(total, node_of.ravel(), np.tile(value * volume, node_of.shape[0]))
        out.append(total / weight)
    return out
