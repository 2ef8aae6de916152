"""FE contact benchmark: scikit-fem two-body contact against exact Hertz (lowmodel.contact.hertz).

Each scene runs one :class:`ContactCase` of cases.lin2019 through studies.fe_contact (mesh levels, fine zone:
the case's ``fe``) and compares the fitted a, b, p0 and the contact approach delta with Hertz.  Fidelity
``quick`` is the coarse CI level, ``default`` the default level, ``fine`` the convergence study (>= 4 levels;
the finest is checked).  Tolerances (docs/fem.md, "Validation"): default level a, b 0.5 %, p0 1 %, delta 0.5 %,
<= 60 s; finest level a, b 0.3 %, p0 0.5 %, delta 0.2 %, <= 300 s.  The quick level is a smoke test of the
whole chain with its own, stated tolerance (3 %, p0 4 %).
"""
from __future__ import annotations

import functools
import time

from ballbench.fem.hertz_case import LOAD_FACTORS
from ballbench.validation.cases import lin2019
from ballbench.validation.figures import render3d
from ballbench.validation.scene import scene
from ballbench.validation.studies import fe_contact

MODEL = "fem.contact"
QUANTITIES = (("a", "m"), ("b", "m"), ("p0", "Pa"), ("delta", "m"))
TOLERANCES = {
    "quick": {"a": 0.03, "b": 0.03, "p0": 0.04, "delta": 0.03},
    "default": {"a": 0.005, "b": 0.005, "p0": 0.01, "delta": 0.005},
    "fine": {"a": 0.003, "b": 0.003, "p0": 0.005, "delta": 0.002},
}
TIME_LIMIT_S = {"quick": 60.0, "default": 60.0, "fine": 300.0}
# the whole scene: the checked level's solve (TIME_LIMIT_S) plus the fields, figures and reference
SCENE_BUDGET_S = {"quick": 90.0, "default": 120.0, "fine": 600.0}
# (scene, description, case, rough wall time of the default level on 2 shared cores [s] for `ballbench scenes`)
FE_SCENES = (
    ("fe-hertz-flat", "FE contact, ball (R 5 mm) on a flat, 100 N, steel: a, b, p0, delta against Hertz",
     lin2019.CONTACT_FLAT, 15),
    ("fe-hertz-ball-ball", "FE contact, ball on ball (R 5 mm each), 100 N: a, b, p0, delta against Hertz",
     lin2019.CONTACT_BALL, 15),
    ("fe-hertz-groove-052", "FE contact, ball in a straight groove, conformity 0.52, 100 N: against Hertz",
     lin2019.CONTACT_GROOVE_052, 60),
    ("fe-hertz-groove-056", "FE contact, ball in a straight groove, conformity 0.56, 100 N: against Hertz",
     lin2019.CONTACT_GROOVE_056, 30),
    ("fe-hertz-groove-060", "FE contact, ball in a straight groove, conformity 0.60, 100 N: against Hertz",
     lin2019.CONTACT_GROOVE_060, 25),
    ("fe-hertz-screw", "FE contact, ball in a helical screw groove (lin2019 Table 4), 100 N: against Hertz",
     lin2019.CONTACT_SCREW, 90),
    ("fe-hertz-nut", "FE contact, ball in a helical nut groove (lin2019 Table 4), 100 N: against Hertz",
     lin2019.CONTACT_NUT, 90),
)


def _run(run, case) -> None:
    pair = fe_contact.pair_model(case)
    levels = case.fe.levels[run.fidelity]
    rows, results = [], []
    for level in run.progress(levels, desc=f"{run.scene.name} mesh levels"):
        start = time.perf_counter()
        result, ref = fe_contact.solve_level(pair, level)
        wall = time.perf_counter() - start
        errors = {q: float(getattr(result, q) / float(getattr(ref, q)) - 1.0) for q, _ in QUANTITIES}
        rows.append(dict(n=level.n, growth=level.growth, h_contact=result.h_contact, ndofs=result.ndofs,
                         candidates=result.n_candidates, iterations=result.iterations, residual=result.residual,
                         wall_s=wall, **{k if k.endswith("_s") else f"{k}_s": v for k, v in result.timings.items()},
                         **{f"err_{q}": e for q, e in errors.items()}))
        results.append((result, ref, wall))
        if len(results) < len(levels) and result.model.factor is not None:
            result.model.factor.free()  # only the checked level's factor is kept (for the VTU export)
    result, ref, wall = results[-1]
    tolerances = TOLERANCES[run.fidelity]
    checked = levels[-1]
    level = f"n = b/h {checked.n:g}, growth {checked.growth:g}"
    which = "finest level" if run.fidelity == "fine" else f"{run.fidelity} level"
    for quantity, unit in QUANTITIES:
        run.check(model=MODEL, family="FE", level=level, quantity=quantity, unit=unit,
                  value=getattr(result, quantity), reference=float(getattr(ref, quantity)), source=pair.source,
                  tolerance=tolerances[quantity], time_s=wall,
                  note=f"{which}: n = b/h = {rows[-1]['n']:g}, growth {rows[-1]['growth']:g}, {result.ndofs} DOFs")
    if run.fidelity == "fine":
        for quantity, tolerance in case.fe.fine_targets:
            run.check(model=MODEL, family="FE", level=level, quantity=f"{quantity} (finest-level target)",
                      unit=dict(QUANTITIES)[quantity], value=getattr(result, quantity),
                      reference=float(getattr(ref, quantity)), source=pair.source, tolerance=tolerance, time_s=wall,
                      note="finest level: the targets of docs/fem.md (a, b <= 0.2 %, p0 <= 0.3 % at --fine)")
    run.check(model=MODEL, family="FE", level=level, quantity="force_sum", unit="N", value=result.force_sum,
              reference=case.force, source="load equilibrium (sum of contact forces)", tolerance=1e-9, time_s=wall)
    run.budget(model=MODEL, family="FE", level=level, quantity="wall_time", unit="s", value=wall,
               budget=TIME_LIMIT_S[run.fidelity], time_s=wall,
               source="docs/fem.md time budget (meshing + assembly + condensation + load sweep + fit of the checked "
                      "level; a cached mesh costs nothing)")
    run.note(f"contact solve: {result.iterations} active-set iterations, complementarity residual "
             f"{result.residual:.1e} (tolerance 1e-10); bulk compliance C_b = {result.bulk_compliance:.3e} m/N "
             f"(FE approach of the reference faces {result.approach:.4e} m = delta + C_b F; rms residual of "
             f"U = C_H F^(2/3) + C_b F over the sweep F x {LOAD_FACTORS}: "
             f"{result.approach_fit.rms / result.delta:.1e} delta)")
    run.write_csv("convergence.csv", rows)
    if run.fidelity != "quick":  # one more solve with the kept factor; CI skips it
        start = time.perf_counter()
        for path in fe_contact.write_fields(result, ref, run.path(""), scene_name=run.scene.name,
                                            fidelity=run.fidelity, level=checked, material=case.material):
            run.add_artifact(path)
        for path in render3d.artifacts(run.path(""), run.note):  # 3D screenshots of those fields
            run.add_artifact(path)
        run.note(f"fields.vtu (quadratic tetrahedra: the P2 displacement at all nodes, contact pressure, von Mises "
                 f"and sigma_zz of the P2 stress; `ballbench show {run.scene.name}` draws them) took "
                 f"{time.perf_counter() - start:.1f} s more (one solve with the factor of the condensation, no second "
                 "factorisation); not part of the checked wall time")
    from ballbench.validation.figures.fe_contact import convergence_figure

    run.save_figure(convergence_figure(run.scene.name, rows), "convergence.png")


def _register(name: str, description: str, case, cost_s: float) -> None:
    def run_case(run):
        _run(run, case)

    run_case.__name__ = run_case.__qualname__ = name.replace("-", "_")
    default = case.fe.levels.checked("default")
    scene(name, description, kind="FE", cost_s=cost_s, level=f"n = b/h {default.n:g}, growth {default.growth:g}",
          budget_s=SCENE_BUDGET_S, case=case,
          show=functools.partial(fe_contact.show_fields, case, cost_s=cost_s))(run_case)


for _entry in FE_SCENES:
    _register(*_entry)
