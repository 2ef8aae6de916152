"""The four ball-groove contacts of a linear-bearing ball as steady rolling contacts with stick and slip.

From a quasi-static ball state (:mod:`lowmodel.linear_bearing.ball`: ball velocity ``v_B`` along ``z``,
angular velocity ``Omega = (omega_x, omega_y, 0)``; lin2019 eqs 1-4) this module derives, per contact, the
rigid relative motion of the ball against the groove in Kalker's contact frame and solves the rolling
contact (:mod:`lowmodel.contact.rolling`).  The full-slip model of lin2019 (eqs A4-A7) keeps only the slip
at the contact centre and the spin; here every surface point slips with the rigid motion, the conformal
contact surface bending across the groove included (Heathcote's slip).

Frames.  lin2019 Fig 2 / lowmodel.geometry.fourpoint: ball centre at the origin, ``z`` along the grooves,
contact ``i`` at ``R_B n_i`` (``n_i`` outward, in the ``xy`` plane); lin2019's contact frame ``x_i`` (major
semi-axis ``a_i``, across the groove), ``y_i = -n_i`` (into the ball), ``z_i = z`` (rolling).  Kalker's frame
(:mod:`lowmodel.contact.rolling`) with body 1 = the ball: ``z_K = -n_i``; the material passes through the
contact with the mean velocity ``u_m = ((Omega x R_B n_i)_z + V_i - v_B) / 2`` (in the frame of the ball
centre, which carries the contact), so the rolling direction is ``x_K = -sign(u_m) z``, and
``y_K = z_K x x_K = -sign(u_m) x_i``; rolling speed ``V = |u_m|``.  Kalker's semi-axes: ``a = b_i`` (along
rolling), ``b = a_i`` (across).

Rigid relative motion (ball minus groove; the groove translates with ``V_i``, bottom 0, top ``v``): at a point
``r`` of the contact surface ``v_B z + Omega x r - V_i z``, i.e. the sliding velocity at the contact centre
``(v_B - V_i + (Omega x R_B n_i)_z) z`` and the angular velocity ``Omega``.  The contact surface is curved
across the groove with the radius ``R_d = 2 R_B r_g / (R_B + r_g)`` (``r_g = 2 f R_B`` the groove radius): for
bodies of one material the deformed surface lies midway between ball (``1/R_B``) and groove (``1/r_g``)
(Harris and Kotzalas 2006, Sec 'Rolling and sliding'; Johnson 1985 Sec 8.4 for Heathcote's slip).

Results back in lin2019's terms: the friction force on the ball along ``+z``, ``f_i = -sign(u_m) F_x``; the
lateral force along ``x_i``, ``-sign(u_m) F_y`` (zero in the full-slip model); the spin moment about ``-y_i``,
``M_i = -M_z`` (lin2019 eq A5's sign).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact.influence import combined_material
from ballbench.lowmodel.geometry.fourpoint import contact_normals
from ballbench.lowmodel.linear_bearing.ball import BallState
from ballbench.lowmodel.linear_bearing.contacts import BallContacts

__all__ = ["ContactMotion", "contact_motions", "RollingBallContact", "solve_contacts", "deformed_radius"]

_TOP = np.array([0.0, 0.0, 1.0, 1.0])


def deformed_radius(ball_radius: float, conformity: float) -> float:
    """Radius [m] of the deformed contact surface across the groove, ``2 R_B r_g / (R_B + r_g)``, ``r_g = 2 f R_B``."""
    radius = checks.positive("ball_radius", ball_radius, "m")
    groove = 2.0 * checks.conformity("conformity", conformity) * radius
    return 2.0 * radius * groove / (radius + groove)


@dataclass(frozen=True)
class ContactMotion:
    """Rigid relative motion of one contact in Kalker's frame (module docstring).

    rolling_speed V [m/s]; flow_sign ``sign(u_m)`` (``x_K = -flow_sign z``); sliding_velocity (2,) [m/s] at
    the contact centre; angular_velocity (3,) [rad/s]; creepage_rolling, creepage_lateral [-] and spin
    [rad/m] (Kalker's, ``sliding_velocity / V`` and ``omega_z / V``); semi_axis_rolling, semi_axis_lateral
    [m]; normal_force [N]; lateral_curvature ``1/R_d`` [1/m].
    """

    rolling_speed: float
    flow_sign: float
    sliding_velocity: tuple
    angular_velocity: tuple
    creepage_rolling: float
    creepage_lateral: float
    spin: float
    semi_axis_rolling: float
    semi_axis_lateral: float
    normal_force: float
    lateral_curvature: float


def contact_motions(contacts: BallContacts, state: BallState, conformity: float, ball: int = 0) -> list[ContactMotion]:
    """The four :class:`ContactMotion` (BL, BR, TR, TL) of ball ``ball`` in ``state`` (module docstring)."""
    index = checks.count("ball", ball, 0, contacts.n_balls - 1)
    radius = contacts.ball_radius
    normals = contact_normals(contacts.contact_angles[index])  # (4, 2)
    omega = np.array([state.omega[index, 0], state.omega[index, 1], 0.0])
    v_ball = float(state.ball_velocity[index])
    curvature = 1.0 / deformed_radius(radius, conformity)
    motions = []
    for i in range(4):
        n = np.array([normals[i, 0], normals[i, 1], 0.0])
        groove = contacts.groove_velocity * _TOP[i]
        surface = float(np.cross(omega, radius * n)[2])  # (Omega x R_B n_i)_z
        mean = 0.5 * (surface + groove - v_ball)
        if mean == 0.0:
            raise ValueError(f"contact {i}: no rolling (mean surface velocity 0): steady rolling needs V > 0")
        sign = math.copysign(1.0, mean)
        z = np.array([0.0, 0.0, 1.0])
        x_k = -sign * z
        z_k = -n
        y_k = np.cross(z_k, x_k)
        sliding = (v_ball - groove + surface) * z
        speed = abs(mean)
        sliding_k = (float(sliding @ x_k), float(sliding @ y_k))
        omega_k = (float(omega @ x_k), float(omega @ y_k), float(omega @ z_k))
        major = float(contacts.semi_major[index, i])
        motions.append(ContactMotion(speed, sign, sliding_k, omega_k, sliding_k[0] / speed, sliding_k[1] / speed,
                                     omega_k[2] / speed, major * float(contacts.b_over_a[index, i]), major,
                                     float(contacts.normal_forces[index, i]), curvature))
    return motions


@dataclass(frozen=True)
class RollingBallContact:
    """One contact solved with stick and slip, in lin2019's terms and Kalker's.

    friction_force : [N] on the ball along ``+z`` (lin2019 ``f_i``); lateral_force [N] along ``x_i``;
    spin_moment : [N m] about ``-y_i`` (lin2019 ``M_{i,O}``); spin_parameter Lambda; motion; solution (the
    :class:`~lowmodel.contact.rolling.RollingContact` in Kalker's frame).
    """

    friction_force: float
    lateral_force: float
    spin_moment: float
    spin_parameter: float
    motion: ContactMotion
    solution: rolling.RollingContact


def solve_contacts(contacts: BallContacts, state: BallState, conformity: float, *, youngs_modulus: float,
                   poisson_ratio: float, cells=(20, 80), ball: int = 0, heathcote: bool = True,
                   operator_for=None, tolerance: float = 1e-9) -> list[RollingBallContact]:
    """Solve the four contacts of ball ``ball`` as steady rolling contacts on two half-spaces (Hertz pressure).

    ``youngs_modulus`` [Pa], ``poisson_ratio``: ball and groove (one material); ``cells`` ``(n_rolling,
    n_lateral)`` across each ellipse; ``heathcote=False`` drops the surface curvature (the slip of lin2019's
    eqs 1-3: centre slip and spin only).  ``operator_for(grid, motion)`` optionally returns the operator to use
    (e.g. an FE compliance, :class:`~lowmodel.contact.rolling.MatrixOperator`); default the half-space.
    """
    e = checks.positive("youngs_modulus", youngs_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    shear, nu_c, _ = combined_material(e / (2.0 * (1.0 + nu)), nu)
    results = []
    for motion in contact_motions(contacts, state, conformity, ball):
        a, b = motion.semi_axis_rolling, motion.semi_axis_lateral
        grid = rolling.hertz_grid(a, b, cells)
        pressure = rolling.hertz_pressure(grid, a, b, motion.normal_force)
        operator = rolling.half_space_operator(grid, shear, nu_c) if operator_for is None else \
            operator_for(grid, motion)
        w = rolling.rigid_slip_field(grid, motion.sliding_velocity, motion.angular_velocity, motion.rolling_speed,
                                     lateral_curvature=motion.lateral_curvature if heathcote else 0.0)
        solution = rolling.solve(pressure, operator, contacts.friction_coefficient, w,
                                 rolling_speed=motion.rolling_speed, tolerance=tolerance)
        p0 = 1.5 * motion.normal_force / (math.pi * a * b)
        lam = float(rolling.spin_parameter(motion.spin, b, contacts.friction_coefficient, p0, shear))
        results.append(RollingBallContact(-motion.flow_sign * solution.force_rolling,
                                          -motion.flow_sign * solution.force_lateral, -solution.spin_moment, lam,
                                          motion, solution))
    return results
