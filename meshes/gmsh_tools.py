"""Small gmsh utilities shared by the mesh builders of ``meshes/``.

* :func:`session` - a gmsh session (initialise, quiet terminal, a fresh model;
  finalise on exit).  Use the OCC kernel through ``gmsh.model.occ``.
* :func:`cached_msh` - the cache path of a mesh from its parameters and whether
  it must be built (``lowmodel.cache``: ``cache_dir("meshes")``, ``parameter_hash``).
* :func:`write_msh` - write the current model as gmsh 4.1 ``.msh`` atomically.
* :func:`physical` - add a named physical group, refusing empty ones.
* :func:`face_point` - a point on a surface (to classify the faces of an OCC body).
* :func:`msh_to_vtu` - convert a ``.msh`` to ``.vtu`` through meshio (tetrahedra
  with a ``body`` cell tag).

Mesh-size fields: :mod:`meshes.refinement`.  gmsh is imported inside the functions
(``import ballbench.meshes.gmsh_tools`` stays light).
All lengths in metres.
"""
from __future__ import annotations

import contextlib
import os
from pathlib import Path
from typing import Iterator, Sequence

import numpy as np

from ballbench.lowmodel.cache import cache_dir, parameter_hash

__all__ = ["session", "cached_msh", "write_msh", "physical", "name_solid", "face_point", "msh_to_vtu"]


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


def physical(gmsh, dim: int, tags: Sequence[int], name: str) -> int:
    """Add the physical group ``name`` of entities ``tags`` of dimension ``dim``; returns its tag."""
    tags = [int(t) for t in tags]
    if not tags:
        raise RuntimeError(f"physical group {name!r} would be empty (geometry not identified)")
    return gmsh.model.addPhysicalGroup(dim, tags, name=name)


def name_solid(gmsh, volume: int, name: str, roles: dict) -> None:
    """The physical groups of a one-volume part: the volume ``name`` and a surface group per ``roles`` entry
    (name -> face tags)."""
    physical(gmsh, 3, [volume], name)
    for role, faces in roles.items():
        physical(gmsh, 2, faces, role)


def face_point(gmsh, tag: int) -> np.ndarray:
    """A point [m] on surface ``tag``: its value at the middle of its parametric box, shape (3,)."""
    lo, hi = gmsh.model.getParametrizationBounds(2, tag)
    return np.asarray(gmsh.model.getValue(2, tag, [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2]))


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
