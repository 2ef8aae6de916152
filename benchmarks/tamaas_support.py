"""tamaas on a half-space contact, for the benchmarks that set our solvers beside it.

Shared by benchmarks/test_bench_halfspace.py (in process) and benchmarks/test_bench_fem_vs_tamaas.py
(in a child process, :func:`hertz_groove_in_child`).  tamaas's Polonsky-Keer-Rey solver with its
non-periodic DC-FFT operator, the algorithm and operator of :func:`lowmodel.contact.halfspace.solve`.

Run as a script (what :func:`hertz_groove_in_child` does): ``python tamaas_support.py JSON`` with JSON the
list ``[R_B m, conformity, E Pa, nu, force N, grid n, tolerance]``; prints one JSON line.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np


def timed(function):
    """``(function(), wall time s, CPU time s of this process)``: the machine is shared, CPU time is steadier."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = function()
    return result, time.perf_counter() - wall, time.process_time() - cpu


def tamaas_pressure(gap: np.ndarray, grid, contact_modulus: float, force: float, tolerance: float) -> np.ndarray:
    """Contact pressure [Pa], shape (nx, ny), from tamaas on ``gap`` [m] over ``grid``
    (:class:`lowmodel.contact.halfspace.SurfaceGrid`), E* ``contact_modulus`` [Pa], normal ``force`` [N],
    relative ``tolerance`` of its Polonsky-Keer iteration.  Builds a new model each call (set-up and solve)."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    sizes = [grid.nx * grid.dx, grid.ny * grid.dy]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, sizes, [grid.nx, grid.ny])
    model.E, model.nu = contact_modulus, 0.0  # E* = E / (1 - nu^2)
    tm.ModelFactory.registerNonPeriodic(model, "dcfft")
    solver = tm.PolonskyKeerRey(model, -gap, tolerance)
    solver.setIntegralOperator("dcfft")
    solver.solve(force / (sizes[0] * sizes[1]))  # mean pressure over the grid
    return np.array(model.traction)


def hertz_groove_in_child(ball_radius: float, conformity: float, youngs_modulus: float, poisson_ratio: float,
                          force: float, grid_n: int, tolerance: float) -> dict:
    """tamaas on the Hertz problem of a ball [m] in a straight groove (quadratic gap on
    :func:`halfspace.hertz_surface_grid`, ``grid_n`` cells a side), in a child process with
    ``OMP_NUM_THREADS=1`` (set before its OpenMP runtime starts).

    Returns ``a``, ``b`` [m] (:func:`halfspace.pressure_ellipse`), ``p0`` [Pa], tamaas's own ``wall`` and
    ``cpu`` time [s] of model set-up and solve, and its ``version``.
    """
    args = [ball_radius, conformity, youngs_modulus, poisson_ratio, force, grid_n, tolerance]
    out = subprocess.run([sys.executable, __file__, json.dumps(args)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1"))
    return json.loads(out.stdout.strip().splitlines()[-1])


def _main(argument: str) -> dict:
    import tamaas as tm

    from ballbench.lowmodel.contact import halfspace as hs
    from ballbench.lowmodel.contact import hertz

    radius, conformity, modulus, ratio, force, grid_n, tolerance = json.loads(argument)
    geometry = hertz.ball_in_groove(radius, conformity, youngs_modulus=modulus, poisson_ratio=ratio)
    contact = hertz.solve_load(geometry, force)
    grid = hs.hertz_surface_grid(float(contact.a), float(contact.b), grid_n)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    pressure, wall, cpu = timed(lambda: tamaas_pressure(gap, grid, geometry.contact_modulus, force, tolerance))
    a, b, _, _ = hs.pressure_ellipse(pressure, grid)
    return dict(a=a, b=b, p0=float(pressure.max()), wall=wall, cpu=cpu, version=tm.__version__)


if __name__ == "__main__":
    print(json.dumps(_main(sys.argv[1])))
