"""Habits of the library code (lowmodel/, fem/, meshes/, validation/, src/; docs/developing.md), read from the files:

* figures use matplotlib's object API (``matplotlib.figure.Figure``): no ``matplotlib.use``, no pyplot;
* code cites papers, equations and docs pages, never an issue number;
* a file stays at 600 lines or below unless its module docstring says why it is one concept.
"""
from __future__ import annotations

import ast
import re

import pytest

from tests import paths

LIBRARY = ("lowmodel", "fem", "meshes", "validation", "src")
LONGEST = 600
# being split into smaller modules on its own branch; remove the entry when that lands
SPLIT_PENDING: set[str] = set()  # files over the limit whose split is on its way (none)
ISSUE_NUMBER = re.compile(r"\bissues? ?#?\d+", re.IGNORECASE)
PYPLOT = re.compile(r"matplotlib\.use\(|import matplotlib\.pyplot|from matplotlib import pyplot|\bplt\.")


def library_files():
    return sorted(path for package in LIBRARY for path in (paths.ROOT / package).rglob("*.py"))


def relative(path) -> str:
    return path.relative_to(paths.ROOT).as_posix()


def pyplot_uses(text: str) -> list[int]:
    return [number for number, line in enumerate(text.splitlines(), start=1) if PYPLOT.search(line)]


def issue_numbers(text: str) -> list[int]:
    return [number for number, line in enumerate(text.splitlines(), start=1) if ISSUE_NUMBER.search(line)]


def too_long(text: str) -> bool:
    doc = ast.get_docstring(ast.parse(text)) or ""
    return text.count("\n") > LONGEST and "one concept" not in doc.lower()


def test_the_library_is_read():
    names = {relative(path) for path in library_files()}
    assert {"lowmodel/contact/hertz.py", "fem/elasticity.py", "validation/cli.py"} <= names


def test_figures_use_the_object_api():
    found = [f"{relative(path)}:{line}" for path in library_files() for line in pyplot_uses(path.read_text())]
    assert not found, found


def test_code_cites_no_issue_number():
    found = [f"{relative(path)}:{line}" for path in library_files() for line in issue_numbers(path.read_text())]
    assert not found, found


def test_files_stay_short_or_say_why():
    found = [f"{relative(path)}: {path.read_text().count(chr(10))} lines" for path in library_files()
             if relative(path) not in SPLIT_PENDING and too_long(path.read_text())]
    assert not found, found


@pytest.mark.parametrize("text, pyplot, issue", [
    ("import matplotlib\nmatplotlib.use('Agg')\n", [2], []),
    ("def f():\n    import matplotlib.pyplot as plt\n    plt.figure()\n", [2, 3], []),
    ("# tolerance from issue 12\nx = 1\n", [], [1]),
    ("# see Issues #7 and lin2019 eq 12\n", [], [1]),
    ("from matplotlib.figure import Figure\n# lin2019 eq 12, docs/fem.md\n", [], []),
])
def test_the_checks_see_each_breach(text, pyplot, issue):
    assert pyplot_uses(text) == pyplot and issue_numbers(text) == issue


def test_a_long_file_needs_its_reason():
    body = "x = 1\n" * (LONGEST + 1)
    assert too_long('"""A module."""\n' + body)
    assert not too_long('"""A module: one concept, the X solver and its table."""\n' + body)
    assert not too_long('"""A module."""\n' + "x = 1\n" * (LONGEST - 2))
