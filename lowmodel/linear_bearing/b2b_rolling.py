"""Ball-to-ball (B2B) contact in the linear bearing with stick/slip ball-to-groove contacts (docs/b2b_rolling.md).

lin2019 Sec 2.2, eqs 4-10, with the friction of every ball-to-groove contact from the steady rolling solve
(:mod:`lowmodel.contact.rolling_friction`: stick and slip, elastic creep, the tangential compliance of a
half-space or of the FE) in place of the full-slip maps of eqs A4-A7.  The rest is the low-order model's:

* unknowns per ball ``x = (v_B, omega_x R_B, omega_y R_B)/|v|`` and the three rows of eq 4 (z force, x and y
  moments / R_B) as the generalised forces of ``x`` (``omega_z = 0``: the lateral forces that full slip does
  not have act about ``z``, a moment eq 4 does not balance; it is reported, docs/b2b_rolling.md);
* the rigid slip of the ball against its groove at every contact point, lin2019 eqs 1 and A1-A3 as a field
  (:func:`lowmodel.linear_bearing.b2b_traction.slip_field`), on the contact surface curved across the groove
  (Heathcote's slip, :func:`lowmodel.linear_bearing.rolling_contacts.deformed_radius`);
* the B2B contact a point at ``+-R_B e_z`` with full sliding (eqs 5-8,
  :func:`lowmodel.linear_bearing.b2b.pair_function`: the two balls' surfaces move in opposite directions, the
  contact slides at about ``v / cos beta_0`` while its rolling speed is the small difference of the two balls'
  spins; :func:`b2b_contact_check` solves it as a rolling contact to show it), the complementarity of
  eqs 9-10 (``min``, the chain of :mod:`lowmodel.b2b_chain`);
* ball-to-groove normal loads decoupled from friction and from the B2B force (given pressures).

Each solve first solves the same balls with the full-slip law on the same cells (pointwise Coulomb,
:func:`lowmodel.linear_bearing.b2b_traction.solve` on :meth:`GridContact.patch`: analytic Jacobian), then the
stick/slip balls from there (free balls on their own, touching balls with the B2B chain); the power balance
``v sum_top f . e_z = sum rigid_power + mu F_B2B |dv|`` (lin2019 eq 7) is checked in every solve to
:data:`POWER_BALANCE_TOLERANCE`.

```python
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling
contacts = b2b.module_contacts(theta, rho)                        # lin2019 Fig 7, Table 1
balls = [b2b_rolling.hertz_contacts(contacts, j, cells=(20, 80)) for j in range(2)]
result = b2b_rolling.module_b2b(balls, ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)
result.b2b_force, result.full_slip.b2b_force, result.friction_increase, result.touching.contacts[0][0].stick_fraction
```
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks, model_inputs
from ballbench.lowmodel.bearing import guide_values
from ballbench.lowmodel.contact import hertz, rolling
from ballbench.lowmodel.contact import rolling_friction as rf
from ballbench.lowmodel.contact.influence import combined_material
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_normals
from ballbench.lowmodel.linear_bearing import b2b, b2b_traction
from ballbench.lowmodel.linear_bearing.contacts import BallContacts
from ballbench.lowmodel.linear_bearing.rolling_contacts import deformed_radius
from ballbench.lowmodel.solvers import check_solver_options
from ballbench.lowmodel.state import BallStateBase
from ballbench.lowmodel.state import friction_increase

__all__ = ["RollingB2BState", "RollingModuleB2B", "hertz_contacts", "loaded_contacts", "sampled_contacts", "solve",
           "module_b2b", "b2b_contact_check", "POWER_BALANCE_TOLERANCE", "AXIS"]

POWER_BALANCE_TOLERANCE = 1e-6  # relative: every solve checks it (docs/b2b_rolling.md: power balance to 1e-6)
AXIS = np.array([0.0, 0.0, 1.0])  # the grooves' direction (lin2019 Fig 2: z along the rails)
# the default material: lin2019 Table 1's steel (lowmodel.contact.hertz's)
TABLE1_STEEL = {"youngs_modulus": hertz.STEEL_YOUNGS_MODULUS, "poisson_ratio": hertz.STEEL_POISSON_RATIO}
TABLE1 = {"conformity": 0.56, **TABLE1_STEEL}  # the default grooves: lin2019 Table 1
AXIS.setflags(write=False)


@dataclass(frozen=True)
class RollingB2BState(BallStateBase):
    """Quasi-static state of ``n`` balls with stick/slip (or full-slip) contacts on grids; the power, B2B and loss
    fields of :class:`lowmodel.state.BallStateBase` (``friction_loss`` (n, c): each contact's rigid power, zero
    after the last contact of a ball with fewer).

    law : "stick-slip" or "full-slip";  ball_velocity (n,) m/s;  omega (n, 2) rad/s ``(omega_x, omega_y)``
    velocity_deviation : (n,) ``2 v_B / v - 1`` (lin2019 eq 21)
    contacts : per ball the :class:`~lowmodel.contact.rolling_friction.ContactSummary` of each contact
    z_moment : (n,) N m, the moment about ``z`` of the friction (the row eq 4 leaves out; 0 for full slip on
        symmetric contacts)
    power_balance : |input - losses| / input;  rolling_solves : rolling solves of the stick/slip solve
    """

    law: str
    ball_velocity: np.ndarray
    omega: np.ndarray
    velocity_deviation: np.ndarray
    contacts: tuple
    z_moment: np.ndarray
    power_balance: float
    rolling_solves: int = 0


def _material(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    e = checks.positive("youngs_modulus", youngs_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    shear, nu_c, _ = combined_material(e / (2.0 * (1.0 + nu)), nu)
    return shear, nu_c


def hertz_contacts(contacts: BallContacts, ball: int = 0, *, cells=(20, 80), guide=None,
                   conformity: float | None = None, youngs_modulus: float | None = None,
                   poisson_ratio: float | None = None, heathcote: bool = True, operator_for=None) -> tuple:
    """The four contacts (BL, BR, TR, TL) of ``ball`` of the low-order model as :class:`GridContact` with Hertz's
    pressure: at ``R_B n_i`` (rigid contact angles, lin2019 Fig 2), semi-axes ``b_i`` along the rails and ``a_i``
    across, ``cells = (n_along, n_across)`` across the ellipse (or one fixed ``SurfaceGrid`` for every contact).
    ``conformity``: of the grooves, for the curvature of the contact surface (``heathcote=False``: planar,
    lin2019's slip field eq 3); ``youngs_modulus`` [Pa], ``poisson_ratio``: ball and grooves (default lin2019
    Table 1's 0.56 and steel), or all three from ``guide`` (a :class:`lowmodel.bearing.LinearGuide`);
    ``operator_for(grid)`` the operator (default the half-space)."""
    index = checks.count("ball", ball, 0, contacts.n_balls - 1)
    return loaded_contacts(contacts.contact_angles[index], contacts.normal_forces[index],
                           contacts.semi_major[index], contacts.b_over_a[index], ball_radius=contacts.ball_radius,
                           cells=cells, guide=guide, conformity=conformity, youngs_modulus=youngs_modulus,
                           poisson_ratio=poisson_ratio, heathcote=heathcote, operator_for=operator_for)


def loaded_contacts(contact_angles, normal_forces, semi_major, b_over_a, *, ball_radius: float, cells=(20, 80),
                    guide=None, conformity: float | None = None, youngs_modulus: float | None = None,
                    poisson_ratio: float | None = None, heathcote: bool = True, operator_for=None) -> tuple:
    """The loaded contacts of one ball as :class:`GridContact` with Hertz's pressure (as :func:`hertz_contacts`):
    ``contact_angles`` (4,) rad (BL, BR, TR, TL; rigid, lin2019 Fig 2), ``normal_forces`` (4,) N, ``semi_major``
    (4,) m and ``b_over_a`` (4,) of each; a contact without load (force <= 0) is left out: a ball in two- or
    three-point contact (a carriage's ball in its end relief or under a moment, lowmodel.linear_bearing.
    carriage_friction)."""
    conformity, youngs_modulus, poisson_ratio = guide_values(guide, dict(
        conformity=conformity, youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio), TABLE1).values()
    shear, nu = _material(youngs_modulus, poisson_ratio)
    radius = checks.positive("ball_radius", ball_radius, "m")
    curvature = 1.0 / deformed_radius(radius, conformity) if heathcote else 0.0
    normals = contact_normals(np.asarray(contact_angles, dtype=float))
    out = []
    for i, name in enumerate(CONTACT_NAMES):
        force = float(normal_forces[i])
        if force <= 0.0:
            continue
        n = np.array([normals[i, 0], normals[i, 1], 0.0])
        a = float(semi_major[i])
        out.append(rf.hertz_contact(name, i >= 2, radius * n, n, AXIS, a * float(b_over_a[i]), a, force, cells,
                                    lateral_curvature=curvature, shear_modulus=shear, poisson_ratio=nu,
                                    operator_for=operator_for))
    return tuple(out)


def sampled_contacts(samples, *, guide=None, ball_radius: float | None = None, conformity: float | None = None,
                     cells=None, grid=None, youngs_modulus: float | None = None, poisson_ratio: float | None = None,
                     heathcote: bool = True, operator=None, outside: float = 0.0) -> tuple:
    """The contacts of one ball from sampled pressures (e.g. the FE module's, ``fem.fourpoint``): ``samples`` a
    sequence of ``(name, top, points (q, 3) [m], pressure (q,) [Pa], areas (q,) [m^2])`` in lin2019's frame
    (points on the ball relative to its centre); each on a grid of ``cells`` over its pressure, or on the given
    ``grid`` with ``operator`` (an FE compliance; ``outside`` the share of the force allowed beyond its inner cells)
    (:func:`lowmodel.contact.rolling_friction.sampled_contact`).  Ball radius, conformity and material: given, or
    from ``guide`` (a :class:`lowmodel.bearing.LinearGuide`); the material defaults to lin2019 Table 1's steel."""
    ball_radius, conformity, youngs_modulus, poisson_ratio = guide_values(guide, dict(
        ball_radius=ball_radius, conformity=conformity, youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio),
        TABLE1_STEEL).values()
    shear, nu = _material(youngs_modulus, poisson_ratio)
    curvature = 1.0 / deformed_radius(ball_radius, conformity) if heathcote else 0.0
    return tuple(rf.sampled_contact(name, top, points, pressure, areas, AXIS, cells=cells, grid=grid,
                                    lateral_curvature=curvature, shear_modulus=shear, poisson_ratio=nu,
                                    operator=operator, outside=outside)
                 for name, top, points, pressure, areas in samples)


def _friction(balls, radius: float, mu: float, velocity: float, law: str, reference_force: float):
    sign = math.copysign(1.0, velocity)

    def field(points, moving):
        return b2b_traction.slip_field(points, radius, moving)

    return rf.StickSlipFriction(balls, field, mu, reference_force, sign, abs(velocity), law=law)


def _balls(balls, law: str, full_slip, start: str) -> tuple[list, bool]:
    """``(balls as tuples, whether their numbers of contacts differ)``; ValueError where they do and a full-slip
    state on the cells is asked for (``b2b_traction`` takes as many contacts per ball)."""
    balls = [tuple(contacts) for contacts in balls]
    if len(balls) < 1 or not all(balls):
        raise ValueError("balls must hold n >= 1 balls with at least one contact each")
    mixed = len({len(c) for c in balls}) != 1
    if mixed and (law == "full-slip" or full_slip is not None or start == "full-slip"):
        raise ValueError("balls with different numbers of contacts take the stick/slip law from start='auto', "
                         "'rolling' or 'alone' (the full-slip law on the cells needs as many contacts per ball)")
    return balls, mixed


def solve(balls, *, ball_radius: float, friction_coefficient: float, groove_velocity: float, gaps=None,
          law: str = "stick-slip", tolerance: float = 1e-9, max_iterations: int = 40,
          full_slip: b2b_traction.TractionState | None = None, start: str = "full-slip",
          warm: RollingB2BState | None = None) -> RollingB2BState:
    """Quasi-static motion of ``n >= 1`` balls whose ball-to-groove contacts are :class:`GridContact` s, with B2B
    contact (lin2019 eqs 4-10; module docstring).

    balls : per ball its contacts (ball 0 behind, lin2019's "ball 1"); the stick/slip law takes any number per ball
        (a ball of a carriage's chain in two- or three-point contact beside four-point ones), the full-slip law and
        its start the same number
    ball_radius [m];  friction_coefficient mu (ball-to-groove and ball-to-ball);  groove_velocity v [m/s] of
    the top groove;  gaps : (n-1,) m (default all touching)
    law : "stick-slip" (the rolling solve) or "full-slip" (pointwise Coulomb on the same cells)
    tolerance : max residual of eq 4 in units of ``mu F_ref`` (F_ref the largest contact force) and of eqs 9-10
    full_slip : the full-slip state of the same balls and gaps (the start; solved here when None)
    start : "full-slip" (from ``full_slip``), "rolling" (stick/slip only: from each ball's kinematics nearest to
        rolling, :meth:`~lowmodel.contact.rolling_friction.StickSlipFriction.rolling_start`, the B2B forces from
        zero), "alone" (stick/slip only, touching balls: from the states of its balls each solved alone by
        "auto", the B2B forces from zero) or "auto" (stick/slip only: from full slip on the cells where that has a
        state and the stick/slip solve converges from it, else (``warm``, then) "alone" for a chain, else from
        rolling with ``rolling_friction.ROLLING_ITERATIONS`` times the steps; docs/b2b_rolling.md, "Where full
        sliding has no state")
    warm : a stick/slip state of as many balls near this one (e.g. the step before on a travel): a start from its
        balls' motion and B2B forces, tried before ``start``; with "auto" and a chain (n > 1) after full slip and
        before rolling (full slip's is the nearer start of a chain where it has a state: the result then the same as
        without ``warm``; docs/carriage.md, "Over travel")

    ValueError for bad input; ConvergenceError (with its residual) when Newton fails or the power balance misses
    :data:`POWER_BALANCE_TOLERANCE`.
    """
    check_solver_options(tolerance, max_iterations)
    law = checks.choice("law", law, rf.LAWS)
    radius = checks.positive("ball_radius", ball_radius, "m")
    mu = model_inputs.guide_friction_coefficient(friction_coefficient)
    velocity = model_inputs.groove_velocity(groove_velocity)
    balls, mixed = _balls(balls, law, full_slip, start)
    n = len(balls)
    touching = b2b.touching_pairs(gaps, n, radius)
    patches = [[c.patch() for c in contacts] for contacts in balls]
    if warm is not None and (law != "stick-slip" or len(warm.ball_velocity) != n):
        raise ValueError(f"warm: a stick/slip state of {n} balls for the stick/slip law, got {warm.law!r} of "
                         f"{len(warm.ball_velocity)}")
    reference_force = max(p.normal_force for contacts in patches for p in contacts)  # b2b_traction's F_ref
    speed = abs(velocity)

    def chain_state(friction, start_states, forces, what):   # the stick/slip chain from a start, and its checks
        states, slots, iterations, residual = rf.solve_balls(
            friction, start_states, touching, lambda layout: b2b.pair_function(layout, mu), forces=forces,
            complementarity="min", tolerance=tolerance, max_iterations=max_iterations, what=what)
        return _state(friction, states, slots, mu, velocity, radius, reference_force, iterations, residual, law)

    def from_warm():
        return chain_state(_friction(balls, radius, mu, velocity, law, reference_force),
                           np.column_stack([warm.ball_velocity / speed, warm.omega * radius / speed]),
                           warm.b2b_force / (mu * reference_force),
                           f"stick/slip {n}-ball B2B contact from a warm start")

    def from_alone():   # a chain from the states of its balls each solved alone, the B2B forces from zero
        if not touching.size:
            raise ValueError('start="alone" is the start of touching balls: from the states of each ball alone')
        singles = [solve([ball], ball_radius=radius, friction_coefficient=mu, groove_velocity=velocity,
                         tolerance=tolerance, max_iterations=max_iterations, start="auto") for ball in balls]
        return chain_state(_friction(balls, radius, mu, velocity, law, reference_force),
                           np.vstack([np.column_stack([s.ball_velocity / speed, s.omega * radius / speed])
                                      for s in singles]), np.zeros(n - 1),
                           f"stick/slip {n}-ball B2B contact from its balls alone")

    if rf.check_start(start, law, full_slip) == "auto":
        if warm is not None and n == 1:   # a ball alone: its warm state is the nearer start
            try:
                return from_warm()
            except ConvergenceError:
                pass
        return rf.solve_from_either_start(
            lambda first, steps: solve(balls, ball_radius=radius, friction_coefficient=mu, groove_velocity=velocity,
                                       gaps=gaps, tolerance=tolerance, max_iterations=steps, start=first),
            max_iterations, f"stick/slip {n}-ball B2B contact", warm=from_warm if warm is not None and n > 1 else None,
            alone=from_alone if touching.size else None, full_slip=not mixed)
    if warm is not None:
        try:
            return from_warm()
        except ConvergenceError:   # too far from the warm state: the cold start below
            pass
    friction = _friction(balls, radius, mu, velocity, law, reference_force)
    if start in ("rolling", "alone"):
        return from_alone() if start == "alone" else chain_state(friction, friction.rolling_start(), np.zeros(n - 1),
                                                                 f"stick/slip {n}-ball B2B contact from rolling")
    if full_slip is None:
        full_slip = b2b_traction.solve(patches, ball_radius=radius, friction_coefficient=mu, groove_velocity=velocity,
                                       gaps=gaps, tolerance=min(tolerance, 1e-11), max_iterations=100,
                                       name=rf.FULL_SLIP_NAME)
    start = np.column_stack([full_slip.ball_velocity / speed, full_slip.omega * radius / speed])
    forces = full_slip.b2b_force / (mu * reference_force)
    if law == "full-slip":
        return _state(friction, start, forces, mu, velocity, radius, reference_force, full_slip.iterations,
                      full_slip.residual, law)
    return chain_state(friction, start, forces, f"stick/slip {n}-ball B2B contact")


def _state(friction: rf.StickSlipFriction, states, slots, mu, velocity, radius, reference_force, iterations, residual,
           law) -> RollingB2BState:
    speed = abs(velocity)
    summaries = friction.summaries(states)
    width = max(len(row) for row in summaries)  # balls with fewer contacts: zeros after their own
    loss = np.array([[c.rigid_power for c in row] + [0.0] * (width - len(row)) for row in summaries])
    input_power = float(sum(c.drive_power for row in summaries for c in row))
    b2b_slip = b2b.b2b_terms(states, slots, mu)[3] * speed
    b2b_force = slots * mu * reference_force
    b2b_loss = mu * b2b_force * b2b_slip  # lin2019 eq 7
    losses = float(loss.sum() + b2b_loss.sum())
    balance = abs(input_power - losses) / max(abs(input_power), 1e-300)
    if not balance <= POWER_BALANCE_TOLERANCE:
        raise ConvergenceError(f"{law} B2B: power balance missed", residual=balance, iterations=iterations,
                               tolerance=POWER_BALANCE_TOLERANCE, reason="power balance missed")
    z_moment = np.array([sum(float(c.moment[2]) for c in row) for row in summaries])
    ball_velocity = states[:, 0] * speed
    return RollingB2BState(law, ball_velocity, states[:, 1:3] * speed / radius, 2.0 * ball_velocity / velocity - 1.0,
                           tuple(tuple(row) for row in summaries), z_moment, balance, friction.solves,
                           friction_loss=loss, input_power=input_power, b2b_force=b2b_force,
                           b2b_friction_loss=b2b_loss, b2b_slip=b2b_slip, iterations=iterations, residual=residual)


@dataclass(frozen=True)
class RollingModuleB2B:
    """lin2019's two-ball module (Sec 2.4-2.5) with stick/slip contacts and its full-slip limit on the same cells.

    touching, free : stick/slip states with and without B2B contact;  full_slip, full_slip_free : the same with
    the full-slip law;  b2b_force : (n-1,) N (stick/slip);  friction_increase : % (total loss touching / free - 1)
    and full_slip_increase : % (full slip);  power_balance : the largest relative power error of the four solves
    """

    touching: RollingB2BState
    free: RollingB2BState
    full_slip: RollingB2BState
    full_slip_free: RollingB2BState
    b2b_force: np.ndarray
    friction_increase: float
    full_slip_increase: float
    power_balance: float


def module_b2b(balls, guide=None, *, ball_radius: float | None = None, friction_coefficient: float | None = None,
               groove_velocity: float | None = None, low_order=None, **options) -> RollingModuleB2B:
    """Touching and free (gaps of ``R_B``) states of ``balls`` with both laws (:func:`solve`) in ``guide`` (a
    :class:`lowmodel.bearing.LinearGuide`: its ball radius, friction and speed; or those given one by one);
    ``options`` go to :func:`solve` (tolerance, max_iterations).  ``low_order(gaps)``: the low-order state of the
    same balls (:func:`lowmodel.linear_bearing.b2b.solve`), the second start of the full-slip chain where it does
    not converge from the free balls (high ``mu``, light loads: the touching state is far from the free one)."""
    ball_radius, friction_coefficient, groove_velocity = guide_values(guide, dict(
        ball_radius=ball_radius, friction_coefficient=friction_coefficient, groove_velocity=groove_velocity)).values()
    common = dict(ball_radius=ball_radius, friction_coefficient=friction_coefficient,
                  groove_velocity=groove_velocity, **options)
    n = len(balls)
    apart = np.full(n - 1, float(ball_radius))
    states = {}
    for gaps, key in ((None, "touching"), (apart, "free")):
        patches = [[c.patch() for c in contacts] for contacts in balls]
        limit_options = dict(ball_radius=ball_radius, friction_coefficient=friction_coefficient,
                             groove_velocity=groove_velocity, gaps=gaps, tolerance=1e-11, max_iterations=100,
                             name=rf.FULL_SLIP_NAME)
        try:
            limit = b2b_traction.solve(patches, **limit_options)
        except ConvergenceError as error:
            if low_order is None or gaps is not None:
                raise
            try:
                start = low_order(gaps)
            except ConvergenceError:  # no second start: the first failure is the answer
                raise error from None
            try:
                limit = b2b_traction.solve(patches, start=start, **limit_options)
            except ConvergenceError as again:
                raise ConvergenceError(f"{rf.FULL_SLIP_NAME}: converged neither from the free balls ({error}) nor "
                                       "from the low-order state", residual=again.residual, iterations=again.iterations,
                                       tolerance=again.tolerance, reason=again.reason or error.reason) from again
        states[key] = solve(balls, gaps=gaps, full_slip=limit, **common)
        states["full-slip " + key] = solve(balls, gaps=gaps, law="full-slip", full_slip=limit, **common)

    return RollingModuleB2B(states["touching"], states["free"], states["full-slip touching"],
                            states["full-slip free"], states["touching"].b2b_force,
                            100.0 * friction_increase(states["touching"], states["free"]),
                            100.0 * friction_increase(states["full-slip touching"], states["full-slip free"]),
                            max(s.power_balance for s in states.values()))


def b2b_contact_check(state: RollingB2BState, pair: int = 0, *, guide=None, ball_radius: float | None = None,
                      friction_coefficient: float | None = None, youngs_modulus: float | None = None,
                      poisson_ratio: float | None = None, cells: int = 24):
    """The B2B contact of ``pair`` solved as a steady rolling contact: ``(F_x / (mu F), creepage parameter)``.

    The two balls touch at ``+R_B e_z`` of ball j and ``-R_B e_z`` of ball j+1 (Hertz circle of two spheres of
    radius ``R_B`` under ``F_B2B``).  Relative to the contact (which moves with the balls), ball j's surface moves
    at ``Omega_j x R_B e_z`` and ball j+1's at ``-Omega_{j+1} x R_B e_z``: their mean is the rolling speed
    ``V = |Omega_j - Omega_{j+1}| R_B / 2`` (near zero), their difference the slip ``|dv|`` of eq 5; the
    creepage ``|dv| / V`` against ``mu p0 / G``.  lin2019's full sliding (eq 6) holds where the rolling solver's
    force is ``mu F`` (a ratio of 1); returns ``(nan, inf)`` for an open pair and ``(1, inf)`` for ``V = 0``.
    Ball radius, friction and material: given (the material defaults to lin2019 Table 1's steel), or from ``guide``
    (a :class:`lowmodel.bearing.LinearGuide`).
    """
    ball_radius, friction_coefficient, youngs_modulus, poisson_ratio = guide_values(guide, dict(
        ball_radius=ball_radius, friction_coefficient=friction_coefficient, youngs_modulus=youngs_modulus,
        poisson_ratio=poisson_ratio), TABLE1_STEEL).values()

    force = float(state.b2b_force[pair])
    if force <= 0.0:
        return math.nan, math.inf
    shear, nu = _material(youngs_modulus, poisson_ratio)
    omega = np.column_stack([state.omega, np.zeros(len(state.omega))])
    z = np.array([0.0, 0.0, 1.0])
    surface_1 = np.cross(omega[pair], ball_radius * z)
    surface_2 = np.cross(omega[pair + 1], -ball_radius * z)
    slip = surface_1 - surface_2
    mean = 0.5 * (surface_1 + surface_2)
    speed = float(np.linalg.norm(mean))
    e_star = youngs_modulus / (2.0 * (1.0 - poisson_ratio ** 2))  # two equal bodies: 1/E* = 2 (1 - nu^2) / E
    a = (3.0 * force * (0.5 * ball_radius) / (4.0 * e_star)) ** (1.0 / 3.0)  # Johnson eq 4.22, R = R_B / 2
    p0 = 1.5 * force / (math.pi * a * a)
    if speed == 0.0:
        return 1.0, math.inf
    creepage = float(np.linalg.norm(slip)) / speed
    result = rolling.steady_rolling(a, a, force, shear, nu, friction_coefficient, creepage, 0.0, 0.0, cells,
                                    rolling_speed=speed)
    return abs(result.force_rolling) / (friction_coefficient * force), creepage * shear / (friction_coefficient * p0)
