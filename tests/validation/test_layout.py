"""The validation layout (docs/architecture.md, "validation"): cases as data, scenes as thin runners, figures and
references apart, model identity as data.

* nothing imports a scene module (the registry loads them; calibrate, show, sweeps, studies and tests read cases
  and studies);
* a scene module holds only its ``@scene`` functions and private helpers;
* ``show.py`` and the calibrate command (studies/calibration/, but for the round trip of its scene) name no scene;
* every check declares its model family.

The habits of the whole library (object-API figures, no issue numbers, file length): tests/test_habits.py.
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest
from tests import paths
from tests.import_graph import imported_names

ROOT = paths.ROOT
SCENES = ROOT / "validation" / "scenes"
SCENE_MODULES = {f"ballbench.validation.scenes.{p.stem}" for p in SCENES.glob("*.py") if p.stem != "__init__"}


def _python_files():
    for folder in ("lowmodel", "fem", "meshes", "validation", "tests", "benchmarks", "examples", "src"):
        yield from (ROOT / folder).rglob("*.py")


def _imported_modules(path: Path) -> set[str]:
    return imported_names(path, ROOT)


def test_nothing_imports_a_scene_module():
    offenders = []
    for path in _python_files():
        if path.parent == SCENES and path.name == "__init__.py":
            continue  # the package loader the registry calls
        hits = _imported_modules(path) & SCENE_MODULES
        if hits:
            offenders.append(f"{path.relative_to(ROOT)}: {sorted(hits)}")
    assert not offenders, "scene modules are imported (move the shared code to validation/studies, cases, " \
                          "references or figures):\n" + "\n".join(offenders)


def test_the_import_check_sees_a_scene_import(tmp_path):
    probe = ROOT / "validation" / "studies" / "_probe_for_the_layout_test.py"
    try:
        probe.write_text("from ballbench.validation.scenes import fe_hertz\nfrom ..scenes.sun2021 import POINTS\n")
        assert _imported_modules(probe) & SCENE_MODULES == {"ballbench.validation.scenes.fe_hertz",
                                                            "ballbench.validation.scenes.sun2021"}
    finally:
        probe.unlink()


def test_scene_modules_hold_only_scenes_and_private_helpers():
    from ballbench.validation.scene import registry

    scene_functions = {entry.function.__name__ for entry in registry().values()}
    for path in SCENES.glob("*.py"):
        if path.name == "__init__.py":
            continue
        tree = ast.parse(path.read_text())
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and not node.name.startswith("_"):
                assert node.name in scene_functions, f"{path.name}: {node.name} is public but not a scene"


# the calibrate command's modules; the round trip is the study of the calibration-roundtrip scene
CALIBRATE = sorted(f"studies/calibration/{p.name}" for p in (ROOT / "validation/studies/calibration").glob("*.py")
                   if p.name != "roundtrip.py")


@pytest.mark.parametrize("name", ["show.py", *CALIBRATE])
def test_show_and_calibrate_name_no_scene(name):
    from ballbench.validation.scene import registry

    text = (ROOT / "validation" / name).read_text()
    named = [scene for scene in registry() if scene in text]
    prefixes = re.findall(r"""["'](?:fe|hertz|lin20\d\d|sun20\d\d|wang20\d\d)-[a-z0-9-]*\*?["']""", text)
    assert not named and not prefixes, (named, prefixes)


def test_every_check_declares_its_family(tmp_path):
    from ballbench.validation.scene import FAMILIES, Run, Scene

    run = Run(Scene("zz-family", "probe", lambda r: None), "quick", tmp_path)
    with pytest.raises(TypeError, match="family"):
        run.check(model="m", quantity="q", unit="1", value=1.0, reference=1.0, source="s", tolerance=0.0,
                  time_s=0.0)
    with pytest.raises(ValueError, match="family must be one of"):
        run.check(model="m", family="numerical", quantity="q", unit="1", value=1.0, reference=1.0, source="s",
                  tolerance=0.0, time_s=0.0)
    output = run.check(model="m", family="FE-informed", level="h 30 um", quantity="q", unit="1", value=1.0,
                       reference=1.0, source="s", tolerance=0.0, time_s=0.0)
    assert (output.family, output.level) == ("FE-informed", "h 30 um") and "FE-informed" in FAMILIES
    source = "\n".join(p.read_text() for p in SCENES.glob("*.py"))
    assert 'family="FE-informed"' in source  # the fe-b2b-* scenes' FE-informed models
