"""The whole carriage in a case file: the [carriage] table (validation.cases.case_file) and the scene <stem>-whole
(validation.ladder.whole; docs/carriage.md)."""
from __future__ import annotations

import re

import pytest

from ballbench.lowmodel.linear_bearing import carriage
from ballbench.validation import ladder
from ballbench.validation.cases import case_file
from ballbench.validation.ladder import whole
from ballbench.validation.runner import run_scene
from tests import paths

EXAMPLE = paths.ROOT / "examples" / "compact_linear_guide.toml"


def _uncommented_template() -> str:
    text = case_file.template("linear-guide")
    text = re.sub(r"^# \[carriage\].*$", "[carriage]", text, flags=re.M)
    keys = "|".join(k.name for k in case_file.SCHEMA["linear-guide"]["carriage"])
    return re.sub(rf"^# ({keys}) =", r"\1 =", text, flags=re.M)


def test_the_template_shows_the_carriage_table_and_loads_with_it_uncommented():
    assert case_file.loads(case_file.template("linear-guide")).carriage is None  # commented out: the module alone
    case = case_file.loads(_uncommented_template())
    assert isinstance(case.carriage, carriage.Carriage) and len(case.carriage.rows) == 2
    assert case.carriage_load.vertical == pytest.approx(400.0) and case.carriage_load.roll == pytest.approx(2.0)
    # gothic rows of the guide's four-point balls at nominal_angle + the deviations, facing the rail
    assert len(case.carriage.rows[0].normals) == 4 and case.carriage.rows[0].normals[0][0] < 0


@pytest.mark.parametrize("old, new, words", [
    ('height = "2 mm"', "", "carriage.height"),
    ('rows = "gothic"', 'rows = "gotic"', "did you mean 'gothic'"),
    ('pitch = "3.4 mm"', 'pitch = "1 mm"', "pitch"),
    ('relief_depth = "3 um"', 'relief_depth = "-3 um"', "relief_depth")])
def test_a_mistake_in_the_carriage_table_names_its_key(old, new, words):
    text = _uncommented_template()
    assert old in text
    with pytest.raises(case_file.CaseFileError, match=re.escape(words)):
        case_file.loads(text.replace(old, new))


def test_the_example_runs_its_whole_carriage(tmp_path, monkeypatch):
    monkeypatch.setitem(whole.TRAVEL_STEPS, "quick", 1)  # the travel at rest only: the steps' cost is the model's
    case = case_file.load(EXAMPLE)
    (scene,) = [s for s in ladder.case_scenes(case, "g", top="FE") if s.name == "g-whole"]
    result = run_scene(scene, "quick", tmp_path)
    # the rigid carriage's vertical stiffness is 10 % above the elastic body's: a finding (docs/carriage.md)
    assert result.passed and not result.error and result.status() == "findings", result.error
    judged = {c.quantity: c for c in result.outputs}
    assert judged["load balance of the carriage and of every ball"].value < carriage.BALANCE_TOLERANCE
    assert judged["largest contact pressure p0"].value < 4200e6
    assert any(title.startswith("Friction of the rows") for title, _, _ in result.tables)
    assert any("Friction force of the carriage" in note for note in result.notes)
    assert any(title.startswith("Friction over one ball pitch") for title, _, _ in result.tables)
    assert any(tmp_path.rglob("friction_over_travel.png")) and any(tmp_path.rglob("rigid_elastic.png"))
    assert any(tmp_path.rglob("elastic_carriage.vtu"))
    assert judged["load balance of the elastic carriage and its balls"].value < carriage.BALANCE_TOLERANCE
    worst = judged["ball load of the worst ball against the elastic carriage"]
    assert worst.passed and abs(worst.value - worst.reference) > 0.01 * worst.reference  # elastic: not the rigid
    assert any(title.startswith("Rigid against elastic carriage") for title, _, _ in result.tables)
    # ballbench show draws the pictures again from the saved tables
    folder = next(tmp_path.rglob("rigid_elastic.png")).parent
    (folder / "rigid_elastic.png").unlink()
    drawn = scene.show(folder, "quick", False)
    assert {p.name for p in drawn} == {"ball_loads.png", "load_deflection.png", "friction_over_travel.png",
                                       "rigid_elastic.png"} and (folder / "rigid_elastic.png").exists()
    with pytest.raises(FileNotFoundError):
        scene.show(tmp_path / "nothing", "quick", False)
    assert "g-whole" in ladder.scene_names(case, "g")
    assert "g-whole" not in ladder.scene_names(case_file.loads(case_file.template("linear-guide")), "g")
