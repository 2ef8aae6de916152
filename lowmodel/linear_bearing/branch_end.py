"""Where a B2B solve of touching balls fails: the end of a full-sliding branch, a gap, or only the solver?

lin2019's friction (eqs A4-A7) assumes every contact slides.  Along ``mu`` the slip speed of a contact can fall
to 0: there the full-sliding branch ends and the physical state has a sticking contact, outside the model
(``ball.STICK_REASON``; docs/b2b_bearing.md, "validity").  A branch that ends need not be the last: a
little further another full-sliding branch may begin (the same contact sliding the other way), leaving a *gap*
of ``mu`` without a full-sliding state; and a slip that only passes *near* 0 turns the friction direction fast,
so that Newton and the continuation stop although the branch goes on.  The continuation alone cannot tell
these apart (two touching balls with a gap between mu = 0.2522 and 0.2625 were reported at 0.255 and 0.26 as
"stops sliding", as if no state lay beyond).  :func:`judge` establishes the reason by evidence:

1. from the last converged point of the ``mu`` path, walk towards the target with warm starts and step halving
   (:func:`walk`): reaching it returns the state; else the slip speed at the furthest point is the evidence
   whether a contact stops sliding there (below :data:`STICK_SLIP`);
2. probes: direct solves at ``mu`` a little below and above the target (:data:`PROBES`); from the nearest state
   found, walk back towards the target (reaching it returns the state);
3. the reason: a contact stopping on the way and no state beyond: ``STICK_REASON`` (the branch ends); stopping
   on both sides: ``STICK_REASON`` with the gap's ends (full-sliding states again beyond); no slip near 0 but
   states found beside the target: :data:`NOT_REACHED_REASON` (a solver failure, not an end of the model);
   else the continuation's own reason marked unconfirmed;
4. where the relaxation in time does not settle at the target either (:func:`relaxed_beside`, called by the model's
   solve): relaxed states at :data:`RELAXATION_PROBES` times the target and walks from them; a walk from above that
   stops at a contact whose slip falls below :data:`STICK_SLIP` makes an end of the branch below a gap
   (:func:`with_gap`).  Every walk's stop names its slowest contact and its slip speed.
"""
from __future__ import annotations

import math

from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["PROBES", "STICK_SLIP", "WALK_STEPS", "NOT_REACHED_REASON", "RELAXATION_PROBES", "walk", "judge",
           "relaxed_beside", "with_gap"]

PROBES = (0.98, 0.99, 1.01, 1.02, 1.05, 1.1)  # mu / target of the probe solves
STICK_SLIP = 1e-3  # |v|: a slip speed below this where a walk stops is a contact that stops sliding
WALK_STEPS = 20  # step halvings of a walk: its stop is resolved to ~2^-20 of the distance walked
NOT_REACHED_REASON = "not reached: full-sliding states exist beside the target"
RELAXATION_PROBES = (0.95, 1.05, 1.1)  # mu / target of the relaxations beside a target whose relaxation stalls


def walk(solve_from, start: float, state, target: float, steps: int = WALK_STEPS):
    """From a converged ``state`` at ``mu = start`` towards ``target``: Newton from the last converged state at the
    target, halving the step (geometrically in mu) on failure and going for the target again after a success.

    ``solve_from(mu, z0)`` returns ``(z, residual, iterations)`` or raises ConvergenceError.  Returns
    ``(mu_reached, (z, residual, iterations), failed_at)`` with ``failed_at`` None when the target is reached.
    """
    reached, result, aim = start, (state, None, 0), target
    for _ in range(steps + 1):
        try:
            result = solve_from(aim, result[0])
        except ConvergenceError:
            aim = math.sqrt(reached * aim)
            continue
        reached = aim
        if aim == target:
            return reached, result, None
        aim = target
    return reached, result, aim


def _slip(value):
    """``slip_at``'s answer as (slip speed, where): a float, or (float, the contact's name)."""
    if isinstance(value, tuple):
        return float(value[0]), f" (contact {value[1]})"
    return float(value), ""


def judge(failure: ConvergenceError, target: float, solve_from, probe, slip_at, *, stick_reason: str):
    """Rescue or classify ``failure`` (a ConvergenceError of the solve at friction coefficient ``target``).

    ``solve_from(mu, z0)``: Newton at ``mu`` from ``z0``; ``probe(mu)``: a solve at ``mu`` from the cheap starts;
    both return ``(z, residual, iterations)`` or raise ConvergenceError.  ``slip_at(z, mu)``: the smallest contact
    slip speed [|v|] of state ``z`` at ``mu``, or (that, the name of its contact) for the evidence.
    ``failure.last_state`` / ``failure.last_contacts`` (from
    :func:`lowmodel.linear_bearing.ball.solve_with_continuation`) give the walk's start when the furthest path was
    the ``mu`` path (``failure.last_mu``, else None).  Returns ``((z, residual, iterations), start_mu)``
    when the target is reached; raises ConvergenceError with the reason established otherwise.
    """
    message = str(failure).split(" (residual")[0]
    evidence = []
    stops = []  # (side, mu where a walk stopped, slip speed there)
    start_mu = getattr(failure, "last_mu", None)
    if start_mu is not None:
        reached, result, failed_at = walk(solve_from, start_mu, failure.last_state, target)
        if failed_at is None:
            return result, start_mu
        stops.append(("below" if start_mu < target else "above", reached, *_slip(slip_at(result[0], reached))))
    found = []
    for factor in PROBES:
        try:
            found.append((target * factor, probe(target * factor)))
        except ConvergenceError:
            continue
    for mu_p, (z_p, _, _) in sorted(found, key=lambda item: abs(math.log(item[0] / target)))[:2]:
        reached, result, failed_at = walk(solve_from, mu_p, z_p, target)
        if failed_at is None:
            return result, mu_p
        stops.append(("below" if mu_p < target else "above", reached, *_slip(slip_at(result[0], reached))))
    evidence += [f"a walk from {side} stops at mu = {mu:.6g} with a slip speed of {slip:.3g} |v|{where}"
                 for side, mu, slip, where in stops]
    stops = [stop[:3] for stop in stops]
    if found:
        evidence.append("direct solves converge at mu = " + ", ".join(f"{mu:.6g}" for mu, _ in found))
    sticking = [(side, mu) for side, mu, slip in stops if slip < STICK_SLIP]
    sides = {side for side, _ in sticking}
    if sticking and found and len(sides) == 2:
        low = max(mu for side, mu in sticking if side == "below")
        high = min(mu for side, mu in sticking if side == "above")
        reason = (f"{stick_reason}: no full-sliding state between mu = {low:.6g} and {high:.6g} (a contact sticks; "
                  "full-sliding states again beyond)")
    elif sticking and not any(mu > target for mu, _ in found):  # the branch ends, and nothing beyond
        reason = (f"{stick_reason} at mu = {sticking[0][1]:.6g}; no full-sliding state found beyond, up to mu = "
                  f"{target * max(PROBES):.6g}")
    elif sticking:
        reason = (f"{stick_reason}: at mu = {sticking[0][1]:.6g}; full-sliding states exist beyond (mu = "
                  f"{min(mu for mu, _ in found if mu > target):.6g})")
    elif found:
        reason = NOT_REACHED_REASON
    else:
        reason = f"{failure.reason} (unconfirmed: no slip speed near 0 where the walks stop, no state beside it)"
    error = ConvergenceError(f"{message}; {reason}; evidence: {'; '.join(evidence) or 'none'}",
                             residual=failure.residual, iterations=failure.iterations, tolerance=failure.tolerance,
                             reason=reason, last_converged=failure.last_converged)
    error.min_slip_speed = getattr(failure, "min_slip_speed", math.nan)
    error.stops = tuple(stops)  # (side, mu where a walk stopped, slip speed there): for a caller's further evidence
    raise error from None


def relaxed_beside(target: float, relax_from, solve_from, slip_at):
    """4. where the relaxation in time does not settle at the target either: relax at :data:`RELAXATION_PROBES`
    times the target and walk (:func:`walk`) from a state found there to the target.

    ``relax_from(mu)``: the Newton start of a relaxed state at ``mu``, None where the relaxation does not settle;
    ``solve_from`` and ``slip_at`` as :func:`judge` (``slip_at`` with the contact's name).  Returns ``((z, residual,
    iterations), factor, stops)`` when a walk reaches the target, else ``(None, None, stops)``; ``stops``: (mu of
    the relaxed state, mu where its walk stopped, the smallest contact slip speed there [|v|], its contact).
    """
    stops = []
    for factor in RELAXATION_PROBES:
        start = relax_from(target * factor)
        if start is None:
            continue
        try:
            z0 = solve_from(target * factor, start)[0]
        except ConvergenceError:
            continue
        reached, result, failed_at = walk(solve_from, target * factor, z0, target)
        if failed_at is None:
            return result, factor, stops
        stops.append((target * factor, reached, *_slip(slip_at(result[0], reached))))
    return None, None, stops


def with_gap(failure: ConvergenceError, stops, *, stick_reason: str) -> ConvergenceError:
    """``failure`` (the account of :func:`judge`) with the walks of :func:`relaxed_beside` (``stops``) as evidence;
    where the account was the end of the branch below the target and a walk from above stops at a contact whose slip
    falls below :data:`STICK_SLIP`, the reason is the gap between the two (full-sliding states again beyond), naming
    that contact."""
    if not stops:
        return failure
    evidence = "; ".join(f"a walk from the relaxed state at mu = {start:.6g} stops at mu = {mu:.6g} with a slip "
                         f"speed of {slip:.3g} |v|{where}" for start, mu, slip, where in stops)
    reason = failure.reason
    below = [mu for side, mu, slip in getattr(failure, "stops", ()) if side == "below" and slip < STICK_SLIP]
    above = [(mu, slip, where) for start, mu, slip, where in stops if slip < STICK_SLIP and start > mu]
    if below and above and "no full-sliding state found beyond" in reason:
        low, (high, slip, where) = max(below), min(above)
        reason = (f"{stick_reason}: no full-sliding state between mu = {low:.6g} and {high:.6g} (a contact sticks; "
                  f"full-sliding states again beyond: from mu = {high:.6g}, slip speed {slip:.3g} |v|{where} there)")
    message = str(failure).split(" (residual")[0]
    error = ConvergenceError(f"{message}; {evidence}" + (f"; so: {reason}" if reason != failure.reason else ""),
                             residual=failure.residual, iterations=failure.iterations, tolerance=failure.tolerance,
                             reason=reason, last_converged=failure.last_converged)
    error.min_slip_speed = getattr(failure, "min_slip_speed", math.nan)
    return error
