"""FE four-point contact module of a linear ball bearing: one ball between a fixed bottom rail
and a loaded top rail, P2 elasticity, mortar contact at the four ball-to-groove contacts.

Mesh: :func:`meshes.assemblies.fourpoint_module.fourpoint_module` (one ball, gothic-arch rails, the
real sphere and flank surfaces, refined about the four contact points).  Frame of
lin2017 Fig 2: ball centre at the origin, ``z`` along the rails, ``y`` up; contacts
(BL, BR, TR, TL) at ``R_B n_i`` with the outward normals of lin2017 eq 1.

Contact (per contact ``i``, frame ``e1 = (-n_y, n_x, 0)`` in the cross-section, ``e2 = e_z``,
``e3 = -n_i`` from the flank into the ball): as :mod:`fem.mortar`, a piecewise-linear
pressure on the ball's cap triangles and weighted gaps over their projection on the tangent
plane, ``g = g0 + (u_ball - u_rail(P)) . e3`` with ``P`` the projection along ``e3`` on the
flank triangles.  **The initial gap ``g0`` is that of the exact surfaces** (sphere of radius
``R_B`` and flank cylinder of radius ``r_g = f 2 R_B`` about its arc centre, intersected along
``e3`` at every quadrature point), not Hertz's quadratic ``A x^2 + B y^2``: the FE can disagree
with Hertz where the real shape differs.

Boundary conditions and rigid modes: the bottom rail is clamped on ``bottom_support``; the
top rail's ``top_load`` face moves rigidly by ``(U_x, U_y, 0)`` (unknown), carrying the load
``(N_x, -N_y)`` (lin2017 eq 35: ``N_x`` along +x, ``N_y`` pressing down); the ball is held by
a 3-2-1 set of interior nodes (centre; ``0.5 R_B e_z``: x, y; ``0.5 R_B e_x``: y) and
translates by ``(X, Y, 0)`` (unknown).  The frictionless contact cannot hold the ball's
rotations or its z translation (all normals pass through the centre), so the 3-2-1 nodes
carry only the small residual moments and z force of the discretised pressure (reported).
Condensed on the multipliers (``W = B K^-1 B^T``, :func:`fem.linsolve.compliance`) the
problem is the mixed LCP

    g = g0 + W lam + G q >= 0,  lam >= 0,  lam . g = 0,   G^T lam = r,

``q = (X, Y, U_x, U_y)``, ``G_k = m_k (e3_x, e3_y, -e3_x [top], -e3_y [top])``,
``r = (0, 0, -N_x, N_y)`` (ball free in x, y; top rail loaded).  It is the convex QP
``min 1/2 lam W lam + g0 . lam``, ``lam >= 0``, ``G^T lam = r``, solved by the dual active-set
method of Goldfarb & Idnani (1983, quadprog) and polished by one exact solve on its active set
(:func:`solve`; ``W`` of P2 mortar contact is not an M-matrix, and the primal-dual active set
method of :mod:`fem.contact` cycles on it from a cold start: it is kept only for warm starts
during the geometric update of the gap).  The ball-screw module (:mod:`fem.screw_module`) is
the same problem with its own geometry (the module protocol of :class:`ModuleGeometry`).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ballbench.fem import elasticity, linsolve
from ballbench.fem.contact import solve_free
from ballbench.fem.elasticity import PairMesh, load_pair, stiffness_fast
from ballbench.fem.module_lcp import solve_lcp
from ballbench.fem.mortar import (edge_index, projected_quadrature, sub_triangle_points, surface_dofs,
                                  surface_shape, triangle_dofs, weighted_gaps)
from ballbench.fem.postprocess import EllipseFit, moment_ellipse
from ballbench.fem.surface import locate
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_normals
from ballbench.lowmodel.geometry.groove import groove_radius
from ballbench.lowmodel.linear_bearing.b2b_traction import TractionPatch

__all__ = ["CONTACTS", "ShoulderContact", "ZoneEdgeContact", "ModuleGeometry", "ModuleModel", "ContactResult",
           "ModuleResult", "load_module", "exact_gap", "build_module_model", "solve",
           "residual_load", "traction_patches", "full_displacement", "von_mises"]

CONTACTS = CONTACT_NAMES  # (BL, BR, TR, TL), the project-wide order
_SUBDIVISIONS = 4  # mortar quadrature: 16 sub-triangles per ball triangle


@dataclass(frozen=True)
class ModuleGeometry:
    """Ball and groove geometry of the module: ``ball_radius`` [m], ``conformity``,
    ``contact_angles`` (4,) [rad] (BL, BR, TR, TL) of the undeformed contacts."""

    ball_radius: float
    conformity: float
    contact_angles: tuple

    @property
    def normals(self) -> np.ndarray:
        """(4, 3) outward unit contact normals (lin2017 eq 1, :func:`lowmodel.geometry.fourpoint.contact_normals`)."""
        return np.column_stack([contact_normals(np.asarray(self.contact_angles, dtype=float)), np.zeros(4)])

    @property
    def groove_radius(self) -> float:
        """Flank radius ``r_g = 2 f R_B`` [m] (:func:`lowmodel.geometry.groove.groove_radius`)."""
        return float(groove_radius(self.ball_radius, self.conformity))

    def frame(self, i: int) -> np.ndarray:
        """(3, 3) rows ``e1, e2, e3`` of contact ``i`` (module docstring)."""
        n = self.normals[i]
        return np.array([[-n[1], n[0], 0.0], [0.0, 0.0, 1.0], -n])

    def arc_centre(self, i: int) -> np.ndarray:
        """(3,) centre of the flank circle of contact ``i`` (z = 0): ``-(r_g - R_B) n_i``."""
        return -(self.groove_radius - self.ball_radius) * self.normals[i]

    # --- the module protocol of build_module_model / solve_loaded (fem.screw_module has the screw's) ---
    contact_names = CONTACT_NAMES
    volumes = {"ball1": 0, "bottom_rail": 1, "top_rail": 2}  # physical volume -> body index
    clamped = ("bottom_support", "top_load")  # Dirichlet faces (the load face moves by load_face_motion)
    load_face = "top_load"
    ball_centre = np.zeros(3)
    free_axis = np.array([0.0, 0.0, 1.0])  # the ball's translation no contact holds (along the rails)
    rigid_names = ("X", "Y", "U_x", "U_y")
    all_contacts = True  # every contact must carry load (lin2017 eq 37)

    def contact_point(self, i: int) -> np.ndarray:
        """(3,) undeformed contact point of contact ``i`` on the ball [m] (tangent-plane origin)."""
        return self.ball_radius * self.normals[i]

    def gap(self, i: int, local: np.ndarray, shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """:func:`exact_gap` (sphere points relative to the ball centre)."""
        return exact_gap(self, i, local, shift)

    def rigid_modes(self, i: int) -> np.ndarray:
        """(4, 3): rigid displacement of the ball relative to the rail of contact ``i`` per unit
        ``q = (X, Y, U_x, U_y)`` (ball translation, top-rail translation)."""
        top = -1.0 if i >= 2 else 0.0
        return np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [top, 0.0, 0.0], [0.0, top, 0.0]])

    def load_face_motion(self, rigid: np.ndarray) -> np.ndarray:
        """(3,) rigid displacement [m] of the load face for the rigid unknowns ``rigid``."""
        return np.array([rigid[2], rigid[3], 0.0])

    def moving(self, i: int) -> bool:
        """True for the contacts on the loaded (top) rail."""
        return i >= 2

    def loaded_angle(self, i: int, centre: np.ndarray) -> float:  # noqa: ARG002 - the contact-geometry interface: the screw's geometry reads i
        """Contact angle [rad] (lin2017 eq 1, from -y or +y) of the point ``centre`` (3,) on the ball."""
        return math.atan2(abs(centre[0]), abs(centre[1]))

    def flank_normals(self, i: int, points: np.ndarray) -> np.ndarray:
        """(k, 3) unit normals of the flank of contact ``i`` facing the points (k, 3) (from its arc centre)."""
        radial = points - self.arc_centre(i)
        radial[:, 2] = 0.0
        return radial / np.linalg.norm(radial, axis=1)[:, None]

    def to_ball_frame(self, vectors: np.ndarray) -> np.ndarray:
        """Vectors (k, 3) in the frame of TractionPatch (lin2017 Fig 2: the module's own frame)."""
        return vectors


def exact_gap(geometry: ModuleGeometry, i: int, local: np.ndarray, shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Gap [m] between the exact sphere and flank cylinder of contact ``i`` along ``e3`` at the
    tangent-plane points ``local`` (k, 2) = (x along e1, y along e2) [m]; also the sphere points (k, 3).

    Line ``Q + s e3``, ``Q = R_B n_i + x e1 + y e2``: ``s_ball`` solves ``|Q + s e3| = R_B``,
    ``s_rail`` solves ``|(Q + s e3 - C_i)_xy| = r_g`` (the roots nearest the tangent plane);
    ``g0 = s_ball - s_rail``.  ``shift`` [m]: the ball moved rigidly by ``shift e1`` relative to the rail
    (its point ``local`` then faces the flank at ``local + shift e1``; the normal part of the rigid motion
    is not included here).
    """
    radius, r_g = geometry.ball_radius, geometry.groove_radius
    e1, e2, e3 = geometry.frame(i)
    q = radius * geometry.normals[i] + local[:, :1] * e1 + local[:, 1:2] * e2
    # sphere: s^2 + 2 s (q.e3) + |q|^2 - R^2 = 0, root near 0 (q.e3 ~ -R)
    b = q @ e3
    c = np.einsum("ki,ki->k", q, q) - radius**2
    disc = b * b - c
    if np.any(disc < 0.0):
        raise ValueError("exact_gap: a point lies outside the ball's silhouette (candidate zone too large)")
    s_ball = c / (-b + np.sqrt(disc))  # = -b - sqrt(disc), written without cancellation
    # cylinder about the z axis through C: only x, y count
    d = (q + shift * e1 - geometry.arc_centre(i))[:, :2]
    e = e3[:2]
    bb = d @ e
    cc = np.einsum("ki,ki->k", d, d) - r_g**2
    disc = bb * bb - cc
    if np.any(disc < 0.0):
        raise ValueError("exact_gap: a point misses the flank cylinder")
    s_rail = cc / (-bb + np.sqrt(disc))  # root near 0 (bb ~ -r_g < 0)
    return s_ball - s_rail, q + s_ball[:, None] * e3


MODULE_VOLUMES = ModuleGeometry.volumes  # physical volume -> body index


def load_module(path, volumes=None) -> PairMesh:
    """Read a one-ball module mesh (default :func:`meshes.assemblies.fourpoint_module.fourpoint_module`:
    ``body`` 0 = ball, 1 = bottom rail, 2 = top rail; ``volumes`` another name -> body map); surfaces by
    their physical names."""
    return load_pair(path, MODULE_VOLUMES if volumes is None else volumes)


def _surface_dofs(basis, pair: PairMesh, name: str, edges: dict) -> np.ndarray:
    """All P2 DOFs (every component) on the named surface."""
    return np.unique(np.concatenate([surface_dofs(basis, pair, name, c, 2, edges) for c in range(3)]))


@dataclass
class _Patch:
    """Mortar data of one contact (local quadrature points, gap operator rows)."""

    name: str
    candidates: np.ndarray  # ball vertex indices
    local_nodes: np.ndarray  # (n, 2) tangent-plane coordinates of the candidates
    triangles: np.ndarray  # (t, 3) candidate-local indices (-1 outside) of the ball triangles
    xq: np.ndarray  # (q, 2) quadrature points (tangent plane)
    wq: np.ndarray  # (q,) projected areas
    phi: np.ndarray  # (q, 3) multiplier hats
    mult: np.ndarray  # (q, 3) global multiplier index (-1 outside)
    g0q: np.ndarray  # (q,) exact initial gap
    surface: np.ndarray  # (q, 3) sphere points of the quadrature points
    boundary: np.ndarray  # (n,) candidates on the zone edge
    shoulder: np.ndarray  # (n,) candidates on the zone edge the flank's end (the groove's shoulder) cuts


@dataclass
class ModuleModel:
    """Condensed four-point module (build with :func:`build_module_model`)."""

    geometry: ModuleGeometry
    pair: PairMesh
    patches: list
    g0: np.ndarray  # (n_c,) weighted initial gaps [m^3]
    weights: np.ndarray  # (n_c,) m_k [m^2]
    G: np.ndarray  # (n_c, 4) [m^2]: weighted gap per rigid translation (X, Y, U_x, U_y)
    W: np.ndarray  # (n_c, n_c) [m^5/N]: weighted gaps [m^3] per nodal pressure [Pa], B K^-1 B^T
    contact_of: np.ndarray  # (n_c,) contact index 0..3
    B: sp.csr_matrix
    K: sp.csr_matrix
    free: np.ndarray
    basis: object
    top_dofs: np.ndarray  # (2, k) x and y DOFs of the top_load face
    pin_dofs: np.ndarray
    timings: dict = field(default_factory=dict)
    factor: object = field(default=None, repr=False)  # the factor W was computed with (linsolve.compliance)

    @property
    def ndofs(self) -> int:
        return int(self.K.shape[0])

    @property
    def n_multipliers(self) -> int:
        return int(self.g0.size)


class ShoulderContact(ValueError):
    """The contact pressure of a solved module reaches the end of its flank (the groove's shoulder, the land of
    the module's mesh): the contact ellipse is truncated in the FE (docs/truncation.md), an edge contact the
    module's mortar zone on the flank does not resolve.  ``contact`` names it (BL, BR, TR, TL or SL, ...)."""

    def __init__(self, contact: str):
        self.contact = contact
        super().__init__(f"contact {contact}: the FE contact pressure reaches the groove's shoulder (the end of its "
                         "flank): the contact ellipse is truncated (docs/truncation.md)")


class ZoneEdgeContact(ValueError):
    """The contact pressure of a solved module reaches the edge of its candidate zone (the gap ``gap_limit`` or the
    ball cap's edge, meshes.parts.ball.cap_limit): a larger zone is needed.  ``contact`` names it."""

    def __init__(self, contact: str):
        self.contact = contact
        super().__init__(f"contact {contact} reaches the edge of the candidate zone: raise gap_limit or the ball's "
                         "cap_angle")


def _on_flank(local: np.ndarray, ball_tris: np.ndarray, rail_tris: np.ndarray, candidates: np.ndarray,
              bary: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The candidate zone trimmed to the ball triangles that face the flank: every vertex of a candidate triangle
    (one with a candidate vertex) whose quadrature points do not all project on the flank along e3 leaves the zone
    (a heavy contact's zone, the whole ball cap, can reach past the flank's end, the groove's shoulder; ball points
    there face the land).  Returns ``(candidates, shoulder)``: the kept vertices, those next to a dropped one."""
    index = -np.ones(len(local), dtype=np.int64)
    index[candidates] = np.arange(candidates.size)
    tris = ball_tris[(index[ball_tris] >= 0).any(axis=1)]
    corners = local[tris][:, :, :2]
    points = np.einsum("qk,tkd->tqd", bary, corners).reshape(-1, 2)  # the triangles' sub-triangle points
    _, _, inside = locate(local, rail_tris, points)
    off_tris = ~inside.reshape(len(tris), len(bary)).all(axis=1)
    if not off_tris.any():
        return candidates, np.zeros(0, dtype=candidates.dtype)
    off = np.unique(tris[off_tris])
    kept = np.setdiff1d(candidates, off)
    beside = ball_tris[np.isin(ball_tris, off).any(axis=1)]
    return kept, np.intersect1d(kept, beside)


def build_module_model(mesh, geometry: ModuleGeometry, *, materials=(2.1e11, 0.28), gap_limit: float,
                       method: str = "augmented") -> ModuleModel:
    """Assemble (P2), constrain and condense the four-point module on its contact multipliers.

    ``mesh``: path of a one-ball module mesh or a :class:`PairMesh` from :func:`load_module`;
    ``geometry`` its ball/groove geometry; ``materials`` ``(E [Pa], nu)`` of all bodies;
    ``gap_limit`` [m]: ball cap vertices with an exact initial gap at most this are multipliers
    (it must exceed the approach at every contact; a contact reaching the zone edge raises).
    """
    if not (math.isfinite(gap_limit) and gap_limit > 0.0):
        raise ValueError(f"gap_limit must be a finite length > 0 m, got {gap_limit!r}")
    timings = {}
    t0 = time.perf_counter()
    names = geometry.contact_names
    pair = mesh if isinstance(mesh, PairMesh) else load_module(mesh, geometry.volumes)
    for name in tuple(geometry.clamped) + tuple(names) + tuple(f"ball1_{c}" for c in names):
        if name not in pair.surfaces:
            raise ValueError(f"mesh {pair.path}: physical surface {name!r} missing")
    timings["load_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    K, basis = stiffness_fast(pair, [materials] * len(geometry.volumes), order=2)
    timings["assembly_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    edges = edge_index(basis.mesh)
    points = pair.points
    radius = geometry.ball_radius
    # Dirichlet: the support clamped, the load face clamped (its rigid translation is in G)
    fixed = [_surface_dofs(basis, pair, name, edges) for name in geometry.clamped]
    ball_nodes = np.unique(pair.tets[pair.body == 0])
    pins = []
    for target, components in (((0.0, 0.0, 0.0), (0, 1, 2)), ((0.0, 0.0, 0.5 * radius), (0, 1)),
                               ((0.5 * radius, 0.0, 0.0), (1,))):
        target = geometry.ball_centre + np.array(target)
        node = ball_nodes[np.argmin(np.linalg.norm(points[ball_nodes] - target, axis=1))]
        pins += [basis.nodal_dofs[c][node] for c in components]
    pin_dofs = np.array(pins, dtype=np.int64)
    fixed = np.unique(np.concatenate(fixed + [pin_dofs]))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    top_nodes = pair.nodes(geometry.load_face)
    top_dofs = np.stack([basis.nodal_dofs[0][top_nodes], basis.nodal_dofs[1][top_nodes]])

    bary = sub_triangle_points(_SUBDIVISIONS)
    nq = len(bary)
    shape = surface_shape(bary, 2)
    patches, rows, cols, vals, g0_all, w_all, contact_of, g_cols = [], [], [], [], [], [], [], []
    offset = 0
    for i, name in enumerate(names):
        frame = geometry.frame(i)
        origin = geometry.contact_point(i)
        local = (points - origin) @ frame.T  # (n, 3): e1, e2, e3 coordinates
        ball_tris = pair.surfaces[f"ball1_{name}"]
        rail_tris = pair.surfaces[name]
        verts = np.unique(ball_tris)
        g_vert, _ = geometry.gap(i, local[verts, :2])
        candidates = verts[g_vert <= gap_limit]
        candidates, shoulder = _on_flank(local, ball_tris, rail_tris, candidates, bary)
        if candidates.size < 20:
            raise ValueError(f"contact {name}: only {candidates.size} candidate nodes (need >= 20): refine the mesh "
                             "at the contact (smaller h_contact) or raise gap_limit")
        index = -np.ones(len(points), dtype=np.int64)
        index[candidates] = np.arange(candidates.size)
        tris = ball_tris[(index[ball_tris] >= 0).any(axis=1)]
        xq, wq, phi, mult = projected_quadrature(local[tris][:, :, :2], index[tris], bary)
        g0q, surface = geometry.gap(i, xq)
        rail_rows, rail_bary, inside = locate(local, rail_tris, xq)  # along e3: the local z
        if not inside.all():  # _on_flank keeps only the triangles whose points all land on the flank
            raise RuntimeError(f"contact {name}: a ball quadrature point projects outside its flank after the "
                               "candidate zone was trimmed to the flank (fem.fourpoint._on_flank)")
        ball_dofs = [np.repeat(triangle_dofs(basis, tris, c, edges), nq, axis=0) for c in range(3)]
        rail_dofs = [triangle_dofs(basis, rail_tris[rail_rows], c, edges) for c in range(3)]
        ball_shape = np.tile(shape, (len(tris), 1))
        rail_shape = surface_shape(rail_bary, 2)
        e3 = frame[2]
        n_c = candidates.size
        couplings = []
        for c in range(3):  # g = g0 + (u_ball - u_rail) . e3
            if abs(e3[c]) >= 1e-15:
                couplings += [(ball_dofs[c], ball_shape, e3[c]), (rail_dofs[c], rail_shape, -e3[c])]
        g0, weights, r, cc, v = weighted_gaps(mult, phi, wq, g0q, n_c, couplings, row_offset=offset)
        rows += r
        cols += cc
        vals += v
        g_cols.append(weights[:, None] * (geometry.rigid_modes(i) @ e3)[None, :])
        edge_tris = tris[(index[tris] < 0).any(axis=1)]
        patches.append(_Patch(name, candidates, local[candidates, :2], index[tris], xq, wq, phi,
                              np.where(mult >= 0, mult + offset, -1), g0q, surface,
                              np.isin(candidates, edge_tris), np.isin(candidates, shoulder)))
        g0_all.append(g0)
        w_all.append(weights)
        contact_of.append(np.full(n_c, i))
        offset += n_c
    B = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(offset, K.shape[0]))
    B.sum_duplicates()
    timings["contact_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    W, factor = linsolve.compliance(K[free][:, free].tocsr(), B[:, free], method=method, keep_factor=True)
    timings["condense_s"] = time.perf_counter() - t0
    return ModuleModel(geometry, pair, patches, np.concatenate(g0_all), np.concatenate(w_all), np.vstack(g_cols), W,
                       np.concatenate(contact_of), B.tocsr(), K, free, basis, top_dofs, pin_dofs, timings,
                       factor=factor)


@dataclass(frozen=True)
class ContactResult:
    """One contact of a solved module.

    normal_force [N]; contact_angle [rad] under load (force-weighted centre of the pressure on the
    ball); approach [m]: rigid ball-to-rail displacement along ``-n_i`` (ball into rail; includes the
    bulk compliance of the truncated bodies); ellipse: Hertz field fitted to the pressure (``a`` along
    e1 in the cross-section, ``b`` along z); quadrature (points on the sphere (q, 3) [m], pressure (q,)
    [Pa], projected areas (q,) [m^2], tangent-plane coordinates (q, 2) [m]); nodal pressures (n,) [Pa]
    at the candidate nodes ``local_nodes`` (n, 2) [m].
    """

    name: str
    normal_force: float
    contact_angle: float
    approach: float
    ellipse: EllipseFit | None
    points: np.ndarray
    pressure: np.ndarray
    areas: np.ndarray
    local: np.ndarray
    nodal_pressure: np.ndarray
    local_nodes: np.ndarray


@dataclass(frozen=True)
class ModuleResult:
    """Solved module: contacts (BL, BR, TR, TL); ``rigid`` (X, Y, U_x, U_y) [m]; ``pin_force`` [N] and
    ``pin_moment`` [N m]: the z force and moment the ball's 3-2-1 nodes carry (:func:`residual_load`);
    ``iterations``, ``residual`` of the active set; ``multipliers`` the nodal pressures [Pa]."""

    contacts: tuple
    rigid: np.ndarray
    pin_force: float
    pin_moment: float
    iterations: int
    residual: float
    multipliers: np.ndarray


def solve(model: ModuleModel, side_force: float, vertical_force: float, *, tol: float = 1e-9,
                 fit: bool = True, geometric_update: bool = True, max_updates: int = 20) -> ModuleResult:
    """Solve the module under ``N_x = side_force`` [N] (along +x on the top rail) and
    ``N_y = vertical_force`` [N] > 0 (pressing the top rail down), lin2017 eq 35.

    The mixed LCP is the convex QP ``min 1/2 lam W lam + g0 . lam`` subject to ``lam >= 0``,
    ``G^T lam = r`` (``W`` is SPD; the gaps are the multipliers of ``lam >= 0``, ``q`` those of
    the equalities).  ``W`` of P2 mortar contact is not an M-matrix (about 44 % positive
    off-diagonal entries), and the primal-dual active set method of :mod:`fem.contact` cycles
    from a cold start; the QP is solved by the dual active-set method of Goldfarb & Idnani (1983,
    quadprog), then polished by one exact solve on its active set.  The geometric updates start the
    active set iteration from the previous active set (quadprog if that fails).  ConvergenceError unless the polished
    state meets complementarity to ``tol`` (lam in units of its mean, weighted gaps in units of
    the largest rigid displacement times the median weight).

    ``geometric_update``: the ball's rigid displacement relative to a rail has a tangential part
    ``t_i`` (along e1) of the order of the approach, which moves the contact along the conforming
    flank by about ``t_i R_B / (r_g - R_B)`` on the ball (the contact angle under load); small-deformation
    contact with a fixed projection misses it.  With the update the exact gap is re-evaluated with
    the ball shifted by ``t_i`` (:func:`exact_gap`) and the QP re-solved on the same ``W`` until
    ``t_i`` changes by less than 1e-4 of the rigid displacement (fixed point; 3-5 solves).  The
    force directions stay the contact normals ``n_i`` (small deformation), so the forces remain
    those of lin2017 eq 36 at the undeformed angles."""
    if not (math.isfinite(vertical_force) and vertical_force > 0.0):
        raise ValueError(f"vertical_force must be a finite number > 0 N, got {vertical_force!r}")
    if not math.isfinite(side_force):
        raise ValueError(f"side_force must be finite N, got {side_force!r}")
    return solve_loaded(model, np.array([0.0, 0.0, -side_force, vertical_force]), tol=tol, fit=fit,
                        geometric_update=geometric_update, max_updates=max_updates)


def solve_loaded(model: ModuleModel, load: np.ndarray, *, tol: float = 1e-9, fit: bool = True,
                 geometric_update: bool = True, max_updates: int = 20) -> ModuleResult:
    """Solve a module for the right-hand side ``r = load`` of ``G^T lam = r`` (one entry per rigid unknown
    of ``model.geometry.rigid_names`` [N]; :func:`solve` for the linear bearing's loads,
    :func:`fem.screw_module.solve` for the ball screw's), with the geometric update of the
    gap described in :func:`solve`."""
    geometry = model.geometry
    n_contacts = len(model.patches)
    g0 = model.g0
    shifts = np.zeros(n_contacts)
    active = None
    iteration = 0
    for _ in range(max_updates + 1):
        lam, q, active, iterations, residual = solve_lcp(model, load, tol, g0, active)
        iteration += iterations
        if not geometric_update:
            break
        new_shifts = np.array([_relative_displacement(model, q, i) @ geometry.frame(i)[0]
                               for i in range(n_contacts)])
        change = float(np.max(np.abs(new_shifts - shifts)))
        shifts = new_shifts
        if change <= 1e-4 * float(np.max(np.abs(q))):
            break
        g0 = _weighted_gap(model, shifts)
    else:
        raise ConvergenceError("four-point module: geometric update of the gap did not converge", residual=change,
                               iterations=max_updates, tolerance=1e-4 * float(np.max(np.abs(q))))
    for patch in model.patches:
        touching = active[np.flatnonzero(model.contact_of == geometry.contact_names.index(patch.name))]
        if np.any(touching[patch.shoulder]):
            raise ShoulderContact(patch.name)
        if np.any(touching[patch.boundary]):
            raise ZoneEdgeContact(patch.name)
    results = []
    for i, patch in enumerate(model.patches):
        sel = model.contact_of == i
        lam_i = lam[sel]
        force = float(model.weights[sel] @ lam_i)
        p_q = np.zeros(len(patch.xq))
        for k in range(3):
            ok = patch.mult[:, k] >= 0
            p_q[ok] += patch.phi[ok, k] * lam[patch.mult[ok, k]]
        f_q = p_q * patch.wq
        centre = f_q @ patch.surface / max(f_q.sum(), 1e-300)
        angle = geometry.loaded_angle(i, centre)
        e3 = geometry.frame(i)[2]
        approach = float(-(_relative_displacement(model, q, i) @ e3))  # ball towards the rail: along -e3 = n_i
        ellipse = _fit(patch, lam_i) if fit else None
        results.append(ContactResult(patch.name, force, angle, approach, ellipse, patch.surface, p_q, patch.wq,
                                     patch.xq, lam_i, patch.local_nodes))
    pin_force, pin_moment = residual_load(model, results)
    return ModuleResult(tuple(results), q, pin_force, pin_moment, iteration, residual, lam)


def _relative_displacement(model: ModuleModel, q: np.ndarray, i: int) -> np.ndarray:
    """Rigid displacement (3,) [m] of the ball relative to the rail (flank) of contact ``i``."""
    return q @ model.geometry.rigid_modes(i)


def _weighted_gap(model: ModuleModel, shifts: np.ndarray) -> np.ndarray:
    """Weighted exact gaps ``int phi_k g0 dA`` (n_c,) with the ball shifted by ``shifts`` (one per contact) [m]
    along e1."""
    g0 = np.zeros(model.n_multipliers)
    for i, patch in enumerate(model.patches):
        g0q, _ = model.geometry.gap(i, patch.xq, float(shifts[i]))
        g0 += weighted_gaps(patch.mult, patch.phi, patch.wq, g0q, model.n_multipliers)[0]
    return g0


def _fit(patch: _Patch, nodal: np.ndarray) -> EllipseFit | None:
    """Hertz ellipse with the force and second moments of the piecewise-linear pressure with nodal
    values ``nodal`` (the multipliers) [Pa] (fem.postprocess.moment_ellipse), centre free along e1."""
    tris = patch.triangles[(patch.triangles >= 0).all(axis=1)]
    if len(tris) < 5 or np.count_nonzero(nodal > 0) < 5:
        return None
    return moment_ellipse(patch.local_nodes[:, :2], tris, nodal, symmetric_x=False, symmetric_y=True)


def residual_load(model: ModuleModel, result_contacts) -> tuple[float, float]:
    """Force along the geometry's ``free_axis`` (z for the rails) [N] and moment about the centre [N m] of all
    contact pressures on the ball: what the 3-2-1 nodes carry (zero for an exactly symmetric, radial pressure)."""
    force = np.zeros(3)
    moment = np.zeros(3)
    for i, contact in enumerate(result_contacts):
        e3 = model.geometry.frame(i)[2]
        f = (contact.pressure * contact.areas)[:, None] * e3[None, :]
        force += f.sum(axis=0)
        moment += np.cross(contact.points, f).sum(axis=0)
    return float(abs(force @ model.geometry.free_axis)), float(np.linalg.norm(moment))


def traction_patches(model: ModuleModel, result: ModuleResult, *, normal: str = "mid", offset=(0.0, 0.0, 0.0)):
    """The solved contacts as :class:`lowmodel.linear_bearing.b2b_traction.TractionPatch` (in the order of
    ``geometry.contact_names``: BL, BR, TR, TL for the rails; ``top`` = on the loaded body).

    Points: the quadrature points of the mortar pressure on the exact sphere [m] (relative to the ball
    centre, in the frame of ``geometry.to_ball_frame``, plus ``offset``); forces: pressure x projected area
    [N].  ``normal``: ``"mid"`` (default) the normalised mean of the sphere's and the flank's normals at the
    point (for equal elastic constants the loaded interface lies halfway between the two surfaces),
    ``"sphere"`` the ball's normal, ``"contact"`` the fixed contact normal ``n_i`` of the mortar gap.
    """
    if normal not in ("mid", "sphere", "contact"):
        raise ValueError(f"normal must be 'mid', 'sphere' or 'contact', got {normal!r}")
    geometry = model.geometry
    patches = []
    for i, contact in enumerate(result.contacts):
        keep = contact.pressure > 0.0
        points = contact.points[keep]
        sphere = points / np.linalg.norm(points, axis=1)[:, None]
        if normal == "sphere":
            normals = sphere
        elif normal == "contact":
            normals = np.repeat(geometry.normals[i][None, :], len(points), axis=0)
        else:
            normals = sphere + geometry.flank_normals(i, points)
            normals /= np.linalg.norm(normals, axis=1)[:, None]
        forces = (contact.pressure * contact.areas)[keep]
        patches.append(TractionPatch(geometry.to_ball_frame(points) + np.asarray(offset, dtype=float),
                                     geometry.to_ball_frame(normals), forces, top=geometry.moving(i),
                                     name=contact.name))
    return tuple(patches)


def full_displacement(model: ModuleModel, result: ModuleResult) -> np.ndarray:
    """Displacement DOF vector (ndofs,) [m] of a solved module: one sparse solve with the contact
    forces ``B^T lam``, the load face moved rigidly (top rail: ``(U_x, U_y, 0)``) and the ball's 3-2-1 nodes held
    (the ball's rigid translation is not added: it carries no stress)."""
    edges = edge_index(model.basis.mesh)
    tris = model.pair.surfaces[model.geometry.load_face]
    motion = model.geometry.load_face_motion(result.rigid)
    u = np.zeros(model.ndofs)
    for component in range(3):
        if motion[component] != 0.0:
            u[np.unique(triangle_dofs(model.basis, tris, component, edges))] = motion[component]
    rhs = model.B.T @ result.multipliers - model.K @ u
    u[model.free] = solve_free(model.K, model.free, rhs[model.free], model.factor)  # the condensation's factor
    return u


def von_mises(model: ModuleModel, displacement: np.ndarray, materials=(2.1e11, 0.28)) -> np.ndarray:
    """Element-mean von Mises stress (n_tets,) [Pa] of the displacement DOF vector (P2, 4-point rule):
    :func:`fem.elasticity.von_mises` of Hooke's law (:func:`fem.elasticity.stress`) at the quadrature points."""
    lam, mu = elasticity.lame(*materials)
    sigma = elasticity.stress(model.basis.interpolate(displacement).grad, lam, mu)  # (3, 3, nel, nq)
    return elasticity.von_mises(sigma).mean(axis=1)
