"""What an engineer reads from a case: per ball and contact the loads, angles, Hertz ellipses and pressures; the
carriage friction force [N] of a linear guide or the friction torque [N m] of a ball screw, with and without
ball-to-ball (B2B) contact, the friction increase and the B2B forces.  Plain frozen dataclasses in SI units
(``to_dataset()`` gives an xarray Dataset), computed by the low-order numerical models:

* linear guide: ``lowmodel.linear_bearing.b2b`` (lin2019 eqs 1-10; contacts by lin2017 eq 36 with Hertz ellipses);
  the friction force of the carriage is the power its drive puts in over its speed, ``F = P_in / |v|`` (at
  equilibrium ``P_in`` equals the friction losses, lin2019 eq 7);
* ball screw: ``lowmodel.screw.b2b`` (lin2019 eqs 34-61); the nut drives, the screw is at rest, and the friction
  torque is ``T = P_in / |omega_N|``.

"Free" is the state with the balls apart (no B2B contact), "touching" the state with every neighbouring pair in
contact; the friction increase is ``P_touching / P_free - 1`` (lin2019 Fig 9c, Table 5).  The numbers are those of
the balls of the case (the two-ball module of lin2019), not of a whole carriage or nut: a carriage of N balls
carries N / n_balls such modules if its balls are loaded alike.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

__all__ = ["ContactLoad", "GuideResult", "ScrewResult", "guide_contacts", "guide_result", "screw_result",
           "screw_frictionless_contacts"]


@dataclass(frozen=True)
class ContactLoad:
    """One ball-raceway contact of the touching state: ``ball`` (1-based), ``contact`` (BL, BR, TR, TL or SL, SR,
    NR, NL), ``normal_force`` [N], ``contact_angle`` [rad], Hertz semi-axes ``a``, ``b`` [m], maximum pressure
    ``p0`` [Pa] (``3 F / (2 pi a b)``), ``approach`` [m]."""

    ball: int
    contact: str
    normal_force: float
    contact_angle: float
    a: float
    b: float
    p0: float
    approach: float


def _table(contacts) -> list[dict]:
    return [asdict(c) for c in contacts]


def _dataset(contacts, names, attrs: dict):
    import xarray as xr

    balls = sorted({c.ball for c in contacts})
    data = {}
    for field in ("normal_force", "contact_angle", "a", "b", "p0", "approach"):
        grid = np.full((len(balls), len(names)), np.nan)
        for c in contacts:
            grid[balls.index(c.ball), names.index(c.contact)] = getattr(c, field)
        data[field] = (("ball", "contact"), grid)
    return xr.Dataset(data, coords={"ball": balls, "contact": list(names)}, attrs=attrs)


@dataclass(frozen=True)
class GuideResult:
    """A linear guide's balls touching and free (see the module docstring); SI units."""

    case: str
    model: str
    contacts: tuple[ContactLoad, ...]
    b2b_forces: tuple[float, ...]             # [N] between balls j and j+1
    friction_force_free: float                # [N] carriage friction force, balls apart
    friction_force: float                     # [N] carriage friction force, balls touching
    power_free: float                         # [W]
    power: float                              # [W]
    velocity_deviation_free: tuple[float, ...]  # epsilon = 2 v_B / v - 1 of each free ball (lin2019 eq 21)

    @property
    def friction_increase(self) -> float:
        """``F_touching / F_free - 1`` [-] (lin2019 Fig 9c)."""
        return self.friction_force / self.friction_force_free - 1.0

    def table(self) -> list[dict]:
        """One dict per contact (ball, contact, normal_force, contact_angle, a, b, p0, approach; SI)."""
        return _table(self.contacts)

    def to_dataset(self):
        """The contacts as an xarray Dataset (dims ball, contact) with the scalars as attributes."""
        return _dataset(self.contacts, ("BL", "BR", "TR", "TL"), {
            "case": self.case, "model": self.model, "friction_force_N": self.friction_force,
            "friction_force_free_N": self.friction_force_free, "friction_increase": self.friction_increase,
            "b2b_forces_N": list(self.b2b_forces)})


@dataclass(frozen=True)
class ScrewResult:
    """A ball screw's balls touching and free (see the module docstring); SI units."""

    case: str
    model: str
    contacts: tuple[ContactLoad, ...]
    b2b_forces: tuple[float, ...]             # [N]
    friction_torque_free: float               # [N m] on the nut, balls apart
    friction_torque: float                    # [N m] on the nut, balls touching
    power_free: float                         # [W]
    power: float                              # [W]
    axial_shares: tuple[float, ...]           # [N] axial load carried by each ball (touching)

    @property
    def friction_increase(self) -> float:
        """``T_touching / T_free - 1`` [-] (lin2019 Table 5's friction increase / 100)."""
        return self.friction_torque / self.friction_torque_free - 1.0

    def table(self) -> list[dict]:
        return _table(self.contacts)

    def to_dataset(self):
        return _dataset(self.contacts, ("SL", "SR", "NR", "NL"), {
            "case": self.case, "model": self.model, "friction_torque_Nm": self.friction_torque,
            "friction_torque_free_Nm": self.friction_torque_free, "friction_increase": self.friction_increase,
            "b2b_forces_N": list(self.b2b_forces)})


def guide_contacts(case):
    """The balls' contacts of a :class:`LinearGuideCase` (lowmodel.linear_bearing): ``b2b.module_contacts`` for the
    bottom deviations ``(-theta, +theta)`` of lin2019 Sec 2.4, else ``contacts.ball_contacts`` with the case's
    four deviations and alternating side forces (lin2017 eq 36 per ball)."""
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts

    guide = case.guide
    if case.deviations[0] == -case.deviations[1]:
        return b2b.module_contacts(case.theta, case.side_force_ratio, top_deviations=case.top_deviations,
                                   n_balls=case.n_balls, nominal_angle=guide.nominal_angle,
                                   vertical_force=case.vertical_force, ball_radius=guide.ball_radius,
                                   conformity=guide.conformity, friction_coefficient=guide.friction_coefficient,
                                   groove_velocity=guide.groove_velocity, **guide.material.keywords)
    angles = np.tile(case.contact_angles, (case.n_balls, 1))
    sides = np.array([case.side_force(j) for j in range(case.n_balls)])
    return bearing_contacts.ball_contacts(angles, sides, case.vertical_force, ball_radius=guide.ball_radius,
                                          conformity=guide.conformity,
                                          friction_coefficient=guide.friction_coefficient,
                                          groove_velocity=guide.groove_velocity, **guide.material.keywords)


def guide_result(case, touching=None, free=None, contacts=None) -> GuideResult:
    """:class:`GuideResult` of a :class:`LinearGuideCase` by the low-order numerical model (solved here unless the
    states are given: ``contacts`` of :func:`guide_contacts`, ``touching`` and ``free`` of ``b2b.solve``)."""
    from ballbench.lowmodel.contact import hertz
    from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES
    from ballbench.lowmodel.linear_bearing import b2b

    guide = case.guide
    if contacts is None:
        contacts = guide_contacts(case)
    gaps_touching = np.zeros(case.n_balls - 1)
    if touching is None:
        touching = b2b.solve(contacts, gaps_touching)
    if free is None:
        free = b2b.solve(contacts, np.full(case.n_balls - 1, 1e-3))
    constant = hertz.hertz_constant(hertz.ball_in_groove(guide.ball_radius, guide.conformity,
                                                         **guide.material.keywords))
    rows = []
    forces, angles = contacts.normal_forces, contacts.contact_angles
    a = contacts.semi_major
    b = a * contacts.b_over_a
    for ball in range(contacts.normal_forces.shape[0]):
        for i, name in enumerate(CONTACT_NAMES):
            f = float(forces[ball, i])
            rows.append(ContactLoad(ball + 1, name, f, float(angles[ball, i]), float(a[ball, i]), float(b[ball, i]),
                                    1.5 * f / (math.pi * float(a[ball, i]) * float(b[ball, i])),
                                    constant * f ** (2.0 / 3.0)))
    speed = abs(guide.groove_velocity)
    return GuideResult(case.name, "lowmodel.linear_bearing.b2b", tuple(rows),
                       tuple(float(x) for x in touching.b2b_force), free.input_power / speed,
                       touching.input_power / speed, float(free.input_power), float(touching.input_power),
                       tuple(float(x) for x in free.velocity_deviation))


def screw_result(case, touching=None, free=None, contacts=None) -> ScrewResult:
    """:class:`ScrewResult` of a :class:`BallScrewCase` by the low-order numerical model (solved here unless the
    states are given, as ``studies.screw_two_ball.two_ball`` returns them)."""
    from ballbench.validation.studies import fe_b2b_screw, screw_two_ball

    if contacts is None:
        contacts = screw_two_ball.ball_contacts(case)
    if touching is None or free is None:
        free, touching = screw_two_ball.two_ball(case)
    a = touching.semi_major
    rows = _screw_rows(touching.normal_force, touching.contact_angle, a, a * contacts.b_over_a, touching.approach)
    speed = abs(case.screw.nut_speed)
    shares = fe_b2b_screw.axial_shares(contacts, touching)
    return ScrewResult(case.name, "lowmodel.screw.b2b", tuple(rows), tuple(float(x) for x in touching.b2b_force),
                       free.input_power / speed, touching.input_power / speed, float(free.input_power),
                       float(touching.input_power), tuple(float(x) for x in shares))


def screw_frictionless_contacts(case) -> tuple[ContactLoad, ...]:
    """The contacts of a :class:`BallScrewCase`'s balls by the frictionless statics at the case's axial load
    (lowmodel.screw.preload.frictionless_statics: exact flank arcs, Hertz's law lin2019 eq 53, contacts unload; below
    or past the preload loss), not lin2019's friction model: per ball and contact the normal force, the actual contact
    angle (eq 37), the Hertz semi-axes and maximum pressure of the same Hertz solution as the statics' ``C_i`` (at the
    flank's contact angle, lowmodel.screw.contacts) and the approach (not positive: the contact is open)."""
    from ballbench.lowmodel.screw import preload
    from ballbench.validation.studies import screw_two_ball

    contacts = screw_two_ball.ball_contacts(case)
    state = preload.frictionless_statics(contacts, case.axial_load)
    a = contacts.semi_major_unit * np.cbrt(state.normal_force)
    return tuple(_screw_rows(state.normal_force, state.contact_angle, a, a * contacts.b_over_a, state.approach))


def _screw_rows(forces, angles, a, b, approaches) -> list[ContactLoad]:
    """ContactLoad rows (SL, SR, NR, NL of each ball) of (n, 4) normal forces [N], contact angles [rad], semi-axes
    a, b [m] and approaches [m]; p0 = 1.5 F / (pi a b) (Hertz), 0 where the contact carries no load."""
    from ballbench.lowmodel.screw.contacts import CONTACT_NAMES

    rows = []
    for ball in range(forces.shape[0]):
        for i, name in enumerate(CONTACT_NAMES):
            f = float(forces[ball, i])
            area = math.pi * float(a[ball, i]) * float(b[ball, i])
            rows.append(ContactLoad(ball + 1, name, f, float(angles[ball, i]), float(a[ball, i]), float(b[ball, i]),
                                    1.5 * f / area if f > 0 else 0.0, float(approaches[ball, i])))
    return rows
