"""The report package (validation/report/): one document behind every format, model families as declared data,
an error-against-run-time figure whose labels do not collide at 50+ scenes."""
from __future__ import annotations

import itertools
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from ballbench.validation import report
from ballbench.validation.report import contents, document, html, markdown
from ballbench.validation.report.figure import error_figure
from ballbench.validation.report.records import tally
from ballbench.validation.scene import FAMILIES, Output, SceneResult
from ballbench.validation import cli


def _output(model, family, level="", *, error=0.5, tolerance=0.03, time_s=1e-3, quantity="a"):
    rel = error * tolerance
    return Output(model, quantity, "m", 1.0 + rel, 1.0, "closed form", rel, tolerance, rel <= tolerance, time_s,
                  family=family, level=level)


def _scene(name, *outputs, artifacts=()):
    return SceneResult(name, f"scene {name}", "default", tuple(outputs), tuple(artifacts), (), 1.0, "", 60.0,
                       "low-order")


def many_scenes(n_per_family: int = 9, out_dir: Path | None = None) -> list[SceneResult]:
    """About 9 scenes per family (54 in all), crowded as a real run is: many analytical models near 0.1 ms and
    error / tol 0.5, levelled models, an FE scene with a convergence.csv."""
    rng = np.random.default_rng(7)
    results = []
    for family, k in itertools.product(FAMILIES, range(n_per_family)):
        name = f"zz-{family.replace(' ', '-').lower()}-{k:02d}"
        if family in ("BEM", "EHL", "FE-informed"):
            outputs = [_output(f"model.{family}", family, f"level {j}", error=0.9 / (j + 1) * rng.uniform(0.6, 1.4),
                               time_s=10.0 ** (j - 1) * rng.uniform(0.5, 2)) for j in range(3)]
        else:
            time_s = {"analytical": 1e-4, "low-order numerical": 1e-2, "FE": 30.0}[family] * rng.uniform(0.5, 2)
            outputs = [_output(f"model.{family}", family, error=rng.uniform(0.3, 0.9), time_s=time_s)]
        artifacts = ()
        if family == "FE" and out_dir is not None:
            (out_dir / name).mkdir(parents=True, exist_ok=True)
            (out_dir / name / "convergence.csv").write_text(
                "n,growth,wall_s,err_a\n4,1.4,8.0,0.05\n6,1.3,30.0,0.012\n9,1.2,150.0,0.003\n")
            artifacts = (f"{name}/convergence.csv",)
        results.append(_scene(name, *outputs, artifacts=artifacts))
    return results


def test_error_budget_table_groups_by_declared_family_and_names_undeclared():
    results = [
        _scene("zz-informed", _output("lowmodel.linear_bearing.b2b_traction", "FE-informed", "h 30 um", time_s=90.0),
               _output("lowmodel.linear_bearing.b2b", "low-order numerical", time_s=0.01),
               _output("lowmodel.linear_bearing.b2b_analytical", "analytical", time_s=1e-5)),
        _scene("zz-old", _output("lowmodel.contact.hertz", "", time_s=1e-5)),  # results.json of an older version
    ]
    points = report.error_points(report.to_json(results, "default"))
    assert {(p["model"], p["family"], p["level"]) for p in points} == {
        ("lowmodel.linear_bearing.b2b_traction", "FE-informed", "h 30 um"),
        ("lowmodel.linear_bearing.b2b", "low-order numerical", ""),
        ("lowmodel.linear_bearing.b2b_analytical", "analytical", ""), ("lowmodel.contact.hertz", "undeclared", "")}
    rows = contents.family_table(points)
    assert [r[0] for r in rows] == ["analytical", "low-order numerical", "FE-informed", "undeclared"]
    assert rows[2][5] == "linear_bearing.b2b_traction (h 30 um)"
    text = report.to_markdown(results, "default", points=points)
    assert "**lowmodel.linear_bearing.b2b_traction** (FE-informed, h 30 um), one evaluation 90 s:" in text
    assert "**lowmodel.contact.hertz** (undeclared), one evaluation 10 us:" in text
    summary = text.split("## Summary")[1].split("## Known gaps")[0]
    assert "| analytical, low-order numerical, FE-informed |" in summary and "| undeclared |" in summary


def test_results_json_of_an_older_version_reads_as_undeclared():
    data = report.to_json([_scene("zz-a", _output("m", "analytical", "fine"))], "default")
    for o in data["scenes"][0]["outputs"]:
        del o["family"], o["level"]
    output = report.results_from_json(data)[0].outputs[0]
    assert (output.family, output.level) == ("", "")
    assert report.error_points(data)[0]["family"] == "undeclared"


def _plain(text) -> str:
    if isinstance(text, tuple):
        return "".join(_plain(t) for t in text)
    return text if isinstance(text, str) else text.text


def test_markdown_and_html_say_the_same_document(tmp_path):
    """Every heading and table cell of the one document appears in both renderings."""
    import html as html_module

    results = many_scenes(2)
    built = contents.build_document(results, "default", tally(results),
                           points=report.error_points(report.to_json(results, "default")))
    md, page = markdown.render(built).replace("\\|", "|"), html.render(built, tmp_path)
    texts = [s.title for s in built.sections if s.title]
    texts += [_plain(c) for s in built.sections for b in s.blocks if isinstance(b, document.Table)
              for r in b.rows for c in r]
    assert len(texts) > 100
    for text in texts:
        assert text in md, text
        assert html_module.escape(text) in page, text


def test_status_counts_are_those_of_the_one_tally():
    results = many_scenes(1)
    bad = _scene("zz-bad", _output("m", "FE", error=2.0))
    counted = tally([*results, bad])
    assert counted.counts == {"pass": len(results), "known gap": 0, "findings": 0, "not applicable": 0,
                              "inconclusive": 0, "fail": 1, "error": 0}
    built = contents.build_document([*results, bad], "quick", counted)
    assert [v.status for v in built.verdicts] == list(counted.statuses)
    assert report.to_json([*results, bad], "quick")["counts"] == counted.counts


def _finding(error, **kw):
    from dataclasses import replace

    return replace(_output("model.analytical", "analytical", error=error, **kw), finding=True)


def test_a_missed_finding_passes_the_run_a_failed_self_check_does_not(tmp_path):
    # a model outside its declared accuracy on a case's geometry is a finding (passes, --strict fails); a failed
    # self-check beside it (power balance, equilibrium: no finding) still fails the scene
    found = _scene("zz-found", _finding(2.0), _output("model.low", "low-order numerical"))
    broken = _scene("zz-broken", _finding(2.0), _output("model.low", "low-order numerical", error=2.0))
    fine = _scene("zz-fine", _finding(0.5))
    assert [o.status for o in found.outputs] == ["outside accuracy", "pass"]
    assert fine.outputs[0].status == "pass"
    assert (found.status(), found.status(strict=True), found.passed) == ("findings", "fail", True)
    assert (broken.status(), broken.passed) == ("fail", False)
    counted = tally([found, broken, fine])
    assert counted.counts == {"pass": 1, "known gap": 0, "findings": 1, "not applicable": 0, "inconclusive": 0,
                              "fail": 1, "error": 0}
    assert not counted.passed and tally([found, fine]).passed and not tally([found], strict=True).passed
    report.write_report([found, fine], tmp_path, "quick")
    text = (tmp_path / "report.md").read_text()
    assert "1 passed with findings" in text and "Findings: models outside their accuracy" in text


def test_figure_labels_do_not_collide_at_fifty_scenes(tmp_path):
    from matplotlib.text import Annotation, Text

    results = many_scenes(9, tmp_path)
    assert len(results) >= 50
    figure, points = error_figure(report.to_json(results, "default"), tmp_path)
    figure.canvas.draw()  # the labels' final positions
    renderer = figure.canvas.get_renderer()
    panels = [a for a in figure.axes if a.get_title().split(":")[0] in FAMILIES]
    assert [a.get_title().split(":")[0] for a in panels] == list(FAMILIES)
    labelled = 0
    for axes in panels:
        frame = axes.get_window_extent(renderer)
        # the text's own box (an Annotation's extent also holds its leader line)
        boxes = [Text.get_window_extent(t, renderer) for t in axes.texts if isinstance(t, Annotation)]
        labelled += len(boxes)
        for box in boxes:
            assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
        for a, b in itertools.combinations(boxes, 2):
            assert not a.overlaps(b), (axes.get_title(), a, b)
    scenes = {p["scene"] for p in points}
    assert labelled >= len(scenes)  # every scene named in its family's panel (levels named as well)
    fe = next(a for a in panels if a.get_title().startswith("FE:"))
    assert "mesh levels" in fe.get_title()


def test_error_figure_of_one_fe_scene_has_a_readable_time_axis(tmp_path):
    data = {"fidelity": "quick", "scenes": [{"name": "zz-fe", "artifacts": [], "outputs": [
        {"model": "fem.contact", "kind": "accuracy", "quantity": "a", "rel_error": 0.001, "tolerance": 0.03,
         "time_s": 23.9, "status": "pass", "family": "FE"}]}]}
    figure, _ = error_figure(data, tmp_path)
    summary, panel = figure.axes[0], figure.axes[-1]
    # a run of one FE scene gave the panel 23.9 - 36 s, whose log axis printed its minor labels on each other
    for axes in (summary, panel):
        low, high = axes.get_xlim()
        assert high >= 10 * low * (1 - 1e-9) and low <= 23.9 <= high
    assert any("all bounds met" in t.get_text() for t in panel.texts)


def test_the_report_names_no_scene_and_no_module_prefix():
    """Model identity is data: the report's code holds no scene name and no list of model-module prefixes."""
    from ballbench.validation.scene import registry

    names = set(registry())
    sources = {path.name: path.read_text() for path in Path(report.__file__).parent.glob("*.py")}
    for file, text in sources.items():
        assert not [n for n in names if n in text], file
        assert not re.search(r"\"lowmodel\.\w+(\.\w+)*\"", text), file  # a model-module string
        assert "matplotlib.use(" not in text and "import matplotlib.pyplot" not in text, file
        assert not re.search(r"\bissue \d", text), file
        assert len(text.splitlines()) <= 600, file


def test_front_of_each_family_steps_down_to_the_best_error():
    family = [{"time_s": 1e-3, "error": 0.5}, {"time_s": 1e-2, "error": 0.1}, {"time_s": 1e-1, "error": 0.2}]
    times, errors = report.front_line(family)
    assert times == [1e-3, 1e-2, 1e-1] and errors == [0.5, 0.1, 0.1]
    assert math.isclose(report.front_line([{"time_s": 2.0, "error": 0.0}])[1][0], 1e-8)


def test_write_report_files(tmp_path):
    results = many_scenes(1, tmp_path)
    paths = report.write_report(results, tmp_path, "default", junit=tmp_path / "junit.xml")
    assert {"markdown", "html", "csv", "json", "png", "points", "junit"} <= set(paths)
    data = json.loads(paths["json"].read_text())
    assert data["scenes"][0]["outputs"][0]["family"] == FAMILIES[0]
    header = paths["points"].read_text().splitlines()[0].split(",")
    assert header[:5] == ["number", "scene", "model", "family", "level"]


@pytest.mark.parametrize("family", ["", "analytical"])
def test_csv_carries_family_and_level(tmp_path, family):
    report.write_csv([_scene("zz", _output("m", family, "h 30 um"))], tmp_path / "r.csv")
    text = (tmp_path / "r.csv").read_text().splitlines()
    assert text[0].endswith(",family,level") and text[1].endswith(f",{family},h 30 um")


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
                  reference=0.9, relation="ge", tolerance=0.0, source="docs/sweeps.md", time_s=1e-3)

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


def test_result_tables_reach_markdown_and_json_and_read_back():
    from dataclasses import replace

    from ballbench.validation.report.records import results_from_json, to_json

    table = ("Friction of the balls", ("state", "friction force [N]"), (("balls touching", "1.269"),))
    result = replace(_scene("case-balls", _output("m", "analytical")), tables=(table,))
    text = report.to_markdown([result], "default")
    assert "Friction of the balls" in text and "1.269" in text
    data = json.loads(json.dumps(to_json([result], "default")))
    assert results_from_json(data)[0].tables == (table,)


def test_angles_are_shown_in_degrees():
    # a check in rad (SI inside) reads in degrees in the report, as the truncation verdict's own words do
    from ballbench.validation.report.rows import engineering

    factor, unit = engineering("rad", 1.3361)
    assert unit == "deg" and 1.3361 * factor == pytest.approx(76.553, abs=1e-3)
