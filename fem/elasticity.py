"""3D linear elasticity on tetrahedra (scikit-fem), for the contact-pair meshes of ``meshes/``.

* :func:`load_pair` reads a gmsh ``.msh`` (docs/developing.md, contact-pair
  meshes) into a :class:`PairMesh`: node coordinates, tetrahedra, body of each
  tetrahedron and the node sets / triangles of the named surfaces.
* Hooke's law once (as ``skfem.models.elasticity`` does it): :func:`lame` (E, nu ->
  lambda, mu), :func:`stress` (``sigma = 2 mu eps + lambda tr(eps) I`` of the
  displacement gradient) and :func:`von_mises`; the assembly below and the
  post-processing (:func:`fem.postprocess.nodal_stress`, :func:`fem.fourpoint.von_mises`)
  use them.
* :func:`stiffness` assembles ``K`` [N/m] of the isotropic linear-elastic
  bodies with P1 (``order=1``) or P2 (``order=2``) tetrahedra, Lame parameters
  per body, through the scikit-fem form ``ddot(stress(grad u), grad v)``;
  :func:`stiffness_fast` builds the same matrix (same DOF numbering, equal to
  1e-15: test) with that form's element matrices integrated in closed form,
  3-4x faster for P2; the contact solvers use it.  P1 uses the one-point rule
  (exact for constant strains, about 10x faster than the default rule,
  docs/fem.md); P2 the degree-2 rule (exact on straight-sided tetrahedra).

DOF numbering (scikit-fem ``ElementVector``): ``basis.nodal_dofs[c, n]`` is the
DOF of component ``c`` (x, y, z) at mesh node ``n``.  SI units throughout.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp

__all__ = ["PairMesh", "load_pair", "contact_pair", "CONTACT_PAIR_SURFACES", "lame", "stress", "von_mises", "stiffness",
           "stiffness_fast", "vector_basis"]


@dataclass(frozen=True)
class PairMesh:
    """Two-body tetrahedral mesh.

    ``points`` (n, 3) [m]; ``tets`` (m, 4) node indices; ``body`` (m,) 0 = ball,
    1 = counter; ``surfaces[name]`` the (k, 3) triangles of a named surface and
    ``nodes(name)`` its sorted node indices.
    """

    points: np.ndarray
    tets: np.ndarray
    body: np.ndarray
    surfaces: dict = field(default_factory=dict)
    path: str = ""

    def nodes(self, name: str) -> np.ndarray:
        if name not in self.surfaces:
            return np.zeros(0, dtype=np.int64)
        return np.unique(self.surfaces[name])

    def skfem_mesh(self):
        from skfem import MeshTet

        return MeshTet(self.points.T.copy(), self.tets.T.copy())

    @property
    def symmetry_factor(self) -> int:
        """Full model / this model: 4 (quarter), 2 (half) or 1."""
        return (2 if "symmetry_x" in self.surfaces else 1) * (2 if "symmetry_y" in self.surfaces else 1)


PAIR_VOLUMES = {"ball": 0, "counter": 1}  # physical volume -> body index of a contact-pair mesh


def load_pair(path: Path | str, volumes: dict[str, int] | None = None) -> PairMesh:
    """Read a gmsh ``.msh`` of tetrahedra (second-order meshes keep their corner nodes) into a :class:`PairMesh`.

    ``volumes`` maps physical volume names to body indices (default :data:`PAIR_VOLUMES`, a contact
    pair: ball 0, counter-body 1); every one must hold tetrahedra.  Surfaces keep their physical names;
    nodes in no tetrahedron are dropped; tetrahedra are oriented positively.
    """
    import meshio

    volumes = PAIR_VOLUMES if volumes is None else volumes
    mesh = meshio.read(path)
    tets, body = [], []
    surfaces: dict[str, list] = {}
    for name, per_block in mesh.cell_sets.items():
        if name.startswith("gmsh:"):
            continue
        for i, idx in enumerate(per_block):
            idx = np.asarray(idx, dtype=np.int64)
            if idx.size == 0:
                continue
            block = mesh.cells[i]
            if block.type.startswith("tetra") and name in volumes:
                tets.append(block.data[idx, :4])
                body.append(np.full(idx.size, volumes[name]))
            elif block.type.startswith("triangle"):
                surfaces.setdefault(name, []).append(block.data[idx, :3])
    found = {int(b[0]) for b in body}
    if found != set(volumes.values()):
        missing = sorted(name for name, index in volumes.items() if index not in found)
        raise ValueError(f"{path}: no tetrahedra in the physical volumes {missing} (need {sorted(volumes)})")
    tets = np.vstack(tets).astype(np.int64)
    body = np.concatenate(body)
    # drop unused nodes (second-order nodes, geometry points)
    used = np.unique(tets)
    remap = -np.ones(len(mesh.points), dtype=np.int64)
    remap[used] = np.arange(used.size)
    points = np.asarray(mesh.points[used], dtype=float)
    tets = remap[tets]
    surf = {name: remap[np.vstack(tris).astype(np.int64)] for name, tris in surfaces.items()}
    for name, tris in surf.items():
        if np.any(tris < 0):
            raise ValueError(f"{path}: surface {name!r} has nodes not in any tetrahedron")
    # positive orientation
    d = points[tets]
    vol = np.einsum("ij,ij->i", np.cross(d[:, 1] - d[:, 0], d[:, 2] - d[:, 0]), d[:, 3] - d[:, 0])
    flip = vol < 0
    tets[flip] = tets[flip][:, [0, 2, 1, 3]]
    return PairMesh(points, tets, body, surf, str(path))



CONTACT_PAIR_SURFACES = ("ball_contact", "counter_contact", "ball_load", "counter_support")  # meshes.assemblies


def contact_pair(mesh) -> PairMesh:
    """A contact pair's :class:`PairMesh` (``mesh`` one already, or the path of its ``.msh``) with the named surfaces
    every contact solve needs (:data:`CONTACT_PAIR_SURFACES`); ValueError naming a missing one."""
    pair = mesh if isinstance(mesh, PairMesh) else load_pair(mesh)
    for name in CONTACT_PAIR_SURFACES:
        if name not in pair.surfaces:
            raise ValueError(f"mesh {pair.path}: physical surface {name!r} missing")
    return pair


def lame(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """Lame parameters (lambda, mu) [Pa] of E [Pa] and nu (0 < nu < 0.5)."""
    if not (np.isfinite(youngs_modulus) and youngs_modulus > 0):
        raise ValueError(f"youngs_modulus must be a finite number > 0 Pa, got {youngs_modulus!r}")
    if not (np.isfinite(poisson_ratio) and -1.0 < poisson_ratio < 0.5):
        raise ValueError(f"poisson_ratio must lie in (-1, 0.5), got {poisson_ratio!r}")
    mu = youngs_modulus / (2.0 * (1.0 + poisson_ratio))
    lam = youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio))
    return lam, mu


def stress(grad: np.ndarray, lam, mu) -> np.ndarray:
    """Hooke's law: Cauchy stress [Pa] ``sigma = 2 mu eps + lambda tr(eps) I`` of the displacement gradient ``grad``
    (3, 3, ...) (``grad[i, j] = du_i / dx_j``, ``eps`` its symmetric part); ``lam``, ``mu`` [Pa] scalars or arrays
    broadcasting with ``grad[0, 0]``."""
    strain = 0.5 * (grad + np.swapaxes(grad, 0, 1))
    trace = strain[0, 0] + strain[1, 1] + strain[2, 2]
    return 2.0 * mu * strain + lam * trace * np.eye(3).reshape((3, 3) + (1,) * (grad.ndim - 2))


def von_mises(sigma: np.ndarray) -> np.ndarray:
    """Von Mises stress ``sqrt(3/2 s : s)`` [Pa], ``s`` the deviator of ``sigma`` (3, 3, ...); shape ``sigma[0, 0]``."""
    mean = (sigma[0, 0] + sigma[1, 1] + sigma[2, 2]) / 3.0
    deviator = sigma - mean * np.eye(3).reshape((3, 3) + (1,) * (sigma.ndim - 2))
    return np.sqrt(1.5 * np.einsum("ij...,ij...->...", deviator, deviator))


def vector_basis(pair: PairMesh, order: int = 1):
    """scikit-fem vector basis of P1 or P2 tetrahedra on ``pair``."""
    from skfem import Basis, ElementTetP1, ElementTetP2, ElementVector

    if order not in (1, 2):
        raise ValueError(f"order must be 1 or 2, got {order!r}")
    element = ElementVector(ElementTetP1() if order == 1 else ElementTetP2())
    return Basis(pair.skfem_mesh(), element, intorder=1 if order == 1 else 2)


def stiffness(pair: PairMesh, materials, order: int = 1):
    """Stiffness matrix ``K`` (CSR, [N/m]) and the basis.

    ``materials``: ``(E, nu)`` for both bodies, or ``[(E_ball, nu_ball), (E_counter, nu_counter)]``.
    """
    from skfem import BilinearForm, asm
    from skfem.helpers import ddot, grad

    if np.ndim(materials[0]) == 0:
        materials = [materials, materials]
    lam_mu = np.array([lame(*m) for m in materials])  # (2, 2)
    basis = vector_basis(pair, order)
    lam_e = lam_mu[pair.body, 0][:, None]
    mu_e = lam_mu[pair.body, 1][:, None]

    @BilinearForm
    def form(u, v, w):
        return ddot(stress(grad(u), w["lam"], w["mu"]), grad(v))  # sigma symmetric: ddot with grad v = with eps(v)

    nqp = basis.X.shape[-1]
    K = asm(form, basis, lam=np.repeat(lam_e, nqp, axis=1), mu=np.repeat(mu_e, nqp, axis=1))
    return K.tocsr(), basis


_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))
_QA, _QB = 0.5854101966249685, 0.1381966011250105  # 4-point degree-2 rule on the tetrahedron


def _global_dofs(pair: PairMesh, basis, order: int) -> np.ndarray:
    """(nel, nloc, 3) global DOF of (scalar local function, component) on each tetrahedron."""
    tets = pair.tets
    dofs = [basis.nodal_dofs[:, tets].transpose(1, 2, 0)]  # (nel, 4, 3)
    if order == 2:
        edges = np.sort(basis.mesh.edges, axis=0)
        n = len(pair.points)
        keys = edges[0].astype(np.int64) * n + edges[1]
        sorter = np.argsort(keys)
        local = []
        for i, j in _EDGES:
            lo = np.minimum(tets[:, i], tets[:, j]).astype(np.int64)
            hi = np.maximum(tets[:, i], tets[:, j])
            pos = sorter[np.searchsorted(keys, lo * n + hi, sorter=sorter)]
            local.append(basis.edge_dofs[:, pos].T)  # (nel, 3)
        dofs.append(np.stack(local, axis=1))
    return np.concatenate(dofs, axis=1)


def _shape_gradients(pair: PairMesh, order: int):
    """Gradients (nel, nq, nloc, 3) [1/m] and quadrature weights (nel, nq) [m^3]."""
    x = pair.points[pair.tets]  # (nel, 4, 3)
    jac = np.stack([x[:, 1] - x[:, 0], x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]], axis=2)  # columns
    inv = np.linalg.inv(jac)  # rows: grad lambda_1..3
    grad_l = np.concatenate([-inv.sum(axis=1, keepdims=True), inv], axis=1)  # (nel, 4, 3)
    volume = np.abs(np.linalg.det(jac)) / 6.0
    if order == 1:
        return grad_l[:, None], volume[:, None]
    bary = np.full((4, 4), _QB) + np.eye(4) * (_QA - _QB)  # (nq, 4)
    grads = []
    for k in range(4):
        grads.append((4.0 * bary[:, k] - 1.0)[None, :, None] * grad_l[:, None, k, :])
    for i, j in _EDGES:
        grads.append(4.0 * (bary[:, i][None, :, None] * grad_l[:, None, j, :]
                            + bary[:, j][None, :, None] * grad_l[:, None, i, :]))
    return np.stack(grads, axis=2), np.repeat(volume[:, None] / 4.0, 4, axis=1)


def stiffness_fast(pair: PairMesh, materials, order: int = 1, chunk: int = 20000):
    """Same matrix as :func:`stiffness` (same DOF numbering), assembled with numpy element matrices.

    The form ``ddot(stress(grad u), grad v)`` on the basis ``u = phi_i e_c``, ``v = phi_j e_d`` is, by
    :func:`stress`, ``K_e[(i,c),(j,d)] = lambda T_icjd + mu (T_idjc + delta_cd sum_k T_ikjk)`` with
    ``T_icjd = sum_q w_q d_c phi_i d_d phi_j``: Hooke's law contracted with the gradients in closed form
    (about 3x faster for P2 than the generic form; equal to :func:`stiffness` to 1e-15, test)."""
    if np.ndim(materials[0]) == 0:
        materials = [materials, materials]
    lam_mu = np.array([lame(*m) for m in materials])
    basis = vector_basis(pair, order)
    gdofs = _global_dofs(pair, basis, order)
    ndof = basis.N
    K = sp.csr_matrix((ndof, ndof))
    eye = np.eye(3)
    for start in range(0, len(pair.tets), chunk):
        sl = slice(start, start + chunk)
        sub = PairMesh(pair.points, pair.tets[sl], pair.body[sl])
        grads, weights = _shape_gradients(sub, order)
        T = np.einsum("eqic,eqjd,eq->eicjd", grads, grads, weights, optimize=True)
        lam = lam_mu[pair.body[sl], 0][:, None, None, None, None]
        mu = lam_mu[pair.body[sl], 1][:, None, None, None, None]
        trace = np.einsum("eikjk->eij", T)[:, :, None, :, None] * eye[None, None, :, None, :]
        Ke = lam * T + mu * (T.transpose(0, 1, 4, 3, 2) + trace)
        g = gdofs[sl]  # (e, nloc, 3)
        nloc = g.shape[1] * 3
        rows = np.broadcast_to(g.reshape(-1, nloc, 1), (g.shape[0], nloc, nloc))
        cols = np.broadcast_to(g.reshape(-1, 1, nloc), (g.shape[0], nloc, nloc))
        K = K + sp.csr_matrix((Ke.reshape(-1), (rows.reshape(-1), cols.reshape(-1))), shape=(ndof, ndof))
    return K.tocsr(), basis
