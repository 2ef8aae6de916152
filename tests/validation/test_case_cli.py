"""``ballbench init``, ``validate CASE.toml`` and ``show CASE.toml``: one's own bearing through the command line
(docs/cases.md); wrong use is one line and exit 2, before any work."""
from __future__ import annotations

import json

import pytest

import ballbench

from ballbench.validation import cli
from tests.cli_support import one_error_line


def _init(kind, tmp_path, capsys, name="g.toml"):
    assert cli.main(["init", kind]) == 0
    path = tmp_path / name
    path.write_text(capsys.readouterr().out)
    return path


def test_init_writes_a_template_that_validate_runs_up_to_the_bem(tmp_path, capsys):
    path = _init("linear-guide", tmp_path, capsys)
    text = path.read_text().replace('vertical_force = "50 N"', 'vertical_force = "60 N"')
    path.write_text(text)  # a user's edit
    out = tmp_path / "report"
    code = cli.main(["validate", str(path), "--quick", "--levels", "BEM", "--out", str(out)])
    err = capsys.readouterr().err
    data = json.loads((out / "results.json").read_text())
    scenes = {s["name"]: s for s in data["scenes"]}
    assert set(scenes) == {"g-balls", "g-contact"}, err
    balls = scenes["g-balls"]
    assert not balls["error"] and [t["title"] for t in balls["tables"]][1].startswith("Friction of the balls")
    contact = scenes["g-contact"]
    families = {o["family"] for o in contact["outputs"]}
    assert families == {"analytical", "BEM"}, contact["outputs"]
    assert all(o["time_s"] > 0 for o in contact["outputs"])
    assert "Friction of the balls" in (out / "report.md").read_text()
    assert code in (0, 1)  # 1 when a model misses its tolerance against the reference: a finding, not a crash
    assert "Traceback" not in err


@pytest.mark.parametrize("args, words", [
    (["validate", "missing.toml"], "no such file"),
    (["validate", "{case}", "--levels", "FEM"], "invalid choice"),
    (["validate", "{case}", "--budget", "-3"], "--budget"),
    (["show", "missing.toml"], "no such file"),
    (["init", "linear-bearing"], "invalid choice"),
    (["validate", "hertz-ball-ball", "--levels", "BEM"], "apply to case files"),
])
def test_wrong_use_is_one_line(args, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    case = _init("contact", tmp_path, capsys)
    code = cli.main([a.replace("{case}", str(case)) for a in args])
    assert words in one_error_line(capsys, code)


def test_a_unit_mistake_in_a_case_file_is_named_before_any_work(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = _init("ball-screw", tmp_path, capsys)
    path.write_text(path.read_text().replace('pitch_radius = "16.6 mm"', "pitch_radius = 20"))
    line = one_error_line(capsys, cli.main(["validate", str(path), "--out", "r"]))
    assert "screw.pitch_radius" in line and "line 10" in line
    assert not (tmp_path / "r").exists()


def test_calibrate_takes_a_case_file(tmp_path, capsys, monkeypatch):
    # [contact.<name>] fe_case = "g.toml": the FE load sweep of the case's most loaded contact, levels from its
    # ellipse; a bad case file is named before any FE runs
    import numpy as np

    from ballbench.validation.studies.calibration import fe_laws
    from ballbench.validation.studies import fe_contact

    path = _init("linear-guide", tmp_path, capsys)
    spec = tmp_path / "spec.toml"
    spec.write_text(f'output = "{tmp_path / "out" / "calibration.json"}"\n[contact.mine]\nfe_case = "g.toml"\n')
    seen = []

    def sweep(case, fidelity, factors):  # Hertz itself stands in for the FE sweep: the plumbing is under test
        from ballbench.lowmodel.contact import hertz

        geometry = fe_contact.hertz_geometry(case)
        forces = case.force * np.asarray(factors)
        contact = hertz.solve_load(geometry, forces)
        seen.append(case)
        return dict(force=forces, approach=np.asarray(contact.delta), a=np.asarray(contact.a),
                    ball_radius=case.ball_radius, geometry=geometry, level=(5.5, 1.4), ndofs=1, wall_time_s=0.0)

    monkeypatch.setattr(fe_contact, "load_sweep", sweep)
    assert cli.main(["calibrate", str(spec)]) == 0, capsys.readouterr().err
    assert (tmp_path / "out" / "calibration.json").is_file()
    (case,) = seen
    assert case.fe is not None and case.pair == "groove" and case.conformity == 0.52
    loads = ballbench.friction(ballbench.load_case(path)).contacts
    assert case.force == max(c.normal_force for c in loads) == fe_laws.case_contact(path).force
    path.write_text(path.read_text().replace("conformity = 0.52", "conformity = 52"))
    line = one_error_line(capsys, cli.main(["calibrate", str(spec)]))
    assert "fe_case" in line and "guide.conformity" in line


def _walkthrough_guide(tmp_path, capsys):
    """The guide of docs/your_own_bearing.md's walk-through: 1/4-inch balls, conformity 0.54, 500 N per ball; lin2019
    eq 30 misses its 7 % claim against the numerical model on it."""
    path = _init("linear-guide", tmp_path, capsys)
    text = path.read_text().replace('ball_radius = "1.5875 mm"', 'ball_radius = "3.175 mm"')
    text = text.replace("conformity = 0.52 ", "conformity = 0.54 ").replace('"50 N"', '"500 N"')
    path.write_text(text)
    return path


@pytest.mark.parametrize("strict", [False, True])
def test_a_model_outside_its_accuracy_on_ones_own_guide_is_a_finding(strict, tmp_path, capsys):
    # the analytical B2B model (lin2019 eq 30) misses its declared 7 % against the numerical model here: a result of
    # the validation (status "outside accuracy", scene "findings", exit 0), a failure only with --strict
    path = _walkthrough_guide(tmp_path, capsys)
    out = tmp_path / "report"
    code = cli.main(["validate", str(path), "--quick", "--levels", "analytical", "--out", str(out)]
                    + (["--strict"] if strict else []))
    err = capsys.readouterr().err
    data = json.loads((out / "results.json").read_text())
    balls = next(s for s in data["scenes"] if s["name"] == "g-balls")
    analytical = next(o for o in balls["outputs"] if o["model"] == "lowmodel.linear_bearing.b2b_analytical")
    assert analytical["rel_error"] > analytical["tolerance"] and analytical["status"] == "outside accuracy"
    assert all(o["status"] == "pass" for o in balls["outputs"] if o is not analytical), balls["outputs"]
    assert "Traceback" not in err
    if strict:
        assert code == 1 and balls["status"] == "fail" and not data["passed"]
        assert "outside accuracy (--strict)" in err
        return
    assert code == 0, err
    assert balls["status"] == "findings" and balls["passed"] and data["counts"]["findings"] == 1
    assert "findings" in err and "outside accuracy" in err
    report = (out / "report.md").read_text()
    assert "Findings: models outside their accuracy on this geometry" in report
    assert 'class="finding"' in (out / "report.html").read_text()
    rows = (out / "results.csv").read_text()
    assert "outside accuracy" in rows
    from ballbench.validation.report import results_from_json

    again = results_from_json(data)  # the status survives a re-render of the report from results.json
    assert next(r for r in again if r.name == "g-balls").status() == "findings"


def _no_solve(*args, **kwargs):
    raise AssertionError("show solved although it was not asked to")


def test_every_case_file_keeps_its_own_default_report_and_show_never_solves_unasked(tmp_path, capsys, monkeypatch):
    # both case files used to write into ./ballbench-report, the second run deleting the first's report; 'show'
    # then solved the FE levels the run had not saved (minutes) and exited 1 where a scene had errored
    from ballbench.validation.ladder import b2b_fe
    from ballbench.validation.studies import fe_contact

    monkeypatch.chdir(tmp_path)
    for name in ("g.toml", "h.toml"):
        capsys.readouterr()
        path = _init("linear-guide", tmp_path, capsys, name=name)
        assert cli.main(["validate", path.name, "--quick", "--levels", "low-order"]) in (0, 1)
    capsys.readouterr()
    for stem in ("g", "h"):
        data = json.loads((tmp_path / f"ballbench-report-{stem}" / "results.json").read_text())
        assert {s["name"] for s in data["scenes"]} == {f"{stem}-balls", f"{stem}-contact"}
    assert not (tmp_path / "ballbench-report").exists()
    monkeypatch.setattr(fe_contact, "solve_level", _no_solve)
    monkeypatch.setattr(fe_contact, "compute_fields", _no_solve)
    monkeypatch.setattr(b2b_fe, "module_fe", _no_solve)
    assert cli.main(["show", "g.toml"]) == 0
    captured = capsys.readouterr()
    assert captured.out.strip() == ""  # no picture: nothing was saved
    lines = [x for x in captured.err.splitlines() if x.startswith("ballbench: g-")]
    assert [x.split(":")[1].strip() for x in lines] == ["g-contact", "g-b2b-fe"], captured.err
    assert "below FE" in lines[0] and "not in this report" in lines[1] and "--solve" in lines[1]
    assert "no pictures drawn from ballbench-report-g" in captured.err
    # only an interrupted run's partial report: show draws from it and says so
    (tmp_path / "ballbench-report-h").rename(tmp_path / "ballbench-report-h-partial")
    assert cli.main(["show", "h.toml"]) == 0
    assert "drawing from the partial report ballbench-report-h-partial" in capsys.readouterr().err
