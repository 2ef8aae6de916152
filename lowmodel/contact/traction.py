"""Sampled contact tractions with pointwise full-slip Coulomb friction (the FE-informed B2B models,
docs/b2b_traction.md).

Shared by the FE-informed ball-to-ball models of the linear bearing
(:mod:`lowmodel.linear_bearing.b2b_traction`) and the ball screw
(:mod:`lowmodel.screw.b2b_traction`): one implementation of

* :class:`TractionPatch`, one ball-to-groove contact given as sampled points of the
  (curved) contact surface, each with its unit normal and the normal force it carries
  (an FE pressure times its quadrature area, or samples of a Hertz ellipse);
* :func:`ellipse_samples`, the Gauss-Jacobi quadrature of Hertz's pressure over an ellipse
  (lin2019 eq A7, ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)``), used by both models' ``hertz_patches``;
* :class:`SampledCoulomb`, the friction of every point opposite to the rigid-body slip
  projected on the local tangent plane (lin2019 eqs 1-3 and 43-47 without the contact-plane
  approximation) and the generalised forces of a ball's unknowns, with their Jacobian:

      s_k = D_k x_b - g_k                       (slip, linear in the ball's unknowns x_b)
      f_k = -F_k P_k s_k / sqrt(|P_k s_k|^2 + eps^2),    P_k = I - N_k N_k^T
      R_b = sum_{k on ball b} D_k^T f_k           (generalised force conjugate to x_b)

  ``R_b = -grad`` of the regularised dissipation ``sum F_k sqrt(|P s|^2 + eps^2)``: its
  Jacobian is symmetric negative semi-definite, a ball alone has a unique state.  At
  ``R_b = 0`` the power identity ``sum f_k . s_k = -sum f_k . g_k`` holds exactly (the
  models' power balance; independent of ``eps``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import roots_jacobi

from ballbench.lowmodel import checks
from ballbench.lowmodel.b2b_chain import COMPLEMENTARITY_SCALE, BallBlocks, ChainLayout, chain_forces, chain_system
from ballbench.lowmodel.solvers import newton

__all__ = ["TractionPatch", "check_patch", "ellipse_samples", "SampledCoulomb", "free_ball_starts", "StackedPatches",
           "stack_patches", "solve_chain"]


@dataclass(frozen=True)
class TractionPatch:
    """Sampled normal traction of one ball-to-groove contact.

    points  : (k, 3) m, on the ball surface, relative to the ball centre (the model's ball frame:
              lin2019 Fig 2 for the linear bearing, CS3 of lin2019 eq 41 for the ball screw)
    normals : (k, 3) unit outward normal of the contact surface at the points (from the ball into the groove)
    forces  : (k,) N, normal force carried by each point (>= 0)
    top     : True on the moving body (the top groove of the linear bearing, the nut of the ball screw)
    name    : contact name, e.g. "BL" or "SL"
    """

    points: np.ndarray
    normals: np.ndarray
    forces: np.ndarray
    top: bool
    name: str = ""

    @property
    def normal_force(self) -> float:
        """Total normal force [N]."""
        return float(self.forces.sum())

    @property
    def centre(self) -> np.ndarray:
        """Force-weighted centre of the patch (3,) [m] (the loaded contact point)."""
        return self.forces @ self.points / self.normal_force

    def contact_angle(self) -> float:
        """Loaded contact angle [rad] of the patch centre, measured from -y (bottom) or +y (top) (lin2017 eq 1;
        linear-bearing frame)."""
        x, y, _ = self.centre
        return math.atan2(abs(x), abs(y))


def check_patch(patch: TractionPatch, index: int) -> TractionPatch:
    """The patch with float arrays and unit normals; ValueError naming the array otherwise.

    Shapes (k, 3), (k, 3), (k,); finite values; forces >= 0 N with a positive sum (loss of
    contact otherwise); normals unit vectors within 1e-6 (renormalised).
    """
    points = np.asarray(patch.points, dtype=float)
    normals = np.asarray(patch.normals, dtype=float)
    forces = np.asarray(patch.forces, dtype=float)
    name = patch.name or f"patch {index}"
    if points.ndim != 2 or points.shape[1] != 3 or normals.shape != points.shape or forces.shape != points[:, 0].shape:
        raise ValueError(f"{name}: points and normals must have shape (k, 3) and forces (k,), got "
                         f"{points.shape}, {normals.shape}, {forces.shape}")
    if not (np.all(np.isfinite(points)) and np.all(np.isfinite(normals)) and np.all(np.isfinite(forces))):
        raise ValueError(f"{name}: points, normals and forces must be finite")
    if np.any(forces < 0.0) or forces.sum() <= 0.0:
        raise ValueError(f"{name}: forces must be >= 0 N with a positive sum (loss of contact otherwise)")
    length = np.linalg.norm(normals, axis=1)
    if np.any(np.abs(length - 1.0) > 1e-6):
        raise ValueError(f"{name}: normals must be unit vectors (|N| in [1 - 1e-6, 1 + 1e-6])")
    return TractionPatch(points, normals / length[:, None], forces, bool(patch.top), patch.name)


def ellipse_samples(n_radial: int = 24, n_angular: int = 96) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Quadrature of Hertz's pressure over the unit disk: ``(u, v, w)``, each (n_radial n_angular,).

    Points ``(u, v) = rho (cos t, sin t)``; Gauss-Jacobi in ``q = 1 - rho^2`` with weight
    ``sqrt(q)`` (exact for the radial profile of ``p0 sqrt(1 - rho^2)``, lin2019 eq A7) times
    ``n_angular`` equal angles ``t = 2 pi (i + 1/2) / n_angular`` (symmetric in ``v -> -v``);
    the weights ``w`` sum to 1, so ``F w`` are the forces of an ellipse ``(a u, b v)`` carrying ``F``.
    """
    if not (isinstance(n_radial, int) and n_radial >= 1 and isinstance(n_angular, int) and n_angular >= 4):
        raise ValueError(f"n_radial must be an integer >= 1 and n_angular >= 4, got {n_radial!r}, {n_angular!r}")
    nodes, weights = roots_jacobi(n_radial, 0.0, 0.5)  # weight (1 + t)^(1/2) on [-1, 1]
    q = 0.5 * (1.0 + nodes)  # q = 1 - rho^2 in [0, 1]
    rho = np.sqrt(1.0 - q)
    angle = 2.0 * math.pi * (np.arange(n_angular) + 0.5) / n_angular
    rr, tt = np.meshgrid(rho, angle, indexing="ij")
    w = np.repeat(weights[:, None], n_angular, axis=1).ravel()
    return (rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel(), w / w.sum()


class SampledCoulomb:
    """Full-slip Coulomb friction of sampled points of ``n_balls`` balls (module docstring).

    ball : (k,) int, the ball of each point;  slip_matrix : (k, 3, m) ``D_k = d s_k / d x`` (m unknowns per ball)
    groove_slip : (k, 3) ``g_k`` (the groove's velocity at the point, in the units of ``s``)
    normals : (k, 3) unit normals;  load : (k,) normal forces (any force unit: the residual is in it)
    eps : slip floor (units of ``s``) in ``sqrt(|P s|^2 + eps^2)``
    """

    def __init__(self, ball, slip_matrix, groove_slip, normals, load, n_balls: int, eps: float):
        self.ball = np.asarray(ball, dtype=int)
        self.D = np.asarray(slip_matrix, dtype=float)
        self.groove_slip = np.asarray(groove_slip, dtype=float)
        self.normal = np.asarray(normals, dtype=float)
        self.load = np.asarray(load, dtype=float)
        self.n_balls = int(n_balls)
        self.n_unknowns = self.D.shape[2]
        self.eps = float(eps)
        self.projector = np.eye(3)[None] - self.normal[:, :, None] * self.normal[:, None, :]
        self.PD = self.projector @ self.D
        m = self.n_unknowns
        self.gram = np.matmul(self.PD.transpose(0, 2, 1), self.PD).reshape(-1, m * m)  # (P D)^T (P D), constant
        self.index = [np.flatnonzero(self.ball == b) for b in range(self.n_balls)]

    def evaluate(self, balls: np.ndarray, jacobian: bool = True, ball: int | None = None):
        """Residual ``R`` (n, m) and Jacobian (n, m, m) at ``balls`` (n, m); slips (k, 3) and forces (k, 3).

        ``ball``: only that ball's points (residual (m,), Jacobian (m, m), its points' slips and forces).
        """
        m = self.n_unknowns
        if ball is None:
            index, owner, count = slice(None), self.ball, self.n_balls
        else:
            index = self.index[ball]
            owner, count = np.zeros(len(index), dtype=int), 1
        D, normal = self.D[index], self.normal[index]
        x = np.asarray(balls, dtype=float)[self.ball[index]]  # (k, m)
        slip = np.matmul(D, x[:, :, None])[:, :, 0] - self.groove_slip[index]
        tangential = slip - normal * np.einsum("ki,ki->k", normal, slip)[:, None]  # P s
        norm = np.sqrt(np.einsum("ki,ki->k", tangential, tangential) + self.eps**2)
        weight = self.load[index] / norm
        force = -weight[:, None] * tangential  # Coulomb, full slip
        rows = np.matmul(force[:, None, :], D)[:, 0, :]  # D^T f
        residual = np.stack([np.bincount(owner, rows[:, j], minlength=count) for j in range(m)], axis=1)
        jac = None
        if jacobian:
            # d f / d x = -(F / |Ps|) (I - u u^T) P D, u = Ps / |Ps|:  block = -w ((PD)^T PD - (PD)^T u u^T PD)
            pdu = np.matmul((tangential / norm[:, None])[:, None, :], self.PD[index])[:, 0, :]  # (k, m)
            gram = self.gram[index]
            jac = np.empty((count, m, m))
            groups = [np.arange(len(weight))] if ball is not None else self.index
            for b, rows_b in enumerate(groups):
                w = weight[rows_b]
                jac[b] = -(w @ gram[rows_b]).reshape(m, m) + (pdu[rows_b] * w[:, None]).T @ pdu[rows_b]
        if ball is not None:
            return residual[0], jac[0] if jacobian else None, slip, force
        return residual, jac, slip, force


def free_ball_starts(evaluate, guess: np.ndarray, *, tolerance: float, max_iterations: int,
                     what: str) -> tuple[np.ndarray, int]:
    """Every ball on its own, with its own points only: the start of a coupled B2B solve.

    ``evaluate(states, ball=b)`` returns ``(residual, jacobian, ...)`` of ball ``b`` (shapes ``(k,)``, ``(k, k)``)
    for the ``(n, k)`` states; ``guess`` is ``(n, k)``.  Returns the ``(n, k)`` free states and the largest Newton
    iteration count (:func:`lowmodel.solvers.newton`, which raises ConvergenceError naming ``what`` and the ball).
    """
    free = np.empty_like(guess)
    iterations = 0
    for b in range(len(guess)):
        def single(x, b=b):
            states = guess.copy()
            states[b] = x
            residual, jac = evaluate(states, ball=b)[:2]
            return residual, jac

        free[b], _, its = newton(single, guess[b], tolerance=tolerance, max_iterations=max_iterations,
                                 what=f"{what} {b}")
        iterations = max(iterations, its)
    return free, iterations


def solve_chain(samples: SampledCoulomb, guess: np.ndarray, touching: np.ndarray, pair_function_of, *,
                complementarity: str, tolerance: float, max_iterations: int, what_ball: str, what_chain: str,
                start=None):
    """The balls of ``samples`` with B2B contact of the ``touching`` pairs: every ball alone first
    (:func:`free_ball_starts` from ``guess`` (n, k)), then the chain of :mod:`lowmodel.b2b_chain` (rate: unknown 0,
    ``gamma`` = COMPLEMENTARITY_SCALE) with the pair loads ``pair_function_of(layout)`` (the model's B2B law);
    ``start`` = ``(states (n, k), forces (n-1,) in force-slot units)``: the chain starts there instead of at the
    free balls (which are then not solved).

    Returns ``(states (n, k), forces (n-1,) in force-slot units (0 on open pairs), iterations, max residual)``;
    ConvergenceError (:func:`lowmodel.solvers.newton`, :func:`lowmodel.b2b_chain.chain_forces`) naming
    ``what_ball`` or ``what_chain``.
    """
    def ball_function(states, _extra=None):
        residual, jac, _, _ = samples.evaluate(states)
        return BallBlocks(residual, jac)

    n = len(guess)
    if start is not None and touching.size:
        free, iterations = np.asarray(start[0], dtype=float), 0
    else:
        free, iterations = free_ball_starts(samples.evaluate, guess, tolerance=tolerance,
                                            max_iterations=max_iterations, what=what_ball)
    if touching.size == 0:
        return free, np.zeros(n - 1), iterations, float(np.max(np.abs(ball_function(free).residual)))
    layout = ChainLayout(n, guess.shape[1], touching)
    function = chain_system(ball_function, pair_function_of(layout), layout, rate_index=0,
                            rate_scale=COMPLEMENTARITY_SCALE, complementarity=complementarity)
    forces = None if start is None else np.asarray(start[1], dtype=float)
    z, residual, its = newton(function, layout.pack(free, forces), tolerance=tolerance,
                              max_iterations=max_iterations, what=what_chain)
    iterations += its
    states, forces, _ = chain_forces(z, layout, rate_index=0, rate_scale=COMPLEMENTARITY_SCALE, tolerance=tolerance,
                                     iterations=iterations, what=what_chain)
    return states, forces, iterations, float(np.max(np.abs(residual)))


@dataclass(frozen=True)
class StackedPatches:
    """The sample points of all patches of all balls, stacked (``(k,)`` or ``(k, 3)`` arrays).

    points [m] and normals as given; load = force / F_ref; moving = ``moving_value`` on patches with
    ``top=True`` (the driven groove: linear top rail or nut), 0 elsewhere; ball and patch indices
    (patch = ``ball * n_patches + position``).
    """

    points: np.ndarray
    normals: np.ndarray
    load: np.ndarray
    moving: np.ndarray
    ball: np.ndarray
    patch: np.ndarray


def stack_patches(balls, n_patches: int, reference_force: float, moving_value: float) -> StackedPatches:
    """Stack the ``TractionPatch`` samples of ``balls`` (a sequence of patch sequences), see StackedPatches.

    ``n_patches`` >= 1 per ball, ``reference_force`` F_ref [N] > 0 with finite ``force / F_ref``, ``moving_value``
    finite (ValueError naming the parameter otherwise).
    """
    n_patches = checks.count("n_patches", n_patches, 1)
    reference_force = checks.positive("reference_force", reference_force, "N")
    moving_value = checks.finite("moving_value", moving_value)
    rows = [(b * n_patches + p, b, patch) for b, patches in enumerate(balls) for p, patch in enumerate(patches)]
    count = [len(patch.forces) for _, _, patch in rows]
    with np.errstate(over="ignore"):
        load = np.concatenate([patch.forces / reference_force for _, _, patch in rows])
    if not np.all(np.isfinite(load)):
        raise ValueError(f"reference_force {reference_force!r} N is too small for the forces (force / F_ref overflows)")
    return StackedPatches(
        points=np.concatenate([patch.points for _, _, patch in rows]),
        normals=np.concatenate([patch.normals for _, _, patch in rows]),
        load=load,
        moving=np.repeat([moving_value if patch.top else 0.0 for _, _, patch in rows], count),
        ball=np.repeat([b for _, b, _ in rows], count),
        patch=np.repeat([i for i, _, _ in rows], count))
