"""What the scenes of a case file share (validation.ladder): the tolerances they judge by, the number format of
their tables, the per-contact table and the power-balance check of a low-order or FE-informed state; the preload
loss of a ball screw and the limits of lin2019's model it sets (:func:`preload_loss`, :func:`within_model_limits`,
:func:`limits_lines`)."""
from __future__ import annotations

import contextlib
import dataclasses
import functools
import math
import time

from ballbench.lowmodel import bearing_results, truncation
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES as GUIDE_CONTACTS
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import preload
from ballbench.lowmodel.screw.b2b import FULL_SLIDING_LIMIT
from ballbench.lowmodel.screw.contacts import CONTACT_NAMES as SCREW_CONTACTS
from ballbench.lowmodel.screw.contacts import flank_angles
from ballbench.lowmodel.screw.preload import nominal_preload_loss
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.scene import NotApplicable

# the FE reference must be known to 1 % (its uncertainty by references.uncertainty) to judge models against it;
# above that the scene is inconclusive (validation.scene, "Inconclusive")
REFERENCE_UNCERTAINTY = 0.01
B2B_TOLERANCE = {"linear-guide": 0.07, "ball-screw": 0.10}  # lin2019's own claims, docs/fe_b2b.md
POWER_TOLERANCE = 1e-6  # docs/fe_b2b.md: energy conservation incl. the B2B loss
# a B2B force below this share of the friction scale mu N (N: the ball load) is "near zero" and judged on that
# share instead of on itself (lin2019 Table 3 case (b): 0.13 % of case (a)); above it the relative error counts
NEAR_ZERO_B2B = 0.05
# Hamrock-Dowson's film against the numerical EHL solve: the 15 % the ehl-hamrock-dowson and sun2021-ehl scenes
# judge the solver by (docs/ehl.md, "Checks": the fit itself scatters by about 10 %)
HAMROCK_DOWSON_TOLERANCE = 0.15
EHL_LOAD_TOLERANCE = 1e-4  # load balance of the EHL solve (sun2021 eq 19), as those scenes check it

__all__ = ["settle_words", "B2B_SETTLE_CAVEAT",
           "B2B_TOLERANCE", "EHL_LOAD_TOLERANCE", "HAMROCK_DOWSON_TOLERANCE", "NEAR_ZERO_B2B", "POWER_TOLERANCE",
           "REFERENCE_UNCERTAINTY", "contact_table", "fmt", "power_check", "preload_loss",
           "preload_loss_words", "oversize_for", "past_preload_loss", "beyond_full_sliding", "largest_state_load",
           "NO_STATE_REASONS", "no_state_reason", "FRICTIONLESS_WORDS", "within_model_limits", "limited",
           "limits_lines",
           "LIN2019_SCENES", "touching_state", "truncations", "truncation_check", "not_truncated"]

# the scenes of a ball-screw case built on the state of lin2019's model (balls, contact loads, FE module shares, the
# stick/slip balls, the EHL loads): where that model has no state they do not apply, but for the contact rung, which
# judges contact mechanics and then runs on the loads of the frictionless statics (FRICTIONLESS_WORDS)
LIN2019_SCENES = ("balls", "contact", "ehl", "b2b-fe", "stick-slip")
# what the -contact scene and the header say when its loads are those of the frictionless statics
FRICTIONLESS_WORDS = ("the loads of the frictionless statics of the balls at the case's axial load "
                      "(lowmodel.screw.preload.frictionless_statics: exact flank arcs, Hertz's law lin2019 eq 53, "
                      "unloaded contacts carry nothing: two-point contact past the preload loss), not those of "
                      "lin2019's friction model, which has no state "
                      "at this load; the contact rung judges contact mechanics (Hertz, BEM, FE at a given load), "
                      "not friction")


def settle_words(fidelity: str, finer: str, caveat: str = "") -> str:
    """What settles an inconclusive reference (docs/verification.md, "Bounds and INCONCLUSIVE"): the next fidelity
    of the run at ``fidelity``, and ``finer``, the finer levels in words (e.g. "FE levels n = b/h 5.5, 6.6, 7.92,
    9.5, 11.4"), for a case file's own ``[fe]`` table; ``caveat``: where finer levels are not shown to settle it,
    what the measurements say (the words then read "What may settle it")."""
    step = {"quick": "run at the default fidelity (without --quick) or --fine",
            "default": "run --fine"}.get(fidelity, "give the case file an [fe] table with finer levels")
    if caveat:
        return f"What may settle it: a finer study: {step}; or {finer} ({caveat})."
    return f"What settles it: a finer study: {step}; or {finer}."


# where finer module levels are not shown to settle the FE-informed B2B reference (the measured levels of
# docs/your_own_bearing.md, "How the FE-informed B2B force converges with h")
B2B_SETTLE_CAVEAT = ("on the catalogue's small B2B forces finer module levels still scattered, at the default "
                     "fidelity too: docs/your_own_bearing.md, 'How the FE-informed B2B force converges with h'")


def fmt(value: float, digits: int = 4) -> str:
    """``value`` with ``digits`` significant digits, as the tables of the case scenes show numbers."""
    return f"{value:.{digits}g}"


def contact_table(run, result, what: str) -> None:
    """The per-ball, per-contact table of a GuideResult or ScrewResult (lowmodel.bearing_results) and its CSV."""
    run.table(f"Per ball and contact ({what}, {result.model})",
              ("ball", "contact", "F [N]", "angle [deg]", "a [mm]", "b [mm]", "p0 [MPa]", "approach [um]"),
              [(c.ball, c.contact, fmt(c.normal_force), fmt(math.degrees(c.contact_angle)), fmt(c.a * 1e3),
                fmt(c.b * 1e3), fmt(c.p0 / 1e6), fmt(c.approach * 1e6)) for c in result.contacts])
    run.write_csv("contacts.csv", result.table())


def power_check(run, model: str, state, time_s: float, what: str) -> None:
    """Check the relative power balance of a low-order state (input power against every loss incl. B2B)."""
    balance = (state.input_power - state.total_loss) / state.input_power
    run.check(model=model, family="low-order numerical", quantity=f"power balance (input - losses)/input, {what}",
              unit="1", value=balance, reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=time_s,
              source="energy conservation incl. the B2B loss (lin2019 eq 7); docs/fe_b2b.md: 1e-6",
              why="the value is itself a relative power error: zero judged on the scale 1")


@functools.lru_cache(maxsize=16)
def preload_loss(case):
    """The preload loss of a BallScrewCase's balls under one nut shift (lowmodel.screw.preload: frictionless, exact
    flank arcs, Hertz's law lin2019 eq 53): ``PreloadLoss`` with the total axial load [N] at which the first contact
    unloads."""
    return preload.preload_loss(screw_b2b.contacts(case))


def oversize_for(case, axial_load: float) -> float:
    """The oversize [m] that moves the preload loss of ``case`` to ``axial_load`` [N], from the preload loss's
    growth like ``oversize^(3/2)`` (lowmodel.screw.preload.nominal_preload_loss): an estimate for the reader."""
    loss = preload_loss(case)
    if loss.axial_load > 0.0:
        return case.screw.oversize * (axial_load / loss.axial_load) ** (2.0 / 3.0)
    # no preload: the closed form of a nominal ball at a unit oversize, scaled the same way
    contacts = screw_b2b.contacts(case, oversize=1e-6)
    per_ball = nominal_preload_loss(contacts)
    return 1e-6 * (axial_load / (contacts.n_balls * per_ball)) ** (2.0 / 3.0)


def preload_loss_words(case) -> str:
    """How the preload loss of ``case`` is computed, in parentheses (the number itself is the caller's)."""
    loss = preload_loss(case)
    return (f"(oversize {case.screw.oversize * 1e6:.3g} um; frictionless four-point contacts with Hertz's law, "
            f"lin2019 eq 53, lowmodel.screw.preload; ball {loss.ball + 1} {loss.contact} unloads first; "
            "docs/ball_screw.md, 'Preload loss')")


# the reasons a ConvergenceError of lin2019's ball-screw model gives when its continuation finds no state: the load
# ramp stopping near full sliding (lowmodel.screw.b2b), the preload continuation stopping at a contact that slides
# fully or without a named cause (lowmodel.screw.convergence.stall_reason); any other reason is a solver fault
NO_STATE_REASONS = (FULL_SLIDING_LIMIT, "a contact slides fully", "continuation stalled",
                    "preload continuation stalled")


def no_state_reason(reason: str) -> bool:
    """Whether a ConvergenceError's ``reason`` is one of :data:`NO_STATE_REASONS`, also where the load ramp of
    lowmodel.screw.b2b stopped at its first step with one of them (lowmodel.screw.b2b.ramp_stop_cause: the ramp
    starts at a fixed load per ball, already past the preload loss of a small screw)."""
    return screw_b2b.ramp_stop_cause(reason) in NO_STATE_REASONS


STATE_SEARCH_STEPS = 8  # bisection steps of :func:`largest_state_load` (the load known to 2^-8 of the case's)


@functools.lru_cache(maxsize=16)
def largest_state_load(case) -> float | None:
    """The largest axial load [N] at or below ``case.axial_load`` at which lin2019's ball-screw model of ``case``
    finds a state, by bisection on the axial load (:data:`STATE_SEARCH_STEPS` steps; the model found no state at
    ``case.axial_load``); None when it finds none even at zero axial load (the preload alone).  Evidence for the
    reader, not a proof: a continuation may stop short of a state that exists."""
    def has_state(load: float) -> bool:
        try:
            bearing_results.screw_states(dataclasses.replace(case, axial_load=load))
        except ConvergenceError:
            return False
        return True

    if not has_state(0.0):
        return None
    low, high = 0.0, float(case.axial_load)
    for _ in range(STATE_SEARCH_STEPS):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if has_state(middle) else (low, middle)
    return low


def past_preload_loss(case, error) -> str:
    """The reason a ConvergenceError of lin2019's ball-screw model is the limit of that model on ``case``, or ""
    when it is not (a solver fault, which then stands): its load ramp or its preload continuation stopped at a
    contact near full sliding or without a named cause (:data:`NO_STATE_REASONS`), either past the frictionless
    preload loss (two-point contact) or below it, where friction unloads a contact earlier (docs/ball_screw.md,
    'Preload loss') and the model finds states at lower loads (below the loss with no state even under the preload
    alone, the error stands: a fault, not a limit).  The reason names the stop, the preload loss and the largest
    axial load at which the model finds a state (:func:`largest_state_load`)."""
    if not isinstance(case, BallScrewCase) or not no_state_reason(getattr(error, "reason", "") or ""):
        return ""
    try:
        loss = preload_loss(case)
    except (ConvergenceError, ValueError):  # no preload loss to judge against: the original error stands
        return ""
    reach = largest_state_load(case)
    past = case.axial_load > loss.axial_load
    if not past and reach is None:  # below the loss with no state even under the preload alone: a fault, it stands
        return ""
    stop = str(error).split(" (residual")[0]
    found = ("it finds no state even at zero axial load (the preload alone)" if reach is None else
             f"it finds states up to about {reach:.4g} N axial load at this oversize (bisection on the axial load)")
    if past:
        where = (f"axial load {case.axial_load:.4g} N is past the preload loss at {loss.axial_load:.4g} N "
                 f"{preload_loss_words(case)}: the balls go over to two-point contact, where one contact rolls "
                 "without spin, and lin2019's four-point full-sliding model has no state there")
    else:
        where = (f"axial load {case.axial_load:.4g} N lies below the frictionless preload loss at "
                 f"{loss.axial_load:.4g} N {preload_loss_words(case)}, but friction unloads a contact earlier: "
                 "lin2019's four-point full-sliding model found no state at this load")
    return (f"{where} ({stop}); {found}. Below that load it models the four-point contact it was made for; near it "
            "its contacts slide close to their limit mu F: judge its friction with care.")


def beyond_full_sliding(case, error) -> str:
    """The reason a ConvergenceError of lin2019's linear-guide model is the limit of that model on ``case``, or ""
    when it is not (a solver fault, which then stands): a free ball's spin-capacity ratio below 1 (no full-sliding
    state can exist, docs/b2b_bearing.md) or the full-sliding branch ending where a contact's slip falls to zero
    (lowmodel.linear_bearing.b2b.no_full_sliding_state).  Near the four-point limit a contact sticks (rolls without
    spin) and its traction is no longer mu p: the ``-balls`` scene gives the friction by the stick/slip law
    (lowmodel.bearing_results.guide_states); a scene built on full sliding does not apply."""
    if not isinstance(case, LinearGuideCase) or not b2b.no_full_sliding_state(error):
        return ""
    return (f"lin2019's full-sliding model has no state for these balls ({error.reason}): near the four-point limit a "
            "contact sticks (rolls without spin) and its traction is no longer mu p. This scene is built on full "
            "sliding; the -balls scene gives the friction by the stick/slip law on a half-space (docs/b2b_rolling.md, "
            "'Where full sliding has no state'), and the contact rung runs on the loads of lin2017 eq 36, which do "
            "not depend on friction.")


@contextlib.contextmanager
def within_model_limits(case):
    """Run a ball-screw or linear-guide scene's work; a ConvergenceError that is lin2019's limit on ``case`` (the
    full-sliding model has no state past a screw's preload loss, :func:`past_preload_loss`, or near a guide's
    four-point limit, :func:`beyond_full_sliding`) becomes NotApplicable with the reason; any other
    ConvergenceError stays as it is (the scene ends in error)."""
    try:
        yield
    except ConvergenceError as error:
        reason = past_preload_loss(case, error) or beyond_full_sliding(case, error)
        if not reason:
            raise
        raise NotApplicable(reason) from error


def limited(function, case):
    """``function`` (a scene function ``f(run)`` or a show hook ``f(scene_dir, fidelity)``) run
    :func:`within_model_limits` of ``case`` (a partial of a module function: it pickles for a distributed run)."""
    return functools.partial(_within_limits, function, case)


def _within_limits(function, case, *args, **kwargs):
    with within_model_limits(case):
        return function(*args, **kwargs)


def limits_lines(case, names) -> list[str]:
    """What a ball-screw case's header says before any work: its preload loss, and when the axial load is past it,
    which of the scenes ``names`` may not apply and why (docs/your_own_bearing.md, 'Reading the verdict')."""
    if not isinstance(case, BallScrewCase):
        return []
    try:
        loss = preload_loss(case)
    except (ConvergenceError, ValueError) as error:  # said, not hidden: the scenes run and decide on their own
        return [f"the preload loss of this screw was not found ({type(error).__name__}: {error}); no scene can be "
                "declared not applicable past it"]
    words = preload_loss_words(case)
    head = f"preload loss at {loss.axial_load:.4g} N axial load {words}"
    if not case.axial_load > loss.axial_load:
        return [f"{head}; the axial load {case.axial_load:.4g} N lies below it: lin2019's four-point model "
                "applies."]
    fe = [n for n in names if n.endswith("-b2b-fe")]
    built = [n for n in names if any(n.endswith("-" + s) for s in LIN2019_SCENES)]
    lines = [f"{head}; the axial load {case.axial_load:.4g} N is past it: contacts unload and the balls go over "
             "to two-point contact, outside lin2019's four-point full-sliding model "
             f"(the frictionless preload loss reaches this load at an oversize of about "
             f"{oversize_for(case, case.axial_load) * 1e6:.2g} um; friction unloads a contact earlier)."]
    if fe:
        lines.append(f"{fe[0]} does not apply where lin2019's state leaves a contact unloaded (its FE module needs "
                     "four loaded contacts, lin2017 eq 37).")
    contact = [n for n in built if n.endswith("-contact")]
    balls = [n for n in built if n.endswith("-balls")]
    built = [n for n in built if not n.endswith(("-contact", "-balls"))]
    if balls:
        lines.append(f"Where lin2019's model finds no state at this load, {balls[0]} gives the friction by the "
                     "stick/slip law on a half-space at the loads of the frictionless statics (docs/b2b_rolling.md, "
                     "'Where full sliding has no state'); where it finds one, its contacts slide near their limit "
                     "mu F: judge its friction with care.")
    if built:
        lines.append(f"Where lin2019's model finds no state at this load, {', '.join(built)} (built on its state) do "
                     "not apply.")
    if contact:
        lines.append(f"Where lin2019's model finds no state at this load, {contact[0]} runs on {FRICTIONLESS_WORDS}.")
    return lines


# --------------------------------------------------------------------------
# contact ellipse truncation by the groove's shoulder (lowmodel.truncation, docs/truncation.md)
# --------------------------------------------------------------------------
def touching_state(case):
    """The contact loads of the low-order touching state of a guide or screw ``case``: a guide's lin2017 eq 36 loads
    (lowmodel.bearing_results.guide_contacts, the same under either contact law), a screw's screw_result, or None
    when the screw model has no state there (ConvergenceError) or ``case`` is neither."""
    if isinstance(case, LinearGuideCase):  # lin2017 eq 36's loads and ellipses: the same under either law
        return bearing_results.guide_contacts(case)
    if not isinstance(case, BallScrewCase):
        return None
    try:  # lin2019's state (full sliding): the module FE is built on it
        free, touching = bearing_results.screw_states(case)
        return bearing_results.screw_result(case, touching, free)
    except ConvergenceError:
        return None


def truncations(case, result=None) -> tuple:
    """The :class:`lowmodel.truncation.Truncation` of every loaded contact of a guide's or screw's low-order touching
    state (``result``: its lowmodel.bearing_results result, computed when None; none without a state): the flank's
    shoulder from the
    contact angle with the ball centred (a guide's ``beta_0 + deviation``; a screw's flank angles of its deviation
    reading, lowmodel.screw.contacts.flank_angles), the ellipse's end from the loaded angle and ``a``."""
    result = result or touching_state(case)
    if result is None:  # no low-order state: no ellipse to check (the rungs say why, LIN2019_SCENES)
        return ()
    if isinstance(case, LinearGuideCase):
        radius, conformity = case.guide.ball_radius, case.guide.conformity
        rigid = {(j, name): float(angle) for j in range(1, case.n_balls + 1)
                 for name, angle in zip(GUIDE_CONTACTS, case.contact_angles)}
    elif isinstance(case, BallScrewCase):
        radius, conformity = case.screw.ball_radius, case.screw.conformity
        angles = flank_angles(case.screw.nominal_angle, list(case.deviations), case.reading)
        rigid = {(j + 1, name): float(angle) for j, row in enumerate(angles)
                 for name, angle in zip(SCREW_CONTACTS, row)}
    else:
        return ()
    return tuple(truncation.truncation(f"ball {c.ball} {c.contact}", radius, conformity, rigid[(c.ball, c.contact)],
                                       c.contact_angle, c.a)
                 for c in result.contacts if c.normal_force > 0)


def truncation_check(run, case, result=None, *, time_s: float = 0.0) -> tuple:
    """The truncation finding of a rung (docs/truncation.md): the end of the worst contact ellipse's major axis
    against its groove's shoulder, a finding when it reaches it (every model of the rung then works outside its
    assumptions; the verdict names the contact and the angles).  Returns the truncations."""
    start = time.perf_counter()
    found = truncations(case, result)
    if result is None:  # the state solved here: its time is the check's
        time_s += time.perf_counter() - start
    if not found:
        return found
    worst = min(found, key=lambda t: t.margin)
    run.check(model="contact ellipse of the low-order touching state (Hertz semi-axis a)", family="analytical",
              quantity=f"end of the major semi-axis, beta + asin(a/R_B), {worst.contact}", unit="rad",
              value=worst.end_angle, reference=worst.shoulder_angle, relation="le", tolerance=0.0, time_s=time_s,
              source=f"the groove's shoulder, the land {truncation.SHOULDER_DEPTH:g} R_B from the ball centre "
                     "(lowmodel.truncation; Harris & Kotzalas, contact ellipse truncation; docs/truncation.md)",
              note=truncation.words(found) or f"worst margin {math.degrees(worst.margin):.1f} deg: "
                                              f"{worst.text()}", finding=True)
    return found


def not_truncated(case, result=None) -> None:
    """NotApplicable when a contact ellipse of ``case`` reaches its groove's shoulder (docs/truncation.md): an
    edge contact, which the FE modules (their mortar zones on the flank, fem.fourpoint) do not resolve."""
    words = truncation.words(truncations(case, result))
    if words:
        raise NotApplicable(f"{words}. The FE module (fem.fourpoint, fem.screw_module) needs every contact ellipse "
                            "on its flank.")
