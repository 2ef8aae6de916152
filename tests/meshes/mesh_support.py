"""Shared by the gmsh builder tests (tests/meshes/...): the lin2019 Table 4 and Table 1 dimensions, the private mesh
cache fixture, and the readers of a meshio mesh (physical groups, volumes, surface fits)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove as groove_core

# lin2019 Table 4
R_B, CONF, R_P, LEAD, BETA = 2.778e-3, 0.56, 16.5e-3, 20e-3, math.radians(45.0)
COARSE = dict(h_contact=1.0e-4, growth=1.5)
R_RAIL = 5e-3  # lin2019 Table 1
DEV = math.radians(2.0)


def circle_fit(xy: np.ndarray) -> tuple[np.ndarray, float]:
    """Algebraic (Kasa) least-squares circle through points (n, 2): centre, radius."""
    basis = np.column_stack([2 * xy, np.ones(len(xy))])
    (cx, cy, c), *_ = np.linalg.lstsq(basis, (xy**2).sum(1), rcond=None)
    return np.array([cx, cy]), math.sqrt(c + cx * cx + cy * cy)


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    """Each test meshes into its own cache folder (import it into a test module to use it there)."""
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))


def group_nodes(mesh, name: str) -> np.ndarray:
    blocks = [block.data[ids] for block, ids in zip(mesh.cells, mesh.cell_sets[name]) if len(ids)]
    assert blocks, f"physical group {name} is empty"
    return np.unique(np.concatenate([b.ravel() for b in blocks]))


def group_cells(mesh, name: str, kind: str) -> np.ndarray:
    blocks = [block.data[ids] for block, ids in zip(mesh.cells, mesh.cell_sets[name])
              if len(ids) and block.type == kind]
    return np.concatenate(blocks) if blocks else np.empty((0, 4 if kind == "tetra" else 3), int)


def radii(mesh, group: str) -> np.ndarray:
    nodes = mesh.points[group_nodes(mesh, group)]
    return np.hypot(nodes[:, 0], nodes[:, 1])


def tet_volume(points: np.ndarray, tets: np.ndarray) -> float:
    a, b, c, d = (points[tets[:, i]] for i in range(4))
    return float(np.sum(np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a))) / 6.0)


def quadratic_fit(points: np.ndarray, radius: float, degree: int = 3) -> np.ndarray:
    """Least-squares z = polynomial of ``degree`` in (x, y) on nodes with |(x, y)| < radius
    (coordinates scaled by ``radius``).  Returns the coefficients of (1, x, y, x^2, xy, y^2) [SI]."""
    near = points[np.hypot(points[:, 0], points[:, 1]) < radius]
    x, y, z = near.T / radius
    basis = np.stack([x**i * y ** (n - i) for n in range(degree + 1) for i in range(n, -1, -1)], 1)
    assert len(near) > 2 * basis.shape[1]
    coef, *_ = np.linalg.lstsq(basis, z, rcond=None)
    return coef[:6] * radius / radius ** np.array([0, 1, 1, 2, 2, 2])


def pair_hertz_geometry(ball_radius, conformity, pitch_radius, lead, contact_angle, body="screw", *, flank="left",
                        profile_plane="normal", youngs_modulus=2.1e11, poisson_ratio=0.28):
    """Hertz geometry of the contact meshed by ``ball_in_screw_groove_pair`` with the same
    arguments: the ball's curvature ``1/R_B`` and the groove's exact principal curvatures at
    the contact (``A`` belongs to the contact-frame x axis)."""
    frame = groove_core.contact_frame(groove_core.helical_groove(ball_radius, conformity, pitch_radius, lead,
                                                                 contact_angle, body, flank, profile_plane))
    curvature = 1.0 / float(ball_radius)
    return hertz.from_curvatures((curvature, curvature), (frame.curvature_major, frame.curvature_minor),
                                 youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)


def surface_area_and_longest_edge(mesh, name: str) -> tuple[float, float]:
    tri = group_cells(mesh, name, "triangle")
    a, b, c = (mesh.points[tri[:, i]] for i in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    edges = np.concatenate([np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1),
                            np.linalg.norm(a - c, axis=1)])
    return float(area), float(edges.max())
