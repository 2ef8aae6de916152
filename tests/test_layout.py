"""The install layout: one ``ballbench`` namespace, a light ``lowmodel``."""
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = ("lowmodel", "fem", "meshes", "validation")


def test_every_package_folder_is_installed():
    # a sub-package missing from pyproject's explicit list would be absent from a wheel
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    for folder in FOLDERS:
        assert config["package-dir"][f"ballbench.{folder}"] == folder
        for init in (ROOT / folder).rglob("__init__.py"):
            name = ".".join(("ballbench",) + init.parent.relative_to(ROOT).parts)
            assert name in listed, f"{name} is missing from [tool.setuptools] packages"


def test_lowmodel_import_is_light():
    # gmsh, pyvista, vtk and matplotlib are imported only inside the code that needs them
    # numba too: the compiled kernels (modules *_kernels) are imported by lowmodel.kernels.load at the first solve
    code = ("import sys, ballbench.lowmodel, pkgutil, importlib\n"
            "for m in pkgutil.walk_packages(ballbench.lowmodel.__path__, 'ballbench.lowmodel.'):\n"
            "    if not m.name.endswith('_kernels'):\n"
            "        importlib.import_module(m.name)\n"
            "heavy = sorted({n.split('.')[0] for n in sys.modules} & {'gmsh', 'pyvista', 'vtk', 'matplotlib', "
            "'numba', 'llvmlite'})\n"
            "print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_python_m_ballbench_runs():
    out = subprocess.run([sys.executable, "-m", "ballbench", "scenes"], capture_output=True, text=True, cwd="/")
    assert out.returncode == 0, out.stderr
    assert "lin2019-table3-a" in out.stdout
