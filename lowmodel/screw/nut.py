"""The whole nut of a ball screw: its balls' axial loads, its axial stiffness, a double nut's preload and lift-off,
and the friction torque over rotation (docs/nut.md).

A nut (:class:`Nut`) holds ``balls`` balls in ``turns`` loaded turns of the case's screw (:class:`ScrewModule`), spread
evenly over the turns (:func:`positions`; as lin2019 Sec 3.4's track).  Two arrangements:

* ``"single"``: one nut preloaded by the ball oversize of the module (lin2019 eq 53; four-point balls).  The axial
  load spreads over the balls by :func:`lowmodel.screw.load_distribution.distribute` (each ball's shift ``U(q)``
  from the frictionless statics of a nominal ball, below and past the preload loss, or lin2019's single-ball model
  with friction, :func:`ball_table`; screw and nut as bars, the nut held at its flange at the loaded end; or the
  nut as an elastic body, fem.nut_fe); the nut's shift at its flange ``|u_0|``,
  ``u_0 = U(q_1) + F_a z_1 / (E A_s) + (G q)_1`` (the first ball at ``z_1``, the screw carrying ``F_a`` up to it;
  ``G`` the nut's compliance, lowmodel.screw.load_distribution.nut_bar_compliance: held at the loaded end
  ``(G q)_1 = F_a z_1 / (E A_n)``, at the far end the nut's stretch from the first ball to its flange; the table's
  sign).  The
  friction torque over rotation is lin2019 Sec 3.4's whole-screw simulation over the nut's turns
  (:func:`lowmodel.screw.whole_screw.simulate`: its own distribution by lin2019's ball with friction; below the
  preload loss).
* ``"double"``: two halves of ``balls`` balls each, pressed apart by a spacer with the preload force ``F_pr``
  (``preload``); every ball is a two-point ball without oversize (half A on the diagonal SL-NR, half B on SR-NL),
  its axial law ``q = Q(u)`` the frictionless statics of one nominal ball (:func:`lowmodel.screw.preload.
  frictionless_statics`, the exact flank arcs and eq 53's Hertz law) or, ``law="hertz"``, Hertz's law along the
  nominal diagonal, ``u = (C_S + C_N) (q / (sin beta_0 cos alpha))^(2/3) / (sin beta_0 cos alpha)`` (the approaches
  of the diagonal's two contacts add; preload.py's closed form).  The balls of a half share its load equally
  (rigid bars within the nut).  Preloaded, both halves sit at ``u_pr = U(F_pr / n)``; an axial load ``F_a`` on the
  screw moves it by ``u``: half A approaches, B recedes,

      F_a = n (Q(u_pr + u) - Q(u_pr - u)),     Q(u <= 0) = 0,

  until half B lifts off at ``u = u_pr``: ``F_lift = n Q(2 u_pr)``, for Hertz's law ``2^(3/2) F_pr`` (the check
  of the solve).  Friction of a double nut: its balls are two-point, lin2019's friction model is four-point: no
  model yet.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import preload, whole_screw

__all__ = ["Nut", "NutLoads", "DoubleNutState", "ARRANGEMENTS", "LAWS", "DISTRIBUTION_LAWS", "capacity", "positions",
           "ball_table", "distribution", "ball_law", "double_nut", "lift_off", "friction_over_rotation",
           "BALANCE_TOLERANCE", "BALANCE_TOLERANCE_SINGLE"]

ARRANGEMENTS = ("single", "double")
LAWS = ("exact", "hertz")  # a double nut's two-point ball: the exact frictionless statics, or Hertz on the diagonal
BALANCE_TOLERANCE = 1e-10  # the axial balance of a double nut's halves, relative to the load
# a single nut's balls against its load, relative: load_distribution.distribute iterates its loads to 1e-10 of the
# load and finds the nut's shift to Brent's tolerance, which leaves the sum within a few 1e-10 of it
BALANCE_TOLERANCE_SINGLE = 1e-8
DISTRIBUTION_LAWS = ("frictionless", "lin2019")  # a single nut's ball law in the load distribution


def capacity(module: screw_contacts.ScrewModule, turns: int) -> int:
    """The most balls that fit in ``turns`` loaded turns: the helix azimuth of the turns over the azimuth of two
    touching balls (lowmodel.screw.b2b.pair_geometry)."""
    turns = checks.count("turns", turns, 1, 1000)
    return int(2.0 * math.pi * turns / b2b.pair_geometry(module).azimuth_step)


@dataclass(frozen=True)
class Nut:
    """A whole nut (module docstring): ``module`` the screw's (lowmodel.screw.contacts.module), ``turns`` loaded
    turns (of each half for a double nut), ``balls`` in them (default: :func:`capacity` less one, a gap in the
    track), ``arrangement`` one of :data:`ARRANGEMENTS`, ``preload`` [N] the spacer force of a double nut (0 for a
    single nut: its preload is the module's oversize), ``nut_outer_radius`` [m] of the nut as a bar (default
    lowmodel.screw.load_distribution.bar_sections'), ``flange`` where the nut is held (one of
    lowmodel.screw.load_distribution.FLANGES: at the loaded end, the screw in tension and the nut in compression, or
    at the far end, both in tension)."""

    module: screw_contacts.ScrewModule
    turns: int = 2
    balls: int = 0
    arrangement: str = "single"
    preload: float = 0.0
    nut_outer_radius: float | None = None
    flange: str = "loaded end"

    def __post_init__(self):
        if not isinstance(self.module, screw_contacts.ScrewModule):
            raise ValueError(f"module must be a lowmodel.screw.contacts.ScrewModule, got {type(self.module).__name__}")
        most = capacity(self.module, self.turns)
        object.__setattr__(self, "balls", checks.count("balls", most - 1 if self.balls == 0 else self.balls, 2,
                                                       most))
        checks.choice("arrangement", self.arrangement, ARRANGEMENTS)
        checks.choice("flange", self.flange, ld.FLANGES)
        checks.non_negative("preload", self.preload, "N")
        if self.arrangement == "double" and self.preload == 0.0:
            raise ValueError("preload: a double nut needs its preload force > 0 N (the spacer's)")
        if self.arrangement == "single" and self.preload != 0.0:
            raise ValueError(f"preload {self.preload!r} N: a single nut is preloaded by the ball oversize (the "
                             "screw's oversize), not by a force; arrangement = 'double' for a spacer's preload")

    @property
    def sections(self) -> ld.BarSections:
        return ld.bar_sections(self.module, nut_outer_radius=self.nut_outer_radius)


def positions(nut: Nut) -> np.ndarray:
    """(balls,) rad, each ball's azimuth in the nut from its loaded end: evenly spread over the turns, the gaps
    equal and half a gap before the first (lowmodel.screw.whole_screw.simulate's start)."""
    step = b2b.pair_geometry(nut.module).azimuth_step
    gap = (2.0 * math.pi * nut.turns - nut.balls * step) / nut.balls
    return 0.5 * gap + np.arange(nut.balls) * (gap + step)


@dataclass(frozen=True)
class NutLoads:
    """A single nut under an axial load (:func:`distribution`): ``axial_load`` [N]; ``positions`` (n,) rad;
    ``z`` (n,) m along the nut; ``ball_loads`` (n,) N; ``shift`` [m] the nut's axial shift against the screw at its
    loaded end (magnitude, from the preloaded state); ``balance`` the loads' sum against the axial load, relative."""

    axial_load: float
    positions: np.ndarray
    z: np.ndarray
    ball_loads: np.ndarray
    shift: float
    balance: float = 0.0

    def __post_init__(self):
        checks.freeze_arrays(self, "positions", "z", "ball_loads")


def ball_table(module: screw_contacts.ScrewModule, max_load: float, law: str = "frictionless",
               points: int = 25) -> ld.AxialStiffness:
    """The shift ``U(q)`` of one nominal ball of ``module`` (its oversize) against its axial load, tabulated up to
    ``max_load`` [N]: ``law`` one of :data:`DISTRIBUTION_LAWS`: ``"frictionless"`` the frictionless statics
    (lowmodel.screw.preload.frictionless_statics: exact flank arcs, below and past the preload loss, ``points``
    loads spaced as ``q ~ u^(3/2)``), ``"lin2019"`` the single-ball model with friction (as the whole screw,
    lowmodel.screw.load_distribution.axial_stiffness; below the preload loss only)."""
    checks.choice("law", law, DISTRIBUTION_LAWS)
    max_load = checks.positive("max_load", max_load, "N")
    if law == "lin2019":
        return ld.axial_stiffness(module, max_load)
    loads = max_load * np.linspace(0.0, 1.0, checks.count("points", points, 4)) ** 1.5
    contacts = screw_contacts.ball_contacts(module, 0.0)
    return ld.AxialStiffness(loads, np.array([preload.frictionless_statics(contacts, float(q)).nut_shift
                                              for q in loads]))


def distribution(nut: Nut, axial_load: float, stiffness: ld.AxialStiffness | None = None, *,
                 law: str = "frictionless", nut_compliance=None) -> NutLoads:
    """The axial load of each ball of a single nut under ``axial_load`` [N] on the screw (module docstring);
    ``stiffness`` the ball's ``U(q)`` table (default :func:`ball_table` of ``law`` up to three times the mean ball
    load); ``nut_compliance`` (n, n) [m/N] an elastic nut's in place of the nut bar (fem.nut_fe, held at its
    ``flange``).  The loads sum to the axial load (checked, :data:`BALANCE_TOLERANCE_SINGLE`)."""
    if nut.arrangement != "single":
        raise ValueError("distribution: a single nut's (arrangement 'single'); a double nut: double_nut")
    total = checks.non_negative("axial_load", axial_load, "N")
    module, psi = nut.module, positions(nut)
    if stiffness is None:
        stiffness = ball_table(module, 3.0 * max(total, 1.0) / nut.balls, law)
    loads = ld.distribute(psi, total, stiffness, nut.sections, module.lead, module.youngs_modulus,
                          flange=nut.flange, nut_compliance=nut_compliance)
    balance = abs(float(loads.sum()) - total) / total if total > 0.0 else 0.0
    if not balance <= BALANCE_TOLERANCE_SINGLE:
        raise ConvergenceError("nut.distribution: the balls' loads do not sum to the axial load", residual=balance,
                               iterations=1, tolerance=BALANCE_TOLERANCE_SINGLE, reason="axial load balance")
    z = module.lead * psi / (2.0 * math.pi)
    first = int(np.argmin(z))
    sign = 1.0 if stiffness.shifts[-1] > stiffness.shifts[0] else -1.0  # the table's direction (distribute's)
    if nut_compliance is None:   # the nut bar: its groove's moves towards the flange
        nut_compliance = ld.nut_bar_compliance(z, nut.sections.nut_area, module.youngs_modulus, nut.flange)
    # the screw from its loaded section (z = 0) to the first ball, the nut from that ball's groove to its flange
    bars = total * z[first] / (module.youngs_modulus * nut.sections.screw_area) + float(
        np.asarray(nut_compliance)[first] @ loads)
    shift = float(stiffness.shift(float(loads[first]))) + sign * bars
    return NutLoads(total, psi, z, loads, abs(shift), balance)


@dataclass(frozen=True)
class BallLaw:
    """A two-point ball's axial law: ``shift(q)`` [m] of its axial load ``q`` [N] and the inverse ``load(u)``
    (0 for ``u <= 0``)."""

    shift: object
    load: object
    name: str


def ball_law(module: screw_contacts.ScrewModule, law: str = "exact", max_load: float = 0.0,
             points: int = 41) -> BallLaw:
    """A double nut's two-point ball without oversize (module docstring): ``law`` one of :data:`LAWS`; ``"exact"``
    tabulated on ``points`` loads up to ``max_load`` [N] (spaced as ``q ~ u^(3/2)``) and interpolated by
    lowmodel.screw.load_distribution.AxialStiffness (monotone cubic)."""
    checks.choice("law", law, LAWS)
    bare = replace(module, oversize=0.0)
    factor = math.sin(module.nominal_angle) * math.cos(module.lead_angle)
    if law == "hertz":
        contacts = screw_contacts.ball_contacts(bare, 0.0)
        constant = float(contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2])  # SL + NR: the diagonal

        def shift(q):
            return constant * (np.maximum(np.asarray(q, dtype=float), 0.0) / factor) ** (2.0 / 3.0) / factor

        def load(u):
            return factor * (np.maximum(np.asarray(u, dtype=float), 0.0) * factor / constant) ** 1.5

        return BallLaw(shift, load, "Hertz on the nominal diagonal")
    frictionless = ball_table(bare, max_load, "frictionless", points)
    table = ld.AxialStiffness(frictionless.loads, np.abs(frictionless.shifts))  # the shift as the approach

    def exact_load(u):
        u = np.asarray(u, dtype=float)
        return np.where(u > 0.0, table.load(np.maximum(u, 0.0)), 0.0)

    return BallLaw(table.shift, exact_load, "exact frictionless statics (tabulated)")


@dataclass(frozen=True)
class DoubleNutState:
    """A double nut under an axial load (:func:`double_nut`): ``axial_load`` [N]; ``half_loads`` (2,) N of halves A
    (loaded by it) and B; ``shift`` [m] of the screw against the nut from the preloaded state; ``lifted`` whether B
    has lifted off; ``stiffness`` [N/m] ``dF_a / du``; ``balance`` the axial balance's residual over the load."""

    axial_load: float
    half_loads: np.ndarray
    shift: float
    lifted: bool
    stiffness: float
    balance: float

    def __post_init__(self):
        checks.freeze_arrays(self, "half_loads")


def lift_off(nut: Nut, law: BallLaw) -> float:
    """N, the axial load at which half B of a double nut lifts off: ``n Q(2 U(F_pr / n))`` (module docstring)."""
    n = nut.balls
    return float(n * law.load(2.0 * law.shift(nut.preload / n)))


def double_nut(nut: Nut, axial_load: float, law: BallLaw) -> DoubleNutState:
    """A double nut (``arrangement="double"``) under ``axial_load`` [N] >= 0 on the screw, its balls by ``law``
    (:func:`ball_law`): the shift ``u`` by brentq on the axial balance (module docstring), checked (1e-10 of the
    load) before it is returned."""
    if nut.arrangement != "double":
        raise ValueError("double_nut: a double nut's (arrangement 'double'); a single nut: distribution")
    total = checks.non_negative("axial_load", axial_load, "N")
    n = nut.balls
    u_pr = float(law.shift(nut.preload / n))

    def carried(u):
        return float(n * (law.load(u_pr + u) - law.load(u_pr - u)))

    lifted = total >= lift_off(nut, law)
    if total == 0.0:
        u = 0.0
    else:
        high = u_pr
        while carried(high) < total:
            high *= 2.0
            if high > 0.1 * nut.module.ball_radius:
                raise ValueError(f"axial_load {total!r} N needs a shift beyond 0.1 ball_radius: outside the "
                                 "small-strain Hertz law (eq 53)")
        u = brentq(lambda s: carried(s) - total, 0.0, high, xtol=1e-15 * u_pr, rtol=4.0 * np.finfo(float).eps,
                   maxiter=200)
    halves = np.array([n * float(law.load(u_pr + u)), n * float(law.load(u_pr - u))])
    balance = abs(halves[0] - halves[1] - total) / max(total, nut.preload)
    if not balance <= BALANCE_TOLERANCE:
        raise ConvergenceError("nut.double_nut: the halves' loads do not balance the axial load", residual=balance,
                               iterations=1, tolerance=BALANCE_TOLERANCE, reason="axial load balance")
    h = 1e-6 * u_pr
    stiffness = (carried(u + h) - carried(max(u - h, 0.0))) / (u + h - max(u - h, 0.0))
    return DoubleNutState(total, halves, float(u), bool(lifted), float(stiffness), float(balance))


def friction_over_rotation(nut: Nut, axial_load: float, *, steps: int = 200, duration: float | None = None,
                           amplitude: float = 0.0, cycles: int = 4, progress=None):
    """A single nut's friction torque over rotation: lin2019 Sec 3.4's whole-screw simulation
    (:func:`lowmodel.screw.whole_screw.simulate`) of the nut's balls in its turns under ``axial_load`` [N], over
    ``duration`` [s] (default one nut revolution) in ``steps``; screw-side deviations ``amplitude`` [rad] with
    ``cycles`` over the turns (default none: nominal balls, B2B forces from the load distribution alone).  Returns
    the :class:`~lowmodel.screw.whole_screw.ScrewHistory`."""
    if nut.arrangement != "single":
        raise ValueError("friction_over_rotation: a double nut's balls are two-point; lin2019's friction model is "
                         "four-point: no model yet")
    module = nut.module
    duration = 2.0 * math.pi / abs(module.nut_speed) if duration is None else duration
    return whole_screw.simulate(module, n_balls=nut.balls, axial_load=axial_load, duration=duration, steps=steps,
                                amplitude=amplitude, cycles=cycles, sections=nut.sections, turns=nut.turns,
                                progress=progress, flange=nut.flange)
