"""Scenes of a case file that do not apply to the case (status ``not applicable``): the verdict, its reason with
the case's number, and what every output says (docs/your_own_bearing.md, 'Reading the verdict';
docs/validation.md, 'Does not apply')."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

from ballbench.lowmodel import bearing_results
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.validation import cli, ladder
from ballbench.validation.ladder import common
from ballbench.validation.cases import case_file
from ballbench.validation.runner import run_scene, run_scenes
from ballbench.validation.scene import NotApplicable, Scene
from tests import paths

# the new user's walk-through: the ball-screw template with three values edited (docs/your_own_bearing.md)
PRELOAD_LOSS_N = 127.6  # lowmodel.screw.preload of the walk-through screw (frictionless, lin2019 eq 53)


def _screw_file(tmp_path, axial_load: str):
    text = case_file.template("ball-screw")
    for old, new in (('pitch_radius = "16.6 mm"', 'pitch_radius = "20 mm"'),
                     ("conformity = 0.55 ", "conformity = 0.54 "),
                     ('axial_load = "100 N"', f'axial_load = "{axial_load}"')):
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "s.toml"
    path.write_text(text)
    return path


def _scene(case, name, top="stick-slip"):
    (scene,) = [s for s in ladder.case_scenes(case, "s", top=top) if s.name == f"s-{name}"]
    return scene


def test_the_preload_loss_of_the_walk_through_screw(tmp_path):
    case = case_file.load(_screw_file(tmp_path, "300 N"))
    loss = common.preload_loss(case)
    assert loss.axial_load == pytest.approx(PRELOAD_LOSS_N, abs=0.05)
    assert (loss.ball, loss.contact) == (1, "NL")  # the deviated ball's nut flank goes first


def test_the_fe_module_does_not_apply_where_lin2019_leaves_a_contact_unloaded(tmp_path):
    # 300 N, 1.5 um: lin2019's state leaves SR of both balls without load; the FE module needs all four
    case = case_file.load(_screw_file(tmp_path, "300 N"))
    result = run_scene(_scene(case, "b2b-fe"), "quick", tmp_path / "out")
    assert not result.error, result.error
    assert result.status() == "not applicable" and result.passed
    assert result.status(strict=True) == "fail"
    assert "ball 1 SR" in result.not_applicable and "lin2017 eq 37" in result.not_applicable
    assert f"preload loss at {PRELOAD_LOSS_N:g} N" in result.not_applicable
    # show skips it with the reason instead of solving a module it cannot build
    with pytest.raises(NotApplicable, match="needs all four contacts"):
        _scene(case, "b2b-fe").show(tmp_path / "out" / "s-b2b-fe", "quick")


def test_past_the_preload_loss_the_balls_run_on_the_stick_slip_law_and_the_run_passes(tmp_path, capsys):
    path = _screw_file(tmp_path, "450 N")
    out = tmp_path / "report"
    code = cli.main(["validate", str(path), "--quick", "--levels", "low-order", "--no-progress", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 0, err
    # before any work, the header says where the axial load stands against the preload loss
    head = err[:err.index("PASS s-balls")]
    assert f"preload loss at {PRELOAD_LOSS_N:g} N" in head and "450 N is past it" in head
    assert "s-balls gives the friction by the stick/slip law" in head
    assert "s-contact runs on the loads of the frictionless statics" in head
    assert "two-point contact past the preload loss" in head
    data = json.loads((out / "results.json").read_text())
    assert data["passed"] and data["counts"]["not applicable"] == 0 and data["counts"]["error"] == 0
    scenes = {scene["name"]: scene for scene in data["scenes"]}
    balls = scenes["s-balls"]
    assert balls["status"] == "pass" and not balls["error"]
    notes = " ".join(balls["notes"])
    assert "stick/slip on a half-space" in notes and "load ramp stopped" in notes and "frictionless statics" in notes
    titles = [table["title"] for table in balls["tables"]]
    assert any(t.startswith("Friction torque on the nut (contact law: stick/slip") for t in titles), titles
    assert any(t.startswith("Contact law per ball and contact") for t in titles), titles
    # the contact rung runs on the frictionless two-point statics, and says so and why
    contact = scenes["s-contact"]
    assert contact["status"] != "not applicable" and contact["passed"] and not contact["error"]
    notes = " ".join(contact["notes"])
    assert "frictionless statics" in notes and "not those of lin2019's friction model" in notes
    assert "450 N is past the preload loss at 127.6 N" in notes
    assert contact["tables"][0]["title"].startswith("Per ball and contact (frictionless two-point statics")


def test_a_small_screw_whose_load_ramp_stops_at_its_first_step_runs_the_contact_rung(tmp_path, capsys):
    """A screw of 3/16-inch balls (R_B 2.381 mm, R_P 12.5 mm, lead 5 mm, f 0.54, 1.5 um, mu 0.05) at 300 N axial
    load: lin2019's load ramp starts at 100 N per ball, already past this screw's preload loss (111 N), and stops
    at its first step ("load ramp stopped (a contact slides fully)").  That is the model's limit, not a fault:
    -balls gives the friction by the stick/slip law on the frictionless loads (it did not apply; before that it ended
    in ERROR), -contact runs on the frictionless statics (it ended in ERROR)."""
    text = case_file.template("ball-screw")
    for old, new in (('ball_radius = "3.175 mm"', 'ball_radius = "2.381 mm"'),
                     ('pitch_radius = "16.6 mm"', 'pitch_radius = "12.5 mm"'), ('lead = "10 mm"', 'lead = "5 mm"'),
                     ("conformity = 0.55 ", "conformity = 0.54 "),
                     ("friction_coefficient = 0.1 ", "friction_coefficient = 0.05 "),
                     ('axial_load = "100 N"', 'axial_load = "300 N"')):
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / "small.toml"
    path.write_text(text)
    with pytest.raises(ConvergenceError, match="load ramp stopped") as caught:
        bearing_results.screw_states(case_file.load(path))
    assert caught.value.reason == screw_b2b.RAMP_STOP.format("a contact slides fully")
    assert common.no_state_reason(caught.value.reason)
    assert not common.no_state_reason(screw_b2b.RAMP_STOP.format("Newton diverged"))
    out = tmp_path / "report"
    code = cli.main(["validate", str(path), "--quick", "--levels", "analytical", "--no-progress", "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    scenes = {scene["name"]: scene for scene in json.loads((out / "results.json").read_text())["scenes"]}
    assert scenes["small-balls"]["status"] == "pass"  # the stick/slip law on the frictionless loads
    result = bearing_results.friction(case_file.load(path))
    assert result.law == bearing_results.STICK_SLIP and "load ramp stopped" in result.law_reason
    assert result.friction_torque > result.friction_torque_free > 0.0
    contact = scenes["small-contact"]
    assert contact["passed"] and not contact["error"] and contact["status"] != "not applicable"
    assert "frictionless statics" in " ".join(contact["notes"])


@pytest.mark.parametrize("theta, rho, vertical, mu, words", [
    ("1.5 deg", -0.9, "300 N", 0.2, "spin-capacity ratio < 1"),
    ("2.87 deg", -0.83, "128 N", 0.604, "a contact stops sliding (full-sliding branch ends")])
def test_a_guide_without_a_full_sliding_state_gets_its_friction_from_the_stick_slip_law(
        tmp_path, theta, rho, vertical, mu, words):
    """lin2019 Table 1's guide near the four-point limit, where the full-sliding model has no state (a free ball's
    spin-capacity ratio 0.738 < 1; the hard case whose branch ends at mu 0.145): -balls gives the friction by the
    stick/slip law and says why (it did not apply, and before that ended in ERROR); -b2b-fe, built on full sliding,
    does not apply and says where the friction is; -contact runs on the lin2017 eq 36 loads, which friction does not
    change.  The eq 36 loads are those of lin2019's state wherever it has one."""
    from ballbench.validation.ladder import rungs

    text = (paths.ROOT / "validation" / "cases" / "files" / "lin2019-table3-a.toml").read_text()
    text = text[:text.index("[fe]")]
    for old, new in (('vertical_force = "100 N"', f'vertical_force = "{vertical}"'),
                     ("side_force_ratio = -0.6", f"side_force_ratio = {rho}"),
                     ("friction_coefficient = 0.1 ", f"friction_coefficient = {mu} "),
                     ('bottom_left = "-2 deg"', f'bottom_left = "-{theta}"'),
                     ('bottom_right = "2 deg"', f'bottom_right = "{theta}"')):
        assert old in text, old
        text = text.replace(old, new)
    case = case_file.load(_write(tmp_path / "g.toml", text))
    with pytest.raises(ConvergenceError):
        b2b.solve(b2b.contacts(case), [0.0])
    balls = run_scene(_scene(case, "balls"), "quick", tmp_path / "balls")
    assert balls.passed and not balls.error and balls.status() != "not applicable", balls.error
    notes = " ".join(balls.notes)
    assert bearing_results.STICK_SLIP in notes and words in notes
    judged = {c.quantity for c in balls.outputs}
    assert {"friction force, balls touching (grid error of the stick/slip solve)",
            "power balance (input - losses)/input, balls touching"} <= judged
    fe = run_scene(_scene(case, "b2b-fe"), "quick", tmp_path / "b2b-fe")
    assert fe.status() == "not applicable" and not fe.error, fe.error
    assert words in fe.not_applicable and "-balls" in fe.not_applicable and "lin2017 eq 36" in fe.not_applicable
    contact = run_scene(_scene(case, "contact", top="BEM"), "quick", tmp_path / "contact")
    assert contact.passed and not contact.error and contact.status() != "not applicable"
    # where the model has a state, the eq 36 loads are its loads
    state = bearing_results.guide_result(case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml"))
    loads = bearing_results.guide_contacts(case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml"))
    assert loads.contacts == state.contacts and state.law == bearing_results.FULL_SLIDING
    assert rungs.distinct_contacts(case, bearing_results.guide_contacts(case))[0].contact.force == max(
        c.normal_force for c in bearing_results.guide_contacts(case).contacts)


def test_the_stick_slip_rung_gives_the_law_alone_where_full_slip_on_its_cells_has_no_state(tmp_path):
    """The hard guide (theta 2.87 deg, rho -0.83, 128 N, mu 0.604): full slip on the rung's cells has no state, so
    there is nothing to compare; the rung gives the stick/slip states alone with their power balance (it ended in
    ERROR)."""
    text = (paths.ROOT / "validation" / "cases" / "files" / "lin2019-table3-a.toml").read_text()
    text = text[:text.index("[fe]")]
    for old, new in (('vertical_force = "100 N"', 'vertical_force = "128 N"'),
                     ("side_force_ratio = -0.6", "side_force_ratio = -0.83"),
                     ("friction_coefficient = 0.1 ", "friction_coefficient = 0.604 "),
                     ('bottom_left = "-2 deg"', 'bottom_left = "-2.87 deg"'),
                     ('bottom_right = "2 deg"', 'bottom_right = "2.87 deg"')):
        text = text.replace(old, new)
    case = case_file.load(_write(tmp_path / "g.toml", text))
    result = run_scene(_scene(case, "stick-slip"), "quick", tmp_path / "out")
    assert result.passed and not result.error and result.status() != "not applicable", result.error
    assert any("Full slip on the same cells has no state" in note for note in result.notes)
    assert {"power balance |P_in - P_loss| / P_in, balls touching"} <= {c.quantity for c in result.outputs}


def _write(path, text):
    path.write_text(text)
    return path


def test_junit_skips_a_scene_that_does_not_apply(tmp_path):
    """Past the preload loss (450 N) the FE module does not apply (lin2019's state leaves contacts unloaded): JUnit
    skips it with the reason, and the balls' scene (the stick/slip law) passes."""
    from ballbench.validation.report import to_junit

    case = case_file.load(_screw_file(tmp_path, "450 N"))
    results = [run_scene(_scene(case, name), "quick", tmp_path / name) for name in ("balls", "b2b-fe")]
    path = tmp_path / "junit.xml"
    path.write_bytes(to_junit(results))
    suite = ET.parse(path).getroot()
    assert suite.get("skipped") == "1" and suite.get("errors") == "0" and suite.get("failures") == "0"
    skipped = {case.get("name"): case.find("skipped") for case in suite.iter("testcase")}
    assert skipped["s-b2b-fe"].get("message").startswith("does not apply: axial load 450 N")
    assert skipped["s-balls"] is None


def _contact_loads(case, tmp_path, monkeypatch, top="analytical"):
    """The result of the -contact scene of ``case`` and the forces [N] of the contacts it ran (by pair)."""
    from ballbench.validation.ladder import rungs

    seen = {}
    hertz_values = rungs.hertz_values

    def spy(contact):
        seen[contact.pair] = contact.force
        return hertz_values(contact)

    monkeypatch.setattr(rungs, "hertz_values", spy)
    result = run_scene(_scene(case, "contact", top=top), "quick", tmp_path / "out")
    assert not result.error, result.error
    return result, seen


def _largest_per_side(forces):
    return {"screw": float(forces[:, :2].max()), "nut": float(forces[:, 2:].max())}


def test_past_the_preload_loss_the_contact_rung_runs_on_the_frictionless_statics(tmp_path, monkeypatch):
    from ballbench.lowmodel.screw import preload
    from ballbench.lowmodel.screw import b2b as screw_b2b

    case = case_file.load(_screw_file(tmp_path, "450 N"))
    result, seen = _contact_loads(case, tmp_path, monkeypatch)
    assert result.status() == "pass" and not result.not_applicable
    state = preload.frictionless_statics(screw_b2b.contacts(case), 450.0)
    assert seen == _largest_per_side(state.normal_force)  # the very loads of the frictionless solve
    assert state.normal_force[0, 1] == 0.0 and state.normal_force[0, 3] == 0.0  # two-point contact


@pytest.mark.parametrize("load", ["100 N", "300 N"])
def test_where_lin2019_has_a_state_the_contact_rung_runs_on_it(tmp_path, monkeypatch, load):
    # below the preload loss (100 N, four-point) and past it where lin2019's ramp still finds a state (300 N):
    # the loads of lin2019's state, as before, and no word of the frictionless statics
    from ballbench.lowmodel import bearing_results

    case = case_file.load(_screw_file(tmp_path, load))
    states = []
    screw_result = bearing_results.screw_result

    def spy(*args, **kwargs):  # lin2019's state the scene solves (solved once)
        states.append(screw_result(*args, **kwargs))
        return states[-1]

    monkeypatch.setattr(bearing_results, "screw_result", spy)
    result, seen = _contact_loads(case, tmp_path, monkeypatch)
    (state,) = states
    assert state.model == "lowmodel.screw.b2b"
    assert seen == {pair: max(c.normal_force for c in state.contacts if c.contact[0] == pair[0].upper())
                    for pair in ("screw", "nut")}
    assert not any("frictionless statics" in note for note in result.notes)
    # the header speaks of the frictionless statics past the preload loss only (there, where lin2019 finds no state)
    header = " ".join(common.limits_lines(case, ["s-contact"]))
    assert ("s-contact runs on the loads of the frictionless statics" in header) == (load == "300 N")


@pytest.mark.slow
def test_past_the_preload_loss_the_contact_scene_passes_up_to_the_bem(tmp_path, monkeypatch):
    # the walk-through's -contact at --levels BEM (about 40 s): Hertz and the BEM on the exact helical gap at the
    # frictionless loads; a Hertz miss against the BEM is a finding, not a failure
    from ballbench.lowmodel.screw import preload
    from ballbench.lowmodel.screw import b2b as screw_b2b

    case = case_file.load(_screw_file(tmp_path, "450 N"))
    result, seen = _contact_loads(case, tmp_path, monkeypatch, top="BEM")
    assert result.status() in ("pass", "findings") and result.passed
    state = preload.frictionless_statics(screw_b2b.contacts(case), 450.0)
    assert seen == _largest_per_side(state.normal_force)


def _raise(reason):
    def solve(*args, **kwargs):
        raise ConvergenceError("no converged state", residual=1.0, iterations=3, tolerance=1e-10, reason=reason,
                               last_converged=("load fraction", 0.5))
    return solve


@pytest.mark.parametrize("load, reason", [("450 N", "no descent step"), ("100 N", screw_b2b.FULL_SLIDING_LIMIT)])
def test_where_lin2019_finds_no_state_the_balls_answer_by_the_stick_slip_law_and_keep_its_words(
        tmp_path, monkeypatch, load, reason):
    # lin2019's solve stopped (past the preload loss for a reason of its solver; below it at its declared limit):
    # the stick/slip law on the frictionless loads answers, the scene says what lin2019's solve said
    case = case_file.load(_screw_file(tmp_path, load))
    monkeypatch.setattr(screw_b2b, "solve", _raise(reason))
    result = run_scene(_scene(case, "balls", top="low-order"), "quick", tmp_path / "out")
    assert result.status() == "pass" and not result.error, result.error
    notes = " ".join(result.notes)
    assert "stick/slip on a half-space" in notes and "no converged state" in notes and reason in notes


def test_a_failure_of_the_stick_slip_law_too_stays_an_error(tmp_path, monkeypatch):
    from ballbench.lowmodel.screw import b2b_rolling as screw_rolling

    case = case_file.load(_screw_file(tmp_path, "450 N"))
    monkeypatch.setattr(screw_b2b, "solve", _raise(screw_b2b.FULL_SLIDING_LIMIT))
    monkeypatch.setattr(screw_rolling, "solve", _raise("no descent step"))
    result = run_scene(_scene(case, "balls", top="low-order"), "quick", tmp_path / "out")
    assert result.status() == "error" and "ConvergenceError" in result.error and not result.not_applicable


def test_a_paper_scene_still_errors_on_the_declared_limit(tmp_path, monkeypatch):
    from ballbench.validation.scene import registry

    monkeypatch.setattr(screw_b2b, "solve", _raise(screw_b2b.FULL_SLIDING_LIMIT))
    result = run_scene(registry()["lin2019-table5-a"], "quick", tmp_path)
    assert result.status() == "error" and "ConvergenceError" in result.error and not result.not_applicable


def test_only_a_case_file_s_scene_may_not_apply(tmp_path):
    def unfit(run):
        raise NotApplicable("the model has no state here")

    paper = run_scene(Scene("zz-paper", "a registered scene", unfit), "quick", tmp_path)
    assert paper.status() == "error" and paper.error.startswith("NotApplicable")
    case = run_scene(Scene("zz-case", "a case file's scene", unfit, tags=("case",)), "quick", tmp_path)
    assert case.status() == "not applicable" and case.not_applicable == "the model has no state here"
    with pytest.raises(ValueError, match="reason"):
        NotApplicable(" ")


def test_the_module_fe_does_not_start_a_level_beyond_the_memory(tmp_path, monkeypatch):
    # the module FE's memory guard (as the contact FE's): the level's predicted peak above the available memory
    from ballbench.validation.ladder import rungs
    from ballbench.validation.studies import fe_b2b_linear
    from tests import paths

    def no_solve(*args, **kwargs):
        raise AssertionError("a module level ran although its predicted memory exceeds the available memory")

    monkeypatch.setattr(fe_b2b_linear, "level_dofs", lambda case, level: 400_000)
    monkeypatch.setattr(fe_b2b_linear, "solve_fe_level", no_solve)
    monkeypatch.setattr(rungs, "available_memory", lambda: 4e9)
    monkeypatch.setattr(rungs, "predicted_memory", lambda ndofs, *_: 9e9 if ndofs == 400_000 else 0.0)
    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    (scene,) = [s for s in ladder.case_scenes(case, "g", top="FE-informed") if s.name == "g-b2b-fe"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert result.status() == "error" and result.error.startswith("MemoryError")
    assert "400000 P2 DOFs" in result.error and "9.0 GB" in result.error and "4.0 GB available" in result.error


def test_the_ball_screw_template_states_the_range_of_lin2019_s_model():
    text = case_file.template("ball-screw")
    loss = common.preload_loss(case_file.loads(text))
    at = text.index('axial_load = "')
    comment = text[at:text.index("deviations =")]
    assert f"below the preload loss: {loss.axial_load:.0f} N" in comment and "oversize^1.5" in comment
    # the template's own example lies in that range (a new user's first run is the model's four-point regime)
    assert case_file.loads(text).axial_load < loss.axial_load
