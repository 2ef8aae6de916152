"""studies.ladder.distinct_contacts: the contact geometries of a case the ``-contact`` scene runs
(docs/your_own_bearing.md, "The ladder")."""
from __future__ import annotations

import json

from ballbench.validation import cli
from ballbench.validation.cases import case_file
from ballbench.validation.studies import bearing_results, ladder
from tests import paths


def test_a_guide_has_one_contact_geometry_run_at_its_largest_load():
    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    (only,) = ladder.distinct_contacts(case)
    result = bearing_results.guide_result(case)
    assert only.label == "groove" and len(only.members) == len(result.contacts)
    assert only.contact.force == max(c.normal_force for c in result.contacts)
    assert only.contact.conformity == case.guide.conformity


def test_a_screw_has_a_screw_side_and_a_nut_side_each_at_its_largest_load():
    case = case_file.load(paths.ROOT / "examples" / "ball_screw_32x10.toml")
    distinct = ladder.distinct_contacts(case)
    result = bearing_results.screw_result(case)
    assert {d.label for d in distinct} == {"screw side", "nut side"}
    for d in distinct:
        side = [c for c in result.contacts if c.contact[0] == d.contact.pair[0].upper()]
        assert d.contact.force == max(c.normal_force for c in side) and len(d.members) == len(side)
    assert distinct[0].contact.force >= distinct[1].contact.force  # the most loaded first: its fields are saved
    assert distinct[0].contact.force == ladder.governing_contact(case).force


def test_the_contact_scene_of_a_screw_runs_both_sides(tmp_path, capsys):
    out = tmp_path / "report"
    cli.main(["validate", str(paths.ROOT / "examples" / "ball_screw_32x10.toml"), "--quick", "--no-progress",
              "--levels", "BEM", "--out", str(out)])
    assert "Traceback" not in capsys.readouterr().err
    scene = next(s for s in json.loads((out / "results.json").read_text())["scenes"] if s["name"].endswith("-contact"))
    hertz = [o for o in scene["outputs"] if o["model"] == "lowmodel.contact.hertz" and o["quantity"] == "a"]
    assert sorted(o["level"] for o in hertz) == ["nut side", "screw side"]
    assert hertz[0]["value"] != hertz[1]["value"]
    assert scene["tables"][0]["title"].startswith("Contacts run") and len(scene["tables"][0]["rows"]) == 2


def test_the_stick_slip_rung_of_a_guide_judges_full_slip_at_its_declared_accuracy(tmp_path):
    # the balls of one's own guide with stick/slip contacts against full slip on the same cells: the B2B force at
    # full slip's 2.5 % (docs/b2b_rolling.md), the friction at 1 %, a power balance per solve, a row per contact
    from ballbench.validation import case_scenes
    from ballbench.validation.runner import run_scenes
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    scenes = [s for s in case_scenes.case_scenes(case, "g", top="stick-slip") if s.name == "g-stick-slip"]
    assert scenes and "g-stick-slip" in case_scenes.scene_names(case, "g", top="stick-slip")
    assert "g-stick-slip" not in case_scenes.scene_names(case, "g", top="FE-informed")
    (result,), _ = run_scenes(scenes, "quick", tmp_path, show_progress=False)
    assert not result.error and result.passed, result
    checks = {o.quantity: o for o in result.outputs}
    b2b = checks["F_B2B"]
    assert b2b.tolerance == FULL_SLIP_TOLERANCE and b2b.finding and b2b.value > 0 and b2b.reference > 0
    assert b2b.value != b2b.reference  # two laws, not one model against itself
    assert checks["power balance |P_in - P_loss| / P_in, worst of the four solves"].status == "pass"
    (title, header, rows), _ = result.tables
    assert title.startswith("Per contact") and len(rows) == 4 * case.n_balls
    lam = header.index("Lambda")
    assert all(float(r[lam]) > 1.0 for r in rows)


def test_the_quick_level_runs_the_fe_on_the_most_loaded_contact_only(tmp_path):
    # --budget already passed: the FE rung of the screw side starts no level and says so; at quick the nut side has
    # no FE rung at all (one FE study per scene at quick, every contact at the default level)
    from ballbench.validation import case_scenes
    from ballbench.validation.cases import case_file as files
    from ballbench.validation.runner import run_scenes

    case = files.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-table5-a.toml")
    (scene,) = [s for s in case_scenes.case_scenes(case, "m", top="FE", deadline=0.0) if s.name == "m-contact"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    title, header, rows = result.tables[0]
    rungs = {row[0]: row[header.index("rungs")] for row in rows}
    assert rungs == {"screw side": "analytical, BEM, FE", "nut side": "analytical, BEM"}, rows
    assert any("no FE level run" in n for n in result.notes) and any("most loaded contact only" in n
                                                                         for n in result.notes)
    assert not [o for o in result.outputs if o.family == "FE"]
