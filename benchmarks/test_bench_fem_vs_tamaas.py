"""FE Hertz benchmark side by side with a half-space BEM code (docs/fem.md, "Profile of one level").

``fe-hertz-groove-056``'s case (cases.lin2019.CONTACT_GROOVE_056) at its default level (the scene's own mesh level
and solve: ``validation.studies.fe_contact.solve_level``) against tamaas at 256 x 256 on the same Hertz
problem (ball in a straight groove, conformity 0.56, R_B 5 mm, 100 N, steel; Hertz's
quadratic gap), tamaas on one thread (``OMP_NUM_THREADS=1``, in a child process so that its
OpenMP runtime starts with it), measured in one run.  Both errors in a, b and p0 against
``lowmodel.contact.hertz`` and both times (wall and CPU) are printed.

Target (docs/fem.md): ours within 8x tamaas's time, the accuracy class kept (a, b 0.5 %, p0 1 %).
The FE level is timed as the scene checks it (assembly + condensation + load sweep + fit,
the mesh cached; the mesh build is timed separately, uncached, and printed too).

Run: ``.venv/bin/python -m pytest benchmarks/test_bench_fem_vs_tamaas.py -s``.
"""
from __future__ import annotations

import os

import pytest
from tamaas_support import hertz_groove_in_child, timed

from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import lin2019

CASE = lin2019.CONTACT_GROOVE_056
GRID = 256
TOLERANCE = 1e-8  # tamaas's Polonsky-Keer relative tolerance, as benchmarks/test_bench_halfspace.py
TARGET_RATIO = 8.0


def _tamaas(conformity):
    """tamaas on the groove's Hertz problem, in a child process with ``OMP_NUM_THREADS=1``
    (:func:`tamaas_support.hertz_groove_in_child`); its own wall and CPU time of model set-up and solve."""
    pytest.importorskip("tamaas")
    return hertz_groove_in_child(CASE.ball_radius, conformity, CASE.material.youngs_modulus,
                                 CASE.material.poisson_ratio, CASE.force, GRID, TOLERANCE)


def test_bench_fe_vs_tamaas(benchmark, tmp_path, monkeypatch):
    from ballbench.validation.studies import fe_contact

    case = fe_contact.pair_model(CASE)
    n, growth = CASE.fe.levels.checked("default")
    ref = hertz.solve_load(case.geometry, case.force)
    theirs = _tamaas(CASE.conformity)

    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))  # the mesh build, uncached: what a first run pays
    _, mesh_wall, mesh_cpu = timed(lambda: case.builder(float(ref.b) / n, growth))
    measured = benchmark.pedantic(timed, args=(lambda: fe_contact.solve_level(case, (n, growth)),), rounds=1,
                                  iterations=1)  # the benchmark's own statistic is the FE level's wall time
    (result, _), wall, cpu = measured
    ours = dict(a=result.a, b=result.b, p0=result.p0)
    errors = {who: {q: values[q] / float(getattr(ref, q)) - 1.0 for q in ("a", "b", "p0")}
              for who, values in (("ours", ours), ("tamaas", theirs))}
    ratio_cpu, ratio_wall = cpu / theirs["cpu"], wall / theirs["wall"]
    benchmark.extra_info.update(ndofs=result.ndofs, ours_wall_s=wall, ours_cpu_s=cpu, mesh_wall_s=mesh_wall,
                                tamaas_wall_s=theirs["wall"], tamaas_cpu_s=theirs["cpu"], ratio_cpu=ratio_cpu,
                                ratio_wall=ratio_wall, load_average=os.getloadavg()[0],
                                **{f"{who}_err_{q}": e for who, err in errors.items() for q, e in err.items()})

    def line(who):
        return ", ".join(f"{q} {100 * e:+.3f} %" for q, e in errors[who].items())

    print(f"\n{CASE.name} default level (n = b/h {n:g}, growth {growth:g}, {result.ndofs} DOFs) vs tamaas "
          f"{theirs['version']} {GRID} x {GRID} (PolonskyKeerRey, dcfft, tolerance {TOLERANCE:g}, one thread); "
          f"load average {os.getloadavg()[0]:.1f}\n"
          f"  ours:   wall {wall:.2f} s, CPU {cpu:.2f} s (+ mesh build {mesh_wall:.2f} s wall, {mesh_cpu:.2f} s CPU, "
          f"uncached); error vs Hertz {line('ours')}\n"
          f"  tamaas: wall {theirs['wall']:.2f} s, CPU {theirs['cpu']:.2f} s; error vs Hertz {line('tamaas')}\n"
          f"  time ratio ours/tamaas: CPU {ratio_cpu:.1f}, wall {ratio_wall:.1f} (target <= {TARGET_RATIO:g}); "
          f"with the mesh build: CPU {(cpu + mesh_cpu) / theirs['cpu']:.1f}")
