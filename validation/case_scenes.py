"""Scenes generated from a case file: ``ballbench validate my_guide.toml`` runs the validation ladder on one's own
bearing (studies.ladder) with the same harness, report, ``show`` pictures and VTU as the paper scenes.

This module is a factory, not a scene module: it builds :class:`~ballbench.validation.scene.Scene` objects from a
case (they are not registered; the CLI runs them beside or instead of the registered scenes).  A case file gives:

* ``<stem>-balls`` (linear guide, ball screw): the low-order numerical model of the balls, touching and free:
  loads, angles, ellipses and pressures per ball and contact, the friction force [N] or torque [N m] with and
  without B2B contact, the friction increase, the B2B forces (studies.bearing_results); power balance and statics
  checks; for a guide the analytical B2B model (lin2019 eq 30) against the numerical one;
* ``<stem>-contact``: the most loaded contact (or the case's own contact) up the ladder: exact Hertz, the BEM on
  the exact gap on two or three grids, the FE on three or more meshes sized from its ellipse, the Richardson
  extrapolation of the FE study with its uncertainty as the reference, every model's error against it and its run
  time; its fields (fields.vtu) and 3D screenshots;
* ``<stem>-b2b-fe`` (linear guide, ball screw; rung ``FE-informed``): the FE modules of the two balls on meshes from
  their ellipses, the FE-informed B2B force per level and its extrapolation, the reference of the analytical and
  low-order B2B forces; the modules' fields and screenshots.

Every model judged against a higher rung is a *finding* check (``run.check(finding=True)``): a miss says the model is
outside its declared accuracy on this geometry (status ``outside accuracy``; docs/your_own_bearing.md, "Reading the
verdict"), not that the software failed; the solvers' own checks (power balance, statics, load balance) and the
uncertainty of the extrapolated reference stay pass/fail.

``top`` (``--levels``) names the highest rung to run; ``deadline`` (``--budget``, a ``time.monotonic()`` value)
stops refining a mesh study when the next level's predicted time would pass it.
"""
from __future__ import annotations

import functools
import math
import re
import time
from pathlib import Path

import numpy as np

from ballbench.validation.cases.case import BallScrewCase, ContactCase, LinearGuideCase
from ballbench.validation.scene import Scene
from ballbench.lowmodel.state import friction_increase

__all__ = ["case_scenes", "scene_names", "show_case", "slug"]

BUDGET_S = {"quick": 900.0, "default": 1800.0, "fine": 7200.0}  # wall-time budget of a generated FE scene [s]
LOW_BUDGET_S = {"quick": 60.0, "default": 60.0, "fine": 60.0}   # of a generated scene without FE [s]
REFERENCE_UNCERTAINTY = 0.01  # the extrapolated FE reference must be known to 1 % to judge models against it
B2B_TOLERANCE = {"linear-guide": 0.07, "ball-screw": 0.10}  # lin2019's own claims, docs/fe_b2b.md
POWER_TOLERANCE = 1e-6  # docs/fe_b2b.md: energy conservation incl. the B2B loss
# a B2B force below this share of the friction scale mu N (N: the ball load) is "near zero" and judged on that
# share instead of on itself (lin2019 Table 3 case (b): 0.13 % of case (a)); above it the relative error counts
NEAR_ZERO_B2B = 0.05


def slug(path: str | Path) -> str:
    """The scene-name prefix of a case file: its stem in lower case, letters, digits and '-'."""
    text = re.sub(r"[^a-z0-9]+", "-", Path(path).stem.lower()).strip("-")
    return text or "case"


def _kind(case) -> str:
    return ("contact" if isinstance(case, ContactCase) else "linear-guide" if isinstance(case, LinearGuideCase)
            else "ball-screw")


def scene_names(case, stem: str, top: str = "FE-informed") -> list[str]:
    """The names of the scenes :func:`case_scenes` builds."""
    from ballbench.validation.studies.ladder import rungs_up_to

    rungs = rungs_up_to(top)
    names = [] if isinstance(case, ContactCase) else [f"{stem}-balls"]
    names.append(f"{stem}-contact")
    if "FE-informed" in rungs and not isinstance(case, ContactCase):
        names.append(f"{stem}-b2b-fe")
    return names


def case_scenes(case, stem: str, *, top: str = "FE-informed", deadline: float | None = None) -> list[Scene]:
    """The scenes of ``case`` (a LinearGuideCase, BallScrewCase or ContactCase) named ``<stem>-...``, up to the
    rung ``top`` (studies.ladder.RUNGS)."""
    from ballbench.validation.studies.ladder import rungs_up_to

    rungs = rungs_up_to(top)
    kind = _kind(case)
    fe = "FE" in rungs
    scenes = []
    if kind != "contact":
        what = "linear guide" if kind == "linear-guide" else "ball screw"
        scenes.append(Scene(f"{stem}-balls", f"{case.name}: the balls of the {what} by the low-order numerical model "
                            "(loads, angles, ellipses, pressures, friction with and without B2B contact)",
                            functools.partial(_balls, case=case, rungs=rungs), tags=("case",), kind="low-order",
                            cost_s=5.0, budget_s=LOW_BUDGET_S, case=case))
    scenes.append(Scene(f"{stem}-contact", f"{case.name}: the most loaded contact up the ladder ("
                        + ", ".join(r for r in rungs if r in ("analytical", "BEM", "FE")) + ")",
                        functools.partial(_contact, case=case, rungs=rungs, deadline=deadline), tags=("case",),
                        kind="FE" if fe else "low-order", cost_s=120.0 if fe else 5.0,
                        budget_s=BUDGET_S if fe else LOW_BUDGET_S, case=case,
                        show=functools.partial(_show_contact, case) if fe else None))
    if "FE-informed" in rungs and kind != "contact":
        scenes.append(Scene(f"{stem}-b2b-fe", f"{case.name}: FE modules of the two balls and the FE-informed B2B "
                            "force per mesh level, extrapolated: the reference of the analytical and low-order models",
                            functools.partial(_b2b_fe, case=case, deadline=deadline), tags=("case",), kind="FE",
                            cost_s=300.0, budget_s=BUDGET_S, case=case, show=functools.partial(_show_module, case)))
    return scenes


def show_case(case, stem: str, out_dir: Path, fidelity: str = "default") -> list[Path]:
    """``ballbench show my_case.toml``: the pictures of every generated scene that has them, drawn from the fields
    ``validate`` saved in ``out_dir/<scene>/`` (solved first only where none are saved)."""
    paths = []
    for scene in case_scenes(case, stem):
        if scene.show is not None:
            paths += scene.show(Path(out_dir) / scene.name, fidelity)
    return paths


# --------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------
def _f(value: float, digits: int = 4) -> str:
    return f"{value:.{digits}g}"


def _contact_table(run, result, what: str) -> None:
    run.table(f"Per ball and contact ({what}, {result.model})",
              ("ball", "contact", "F [N]", "angle [deg]", "a [mm]", "b [mm]", "p0 [MPa]", "approach [um]"),
              [(c.ball, c.contact, _f(c.normal_force), _f(math.degrees(c.contact_angle)), _f(c.a * 1e3),
                _f(c.b * 1e3), _f(c.p0 / 1e6), _f(c.approach * 1e6)) for c in result.contacts])
    run.write_csv("contacts.csv", result.table())


# --------------------------------------------------------------------------
# <stem>-balls: the low-order numerical model of the balls
# --------------------------------------------------------------------------
def _balls(run, *, case, rungs) -> None:
    from ballbench.validation.studies import bearing_results

    if isinstance(case, LinearGuideCase):
        _guide_balls(run, case, rungs, bearing_results)
    else:
        _screw_balls(run, case, bearing_results)


def _power_check(run, model: str, state, time_s: float, what: str) -> None:
    balance = (state.input_power - state.total_loss) / state.input_power
    run.check(model=model, family="low-order numerical", quantity=f"power balance (input - losses)/input, {what}",
              unit="1", value=balance, reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=time_s,
              source="energy conservation incl. the B2B loss (lin2019 eq 7); docs/fe_b2b.md: 1e-6",
              why="the value is itself a relative power error: zero judged on the scale 1")


def _guide_balls(run, case: LinearGuideCase, rungs, bearing_results) -> None:
    from ballbench.lowmodel.linear_bearing import b2b

    guide = case.guide
    contacts = bearing_results.guide_contacts(case)
    model = "lowmodel.linear_bearing.b2b"
    touching, time_touching = run.time(b2b.solve, contacts, np.zeros(case.n_balls - 1))
    free, time_free = run.time(b2b.solve, contacts, np.full(case.n_balls - 1, 1e-3))
    result = bearing_results.guide_result(case, touching, free, contacts)
    _power_check(run, model, touching, time_touching, "balls touching")
    _power_check(run, model, free, time_free, "balls apart")
    statics = _eq36_residual(case, contacts)
    run.check(model=model, family="low-order numerical", quantity="ball statics, max |residual| / N_y", unit="1",
              value=statics, reference=0.0, scale=1.0, tolerance=1e-12, time_s=time_touching,
              source="vertical and lateral balance of each ball with the contact forces along the contact normals "
                     "(lin2017 Fig 2, eq 36)", why="the value is itself a relative force residual")
    if "analytical" in rungs and case.n_balls == 2 and case.deviations[0] == -case.deviations[1]:
        _guide_analytical(run, case, result)
    _contact_table(run, result, "balls touching")
    v = abs(guide.groove_velocity)
    run.table("Friction of the balls (the carriage's drive force over them)",
              ("state", "friction force [N]", "power [W]", "B2B forces [N]", "velocity deviation epsilon [%]"),
              [("balls apart", _f(result.friction_force_free), _f(result.power_free), "-",
                " / ".join(_f(100 * e) for e in result.velocity_deviation_free)),
               ("balls touching", _f(result.friction_force), _f(result.power),
                " / ".join(_f(f) for f in result.b2b_forces), "-"),
               ("friction increase by B2B", _f(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction force = power of the carriage's drive / speed ({_f(v * 1e3)} mm/s), for the {case.n_balls} "
             "balls of the case; free balls: epsilon > 0 on ball 1 (behind) and < 0 on ball 2 makes them touch "
             "(lin2019 Sec 2.4).")


def _eq36_residual(case: LinearGuideCase, contacts) -> float:
    """Largest force residual of the balls' statics with the low-order normal forces [N_y]: with the outward unit
    normals ``n_i`` of lin2017 eq 1 the four forces of a ball balance, ``sum_i F_i n_i = 0``, and its two rail
    contacts (BL, BR) carry the ball's load, ``F_BL n_BL + F_BR n_BR = (N_x, -N_y)`` (lin2017 eq 36)."""
    from ballbench.lowmodel.geometry.fourpoint import contact_normals

    worst = 0.0
    for ball in range(contacts.normal_forces.shape[0]):
        normals = np.asarray(contact_normals(contacts.contact_angles[ball]))  # (4, 2)
        forces = contacts.normal_forces[ball]
        load = np.array([case.side_force(ball), -case.vertical_force])
        residuals = (forces @ normals, forces[:2] @ normals[:2] - load)
        worst = max(worst, *(float(np.max(np.abs(r))) for r in residuals))
    return worst / case.vertical_force


def _guide_analytical(run, case: LinearGuideCase, result) -> None:
    from ballbench.validation.studies import fe_b2b_linear

    guide = case.guide
    analytical, time_a = run.time(fe_b2b_linear.analytical, case)
    numerical = result.b2b_forces[0]
    scale = NEAR_ZERO_B2B * guide.friction_coefficient * case.vertical_force
    run.check(model="lowmodel.linear_bearing.b2b_analytical", family="analytical", quantity="F_B2B", unit="N",
              value=float(analytical.b2b_force), reference=numerical, scale=scale if numerical < scale else 0.0,
              tolerance=B2B_TOLERANCE["linear-guide"], time_s=time_a,
              source="the low-order numerical model (lowmodel.linear_bearing.b2b) of the same case",
              note="k_f = 1.38, Psi from Hertz; lin2019's own claim for eq 30: within 6-7 % of the numerical model",
              why="" if numerical >= scale else "a B2B force near zero judged against 5 % of mu N_y", finding=True)


def _screw_balls(run, case: BallScrewCase, bearing_results) -> None:
    from ballbench.validation.studies import fe_b2b_screw, screw_two_ball

    model = "lowmodel.screw.b2b"
    contacts = screw_two_ball.ball_contacts(case)
    (free, touching), time_s = run.time(screw_two_ball.two_ball, case)
    result = bearing_results.screw_result(case, touching, free, contacts)
    _power_check(run, model, touching, time_s, "balls touching")
    _power_check(run, model, free, time_s, "balls apart")
    shares = fe_b2b_screw.axial_shares(contacts, touching)
    run.check(model=model, family="low-order numerical", quantity="axial balance: sum of the balls' axial loads",
              unit="N", value=float(np.sum(shares)), reference=case.axial_load,
              scale=0.0 if case.axial_load > 0 else 1.0, tolerance=1e-9, time_s=time_s,
              source="the case's axial load on the screw (lin2019 eq 55)",
              why="" if case.axial_load > 0 else "zero axial load judged on 1 N")
    _contact_table(run, result, "balls touching")
    run.table("Friction torque on the nut",
              ("state", "friction torque [N m]", "power [W]", "B2B forces [N]", "axial loads [N]"),
              [("balls apart", _f(result.friction_torque_free), _f(result.power_free), "-", "-"),
               ("balls touching", _f(result.friction_torque), _f(result.power),
                " / ".join(_f(f) for f in result.b2b_forces), " / ".join(_f(s) for s in result.axial_shares)),
               ("friction increase by B2B", _f(100 * result.friction_increase) + " %", "", "", "")])
    run.note(f"Friction torque = input power of the nut / its speed ({_f(case.screw.nut_speed)} rad/s), for the "
             f"{len(case.deviations)} balls of the case; deviation reading {case.reading!r} (docs/ball_screw.md).")


# --------------------------------------------------------------------------
# <stem>-contact: Hertz, BEM, FE study and its extrapolation
# --------------------------------------------------------------------------
def _governing(case) -> ContactCase:
    from ballbench.validation.studies import ladder

    return ladder.contact_fe(ladder.governing_contact(case))


def _contact(run, *, case, rungs, deadline) -> None:
    from ballbench.lowmodel.contact import hertz
    from ballbench.validation.references.richardson import extrapolate
    from ballbench.validation.studies import fe_contact, ladder

    contact = _governing(case)
    run.note(f"Contact: {contact.name}; pair {contact.pair}, R_B {_f(contact.ball_radius * 1e3)} mm"
             + (f", conformity {contact.conformity:g}" if contact.conformity else "") + f", F {_f(contact.force)} N.")
    models = []  # (model, family, level, values, time)
    hertz_model = "lowmodel.contact.hertz"
    ref_hertz, time_h = run.time(ladder.hertz_values, contact)
    models.append((hertz_model, "analytical", "", ref_hertz, time_h))
    geometry = fe_contact.hertz_geometry(contact)
    radius = geometry.reference_radius
    run.check(model=hertz_model, family="analytical", quantity="a / R (Hertz's small-contact assumption)", unit="1",
              value=ref_hertz["a"] / radius, reference=hertz.VALIDITY_RATIO, relation="le", tolerance=0.0,
              time_s=time_h, source="lowmodel.contact.hertz.VALIDITY_RATIO (docs/hertz.md, validity)", finding=True)
    if "BEM" in rungs:
        for n in ladder.BEM_GRIDS[run.fidelity]:
            run.checkpoint()
            values, wall = ladder.timed(ladder.bem_values, contact, n)
            models.append(("lowmodel.contact.halfspace (exact gap)", "BEM", f"{n} x {n}", values, wall))
    fe_rows, fe_results, fe_levels = [], [], []
    if "FE" in rungs:
        pair = fe_contact.pair_model(contact)
        levels = contact.fe.levels[run.fidelity]
        sizes, times = [], []
        for level in run.progress(levels, desc=f"{run.scene.name} FE mesh levels"):
            size = ref_hertz["b"] / level.n
            if deadline is not None and times:
                predicted = ladder.predicted_time(times, sizes, size)
                if time.monotonic() + predicted > deadline:
                    run.note(f"--budget: FE levels from n = b/h {level.n:g} on not run (predicted {predicted:.0f} s "
                             "beyond the budget)")
                    break
            start = time.perf_counter()
            result, ref = fe_contact.solve_level(pair, level)
            wall = time.perf_counter() - start
            sizes.append(size)
            times.append(wall)
            values = {q: float(getattr(result, q)) for q, _ in ladder.QUANTITIES}
            words = f"n = b/h {level.n:g}, growth {level.growth:g}"
            models.append(("fem.contact", "FE", words, values, wall))
            fe_rows.append(dict(n=level.n, growth=level.growth, h_contact=result.h_contact, ndofs=result.ndofs,
                                iterations=result.iterations, residual=result.residual, wall_s=wall,
                                force_sum=result.force_sum, **{f"{q}": v for q, v in values.items()}))
            if fe_results and fe_results[-1].model.factor is not None:
                fe_results[-1].model.factor.free()  # only the finest level's factor is kept (for the fields)
            fe_results.append(result)
            fe_levels.append(level)
            if deadline is not None and time.monotonic() > deadline:
                run.note("--budget reached after this level")
                break
    reference, source, uncertainty = _contact_reference(run, models, fe_rows, extrapolate)
    if reference is None:
        run.table("Contact by each rung", ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]",
                                           "one evaluation [s]"), _model_rows(models))
        return
    for model, family, level, values, wall in models:
        if values is reference:
            continue  # the model that is the reference (one FE level, or the finest BEM grid): no check of itself
        tolerances = (ladder.FE_TOLERANCES[run.fidelity] if family == "FE" else
                      {q: ladder.BEM_TOLERANCE for q, _ in ladder.QUANTITIES} if family == "BEM"
                      else ladder.HERTZ_TOLERANCES)
        for quantity, unit in ladder.QUANTITIES:
            run.check(model=model, family=family, level=level, quantity=quantity, unit=unit, value=values[quantity],
                      reference=reference[quantity], source=source, tolerance=tolerances[quantity], time_s=wall,
                      note=_tolerance_note(family, run.fidelity), finding=True)
    if fe_results:
        finest = fe_results[-1]
        run.check(model="fem.contact", family="FE", level=models[-1][2], quantity="force_sum", unit="N",
                  value=finest.force_sum, reference=contact.force, tolerance=1e-9, time_s=models[-1][4],
                  source="load equilibrium (sum of contact forces)")
        if uncertainty is not None:
            worst = max(uncertainty.values())
            run.check(model="Richardson extrapolation of the FE study", family="FE", level="h -> 0",
                      quantity="relative uncertainty of the reference, worst of a, b, p0, delta", unit="1",
                      value=worst, reference=REFERENCE_UNCERTAINTY, relation="le", tolerance=0.0,
                      time_s=sum(m[4] for m in models if m[1] == "FE"),
                      source="grid convergence index (references.richardson; Roache 1994)",
                      note="the reference must be known better than the tolerances it judges; a larger value asks "
                           "for finer levels (--fine)")
        run.write_csv("levels.csv", fe_rows)
        _fields(run, contact, finest, fe_levels[-1])
    run.table("Contact by each rung (reference: " + source + ")",
              ("model", "level", "a [mm]", "b [mm]", "p0 [MPa]", "delta [um]", "one evaluation [s]"),
              _model_rows(models) + [("reference", "h -> 0" if uncertainty else "", _f(reference["a"] * 1e3),
                                      _f(reference["b"] * 1e3), _f(reference["p0"] / 1e6),
                                      _f(reference["delta"] * 1e6), "")])


def _model_rows(models) -> list[tuple]:
    return [(m, level or "-", _f(v["a"] * 1e3), _f(v["b"] * 1e3), _f(v["p0"] / 1e6), _f(v["delta"] * 1e6),
             f"{t:.3g}") for m, _, level, v, t in models]


def _tolerance_note(family: str, fidelity: str) -> str:
    if family == "FE":
        return f"tolerance: the {fidelity} level's stated accuracy (docs/fem.md)"
    if family == "BEM":
        return "tolerance: the BEM's stated accuracy at its grids (docs/halfspace.md: 0.5 %)"
    return "tolerance: FE and Hertz agree within it for the papers' contacts (docs/fem.md); a miss flags a contact " \
           "outside Hertz's assumptions"


def _contact_reference(run, models, fe_rows, extrapolate):
    """(reference values, source text, relative uncertainties or None): the extrapolated FE study (>= 2 levels),
    the one FE level, or the finest BEM grid; None when only Hertz ran."""
    from ballbench.validation.studies import ladder

    fe = [m for m in models if m[1] == "FE"]
    if len(fe) >= 2:
        sizes = [r["h_contact"] for r in fe_rows]
        reference, uncertainty, notes = {}, {}, []
        for quantity, _ in ladder.QUANTITIES:
            e = extrapolate(sizes, [r[quantity] for r in fe_rows])
            reference[quantity] = e.value
            uncertainty[quantity] = e.relative_uncertainty
            notes.append(f"{quantity}: {e.note}, U = {100 * e.relative_uncertainty:.2g} %")
        run.note("Reference: Richardson extrapolation of the FE levels (" + "; ".join(notes) + ").")
        return reference, f"FE extrapolated to h -> 0 from {len(fe)} levels (references.richardson)", uncertainty
    if len(fe) == 1:
        run.note("Reference: the one FE level that ran (no extrapolation, its uncertainty unknown).")
        return fe[0][3], f"FE, {fe[0][2]} (one level)", None
    bem = [m for m in models if m[1] == "BEM"]
    if bem:
        run.note("Reference: the finest BEM grid (no FE rung in this run).")
        return bem[-1][3], f"BEM {bem[-1][2]} (finest grid)", None
    run.note("Hertz only (--levels analytical): no reference to judge it against.")
    return None, "", None


def _fields(run, contact: ContactCase, result, level) -> None:
    """fields.vtu and fields.json of the finest FE level that ran (studies.fe_contact.write_fields) and their 3D
    screenshots (figures.render3d), as artifacts of the scene."""
    from ballbench.lowmodel.contact import hertz
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_contact

    ref = hertz.solve_load(fe_contact.hertz_geometry(contact), contact.force)
    for path in fe_contact.write_fields(result, ref, run.path(""), scene_name=run.scene.name, fidelity=run.fidelity,
                                        level=level, material=contact.material):
        run.add_artifact(path)
    for path in render3d.artifacts(run.path(""), run.note):
        run.add_artifact(path)


def _show_contact(case, scene_dir, fidelity: str) -> list[Path]:
    from ballbench.validation.studies import fe_contact

    return fe_contact.show_fields(_governing(case), scene_dir, fidelity, cost_s=60.0)


# --------------------------------------------------------------------------
# <stem>-b2b-fe: FE modules and the FE-informed B2B force
# --------------------------------------------------------------------------
def _b2b_fe(run, *, case, deadline) -> None:
    from ballbench.validation.studies.ladder import module_fe

    if isinstance(case, LinearGuideCase):
        _guide_b2b_fe(run, module_fe(case), deadline)
    else:
        _screw_b2b_fe(run, module_fe(case), deadline)


def _levels(run, case, deadline, solve):
    """Run ``solve(level) -> dict`` over the case's module levels (stopping where the budget would be passed);
    returns the rows."""
    from ballbench.validation.studies import ladder

    rows, sizes, times = [], [], []
    for level in run.progress(case.fe.levels[run.fidelity], desc=f"{run.scene.name} FE module levels"):
        if deadline is not None and times:
            predicted = ladder.predicted_time(times, sizes, level.h_contact)
            if time.monotonic() + predicted > deadline:
                run.note(f"--budget: module levels from h {level.h_contact * 1e6:.0f} um on not run (predicted "
                         f"{predicted:.0f} s beyond the budget)")
                break
        start = time.perf_counter()
        row = solve(level)
        row["wall_s"] = time.perf_counter() - start
        rows.append(row)
        sizes.append(level.h_contact)
        times.append(row["wall_s"])
    return rows


def _b2b_reference(run, rows, key: str = "F_B2B"):
    from ballbench.validation.references.richardson import extrapolate

    if len(rows) >= 2:
        e = extrapolate([r["h_contact_um"] for r in rows], [r[key] for r in rows])
        run.note(f"Reference F_B2B: Richardson extrapolation of the FE-informed levels ({e.note}, U = "
                 f"{e.uncertainty:.3g} N).")
        return e.value, f"FE-informed extrapolated to h -> 0 from {len(rows)} levels", e
    run.note("Reference F_B2B: the one FE-informed level that ran (no extrapolation).")
    return rows[-1][key], "FE-informed, one level", None


def _b2b_checks(run, kind, reference, source, extrapolation, low, rows, scale) -> None:
    tolerance = B2B_TOLERANCE[kind]
    claim = "lin2019's own claim: within 7 % (docs/fe_b2b.md)" if kind == "linear-guide" else \
        "within 10 % (docs/fe_b2b.md)"
    scale = NEAR_ZERO_B2B * scale
    why = "" if abs(reference) >= scale else "a B2B force near zero judged against 5 % of mu times the ball load"
    use_scale = scale if abs(reference) < scale else 0.0
    for model, family, value, time_s in low:
        run.check(model=model, family=family, quantity="F_B2B", unit="N", value=value, reference=reference,
                  scale=use_scale, source=source, tolerance=tolerance, time_s=time_s, note=claim, why=why,
                  finding=True)
    # the finest level is judged; the coarser ones are the convergence study, summarised by the uncertainty of
    # the extrapolation below and listed with their errors in the levels table (_module_table)
    for r in rows[-1:] if extrapolation is not None else ():
        words = f"h {r['h_contact_um']:.0f} um"
        run.check(model=f"FE-informed B2B ({words})", family="FE-informed", level=words, quantity="F_B2B", unit="N",
                  value=r["F_B2B"], reference=reference, scale=use_scale, source=source, tolerance=tolerance,
                  time_s=r["wall_s"], note=claim, why=why, finding=True)
    if extrapolation is not None:
        run.check(model="Richardson extrapolation of the FE-informed levels", family="FE-informed", level="h -> 0",
                  quantity="relative uncertainty of the F_B2B reference", unit="1",
                  value=extrapolation.uncertainty / max(abs(extrapolation.value), scale),
                  reference=REFERENCE_UNCERTAINTY * 5, relation="le", tolerance=0.0,
                  time_s=sum(r["wall_s"] for r in rows),
                  source="grid convergence index (references.richardson; Roache 1994); 5 % against the 7-10 % claims",
                  note="a larger value asks for finer module levels (--fine)")


def _guide_b2b_fe(run, case: LinearGuideCase, deadline) -> None:
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_linear as study

    guide = case.guide
    contacts = study.low_order_contacts(case)
    b2b.solve(contacts, [0.0])  # loads the friction map outside the timed call
    low_state, time_low = run.time(b2b.solve, contacts, [0.0])
    low = [("lowmodel.linear_bearing.b2b", "low-order numerical", float(low_state.b2b_force[0]), time_low)]
    analytical, time_a = run.time(study.analytical, case)
    low.append(("lowmodel.linear_bearing.b2b_analytical", "analytical", float(analytical.b2b_force), time_a))
    kept = {}

    def solve(level):
        model, results, timings = study.solve_fe_level(case, level)
        state = study.fe_informed(case, model, results)
        free = study.fe_informed(case, model, results, gaps=[1e-3])
        kept.update(model=model, results=results, level=level, state=state)
        v = abs(guide.groove_velocity)
        return dict(h_contact_um=level.h_contact * 1e6, growth=level.growth, ndofs=model.ndofs,
                    F_B2B=float(state.b2b_force[0]), friction_force_N=state.input_power / v,
                    friction_force_free_N=free.input_power / v,
                    friction_increase=friction_increase(state, free),
                    power_balance=float(state.power_balance), **{k: float(x) for k, x in timings.items()})

    rows = _levels(run, case, deadline, solve)
    reference, source, extrapolation = _b2b_reference(run, rows)
    _b2b_checks(run, "linear-guide", reference, source, extrapolation, low, rows,
                guide.friction_coefficient * case.vertical_force)
    words = f"h {rows[-1]['h_contact_um']:.0f} um"
    run.check(model=f"FE-informed B2B ({words})", family="FE-informed", level=words,
              quantity="power balance (input - losses)/input", unit="1", value=rows[-1]["power_balance"],
              reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=rows[-1]["wall_s"],
              source="energy conservation incl. B2B loss (lin2019 eq 7; docs/fe_b2b.md: 1e-6)",
              why="the value is itself a relative power error: zero judged on the scale 1")
    _module_table(run, rows, "friction_force_N", "friction force [N]", low_state, guide.groove_velocity, reference)
    run.write_csv("levels.csv", rows)
    render3d.module_artifacts(run, kept["model"], kept["results"], materials=guide.material.pair,
                              case=case.name, level={"h_contact_m": kept["level"].h_contact,
                                                     "growth": kept["level"].growth})


def _module_table(run, rows, key, label, low_state, speed, reference) -> None:
    def error(value):
        return _f(100 * (value / reference - 1.0), 3) + " %" if reference else "-"

    low = float(low_state.b2b_force[0])
    table = [("low-order numerical", "-", "-", _f(low), error(low), _f(low_state.input_power / abs(speed)), "-")]
    table += [(f"FE-informed, h {r['h_contact_um']:.0f} um", str(r["ndofs"]), f"{r['wall_s']:.0f}", _f(r["F_B2B"]),
               error(r["F_B2B"]), _f(r[key]), _f(100 * r["friction_increase"]) + " %") for r in rows]
    table.append(("reference (" + ("h -> 0" if len(rows) >= 2 else "finest level") + ")", "", "", _f(reference), "",
                  "", ""))
    run.table("B2B force and friction by model and mesh level", ("model", "DOFs", "wall [s]", "F_B2B [N]",
                                                                 "F_B2B error", label, "friction increase"), table)


def _screw_b2b_fe(run, case: BallScrewCase, deadline) -> None:
    from ballbench.lowmodel.screw.contacts import CONTACT_NAMES
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_screw as study

    (contacts, free, state), time_low = run.time(study.low_order, case)
    lost = [f"ball {j + 1} {name}" for j, row in enumerate(np.asarray(state.normal_force))
            for name, force in zip(CONTACT_NAMES, row) if not force > 0]
    if lost:
        raise ValueError(f"the FE screw module needs all four contacts of each ball loaded (lin2017 eq 37), but "
                         f"{', '.join(lost)} carry no load at this axial load and oversize; raise the oversize "
                         "(preload) or run --levels FE")
    low = [("lowmodel.screw.b2b", "low-order numerical", float(state.b2b_force[0]), time_low)]
    shares = study.axial_shares(contacts, state)
    kept = {}
    speed = abs(case.screw.nut_speed)

    def solve(level):
        models, results, timings = study.solve_fe_level(case, level, shares)
        informed = study.fe_informed(case, models, results)
        kept.update(models=models, results=results, level=level)
        return dict(h_contact_um=level.h_contact * 1e6, growth=level.growth, ndofs=sum(m.ndofs for m in models),
                    F_B2B=float(informed.b2b_force[0]), friction_torque_Nm=informed.touching.input_power / speed,
                    friction_increase=float(informed.friction_increase) / 100.0,
                    power_balance=float(informed.power_balance), **{k: float(x) for k, x in timings.items()})

    rows = _levels(run, case, deadline, solve)
    reference, source, extrapolation = _b2b_reference(run, rows)
    _b2b_checks(run, "ball-screw", reference, source, extrapolation, low, rows,
                case.screw.friction_coefficient * max(case.axial_load, 1.0))
    words = f"h {rows[-1]['h_contact_um']:.0f} um"
    run.check(model=f"FE-informed B2B ({words})", family="FE-informed", level=words,
              quantity="power balance (input - losses)/input", unit="1", value=rows[-1]["power_balance"],
              reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=rows[-1]["wall_s"],
              source="energy conservation incl. B2B loss (docs/fe_b2b.md: 1e-6)",
              why="the value is itself a relative power error: zero judged on the scale 1")
    _module_table(run, rows, "friction_torque_Nm", "friction torque [N m]", state, speed, reference)
    run.write_csv("levels.csv", rows)
    render3d.module_artifacts(run, kept["models"], kept["results"], materials=case.screw.material.pair,
                              case=case.name, level={"h_contact_m": kept["level"].h_contact,
                                                     "growth": kept["level"].growth})


def _show_module(case, scene_dir, fidelity: str) -> list[Path]:
    from ballbench.validation.figures import render3d
    from ballbench.validation.studies import fe_b2b_linear, fe_b2b_screw
    from ballbench.validation.studies.ladder import module_fe

    if render3d.has_fields(scene_dir):
        return render3d.render(scene_dir)
    show = fe_b2b_linear.show_module if isinstance(case, LinearGuideCase) else fe_b2b_screw.show_module
    return show(module_fe(case), scene_dir, "quick" if fidelity == "quick" else "default")
