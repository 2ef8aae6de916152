"""Imports sit at the top of their module (docs/developing.md, 'Imports'), read from the files with ``ast``
(nothing is imported): an import inside a function of lowmodel/, fem/, meshes/, validation/ or src/ needs a reason
named here.

* :data:`OPTIONAL`: a library outside ``pip install ballbench`` (pyproject's extras), imported where it is used,
  anywhere: the modules that use it still import on the base install.
* :data:`LIGHT`: ``(file, module)`` pairs that keep a module off a light path: ``import ballbench``, the CLI's startup
  (``ballbench --version``, ``init``, ``validate --help``: cli imports the ladder, the sweeps, calibrate and the case
  files for their names) and ``ballbench scenes`` (every scene module and what it imports).  Each keeps out a module
  that path does not load; moved to the top together they would nearly double ``ballbench --version``
  (docs/developing.md, 'Imports', has the figures).  ``test_the_light_paths_stay_light`` checks the paths.

A module is matched with its submodules (``scipy.interpolate`` allows ``scipy.interpolate._cubic``); ``from a import
b`` imports ``a`` and, when it is one, the module ``a.b``.
"""
from __future__ import annotations

import ast
import subprocess
import sys

import pytest

from tests import paths

LIBRARY = ("lowmodel", "fem", "meshes", "validation", "src")

# library -> the extra of pyproject that installs it
OPTIONAL = {
    "gmsh": "fem", "skfem": "fem", "meshio": "fem", "pypardiso": "fem", "quadprog": "fem",
    "pyvista": "pictures", "vtk": "pictures", "vtkmodules": "pictures (pyvista's VTK)", "matplotlib": "pictures",
    "PIL": "pictures (matplotlib's Pillow)",
    "dask": "sweeps", "distributed": "sweeps", "pyarrow": "sweeps", "xarray": "sweeps", "zarr": "sweeps",
    "psutil": "sweeps (dask.distributed's)",
    "numba": "fast", "llvmlite": "fast (numba's)",
    "tamaas": "test",
}

FRONT = "import ballbench loads no layer and nothing a bare interpreter does not (tests/test_api.py)"
STARTUP = "the CLI's startup imports this file; the module is not loaded there"
SCENES = "ballbench scenes imports this file; the module is not loaded there"
READ = "ballbench.load_case imports this file and loads no model (numpy and the description types only)"
CARRIAGE = ("ballbench.load_case imports this file; the carriage and nut models load only for a file with a [carriage] "
            "or [nut] table")
LIGHT = {
    ("lowmodel/bearing.py", "ballbench.lowmodel.contact.hertz"): READ,
    ("validation/cases/case_file.py", "ballbench.lowmodel.linear_bearing.carriage"): CARRIAGE,
    ("validation/cases/case_file.py", "ballbench.lowmodel.screw"): READ,
    ("src/ballbench/__init__.py", "importlib"): FRONT,
    ("src/ballbench/__init__.py", "pathlib"): FRONT,
    ("src/ballbench/__init__.py", "tempfile"): FRONT,
    ("src/ballbench/__init__.py", "ballbench.validation"): FRONT,
    # lowmodel: scipy.stats (260 ms), scipy.interpolate (30 ms) and the friction maps' modules
    ("lowmodel/calibration.py", "scipy.stats"): STARTUP,
    ("lowmodel/screw/contacts.py", "scipy.interpolate"): STARTUP,
    ("lowmodel/contact/ehl.py", "scipy.interpolate"): SCENES,
    ("lowmodel/contact/ellipse_friction.py", "scipy.interpolate"): SCENES,
    ("lowmodel/contact/halfspace.py", "ducc0.fft"): SCENES,
    ("lowmodel/contact/rolling_operators.py", "ducc0.fft"): SCENES,
    ("lowmodel/bearing_results.py", "ballbench.lowmodel.linear_bearing.b2b_rolling"): STARTUP,
    ("lowmodel/bearing_results.py", "ballbench.lowmodel.screw.b2b_rolling"): STARTUP,
    ("lowmodel/linear_bearing/carriage_friction.py", "ballbench.lowmodel.linear_bearing.b2b"): STARTUP,
    ("lowmodel/linear_bearing/carriage_friction.py", "ballbench.lowmodel.linear_bearing.b2b_rolling"): STARTUP,
    ("lowmodel/linear_bearing/carriage_friction.py", "ballbench.lowmodel.linear_bearing.contacts"): STARTUP,
    ("lowmodel/linear_bearing/ball_fast.py", "ballbench.lowmodel.contact.ellipse_friction"): STARTUP,
    ("lowmodel/linear_bearing/contacts.py", "ballbench.lowmodel.contact.ellipse_friction"): STARTUP,
    ("lowmodel/linear_bearing/contacts.py", "ballbench.lowmodel.linear_bearing.fourpoint"): STARTUP,
    ("lowmodel/screw/ball.py", "ballbench.lowmodel.contact.ellipse_friction_offset"): STARTUP,
    ("lowmodel/screw/contacts.py", "ballbench.lowmodel.contact.ellipse_friction"): STARTUP,
    # validation: the report writers, the progress bars (tqdm.auto: 20 ms), and what the ladder's rungs run
    ("validation/cli.py", "ballbench.validation.report"): STARTUP,
    ("validation/scene.py", "tqdm.auto"): STARTUP,
    ("validation/runner.py", "tqdm.auto"): STARTUP,
    ("validation/sweep/execution.py", "tqdm.auto"): STARTUP,
    ("validation/studies/fe_contact.py", "tqdm.auto"): SCENES,
    ("validation/ladder/__init__.py", "ballbench.validation.studies.case_ehl"): STARTUP,
    ("validation/ladder/b2b_fe.py", "ballbench.fem.fourpoint"): STARTUP,
    ("validation/ladder/b2b_fe.py", "ballbench.lowmodel.linear_bearing.b2b_analytical"): STARTUP,
    ("validation/ladder/b2b_fe.py", "ballbench.validation.figures.render3d"): STARTUP,
    ("validation/ladder/b2b_fe.py", "ballbench.validation.studies.fe_b2b_linear"): STARTUP,
    ("validation/ladder/b2b_fe.py", "ballbench.validation.studies.fe_b2b_screw"): STARTUP,
    ("validation/ladder/balls.py", "ballbench.lowmodel.linear_bearing.b2b_analytical"): STARTUP,
    ("validation/ladder/contact.py", "ballbench.validation.figures.render3d"): STARTUP,
    ("validation/ladder/contact.py", "ballbench.validation.studies.fe_contact"): STARTUP,
    ("validation/ladder/ehl.py", "ballbench.validation.studies.case_ehl"): STARTUP,
    ("validation/ladder/rungs.py", "ballbench.lowmodel.contact.halfspace"): STARTUP,
    ("validation/ladder/rungs.py", "ballbench.lowmodel.contact.screw_contact"): STARTUP,
    ("validation/ladder/rungs.py", "ballbench.validation.studies.fe_contact"): STARTUP,
    ("validation/ladder/rungs.py", "ballbench.fem.hertz_case"): STARTUP,
    ("validation/ladder/stick_slip.py", "ballbench.lowmodel.contact.rolling_friction"): STARTUP,
    ("validation/ladder/stick_slip.py", "ballbench.lowmodel.full_slip_validity"): STARTUP,
    ("validation/ladder/stick_slip.py", "ballbench.validation.figures.stickslip3d"): STARTUP,
    ("validation/ladder/whole.py", "ballbench.validation.figures.carriage"): STARTUP,
    ("validation/ladder/whole_nut.py", "ballbench.validation.figures"): STARTUP,
    ("validation/ladder/whole.py", "ballbench.fem"): STARTUP,
    ("validation/ladder/whole_show.py", "ballbench.validation.figures"): STARTUP,
    ("validation/ladder/whole_nut.py", "ballbench.lowmodel.screw"): STARTUP,
    ("validation/ladder/whole_nut.py", "ballbench.fem"): STARTUP,
    ("validation/ladder/stick_slip.py", "ballbench.validation.studies.case_stick_slip"): STARTUP,
    ("validation/ladder/stick_slip.py", "ballbench.validation.studies.rolling_b2b"): STARTUP,
    ("validation/studies/calibration/fe_laws.py", "ballbench.validation.studies.fe_contact"): STARTUP,
    ("validation/studies/calibration/spec.py", "ballbench.lowmodel.contact.ellipse_friction"): STARTUP,
    # validation: the FE solves, meshes and figures the scene modules and their studies use when they run
    ("validation/figures/render3d.py", "ballbench.fem.fields"): SCENES,
    ("validation/scenes/calibration.py", "ballbench.lowmodel.screw.load_distribution"): SCENES,
    ("validation/scenes/calibration.py", "ballbench.lowmodel.screw.whole_screw"): SCENES,
    ("validation/scenes/calibration.py", "ballbench.validation.figures.hertz"): SCENES,
    ("validation/scenes/fe_hertz.py", "ballbench.validation.figures.fe_contact"): SCENES,
    ("validation/scenes/hertz.py", "ballbench.validation.figures.hertz"): SCENES,
    ("validation/scenes/lin2019_bearing.py", "ballbench.lowmodel.linear_bearing.b2b_rolling"): SCENES,
    ("validation/scenes/lin2019_screw.py", "ballbench.lowmodel.screw.whole_screw"): SCENES,
    ("validation/scenes/rolling.py", "ballbench.fem.rolling_compliance"): SCENES,
    ("validation/scenes/rolling.py", "ballbench.meshes.assemblies.contact_pairs"): SCENES,
    ("validation/studies/fe_b2b_linear.py", "ballbench.fem.fields"): SCENES,
    ("validation/studies/fe_b2b_linear.py", "ballbench.fem.fourpoint"): SCENES,
    ("validation/studies/fe_b2b_linear.py", "ballbench.meshes.assemblies.fourpoint_module"): SCENES,
    ("validation/studies/fe_b2b_screw.py", "ballbench.fem.fields"): SCENES,
    ("validation/studies/fe_b2b_screw.py", "ballbench.fem.fourpoint"): SCENES,
    ("validation/studies/fe_b2b_screw.py", "ballbench.fem.screw_module"): SCENES,
    ("validation/studies/fe_b2b_screw.py", "ballbench.meshes.assemblies.ball_screw_module"): SCENES,
    ("validation/studies/fe_contact.py", "ballbench.meshes.assemblies.contact_pairs"): SCENES,
    ("validation/studies/fe_contact.py", "ballbench.meshes.assemblies.screw_pair"): SCENES,
    ("validation/studies/fe_contact.py", "ballbench.validation.figures.fe_contact"): SCENES,
    ("validation/studies/rolling_b2b.py", "ballbench.fem.rolling_compliance"): SCENES,
    ("validation/studies/rolling_b2b.py", "ballbench.meshes.assemblies.contact_pairs"): SCENES,
    ("validation/studies/sun2021.py", "ballbench.meshes.assemblies.screw_pair"): SCENES,
    ("validation/sweep/functions.py", "ballbench.lowmodel.screw.load_distribution"): SCENES,
    ("validation/sweep/functions.py", "ballbench.lowmodel.screw.whole_screw"): SCENES,
}
ALLOWED = dict(LIGHT)


def library_files():
    return sorted(path for package in LIBRARY for path in (paths.ROOT / package).rglob("*.py"))


def relative(path) -> str:
    return path.relative_to(paths.ROOT).as_posix()


def within(module: str, name: str) -> bool:
    """``module`` is ``name`` or one of its submodules."""
    return module == name or module.startswith(name + ".")


def function_imports(text: str) -> list[tuple[int, list[list[str]]]]:
    """Every import statement inside a function (at any depth) of the module ``text``: ``(line, targets)`` with,
    per imported name, the modules it may load (``from a import b``: ``a`` and ``a.b``)."""
    found = []

    def visit(node, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            if in_function and isinstance(child, ast.Import):
                found.append((child.lineno, [[alias.name] for alias in child.names]))
            elif in_function and isinstance(child, ast.ImportFrom):
                module = "." * child.level + (child.module or "")
                found.append((child.lineno, [[module, f"{module}.{alias.name}"] for alias in child.names]))
            visit(child, in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

    visit(ast.parse(text), False)
    return found


def reason(file: str, targets: list[str]) -> str | None:
    """Why ``file`` may import one name (its ``targets``) inside a function; None if nothing allows it."""
    for module in targets:
        top = module.split(".")[0]
        if top in OPTIONAL:
            return f"optional ({OPTIONAL[top]})"
        for (where, name), why in ALLOWED.items():
            if where == file and within(module, name):
                return why
    return None


def stray_imports(file: str, text: str) -> list[str]:
    """``file:line: module`` of each import inside a function that no reason allows."""
    return [f"{file}:{line}: {targets[0]}" for line, names in function_imports(text) for targets in names
            if reason(file, targets) is None]


def test_the_library_is_read():
    names = {relative(path) for path in library_files()}
    assert {"lowmodel/contact/hertz.py", "fem/elasticity.py", "validation/cli.py", "src/ballbench/__init__.py"} <= names


def test_imports_inside_functions_have_a_reason():
    found = [line for path in library_files() for line in stray_imports(relative(path), path.read_text())]
    assert not found, "move these imports to the top of their module, or name the reason in tests/test_imports.py: " \
        + ", ".join(found)


def test_every_allowed_lazy_import_is_used():
    # an entry whose import moved up (or went) is removed, so that the list stays the list of what is lazy
    used = set()
    for path in library_files():
        file = relative(path)
        for _, names in function_imports(path.read_text()):
            for targets in names:
                used |= {(file, name) for (where, name) in ALLOWED if where == file
                         and any(within(module, name) for module in targets)}
    assert not set(ALLOWED) - used, sorted(set(ALLOWED) - used)


@pytest.mark.parametrize("file, text, stray", [
    ("validation/x.py", "import json\n\n\ndef f():\n    return json\n", []),
    ("validation/x.py", "def f():\n    import json\n    return json\n", ["validation/x.py:2: json"]),
    ("lowmodel/x.py", "class A:\n    def f(self):\n        from scipy import optimize\n",
     ["lowmodel/x.py:3: scipy"]),
    ("fem/x.py", "def f():\n    def g():\n        from ballbench.fem import surface\n    return g\n",
     ["fem/x.py:3: ballbench.fem"]),
    ("lowmodel/x.py", "def f():\n    try:\n        import threadpoolctl\n    except ImportError:\n        pass\n",
     ["lowmodel/x.py:3: threadpoolctl"]),
    ("validation/x.py", "def f():\n    from matplotlib.figure import Figure\n    import pyvista, gmsh\n", []),
    ("validation/x.py", "def f():\n    import dask.distributed\n    from skfem import MeshTet\n", []),
    # a light-path entry allows its file only, and the named module with its submodules only
    ("validation/cli.py", "def f():\n    from ballbench.validation.report.rows import passing_lines\n", []),
    ("validation/usage.py", "def f():\n    from ballbench.validation.report.rows import passing_lines\n",
     ["validation/usage.py:2: ballbench.validation.report.rows"]),
    ("lowmodel/calibration.py", "def f():\n    from scipy import optimize, stats\n",
     ["lowmodel/calibration.py:2: scipy"]),
    ("lowmodel/calibration.py", "def f():\n    from scipy import stats\n", []),
])
def test_the_check_sees_each_stray_import(file, text, stray):
    assert stray_imports(file, text) == stray


# what each light path must not load: the modules the reasons above keep off it
KEPT_OFF = {
    "import ballbench": ("import ballbench", ["numpy", "importlib.metadata", "tempfile", "ballbench.validation"]),
    "reading a case file": ("import ballbench; ballbench.load_case(sys.argv[1])",
                            ["scipy", "ballbench.lowmodel.contact", "ballbench.lowmodel.screw",
                             "ballbench.lowmodel.linear_bearing", "ballbench.validation.ladder"]),
    "the CLI's startup": ("import ballbench.validation.cli",
                          ["scipy.stats", "scipy.interpolate", "tqdm", "ballbench.validation.report",
                           "ballbench.validation.studies.fe_contact", "ballbench.validation.studies.rolling_b2b",
                           "ballbench.lowmodel.contact.ellipse_friction", "ballbench.lowmodel.contact.halfspace",
                           "ballbench.fem"]),
    "ballbench scenes": ("from ballbench.validation.scene import registry; registry()",
                         ["scipy.interpolate", "tqdm", "ducc0", "skfem", "meshio", "pypardiso", "quadprog",
                          "matplotlib", "ballbench.validation.report", "ballbench.fem.fourpoint",
                          "ballbench.fem.rolling_compliance", "ballbench.meshes.assemblies",
                          "ballbench.lowmodel.screw.whole_screw"]),
}


@pytest.mark.parametrize("path", list(KEPT_OFF))
def test_the_light_paths_stay_light(path, tmp_path):
    """The example screw without its [nut] table (the nut model loads only for a file with one, as the carriage's)."""
    code, kept_off = KEPT_OFF[path]
    text = (paths.ROOT / "examples" / "ball_screw_32x10.toml").read_text()
    case = tmp_path / "screw.toml"
    case.write_text(text[:text.index("[nut]")])
    out = subprocess.run([sys.executable, "-c", f"import sys\n{code}\nprint('\\n'.join(sys.modules))", str(case)],
                         capture_output=True, text=True, check=True)
    loaded = [name for name in kept_off if any(within(module, name) for module in out.stdout.split())]
    assert not loaded, f"{path} loads {loaded}"
