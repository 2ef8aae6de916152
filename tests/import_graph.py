"""The import graph of the source tree, read from the files with ``ast`` (nothing is imported).

Module names are the installed ones (``ballbench.lowmodel.contact.hertz``); relative imports are resolved against
the file's package.  Every import statement counts, also one inside a function (a lazy import is still a
dependency).  Used by tests/test_layers.py (the layer rule) and tests/validation/test_layout.py (no scene import).
"""
from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

PACKAGES = ("lowmodel", "meshes", "fem", "validation")


@dataclass(frozen=True)
class Import:
    """``source`` imports ``target`` (a module, or a package's ``__init__``), taking ``name`` from it
    (``None`` for ``import target``), at ``line``."""
    source: str
    target: str
    name: str | None
    line: int


def module_name(path: Path, root: Path) -> str:
    """``lowmodel/contact/hertz.py`` -> ``ballbench.lowmodel.contact.hertz``; a package's ``__init__.py`` is the
    package."""
    parts = path.relative_to(root).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(("ballbench",) + parts)


def source_files(root: Path, packages=PACKAGES) -> dict[str, Path]:
    """Every module of ``packages`` under ``root``: installed name -> file."""
    return {module_name(path, root): path for package in packages for path in sorted((root / package).rglob("*.py"))}


def imports_of(path: Path, root: Path) -> list[Import]:
    """The import statements of one file, relative ones resolved; ``from a import b`` imports ``a.b`` when that is
    a module of the tree is decided by :func:`graph`, here ``target`` is ``a``."""
    source = module_name(path, root)
    package = source.split(".") if path.name == "__init__.py" else source.split(".")[:-1]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), filename=str(path))):
        if isinstance(node, ast.Import):
            found += [Import(source, alias.name, None, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found += [Import(source, target, alias.name, node.lineno) for alias in node.names]
    return found


def graph(root: Path, packages=PACKAGES) -> dict[str, list[Import]]:
    """Module -> its imports of other modules of the tree (``from pkg import mod`` points at ``pkg.mod``)."""
    files = source_files(root, packages)
    edges = {}
    for module, path in files.items():
        edges[module] = []
        for imp in imports_of(path, root):
            target = imp.target
            if imp.name is not None and f"{target}.{imp.name}" in files:
                target = f"{target}.{imp.name}"
            if target in files and target != module:
                edges[module].append(Import(module, target, imp.name, imp.line))
    return edges


def imported_names(path: Path, root: Path) -> set[str]:
    """Every module a file imports and every ``module.name`` it takes (to find an import of a given module)."""
    names = set()
    for imp in imports_of(path, root):
        names.add(imp.target)
        if imp.name is not None:
            names.add(f"{imp.target}.{imp.name}")
    return names
