"""Parameter sweeps on dask.distributed, written to Parquet as they arrive (``ballbench sweep SPEC.toml``).

A sweep names a model function, its fixed inputs, the swept ones (grids and
seeded random draws) and the outputs to keep (docs/sweeps.md).  Modules:

- :mod:`.spec`: parsing and checking a spec (:func:`load_spec`, :func:`spec_from_dict`), units through
  :mod:`ballbench.validation.cases.units` (shared with case files and calibrate specs);
- :mod:`.cases`: case numbering, reproducible draws, computing a chunk of cases in any process (:func:`run_chunk`);
- :mod:`.execution`: running the chunks on dask or serially (:func:`run_sweep`);
- :mod:`.storage`: Parquet parts, the manifest, resuming, the xarray Dataset of a gridded sweep;
- :mod:`.command`: the ``ballbench sweep`` command.

Spec (TOML)::

    name = "lin2019-fig8-9"
    function = "ballbench.validation.sweep.functions:two_ball_numerical"
    vectorised = false          # true: one call per chunk with arrays (the function broadcasts)
    chunk_size = 200
    outputs = ["epsilon_1", "epsilon_2", "b2b_force", "friction_increase"]

    [fixed]
    vertical_force = 100.0
    top_tr = { value = 0.5, unit = "deg" }

    [grid]
    theta = { linspace = [-3.0, 3.0, 101], unit = "deg" }
    rho = { values = [-0.6, 0.0, 0.6] }

    [random]
    draws = 1000
    seed = 2019
    [random.inputs]
    top_tl = { distribution = "normal", mean = 0.0, sigma = 0.5, unit = "deg" }
"""
from __future__ import annotations

from ballbench.validation.sweep.cases import (DRAW_BLOCK, VECTOR_LEAF, case_inputs, check_inputs, resolve_function,
                                              run_chunk)
from ballbench.validation.sweep.command import add_parser, main
from ballbench.validation.sweep.execution import (DATASET_EVERY_S, LOCAL_CLUSTER_CONFIG, SweepSummary,
                                                  failure_reasons, run_sweep)
from ballbench.validation.sweep.spec import DISTRIBUTIONS, Distribution, SweepSpec, load_spec, spec_from_dict
from ballbench.validation.sweep.storage import (DATASET_NAME, missing_chunks, read_dataset, read_results, to_dataset,
                                                write_dataset)
from ballbench.validation.cases.units import UNITS

__all__ = ["SweepSpec", "Distribution", "load_spec", "spec_from_dict", "case_inputs", "run_chunk", "run_sweep",
           "read_results", "SweepSummary", "UNITS", "DRAW_BLOCK", "to_dataset", "read_dataset", "write_dataset",
           "DATASET_NAME", "DATASET_EVERY_S", "LOCAL_CLUSTER_CONFIG", "VECTOR_LEAF", "DISTRIBUTIONS",
           "check_inputs", "resolve_function", "failure_reasons", "missing_chunks", "main", "add_parser"]
