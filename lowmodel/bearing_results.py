"""What an engineer reads of a load case (:mod:`lowmodel.bearing`): per ball and contact the loads, angles, Hertz
ellipses and pressures; the carriage friction force [N] of a linear guide or the friction torque [N m] of a ball
screw, with and without ball-to-ball (B2B) contact, the friction increase and the B2B forces.  Plain frozen
dataclasses in SI units (``to_dataset()`` gives an xarray Dataset), computed by the low-order numerical models:

* linear guide: ``lowmodel.linear_bearing.b2b`` (lin2019 eqs 1-10; contacts by lin2017 eq 36 with Hertz ellipses);
  the friction force of the carriage is the power its drive puts in over its speed, ``F = P_in / |v|`` (at
  equilibrium ``P_in`` equals the friction losses, lin2019 eq 7);
* ball screw: ``lowmodel.screw.b2b`` (lin2019 eqs 34-61); the nut drives, the screw is at rest, and the friction
  torque is ``T = P_in / |omega_N|``.

Where lin2019's full-sliding model finds no state (a guide near its four-point limit, a screw past its preload loss)
the numbers come from the stick/slip law on a half-space (:func:`guide_states`, :func:`screw_law_states`; a screw's on
the frictionless statics' loads), and the result says so (``law``, ``law_reason``; docs/b2b_rolling.md, "Where full
sliding has no state"): seconds instead of milliseconds.

"Free" is the state with the balls apart (no B2B contact), "touching" the state with every neighbouring pair in
contact; the friction increase is ``P_touching / P_free - 1`` (lin2019 Fig 9c, Table 5).  The numbers are those of
the balls of the case (the two-ball module of lin2019), not of a whole carriage or nut: a carriage of N balls
carries N / n_balls such modules if its balls are loaded alike.

The front door of ``import ballbench`` (docs/your_own_bearing.md): :func:`friction` (the results above) and
:func:`contact` (exact Hertz of a contact, or of the most loaded contact of a guide or screw)::

    import ballbench
    case = ballbench.load_case("my_guide.toml")   # a lowmodel.bearing load case (with the validation's name and FE)
    ballbench.friction(case).friction_force       # [N]
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from types import SimpleNamespace

import numpy as np

from ballbench.lowmodel.bearing import ContactLoadCase, GuideLoadCase, ScrewLoadCase
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES as GUIDE_CONTACTS
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import preload
from ballbench.lowmodel.screw.contacts import CONTACT_NAMES as SCREW_CONTACTS

__all__ = ["ContactLoad", "ContactLoads", "GuideResult", "ScrewResult", "friction", "contact", "most_loaded",
           "guide_contacts", "guide_result", "GuideStates", "guide_states", "guide_stick_slip_states",
           "FULL_SLIDING", "STICK_SLIP", "STICK_SLIP_CELLS", "screw_states", "ScrewStates", "screw_law_states",
           "screw_stick_slip_states", "screw_result", "stick_slip_forces", "axial_shares",
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


FULL_SLIDING = "full sliding"  # lin2019's law: mu p opposite to the rigid slip at every point (eqs 4-10)
STICK_SLIP = "stick/slip on a half-space"  # the steady rolling law of every contact (docs/b2b_rolling.md)
# the stick/slip law's cells (along, across each Hertz ellipse) where full sliding has no state: within 0.1 % of
# 24 x 96 on the friction force at the four-point limit (docs/b2b_rolling.md, "Where full sliding has no state")
STICK_SLIP_CELLS = (16, 64)


@dataclass(frozen=True)
class GuideResult:
    """A linear guide's balls touching and free (see the module docstring); SI units.  ``law``: the contact law
    that gave the friction (:data:`FULL_SLIDING`, or :data:`STICK_SLIP` where full sliding has no state,
    ``law_reason`` then says why)."""

    case: str
    model: str
    contacts: tuple[ContactLoad, ...]
    b2b_forces: tuple[float, ...]             # [N] between balls j and j+1
    friction_force_free: float                # [N] carriage friction force, balls apart
    friction_force: float                     # [N] carriage friction force, balls touching
    power_free: float                         # [W]
    power: float                              # [W]
    velocity_deviation_free: tuple[float, ...]  # epsilon = 2 v_B / v - 1 of each free ball (lin2019 eq 21)
    law: str = FULL_SLIDING
    law_reason: str = ""

    @property
    def friction_increase(self) -> float:
        """``F_touching / F_free - 1`` [-] (lin2019 Fig 9c)."""
        return self.friction_force / self.friction_force_free - 1.0

    def table(self) -> list[dict]:
        """One dict per contact (ball, contact, normal_force, contact_angle, a, b, p0, approach; SI)."""
        return _table(self.contacts)

    def to_dataset(self):
        """The contacts as an xarray Dataset (dims ball, contact) with the scalars as attributes."""
        return _dataset(self.contacts, GUIDE_CONTACTS, {
            "case": self.case, "model": self.model, "friction_force_N": self.friction_force,
            "friction_force_free_N": self.friction_force_free, "friction_increase": self.friction_increase,
            "b2b_forces_N": list(self.b2b_forces)})


@dataclass(frozen=True)
class ScrewResult:
    """A ball screw's balls touching and free (see the module docstring); SI units.  ``law`` and ``law_reason`` as
    :class:`GuideResult`'s (the stick/slip law on the loads of the frictionless statics where lin2019's model has no
    state, e.g. past the preload loss)."""

    case: str
    model: str
    contacts: tuple[ContactLoad, ...]
    b2b_forces: tuple[float, ...]             # [N]
    friction_torque_free: float               # [N m] on the nut, balls apart
    friction_torque: float                    # [N m] on the nut, balls touching
    power_free: float                         # [W]
    power: float                              # [W]
    axial_shares: tuple[float, ...]           # [N] axial load carried by each ball (touching)
    law: str = FULL_SLIDING
    law_reason: str = ""

    @property
    def friction_increase(self) -> float:
        """``T_touching / T_free - 1`` [-] (lin2019 Table 5's friction increase / 100)."""
        return self.friction_torque / self.friction_torque_free - 1.0

    def table(self) -> list[dict]:
        return _table(self.contacts)

    def to_dataset(self):
        return _dataset(self.contacts, SCREW_CONTACTS, {
            "case": self.case, "model": self.model, "friction_torque_Nm": self.friction_torque,
            "friction_torque_free_Nm": self.friction_torque_free, "friction_increase": self.friction_increase,
            "b2b_forces_N": list(self.b2b_forces)})


@dataclass(frozen=True)
class ContactLoads:
    """The loaded contacts of a case without a friction state: what a contact check needs (``contacts``, as in
    :class:`GuideResult`)."""

    contacts: tuple


def guide_contacts(case, contacts=None) -> ContactLoads:
    """The contact loads, angles and Hertz ellipses of a guide's balls (lin2017 eq 36 forces at the rigid angles,
    ``b2b.contacts``): lin2019's normal loads do not depend on friction, so they stand where its full-sliding model
    has no state."""
    if contacts is None:
        contacts = b2b.contacts(case)
    constant = hertz.hertz_constant(hertz.groove_geometry(case.guide))
    rows = []
    forces, angles = contacts.normal_forces, contacts.contact_angles
    a = contacts.semi_major
    b = a * contacts.b_over_a
    for ball in range(contacts.normal_forces.shape[0]):
        for i, name in enumerate(GUIDE_CONTACTS):
            f = float(forces[ball, i])
            rows.append(ContactLoad(ball + 1, name, f, float(angles[ball, i]), float(a[ball, i]), float(b[ball, i]),
                                    1.5 * f / (math.pi * float(a[ball, i]) * float(b[ball, i])),
                                    constant * f ** (2.0 / 3.0)))
    return ContactLoads(tuple(rows))


@dataclass(frozen=True)
class GuideStates:
    """The touching and free states of a guide's balls and the law that gave them: :data:`FULL_SLIDING`
    (``lowmodel.linear_bearing.b2b.solve``'s ``BallState``) or :data:`STICK_SLIP` (``b2b_rolling.solve``'s
    ``RollingB2BState`` on ``cells``); ``reason`` the full-sliding model's own words where it has no state."""

    touching: object
    free: object
    law: str
    reason: str = ""
    cells: tuple = ()

    @property
    def model(self) -> str:
        return "lowmodel.linear_bearing.b2b" if self.law == FULL_SLIDING else "lowmodel.linear_bearing.b2b_rolling"


def guide_states(case, contacts=None, *, cells=STICK_SLIP_CELLS) -> GuideStates:
    """The balls of a :class:`lowmodel.bearing.GuideLoadCase` touching (every pair in contact) and free (gaps
    of 1 mm): lin2019's full-sliding model (``b2b.solve``) where it has a state for both, else both by the
    stick/slip law on a half-space (``b2b_rolling.solve`` on Hertz contacts of ``cells``, from full slip on the
    cells or from rolling: ``start="auto"``, docs/b2b_rolling.md, "Where full sliding has no state"), with the same
    lin2017 eq 36 loads.  The stick/slip law holds in any state from full stick to full slip (full sliding is its
    limit), so it answers wherever the full-sliding solve finds no state, named (:func:`lowmodel.linear_bearing.b2b.
    no_full_sliding_state`) or not; ``reason`` keeps what the full-sliding solve said."""
    if contacts is None:
        contacts = b2b.contacts(case)
    touching_gaps, free_gaps = np.zeros(case.n_balls - 1), np.full(case.n_balls - 1, 1e-3)
    try:
        return GuideStates(b2b.solve(contacts, touching_gaps), b2b.solve(contacts, free_gaps), FULL_SLIDING)
    except ConvergenceError as error:  # no full-sliding state found: the stick/slip law, which holds in any state
        return guide_stick_slip_states(case, contacts, cells=cells, reason=_words(error))


def guide_stick_slip_states(case, contacts=None, *, cells=STICK_SLIP_CELLS, reason: str = "") -> GuideStates:
    """:func:`guide_states` by the stick/slip law alone (``b2b_rolling.solve(start="auto")`` on Hertz contacts of
    ``cells``, touching and with gaps of 1 mm), without trying full sliding first; ``reason``: why (kept on the
    result)."""
    from ballbench.lowmodel.linear_bearing import b2b_rolling

    if contacts is None:
        contacts = b2b.contacts(case)
    guide = case.guide
    balls = [b2b_rolling.hertz_contacts(contacts, j, cells=tuple(cells), guide=guide) for j in range(case.n_balls)]
    options = dict(ball_radius=guide.ball_radius, friction_coefficient=guide.friction_coefficient,
                   groove_velocity=guide.groove_velocity, start="auto")
    return GuideStates(b2b_rolling.solve(balls, gaps=np.zeros(case.n_balls - 1), **options),
                       b2b_rolling.solve(balls, gaps=np.full(case.n_balls - 1, 1e-3), **options), STICK_SLIP, reason,
                       tuple(cells))


def guide_result(case, touching=None, free=None, contacts=None, *, states: GuideStates | None = None) -> GuideResult:
    """:class:`GuideResult` of a :class:`lowmodel.bearing.GuideLoadCase` by the low-order numerical model (solved
    here, :func:`guide_states`, unless the states are given: ``contacts`` of ``b2b.contacts``, ``touching`` and
    ``free`` of ``b2b.solve``, or ``states`` of :func:`guide_states`)."""
    guide = case.guide
    if contacts is None:
        contacts = b2b.contacts(case)
    if states is None:
        if touching is None or free is None:
            states = guide_states(case, contacts)
        else:
            states = GuideStates(touching, free, FULL_SLIDING)
    touching, free = states.touching, states.free
    rows = guide_contacts(case, contacts).contacts
    speed = abs(guide.groove_velocity)
    return GuideResult(_name(case), states.model, tuple(rows),
                       tuple(float(x) for x in touching.b2b_force), free.input_power / speed,
                       touching.input_power / speed, float(free.input_power), float(touching.input_power),
                       tuple(float(x) for x in free.velocity_deviation), states.law, states.reason)


def screw_states(case, contacts=None):
    """(free balls, touching balls) of a :class:`lowmodel.bearing.ScrewLoadCase` by ``screw.b2b.solve`` at the
    case's axial load (``contacts``: default ``screw.b2b.contacts(case)``)."""
    if contacts is None:
        contacts = screw_b2b.contacts(case)
    free = screw_b2b.solve(contacts, case.axial_load, with_b2b=False)
    touching = screw_b2b.solve(contacts, case.axial_load)
    return free, touching


@dataclass(frozen=True)
class ScrewStates:
    """The touching and free states of a screw's balls and the law that gave them: :data:`FULL_SLIDING` (lin2019's
    model, ``screw.b2b.solve``) or :data:`STICK_SLIP` (``screw.b2b_rolling.solve`` on ``cells`` at the loads of the
    frictionless statics ``loads``, :class:`lowmodel.screw.preload.FrictionlessState`); ``reason`` lin2019's model's
    own words where it has no state."""

    touching: object
    free: object
    law: str
    reason: str = ""
    cells: tuple = ()
    loads: object = None

    @property
    def model(self) -> str:
        return "lowmodel.screw.b2b" if self.law == FULL_SLIDING else "lowmodel.screw.b2b_rolling"


def screw_law_states(case, contacts=None, *, cells=STICK_SLIP_CELLS) -> ScrewStates:
    """The balls of a :class:`lowmodel.bearing.ScrewLoadCase` touching and free: lin2019's four-point full-sliding
    model (:func:`screw_states`) where it has a state, else both by the stick/slip law on a half-space at the loads
    of the frictionless statics (``lowmodel.screw.preload.frictionless_statics``: contacts unload past the preload
    loss, two- or three-point contact) on Hertz contacts of ``cells`` (``screw.b2b_rolling.solve(...,
    start="auto")``; docs/b2b_rolling.md, "Where full sliding has no state").  Normal loads and friction are then
    decoupled, as in every stick/slip rung: the friction's axial force is not fed back into the loads."""
    if contacts is None:
        contacts = screw_b2b.contacts(case)
    try:
        free, touching = screw_states(case, contacts)
        return ScrewStates(touching, free, FULL_SLIDING)
    except ConvergenceError as error:  # no state of lin2019's model: the stick/slip law, which holds in any state
        return screw_stick_slip_states(case, contacts, cells=cells, reason=_words(error))


def screw_stick_slip_states(case, contacts=None, *, cells=STICK_SLIP_CELLS, reason: str = "") -> ScrewStates:
    """:func:`screw_law_states` by the stick/slip law alone at the frictionless statics' loads, without trying
    lin2019's model first; ``reason``: why (kept on the result)."""
    from ballbench.lowmodel.screw import b2b_rolling as screw_rolling

    if contacts is None:
        contacts = screw_b2b.contacts(case)
    loads = preload.frictionless_statics(contacts, case.axial_load)
    balls = [screw_rolling.hertz_contacts(loads, contacts, j, cells=tuple(cells)) for j in range(contacts.n_balls)]
    module = contacts.module
    return ScrewStates(screw_rolling.solve(balls, module, start="auto"),
                       screw_rolling.solve(balls, module, with_b2b=False, start="auto"), STICK_SLIP, reason,
                       tuple(cells), loads)


def screw_result(case, touching=None, free=None, contacts=None, *, states: ScrewStates | None = None) -> ScrewResult:
    """:class:`ScrewResult` of a :class:`lowmodel.bearing.ScrewLoadCase` by the low-order numerical model (solved
    here, :func:`screw_law_states`, unless the states are given: as :func:`screw_states` returns them, or
    ``states``)."""
    if contacts is None:
        contacts = screw_b2b.contacts(case)
    if states is None:
        states = (ScrewStates(touching, free, FULL_SLIDING) if touching is not None and free is not None
                  else screw_law_states(case, contacts))
    if states.law != FULL_SLIDING:
        return _stick_slip_screw_result(case, contacts, states)
    touching, free = states.touching, states.free
    a = touching.semi_major
    rows = _screw_rows(touching.normal_force, touching.contact_angle, a, a * contacts.b_over_a, touching.approach)
    speed = abs(case.screw.nut_speed)
    shares = axial_shares(contacts, touching)
    return ScrewResult(_name(case), "lowmodel.screw.b2b", tuple(rows), tuple(float(x) for x in touching.b2b_force),
                       free.input_power / speed, touching.input_power / speed, float(free.input_power),
                       float(touching.input_power), tuple(float(x) for x in shares))


def _stick_slip_screw_result(case, contacts, states: ScrewStates) -> ScrewResult:
    loads = states.loads
    a = contacts.semi_major_unit * np.cbrt(loads.normal_force)
    rows = _screw_rows(loads.normal_force, loads.contact_angle, a, a * contacts.b_over_a, loads.approach)
    speed = abs(case.screw.nut_speed)
    touching, free = states.touching, states.free
    shares = axial_shares(contacts, stick_slip_forces(loads, touching))
    return ScrewResult(_name(case), states.model, tuple(rows), tuple(float(x) for x in touching.b2b_force),
                       free.input_power / speed, touching.input_power / speed, float(free.input_power),
                       float(touching.input_power), tuple(float(x) for x in shares), states.law, states.reason)


def stick_slip_forces(loads, state, friction: bool = True):
    """The contact forces of a stick/slip screw ``state`` on the frictionless ``loads`` in the form
    :func:`axial_shares` reads: normal forces and loaded contact angles (n, 4), friction forces (n, 4, 3) on the
    ball in CS3 (zero with ``friction=False``: the normal loads alone)."""
    friction_force = np.zeros(loads.normal_force.shape + (3,))
    if friction:
        for ball, row in enumerate(state.contacts):
            for summary in row:
                friction_force[ball, SCREW_CONTACTS.index(summary.name)] = summary.force
    return SimpleNamespace(normal_force=loads.normal_force, contact_angle=loads.contact_angle,
                           friction_force=friction_force)


def axial_shares(contacts, state) -> np.ndarray:
    """(n,) N: each ball's axial load, the force of its screw contacts (SL, SR: normal + friction) along the screw
    axis ``z_hat`` (lin2019 eqs 37, 42, 55), of a ``screw.b2b.solve`` ``state`` on ``contacts``."""
    alpha = contacts.module.lead_angle
    z_hat = np.array([0.0, math.sin(alpha), math.cos(alpha)])
    angles = state.contact_angle
    sign_u, sign_w = np.array([-1.0, -1.0]), np.array([-1.0, 1.0])
    e = np.stack([sign_u * np.cos(angles[:, :2]), np.zeros_like(angles[:, :2]), sign_w * np.sin(angles[:, :2])],
                 axis=-1)  # (n, 2, 3) CS3, ball centre -> contact (eq 37)
    normal = -state.normal_force[:, :2, None] * e
    return ((normal + state.friction_force[:, :2]) @ z_hat).sum(axis=1)


def screw_frictionless_contacts(case) -> tuple[ContactLoad, ...]:
    """The contacts of a :class:`lowmodel.bearing.ScrewLoadCase`'s balls by the frictionless statics at the case's
    axial load (lowmodel.screw.preload.frictionless_statics: exact flank arcs, Hertz's law lin2019 eq 53, contacts
    unload; below or past the preload loss), not lin2019's friction model: per ball and contact the normal force, the
    actual contact angle (eq 37), the Hertz semi-axes and maximum pressure of the same Hertz solution as the statics'
    ``C_i`` (at the flank's contact angle, lowmodel.screw.contacts) and the approach (not positive: the contact is
    open)."""
    contacts = screw_b2b.contacts(case)
    state = preload.frictionless_statics(contacts, case.axial_load)
    a = contacts.semi_major_unit * np.cbrt(state.normal_force)
    return tuple(_screw_rows(state.normal_force, state.contact_angle, a, a * contacts.b_over_a, state.approach))


def _words(error: ConvergenceError) -> str:
    """What a failed full-sliding solve said: its message without the numbers, and its reason where the message
    does not hold it."""
    message = str(error).split(" (residual")[0]
    reason = getattr(error, "reason", "") or ""
    return message if not reason or reason in message else f"{message}: {reason}"


def _name(case) -> str:
    """The name a result carries: the case's own (a validation case has one), else its kind."""
    return getattr(case, "name", None) or type(case).__name__


def _screw_rows(forces, angles, a, b, approaches) -> list[ContactLoad]:
    """ContactLoad rows (SL, SR, NR, NL of each ball) of (n, 4) normal forces [N], contact angles [rad], semi-axes
    a, b [m] and approaches [m]; p0 = 1.5 F / (pi a b) (Hertz), 0 where the contact carries no load."""
    rows = []
    for ball in range(forces.shape[0]):
        for i, name in enumerate(SCREW_CONTACTS):
            f = float(forces[ball, i])
            area = math.pi * float(a[ball, i]) * float(b[ball, i])
            rows.append(ContactLoad(ball + 1, name, f, float(angles[ball, i]), float(a[ball, i]), float(b[ball, i]),
                                    1.5 * f / area if f > 0 else 0.0, float(approaches[ball, i])))
    return rows


# --------------------------------------------------------------------------
# the front door
# --------------------------------------------------------------------------
def friction(case) -> GuideResult | ScrewResult:
    """What an engineer reads of a linear guide or ball screw load case (:class:`lowmodel.bearing.GuideLoadCase`,
    :class:`lowmodel.bearing.ScrewLoadCase`, or a case file's case, which is one): per ball and contact the loads,
    angles, Hertz ellipses and pressures; the carriage friction force [N] (:class:`GuideResult`) or the friction
    torque on the nut [N m] (:class:`ScrewResult`) with and without ball-to-ball contact, the friction increase and
    the B2B forces, by the low-order numerical models (``.to_dataset()`` gives xarray): lin2019's full sliding, or the
    stick/slip law where that has no state (``.law``)."""
    if isinstance(case, GuideLoadCase):
        return guide_result(case)
    if isinstance(case, ScrewLoadCase):
        return screw_result(case)
    raise TypeError(f"friction takes a GuideLoadCase or ScrewLoadCase (lowmodel.bearing; a case file's "
                    f"LinearGuideCase or BallScrewCase is one), got {type(case).__name__}")


def most_loaded(case, result: GuideResult | ScrewResult | None = None, *,
                pair: str | None = None) -> tuple[ContactLoad, ContactLoadCase]:
    """The most loaded contact of a guide or screw load case: its row of the low-order touching state (``result``:
    :func:`friction`'s, computed when None) and that contact as a :class:`lowmodel.bearing.ContactLoadCase` at its
    normal force (a guide's groove; a screw's screw or nut flank).  ``pair`` (a screw): ``"screw"`` or ``"nut"``,
    the most loaded contact of that side."""
    result = result or friction(case)
    rows = result.contacts
    if pair is not None:
        if not isinstance(case, ScrewLoadCase):
            raise ValueError(f"pair selects a side of a ball screw's contacts, not of a {type(case).__name__}")
        rows = [c for c in rows if c.contact.startswith(pair[0].upper())]
    worst = max(rows, key=lambda c: c.normal_force)
    if isinstance(case, GuideLoadCase):
        return worst, case.guide.contact(worst.normal_force)
    side = "screw" if worst.contact.startswith("S") else "nut"
    return worst, case.screw.contact(side, worst.normal_force)


def contact(case) -> hertz.HertzContact:
    """Exact Hertz (``lowmodel.contact.hertz.HertzContact``: a, b, p0, approach in SI) of a
    :class:`lowmodel.bearing.ContactLoadCase`, or of the most loaded contact (:func:`most_loaded`) of a linear guide
    or ball screw load case."""
    if not isinstance(case, ContactLoadCase):
        if not isinstance(case, (GuideLoadCase, ScrewLoadCase)):
            raise TypeError(f"contact takes a ContactLoadCase, GuideLoadCase or ScrewLoadCase (lowmodel.bearing), "
                            f"got {type(case).__name__}")
        case = most_loaded(case)[1]
    return hertz.solve_load(hertz.pair_geometry(case), case.force)
