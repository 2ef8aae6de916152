"""The whole nut in a case file: the [nut] table (validation.cases.case_file) and the scene <stem>-whole of a ball
screw (validation.ladder.whole_nut; docs/nut.md)."""
from __future__ import annotations

import re

import pytest

from ballbench.lowmodel.screw import nut as nuts
from ballbench.validation import ladder
from ballbench.validation.cases import case_file
from ballbench.validation.runner import run_scene
from tests import paths

EXAMPLE = paths.ROOT / "examples" / "ball_screw_32x10.toml"
DOUBLE = '[nut]\narrangement = "double"\nturns = 2\npreload = "400 N"\naxial_load = "800 N"\n'


def _without_nut() -> str:
    text = EXAMPLE.read_text()
    return text[:text.index("[nut]")]


def test_the_template_shows_the_nut_table_and_the_example_has_one():
    template = case_file.template("ball-screw")
    assert "# [nut] (optional)" in template and case_file.loads(template).nut is None
    case = case_file.load(EXAMPLE)
    assert isinstance(case.nut, nuts.Nut) and case.nut.turns == 3 and case.nut_load == pytest.approx(1500.0)
    assert case.nut.balls == nuts.capacity(case.nut.module, 3) - 1


@pytest.mark.parametrize("table, words", [
    ('[nut]\narrangement = "single"\nturns = 2\npreload = "100 N"\naxial_load = "1 kN"\n', "nut.preload"),
    ('[nut]\narrangement = "double"\nturns = 2\naxial_load = "1 kN"\n', "nut.preload"),
    ('[nut]\narrangement = "single"\nturns = 2\nballs = 500\naxial_load = "1 kN"\n', "nut.balls"),
    ('[nut]\narrangement = "dual"\nturns = 2\naxial_load = "1 kN"\n', "arrangement"),
    ('[nut]\narrangement = "single"\nturns = 2\naxial_load = "1 kN"\nflange = "middle"\n', "flange")])
def test_a_mistake_in_the_nut_table_names_its_key(table, words):
    with pytest.raises(case_file.CaseFileError, match=re.escape(words)):
        case_file.loads(_without_nut() + table)


def test_the_example_runs_its_whole_nut(tmp_path):
    case = case_file.load(EXAMPLE)
    assert "s-whole" in ladder.scene_names(case, "s")
    (scene,) = [s for s in ladder.case_scenes(case, "s", top="low-order") if s.name == "s-whole"]
    result = run_scene(scene, "quick", tmp_path)
    assert result.status() == "pass", result.error
    judged = {c.quantity: c for c in result.outputs}
    assert judged["axial balance of the nut's balls"].value < 1e-10
    assert judged["power balance of every step of the rotation"].value < 1e-8
    titles = [title for title, _, _ in result.tables]
    assert any(t.startswith("Friction torque over one nut revolution") for t in titles)
    assert any(t.startswith("Axial stiffness curve") for t in titles)


def test_the_example_runs_the_elastic_nut_at_the_fe_rung(tmp_path):
    """Up the ladder the scene adds the FE rung of an elastic nut (fem.nut_fe): its balance, the worst ball and the
    stiffness judged as findings, the table per ball, the csv, the picture and the VTU."""
    case = case_file.load(EXAMPLE)
    (scene,) = [s for s in ladder.case_scenes(case, "s", top="stick-slip") if s.name == "s-whole"]
    result = run_scene(scene, "quick", tmp_path)
    assert result.status() in ("pass", "findings"), result.error
    judged = {c.quantity: c for c in result.outputs}
    assert judged["axial balance of the elastic nut's balls"].status == "pass"
    worst = judged["axial load of the worst ball against the elastic nut"]
    assert worst.finding and 0.0 < abs(worst.value - worst.reference) / worst.reference < 0.2
    assert judged["axial stiffness against the elastic nut"].finding
    folder = tmp_path / "s-whole"
    for name in ("bar_elastic.csv", "bar_elastic.png", "elastic_nut.vtu"):
        assert (folder / name).exists(), name
    assert any(t.startswith("Nut as a bar against the elastic nut") for t, _, _ in result.tables)
    (folder / "bar_elastic.png").unlink()   # ballbench show draws it again from the saved table
    drawn = scene.show(folder, "quick", False)
    assert "bar_elastic.png" in {p.name for p in drawn} and (folder / "bar_elastic.png").exists()


def test_a_double_nut_runs_its_preload_and_lift_off(tmp_path):
    case = case_file.loads(_without_nut() + DOUBLE)
    (scene,) = [s for s in ladder.case_scenes(case, "d", top="low-order") if s.name == "d-whole"]
    result = run_scene(scene, "quick", tmp_path)
    assert result.status() == "pass", result.error
    judged = {c.quantity: c for c in result.outputs}
    assert judged["lift-off load of the double nut, Hertz's law"].value == pytest.approx(2 ** 1.5 * 400.0, rel=1e-9)
    assert any("Lift-off of half B" in note and "no model yet" in note for note in result.notes)
    folder = next(tmp_path.rglob("halves.csv")).parent
    assert {p.name for p in scene.show(folder, "quick", False)} == {"preload.png"}
