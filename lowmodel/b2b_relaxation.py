"""Existence oracle of B2B states: relax the balls' velocities in time under the same friction laws.

Where Newton and its continuations find no quasi-static state of touching balls, the question is whether
one exists.  lin2019's ANSYS runs answered it by simulating the transient; this module does the same with
the low-order friction laws: every ball gets its mass and moment of inertia and its velocities follow the
net friction load (the residual of the quasi-static equations, lin2019 eq 4 with eqs 5-8, friction from the
current slip directions), touching neighbours push each other with a normal force that keeps them from
overlapping (eqs 9-10 as a time-stepping complementarity: Moreau's velocity-level scheme).  The run ends
in one of four ways (:class:`Relaxation`):

* **settled**: the net load of every ball has vanished (below ``settle_tolerance``): a quasi-static state
  exists, and the settled velocities and pair forces are the start from which Newton must converge;
* **a contact stops sliding** (``reason`` starts with :data:`STALL_REASON`): a ball-to-groove contact's slip
  speed falls to zero during the transient, the ball stalls there and the full-sliding friction law of
  lin2019 (eqs A4-A6, a direction of slip at every contact) has no state: the contact sticks;
* **a third contact** (:data:`CONTACT_REASON`): a pair that was apart closes its gap, so the contact set of
  the quasi-static problem posed is not the one the balls reach;
* **a cycle** (:data:`CYCLE_REASON`): the velocities come back to an earlier unsettled state (a limit cycle),
  or do not settle within ``max_time`` (:data:`UNSETTLED_REASON`).

Units (those of the models' residuals): velocities in ``|v|`` (the ball unknowns ``x`` of each model, three
per ball: translation along the chain first, then two rotations times ``R_B``), loads in ``mu F_ref``, time in
``tau = m |v| / (mu F_ref)`` (``m`` the ball mass; the translation has mass 1, the rotations ``I / (m R_B^2)
= 2/5``: a solid sphere).  The time integration is linearly implicit Euler (the load's Jacobian from the
model), stable at the stiff slip directions; the step grows while the velocities change little, so that
near a steady state the steps are Newton steps of the quasi-static equations with the inertia as damping
(pseudo-transient continuation, Kelley and Keyes 1998, with a physical mass matrix).

The model enters through two functions (:func:`relax`), so the linear-bearing and the ball-screw B2B models
share this module: ``ball_loads(x) -> (load (n, 3), jacobian (n, 3, 3), slip (n, c))`` the net friction load
of every ball alone with its derivative and the slip speeds of its ``c`` contacts, and ``pair_loads(x) ->
(p, 2, 3)`` the load on (the ball behind, the ball ahead) per unit normal force of each pair, or that and its
derivative in ``x`` ``(p, 2, 3, 2, 3)`` (the pair's friction turns with its slip: taken implicitly, as the balls'
friction; explicit, the steps that grow near a steady state pass its rate and the balls never settle).

A stall is called only when it persists (``stall_windows`` windows in a row, the same contact quiet in all) and
a step changes the velocities by at most ``max_change`` = 0.01 |v|: a contact of a stable full-sliding state may
slip at 1e-4 |v| while its ball's fastest contact slips at 0.5 |v| (light loads, near the end of a branch); with
steps of 0.05 |v| the transient chattered about such a contact and read as a stall (docs/b2b_bearing.md,
'Reasons that say what happened').
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Relaxation", "relax", "STALL_REASON", "CONTACT_REASON", "CYCLE_REASON", "UNSETTLED_REASON",
           "SOLID_SPHERE"]

STALL_REASON = "a contact stops sliding (relaxation in time: a ball stalls at a contact)"
CONTACT_REASON = "a third contact (relaxation in time: a gap closes)"
CYCLE_REASON = "a cycle (relaxation in time: the velocities return without settling)"
UNSETTLED_REASON = "no settling (relaxation in time: still moving at the end)"
SOLID_SPHERE = (1.0, 0.4, 0.4)  # mass matrix of (translation, rotation x R_B, rotation x R_B) per unit ball mass


@dataclass(frozen=True)
class Relaxation:
    """Outcome of :func:`relax`.

    settled : the net loads vanished (a quasi-static state exists; ``velocities`` and ``forces`` are its
        Newton start);  reason : "" when settled, else one of the reasons of the module docstring with what
        happened (ball, contact, time);  velocities : (n, 3) at the end [|v|];  forces : (p,) normal force of
        each pair at the end [mu F_ref] (0 for open pairs);  time : reached [tau];  steps : time steps taken;
        residual : largest net load at the end [mu F_ref];  min_slip : smallest contact slip speed met [|v|];
        stalled : (ball, contact) of the contact that stopped sliding, or None;  the reason is its ``kind`` (one of
        the module's reason constants), ": " and what happened
    """

    settled: bool
    reason: str
    velocities: np.ndarray
    forces: np.ndarray
    time: float
    steps: int
    residual: float
    min_slip: float
    stalled: tuple | None = None

    @property
    def kind(self) -> str:
        """"" when settled, else the reason's kind: one of :data:`STALL_REASON`, :data:`CONTACT_REASON`,
        :data:`CYCLE_REASON`, :data:`UNSETTLED_REASON` (what ConvergenceError.reason carries)."""
        for kind in (STALL_REASON, CONTACT_REASON, CYCLE_REASON, UNSETTLED_REASON):
            if self.reason.startswith(kind):
                return kind
        return ""


def _net_load(load, pair_direction, forces, behind, ahead):
    total = load.copy()
    np.add.at(total, behind, forces[:, None] * pair_direction[:, 0])
    np.add.at(total, ahead, forces[:, None] * pair_direction[:, 1])
    return total


def relax(ball_loads, pair_loads, x0, *, touching, gaps=None, gap_scale: float = 0.0,  # noqa: C901 - one time integration: its Moreau step, active set and the stop tests
          mass=SOLID_SPHERE, settle_tolerance: float = 1e-10, stall_speed: float = 1e-7, stick_fraction: float = 0.1,
          window: int = 100, stall_windows: int = 3, max_time: float = 1e4, max_steps: int = 5000,
          initial_step: float = 0.02, max_change: float = 0.01, contact_names=None) -> Relaxation:
    """Relax ``n`` balls from the velocities ``x0`` (n, 3) [|v|] until they settle or clearly do not.

    Parameters
    ----------
    ball_loads : ``x (n, 3) -> (load (n, 3), jacobian (n, 3, 3), slip (n, c, 2))``: the net friction load of
        every ball alone [mu F_ref] (the model's residual rows of the ball's equilibrium, friction from the slip
        directions of ``x``), its derivative in ``x`` and the contacts' slip vectors (slide, spin) [|v|]
    pair_loads : ``x -> (p, 2, 3)``: load on the ball behind and on the ball ahead per unit normal force of each
        pair (the normal force and its friction, lin2019 eqs 5-8 / 56-59); or ``(that, derivative)`` with
        ``derivative[k, side, row, other, col]`` = d load[k, side, row] / d x[ball ``other`` of pair k, col]
    touching : bool (p,), the pairs in contact at the start (pairs ``(j, j+1)``, and ``(n-1, 0)`` when ``p = n``:
        a ring)
    gaps : (p,) gaps of the open pairs [m] (default: open pairs never close), ``gap_scale`` [m per |v| tau]
        turns the velocity difference into the change of a gap per unit time
    mass : the diagonal mass matrix per ball (default :data:`SOLID_SPHERE`)
    settle_tolerance : largest net load [mu F_ref] of a settled state
    stall_speed : a contact slip speed [|v|] below which the contact has stopped sliding
    stick_fraction, window : a contact whose slip speed stays below ``stick_fraction`` times the largest of its
        ball over ``window`` steps, whose slip direction reverses in them, while the net load does not halve, has
        stopped sliding too (it chatters about zero slip: it sticks), once this holds for ``stall_windows``
        windows in a row with the same contact quiet in each;  contact_names : names of a ball's contacts
        for the messages (default indices)
    max_time, max_steps : limits of the run [tau], [steps]; initial_step [tau]; max_change : largest velocity
        change of a step [|v|] (the transient is followed, not skipped, while it moves)

    The separation rate of pair (behind, ahead) is ``x[ahead, 0] - x[behind, 0]``: a touching pair carries a
    force ``F >= 0`` with ``rate >= 0`` and ``F rate = 0`` at the end of every step (Moreau), found by an
    active-set iteration over the touching pairs.
    """
    x = np.array(x0, dtype=float)
    n = x.shape[0]
    names = tuple(contact_names) if contact_names is not None else None
    touching = np.asarray(touching, dtype=bool)
    p = touching.size
    behind = np.arange(p)
    ahead = (behind + 1) % n
    mass = np.broadcast_to(np.asarray(mass, dtype=float), (n, 3)).reshape(-1)
    gaps = None if gaps is None else np.array(gaps, dtype=float)
    forces = np.zeros(p)
    active = np.zeros(p, dtype=bool)
    time, dt = 0.0, float(initial_step)
    min_slip = math.inf
    history = []  # (time, x) every so often, for the cycle test
    residual = math.inf
    window_slip, window_residual, window_start = None, math.inf, 0.0  # largest slip speeds of the current window
    window_heading, window_reversed = None, None  # slip directions at its start; reversed since
    stall = None  # (contacts quiet in every window of the stall, windows, start time, largest slip speeds, scales)
    path = 0.0  # velocity path length travelled [|v|]
    steps = 0
    while steps < max_steps and time < max_time:
        load, jacobian, slip = ball_loads(x)
        speeds = np.hypot(slip[..., 0], slip[..., 1])
        heading = slip / np.where(speeds > 0.0, speeds, 1.0)[..., None]
        if window_heading is None:
            window_heading, window_reversed = heading, np.zeros(speeds.shape, dtype=bool)
        window_reversed |= np.einsum("ncd,ncd->nc", heading, window_heading) < 0.0
        worst = np.unravel_index(int(np.argmin(speeds)), speeds.shape)
        min_slip = min(min_slip, float(speeds[worst]))
        direction = pair_loads(x)
        d_direction = None
        if isinstance(direction, tuple):  # the pair loads' derivative in x: implicit in the step below
            direction, d_direction = direction
        net = _net_load(load, direction, forces * touching, behind, ahead)
        rate = x[ahead, 0] - x[behind, 0]
        residual = float(np.max(np.abs(net)))
        complementary = bool(np.all(rate[touching] >= -settle_tolerance)) and bool(np.all(forces >= 0.0))
        if residual <= settle_tolerance and complementary and steps > 0:
            return Relaxation(True, "", x, forces * touching, time, steps, residual, min_slip)
        if speeds[worst] < stall_speed:
            ball, contact = int(worst[0]), int(worst[1])
            name = names[contact] if names else contact
            return Relaxation(False, f"{STALL_REASON}: ball {ball} contact {name}, slip speed "
                              f"{speeds[worst]:.2g} |v| at t = {time:.4g} tau", x, forces * touching, time, steps,
                              residual, min_slip, (ball, contact))
        # one linearly implicit Euler step with the pair forces as unknowns: (M/dt - J) dx = load + B F, rate' >= 0
        size = 3 * n
        system = np.diag(mass / dt)
        for j in range(n):
            system[3 * j:3 * j + 3, 3 * j:3 * j + 3] -= jacobian[j]
        if d_direction is not None:  # the friction of a touching pair turns with its slip: d (F direction) / d x
            for k in np.flatnonzero(touching & (forces > 0.0)):
                for side, ball in enumerate((behind[k], ahead[k])):
                    for other, partner in enumerate((behind[k], ahead[k])):
                        system[3 * ball:3 * ball + 3, 3 * partner:3 * partner + 3] -= (
                            forces[k] * d_direction[k, side, :, other, :])
        columns = np.zeros((size, p))  # the load of a unit force of each pair
        for k in range(p):
            columns[3 * behind[k]:3 * behind[k] + 3, k] += direction[k, 0]
            columns[3 * ahead[k]:3 * ahead[k] + 3, k] += direction[k, 1]
        rows = np.zeros((p, size))  # d rate / d x
        rows[behind, 3 * behind] -= 1.0
        rows[np.arange(p), 3 * ahead] += 1.0
        active &= touching
        change, new_forces = None, np.zeros(p)
        for _ in range(2 * p + 4):  # active set of the pair forces
            index = np.flatnonzero(active)
            k = index.size
            kkt = np.zeros((size + k, size + k))
            kkt[:size, :size] = system
            kkt[:size, size:] = -columns[:, index]
            kkt[size:, :size] = rows[index]
            rhs = np.concatenate([load.reshape(-1), -rate[index]])
            try:
                solution = np.linalg.solve(kkt, rhs)
            except np.linalg.LinAlgError:
                solution = np.linalg.lstsq(kkt, rhs, rcond=None)[0]
            change = solution[:size]
            new_forces = np.zeros(p)
            new_forces[index] = solution[size:]
            new_rate = rate + rows @ change
            negative = active & (new_forces < 0.0)
            violating = touching & ~active & (new_rate < -settle_tolerance)
            if not negative.any() and not violating.any():
                break
            if negative.any():
                active[int(np.argmin(np.where(negative, new_forces, np.inf)))] = False
            else:
                active[int(np.argmin(np.where(violating, new_rate, np.inf)))] = True
        largest = float(np.max(np.abs(change)))
        if not np.isfinite(largest):
            return Relaxation(False, f"{UNSETTLED_REASON}: the time step failed at t = {time:.4g} tau", x,
                              forces * touching, time, steps, residual, min_slip)
        if largest > max_change and dt > 1e-12:
            dt *= 0.5 * max_change / largest if largest < 4 * max_change else 0.125
            continue
        x = x + change.reshape(n, 3)
        path += largest
        forces = new_forces
        time += dt
        steps += 1
        if gaps is not None:  # an open pair whose gap closes: the contact set changes
            closing = rate + (x[ahead, 0] - x[behind, 0])
            gaps = gaps + 0.5 * closing * dt * gap_scale
            closed = ~touching & (gaps <= 0.0)
            if closed.any():
                k = int(np.flatnonzero(closed)[0])
                return Relaxation(False, f"{CONTACT_REASON}: pair ({behind[k]}, {ahead[k]}) closes at t = {time:.4g} "
                                  "tau", x, forces * touching, time, steps, residual, min_slip)
        if largest < 0.25 * max_change:
            dt = min(2.0 * dt, max_time)
        window_slip = speeds if window_slip is None else np.maximum(window_slip, speeds)
        if steps % window == 0:
            # contacts whose slip speed stayed far below their ball's other contacts' over the window while the net
            # load did not halve: the ball stalls there (with full-sliding friction a sticking contact chatters
            # about zero slip, its friction flipping, and the net load does not settle)
            scale = window_slip.max(axis=1, keepdims=True)
            quiet = (window_slip < stick_fraction * scale) & window_reversed
            if quiet.any() and residual > 0.5 * window_residual and residual > 1e3 * settle_tolerance:
                if stall is None or not (stall[0] & quiet).any():  # a stall starts (or another contact's)
                    stall = (quiet, 0, window_start, window_slip, scale)
                stall = (stall[0] & quiet, stall[1] + 1, stall[2], np.maximum(stall[3], window_slip),
                         np.maximum(stall[4], scale))
            else:
                stall = None
            if stall is not None and stall[1] >= stall_windows:
                quiet, _, since, span_slip, scale = stall
                where = ", ".join(f"ball {j} contact {names[c] if names else c}" for j, c in np.argwhere(quiet))
                worst = np.unravel_index(int(np.argmin(np.where(quiet, span_slip / scale, np.inf))), quiet.shape)
                return Relaxation(False, f"{STALL_REASON}: {where} slip at most {span_slip[worst]:.2g} |v| "
                                  f"(the ball's fastest contact {float(scale[worst[0], 0]):.2g} |v|) from t = "
                                  f"{since:.4g} to {time:.4g} tau while the net load stays {residual:.2g} "
                                  "mu F_ref", x, forces * touching, time, steps, residual, min_slip,
                                  (int(worst[0]), int(worst[1])))
            window_slip, window_residual, window_start, window_heading = None, residual, time, None
            for then, earlier, travelled in history:  # back to an earlier unsettled state after moving: a cycle
                if (np.max(np.abs(x - earlier)) < 1e-6 and residual > 1e3 * settle_tolerance
                        and path - travelled > 1e-3):
                    return Relaxation(False, f"{CYCLE_REASON}: period about {time - then:.4g} tau, net load "
                                      f"{residual:.2g} mu F_ref", x, forces * touching, time, steps, residual,
                                      min_slip)
            history.append((time, x.copy(), path))
    return Relaxation(False, f"{UNSETTLED_REASON}: net load {residual:.2g} mu F_ref after t = {time:.4g} tau and "
                      f"{steps} steps", x, forces * touching, time, steps, residual, min_slip)
