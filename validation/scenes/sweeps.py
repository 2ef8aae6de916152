"""Scenes of the sweep engine (validation/sweep.py, docs/sweeps.md)."""
from __future__ import annotations

import math
import shutil
import tempfile
from pathlib import Path

import numpy as np

from ballbench.validation import sweep
from ballbench.validation.scene import scene
from ballbench.validation.sweep.functions import EQUIVALENCE_SPEC

MODEL = "validation.sweep"
SWEEP = dict(model=MODEL, family="low-order numerical")  # the sweep runs the low-order two-ball model


def _difference(first: dict, second: dict) -> tuple[float, int]:
    """(max |difference| over every numeric column, NaN at the same places; number of differing error texts)."""
    worst = 0.0
    for name, values in first.items():
        if name == "error":
            continue
        other = second[name]
        if values.shape != other.shape or not np.array_equal(np.isnan(values), np.isnan(other)):
            return math.inf, 0
        finite = ~np.isnan(values)
        if finite.any():
            worst = max(worst, float(np.max(np.abs(values[finite] - other[finite]))))
    mismatched = int(sum(a != b for a, b in zip(first["error"], second["error"])))
    return worst, mismatched


@scene("sweep-equivalence", "The same sweep (lin2019 two-ball cases, grid x seeded draws, failures included) "
       "serially, on a LocalCluster with 2 workers, and stopped halfway then resumed: identical results",
       kind="low-order", cost_s=10.5)
def sweep_equivalence(run):
    spec = sweep.spec_from_dict(EQUIVALENCE_SPEC)
    work = Path(tempfile.mkdtemp(prefix="ballbench-sweep-"))
    try:
        serial = sweep.run_sweep(spec, work / "serial", serial=True, progress=False)
        reference = sweep.read_results(work / "serial")
        cluster = sweep.run_sweep(spec, work / "cluster", workers=2, progress=False)
        distributed = sweep.read_results(work / "cluster")
        first = sweep.run_sweep(spec, work / "resumed", serial=True, progress=False, max_chunks=3)
        second = sweep.run_sweep(spec, work / "resumed", serial=True, progress=False)
        resumed = sweep.read_results(work / "resumed")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    worst, errors = _difference(reference, distributed)
    run.check(**SWEEP, quantity="max abs(serial - LocalCluster(2 workers)) over all inputs and outputs",
              unit="mixed",
              value=worst, reference=0.0, scale=1.0, tolerance=0.0, time_s=cluster.wall_time_s,
              source="determinism: inputs depend only on the spec and the case number",
              note=f"{spec.n_cases} cases in chunks of {spec.chunk_size}; time: cluster run incl. start-up")
    run.check(**SWEEP, quantity="cases whose failure text differs (serial vs cluster)", unit="count",
              value=float(errors), reference=0.0, scale=1.0, tolerance=0.0, time_s=cluster.wall_time_s,
              source="failures are results: recorded per case with their reason")
    run.check(**SWEEP, quantity="cases in the cluster run", unit="count", value=float(distributed["case"].size),
              reference=float(spec.n_cases), tolerance=0.0, time_s=cluster.wall_time_s,
              source="every case recorded, failed or not")
    worst_resumed, errors_resumed = _difference(reference, resumed)
    run.check(**SWEEP, quantity="max abs(serial - stopped after 3 chunks + resumed)", unit="mixed",
              value=worst_resumed + errors_resumed, reference=0.0, scale=1.0, tolerance=0.0,
              time_s=first.wall_time_s + second.wall_time_s, source="resume from the Parquet parts")
    run.check(**SWEEP, quantity="cases computed by the resumed run", unit="count", value=float(second.computed),
              reference=float(spec.n_cases - first.computed), tolerance=0.0, time_s=second.wall_time_s,
              source="a restart computes only the missing cases")
    failed = int(sum(bool(e) for e in reference["error"]))
    reasons = sorted({e.split(":")[0] for e in reference["error"] if e})
    run.note(f"serial {serial.wall_time_s:.2f} s, LocalCluster(2) {cluster.wall_time_s:.2f} s incl. start-up; "
             f"{failed} of {spec.n_cases} cases failed ({', '.join(reasons) or 'none'}: rho = -0.95 lies outside "
             "four-point contact), recorded with their reason in both runs.")
