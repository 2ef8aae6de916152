"""Rigid four-point contact: rolling/sliding state, ball motion and friction loss (lin2017).

Lin, Duan, Okwudire, Wou, IMECE2017-72486 (papers/lin2017-four-point-rolling-sliding.md).

Frame (lin2017 Figs 1-2): ball centre at the origin, ``z`` along the grooves
(the top groove moves at ``v`` along +z, the bottom groove is fixed), ``y`` up,
``x`` to the right.  Contacts in the order (BL, BR, TR, TL); contact ``i`` sits
at ``q_i = R_B (-sin, -cos), (sin, -cos), (sin, cos), (-sin, cos)`` of its
contact angle ``beta_i`` measured from the -y / +y axis (lin2017 eq 1; :mod:`lowmodel.geometry.fourpoint`).

Model (Coulomb friction, rigid bodies, point contacts, normal forces fixed a
priori by lin2017 eq 35):

* ``omega_z = 0``.  The local-x slip of every contact is ``omega_z R_B``
  (lin2017 eqs 4, 6), so a spinning ball slides at all four points with
  local-x friction of one sign, whose moment about z cannot vanish
  (lin2017 end of Sec 2.4).  Hence the local-x friction is zero and the
  problem is the z-problem below.
* Slip along z (lin2017 eq 7), in the scaled unknowns
  ``u = (v_B, R_B omega_x, R_B omega_y)``:  ``slip = A u - b`` with the rows of
  ``A`` (lin2017 eq 7 / R_B) and ``b = (0, 0, v, v)``.
* Friction on the ball ``f_i`` (along +z); ball equilibrium of force along z
  and moment about x, y (lin2017 eq 19) is ``A^T f = 0``, so ``f = lambda n``
  with ``n`` the null vector of ``A^T`` (the signed 3x3 minors of ``A``).
  Coulomb: ``|f_i| <= mu F_i``, ``f_i = -mu F_i sgn(slip_i)`` where a contact
  slides.  Its magnitudes ``|n_i|`` are the denominators of lin2017 eq 23, so
  ``K_i = F_i / |n_i|`` (eq 23) and ``|lambda| <= mu min_i K_i``.
* The work of the friction on the slips is ``-f . slip = lambda n . b =
  lambda v C_beta`` with ``C_beta = n_TR + n_TL`` (lin2017 eq 13; ``n`` is
  normalised so that ``n_TR > 0``).  Pure rolling is possible iff
  ``C_beta = 0`` (lin2017 eqs 9-10) and then ``u`` is lin2017 eq 11.
  Otherwise ``lambda = mu K_min sgn(v C_beta)``: every contact with
  ``K_i > K_min`` sticks (its Coulomb bound is not reached), the contact(s)
  with the smallest ``K`` slide (lin2017 eq 22, Remark 1; eqs 29, 32, 34 for
  ties), and the friction loss is ``mu K_min |v C_beta|`` (lin2017 eqs 24, 30).

The same state is the minimiser of the dissipation ``sum_i mu F_i |slip_i|``
(a weighted least-absolute-deviation fit of ``b`` by ``A``): its optimality
conditions are exactly equilibrium plus Coulomb's law (checked against an LP
solver in tests/test_fourpoint.py).

With a tie (two to four contacts share ``K_min``), friction forces and loss are
unique but the ball motion is not (lin2017 eq 30): the admissible motions are the
convex hull of the one-point motions of the tied contacts.  :func:`solve`
returns the centroid (each tied contact dissipates ``P/k``), flags
``motion_unique = False`` and gives the componentwise range of the motion over the hull.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_limits, contact_normals

__all__ = ["CONTACT_NAMES", "FourPointState", "normal_forces", "contact_limits", "rolling_condition",
           "characteristic_parameters", "two_point_sliding_ratio", "solve", "solve_forces"]

TIE_TOLERANCE = 1e-12   # relative: K_i <= K_min (1 + tol) counts as a tie (roundoff of eq 23 is ~1e-15)
ROLLING_TOLERANCE = 64 * np.finfo(float).eps  # |C_beta| below this (C_beta is O(1)) is pure rolling


@dataclass(frozen=True)
class FourPointState:
    """Steady rolling/sliding state of a ball in four-point contact (lin2017).

    Shapes: ``(...)`` is the broadcast shape of the inputs; per-contact arrays
    have a trailing axis of 4 in the order (BL, BR, TR, TL).

    Attributes
    ----------
    ball_velocity : (...) m/s, ``v_B`` along z (centroid of the admissible set on a tie)
    omega : (..., 3) rad/s, ``(omega_x, omega_y, omega_z)``; ``omega_z = 0``
    sliding : (..., 4) bool, contacts that slide (all False in pure rolling)
    slip_velocity : (..., 4) m/s, relative velocity ball - groove along z (lin2017 eqs 4, 6)
    friction_forces : (..., 4) N, friction on the ball along +z (lin2017 eqs 14, 20, 27);
        the local-x components are zero
    friction_loss : (...) W, ``sum mu F_i |slip_i|`` over the sliding contacts (lin2017 eqs 24, 30)
    K : (..., 4) N, characteristic parameters (lin2017 eq 23)
    C_beta : (...) 1, lin2017 eq 13; zero is the pure-rolling condition (eq 9)
    normal_forces : (..., 4) N
    pure_rolling : (...) bool
    motion_unique : (...) bool, False on a tie (then the motion is the centroid)
    motion_range : (..., 2, 3) min (row 0) and max (row 1) of ``(v_B [m/s], omega_x, omega_y [rad/s])``
        over the admissible motions (equal to the motion when it is unique)
    """

    ball_velocity: np.ndarray
    omega: np.ndarray
    sliding: np.ndarray
    slip_velocity: np.ndarray
    friction_forces: np.ndarray
    friction_loss: np.ndarray
    K: np.ndarray
    C_beta: np.ndarray
    normal_forces: np.ndarray
    pure_rolling: np.ndarray
    motion_unique: np.ndarray
    motion_range: np.ndarray

    @property
    def n_sliding(self) -> np.ndarray:
        """Number of sliding contacts, (...) int."""
        return np.sum(self.sliding, axis=-1)


# --- input checks (lowmodel.checks) ------------------------------------------------------------
def _angles(contact_angles) -> np.ndarray:
    angles = checks.trailing_axis("contact_angles", contact_angles, 4, "(BL, BR, TR, TL)", "rad")
    return checks.contact_angle("contact_angles", angles)  # lin2017 Sec 2.1


# --- lin2017 eqs 35-37 -------------------------------------------------------------------------
def _eq36(side_force, vertical_force, angles):
    bl, br, tr, tl = np.moveaxis(angles, -1, 0)
    bottom = np.sin(bl + br)
    top = np.sin(tl + tr)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # a degenerate pair: checked by callers
        return np.stack([-(side_force * np.cos(br) - vertical_force * np.sin(br)) / bottom,   # lin2017 eq 36
                         (side_force * np.cos(bl) + vertical_force * np.sin(bl)) / bottom,
                         -(side_force * np.cos(tl) - vertical_force * np.sin(tl)) / top,
                         (side_force * np.cos(tr) + vertical_force * np.sin(tr)) / top], axis=-1)


def _degenerate_pair(angles, where) -> ValueError:
    """ValueError for contact angles whose contact pair (BL, BR) or (TR, TL) nearly coincides (sum near 0)
    or is nearly opposite (sum near pi): lin2017 eqs 23 and 36 divide by ``sin(beta_BL + beta_BR)``,
    ``sin(beta_TR + beta_TL)`` and the forces grow without bound (``where``: the offending entry)."""
    bl, br, tr, tl = (float(a) for a in angles[where])
    return ValueError(
        f"contact_angles: a contact pair degenerates, (BL, BR, TR, TL) = ({bl!r}, {br!r}, {tr!r}, {tl!r}) rad: "
        f"beta_BL + beta_BR = {bl + br:.6g} and beta_TR + beta_TL = {tr + tl:.6g} rad must stay far enough from 0 "
        "and pi that the normal forces (lin2017 eq 36, ~ N / sin(sum)) and K (eq 23) stay finite; two contacts "
        "that coincide (both angles near 0) or face each other (both near 90 deg) cannot carry the load")


def normal_forces(side_force, vertical_force, contact_angles) -> np.ndarray:
    """Normal contact forces from the loads on the top groove (lin2017 eqs 35-36).

    Parameters
    ----------
    side_force : (...) N, ``N_x`` on the top groove along +x
    vertical_force : (...) N, ``N_y`` pressing the top groove down (-y), > 0
    contact_angles : (..., 4) rad, (BL, BR, TR, TL), each in (0, pi/2)

    Returns
    -------
    (..., 4) N, ``(F_BL, F_BR, F_TR, F_TL)``, all > 0.

    Raises ValueError when four-point contact is lost (a force <= 0, lin2017
    eq 37), naming the allowed range of ``side_force``.
    """
    angles = _angles(contact_angles)
    vertical = np.asarray(checks.positive("vertical_force", vertical_force, "N", note="lin2017 eq 37: N_y > 0"))
    side = np.asarray(checks.finite("side_force", side_force, "N"))
    shape = np.broadcast_shapes(side.shape, vertical.shape, angles.shape[:-1])
    side, vertical = np.broadcast_to(side, shape), np.broadcast_to(vertical, shape)
    angles = np.broadcast_to(angles, shape + (4,))
    forces = _eq36(side, vertical, angles)                 # lin2017 eq 36
    if not np.all(forces > 0.0):
        lower, upper = contact_limits(angles)
        with np.errstate(over="ignore"):  # N_x / N_y may overflow for a tiny N_y: the message shows inf
            ratio = side / vertical
        index = np.unravel_index(np.argmin(np.min(forces, axis=-1)), forces.shape[:-1])
        raise ValueError(
            f"side_force: loss of four-point contact (lin2017 eq 37), N_x/N_y = {float(ratio[index]):.6g} "
            f"must lie in ({float(lower[index]):.6g}, {float(upper[index]):.6g}) = "
            f"(-min(tan beta_BL, tan beta_TR), min(tan beta_BR, tan beta_TL)); "
            f"contact {CONTACT_NAMES[int(np.argmin(forces[index]))]} has F = {float(np.min(forces[index])):.6g} N")
    if not np.all(np.isfinite(forces)):  # all > 0 but some overflow: a pair summing to nearly pi under a huge load
        raise _degenerate_pair(angles, np.unravel_index(np.argmin(np.all(np.isfinite(forces), axis=-1)),
                                                        forces.shape[:-1]))
    return forces


# --- kinematics and the null vector of A^T --------------------------------------------------------
def _rows(angles) -> np.ndarray:
    """lin2017 eq 7's A_v with columns 2-3 divided by R_B: rows (1, q_y/R_B, -q_x/R_B), (..., 4, 3),
    with ``q = R_B n`` the contact points of lin2017 eq 1 (:mod:`lowmodel.geometry.fourpoint`)."""
    normals = contact_normals(angles)
    return np.stack([np.ones_like(normals[..., 0]), normals[..., 1], -normals[..., 0]], axis=-1)


def _null_vector(angles) -> np.ndarray:
    """``n`` with ``A^T n = 0`` (``A``: the rows of :func:`_rows`), ``n_TR > 0``, (..., 4): the signed 3x3 minors.

    The rows are ``(1, cos t_i, sin t_i)`` with the contact points at the polar angles ``t_BL = pi - beta_BL``,
    ``t_BR = pi + beta_BR``, ``t_TR = 2 pi - beta_TR``, ``t_TL = 2 pi + beta_TL`` (increasing), and a minor of three
    points on the unit circle is ``4 sin(a/2) sin(b/2) sin((a + b)/2)`` with ``a``, ``b`` the arcs between them
    (``sin x + sin y + sin z = -4 sin(x/2) sin(y/2) sin(z/2)`` for ``x + y + z = 0``).  The arcs are
    ``pi - beta_BL - beta_TL`` (left), ``beta_BL + beta_BR`` (bottom), ``pi - beta_BR - beta_TR`` (right) and
    ``beta_TR + beta_TL`` (top), so the minors are products of sines and cosines of half sums, with no
    cancellation when a pair of contacts nearly coincides (angles near 0) or faces (near 90 deg): lin2017
    eq 23's denominators ``|n_i|`` stay accurate to the last digits there.
    """
    bl, br, tr, tl = np.moveaxis(angles, -1, 0)
    bottom = np.sin(0.5 * (bl + br))      # sin(bottom arc / 2)
    top = np.sin(0.5 * (tr + tl))         # sin(top arc / 2)
    right = np.cos(0.5 * (br + tr))       # sin(right arc / 2)
    left = np.cos(0.5 * (bl + tl))        # sin(left arc / 2)
    cross_bl = np.cos(0.5 * (br - tl))    # sin((right + top) / 2) = sin((left + bottom) / 2)
    cross_br = np.cos(0.5 * (bl - tr))    # sin((top + left) / 2) = sin((bottom + right) / 2)
    return np.stack([4.0 * right * top * cross_bl, -4.0 * top * left * cross_br,
                     4.0 * left * bottom * cross_bl, -4.0 * bottom * right * cross_br], axis=-1)


def rolling_condition(contact_angles) -> np.ndarray:
    """``C_beta`` of lin2017 eq 13, (...) dimensionless, from the minors of eq 7's A_v.

    Pure rolling is possible iff ``C_beta = 0`` (lin2017 eqs 9-10).
    """
    n = _null_vector(_angles(contact_angles))
    return n[..., 2] + n[..., 3]


def characteristic_parameters(contact_angles, forces) -> np.ndarray:
    """``K_i = F_i / |n_i|`` (lin2017 eqs 23, 38), (..., 4) N.

    ``forces`` (..., 4) N are the normal contact forces (BL, BR, TR, TL).
    """
    angles = _angles(contact_angles)
    with np.errstate(over="ignore", divide="ignore"):
        K = np.asarray(forces, dtype=float) / np.abs(_null_vector(angles))  # lin2017 eq 23
    if not np.all(np.isfinite(K)):
        raise _degenerate_pair(np.broadcast_to(angles, K.shape), np.unravel_index(
            np.argmin(np.all(np.isfinite(K), axis=-1)), K.shape[:-1]))
    return K


def two_point_sliding_ratio(contact_angles, first: str, second: str) -> np.ndarray:
    """Side-force ratio ``rho = N_x / N_y`` at which ``K_first = K_second`` (..., ) 1.

    The forces of lin2017 eq 36 are linear in ``rho`` at fixed ``N_y``, so
    ``K_first - K_second`` is linear in ``rho`` and its zero is exact.  Where
    both are also the smallest ``K`` this is a two-point sliding line (lin2017
    Figs 7, 11; eq 39 for case study 1).  Returns NaN where the difference
    does not depend on ``rho`` (identical or parallel K lines).
    """
    if first not in CONTACT_NAMES or second not in CONTACT_NAMES or first == second:
        raise ValueError(f"first and second must be two different contacts of {CONTACT_NAMES}, "
                         f"got {first!r}, {second!r}")
    i, j = CONTACT_NAMES.index(first), CONTACT_NAMES.index(second)
    angles = _angles(contact_angles)
    weight = 1.0 / np.abs(_null_vector(angles))
    at_zero = _eq36(0.0, 1.0, angles) * weight        # K / N_y at rho = 0
    slope = _eq36(1.0, 0.0, angles) * weight          # dK / d(N_x)
    difference = at_zero[..., i] - at_zero[..., j]
    rate = slope[..., j] - slope[..., i]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = difference / rate
    return np.where(np.abs(rate) > 1e-14 * (np.abs(slope[..., i]) + np.abs(slope[..., j])), ratio, np.nan)


def _solve3(matrix, rhs):
    """Solve stacked 3x3 systems by the adjugate (columns r1 x r2, r2 x r0, r0 x r1 over det)."""
    r0, r1, r2 = matrix[..., 0, :], matrix[..., 1, :], matrix[..., 2, :]
    c0, c1, c2 = np.cross(r1, r2), np.cross(r2, r0), np.cross(r0, r1)
    det = np.einsum("...i,...i->...", r0, c0)
    inverse = np.stack([c0, c1, c2], axis=-1) / det[..., None, None]
    return np.einsum("...ij,...jk->...ik", inverse, rhs)


# --- the rolling/sliding state ----------------------------------------------------------------------
def solve(contact_angles, side_force, vertical_force, *, ball_radius, friction_coefficient,
          groove_velocity, tie_tolerance: float = TIE_TOLERANCE) -> FourPointState:
    """Rolling/sliding state of a ball in four-point contact (lin2017 Sec 2-3).

    Parameters
    ----------
    contact_angles : (..., 4) rad, (BL, BR, TR, TL), each in (0, pi/2)
    side_force, vertical_force : (...) N, ``N_x``, ``N_y`` on the top groove (lin2017 eq 35)
    ball_radius : (...) m, ``R_B`` > 0
    friction_coefficient : (...) ``mu_k`` >= 0 (mu -> 0+ limit at 0)
    groove_velocity : (...) m/s, ``v`` of the top groove along z (any sign)
    tie_tolerance : relative tolerance under which two ``K`` count as equal

    All inputs broadcast against each other (leading axes of contact_angles).
    """
    forces = normal_forces(side_force, vertical_force, contact_angles)
    return solve_forces(contact_angles, forces, ball_radius=ball_radius,
                        friction_coefficient=friction_coefficient, groove_velocity=groove_velocity,
                        tie_tolerance=tie_tolerance)


def solve_forces(contact_angles, forces, *, ball_radius, friction_coefficient, groove_velocity,
                 tie_tolerance: float = TIE_TOLERANCE) -> FourPointState:
    """As :func:`solve`, from given normal forces ``forces`` (..., 4) N, each > 0."""
    angles = _angles(contact_angles)
    forces = np.asarray(checks.positive("forces", forces, "N", note="normal forces; four-point contact, lin2017 eq 37"))
    checks.trailing_axis("forces", forces, 4, "(BL, BR, TR, TL)", "N")
    radius = np.asarray(checks.positive("ball_radius", ball_radius, "m"))
    mu = np.asarray(checks.non_negative("friction_coefficient", friction_coefficient))
    velocity = np.asarray(checks.finite("groove_velocity", groove_velocity, "m/s"))
    tie_tolerance = checks.bounded("tie_tolerance", tie_tolerance, 0.0, 1e-3, lower_closed=True)
    shape = np.broadcast_shapes(angles.shape[:-1], forces.shape[:-1], radius.shape, mu.shape, velocity.shape)
    angles = np.broadcast_to(angles, shape + (4,))
    forces = np.broadcast_to(forces, shape + (4,))
    radius, mu, velocity = (np.broadcast_to(x, shape) for x in (radius, mu, velocity))

    rows = _rows(angles)                                   # lin2017 eq 7 / R_B
    n = _null_vector(angles)                               # |n| = denominators of eq 23
    with np.errstate(over="ignore", divide="ignore"):
        K = forces / np.abs(n)                             # lin2017 eq 23
    if not np.all(np.isfinite(K)):
        raise _degenerate_pair(angles, np.unravel_index(np.argmin(np.all(np.isfinite(K), axis=-1)), shape))
    C_beta = n[..., 2] + n[..., 3]                         # lin2017 eq 13
    rolling = (np.abs(C_beta) <= ROLLING_TOLERANCE) | (velocity == 0.0)   # lin2017 eq 9 (or a groove at rest)
    k_min = np.min(K, axis=-1)
    sliding = (K <= k_min[..., None] * (1.0 + tie_tolerance)) & ~rolling[..., None]   # lin2017 eqs 22, 29, 32, 34
    count = np.maximum(np.sum(sliding, axis=-1), 1)

    b = np.zeros(shape + (4,))
    b[..., 2:] = velocity[..., None]                       # top groove moves at v (lin2017 eq 7)
    nb = velocity * C_beta                                 # n . b
    # slip of the tied contacts at the centroid of the admissible set (each dissipates P / k)
    with np.errstate(divide="ignore", invalid="ignore"):
        slip_target = np.where(sliding, -nb[..., None] / (count[..., None] * n), 0.0)
    gram = np.einsum("...ki,...kj->...ij", rows, rows)
    rhs = np.concatenate([np.einsum("...ki,...k->...i", rows, b + slip_target)[..., None],
                          np.swapaxes(rows, -1, -2)], axis=-1)          # (..., 3, 5)
    solution = _solve3(gram, rhs)
    scaled = solution[..., 0]                              # (v_B, R_B omega_x, R_B omega_y)
    slip = np.einsum("...ki,...i->...k", rows, scaled) - b  # lin2017 eqs 4, 6, 7
    slip = np.where(sliding, slip, 0.0)                    # sticking contacts: zero up to roundoff

    # one-point motions of the tied contacts (vertices of the admissible set, lin2017 eq 30): ranges
    base = solution[..., 0] - np.einsum("...ik,...k->...i", solution[..., 1:], slip_target)   # motion for b alone
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex_slip = np.where(sliding, -nb[..., None] / n, 0.0)
    vertices = base[..., None, :] + solution[..., 1:].swapaxes(-1, -2) * vertex_slip[..., None]   # (..., 4, 3)
    any_sliding = np.any(sliding, axis=-1)[..., None]
    mask = sliding[..., None]
    motion_range = np.stack([np.where(any_sliding, np.min(np.where(mask, vertices, np.inf), axis=-2), scaled),
                             np.where(any_sliding, np.max(np.where(mask, vertices, -np.inf), axis=-2), scaled)],
                            axis=-2) / np.stack([np.ones(shape), radius, radius], axis=-1)[..., None, :]

    # friction: f = lambda n (ball equilibrium, lin2017 eq 19), |lambda| = mu K_min (eqs 20-22)
    multiplier = np.where(rolling, 0.0, mu * k_min * np.sign(nb))
    friction = multiplier[..., None] * n                   # lin2017 eq 20 (eqs 14, 27 where sliding)
    loss = np.sum(mu[..., None] * forces * np.abs(slip), axis=-1)   # lin2017 eqs 24, 30

    omega = np.stack([scaled[..., 1] / radius, scaled[..., 2] / radius, np.zeros(shape)], axis=-1)
    return FourPointState(ball_velocity=scaled[..., 0], omega=omega, sliding=sliding, slip_velocity=slip,
                          friction_forces=friction, friction_loss=loss, K=K, C_beta=C_beta,
                          normal_forces=np.array(forces), pure_rolling=rolling,
                          motion_unique=np.sum(sliding, axis=-1) <= 1, motion_range=motion_range)
