"""The layer rule of docs/architecture.md, checked on the source tree (read with ``ast``, nothing imported):

geometry core -> models / meshes -> fem -> validation: a module imports only from its own layer and the layers
before it (models and meshes are siblings: neither imports the other); no import cycle between modules; no
private name (``_x``) imported from another file.
"""
from __future__ import annotations

import pytest

from tests import paths
from tests.import_graph import graph

# the geometry core: the geometry package and what it may use (input checks, errors, the file cache)
CORE = ("ballbench.lowmodel.geometry", "ballbench.lowmodel.checks", "ballbench.lowmodel.errors",
        "ballbench.lowmodel.cache")
# layer -> the layers it may import
MAY_IMPORT = {
    "core": {"core"},
    "models": {"core", "models"},
    "meshes": {"core", "meshes"},
    "fem": {"core", "models", "meshes", "fem"},
    "validation": {"core", "models", "meshes", "fem", "validation"},
}


def layer(module: str) -> str:
    if module == "ballbench.lowmodel" or any(module == c or module.startswith(c + ".") for c in CORE):
        return "core"  # the lowmodel package's __init__ holds only its docstring
    return {"lowmodel": "models"}.get(module.split(".")[1], module.split(".")[1])


def upward_imports(edges) -> list[str]:
    return [f"{imp.source} ({layer(imp.source)}) imports {imp.target} ({layer(imp.target)}), line {imp.line}"
            for imports in edges.values() for imp in imports if layer(imp.target) not in MAY_IMPORT[layer(imp.source)]]


def private_imports(edges) -> list[str]:
    return [f"{imp.source} takes {imp.name} from {imp.target}, line {imp.line}" for imports in edges.values()
            for imp in imports if imp.name and imp.name.startswith("_") and not imp.name.startswith("__")]


def cycles(edges) -> list[list[str]]:
    """The import cycles: groups of two or more modules that reach each other (strongly connected components,
    found as the modules reachable from a module and from which it is reachable)."""
    targets = {module: {imp.target for imp in imports} for module, imports in edges.items()}

    def reachable(start):
        seen, todo = set(), [start]
        while todo:
            for nxt in targets.get(todo.pop(), ()):
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return seen

    reach = {module: reachable(module) for module in targets}
    groups = {frozenset({m} | {o for o in reach[m] if m in reach[o]}) for m in targets if m in reach[m]}
    return sorted(sorted(group) for group in groups if len(group) > 1)


@pytest.fixture(scope="module")
def edges():
    return graph(paths.ROOT)


def test_the_tree_is_read(edges):
    assert "ballbench.lowmodel.geometry.helix" in edges and "ballbench.validation.cli" in edges
    assert {imp.target for imp in edges["ballbench.lowmodel.geometry.groove"]} >= {
        "ballbench.lowmodel.checks", "ballbench.lowmodel.geometry.helix"}


def test_no_upward_import(edges):
    found = upward_imports(edges)
    assert not found, "\n".join(found)


def test_no_import_cycle(edges):
    found = cycles(edges)
    assert not found, "\n".join(" <-> ".join(group) for group in found)


def test_no_private_name_crosses_a_file(edges):
    found = private_imports(edges)
    assert not found, "\n".join(found)


def test_the_checks_see_each_breach(tmp_path):
    # a tree with one breach of each rule: an upward import (a model imports fem), a sibling import (meshes
    # imports a model), a cycle of three modules, a private name taken from another file
    files = {
        "lowmodel/__init__.py": "",
        "lowmodel/geometry/__init__.py": "",
        "lowmodel/geometry/helix.py": "from .. import checks\n",
        "lowmodel/checks.py": "",
        "lowmodel/contact/__init__.py": "",
        "lowmodel/contact/hertz.py": "def f():\n    from ballbench.fem import linsolve\n",
        "lowmodel/contact/a.py": "from . import b\n",
        "lowmodel/contact/b.py": "from ballbench.lowmodel.contact.c import _private\n",
        "lowmodel/contact/c.py": "import ballbench.lowmodel.contact.a\n",
        "meshes/__init__.py": "",
        "meshes/parts.py": "from ballbench.lowmodel.contact import hertz\nfrom ballbench.lowmodel import checks\n",
        "fem/__init__.py": "",
        "fem/linsolve.py": "",
        "fem/contact.py": "from ballbench.lowmodel.contact import hertz\nfrom ballbench.meshes import parts\n",
        "validation/__init__.py": "",
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    breach = graph(tmp_path)
    assert upward_imports(breach) == [
        "ballbench.lowmodel.contact.hertz (models) imports ballbench.fem.linsolve (fem), line 2",
        "ballbench.meshes.parts (meshes) imports ballbench.lowmodel.contact.hertz (models), line 1"]
    assert cycles(breach) == [["ballbench.lowmodel.contact.a", "ballbench.lowmodel.contact.b",
                               "ballbench.lowmodel.contact.c"]]
    assert private_imports(breach) == [
        "ballbench.lowmodel.contact.b takes _private from ballbench.lowmodel.contact.c, line 1"]
