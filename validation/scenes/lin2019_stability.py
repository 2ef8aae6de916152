"""Stability sweep of the single-ball and N-ball solvers of lin2019 (docs/b2b_bearing.md, "Robustness").

Models: lowmodel.linear_bearing.ball (eqs 1-4), lowmodel.linear_bearing.b2b
(eqs 5-10).  Where a quasi-static state with full sliding exists (spin-capacity
ratio >= 1.05, docs/b2b_bearing.md "validity") every solve must converge, by
Newton from the cheap start or by continuation; with touching balls every
solve must converge or end where a contact stops sliding (the end of the
full-sliding branch, checked by a bisection in mu); every failure must carry a
reason; no solve may return NaN.  Parameters around lin2019 Table 1.
"""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ballbench.lowmodel import b2b_relaxation, checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.validation.cases import lin2019
from ballbench.validation.figures.lin2019 import converged_region
from ballbench.validation.scene import scene

MODEL_BALL = "lowmodel.linear_bearing.ball"
MODEL_B2B = "lowmodel.linear_bearing.b2b"
BALL = dict(model=MODEL_BALL, family="low-order numerical")
B2B = dict(model=MODEL_B2B, family="low-order numerical")
GUIDE = lin2019.GUIDE  # lin2019 Table 1
RATIO_FLOOR = 1.05  # spin-capacity ratio above which a state exists and must be found
SIZES = {"quick": dict(grid=(9, 7), margins=(1e-3, 1e-2, 3e-2), loads=9, mus=5, chains=(1, 2, 5, 20, 200),
                       repeats=2, stick_steps=3),
         "default": dict(grid=(17, 13), margins=(1e-4, 1e-3, 3e-3, 1e-2, 3e-2), loads=17, mus=9,
                         chains=(1, 2, 3, 5, 10, 20, 50, 200), repeats=3, stick_steps=4),
         "fine": dict(grid=(33, 25), margins=(1e-5, 1e-4, 1e-3, 3e-3, 1e-2, 2e-2, 3e-2, 5e-2), loads=33, mus=13,
                      chains=(1, 2, 3, 5, 10, 20, 50, 100, 200), repeats=5, stick_steps=8)}


def _case(theta, rho, n_balls=1, **overrides):
    # theta runs to 40 deg, the whole four-point range of the solvers: past the 20 deg a real bearing's deviation
    # reaches (lowmodel.checks.PLAUSIBLE), a limit study on purpose
    with checks.beyond_plausible():
        case = lin2019.module_case(theta, rho, n_balls=n_balls, **overrides)
    return b2b.contacts(case)


class _Tally:
    """Outcome of every solve of the sweep."""

    def __init__(self):
        self.records = []  # (family, ratio, converged, reason, iterations, residual, continued, power error, finite)
        self.coupled = []  # whether the solve had touching balls (B2B forces)
        self.relaxed = []  # the relaxation's verdict on a failed solve (lowmodel.b2b_relaxation), "" if none
        self.failures = []  # (family, n_balls, ratio, reason, last converged, mu, min slip, relaxation's account)

    def solve(self, family, contacts, gaps=None):
        ratio = float(np.min(bearing_contacts.spin_capacity_ratio(contacts)))
        coupled = contacts.n_balls > 1 and (gaps is None or bool(np.any(np.asarray(gaps) == 0.0)))
        self.coupled.append(coupled)
        try:
            state = b2b.solve(contacts, gaps)
        except ConvergenceError as error:
            relaxation = getattr(error, "relaxation", None)
            self.relaxed.append("" if relaxation is None else relaxation.kind or "settled, Newton from it failed")
            self.records.append((family, ratio, False, error.reason, error.iterations, error.residual, False,
                                 math.nan, False))
            self.failures.append((family, contacts.n_balls, ratio, error.reason, error.last_converged,
                                  float(contacts.friction_coefficient), getattr(error, "min_slip_speed", math.nan),
                                  getattr(getattr(error, "relaxation", None), "reason", "no relaxation")))
            return None
        self.relaxed.append("")
        values = np.concatenate([state.ball_velocity, state.omega.ravel(), state.b2b_force,
                                 state.friction_loss.ravel()])
        power = abs(state.input_power - state.total_loss) / abs(state.input_power)
        self.records.append((family, ratio, True, "", state.iterations, state.residual, bool(state.continuation),
                             power, bool(np.all(np.isfinite(values)))))
        return state

    def column(self, index, family=None):
        return np.array([r[index] for r in self.records if family is None or r[0] == family])


@scene("lin2019-stability", "Solver sweep: rho and theta up to the lin2017 eq 37 limit, N_y 1e-3 to 1e5 N, mu 1e-6 "
       "to 1, chains of 1 to 200 balls with random gaps and deviations; 100 % convergence where the "
       "spin-capacity ratio >= 1.05, a reason for every failure; converged-region figure",
       kind="low-order", cost_s=28.0)
def stability(run):
    sizes = SIZES[run.fidelity]
    rng = np.random.default_rng(2019)
    tally = _Tally()
    start = time.perf_counter()
    # 1) (rho, theta) over the whole four-point range, one ball: the converged region
    n_theta, n_uniform = sizes["grid"]
    margins = np.asarray(sizes["margins"])  # fractions of the eq 37 range from either end: the boundary is there
    fractions = np.sort(np.concatenate([margins, np.linspace(0.0, 1.0, n_uniform + 2)[1:-1], 1.0 - margins]))
    n_rho = fractions.size
    thetas = np.radians(np.linspace(0.0, 40.0, n_theta))
    grid = []
    for theta in run.progress(thetas, desc="(rho, theta) grid"):
        low, high = fourpoint.contact_limits(_case(theta, 0.0).contact_angles[0])
        for u in fractions:
            rho = float(low + (high - low) * u)
            state = tally.solve("grid", _case(theta, rho))
            grid.append((math.degrees(theta), rho, float(u), tally.records[-1][1], state is not None))
    # 2) N_y from 1e-3 to 1e5 N, one and two touching balls (theta = 2 deg, rho = -0.6 and 0.3)
    for load in run.progress(np.geomspace(1e-3, 1e5, sizes["loads"]), desc="N_y sweep"):
        for rho in (-0.6, 0.3):
            tally.solve("load", _case(math.radians(2.0), rho, vertical_force=float(load)))
            tally.solve("load", _case(math.radians(2.0), rho, n_balls=2, vertical_force=float(load)), [0.0])
    # 3) mu from 1e-6 to 1, two touching balls
    for mu in run.progress(np.geomspace(1e-6, 1.0, sizes["mus"]), desc="mu sweep"):
        for theta_deg, rho in ((2.0, -0.6), (3.0, -0.7), (1.0, 0.5)):
            tally.solve("mu", _case(math.radians(theta_deg), rho, n_balls=2, friction_coefficient=float(mu)), [0.0])
    # 4) chains of 1 to 200 balls: random gaps (60 % touching), deviations, side loads, N_y, mu
    chain_times = {}
    for n_balls in run.progress(sizes["chains"], desc="chains"):
        for _ in range(sizes["repeats"]):
            deviations = np.radians(rng.uniform(-3.0, 3.0, size=(n_balls, 2)))
            angles = math.pi / 4 + np.column_stack([-deviations[:, 0], deviations[:, 0], 0.3 * deviations[:, 1],
                                                    -0.3 * deviations[:, 1]])
            load = float(10 ** rng.uniform(-1.0, 3.0))
            sides = rng.uniform(-0.6, 0.6, n_balls) * load  # drawn before mu: the cases of the random sequence
            guide = dataclasses.replace(GUIDE, friction_coefficient=float(10 ** rng.uniform(-3.0, 0.0)))
            contacts = bearing_contacts.ball_contacts(angles, sides, load, **guide.keywords)
            gaps = np.where(rng.random(n_balls - 1) < 0.6, 0.0, rng.uniform(0.0, 0.1 * GUIDE.ball_radius,
                                                                            n_balls - 1))
            began = time.perf_counter()
            tally.solve("chain", contacts, gaps)
            chain_times.setdefault(n_balls, []).append(time.perf_counter() - began)
    elapsed = time.perf_counter() - start
    per_solve = elapsed / len(tally.records)
    ratio, converged = tally.column(1), tally.column(2).astype(bool)
    reasons = tally.column(3)
    existing = ratio >= RATIO_FLOOR
    coupled = np.array(tally.coupled)
    single = existing & ~coupled
    run.check(**B2B, quantity=f"converged fraction of free balls where the spin-capacity ratio >= "
              f"{RATIO_FLOOR} ({int(single.sum())} of {len(ratio)} solves)", unit="1",
              value=float(np.mean(converged[single])), reference=1.0, tolerance=0.0,
              source="a state exists there (docs/b2b_bearing.md, validity)", time_s=per_solve)
    pairs = existing & coupled
    coupled_fraction = float(np.mean(converged[pairs])) if np.any(pairs) else 1.0
    stick = np.array([reason.startswith((bearing_ball.STICK_REASON, b2b_relaxation.STALL_REASON))
                      for reason in reasons])
    run.check(**B2B, quantity=f"touching balls, spin-capacity ratio >= {RATIO_FLOOR} ({int(pairs.sum())} "
              "solves): fraction converged or ended where a contact stops sliding", unit="1",
              value=float(np.mean((converged | stick)[pairs])) if np.any(pairs) else 1.0, reference=1.0,
              tolerance=0.0, time_s=per_solve,
              source="the end of the full-sliding branch (a contact's slip speed crosses 0, "
              "docs/b2b_bearing.md 'validity') is the existence bound for touching balls")
    relaxed = np.array([bool(verdict) for verdict in tally.relaxed])
    run.check(**B2B, quantity=f"failures with touching balls without a reason from the relaxation in time "
              f"({int(np.sum(~converged & coupled))} failures with B2B contact)", unit="count",
              value=float(np.sum(~converged & coupled & ~relaxed)), reference=0.0, scale=1.0, tolerance=0.0,
              why="a count: tolerance 0, so a single failure without the relaxation's verdict fails; the scale is one "
              "solve", source="existence oracle (lowmodel.b2b_relaxation): settled, a contact stops sliding, a third "
              "contact, a cycle", time_s=per_solve)
    run.check(**B2B, quantity="failures without a reason", unit="count",
              value=float(np.sum(~converged & (reasons == ""))), reference=0.0, scale=1.0, tolerance=0.0,
              why="a count: tolerance 0, so a single failure without a reason fails; the scale is one solve",
              source="docs/b2b_bearing.md: ConvergenceError names the reason", time_s=per_solve)
    finite = tally.column(8).astype(bool)
    run.check(**B2B, quantity="converged solves returning NaN", unit="count",
              value=float(np.sum(converged & ~finite)), reference=0.0, scale=1.0, tolerance=0.0,
              why="a count: tolerance 0, so a single NaN fails; the scale is one solve",
              source="stability requirement (docs/b2b_bearing.md)", time_s=per_solve)
    power = tally.column(7)
    run.check(**B2B, quantity="worst power balance error, converged solves", unit="1",
              value=float(np.nanmax(power[converged])), reference=0.0, scale=1.0, tolerance=1e-8,
              why="the value is itself a relative power error (per unit input power): zero judged on the scale 1",
              source="energy conservation incl. B2B loss (lin2019 eq 7)", time_s=per_solve)
    iterations, residuals = tally.column(4), tally.column(5)
    run.check(**B2B, quantity="worst final residual, converged solves (units mu max F and v)", unit="1",
              value=float(np.max(residuals[converged])), reference=1e-12, relation="le", tolerance=0.0,
              source="solver tolerance 1e-12", time_s=per_solve)
    _spin_capacity_boundary(run)
    _stick_boundary(run, sizes["stick_steps"])
    _loss_of_contact(run)
    families = ("grid", "load", "mu", "chain")
    summary = "; ".join(
        f"{family}: {int(np.sum(tally.column(2, family)))} of {len(tally.column(2, family))} converged, "
        f"{int(np.sum(tally.column(6, family)))} by continuation, iterations median "
        f"{int(np.median(tally.column(4, family)))} max {int(np.max(tally.column(4, family)))}" for family in families)
    failures = {}
    for record in tally.records:
        if not record[2]:
            failures[record[3]] = failures.get(record[3], 0) + 1
    timing = ", ".join(f"{n}: {1e3 * float(np.median(t)):.0f} ms" for n, t in sorted(chain_times.items()))
    pair_failures = [f for f in tally.failures if f[2] >= RATIO_FLOOR]
    run.note(f"Touching balls: {int(pairs.sum())} solves with B2B contact and every ball's spin-capacity "
             f"ratio >= {RATIO_FLOOR}, of which {100 * coupled_fraction:.1f} % converged; failures: "
             + ("; ".join(f"{f[0]}, {f[1]} balls, mu = {f[5]:.3g}, ratio {f[2]:.2f}: {f[3]} (last converged "
                          f"{f[4]}, smallest slip speed there {f[6]:.2g} |v|; {f[7]})" for f in pair_failures)
                or "none")
             + ".  The single-ball ratio is not an existence bound for touching balls (the B2B force and its "
             "friction moment use friction capacity too); the bound is the end of the full-sliding branch, where "
             "a contact's slip speed reaches 0 (docs/b2b_bearing.md, 'validity').")
    verdicts = {}
    for record, is_coupled, verdict in zip(tally.records, tally.coupled, tally.relaxed):
        if not record[2] and is_coupled:
            verdicts[verdict] = verdicts.get(verdict, 0) + 1
    run.note("Relaxation in time of every failed solve with touching balls (lowmodel.b2b_relaxation): "
             + (", ".join(f"{count} x {kind}" for kind, count in verdicts.items()) or "no such failure") + ". "
             "These are the full-sliding model's limits, not the bearing's: where it has no state the friction of "
             "record is the stick/slip law (lowmodel.bearing_results.guide_states; docs/b2b_rolling.md, 'Where full "
             "sliding has no state').")
    run.note(f"{len(tally.records)} solves in {elapsed:.1f} s. {summary}. Failures by reason: {failures or 'none'} "
             f"(all at spin-capacity ratio < {RATIO_FLOOR}: "
             f"{bool(np.all(ratio[~converged] < RATIO_FLOOR)) if np.any(~converged) else 'no failures'}). "
             f"Worst residual {np.max(residuals[converged]):.2e}, iterations up to {int(np.max(iterations))}. "
             f"Chain solve times (median): {timing}.")
    _figure(run, grid, n_theta, n_rho)


def _spin_capacity_boundary(run) -> None:
    """Bisection of the last converged rho towards the four-point limit against ratio = 1."""
    for theta_deg in (1.0, 2.0, 3.0):
        theta = math.radians(theta_deg)
        low, _ = fourpoint.contact_limits(_case(theta, 0.0).contact_angles[0])
        ok, bad = 0.3, 1e-9
        began = time.perf_counter()
        for _ in range(16):  # bisection in log(margin) on ball 1 alone
            mid = math.sqrt(ok * bad)
            try:
                bearing_ball.solve(_case(theta, float(low) + mid))
                ok = mid
            except ConvergenceError:
                bad = mid
        ratio = float(bearing_contacts.spin_capacity_ratio(_case(theta, float(low) + ok))[0])
        run.check(**BALL, quantity=f"spin-capacity ratio at the last converged rho, theta = {theta_deg:.0f} "
                  "deg", unit="1", value=ratio, reference=1.0, tolerance=0.03,
                  time_s=(time.perf_counter() - began) / 16,
                  source="moment balance along the loaded diagonal (docs/b2b_bearing.md, validity)",
                  note="tolerance: the bound neglects the misalignment theta of the diagonal")


def _stick_boundary(run, steps: int) -> None:
    """Two touching balls, theta = 3 deg, rho = -0.7 (spin-capacity ratio 4.2): the solve at mu = 0.5 (inside the gap
    between the branch that ends at 0.4675 and the one that begins at 0.565, docs/b2b_bearing.md) must fail and
    say that a contact stops sliding; its mu continuation path brackets the end of the branch (last converged s,
    and s + 2 min_step where the step control gave up); ``steps`` bisection steps in that bracket; at the last
    converged mu a contact's slip speed must be ~0 (the full-sliding branch ends there)."""
    theta = math.radians(3.0)
    target = 0.5
    began = time.perf_counter()
    solves = 1
    try:
        b2b.solve(_case(theta, -0.7, 2, friction_coefficient=target), [0.0])
        failure = None
    except ConvergenceError as error:
        failure = error
    run.check(**B2B, quantity=f"failure at mu = {target} (theta = 3 deg, rho = -0.7, two touching balls) "
              "names the stick boundary", unit="1",
              value=float(failure is not None and failure.reason.startswith((bearing_ball.STICK_REASON,
                                                                             b2b_relaxation.STALL_REASON))),
              reference=1.0, tolerance=0.0, time_s=time.perf_counter() - began,
              source="docs/b2b_bearing.md: a failure is proven to be no-state, reason given")
    ok, bad = 0.4, target
    if failure is not None and failure.last_converged and failure.last_converged[0] == "s (mu)":
        s_last = failure.last_converged[1]

        def mu_at(s):
            return target * b2b.MU_PATH_START ** (s - 1.0)  # the mu path of b2b.solve
        ok, bad = mu_at(s_last), mu_at(min(1.0, s_last + 2.0 / 1024.0))  # 1/1024: the continuation's min step
    ok_state = b2b.solve(_case(theta, -0.7, 2, friction_coefficient=ok), [0.0])
    for _ in range(steps):
        mid = 0.5 * (ok + bad)
        solves += 1
        try:
            ok_state, ok = b2b.solve(_case(theta, -0.7, 2, friction_coefficient=mid), [0.0]), mid
        except ConvergenceError:
            bad = mid
    slip = np.hypot(ok_state.slide, ok_state.spin * _case(theta, -0.7, 2).semi_major) / GUIDE.groove_velocity
    run.check(**B2B, quantity=f"smallest contact slip speed / v at the last converged mu = {ok:.6f} "
              f"(next failing {bad:.6f}; theta = 3 deg, rho = -0.7, two touching balls)", unit="1",
              value=float(np.min(slip)), reference=0.0, scale=1.0, tolerance=1e-3,
              time_s=(time.perf_counter() - began) / (solves + 1),
              why="a slip speed per unit groove speed: zero judged on the scale 1 (the other contacts slip at "
              "0.02 to 0.5 v)", source="end of the full-sliding branch (docs/b2b_bearing.md, validity)")


def _loss_of_contact(run) -> None:
    """ValueError exactly at the lin2017 eq 37 limit (bisection from both sides)."""
    theta = math.radians(3.0)
    low = -math.tan(math.pi / 4 - theta)  # ball 1: -min(tan beta_BL, tan beta_TR), beta_BL = 45 deg - theta
    inside, outside = low + 0.05, low - 0.05
    _, setup_time = run.time(_case, theta, inside, 2)
    for _ in range(60):
        mid = 0.5 * (inside + outside)
        try:
            _case(theta, mid, 2)
            inside = mid
        except ValueError:
            outside = mid
    run.check(**B2B, quantity="rho at which ValueError (loss of four-point contact) starts", unit="1",
              value=outside, reference=low, tolerance=1e-12, source="lin2017 eq 37: rho >= -min(tan beta_BL, "
              "tan beta_TR), theta = 3 deg", time_s=setup_time)


def _figure(run, grid, n_theta, n_rho) -> None:
    theta = np.array([g[0] for g in grid]).reshape(n_theta, n_rho)
    rho = np.array([g[1] for g in grid]).reshape(n_theta, n_rho)
    ratio = np.array([g[3] for g in grid]).reshape(n_theta, n_rho)
    converged = np.array([g[4] for g in grid]).reshape(n_theta, n_rho)
    run.save_figure(converged_region(rho, theta, ratio, converged, RATIO_FLOOR), "converged_region.png")
