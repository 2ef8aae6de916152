"""Ball-to-ball (B2B) contact in the ball screw with stick/slip ball-to-groove contacts (docs/b2b_rolling.md).

lin2019 Sec 3.1-3.2, eqs 54-61, with the friction of every ball-to-groove contact from the steady rolling solve
(:mod:`lowmodel.contact.rolling_friction`) in place of the full-slip ellipse friction of eqs 44-47.  The rest is
the FE-informed screw model's (:mod:`lowmodel.screw.b2b_traction`, docs/b2b_traction.md):

* unknowns per ball ``x = (omega_B / |omega_N|, omega R_B / (|omega_N| L / 2 pi))`` (orbit speed, spin relative to
  CS3), rows their generalised forces: the force along ``y3`` with ``z_hat . M`` and the three moments of eq 54;
* the rigid slip of the ball against screw and nut at every contact point from the helical field
  (lin2019 eqs 36, 43-47; :func:`lowmodel.screw.b2b_traction.slip_field`), on the contact surface curved across
  the groove (Heathcote's slip);
* the B2B contact a point on the exact helix chord with full sliding (eqs 56-59,
  :func:`lowmodel.screw.b2b_traction.pair_function`), the complementarity of eqs 60-61 (Fischer-Burmeister,
  the chain of :mod:`lowmodel.b2b_chain`);
* ball-to-groove normal loads decoupled from friction and from the B2B force (given pressures: Hertz's at the
  low-order state's forces and loaded contact angles, or the FE module's).

Each solve starts from the full-slip solution of the same cells (:func:`lowmodel.screw.b2b_traction.solve` on
:meth:`GridContact.patch`); the power balance (the nut's input = the rigid power of all contacts + the B2B loss
``mu F_B2B |s|``, eq 58) is checked in every solve to :data:`POWER_BALANCE_TOLERANCE`.

```python
from ballbench.lowmodel.screw import b2b, b2b_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts
module = screw_contacts.screw_module(oversize=1.6848e-6)
contacts = screw_contacts.ball_contacts(module, [0.0, 0.0349], reading="tilted")
low = b2b.solve(contacts, 50.0)
balls = [b2b_rolling.hertz_contacts(low, contacts, j, cells=(12, 48)) for j in range(2)]
result = b2b_rolling.module_b2b(balls, module)
result.b2b_force, result.full_slip.b2b_force, result.friction_increase
```
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import rolling_friction as rf
from ballbench.lowmodel.contact.influence import combined_material
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing.rolling_contacts import deformed_radius as radius_of
from ballbench.lowmodel.screw import b2b, b2b_traction
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.solvers import check_solver_options
from ballbench.lowmodel.state import BallStateBase
from ballbench.lowmodel.state import friction_increase

__all__ = ["ScrewRollingState", "ScrewRollingModule", "hertz_contacts", "sampled_contacts", "solve", "module_b2b",
           "deformed_radius", "POWER_BALANCE_TOLERANCE", "AXIS"]

POWER_BALANCE_TOLERANCE = 1e-6  # relative: every solve checks it
AXIS = np.array([0.0, 1.0, 0.0])  # y3: the helix tangent at the ball (CS3, lin2019 eq 41), the rolling axis
AXIS.setflags(write=False)
_SIGN_U = (-1.0, -1.0, 1.0, 1.0)  # contact direction from the ball centre: -x3 on the screw, +x3 on the nut (eq 37)
_SIGN_W = (-1.0, 1.0, 1.0, -1.0)  # -z3 on the left flanks, +z3 on the right


@dataclass(frozen=True)
class ScrewRollingState(BallStateBase):
    """Quasi-static state of ``n`` balls of a ball screw with stick/slip (or full-slip) contacts on grids; the
    fields of :class:`lowmodel.state.BallStateBase` (``friction_loss`` (n, c): each contact's rigid power).

    law;  orbit_speed (n,) rad/s;  omega (n, 3) rad/s (spin relative to CS3);  contacts: per ball the
    :class:`~lowmodel.contact.rolling_friction.ContactSummary` of each contact;  power_balance;  rolling_solves
    """

    law: str
    orbit_speed: np.ndarray
    omega: np.ndarray
    contacts: tuple
    power_balance: float
    rolling_solves: int = 0


def deformed_radius(module: screw_contacts.ScrewModule) -> float:
    """Radius [m] of the deformed contact surface across the groove, ``2 R_B r_g / (R_B + r_g)`` (both flanks of
    one conformity; :func:`lowmodel.linear_bearing.rolling_contacts.deformed_radius`)."""
    return radius_of(module.ball_radius, module.conformity)


def _material(module: screw_contacts.ScrewModule) -> tuple[float, float]:
    e, nu = module.youngs_modulus, module.poisson_ratio
    shear, nu_c, _ = combined_material(e / (2.0 * (1.0 + nu)), nu)
    return shear, nu_c


def hertz_contacts(state: sb.ScrewBallState, contacts: screw_contacts.BallContacts, ball: int = 0, *, cells=(12, 48),
                   heathcote: bool = True, operator_for=None) -> tuple:
    """The loaded contacts (SL, SR, NR, NL) of ``ball`` of a low-order ``state`` (:func:`lowmodel.screw.b2b.solve`
    on ``contacts``) as :class:`GridContact` with Hertz's pressure (the ellipses of
    :func:`lowmodel.screw.b2b_traction.hertz_patches`): at ``R_B e_i`` at the loaded contact angle, semi-axis
    ``b_i`` along ``y3`` and ``a_i`` across, the state's force; CS3 of the ball.  ``cells = (n_along,
    n_across)`` (or one fixed ``SurfaceGrid``); ``heathcote=False``: planar contact surfaces;
    ``operator_for(grid)``: the operator (default the half-space of the module's material).  Unloaded contacts are
    left out.  ``state`` may also be the frictionless statics (:class:`lowmodel.screw.preload.FrictionlessState`,
    past the preload loss): its semi-axes are Hertz's of its forces, ``contacts.semi_major_unit F^(1/3)``."""
    index = checks.count("ball", ball, 0, contacts.n_balls - 1)
    module = contacts.module
    shear, nu = _material(module)
    curvature = 1.0 / deformed_radius(module) if heathcote else 0.0
    out = []
    for i, name in enumerate(screw_contacts.CONTACT_NAMES):
        force = float(state.normal_force[index, i])
        if force <= 0.0:
            continue
        beta = float(state.contact_angle[index, i])
        e = np.array([_SIGN_U[i] * math.cos(beta), 0.0, _SIGN_W[i] * math.sin(beta)])
        a = (float(state.semi_major[index, i]) if hasattr(state, "semi_major") else
             float(contacts.semi_major_unit[index, i]) * force ** (1.0 / 3.0))
        b = a * float(contacts.b_over_a[index, i])
        out.append(rf.hertz_contact(name, i >= 2, module.ball_radius * e, e, AXIS, b, a, force, cells,
                                    lateral_curvature=curvature, shear_modulus=shear, poisson_ratio=nu,
                                    operator_for=operator_for))
    return tuple(out)


def sampled_contacts(samples, module: screw_contacts.ScrewModule, *, cells=None, grid=None, heathcote: bool = True,
                     operator=None, outside: float = 0.0) -> tuple:
    """The contacts of one ball from sampled pressures (e.g. the FE screw module's): ``samples`` a sequence of
    ``(name, top, points (q, 3) [m], pressure (q,) [Pa], areas (q,) [m^2])``, points on the ball relative to its
    centre in its CS3; a grid of ``cells`` over each pressure, or the given ``grid`` with ``operator`` (``outside``:
    the share of the force allowed beyond its inner cells, :func:`lowmodel.contact.rolling_friction.sampled_pressure`).
    """
    shear, nu = _material(module)
    curvature = 1.0 / deformed_radius(module) if heathcote else 0.0
    return tuple(rf.sampled_contact(name, top, points, pressure, areas, AXIS, cells=cells, grid=grid,
                                    lateral_curvature=curvature, shear_modulus=shear, poisson_ratio=nu,
                                    operator=operator, outside=outside)
                 for name, top, points, pressure, areas in samples)


def _units(module: screw_contacts.ScrewModule) -> tuple[float, float]:
    """(m/s per slip unit, rad/s per spin unknown)."""
    speed = abs(module.nut_speed) * module.helix_radius
    return speed, speed / module.ball_radius


def solve(balls, module: screw_contacts.ScrewModule, *, gaps=None, with_b2b: bool = True, law: str = "stick-slip",
          tolerance: float = 1e-9, max_iterations: int = 40,
          full_slip: b2b_traction.ScrewTractionState | None = None, start: str = "full-slip") -> ScrewRollingState:
    """Quasi-static motion of ``n >= 1`` balls of a ball screw whose contacts are :class:`GridContact` s (each in its
    ball's CS3), with B2B contact (lin2019 eqs 54-61; module docstring).

    module : the :class:`~lowmodel.screw.contacts.ScrewModule` (ball radius, pitch radius, lead, nut speed, mu,
        material; the normal loads come with the contacts);  gaps (n-1,) rad beyond touching (default touching);
    with_b2b : False solves the balls apart;  law : "stick-slip" or "full-slip" (pointwise Coulomb on the cells)
    tolerance : max residual (units ``mu F_ref``) and of eqs 60-61;  full_slip : the full-slip state (the start)
    start : "full-slip" (from ``full_slip``, solved here when None), "rolling" or "auto" (stick/slip only), as
        :func:`lowmodel.linear_bearing.b2b_rolling.solve`'s (docs/b2b_rolling.md, "Where full sliding has no state")

    ValueError for bad input; ConvergenceError (with its residual) when Newton fails or the power balance misses.
    """
    check_solver_options(tolerance, max_iterations)
    law = checks.choice("law", law, rf.LAWS)
    if not isinstance(module, screw_contacts.ScrewModule):
        raise ValueError(f"module must be a screw.contacts.ScrewModule, got {type(module)!r}")
    balls = [tuple(contacts) for contacts in balls]
    n = len(balls)
    if n < 1 or min(len(c) for c in balls) < 1:
        raise ValueError("balls must hold n >= 1 balls with >= 1 contact each")
    gaps = b2b.check_gaps(gaps, n - 1)
    touching = np.flatnonzero(gaps <= 1e-12) if with_b2b else np.zeros(0, dtype=int)
    patches = [[c.patch() for c in contacts] for contacts in balls]
    if rf.check_start(start, law, full_slip) == "alone":
        raise ValueError('start="alone" is the linear bearing\'s (lowmodel.linear_bearing.b2b_rolling.solve); a screw '
                         'takes "full-slip", "rolling" or "auto"')
    if start == "auto":
        return rf.solve_from_either_start(
            lambda first, steps: solve(balls, module, gaps=gaps, with_b2b=with_b2b, tolerance=tolerance,
                                       max_iterations=steps, start=first),
            max_iterations, f"stick/slip {n}-ball screw B2B contact")
    if start == "rolling":
        full_slip = _rolling_full_slip(balls, module, patches)
    if full_slip is None:
        full_slip = b2b_traction.solve(patches, module, gaps=gaps, with_b2b=with_b2b,
                                       tolerance=min(tolerance, 1e-11), max_iterations=100,
                                       name=rf.FULL_SLIP_NAME)
    mu = module.friction_coefficient
    reference_force = max(p.normal_force for contacts in patches for p in contacts)
    speed, spin = _units(module)
    start = np.column_stack([full_slip.orbit_speed / abs(module.nut_speed), full_slip.omega / spin])
    slots = full_slip.b2b_force / (mu * reference_force)

    def field(points, moving):
        return b2b_traction.slip_field(points, module, moving)

    friction = rf.StickSlipFriction(balls, field, mu, reference_force, math.copysign(1.0, module.nut_speed), speed,
                                    law=law)
    if law == "full-slip":
        states, iterations, residual = start, full_slip.iterations, full_slip.residual
    else:
        states, slots, iterations, residual = rf.solve_balls(
            friction, start, touching, lambda layout: b2b_traction.pair_function(module, layout, reference_force),
            forces=slots, complementarity="fischer-burmeister", tolerance=tolerance, max_iterations=max_iterations,
            what=f"stick/slip {n}-ball screw B2B contact")
    return _state(friction, states, slots, module, reference_force, iterations, residual, law)


def _rolling_full_slip(balls, module: screw_contacts.ScrewModule, patches):
    """The rolling start (:meth:`~lowmodel.contact.rolling_friction.StickSlipFriction.rolling_start`) in the shape
    of a full-slip state: orbit speed, spins, B2B forces zero."""
    speed, spin = _units(module)
    reference_force = max(p.normal_force for contacts in patches for p in contacts)

    def field(points, moving):
        return b2b_traction.slip_field(points, module, moving)

    start = rf.StickSlipFriction(balls, field, module.friction_coefficient, reference_force,
                                 math.copysign(1.0, module.nut_speed), speed).rolling_start()
    return SimpleNamespace(orbit_speed=start[:, 0] * abs(module.nut_speed), omega=start[:, 1:] * spin,
                           b2b_force=np.zeros(max(len(balls) - 1, 0)), iterations=0, residual=math.inf)


def _state(friction, states, slots, module, reference_force, iterations, residual, law) -> ScrewRollingState:
    n = len(states)
    mu = module.friction_coefficient
    speed, spin = _units(module)
    summaries = friction.summaries(states)
    width = max(len(row) for row in summaries)
    loss = np.zeros((n, width))
    for b, row in enumerate(summaries):
        loss[b, :len(row)] = [c.rigid_power for c in row]
    input_power = float(sum(c.drive_power for row in summaries for c in row))
    forces = np.asarray(slots, dtype=float) * mu * reference_force
    b2b_slip = np.zeros(max(n - 1, 0))
    if n > 1:
        b2b_slip = b2b.b2b_loads(states[:, 1:] * spin, forces, b2b.pair_geometry(module), module.ball_radius, mu)[3]
    b2b_loss = mu * forces * b2b_slip  # lin2019 eq 58
    losses = float(loss.sum() + b2b_loss.sum())
    balance = abs(input_power - losses) / max(abs(input_power), 1e-300)
    if not balance <= POWER_BALANCE_TOLERANCE:
        raise ConvergenceError(f"{law} screw B2B: power balance missed", residual=balance, iterations=iterations,
                               tolerance=POWER_BALANCE_TOLERANCE, reason="power balance missed")
    return ScrewRollingState(law, states[:, 0] * abs(module.nut_speed), states[:, 1:] * spin,
                             tuple(tuple(row) for row in summaries), balance, friction.solves, friction_loss=loss,
                             input_power=input_power, b2b_force=forces, b2b_friction_loss=b2b_loss, b2b_slip=b2b_slip,
                             iterations=iterations, residual=residual)


@dataclass(frozen=True)
class ScrewRollingModule:
    """lin2019 Sec 3.3's two-ball module with stick/slip contacts and its full-slip limit on the same cells
    (fields as :class:`lowmodel.linear_bearing.b2b_rolling.RollingModuleB2B`)."""

    touching: ScrewRollingState
    free: ScrewRollingState
    full_slip: ScrewRollingState
    full_slip_free: ScrewRollingState
    b2b_force: np.ndarray
    friction_increase: float
    full_slip_increase: float
    power_balance: float


def module_b2b(balls, module: screw_contacts.ScrewModule, **options) -> ScrewRollingModule:
    """Touching and free states of ``balls`` with both laws (:func:`solve`; ``options`` go there)."""
    states = {}
    for with_b2b, key in ((True, "touching"), (False, "free")):
        patches = [[c.patch() for c in contacts] for contacts in balls]
        limit = b2b_traction.solve(patches, module, with_b2b=with_b2b, tolerance=1e-11, max_iterations=100,
                                   name=rf.FULL_SLIP_NAME)
        states[key] = solve(balls, module, with_b2b=with_b2b, full_slip=limit, **options)
        states["full-slip " + key] = solve(balls, module, with_b2b=with_b2b, law="full-slip", full_slip=limit,
                                           **options)

    return ScrewRollingModule(states["touching"], states["free"], states["full-slip touching"],
                              states["full-slip free"], states["touching"].b2b_force,
                              100.0 * friction_increase(states["touching"], states["free"]),
                              100.0 * friction_increase(states["full-slip touching"], states["full-slip free"]),
                              max(s.power_balance for s in states.values()))
