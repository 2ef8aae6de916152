"""The two example cases that are not the papers' (examples/compact_linear_guide.toml, examples/ball_screw_32x10.toml)
through ``ballbench validate`` at their quick level: up to the BEM in the default run, every rung (FE study,
FE-informed B2B) in the slow run."""
from __future__ import annotations

import json

import pytest

from ballbench.validation import cli
from tests import paths

EXAMPLES = ("compact_linear_guide", "ball_screw_32x10")


def _validate(name, tmp_path, capsys, *levels):
    out = tmp_path / "report"
    code = cli.main(["validate", str(paths.ROOT / "examples" / f"{name}.toml"), "--quick", "--no-progress",
                     "--out", str(out), *levels])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, {s["name"]: s for s in json.loads((out / "results.json").read_text())["scenes"]}, err


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_case_up_to_the_bem(name, tmp_path, capsys):
    code, scenes, err = _validate(name, tmp_path, capsys, "--levels", "BEM")
    stem = name.replace("_", "-")
    balls, contact = scenes[f"{stem}-balls"], scenes[f"{stem}-contact"]
    assert balls["error"] == "" and contact["error"] == "", err
    # the checks of the models' own conditions pass (power balance, statics, axial balance; the coarse BEM grid
    # against the fine one); the models judged against a reference report their errors, which may exceed the
    # tolerance on these cases (docs/your_own_bearing.md, "Reading the verdict"): finite, with their run times, and
    # such a miss is a finding ("outside accuracy"), which does not fail the run
    own = [o for o in balls["outputs"] if o["family"] == "low-order numerical"]
    assert own and all(o["passed"] for o in own), own
    bem = [o for o in contact["outputs"] if o["family"] == "BEM"]
    assert bem and all(o["passed"] for o in bem), bem
    judged = [o for o in balls["outputs"] + contact["outputs"] if o["family"] == "analytical"]
    assert judged and all(o["rel_error"] is not None and o["time_s"] > 0 for o in judged)
    assert all(o["passed"] or o["status"] == "outside accuracy" for o in judged), judged
    assert code == (1 if any(o["status"] == "fail" for s in scenes.values() for o in s["outputs"]) else 0)
    unit = "[N]" if "guide" in name else "[N m]"
    assert any(unit in h for t in balls["tables"] for h in t["header"])


@pytest.mark.slow
@pytest.mark.parametrize("name", EXAMPLES)
def test_example_case_whole_ladder(name, tmp_path, capsys):
    code, scenes, err = _validate(name, tmp_path, capsys)
    stem = name.replace("_", "-")
    whole = {f"{stem}-whole"}  # the guide example has a [carriage] table, the screw a [nut]
    assert set(scenes) == {f"{stem}-balls", f"{stem}-contact", f"{stem}-b2b-fe", f"{stem}-stick-slip"} | whole
    assert all(s["error"] == "" for s in scenes.values()), err
    families = {o["family"] for o in scenes[f"{stem}-contact"]["outputs"]}
    assert {"analytical", "BEM", "FE"} <= families
