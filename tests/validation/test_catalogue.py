"""The public catalogue of real bearings (examples/catalogue/, docs/your_own_bearing.md "The catalogue") through
``ballbench validate``: every file reads; one guide and one screw up to the BEM in the default run, every case
through the whole ladder at --quick in the slow run.  Each scene ends PASS, PASS with findings, DOES NOT APPLY or
INCONCLUSIVE with its reason, never FAIL or ERROR."""
from __future__ import annotations

import json

import pytest

from ballbench.validation import cli
from ballbench.validation.cases import case_file
from tests import paths

CATALOGUE = sorted((paths.ROOT / "examples" / "catalogue").glob("*.toml"))
# statuses a catalogue case may end with (docs/your_own_bearing.md, "Reading the verdict")
ALLOWED = {"pass", "findings", "known gap", "not applicable", "inconclusive"}


def _validate(path, tmp_path, capsys, *options):
    out = tmp_path / "report"
    code = cli.main(["validate", str(path), "--quick", "--no-progress", "--out", str(out), *options])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    scenes = json.loads((out / "results.json").read_text())["scenes"]
    return code, {s["name"]: s for s in scenes}, err


def test_the_catalogue_spans_real_bearings():
    """At least 12 cases: guides and screws over the sizes, conformities and loads the issue of the catalogue names."""
    cases = [case_file.load(p) for p in CATALOGUE]
    guides = [c for c in cases if hasattr(c, "guide")]
    screws = [c for c in cases if hasattr(c, "screw")]
    assert len(cases) >= 12 and len(guides) >= 6 and len(screws) >= 6
    radii = [c.guide.ball_radius for c in guides]
    assert min(radii) <= 1.5875e-3 + 1e-9 and max(radii) >= 3.175e-3 - 1e-9
    conformities = [c.guide.conformity for c in guides] + [c.screw.conformity for c in screws]
    assert min(conformities) <= 0.515 and max(conformities) >= 0.57
    pitch = [2 * c.screw.pitch_radius for c in screws]
    assert min(pitch) <= 12.5e-3 and max(pitch) >= 63e-3


@pytest.mark.parametrize("name", ["guide_15_close", "screw_16x5"])
def test_one_guide_and_one_screw_up_to_the_bem(name, tmp_path, capsys):
    code, scenes, err = _validate(paths.ROOT / "examples" / "catalogue" / f"{name}.toml", tmp_path, capsys,
                                  "--levels", "BEM")
    assert {s["status"] for s in scenes.values()} <= ALLOWED, err
    assert code == 0, err


def test_a_screw_whose_model_stops_below_the_preload_loss_runs_on_the_stick_slip_law(tmp_path, capsys):
    """screw_16x5 at 150 N: below the frictionless preload loss (207 N), lin2019's full-sliding model finds no state
    (friction unloads a contact first): -balls gives the friction by the stick/slip law on the frictionless loads and
    says why, the contact rung runs on the frictionless statics; no ERROR."""
    text = (paths.ROOT / "examples" / "catalogue" / "screw_16x5.toml").read_text()
    case = tmp_path / "screw_16x5_150.toml"
    case.write_text(text.replace('axial_load = "100 N"', 'axial_load = "150 N"'))
    code, scenes, err = _validate(case, tmp_path, capsys, "--levels", "BEM")
    balls, contact = scenes["screw-16x5-150-balls"], scenes["screw-16x5-150-contact"]
    assert balls["status"] == "pass", balls["error"]
    notes = " ".join(balls["notes"])
    assert "stick/slip on a half-space" in notes and "found no state" in notes
    assert contact["status"] in ALLOWED and contact["error"] == "", err
    assert code == 0


@pytest.mark.slow
@pytest.mark.parametrize("path", CATALOGUE, ids=[p.stem for p in CATALOGUE])
def test_catalogue_case_whole_ladder(path, tmp_path, capsys):
    code, scenes, err = _validate(path, tmp_path, capsys)
    bad = {n: (s["status"], s["error"]) for n, s in scenes.items() if s["status"] not in ALLOWED}
    assert not bad, err
    assert all(s["not_applicable"] for s in scenes.values() if s["status"] == "not applicable")
    assert code == 0
