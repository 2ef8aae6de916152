"""One FE Hertz case: mesh -> condensed contact model -> load sweep -> a, b, p0, delta.

:func:`solve_case` is what the ``fe-hertz-*`` scenes, the tests and the
benchmarks call.  The load sweep ``load_factors`` (default 0.5, 0.75, 1, 1.25,
1.5 times the force) feeds the approach convention of
:func:`fem.postprocess.approach_fit`; the ellipse fit is done at the nominal force.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ballbench.fem import contact, postprocess
from ballbench.fem.mortar import build_mortar_model

__all__ = ["CaseResult", "solve_case", "contact_edge_length", "fit_contact_patch"]

LOAD_FACTORS = (0.5, 0.75, 1.0, 1.25, 1.5)


@dataclass
class CaseResult:
    """FE result at the nominal ``force`` [N]: fitted ``a, b`` [m], ``p0`` [Pa],
    contact approach ``delta`` [m] (bulk compliance removed), ``approach`` U [m]
    of the reference faces, ``bulk_compliance`` [m/N], ``force_sum`` [N],
    iterations/residual of the contact solve, ``ndofs``, ``n_candidates``,
    ``h_contact`` [m] (mean edge of the ball's contact triangles in contact),
    ``timings`` [s] (mesh, load, assembly, condense, contact), the sweep
    ``(forces, approaches)``, the model and the nominal state."""

    a: float
    b: float
    p0: float
    delta: float
    approach: float
    bulk_compliance: float
    force_sum: float
    iterations: int
    residual: float
    ndofs: int
    n_candidates: int
    h_contact: float
    timings: dict
    sweep: tuple
    fit: postprocess.EllipseFit
    approach_fit: postprocess.ApproachFit
    model: contact.ContactModel = field(repr=False)
    state: contact.ContactState = field(repr=False)

    @property
    def total_time_s(self) -> float:
        return float(sum(self.timings.values()))


def contact_edge_length(model: contact.ContactModel, active: np.ndarray) -> float:
    """Mean edge length [m] of the ball-contact triangles with all nodes in ``active`` candidates."""
    pts = model.pair.points
    tris = model.pair.surfaces["ball_contact"]
    mask = np.zeros(len(pts), bool)
    mask[model.candidates[active]] = True
    inside = tris[mask[tris].all(axis=1)]
    if inside.size == 0:
        inside = tris[mask[tris].any(axis=1)]
    edges = np.concatenate([inside[:, [0, 1]], inside[:, [1, 2]], inside[:, [2, 0]]])
    return float(np.mean(np.linalg.norm(pts[edges[:, 0]] - pts[edges[:, 1]], axis=1)))


def fit_contact_patch(model: contact.ContactModel, state: contact.ContactState, operator=None):
    """Hertz ellipse (``postprocess.EllipseFit``: a, b [m], p0 [Pa]) of the contact patch of ``state``.

    Mortar models (nodal pressures): :func:`fem.postprocess.moment_ellipse`, the ellipse with the
    FE pressure's force and second moments over the ball's contact triangles whose vertices are all
    candidates.  Node-to-surface models (nodal forces): the least-squares fit of the consistent
    forces (:func:`fem.postprocess.fit_ellipse_forces`); ``operator`` is the ``(xq, M)`` of
    :func:`fem.postprocess.force_operator` for it (computed when None; pass it to fit several
    states of one model; not used by mortar models).
    """
    symmetric_x = "symmetry_x" in model.pair.surfaces
    symmetric_y = "symmetry_y" in model.pair.surfaces
    if model.multiplier == "pressure":
        index = -np.ones(len(model.pair.points), dtype=np.int64)
        index[model.candidates] = np.arange(model.candidates.size)
        tris = index[model.pair.surfaces["ball_contact"]]
        tris = tris[(tris >= 0).all(axis=1)]
        return postprocess.moment_ellipse(model.pair.points[model.candidates, :2], tris, state.pressure,
                                          symmetric_x=symmetric_x, symmetric_y=symmetric_y,
                                          symmetry_factor=model.symmetry_factor)
    if operator is None:
        operator = postprocess.force_operator(model.pair.points, model.pair.surfaces["ball_contact"],
                                              model.candidates)
    xq, matrix = operator
    return postprocess.fit_ellipse_forces(xq, matrix, state.forces, symmetric_x=symmetric_x,
                                          symmetric_y=symmetric_y)


def solve_case(mesh_builder, force: float, materials, gap_limit: float, *, load_factors=LOAD_FACTORS,
               method: str = "augmented", min_elements: float = 5.0, tol: float = 1e-10,
               initial_gap=None, formulation: str = "node", order: int = 1) -> CaseResult:
    """Solve one FE Hertz case.

    ``mesh_builder()`` returns the ``.msh`` path (timed as meshing; a cached
    mesh costs nothing).  ``force`` [N] full-model force; ``materials`` ``(E, nu)``;
    ``gap_limit`` [m] candidate zone (see :func:`fem.contact.build_model`); it must
    hold the contact at ``max(load_factors) * force``.  A contact patch with fewer
    than ``min_elements`` elements across its fitted minor semi-axis raises
    ValueError with the size to use.  ``initial_gap``: see :func:`fem.contact.build_model`.
    """
    timings = {}
    t0 = time.perf_counter()
    path = Path(mesh_builder())
    timings["mesh_s"] = time.perf_counter() - t0
    if formulation == "node":
        if order != 1:
            raise ValueError(f"node-to-surface contact needs order 1, got {order!r}")
        model = contact.build_model(path, materials, gap_limit, method=method, initial_gap=initial_gap)
    elif formulation == "mortar":
        model = build_mortar_model(path, materials, gap_limit, order=order, method=method, initial_gap=initial_gap)
    else:
        raise ValueError(f"formulation must be 'node' or 'mortar', got {formulation!r}")
    timings.update(model.timings)
    t0 = time.perf_counter()
    forces, approaches, nominal, state = [], [], None, None
    for factor in sorted(set(load_factors) | {1.0}):
        state = contact.solve_force(model, factor * force, tol=tol, start=state)
        forces.append(state.force)
        approaches.append(state.approach)
        if factor == 1.0:
            nominal = state
    timings["contact_s"] = time.perf_counter() - t0
    fit = fit_contact_patch(model, nominal)
    h = contact_edge_length(model, nominal.active)
    postprocess.mesh_check(h, min(fit.a, fit.b), min_elements)
    approach = postprocess.approach_fit(forces, approaches)
    return CaseResult(fit.a, fit.b, fit.p0, approach.contact_approach(force), nominal.approach,
                      approach.bulk_compliance, nominal.force, nominal.iterations, nominal.residual, model.ndofs,
                      int(model.candidates.size), h, timings, (np.array(forces), np.array(approaches)), fit,
                      approach, model, nominal)
