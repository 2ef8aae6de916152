"""FE contact benchmark: DOFs, meshing, assembly, condensation and contact-solve time per
mesh level of the conformity-0.56 groove (R_B 5 mm, 100 N, steel).

Run: ``.venv/bin/python -m pytest benchmarks/test_bench_fem.py -s``.  Meshing
is measured with the cache bypassed; the figures are printed and stored in
``benchmark.extra_info``.
"""
from __future__ import annotations

import time

import pytest

from ballbench.fem import contact, hertz_case
from ballbench.lowmodel.contact import hertz
from ballbench.meshes.assemblies import contact_pairs

R, E, NU, LOAD = 5e-3, 2.1e11, 0.28, 100.0
LEVELS = [(5.5, 1.4), (6.0, 1.3), (7.0, 1.25), (8.0, 1.2)]  # capsule zone (fe-hertz-groove-056 before the slab)


@pytest.mark.parametrize("n, growth", LEVELS, ids=[f"n{n:g}-g{g:g}" for n, g in LEVELS])
def test_bench_groove_level(benchmark, n, growth):
    geometry = hertz.ball_in_groove(R, 0.56, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, LOAD)

    def build():
        return contact_pairs.ball_in_groove_pair(R, 0.56, ref.b / n, growth, fine_radius=1.4 * ref.b,
                                                 fine_half_length=1.1 * ref.a, cache=False)

    start = time.perf_counter()
    path = build()
    mesh_s = time.perf_counter() - start

    def run():
        return hertz_case.solve_case(lambda: path, LOAD, (E, NU), gap_limit=1.05 * ref.delta,
                                     initial_gap=lambda x, y: geometry.A * x * x + geometry.B * y * y,
                                     formulation="mortar", order=2)

    result = benchmark.pedantic(run, rounds=1, iterations=1)
    figures = dict(ndofs=result.ndofs, candidates=result.n_candidates, mesh_s=round(mesh_s, 2),
                   **{k: round(v, 2) for k, v in result.timings.items() if k != "mesh_s"},
                   iterations=result.iterations,
                   err_a=result.a / ref.a - 1, err_b=result.b / ref.b - 1, err_p0=result.p0 / ref.p0 - 1,
                   err_delta=result.delta / ref.delta - 1)
    benchmark.extra_info.update(figures)
    print(f"\nlevel n={n:g} growth={growth:g}: " + ", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                                                          for k, v in figures.items()))


@pytest.mark.parametrize("method", ["augmented", "schur", "rhs", "splu"])
def test_bench_condensation_method(benchmark, method):
    """Time of W = B K^-1 B^T by each linear-solver route (fem.linsolve.compliance) on the
    P1 node-to-surface groove level n = 8, growth 1.3 (62k DOFs)."""
    geometry = hertz.ball_in_groove(R, 0.56, youngs_modulus=E, poisson_ratio=NU)
    ref = hertz.solve_load(geometry, LOAD)
    path = contact_pairs.ball_in_groove_pair(R, 0.56, ref.b / 8, 1.3, fine_radius=1.4 * ref.b,
                                             fine_half_length=1.1 * ref.a)
    model = benchmark.pedantic(contact.build_model, args=(path, (E, NU), 1.05 * ref.delta),
                               kwargs=dict(method=method), rounds=1, iterations=1)
    benchmark.extra_info.update(ndofs=model.ndofs, candidates=int(model.candidates.size),
                                condense_s=round(model.timings["condense_s"], 2))
    print(f"\n{method}: ndofs={model.ndofs} candidates={model.candidates.size} "
          f"condense={model.timings['condense_s']:.2f} s")
