"""What the README promises about installing and testing (README, pyproject, .ci/run):

* `.ci/run` runs exactly the README's test command;
* `pip install ballbench` alone installs no FE, mesh, plotting or sweep library; the extras `fem`, `pictures` and
  `sweeps` add them, `all` is the three, `test` is `all` and the test tools;
* the licence file is the one pyproject names.
"""
from __future__ import annotations

import re
import tomllib

from tests import paths

PYPROJECT = tomllib.loads((paths.ROOT / "pyproject.toml").read_text())["project"]
HEAVY = {"scikit-fem", "gmsh", "meshio", "pyvista", "matplotlib", "dask", "pyarrow", "xarray", "zarr", "quadprog",
         "pypardiso", "vtk"}


def names(requirements) -> set[str]:
    return {re.match(r"[A-Za-z0-9_.-]+", r).group(0).lower() for r in requirements}


def test_ci_runs_the_readme_test_command():
    readme = (paths.ROOT / "README.md").read_text()
    blocks = re.findall(r"```bash\n(.*?)```", readme, re.S)
    test_command = next(b.strip() for b in blocks if "pytest" in b and "venv" in b)
    ci = [line for line in (paths.ROOT / ".ci" / "run").read_text().splitlines()
          if line.strip() and not line.startswith(("#", "set ", "cd "))]
    assert ci == [test_command]


def test_the_base_install_is_the_low_order_models():
    assert {"numpy", "scipy"} <= names(PYPROJECT["dependencies"])
    assert not names(PYPROJECT["dependencies"]) & HEAVY


def test_the_extras_add_the_rest():
    extras = PYPROJECT["optional-dependencies"]
    assert {"scikit-fem", "gmsh", "meshio"} <= names(extras["fem"])
    assert {"pyvista", "matplotlib"} <= names(extras["pictures"])
    assert {"dask", "pyarrow", "xarray", "zarr"} <= names(extras["sweeps"])
    assert extras["all"] == ["ballbench[fem,pictures,sweeps]"]
    assert "ballbench[all]" in extras["test"] and "pytest" in names(extras["test"])
    # the compiled kernels: an extra (numba pins numpy from above), which the tests install to run both paths
    assert names(extras["fast"]) == {"numba"} and "ballbench[fast]" in extras["test"]


def test_the_licence_is_shipped():
    assert PYPROJECT["license-files"] == ["LICENSE"] and PYPROJECT["license"] == "BSD-3-Clause"
    assert (paths.ROOT / "LICENSE").read_text().startswith("BSD 3-Clause License")
