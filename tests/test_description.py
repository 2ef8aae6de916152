"""The bearing is described once, at the model layer (lowmodel.bearing; docs/architecture.md, "From a case file to a
report"), read from the files:

* outside lowmodel (and the tests and benchmarks of its models), nothing spells a bearing into the keyword entry
  points of the B2B models: no call of ``module_contacts(`` or ``screw_module(``; those keyword entry points stay
  for the paper figures that sweep one parameter, built from the description types;
* the front door's model functions are defined at the model layer: ``ballbench.friction`` and ``contact`` are
  ``ballbench.lowmodel``'s, not the harness's;
* the description types are defined in lowmodel.bearing alone: no other library module defines a class of their
  names (a validation case extends one of them with its name and FE settings).
"""
from __future__ import annotations

import ast
import re
import subprocess
import sys

import pytest

from tests import paths

OUTSIDE_LOWMODEL = ("fem", "meshes", "validation", "src", "examples")
KEYWORD_SPELLING = re.compile(r"(?<![\w.])(?:\w+\.)*(module_contacts|screw_module)\(")
DESCRIPTIONS = {"Material", "Lubricant", "Fit", "LinearGuide", "BallScrew", "GuideLoadCase", "ScrewLoadCase",
                "ContactLoadCase"}


def spellings(text: str) -> list[int]:
    """Lines that call a keyword entry point ``module_contacts(`` / ``screw_module(`` (a definition, an attribute
    chain ending in another name such as ``sm.screw_module_geometry(`` or ``ball_screw_module(`` is not one)."""
    found = []
    for number, line in enumerate(text.splitlines(), start=1):
        code = line.split("#", 1)[0]
        if code.lstrip().startswith("def "):
            continue
        for match in KEYWORD_SPELLING.finditer(code):
            if not match.group(0).startswith(("sm.", "fem.")):  # fem.screw_module is the FE module, not the model
                found.append(number)
    return found


def library_files(folders=OUTSIDE_LOWMODEL):
    return sorted(path for folder in folders for path in (paths.ROOT / folder).rglob("*.py"))


def test_nothing_outside_lowmodel_spells_a_bearing_into_model_keywords():
    found = [f"{path.relative_to(paths.ROOT)}:{line}" for path in library_files()
             for line in spellings(path.read_text())]
    assert not found, found


@pytest.mark.parametrize("text, lines", [
    ("contacts = b2b.module_contacts(theta, rho, **guide.keywords)\n", [1]),
    ("module = screw_module(lin2019.SCREW)\n", [1]),
    ("module = screw_contacts.screw_module(lead=lead)\n", [1]),
    ("def module_contacts(theta, rho):\n", []),
    ("model = sm.screw_module_geometry(r, f)\npath = ball_screw_module(r, f)\nsm.screw_module(x)\n", []),
    ("# b2b.module_contacts(theta, rho) in a comment\n", []),
    ("contacts = b2b.contacts(case)\n", []),
])
def test_the_check_sees_each_spelling(text, lines):
    assert spellings(text) == lines


def test_the_front_door_is_at_the_model_layer():
    code = ("import ballbench, sys\n"
            "print(ballbench.friction.__module__, ballbench.contact.__module__)\n"
            "print(sorted(m for m in sys.modules if m.startswith('ballbench.validation')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    modules, harness = out.stdout.splitlines()
    assert modules.split() == ["ballbench.lowmodel.bearing_results"] * 2
    assert harness == "[]"  # reaching a model loads none of the harness


def test_the_description_types_are_defined_once():
    defined = {}
    for path in library_files(("lowmodel", "fem", "meshes", "validation", "src")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef) and node.name in DESCRIPTIONS:
                defined.setdefault(node.name, []).append(str(path.relative_to(paths.ROOT)))
    assert defined == {name: ["lowmodel/bearing.py"] for name in DESCRIPTIONS}


def walk_names(text: str) -> list[str]:
    """The dotted ``ballbench.`` names of the table 'From a case file to a report' of docs/architecture.md."""
    section = text.split("## From a case file to a report", 1)[1].split("\n## ", 1)[0]
    return sorted(set(re.findall(r"`(ballbench(?:\.\w+)+)`", section)))


def resolves(name: str) -> bool:
    """Whether ``name`` is a module or an attribute of a module (imported)."""
    import importlib

    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for attribute in parts[cut:]:
                value = getattr(value, attribute)
        except AttributeError:
            return False
        return True
    return False


def test_the_walk_of_the_architecture_page_is_the_code():
    names = walk_names((paths.ROOT / "docs" / "architecture.md").read_text())
    assert len(names) >= 15 and "ballbench.lowmodel.linear_bearing.b2b.contacts" in names
    missing = [name for name in names if not resolves(name)]
    assert not missing, missing


def test_the_walk_check_sees_a_stale_name():
    text = "## From a case file to a report\n| `ballbench.lowmodel.bearing.Nothing` | `ballbench.friction` |\n## Next"
    assert walk_names(text) == ["ballbench.friction", "ballbench.lowmodel.bearing.Nothing"]
    assert [resolves(name) for name in walk_names(text)] == [True, False]
