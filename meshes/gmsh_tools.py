"""Small gmsh utilities shared by the mesh builders of ``meshes/``.

* :func:`session` - a gmsh session (initialise, quiet terminal, a fresh model;
  finalise on exit).  Use the OCC kernel through ``gmsh.model.occ``.
* :func:`cached_msh` - the cache path of a mesh from its parameters and whether
  it must be built (``lowmodel.cache``: ``cache_dir("meshes")``, ``parameter_hash``).
* :func:`write_msh` - write the current model as gmsh 4.1 ``.msh`` atomically.
* :func:`contact_refinement` - a size field ``h(r) = min(h_max, h_contact +
  (growth - 1) max(0, r - fine_radius))`` about a point (the contact point),
  the only size control (MeshSizeFromPoints, MeshSizeFromCurvature and
  MeshSizeExtendFromBoundary switched off: otherwise gmsh ignores the field
  near small curves, issue 5 notes).
* :func:`physical` - add a named physical group, refusing empty ones.
* :func:`msh_to_vtu` - convert a ``.msh`` to ``.vtu`` through meshio (tetrahedra
  with a ``body`` cell tag).

gmsh is imported inside the functions (``import meshes.gmsh_tools`` stays light).
All lengths in metres.
"""
from __future__ import annotations

import contextlib
import math
import os
from pathlib import Path
from typing import Iterator, Sequence

__all__ = ["session", "cached_msh", "write_msh", "contact_refinement", "physical", "msh_to_vtu"]


@contextlib.contextmanager
def session(model_name: str = "model") -> Iterator[object]:
    """Context manager yielding the ``gmsh`` module with a fresh model ``model_name``.

    gmsh is initialised without signal handlers (safe in threads and pytest),
    with its terminal output off, and finalised on exit even after an error.
    """
    import gmsh

    if gmsh.isInitialized():
        gmsh.finalize()
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add(model_name)
        yield gmsh
    finally:
        gmsh.finalize()


def cached_msh(prefix: str, parameters: dict, version: str = "1", *, cache: bool = True) -> tuple[Path, bool]:
    """Cache path ``<cache>/meshes/<prefix>-<hash>.msh`` of a mesh and whether to build it.

    ``parameters`` must hold every input that changes the mesh (JSON-serialisable);
    ``version`` is the builder's format version (bump it when the builder changes).
    Returns ``(path, build)``; ``build`` is True if the file is missing or
    ``cache`` is False.
    """
    from ballbench.lowmodel.cache import cache_dir, parameter_hash

    path = cache_dir("meshes") / f"{prefix}-{parameter_hash(parameters, version)}.msh"
    return path, (not cache) or (not path.exists())


def write_msh(gmsh, path: Path) -> Path:
    """Write the current gmsh model to ``path`` (format 4.1, binary off) atomically."""
    path = Path(path)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    tmp = path.with_name(f"{path.stem}.{os.getpid()}.tmp.msh")
    gmsh.write(str(tmp))
    tmp.replace(path)
    return path


def contact_refinement(gmsh, h_contact: float, growth: float, h_max: float, *,
                       point: Sequence[float] = (0.0, 0.0, 0.0), fine_radius: float = 0.0) -> int:
    """Background size field refined about ``point`` [m]; returns the field tag.

    ``h(r) = min(h_max, h_contact + (growth - 1) max(0, r - fine_radius))`` with
    ``r`` the distance from ``point``: along a ray away from the fine zone the
    size of neighbouring elements differs by about the factor ``growth``
    (``h(r + h) = h + (growth - 1) h``).  ``h_contact``, ``h_max``, ``fine_radius``
    in metres; ``growth`` in [1, 3].
    """
    for name, value in (("h_contact", h_contact), ("h_max", h_max)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be a finite length > 0 m, got {value!r}")
    if not (math.isfinite(growth) and 1.0 <= growth <= 3.0):
        raise ValueError(f"growth (size ratio of neighbouring elements) must lie in [1, 3], got {growth!r}")
    if not h_max >= h_contact:
        raise ValueError(f"h_max must be >= h_contact = {h_contact!r} m, got {h_max!r}")
    if not (math.isfinite(fine_radius) and fine_radius >= 0.0):
        raise ValueError(f"fine_radius must lie in [0, inf) m, got {fine_radius!r}")
    x0, y0, z0 = (float(c) for c in point)
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    field.setString(distance, "F", f"Sqrt((x-({x0!r}))^2 + (y-({y0!r}))^2 + (z-({z0!r}))^2)")
    return size_threshold(gmsh, distance, h_contact, growth, h_max, fine_radius=fine_radius)


def size_threshold(gmsh, distance_field: int, h_contact: float, growth: float, h_max: float, *,
                   fine_radius: float = 0.0) -> int:
    """Background size ``h = min(h_max, h_contact + (growth - 1) max(0, d - fine_radius))``
    with ``d`` the value [m] of the gmsh field ``distance_field``; returns the field tag.

    Turns off MeshSizeFromPoints/FromCurvature/ExtendFromBoundary so that the
    field alone governs the size (issue 5 notes).
    """
    field = gmsh.model.mesh.field
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance_field)
    field.setNumber(threshold, "SizeMin", h_contact)
    field.setNumber(threshold, "SizeMax", h_max)
    field.setNumber(threshold, "DistMin", fine_radius)
    slope = max(growth - 1.0, 1e-9)
    field.setNumber(threshold, "DistMax", fine_radius + (h_max - h_contact) / slope)
    field.setAsBackgroundMesh(threshold)
    for option in ("Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeExtendFromBoundary"):
        gmsh.option.setNumber(option, 0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h_max)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    return threshold


def physical(gmsh, dim: int, tags: Sequence[int], name: str) -> int:
    """Add the physical group ``name`` of entities ``tags`` of dimension ``dim``; returns its tag."""
    tags = [int(t) for t in tags]
    if not tags:
        raise RuntimeError(f"physical group {name!r} would be empty (geometry not identified)")
    return gmsh.model.addPhysicalGroup(dim, tags, name=name)


def msh_to_vtu(msh_path: Path, vtu_path: Path | None = None) -> Path:
    """Convert the tetrahedra of a ``.msh`` to ``.vtu`` (meshio); cell data ``body``
    is the physical volume tag.  Returns the ``.vtu`` path (default: beside the ``.msh``)."""
    import meshio

    msh_path = Path(msh_path)
    vtu_path = msh_path.with_suffix(".vtu") if vtu_path is None else Path(vtu_path)
    mesh = meshio.read(msh_path)
    blocks, tags = [], []
    physical_tags = mesh.cell_data.get("gmsh:physical")
    for i, block in enumerate(mesh.cells):
        if block.type.startswith("tetra"):
            blocks.append(block)
            tags.append(physical_tags[i] if physical_tags is not None else [0] * len(block.data))
    out = meshio.Mesh(mesh.points, blocks, cell_data={"body": tags})
    out.write(vtu_path)
    return vtu_path
