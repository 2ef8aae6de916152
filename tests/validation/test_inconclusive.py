"""Scenes of a case file without a conclusive reference at the run's fidelity (status ``inconclusive``): the verdict,
the counts of results.json, the report (markdown, HTML, JUnit), the exit code of ``ballbench validate`` (0; --strict 1)
and a solver's own check that still fails (validation/scene.py, "Inconclusive"; docs/your_own_bearing.md, 'Reading
the verdict')."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

from ballbench.validation import cli, ladder, report
from ballbench.validation.report import results_from_json
from ballbench.validation.runner import run_scene
from ballbench.validation.scene import PASSING, Scene
from tests import paths

REASON = ("no conclusive reference: the uncertainty of the FE reference is 2.1 % in p0 against the 1 % it needs. "
          "What settles it: a finer study: run at the default fidelity (without --quick) or --fine")


def _scene(*, self_check_error: float = 0.0, self_check: bool = True, name: str = "zz-unsure") -> Scene:
    def fn(run):
        if self_check:  # a solver's own check (load equilibrium)
            run.check(model="fem.contact", family="FE", quantity="force_sum", unit="N", value=1.0 + self_check_error,
                      reference=1.0, source="load equilibrium", tolerance=1e-9, time_s=0.0)
        run.inconclusive(REASON)
        run.table("side by side", ("model", "a [mm]"), [("hertz", "0.79"), ("FE", "0.77")])

    return Scene(name, "a case file's contact rung", fn, tags=("case",))


def test_a_scene_without_a_conclusive_reference_is_inconclusive(tmp_path):
    result = run_scene(_scene(), "quick", tmp_path)
    assert not result.error and result.inconclusive == REASON
    assert result.status() == "inconclusive" and result.passed and "inconclusive" in PASSING
    assert result.status(strict=True) == "fail"


def test_an_inconclusive_scene_with_no_other_check_is_no_error(tmp_path):
    # the reference is what is missing, not the scene's work: no "scene recorded no checked output"
    result = run_scene(_scene(self_check=False), "quick", tmp_path)
    assert not result.error and result.status() == "inconclusive"


def test_a_failed_self_check_still_fails_an_inconclusive_scene(tmp_path):
    result = run_scene(_scene(self_check_error=1e-3), "quick", tmp_path)
    assert result.status() == "fail" and not result.passed


def test_an_inconclusive_scene_needs_a_reason(tmp_path):
    def fn(run):
        run.inconclusive(" ")

    result = run_scene(Scene("zz-no-reason", "no reason", fn, tags=("case",)), "quick", tmp_path)
    assert result.status() == "error" and "needs a reason" in result.error


def test_only_a_case_file_s_scene_may_be_inconclusive(tmp_path):
    def fn(run):
        run.inconclusive(REASON)

    result = run_scene(Scene("zz-paper", "a registered scene", fn), "quick", tmp_path)
    assert result.status() == "error" and "only a case file's scene" in result.error


def test_the_report_counts_and_names_an_inconclusive_scene(tmp_path):
    result = run_scene(_scene(), "quick", tmp_path / "run")
    report.write_report([result], tmp_path, "quick", junit=tmp_path / "junit.xml")
    data = json.loads((tmp_path / "results.json").read_text())
    assert data["passed"] and data["counts"]["inconclusive"] == 1 and data["counts"]["pass"] == 0
    (scene,) = data["scenes"]
    assert scene["status"] == "inconclusive" and scene["passed"] and scene["inconclusive"] == REASON
    assert results_from_json(data)[0].inconclusive == REASON  # a re-rendered report keeps it
    text = (tmp_path / "report.md").read_text()
    assert "## Scenes without a conclusive reference at this fidelity" in text
    assert "INCONCLUSIVE (no conclusive reference at this fidelity)" in text and "What settles it" in text
    assert "1 inconclusive (no conclusive reference at this fidelity)" in text
    assert 'class="inconclusive"' in (tmp_path / "report.html").read_text()
    suite = ET.parse(tmp_path / "junit.xml").getroot()
    assert suite.get("skipped") == "1" and suite.get("failures") == "0" and suite.get("errors") == "0"
    assert suite.find("testcase/skipped").get("message") == "inconclusive: " + REASON


def test_validate_exits_0_on_an_inconclusive_scene_and_1_with_strict(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(ladder, "case_scenes", lambda case, stem, top="stick-slip", deadline=None: [_scene()])
    path = str(paths.ROOT / "examples" / "compact_linear_guide.toml")
    out = ["--quick", "--no-progress", "--out", str(tmp_path / "report")]
    assert cli.main(["validate", path, *out]) == 0
    captured = capsys.readouterr()
    said = captured.out + captured.err
    assert "INCONCLUSIVE" in said and "What settles it" in said
    assert "0 of 1 scenes passed" in said and "1 inconclusive" in said
    assert cli.main(["validate", path, "--strict", *out]) == 1
    captured = capsys.readouterr()
    assert "inconclusive (--strict): no conclusive reference" in captured.out + captured.err


@pytest.mark.parametrize("strict", [False, True])
def test_the_junit_of_a_strict_run_fails_an_inconclusive_scene(tmp_path, strict):
    result = run_scene(_scene(), "quick", tmp_path)
    suite = ET.fromstring(report.to_junit([result], strict=strict))
    assert suite.get("failures") == ("1" if strict else "0")


def _guide(tmp_path, force: str):
    from ballbench.validation.cases import case_file

    text = case_file.template("linear-guide")
    assert 'vertical_force = "50 N"' in text
    path = tmp_path / "g.toml"
    path.write_text(text.replace('vertical_force = "50 N"', f'vertical_force = "{force}"'))
    return case_file.load(path)


def _contact_up_to_the_bem(case, tmp_path):
    (scene,) = [s for s in ladder.case_scenes(case, "g", top="BEM") if s.name == "g-contact"]
    return run_scene(scene, "quick", tmp_path)


def test_the_bem_outside_its_validity_judges_no_model(tmp_path):
    # 1/8-inch ball, f 0.52, 500 N: a/R = 0.47 by the BEM, beyond the half-space rungs' 0.3; the FE study of that
    # contact puts the BEM further from the FE in a (-3.96 %) than Hertz (+2.06 %): the BEM is no referee there
    result = _contact_up_to_the_bem(_guide(tmp_path, "500 N"), tmp_path / "500")
    # Hertz's own a/R flag and the truncation check of the ellipse against the groove's shoulder (docs/truncation.md,
    # the ellipse of ball 2 BR reaches it at 500 N), nothing judged against the BEM
    assert not result.error and result.status() == "findings"
    quantities = [o.quantity for o in result.outputs]
    assert "a / R (Hertz's small-contact assumption)" in quantities
    assert all(q.startswith(("a / R", "end of the major semi-axis")) for q in quantities), quantities
    assert any("No reference at this level" in note and "a/R = 0.467" in note for note in result.notes)
    (table,) = [t for t in result.tables if "no reference at this level" in t[0]]
    assert [row[0] for row in table[2]][:2] == ["lowmodel.contact.hertz", "lowmodel.contact.halfspace (exact gap)"]


def test_the_bem_inside_its_validity_judges_hertz(tmp_path):
    # the template's 50 N: a/R = 0.22, the BEM is the referee of Hertz without an FE rung
    result = _contact_up_to_the_bem(_guide(tmp_path, "50 N"), tmp_path / "50")
    assert not result.error
    judged = {(o.model, o.quantity) for o in result.outputs}
    assert ("lowmodel.contact.hertz", "a") in judged
    assert any("Reference: the finest BEM grid" in note for note in result.notes)


def _b2b_scene(forces):
    from ballbench.validation.ladder import b2b_fe

    # three module levels h_contact = b_max / n, n = 1.25, 1.5625, 1.95 (quick, docs/your_own_bearing.md)
    rows = [dict(h_contact_um=100.0 / n, F_B2B=f, wall_s=1.0) for n, f in zip((1.25, 1.5625, 1.95), forces)]
    low = [("lowmodel.screw.b2b", "low-order numerical", 1.0, 0.01)]

    def fn(run):
        b2b_fe.judge_b2b(run, "ball-screw", rows, low, 10.0)

    return Scene("zz-b2b-fe", "a case file's FE-informed rung", fn, tags=("case",))


def test_scattered_module_levels_leave_the_b2b_models_unjudged(tmp_path):
    # FE-informed forces 0.633, 1.104, 0.971 N oscillate by tens of percent: U far above the 5 % bound
    result = run_scene(_b2b_scene((0.633, 1.104, 0.971)), "quick", tmp_path)
    assert not result.error and result.status() == "inconclusive" and result.passed
    assert not [o for o in result.outputs if o.model == "lowmodel.screw.b2b"]
    # finer module levels are not shown to settle it on small B2B forces: the words say "may" and why
    assert "the 5 % it needs" in result.inconclusive and "What may settle it" in result.inconclusive
    assert "finer module levels still scattered" in result.inconclusive
    assert "run at the default fidelity (without --quick) or --fine" in result.inconclusive
    assert "h_contact = 80, 64, 51, 41, 33 um" in result.inconclusive  # the levels continued at their ratio
    (table,) = [t for t in result.tables if "nothing judged" in t[0]]
    assert ("lowmodel.screw.b2b", "low-order numerical", "1") in table[2]


def test_module_levels_that_agree_judge_the_b2b_models(tmp_path):
    result = run_scene(_b2b_scene((1.004, 1.001, 1.002)), "quick", tmp_path)
    assert not result.error and not result.inconclusive
    (judged,) = [o for o in result.outputs if o.model == "lowmodel.screw.b2b"]
    assert judged.reference == 1.002 and judged.status == "pass"
    (bound,) = [o for o in result.outputs if o.quantity == "relative uncertainty of the F_B2B reference"]
    assert bound.status == "pass" and bound.value < 0.05


def _contact_with_fe_levels(tmp_path, monkeypatch, factors):
    """The -contact scene of the 50 N guide template up to the FE, its FE levels replaced by Hertz's values times
    ``factors`` (coarse to fine): the study's data without the solves (a reference is pure arithmetic on them)."""
    from types import SimpleNamespace

    from ballbench.validation.ladder import contact as contact_module
    from ballbench.validation.ladder import rungs
    from ballbench.validation.studies import fe_contact

    levels = iter(factors)

    def solve_level(pair, level):
        factor = next(levels)
        values = {q: v * factor for q, v in rungs.hertz_values(pair).items()}
        return SimpleNamespace(**values, h_contact=values["b"] / level.n, ndofs=1000, iterations=1, residual=0.0,
                               force_sum=pair.force, model=SimpleNamespace(factor=None)), None

    monkeypatch.setattr(fe_contact, "pair_model", lambda contact: contact)
    monkeypatch.setattr(fe_contact, "level_dofs", lambda pair, level: 1000)
    monkeypatch.setattr(fe_contact, "solve_level", solve_level)
    monkeypatch.setattr(contact_module, "_fields", lambda *args: None)
    (scene,) = [s for s in ladder.case_scenes(_guide(tmp_path, "50 N"), "g", top="FE") if s.name == "g-contact"]
    return run_scene(scene, "quick", tmp_path / "out")


def test_scattered_fe_levels_make_the_contact_inconclusive(tmp_path, monkeypatch):
    result = _contact_with_fe_levels(tmp_path, monkeypatch, (1.0, 1.05, 0.97))
    assert not result.error and result.status() == "inconclusive" and result.status(strict=True) == "fail"
    judged = {(o.model, o.quantity) for o in result.outputs}
    # Hertz's own flag, the truncation check of the ellipse against the shoulder (docs/truncation.md) and the FE's
    # load equilibrium only
    judged -= {(o.model, o.quantity) for o in result.outputs if o.quantity.startswith("end of the major semi-axis")}
    assert judged == {("lowmodel.contact.hertz", "a / R (Hertz's small-contact assumption)"),
                      ("fem.contact", "force_sum")}
    assert "against the 1 % it needs" in result.inconclusive
    assert "FE levels n = b/h 5.5, 6.6, 7.92, 9.5, 11.4" in result.inconclusive
    assert any("no conclusive reference at this fidelity" in t[0] for t in result.tables)


def test_fe_levels_that_agree_with_an_erratic_order_judge_the_models(tmp_path, monkeypatch):
    # increments growing, as the 500 N guide's a (0.07 % then 0.12 %): observed order below 0.5, yet conclusive
    result = _contact_with_fe_levels(tmp_path, monkeypatch, (1.0, 1.0007, 1.0019))
    assert not result.error and not result.inconclusive and result.status() in ("pass", "findings")
    (bound,) = [o for o in result.outputs if o.model == "uncertainty of the FE study"]
    assert bound.status == "pass" and bound.value < 0.01
    assert {o.quantity for o in result.outputs if o.model == "lowmodel.contact.hertz"} >= {"a", "b", "p0", "delta"}
