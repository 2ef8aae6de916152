"""What a new user trips over on the command line (issue 15 audit): each test fails on the behaviour found."""
from __future__ import annotations

from pathlib import Path

import pytest

from ballbench.validation import cli
from tests import paths
from tests.cli_support import helper_module, one_error_line


@pytest.fixture
def no_work(monkeypatch):
    from ballbench.validation import runner, show

    monkeypatch.setattr(runner, "run_scenes", lambda *a, **k: pytest.fail("work started before the check"))
    monkeypatch.setattr(show, "show", lambda *a, **k: pytest.fail("show started on a scene it cannot draw"))


def test_misspelt_scene_name_suggests_the_close_ones(capsys, no_work, tmp_path):
    line = one_error_line(capsys, cli.main(["validate", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line
    line = one_error_line(capsys, cli.main(["show", "fe-hertz-groove56", "--out", str(tmp_path / "r")]))
    assert "did you mean 'fe-hertz-groove-056'" in line


def test_show_of_a_scene_without_saved_fields_says_to_validate_first(capsys, tmp_path):
    # sun2021-fe-bem saves only its BEM surfaces (no fields.vtu): 'show' on a folder without them used to advise
    # deleting a fields.vtu that never existed
    assert cli.main(["show", "sun2021-fe-bem", "--out", str(tmp_path / "r")]) == 1
    lines = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert len(lines) == 1 and "ballbench validate sun2021-fe-bem" in lines[0] and "delete" not in lines[0]


def test_show_names_the_kind_with_the_right_article(capsys, no_work, tmp_path):
    line = one_error_line(capsys, cli.main(["show", "hertz-sphere-flat", "--out", str(tmp_path / "r")]))
    assert "is an analytical scene" in line


# ---------------------------------------------------------------------------------------------- sweep
SWEEP_HELPERS = '''
def square(x, offset=0.0):
    """x^2 + offset [-]; x < 0 raises."""
    if x < 0:
        raise ValueError(f"x must be >= 0, got {x}")
    return {"value": x * x + offset}
'''


@pytest.fixture
def sweep_helpers(tmp_path, monkeypatch):
    return helper_module(tmp_path, monkeypatch, "audit_sweep_helpers", SWEEP_HELPERS)


def _sweep_spec(tmp_path, fixed: str, values: str) -> str:
    path = tmp_path / "spec.toml"
    path.write_text(f'name = "audit"\nfunction = "audit_sweep_helpers:square"\nchunk_size = 2\noutputs = ["value"]\n'
                    f'[fixed]\n{fixed}\n[grid]\nx = {{ values = {values} }}\n')
    return str(path)


@pytest.mark.parametrize("fixed, expected", [
    ("ofset = 1.0", "unexpected keyword argument 'ofset'"),  # a misspelt input
    ("", None),                                               # fine: offset has a default
])
def test_sweep_input_names_are_checked_before_any_case_runs(sweep_helpers, tmp_path, capsys, fixed, expected):
    spec = _sweep_spec(tmp_path, fixed, "[1.0, 2.0]")
    out = tmp_path / "out"
    if expected is None:
        assert cli.main(["sweep", spec, "--serial", "--out", str(out), "--no-progress"]) == 0
        return
    with pytest.raises(SystemExit) as stop:  # used to run every case, record a TypeError each and exit 0
        cli.main(["sweep", spec, "--serial", "--out", str(out), "--no-progress"])
    assert expected in str(stop.value) and "square(x, offset=0.0)" in str(stop.value)
    assert not out.exists()


def test_sweep_names_the_failure_reasons_and_fails_when_every_case_fails(sweep_helpers, tmp_path, capsys):
    out = tmp_path / "out"
    assert cli.main(["sweep", _sweep_spec(tmp_path, "", "[-2.0, -1.0, 3.0]"), "--serial", "--out", str(out),
                     "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "2 failed with ValueError; the first, case 0: ValueError: x must be >= 0, got -2.0" in printed
    everything_fails = _sweep_spec(tmp_path, "", "[-2.0, -1.0]")
    assert cli.main(["sweep", everything_fails, "--serial", "--out", str(tmp_path / "out2"), "--no-progress"]) == 1
    assert "every case failed" in capsys.readouterr().err


# ---------------------------------------------------------------------------------------------- report figure
def test_a_family_front_of_one_point_is_drawn_as_a_line_to_the_longest_time():
    from ballbench.validation.report import front_line

    # the fastest point is also the most accurate: the front is that one point (in the --fast run: the
    # low-order numerical and 'other' families), which a post-step line drew as nothing at all
    family = [{"time_s": 1e-3, "error": 1e-6}, {"time_s": 1e-2, "error": 0.4}, {"time_s": 0.7, "error": 0.9}]
    times, errors = front_line(family)
    assert times == [1e-3, 0.7] and errors == [1e-6, 1e-6]
    # a front of several points keeps its steps and ends at the family's longest time
    family.append({"time_s": 0.1, "error": 1e-9})
    times, errors = front_line(family)
    assert times == [1e-3, 0.1, 0.7] and errors == [1e-6, 1e-8, 1e-8]  # 1e-9 drawn on the 1e-8 floor
    # one point in all: a short stub, still a line
    times, errors = front_line([{"time_s": 2.0, "error": 0.5}])
    assert len(times) == 2 and times[1] > times[0] and errors == [0.5, 0.5]


# ---------------------------------------------------------------------------------------------- calibrate
NUT_DATA = paths.DATA / "fe_nut_quick.load_approach.csv"


def _calibrate_spec(tmp_path, body: str) -> Path:
    (tmp_path / "nut.csv").write_text(NUT_DATA.read_text())
    path = tmp_path / "spec.toml"
    path.write_text(f'output = "{tmp_path / "out" / "calibration.json"}"\n' + body)
    return path


FE_CONTACT = '[contact."ball-groove-0.56"]\nfe_scene = "fe-hertz-groove-056"\n'


@pytest.mark.parametrize("body, expected", [
    (FE_CONTACT + "[k_f]\nconformity = 0.56\nfit_rnage = 0.5\n", "unknown key(s) ['fit_rnage']"),
    (FE_CONTACT + "[friction]\ndata = 'rig.csv'\n", "friction.data: no such file"),
    (FE_CONTACT + "[k_f]\nconformity = 56\n", "k_f.conformity must lie in"),
    ("confidence = 95\n" + FE_CONTACT, "confidence must lie in (0, 1)"),
    ('[contact."ball-groove-0.56"]\nfe_scene = "fe-hertz-groove-056"\nfidelity = "coarse"\n', "fidelity must be"),
    ('[contact.nut]\ndata = "nut.csv"\nball_radius = 3.175\n', "ball_radius must lie in [0.0001, 0.1] m"),
])
def test_calibrate_spec_mistakes_are_found_before_the_fe_sweep(tmp_path, monkeypatch, capsys, body, expected):
    from ballbench.validation import calibrate

    # a typo in the last table used to surface only after the FE load sweep of the first (minutes); a ball
    # radius in mm used to give a Psi 10x off without a word
    monkeypatch.setattr(calibrate, "fe_contact_law", lambda *a, **k: pytest.fail("FE started before the check"))
    with pytest.raises(SystemExit) as stop:
        cli.main(["calibrate", str(_calibrate_spec(tmp_path, body))])
    assert expected in str(stop.value)
    assert not (tmp_path / "out").exists()


def test_calibrate_spec_in_metres_still_runs(tmp_path, capsys):
    body = '[contact.nut]\ndata = "nut.csv"\nball_radius = 2.778e-3\n'
    assert cli.main(["calibrate", str(_calibrate_spec(tmp_path, body))]) == 0
    assert (tmp_path / "out" / "calibration.json").is_file()


# ---------------------------------------------------------------------------------------------- README, help
README = paths.ROOT / "README.md"


def test_readme_calibrate_writes_the_file_the_next_command_reads():
    # the calibrate spec's output is relative to the spec's folder (examples/), so without --out the README's
    # 'validate --calibration calibration.json' found no file (and examples/ got the output files)
    lines = [x.split("#")[0].split() for x in README.read_text().splitlines() if x.startswith("ballbench ")]
    calibrate = next(x for x in lines if x[1] == "calibrate")
    validate = next(x for x in lines if x[1] == "validate" and "--calibration" in x)
    written = calibrate[calibrate.index("--out") + 1] if "--out" in calibrate else None
    assert written == validate[validate.index("--calibration") + 1]


def test_help_states_no_run_time_of_its_own(capsys):
    # the epilog said "about 5 minutes" for the default run while 'ballbench scenes' states ~27 min
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    text = capsys.readouterr().out
    assert "minute" not in text and "'ballbench scenes' states the cost" in text


def test_a_dimensionless_number_is_shown_without_the_unit_1(tmp_path, capsys, monkeypatch):
    from ballbench.validation import scene as scene_module
    from ballbench.validation.report import failure_lines, row
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import Scene

    def ratio_scene(run):
        run.check(model="lowmodel.contact.mixed", family="EHL", quantity="relative change", unit="1", value=0.010156,
                  reference=0.0293, source="sun2021 Sec 4.4", tolerance=0.2, time_s=1e-3)

    result = run_scene(Scene("zz-ratio", "ratio", ratio_scene, default=False, kind="low-order", cost_s=0.1),
                       "default", tmp_path)
    # "0.010156 1 vs reference 0.029300 1" read as a value with a unit called "1"
    assert "0.010156 vs reference 0.029300 (" in failure_lines(result)[0]
    assert row(result.outputs[0]).unit == ""
    monkeypatch.setitem(scene_module.REGISTRY, "zz-ratio", Scene("zz-ratio", "ratio", ratio_scene, default=False,
                                                                 kind="low-order", cost_s=0.1))
    assert cli.main(["validate", "zz-ratio", "--out", str(tmp_path / "r")]) == 1
    assert "| relative change | 0.010156 | 0.029300 | - |" in (tmp_path / "r" / "report.md").read_text()
    import json
    assert json.loads((tmp_path / "r" / "results.json").read_text())["scenes"][0]["outputs"][0]["unit"] == "1"


def test_known_gaps_table_states_a_shared_reason_once(tmp_path):
    from ballbench.validation.report import to_html, to_markdown
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import KnownGap, Scene

    shared = KnownGap(reason="Fig 19 (the deviation along the screw) is not given.", evidence="docs/ball_screw.md")
    other = KnownGap(reason="Table 4 gives no preload.", evidence="this scene")

    def gaps(run):
        for quantity, gap in (("peak", shared), ("angle of the peak", shared), ("F_B2B", other)):
            run.check(model="lowmodel.screw.whole_screw", family="low-order numerical",
                      quantity=quantity, unit="deg", value=100.0,
                      reference=126.0, source="lin2019 Fig 21", tolerance=0.05, time_s=1.0, known_gap=gap)

    result = run_scene(Scene("zz-gaps", "gaps", gaps, default=False, kind="low-order", cost_s=0.1), "default",
                       tmp_path)
    markdown = to_markdown([result], "default")
    section = markdown.split("## Known gaps")[1].split("## Budgets")[0]
    assert section.count(shared.reason) == 1 and section.count(other.reason) == 1  # was 2 and 1
    assert "| as above | as above |" in section
    page = to_html([result], "default", tmp_path)
    assert page.split('id="known-gaps"')[1].split('id="budgets"')[0].count(shared.reason) == 1


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
        show.show("fe-hertz-groove-056", tmp_path, "default")
    # the user ran 'validate --quick' then 'show' and saw the default level solved without a reason
    assert "a --quick run, which saves no fields" in capsys.readouterr().err


def test_junit_lists_every_check_of_a_scene(tmp_path):
    import xml.etree.ElementTree as ET

    from ballbench.validation.report import to_junit
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import Scene

    def two_checks(run):
        run.check(model="fem.mortar", family="FE", quantity="a", unit="m", value=421.3e-6, reference=421.2e-6,
                  source="Hertz, Johnson (1985) eq 4.39", tolerance=0.03, time_s=26.0)
        run.check(model="fem.mortar", family="FE", quantity="p0", unit="Pa", value=1159e6, reference=1159.2e6,
                  source="Hertz, Johnson (1985) eq 4.39", tolerance=0.03, time_s=26.0)

    result = run_scene(Scene("zz-fe", "fe", two_checks, default=False, kind="FE", cost_s=0.1), "default", tmp_path)
    case = ET.fromstring(to_junit([result])).find("testcase")
    text = case.find("system-out").text
    # a passing FE scene's JUnit case held only its wall time: a CI page showed no number of the check
    assert "a [fem.mortar]: 421.30 um vs reference 421.20 um (Hertz, Johnson (1985) eq 4.39)" in text
    assert "p0 [fem.mortar]: 1159.0 MPa" in text and text.count(": pass") == 2


def test_a_scene_that_raises_points_to_its_traceback(tmp_path, capsys, monkeypatch):
    from ballbench.validation import scene as scene_module
    from ballbench.validation.scene import Scene

    def raises(run):
        raise ValueError("conformity must lie in (0.5, 1); got 0.49")

    scene_module.registry()
    monkeypatch.setitem(scene_module.REGISTRY, "zz-raises",
                        Scene("zz-raises", "raises", raises, default=False, kind="low-order", cost_s=0.1))
    assert cli.main(["validate", "zz-raises", "--out", str(tmp_path / "r")]) == 1
    err = capsys.readouterr().err
    # the terminal said only "ERROR zz-raises (0.0 s): ValueError: ..." and the traceback sat in a file it never named
    assert f"traceback: {tmp_path / 'r' / 'zz-raises' / 'error.txt'}" in err
    assert (tmp_path / "r" / "zz-raises" / "error.txt").read_text().startswith("Traceback")


def test_show_labels_give_the_fe_error_against_hertz():
    from ballbench.validation.figures.style import against

    # pressure.png drew Hertz and FE ellipses 0.01 % apart with nothing but the two lengths to 0.1 um
    assert against(421.2844e-6, 421.2438e-6) == "+0.010 %"
    assert against(97.757e-6, 97.790e-6) == "-0.034 %"
    assert against(1.0, 0.0) == "n/a"


VECTOR_HELPERS = '''
import numpy as np

CALLS = []


def vector_square(x):
    """x^2 [-]; raises for the whole batch when any x < 0 (as b2b_analytical does outside four-point contact)."""
    x = np.asarray(x, dtype=float)
    CALLS.append(x.size)
    if np.any(x < 0):
        raise ValueError("x must be >= 0")
    return {"value": x * x}
'''


def test_a_vectorised_chunk_with_one_failing_case_stays_vectorised(tmp_path, monkeypatch):
    import importlib

    import numpy as np

    from ballbench.validation import sweep

    helper_module(tmp_path, monkeypatch, "audit_vector_helpers", VECTOR_HELPERS)
    helpers = importlib.import_module("audit_vector_helpers")
    values = [float(v) for v in range(1, 1025)]
    values[700] = -1.0
    spec = sweep.spec_from_dict({"name": "v", "function": "audit_vector_helpers:vector_square", "vectorised": True,
                                 "chunk_size": 1024, "outputs": ["value"], "grid": {"x": {"values": values}}})
    columns = sweep.run_chunk(spec.source, 0, 1024)
    assert [bool(e) for e in columns["error"]].count(True) == 1 and columns["error"][700].startswith("ValueError")
    ok = np.arange(1024) != 700
    np.testing.assert_array_equal(columns["value"][ok], np.asarray(values)[ok] ** 2)
    singles = [size for size in helpers.CALLS if size == 1]
    # the whole chunk used to be recomputed one case at a time: 1 + 1024 calls
    assert len(singles) <= sweep.VECTOR_LEAF and len(helpers.CALLS) <= 2 * 10 + sweep.VECTOR_LEAF


def test_an_empty_budgets_section_says_so(tmp_path):
    from ballbench.validation.report import to_html, to_markdown
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import Scene

    def quick(run):
        run.check(model="lowmodel.contact.hertz", family="analytical",
                  quantity="a", unit="m", value=1.0e-4, reference=1.0e-4,
                  source="Johnson (1985) eq 4.22", tolerance=1e-9, time_s=1e-5)

    result = run_scene(Scene("zz-quick", "quick", quick, default=False, kind="analytical", cost_s=0.1), "default",
                       tmp_path)
    # the section showed a table header with no row under it
    section = to_markdown([result], "default").split("## Budgets")[1].split("##")[0]
    assert "None in this run" in section and "| scene | what |" not in section
    page = to_html([result], "default", tmp_path).split('id="budgets"')[1].split("<h2")[0]
    assert "None in this run" in page and "<table>" not in page


def test_known_gaps_section_of_a_strict_run_says_they_fail(tmp_path):
    from ballbench.validation.report import to_html, to_markdown
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import KnownGap, Scene

    def gap(run):
        run.check(model="lowmodel.linear_bearing.b2b", family="low-order numerical",
                  quantity="increase", unit="%", value=150.4, reference=185.2,
                  relation="ge", tolerance=0.0, source="lin2019 Sec 2.4.1", time_s=0.01,
                  known_gap=KnownGap(reason="no full-sliding state", evidence="docs/b2b_bearing.md"))

    result = run_scene(Scene("zz-gap", "gap", gap, default=False, kind="low-order", cost_s=0.1), "default", tmp_path)
    # the --strict report failed the scene and said in the same page that known gaps "do not fail the run"
    strict_md = to_markdown([result], "default", strict=True).split("## Known gaps")[1].split("## Budgets")[0]
    assert "do not fail the run" not in strict_md and "counts them as failures" in strict_md
    assert "do not fail the run" in to_markdown([result], "default")
    assert "counts them as failures" in to_html([result], "default", tmp_path, strict=True)


def test_a_bound_that_holds_is_not_called_exact(tmp_path):
    from ballbench.validation.report import fmt_ratio, to_markdown
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import Scene

    def bounds(run):
        run.check(model="lowmodel.calibration", family="low-order numerical",
                  quantity="coverage of the 95 % interval", unit="1", value=0.9525,
                  reference=0.9, relation="ge", tolerance=0.0, source="issue 13", time_s=1e-3)

    def exact(run):
        run.check(model="lowmodel.calibration", family="low-order numerical",
                  quantity="constants changed by save/load", unit="count", value=0.0,
                  reference=0.0, tolerance=0.0, scale=1.0, source="JSON round trip", time_s=1e-3,
                  why="a count: any change is one")

    results = [run_scene(Scene(name, name, f, default=False, kind="low-order", cost_s=0.1), "default", tmp_path)
               for name, f in (("zz-bounds", bounds), ("zz-exact", exact))]
    # calibration-roundtrip's coverage bounds read "0 (exact)" in the table and the summary
    assert fmt_ratio(results[0].outputs[0]) == "0 (bound met)"
    assert fmt_ratio(results[1].outputs[0]) == "0 (exact)"
    summary = to_markdown(results, "default").split("## Summary")[1].split("## Known gaps")[0]
    assert "| 1 | 0 (bounds met) |" in summary and "| 1 | 0 (exact) |" in summary


def test_one_scene_is_not_one_scenes(tmp_path, capsys):
    from ballbench.validation.report import count

    assert count(1, "scene") == "1 scene" and count(35, "scene") == "35 scenes" and count(0, "point") == "0 points"
    assert cli.main(["validate", "hertz-sphere-flat", "--out", str(tmp_path / "r")]) == 0
    assert "ballbench: 1 scene at fidelity default" in capsys.readouterr().err
    assert "mode default. 1 scene: 1 passed" in (tmp_path / "r" / "report.md").read_text()


def test_sweep_summary_of_a_serial_or_finished_run_names_no_workers(sweep_helpers, tmp_path, capsys):
    spec = _sweep_spec(tmp_path, "", "[1.0, 2.0]")
    argv = ["sweep", spec, "--serial", "--out", str(tmp_path / "out"), "--no-progress"]
    assert cli.main(argv) == 0
    first = capsys.readouterr().out
    # "--serial" printed "workers computing 0 % of the time"; a resumed run with nothing left printed it too
    assert "workers" not in first and "this process computing" in first
    assert cli.main(argv) == 0
    assert "computing" not in capsys.readouterr().out
