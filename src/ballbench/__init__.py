"""ballbench: validate and calibrate low-order friction models of ball bearings
and ball screws against finite-element analysis and published numbers.

The four layers install under this namespace from the project's top-level
folders (pyproject ``package-dir``): ``ballbench.lowmodel`` (``lowmodel/``),
``ballbench.meshes`` (``meshes/``), ``ballbench.fem`` (``fem/``) and
``ballbench.validation`` (``validation/``).  Layers and the import rule:
docs/architecture.md.  Importing this package imports none of them.
"""
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("ballbench")
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"
