"""The friction of a whole carriage's rows, at one travel and over a travel of a ball pitch (docs/carriage.md).

At a solved state of the rigid carriage (:func:`lowmodel.linear_bearing.carriage.solve`) each gothic-arch row's
balls are lin2019's four-point balls at the state's contact loads and Hertz ellipses (:func:`row_contacts`),
touching in a chain (lin2019 eqs 4-10, ``b2b.solve``); where full sliding has no state, the stick/slip law on a
half-space (``b2b_rolling.solve(start="auto")``, docs/b2b_rolling.md).  The carriage's friction force is the drive
power over every row's balls over the speed, ``F = P_in / |v|`` (lin2019's power balance).

A ball with one to three open contacts (in the end relief, or under a load past its preload: two- or three-point)
takes the stick/slip law on its loaded contacts alone (lowmodel.linear_bearing.b2b_rolling.loaded_contacts), in a
chain with its neighbours of as many loaded contacts: the law's balls share their number of contacts, so the row's
chain parts where it changes (the B2B force across is not counted; ``RowFriction.parted``).

A chain that has a state by neither law (a ball near the opening of a contact: its spin-capacity ratio far below 1,
the coupled stick/slip Newton stalls) is parted at its weakest ball (the least ratio of its smallest to its largest
contact load): that ball is solved alone (no B2B force on it) and both sides again as chains; a side without a state
either goes ball by ball (a failed chain costs tens of seconds: at most three of them a run).  Such
balls' laws end in ``", alone"`` and the result is then not the coupled chain's (``CarriageFriction.complete``
False).

Over travel (:func:`friction_over_travel`): the balls advance against the carriage
(:func:`lowmodel.linear_bearing.carriage.ball_positions`: a ball leaving the groove at one end enters it at the
other), the carriage is solved again at each step and its rows' friction follows: the drive force's ripple over one
ball pitch, with B2B contact and with every ball alone (the friction without ball-to-ball contact).  Each step's
stick/slip solves start from the step before's states of the same balls (``friction(warm=...)``,
b2b_rolling.solve's ``warm``: a ball alone from there first, a chain after its full-slip start).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import carriage

__all__ = ["RowFriction", "CarriageFriction", "TravelFriction", "row_contacts", "ball_frame", "friction",
           "friction_over_travel", "LAWS"]

LAWS = ("full sliding", "stick/slip on a half-space")  # the friction laws of a ball, tried in this order


@dataclass(frozen=True)
class RowFriction:
    """The friction of one row's balls at the carriage's loads (:func:`friction`): ``force`` [N] the carriage's drive
    force over the row (``P_in / |v|``), per ball ``law`` (one of :data:`LAWS`, with ``", alone"`` when the ball was
    solved without B2B contact because its chain had no state; ``"loose"``: every contact open, no load and no
    friction; ``""``: no model, a ball without a state by either law), ``b2b_forces`` [N] (balls j, j+1; 0 across a
    ball solved alone or without a model and where the chain parts), ``reason`` (what a law's fallback or a missing
    model says; "" when every ball has one), ``parted`` whether touching loaded balls were solved in separate chains
    (a chain without a state parted, or the number of loaded contacts changing along the row)."""

    force: float
    law: tuple
    b2b_forces: np.ndarray
    reason: str = ""
    parted: bool = False


@dataclass(frozen=True)
class CarriageFriction:
    """The friction of the carriage's rows (:func:`friction`): ``force`` [N] their sum, ``rows`` one
    :class:`RowFriction` each; ``complete`` whether every ball of every row has a model and every row's touching
    balls were solved as one chain (with ``b2b=False``: every ball has a model); ``states`` the stick/slip states of its
    chains (the warm start of the next step over travel)."""

    force: float
    rows: tuple
    b2b: bool = True
    states: dict = field(default_factory=dict, compare=False, repr=False)  # (row, balls) -> stick/slip chain state

    @property
    def complete(self) -> bool:
        return all(law for row in self.rows for law in row.law) and (
            not self.b2b or not any(row.parted for row in self.rows))


@dataclass(frozen=True)
class TravelFriction:
    """The carriage's friction over travel (:func:`friction_over_travel`), shapes (steps,) unless said:
    ``travel`` [m] of the balls against the carriage; ``force`` [N] with B2B contact; ``force_alone`` [N] every ball
    alone (no B2B contact; None when not asked); ``complete`` (with B2B) per step; ``displacement`` (steps, 5) the
    carriage's (:data:`carriage.DISPLACEMENT_NAMES`); ``largest_load`` [N] the most loaded contact; ``frictions``
    the :class:`CarriageFriction` of each step (with B2B)."""

    travel: np.ndarray
    force: np.ndarray
    force_alone: np.ndarray | None
    complete: np.ndarray
    displacement: np.ndarray
    largest_load: np.ndarray
    frictions: tuple

    def __post_init__(self):
        checks.freeze_arrays(self, "travel", "force", "complete", "displacement", "largest_load")
        if self.force_alone is not None:
            checks.freeze_arrays(self, "force_alone")

    @property
    def mean(self) -> float:
        """N, the mean drive force over the travel (with B2B)."""
        return float(np.mean(self.force))

    @property
    def parted(self) -> np.ndarray:
        """(steps,) bool: a chain without a state parted at the step (a ball solved alone, module docstring)."""
        return np.array([any(row.parted for row in f.rows) for f in self.frictions])

    @property
    def ripple(self) -> float:
        """N, the drive force's peak-to-peak over the travel (with B2B)."""
        return float(np.ptp(self.force))


def row_contacts(body: carriage.Carriage, state: carriage.CarriageState, row: int, balls=None):
    """Balls ``balls`` (default all; ascending, ball 0 behind along +z) of gothic-arch row ``row`` as lin2019's
    :class:`~lowmodel.linear_bearing.contacts.BallContacts`: its rigid contact angles, the carriage state's contact
    forces and Hertz ellipses, the guide's ball radius, friction and speed.  ValueError for a two-point row or a
    ball with an open contact (lin2019's four-point model needs four loaded contacts)."""
    from ballbench.lowmodel.linear_bearing.contacts import contacts_from_forces  # lin2019's model: only when asked

    shape = body.rows[checks.count("row", row, 0, len(body.rows) - 1)]
    if shape.contact_angles is None:
        raise ValueError(f"row {row}: not a gothic-arch row of lin2019's four-point balls (carriage.gothic_rows): "
                         "lin2019's friction model does not describe its balls")
    index = np.arange(body.balls_per_row) if balls is None else np.asarray(balls, dtype=int)
    forces = state.normal_force[row][index]
    if np.any(forces <= 0.0):
        raise ValueError(f"row {row}: balls {sorted({int(index[k]) + 1 for k in np.argwhere(forces <= 0)[:, 0]})} "
                         "have an open contact: lin2019's four-point friction model needs all four loaded")
    guide = body.guide
    return contacts_from_forces(np.tile(shape.contact_angles, (len(index), 1)), forces, state.a[row][index],
                                state.b[row][index] / state.a[row][index], ball_radius=guide.ball_radius,
                                friction_coefficient=guide.friction_coefficient,
                                groove_velocity=guide.groove_velocity)


def _solve(body, state, row: int, run: list, cells, warm=None) -> tuple:
    """``(state, law)`` of the balls ``run`` of ``row`` touching in a chain (one ball: alone) by the first law of
    :data:`LAWS` that has a state (balls with an open contact: the stick/slip law on their loaded contacts alone);
    ConvergenceError from the last law when none has (its message says both); ``warm`` a stick/slip state of the
    same balls (lowmodel.linear_bearing.b2b_rolling.solve's)."""
    from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling  # the friction models: only when asked

    guide = body.guide
    gaps = np.zeros(len(run) - 1)
    four_point = _gothic(body, row) and bool(np.all(state.normal_force[row][run] > 0.0))
    sliding = "lin2019's full sliding is four-point"
    if four_point:
        contacts = row_contacts(body, state, row, run)
        try:
            return b2b.solve(contacts, gaps), LAWS[0]
        except ConvergenceError as error:
            sliding = str(error).split(" (residual")[0]
    balls = [b2b_rolling.loaded_contacts(*ball_frame(body, state, row, k), ball_radius=guide.ball_radius,
                                         cells=tuple(cells), guide=guide) for k in run]
    try:
        chain = b2b_rolling.solve(balls, ball_radius=guide.ball_radius, friction_coefficient=guide.friction_coefficient,
                                  groove_velocity=guide.groove_velocity, gaps=gaps, start="auto", warm=warm)
    except ConvergenceError as error:
        raise ConvergenceError(f"full sliding: {sliding}; stick/slip: {error}", residual=error.residual,
                               iterations=error.iterations, tolerance=error.tolerance,
                               reason="no state by either law") from None
    return chain, LAWS[1]


def _gothic(body: carriage.Carriage, row: int) -> bool:
    return body.rows[row].contact_angles is not None


def ball_frame(body: carriage.Carriage, state: carriage.CarriageState, row: int, ball: int) -> tuple:
    """Ball ``ball`` of ``row`` in lin2019's frame (lowmodel.geometry.fourpoint: contacts (BL, BR, TR, TL), the
    bottom groove at rest, the top one moving): ``(contact_angles, normal_forces, semi_major, b_over_a)``, each (4,),
    a contact that is not there or open with zero force.  A gothic-arch row as it is; a two-point row's rail contact
    at the bottom, its carriage contact on the opposite diagonal, the angle of its load line from the vertical; a
    row whose rail lies above its balls (a four-row carriage's lower rows) mirrored top to bottom (friction and power
    do not change under a mirror; the carriage's groove is then the top one, as in lin2019)."""
    shape = body.rows[row]
    force, a, b = state.normal_force[row, ball], state.a[row, ball], state.b[row, ball]
    ratio = b / np.where(a > 0.0, a, 1.0)
    if shape.contact_angles is not None:
        return shape.contact_angles, force, a, ratio
    rail, top = shape.carriage.index(False), shape.carriage.index(True)
    n_x, n_y = shape.normals[rail]
    bottom = 0 if n_x < 0.0 else 1  # BL or BR; the carriage's contact across the ball: TR or TL
    out = [np.zeros(4) for _ in range(3)]
    for values, source in zip(out, (force, a, ratio)):
        values[bottom], values[2 + bottom] = source[rail], source[top]
    return (math.atan2(abs(n_x), abs(n_y)),) * 4, *out


def _weakest(state, row: int, run: list) -> int:
    """The position in ``run`` of its ball with the least ratio of smallest to largest contact load."""
    forces = state.normal_force[row][run]
    return int(np.argmin(forces.min(axis=1) / forces.max(axis=1)))


def _chain(body, state, row: int, run: list, cells, coupled: bool, out: dict, parted: bool = False) -> float:
    """The drive force [N] of the balls ``run`` of ``row``: touching in one chain (``coupled``) or each alone; a chain
    without a state is parted at its weakest ball, and a part of it (``parted``) that has none either goes ball by
    ball (module docstring).  Writes each ball's law, the B2B forces and the reasons into ``out``."""
    speed = abs(body.guide.groove_velocity)
    if not coupled and len(run) > 1:
        return sum(_chain(body, state, row, [k], cells, True, out) for k in run)
    key = (row, tuple(run))
    try:
        chain, law = _solve(body, state, row, run, cells, out["warm"].get(key))
    except ConvergenceError as error:
        if len(run) == 1:
            out["laws"][run[0]] = ""
            out["reasons"].append(f"ball {run[0] + 1}: no state by either law ({str(error).split(' (residual')[0]})")
            return 0.0
        out["parted"] = True
        alone = list(run) if parted else [run[_weakest(state, row, run)]]
        out["reasons"].append(f"balls {run[0] + 1}-{run[-1] + 1}: no state by either law as one chain; "
                              + ("each ball solved alone (a part of a parted chain)" if parted else
                                 f"ball {alone[0] + 1} (its least contact load the smallest share) solved alone"))
        force = 0.0
        for k in alone:
            force += _chain(body, state, row, [k], cells, True, out)
            if out["laws"][k]:
                out["laws"][k] += ", alone"
        if parted:
            return force
        weak = run.index(alone[0])
        parts = [run[:weak], run[weak + 1:]]
        return force + sum(_chain(body, state, row, part, cells, True, out, True) for part in parts if part)
    four_point = _gothic(body, row) and bool(np.all(state.normal_force[row][run] > 0.0))  # else full sliding not tried
    if law != LAWS[0] and four_point:
        out["reasons"].append(f"{'balls' if len(run) > 1 else 'ball'} {run[0] + 1}"
                              f"{f'-{run[-1] + 1}' if len(run) > 1 else ''}: full sliding found no state, {law}")
    out["b2b"][run[0]:run[-1]] = chain.b2b_force
    if law == LAWS[1]:
        out["states"][key] = chain
    for k in run:
        out["laws"][k] = law
    return chain.input_power / speed


def friction(body: carriage.Carriage, state: carriage.CarriageState, *, cells=(12, 48),
             b2b: bool = True, warm: CarriageFriction | None = None) -> CarriageFriction:
    """The carriage's friction force at ``state`` (:func:`lowmodel.linear_bearing.carriage.solve`): in each
    gothic-arch row every run of neighbouring balls with four loaded contacts touching in a chain (``b2b``; else
    every ball alone, the friction without ball-to-ball contact) by the laws of :data:`LAWS` (stick/slip on
    ``cells`` = (along, across) cells per contact), a chain without a state parted at its weakest ball (module
    docstring).  A loose ball (every contact open) carries neither load nor friction and parts the chain; a ball with
    one to three open contacts (two- or three-point) takes the stick/slip law on its loaded contacts, in a chain
    with its neighbours of as many loaded contacts (the law's balls share a number of contacts: the chain parts
    where it changes, ``RowFriction.parted``).  A two-point row's balls (a four-row carriage's) take the stick/slip
    law on their two contacts, in lin2019's frame by :func:`ball_frame`.  ``warm`` the
    friction of a nearby state (the step before over travel, with as many ``cells``): its chains' stick/slip states
    start the same chains' solves."""
    if not isinstance(body, carriage.Carriage) or not isinstance(state, carriage.CarriageState):
        raise ValueError("friction needs a carriage.Carriage and its carriage.CarriageState (carriage.solve)")
    n = body.balls_per_row
    rows, states = [], {}
    previous = {} if warm is None or warm.b2b != b2b else warm.states
    for r, shape in enumerate(body.rows):
        count = np.sum(state.normal_force[r] > 0.0, axis=1)  # loaded contacts of each ball
        out = dict(laws=["loose" if count[k] == 0 else "" for k in range(n)], b2b=np.zeros(max(n - 1, 0)), reasons=[],
                   parted=False, warm=previous, states=states)
        runs = []
        for k in range(n):
            if count[k] == 0:
                continue
            if runs and runs[-1][-1] == k - 1 and count[runs[-1][-1]] == count[k]:
                runs[-1].append(k)
            else:
                runs.append([k])
        force = sum(_chain(body, state, r, run, cells, b2b, out) for run in runs)
        partial = [k + 1 for k in range(n) if 0 < count[k] < len(shape.normals)]
        by_count = any(b[0] == a[-1] + 1 for a, b in zip(runs, runs[1:]))
        if partial:
            out["reasons"].append(f"balls {partial}: one to three open contacts, by the stick/slip law on their loaded "
                                  "contacts" + ("; the chain parts where the number of loaded contacts changes"
                                                if by_count else ""))
        out["parted"] |= by_count
        rows.append(RowFriction(float(force), tuple(out["laws"]), out["b2b"], "; ".join(out["reasons"]),
                                out["parted"]))
    return CarriageFriction(float(sum(r.force for r in rows)), tuple(rows), bool(b2b), states)


def friction_over_travel(body: carriage.Carriage, load: carriage.Load, *, steps: int = 20, span: float | None = None,
                         cells=(12, 48), alone: bool = True, loop=None,
                         at_rest: CarriageFriction | None = None) -> TravelFriction:
    """The carriage's friction force over a travel ``span`` [m] (default one ball ``pitch``) of its balls in ``steps``
    equal steps (the end left out: at one pitch the balls sit as at the start): at each the carriage solved under
    ``load`` (:func:`lowmodel.linear_bearing.carriage.solve`) and its rows' :func:`friction` with B2B contact and,
    with ``alone``, with every ball alone.  ``loop(travels)`` wraps the loop over the steps' travels (a progress
    bar; default none); ``at_rest`` the :func:`friction` (with B2B contact, on ``cells``) of the carriage under
    ``load`` at travel 0, where the caller has it already."""
    checks.count("steps", steps, 1, 10_000)
    span = body.pitch if span is None else checks.positive("span", span, "m")
    travel = np.arange(steps) * (span / steps)
    force, force_alone, complete, displacement, largest, frictions = [], [], [], [], [], []
    result = alone_result = None
    for t in (travel if loop is None else loop(travel)):
        state = carriage.solve(body, load, travel=float(t))
        result = at_rest if at_rest is not None and t == 0.0 else friction(body, state, cells=cells, warm=result)
        frictions.append(result)
        force.append(result.force)
        complete.append(result.complete)
        displacement.append(state.displacement)
        largest.append(float(state.normal_force.max()))
        if alone:
            alone_result = friction(body, state, cells=cells, b2b=False, warm=alone_result)
            force_alone.append(alone_result.force)
    return TravelFriction(travel, np.array(force), np.array(force_alone) if alone else None, np.array(complete),
                          np.array(displacement), np.array(largest), tuple(frictions))
