"""``ballbench show``: pictures from the fields ``validate`` saved, without solving again."""
from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from ballbench.validation import cli, show
from ballbench.validation.cases import lin2019
from ballbench.validation.figures import render3d
from ballbench.validation.scene import registry
from ballbench.validation.studies import fe_contact

SCENE = "fe-hertz-ball-ball"
CASE = lin2019.CONTACT_BALL
THREE_D = ["3d_assembly.png", "3d_pressure.png", "3d_stress.png"]  # validation.figures.render3d


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    """A report folder with the saved fields of the coarse level (one FE solve, about 10-20 s)."""
    out = tmp_path_factory.mktemp("report")
    assert registry()[SCENE].case is CASE
    paths = fe_contact.compute_fields(CASE, SCENE, "quick", out / SCENE)
    assert [p.name for p in paths] == ["fields.vtu", "fields.json"]
    return out


def _no_solve(*args, **kwargs):
    raise AssertionError("show solved the FE problem although its fields were saved")


def test_saved_fields_name_their_units(saved):
    meta = json.loads((saved / SCENE / "fields.json").read_text())
    data, _ = fe_contact.load_fields(saved / SCENE)
    for name in meta["fields"].values():
        assert name in data, name
        assert name.endswith(("_m", "_Pa")), name
    assert data[meta["fields"]["displacement"]].shape == data["points"].shape
    assert data["tets"].shape[1] == 10  # the P2 solution at all nodes of quadratic tetrahedra
    tets, points = data["tets"], data["points"]
    for k, (i, j) in enumerate(((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))):  # VTK's edge order
        assert np.allclose(points[tets[:, 4 + k]], 0.5 * (points[tets[:, i]] + points[tets[:, j]]))
    assert meta["symmetry"] == {"x": True, "y": True}
    assert meta["fe"]["p0_Pa"] == pytest.approx(meta["hertz"]["p0_Pa"], rel=0.04)


def test_show_reads_saved_fields_and_writes_into_the_scene_folder(saved, monkeypatch, capfd):
    monkeypatch.setattr(fe_contact, "solve_level", _no_solve)
    monkeypatch.setattr(fe_contact, "compute_fields", _no_solve)
    paths = show.show(SCENE, saved)
    assert [p.name for p in paths] == ["pressure.png", "stress.png"] + THREE_D
    for path in paths:
        assert path.parent == saved / SCENE
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    for path in paths[:2]:
        assert 20_000 < path.stat().st_size < 300_000
    captured = capfd.readouterr()
    assert captured.err == "" and "vtk" not in captured.out.lower()


def test_show_solves_only_when_asked_and_fields_are_missing(saved, tmp_path, monkeypatch):
    calls = []

    def fake_compute(case, scene_name, fidelity, directory, show_progress=False):
        calls.append((scene_name, fidelity))
        assert case is CASE and not show_progress
        shutil.copytree(saved / SCENE, directory, dirs_exist_ok=True)

    monkeypatch.setattr(fe_contact, "compute_fields", fake_compute)
    monkeypatch.setattr(render3d, "render", lambda directory: [])  # the 3D screenshots: tests/test_render3d.py
    with pytest.raises(FileNotFoundError, match="no saved fields"):  # never solved unasked
        show.show(SCENE, tmp_path, fidelity="quick")
    assert calls == []
    show.show(SCENE, tmp_path, fidelity="quick", solve=True)
    show.show(SCENE, tmp_path, fidelity="quick", solve=True)
    assert calls == [(SCENE, "quick")]


def test_cli_show_solve_lists_what_it_wrote_in_the_manifest(saved, tmp_path, monkeypatch, capsys):
    # the fields --solve writes into a report are the report's: the next validate removes them, not a user's file
    from ballbench.validation import report_folder

    def fake_compute(case, scene_name, fidelity, directory, show_progress=False):
        shutil.copytree(saved / SCENE, directory, dirs_exist_ok=True)

    monkeypatch.setattr(fe_contact, "compute_fields", fake_compute)
    monkeypatch.setattr(render3d, "render", lambda directory: [])
    out = tmp_path / "r"
    assert cli.main(["show", SCENE, "--out", str(out)]) == 2  # no report there: nothing solved unasked
    assert not out.exists()
    (out / SCENE).mkdir(parents=True)
    (out / SCENE / "mine.txt").write_text("mine")
    assert cli.main(["show", SCENE, "--out", str(out), "--quick", "--solve"]) == 0
    owned = report_folder.owned(out)
    assert {f"{SCENE}/fields.vtu", f"{SCENE}/fields.json", f"{SCENE}/pressure.png", f"{SCENE}/stress.png"} <= owned
    assert f"{SCENE}/mine.txt" not in owned


def test_cli_show(saved, monkeypatch, capsys):
    monkeypatch.setattr(fe_contact, "solve_level", _no_solve)
    assert cli.main(["show", SCENE, "--out", str(saved)]) == 0
    assert capsys.readouterr().out.split() == [str(saved / SCENE / name) for name in
                                               ["pressure.png", "stress.png"] + THREE_D]


def test_show_refuses_other_scenes(tmp_path):
    with pytest.raises(ValueError, match="FE scenes"):
        show.show("hertz-sphere-flat", tmp_path)
    with pytest.raises(ValueError, match="fidelity"):
        show.show("fe-hertz-flat", tmp_path, fidelity="ultra")


def test_damaged_fields_end_in_one_line(tmp_path, capsys):
    folder = tmp_path / SCENE
    folder.mkdir()
    (folder / "fields.vtu").write_text("not a vtu")
    (folder / "fields.json").write_text("{}")
    assert cli.main(["show", SCENE, "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and "fields.vtu" in err


@pytest.mark.slow
def test_show_fourpoint_module_writes_pngs(tmp_path):
    # FE four-point module at the quick level (111k DOFs) plus one solve for the displacement field
    paths = show.show("fe-b2b-linear-a", tmp_path, fidelity="quick", solve=True)
    assert [p.name for p in paths] == ["pressure.png", "stress.png", "3d_assembly.png", "3d_pressure_overview.png",
                                       "3d_pressure_contacts.png", "3d_stress.png"]
    for path in paths:
        assert path.exists() and path.stat().st_size > 10_000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_show_after_a_quick_run_says_why_it_solves(tmp_path, monkeypatch, capsys):
    import json

    from ballbench.validation import show
    from ballbench.validation.studies import fe_contact

    class Stop(Exception):
        pass

    def stop(*args, **kwargs):
        raise Stop

    monkeypatch.setattr(fe_contact, "compute_fields", stop)
    (tmp_path / "results.json").write_text(json.dumps({"fidelity": "quick", "scenes": []}))
    with pytest.raises(Stop):
        show.show("fe-hertz-groove-056", tmp_path, "default", solve=True)
    # the user ran 'validate --quick' then 'show' and saw the default level solved without a reason
    assert "a --quick run, which saves no fields" in capsys.readouterr().err


def test_show_labels_give_the_fe_error_against_hertz():
    from ballbench.validation.figures.style import against

    # pressure.png drew Hertz and FE ellipses 0.01 % apart with nothing but the two lengths to 0.1 um
    assert against(421.2844e-6, 421.2438e-6) == "+0.010 %"
    assert against(97.757e-6, 97.790e-6) == "-0.034 %"
    assert against(1.0, 0.0) == "n/a"


def test_shown_in_index_matches_the_registry():
    from ballbench.validation import scenes

    full = {name: entry.function.__module__.rsplit(".", 1)[1] for name, entry in registry().items()
            if entry.show is not None}
    assert scenes.SHOWN_IN == full


def test_show_imports_only_the_scene_module():
    import subprocess
    import sys

    code = ("import sys; from ballbench.validation import show; assert show.can_show('fe-b2b-linear-a'); "
            "print(sorted(m for m in sys.modules if m.startswith('ballbench.validation.scenes.')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "['ballbench.validation.scenes.fe_b2b']"


def test_a_contact_rung_that_ran_no_fe_study_is_not_offered_a_solve(tmp_path):
    # an ellipse the FE pair cannot hold (ladder.contact: "FE study not run: ..."): show says so instead of
    # offering '--solve', which would try the same FE study
    from ballbench.validation.report_folder import why_nothing_saved

    note = "FE study not run: the FE pair's counter block would need 1.615 mm across the groove."
    record = {"name": "g-contact", "status": "findings", "kind": "FE", "notes": ["Contact: ...", note]}
    (tmp_path / "results.json").write_text(json.dumps({"fidelity": "quick", "scenes": [record]}))
    words = why_nothing_saved(tmp_path, "g-contact", FileNotFoundError("no saved fields"), "ballbench show g.toml")
    assert "ran no FE study: the FE pair's counter block" in words and "--solve" not in words
    record["notes"] = ["Contact: ..."]  # a contact scene that ran its FE study offers the solve, as before
    (tmp_path / "results.json").write_text(json.dumps({"fidelity": "quick", "scenes": [record]}))
    assert "--solve" in why_nothing_saved(tmp_path, "g-contact", FileNotFoundError("no saved fields"),
                                          "ballbench show g.toml")
