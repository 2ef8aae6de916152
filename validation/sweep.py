"""Parameter sweeps on dask.distributed, written to Parquet as they arrive (``ballbench sweep SPEC.toml``).

A sweep names a model function, its fixed inputs, the swept ones (grids and
seeded random draws) and the outputs to keep.  Cases are numbered
``0 .. n_cases-1``; case ``i`` is grid point ``i // draws`` (C order over the
grid axes in the order of the spec) with random draw ``i % draws`` (the same
draws at every grid point: common random numbers).  Random draws come from
fixed blocks of :data:`DRAW_BLOCK` draws, block ``k`` seeded by
``SeedSequence(seed, spawn_key=(k,))``: a case's inputs depend only on the
spec and its number, never on the chunking or on the worker that ran it.

Execution: chunks of ``chunk_size`` consecutive cases, one task each, on a
``LocalCluster`` (default), an existing scheduler (``--scheduler ADDRESS``) or
in this process (``--serial``).  Every finished chunk is written at once to
``OUT/part-<start>-<stop>.parquet`` (written to a temporary name and renamed,
so a killed sweep never leaves a half file); a restarted sweep reads the part
names and computes only the cases no part holds.  ``OUT/sweep.json`` keeps the
spec; a restart with a different spec (other than ``chunk_size``) is refused.

Gridded sweeps (a ``[grid]`` table) also land in an xarray Dataset,
``OUT/results.zarr`` (Zarr format 3): one dimension per grid axis with the
axis values as coordinates (``rho``, ``theta`` of the Fig 8/9 maps), plus
``draw`` when the spec has random draws; data variables: the outputs, the
random inputs, ``error`` (str) and ``done`` (bool).  It is rebuilt from the
Parquet parts every :data:`DATASET_EVERY_S` seconds while a sweep runs and when
it stops (also when interrupted); cases not computed yet are NaN with
``done = False``.  The Parquet parts stay the record a restart resumes from
(atomic per chunk); :func:`read_dataset` builds the same Dataset from them.

Each row holds ``case``, the swept inputs (SI units), the outputs and
``error`` (empty, or ``"ExceptionType: message"`` of a failed case, whose
outputs are null).  A non-finite output is a failure too.  Nothing is dropped.

Spec (TOML; docs/sweeps.md)::

    name = "lin2019-fig8-9"
    function = "ballbench.validation.sweep_cases:two_ball_numerical"
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

import hashlib
import importlib
import inspect
import itertools
import json
import math
import os
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ballbench.validation.specs import read_toml

__all__ = ["SweepSpec", "Distribution", "load_spec", "spec_from_dict", "case_inputs", "run_chunk", "run_sweep",
           "read_results", "SweepSummary", "UNITS", "DRAW_BLOCK", "to_dataset", "read_dataset", "write_dataset",
           "DATASET_NAME", "DATASET_EVERY_S", "LOCAL_CLUSTER_CONFIG"]

DRAW_BLOCK = 4096  # random draws per seeded block (fixed: changing it changes every draw)
IN_FLIGHT_MIN, IN_FLIGHT_PER_THREAD = 16, 4  # tasks submitted ahead of the results
VECTOR_LEAF = 8  # a vectorised call that raises is halved down to this many cases, then called case by case
DATASET_NAME = "results.zarr"  # xarray Dataset of a gridded sweep (Zarr store)
DATASET_EVERY_S = 30.0  # rebuild the Dataset from the parts at most this often while a sweep runs [s]
# dask settings of the LocalCluster that run_sweep starts: the workers' statistical profiler (a stack sample of
# every thread each 10 ms, for the dashboard) and the 20 ms event-loop tick cost CPU that the cases need on a
# small machine (5,000-case two-ball Monte Carlo, 2 cores: 9-13 % less CPU in all, docs/sweeps.md run 9).
# An external cluster keeps its own settings (DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False, docs).
LOCAL_CLUSTER_CONFIG = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "1s"}
# units accepted in a spec and their SI factor (inputs are converted at the edge, docs/developing.md)
UNITS = {"": 1.0, "1": 1.0, "rad": 1.0, "deg": math.pi / 180.0, "m": 1.0, "mm": 1e-3, "um": 1e-6, "N": 1.0,
         "kN": 1e3, "Pa": 1.0, "GPa": 1e9, "m/s": 1.0, "mm/s": 1e-3, "s": 1.0}
DISTRIBUTIONS = {"normal": ("mean", "sigma"), "uniform": ("low", "high"), "lognormal": ("mean", "sigma")}
_PART = re.compile(r"^part-(\d{12})-(\d{12})\.parquet$")
_TOP_KEYS = {"name", "function", "vectorised", "chunk_size", "outputs", "fixed", "grid", "random", "description"}


def _unit(where: str, unit: str) -> float:
    if unit not in UNITS:
        raise ValueError(f"{where}: unit must be one of {sorted(UNITS)}, got {unit!r}")
    return UNITS[unit]


@dataclass(frozen=True)
class Distribution:
    """A random input: ``kind`` in :data:`DISTRIBUTIONS`, its two parameters (in ``unit``), SI factor."""

    kind: str
    first: float
    second: float
    factor: float = 1.0

    def draw(self, rng: np.random.Generator, size: int) -> np.ndarray:
        if self.kind == "normal":
            values = rng.normal(self.first, self.second, size)
        elif self.kind == "uniform":
            values = rng.uniform(self.first, self.second, size)
        else:  # lognormal: mean and sigma of the underlying normal
            values = rng.lognormal(self.first, self.second, size)
        return values * self.factor


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep spec (see the module docstring); every number in SI units."""

    name: str
    function: str
    outputs: tuple[str, ...]
    fixed: dict = field(default_factory=dict)
    grid: dict = field(default_factory=dict)        # name -> (k,) array
    random: dict = field(default_factory=dict)      # name -> Distribution
    draws: int = 1
    seed: int = 0
    chunk_size: int = 100
    vectorised: bool = False
    source: dict = field(default_factory=dict, repr=False)  # the raw spec, for the manifest

    @property
    def grid_shape(self) -> tuple[int, ...]:
        return tuple(len(v) for v in self.grid.values())

    @property
    def n_cases(self) -> int:
        return int(np.prod(self.grid_shape, dtype=np.int64)) * self.draws

    @property
    def input_names(self) -> tuple[str, ...]:
        return tuple(self.grid) + tuple(self.random)

    def identity(self) -> str:
        """Hash of everything that decides the results (not ``chunk_size``)."""
        raw = {k: v for k, v in self.source.items() if k not in ("chunk_size", "description")}
        return hashlib.sha256(json.dumps(raw, sort_keys=True, default=str).encode()).hexdigest()[:16]


def _number(where: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{where} must be a finite number, got {value!r}")
    return float(value)


def _fixed_value(name: str, value):
    if isinstance(value, dict):
        unknown = set(value) - {"value", "unit"}
        if unknown or "value" not in value:
            raise ValueError(f"fixed.{name}: a table needs 'value' and optionally 'unit', got keys {sorted(value)}")
        factor = _unit(f"fixed.{name}", value.get("unit", ""))
        inner = value["value"]
        if isinstance(inner, list):
            return [_number(f"fixed.{name}.value", v) * factor for v in inner]
        return _number(f"fixed.{name}.value", inner) * factor
    return value  # numbers, strings, booleans and lists pass as they are


def _grid_axis(name: str, axis) -> np.ndarray:
    where = f"grid.{name}"
    if isinstance(axis, list):
        axis = {"values": axis}
    if not isinstance(axis, dict):
        raise ValueError(f"{where} must be a list of values or a table with 'linspace' or 'values'")
    keys = set(axis) - {"unit"}
    if keys not in ({"linspace"}, {"values"}):
        raise ValueError(f"{where} needs exactly one of 'linspace' = [start, stop, num] or 'values', "
                         f"got {sorted(keys)}")
    factor = _unit(where, axis.get("unit", ""))
    if "linspace" in axis:
        spec = axis["linspace"]
        if not (isinstance(spec, list) and len(spec) == 3):
            raise ValueError(f"{where}.linspace must be [start, stop, num], got {spec!r}")
        num = spec[2]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise ValueError(f"{where}.linspace num must be an integer >= 1, got {num!r}")
        values = np.linspace(_number(f"{where}.linspace start", spec[0]), _number(f"{where}.linspace stop", spec[1]),
                             num)
    else:
        values = np.array([_number(f"{where}.values[{k}]", v) for k, v in enumerate(axis["values"])], dtype=float)
        if values.size == 0:
            raise ValueError(f"{where}.values must not be empty")
    return values * factor


def _distribution(name: str, table) -> Distribution:
    where = f"random.inputs.{name}"
    if not isinstance(table, dict) or "distribution" not in table:
        raise ValueError(f"{where} must be a table with 'distribution' = one of {sorted(DISTRIBUTIONS)}")
    kind = table["distribution"]
    if kind not in DISTRIBUTIONS:
        raise ValueError(f"{where}.distribution must be one of {sorted(DISTRIBUTIONS)}, got {kind!r}")
    first, second = DISTRIBUTIONS[kind]
    unknown = set(table) - {"distribution", "unit", first, second}
    if unknown or first not in table or second not in table:
        raise ValueError(f"{where}: a {kind} distribution takes '{first}', '{second}' and optionally 'unit', "
                         f"got keys {sorted(table)}")
    a = _number(f"{where}.{first}", table[first])
    b = _number(f"{where}.{second}", table[second])
    if kind in ("normal", "lognormal") and b < 0.0:
        raise ValueError(f"{where}.sigma must be >= 0, got {b!r}")
    if kind == "uniform" and not b > a:
        raise ValueError(f"{where}: uniform needs high > low, got low = {a!r}, high = {b!r}")
    factor = _unit(where, table.get("unit", ""))
    if kind == "lognormal" and table.get("unit", "") not in ("", "1"):
        raise ValueError(f"{where}: a lognormal input is dimensionless (its mean/sigma are of log x); drop 'unit'")
    return Distribution(kind, a, b, factor)


def spec_from_dict(raw: dict) -> SweepSpec:
    """Parse and check a spec table (the TOML document as a dict)."""
    if not isinstance(raw, dict):
        raise ValueError("a sweep spec must be a table")
    unknown = set(raw) - _TOP_KEYS
    if unknown:
        raise ValueError(f"unknown spec key(s) {sorted(unknown)}; allowed: {sorted(_TOP_KEYS)}")
    for key in ("name", "function", "outputs"):
        if key not in raw:
            raise ValueError(f"spec needs '{key}'")
    name = raw["name"]
    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        raise ValueError(f"name must be letters, digits, '_', '.', '-', got {name!r}")
    function = raw["function"]
    if not isinstance(function, str) or ":" not in function:
        raise ValueError(f"function must be 'package.module:function', got {function!r}")
    outputs = raw["outputs"]
    if not (isinstance(outputs, list) and outputs and all(isinstance(o, str) and o for o in outputs)):
        raise ValueError(f"outputs must be a non-empty list of names (attribute, key or 'name[i]'), got {outputs!r}")
    if len(set(outputs)) != len(outputs):
        raise ValueError("outputs must not repeat a name")
    chunk = raw.get("chunk_size", 100)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ValueError(f"chunk_size must be an integer >= 1, got {chunk!r}")
    vectorised = raw.get("vectorised", False)
    if not isinstance(vectorised, bool):
        raise ValueError(f"vectorised must be true or false, got {vectorised!r}")
    fixed = {k: _fixed_value(k, v) for k, v in raw.get("fixed", {}).items()}
    grid = {k: _grid_axis(k, v) for k, v in raw.get("grid", {}).items()}
    random_table = raw.get("random", {})
    draws, seed, random = 1, 0, {}
    if random_table:
        unknown = set(random_table) - {"draws", "seed", "inputs"}
        if unknown:
            raise ValueError(f"unknown random key(s) {sorted(unknown)}; allowed: draws, seed, inputs")
        draws = random_table.get("draws")
        if isinstance(draws, bool) or not isinstance(draws, int) or draws < 1:
            raise ValueError(f"random.draws must be an integer >= 1, got {draws!r}")
        seed = random_table.get("seed")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ValueError(f"random.seed must be an integer >= 0 (reproducible draws), got {seed!r}")
        inputs = random_table.get("inputs", {})
        if not inputs:
            raise ValueError("random needs at least one input under [random.inputs]")
        random = {k: _distribution(k, v) for k, v in inputs.items()}
    clash = (set(fixed) & set(grid)) | (set(fixed) & set(random)) | (set(grid) & set(random))
    if clash:
        raise ValueError(f"input(s) {sorted(clash)} appear in more than one of fixed, grid, random")
    shared = set(outputs) & (set(grid) | set(random))
    if shared:
        raise ValueError(f"output(s) {sorted(shared)} share a name with a swept input: each is one column (and one "
                         "Dataset variable); rename the output or the input")
    reserved = {"case", "error"} & (set(grid) | set(random) | set(outputs))
    if reserved:
        raise ValueError(f"'case' and 'error' are reserved column names, got {sorted(reserved)}")
    spec = SweepSpec(name, function, tuple(outputs), fixed, grid, random, draws, seed, chunk, vectorised, dict(raw))
    if spec.n_cases < 1:
        raise ValueError("the sweep has no cases")
    return spec


def load_spec(path: str | Path) -> SweepSpec:
    """Read a TOML spec; errors name the file."""
    path = Path(path)
    raw = read_toml(path)
    try:
        return spec_from_dict(raw)
    except ValueError as error:
        raise ValueError(f"{path}: {error}") from None


# --------------------------------------------------------------------------
# cases
# --------------------------------------------------------------------------
def _draws(spec: SweepSpec, draw_index: np.ndarray) -> dict[str, np.ndarray]:
    """Random inputs of the draws ``draw_index`` (independent of how cases are chunked)."""
    out = {name: np.empty(draw_index.size) for name in spec.random}
    blocks = draw_index // DRAW_BLOCK
    for block in np.unique(blocks):
        rng = np.random.default_rng(np.random.SeedSequence(spec.seed, spawn_key=(int(block),)))
        where = blocks == block
        offset = draw_index[where] - block * DRAW_BLOCK
        for name, distribution in spec.random.items():  # every input of the block, in spec order
            out[name][where] = distribution.draw(rng, DRAW_BLOCK)[offset]
    return out


def case_inputs(spec: SweepSpec, start: int, stop: int) -> dict[str, np.ndarray]:
    """Swept inputs (SI) of cases ``start .. stop-1``: ``{name: (stop-start,) array}``."""
    if not 0 <= start < stop <= spec.n_cases:
        raise ValueError(f"case range must satisfy 0 <= start < stop <= {spec.n_cases}, got [{start}, {stop})")
    index = np.arange(start, stop, dtype=np.int64)
    point, draw = np.divmod(index, spec.draws)
    inputs = {}
    if spec.grid:
        axes = np.unravel_index(point, spec.grid_shape)
        for (name, values), k in zip(spec.grid.items(), axes):
            inputs[name] = values[k]
    inputs.update(_draws(spec, draw))
    return inputs


def _resolve(path: str) -> Callable:
    module, _, attribute = path.partition(":")
    try:
        target = importlib.import_module(module)
    except ImportError as error:
        raise ValueError(f"function {path!r}: cannot import {module!r} ({error})") from None
    for part in attribute.split("."):
        if not hasattr(target, part):
            raise ValueError(f"function {path!r}: {module!r} has no attribute {attribute!r}")
        target = getattr(target, part)
    if not callable(target):
        raise ValueError(f"function {path!r} is not callable")
    return target


def check_inputs(spec: SweepSpec, function: Callable | None = None) -> None:
    """ValueError when the spec's inputs (fixed, grid, random) cannot be passed to its function: a misspelt or
    missing input name fails here, before any case runs, instead of failing every case with a TypeError.
    Functions without an inspectable signature (some builtins) are not checked."""
    function = _resolve(spec.function) if function is None else function
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return
    names = list(spec.fixed) + list(spec.input_names)
    try:
        signature.bind(**{name: 0.0 for name in names})
    except TypeError as error:
        raise ValueError(f"the inputs of the spec ({', '.join(names) or 'none'}) do not fit {spec.function}"
                         f"{signature}: {error}") from None


_OUTPUT = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?$")


def _output(result, name: str):
    match = _OUTPUT.match(name)
    if not match:
        raise ValueError(f"output {name!r} must be 'name' or 'name[i]'")
    key, index = match.group(1), match.group(2)
    if isinstance(result, dict):
        if key not in result:
            raise KeyError(f"the function's result has no key {key!r}")
        value = result[key]
    else:
        if not hasattr(result, key):
            raise AttributeError(f"the function's result ({type(result).__name__}) has no attribute {key!r}")
        value = getattr(result, key)
    value = np.asarray(value, dtype=float)
    if index is not None:
        value = value[..., int(index)]
    return value


def _one_case(function, fixed, inputs, outputs) -> tuple[list[float], str]:
    try:
        result = function(**fixed, **inputs)
        values = []
        for name in outputs:
            value = _output(result, name)
            if value.size != 1:
                raise ValueError(f"output {name!r} has {value.size} values per case; name one with '{name}[i]'")
            value = float(value.reshape(-1)[0])
            if not math.isfinite(value):
                raise ValueError(f"output {name!r} is not finite ({value!r})")
            values.append(value)
        return values, ""
    except Exception as error:  # a failed case is a recorded result with its reason
        return [math.nan] * len(outputs), f"{type(error).__name__}: {error}"


def run_chunk(raw: dict, start: int, stop: int) -> dict[str, np.ndarray | list]:
    """Compute cases ``start .. stop-1`` of the spec ``raw`` (a dict: it travels to workers).

    Returns columns ``case``, the swept inputs, the outputs (NaN where failed)
    and ``error`` (list of str), and ``compute_s``: the wall time of this call in
    the process that ran it [s] (not stored; :class:`SweepSummary` sums it).
    Vectorised specs call the function once with arrays; when that call raises, the range is halved and each half
    tried again, down to ranges of ``VECTOR_LEAF`` cases that are called one case at a time, so the failing cases
    are named while the others keep the vectorised speed (one failing case in 10,000 costs about 2 log2(10,000)
    vectorised calls and ``VECTOR_LEAF`` single ones, not 10,000 single calls).
    """
    begin = time.perf_counter()
    spec = spec_from_dict(raw)
    function = _resolve(spec.function)
    inputs = case_inputs(spec, start, stop)
    n = stop - start
    columns = {name: np.full(n, np.nan) for name in spec.outputs}
    errors = [""] * n

    def single(lo: int, hi: int) -> None:
        for k in range(lo, hi):
            values, errors[k] = _one_case(function, spec.fixed, {name: float(v[k]) for name, v in inputs.items()},
                                          spec.outputs)
            for name, value in zip(spec.outputs, values):
                columns[name][k] = value

    def vectorised(lo: int, hi: int) -> None:
        try:
            result = function(**spec.fixed, **{name: v[lo:hi] for name, v in inputs.items()})
            values = {name: np.broadcast_to(_output(result, name), (hi - lo,)).astype(float)
                      for name in spec.outputs}
        except Exception:  # halve the range to find the failing cases; name them by single calls
            if hi - lo <= VECTOR_LEAF:
                single(lo, hi)
            else:
                middle = (lo + hi) // 2
                vectorised(lo, middle)
                vectorised(middle, hi)
            return
        for name, value in values.items():
            columns[name][lo:hi] = value
            for k in np.flatnonzero(~np.isfinite(value)):
                errors[lo + k] = errors[lo + k] or f"ValueError: output {name!r} is not finite ({value[k]!r})"

    if spec.vectorised:
        vectorised(0, n)
    else:
        single(0, n)
    for k, error in enumerate(errors):
        if error:
            for name in spec.outputs:
                columns[name][k] = np.nan
    return {"case": np.arange(start, stop, dtype=np.int64), **inputs, **columns, "error": errors,
            "compute_s": time.perf_counter() - begin}


# --------------------------------------------------------------------------
# storage
# --------------------------------------------------------------------------
def _write_part(out_dir: Path, spec: SweepSpec, chunk: dict) -> Path:
    import pyarrow as pa
    import pyarrow.parquet as pq

    start, stop = int(chunk["case"][0]), int(chunk["case"][-1]) + 1
    failed = np.array([bool(e) for e in chunk["error"]])
    arrays = {"case": pa.array(chunk["case"], pa.int64())}
    for name in spec.input_names:
        arrays[name] = pa.array(np.asarray(chunk[name], float), pa.float64())
    for name in spec.outputs:
        arrays[name] = pa.array(np.asarray(chunk[name], float), pa.float64(), mask=failed)  # failed: null, not NaN
    arrays["error"] = pa.array(list(chunk["error"]), pa.string())
    table = pa.table(arrays)
    target = out_dir / f"part-{start:012d}-{stop:012d}.parquet"
    temporary = out_dir / f".{target.name}.{os.getpid()}.tmp"
    pq.write_table(table, temporary)
    os.replace(temporary, target)  # atomic: a killed sweep never leaves half a part
    return target


def _done_ranges(out_dir: Path) -> list[tuple[int, int]]:
    ranges = []
    for path in out_dir.iterdir():
        match = _PART.match(path.name)
        if match:
            ranges.append((int(match.group(1)), int(match.group(2))))
    return sorted(ranges)


def missing_chunks(n_cases: int, done: list[tuple[int, int]], chunk_size: int) -> list[tuple[int, int]]:
    """Case ranges ``[start, stop)`` no part holds, split into chunks of at most ``chunk_size``."""
    covered = np.zeros(n_cases, dtype=bool)
    for start, stop in done:
        covered[start:min(stop, n_cases)] = True
    chunks = []
    index = 0
    while index < n_cases:
        if covered[index]:
            index += 1
            continue
        stop = index
        while stop < n_cases and not covered[stop] and stop - index < chunk_size:
            stop += 1
        chunks.append((index, stop))
        index = stop
    return chunks


def _prepare(out_dir: Path, spec: SweepSpec) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    manifest = out_dir / "sweep.json"
    record = {"name": spec.name, "identity": spec.identity(), "n_cases": spec.n_cases, "spec": spec.source}
    if manifest.exists():
        old = json.loads(manifest.read_text())
        if old.get("identity") != record["identity"]:
            raise ValueError(f"{out_dir} holds another sweep ({old.get('name')!r}, spec {old.get('identity')}); "
                             f"this spec is {record['identity']}: use another --out or delete the directory")
    else:
        manifest.write_text(json.dumps(record, indent=2, default=str))


def read_results(out_dir: str | Path) -> dict[str, np.ndarray]:
    """All parts of a sweep directory as columns sorted by ``case`` (outputs: NaN where failed).

    ``error`` is an object array of str.  Raises ValueError when two parts
    overlap (the directory was written by two runs at once).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    out_dir = Path(out_dir)
    paths = sorted(p for p in out_dir.iterdir() if _PART.match(p.name)) if out_dir.is_dir() else []
    if not paths:
        raise ValueError(f"{out_dir}: no sweep results (part-*.parquet)")
    table = pa.concat_tables([pq.read_table(p) for p in paths])
    columns = {}
    order = np.argsort(table.column("case").to_numpy())
    for name in table.column_names:
        column = table.column(name)
        if name == "error":
            columns[name] = np.array(column.to_pylist(), dtype=object)[order]
        elif name == "case":
            columns[name] = column.to_numpy()[order]
        else:
            columns[name] = column.to_numpy(zero_copy_only=False).astype(float)[order]  # null -> NaN
    if np.any(np.diff(columns["case"]) == 0):
        raise ValueError(f"{out_dir}: parts overlap (case numbers repeat)")
    return columns


# --------------------------------------------------------------------------
# gridded sweeps as an xarray Dataset
# --------------------------------------------------------------------------
def to_dataset(spec: SweepSpec, columns: dict):
    """The results ``columns`` (as :func:`read_results`, any subset of the cases) of a gridded ``spec`` as an
    ``xarray.Dataset``: dims = the grid axes (coordinates: their values, SI) and ``draw`` if the spec draws;
    variables = outputs and random inputs (NaN where not computed or failed), ``error`` (str) and ``done``."""
    import xarray as xr

    if not spec.grid:
        raise ValueError(f"sweep {spec.name!r} has no grid: its results stay a table (read_results)")
    dims = tuple(spec.grid) + (("draw",) if spec.random else ())
    shape = spec.grid_shape + ((spec.draws,) if spec.random else ())
    index = np.asarray(columns["case"], dtype=np.int64)

    def place(values, fill, dtype):
        out = np.full(spec.n_cases, fill, dtype=dtype)
        out[index] = values
        return out.reshape(shape)

    done = place(True, False, bool)
    data = {name: (dims, place(columns[name], np.nan, float)) for name in spec.outputs + tuple(spec.random)}
    data["error"] = (dims, place(np.asarray(columns["error"], dtype=object), "", object))
    data["done"] = (dims, done)
    coords = {name: values for name, values in spec.grid.items()}
    if spec.random:
        coords["draw"] = np.arange(spec.draws)
    attrs = {"name": spec.name, "function": spec.function, "identity": spec.identity(), "n_cases": spec.n_cases,
             "done_cases": int(done.sum()), "failed_cases": int(sum(bool(e) for e in columns["error"])),
             "units": "SI (angles in rad)", "case": "case = C-order index of the grid point * draws + draw"}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _manifest_spec(out_dir: Path) -> SweepSpec:
    manifest = out_dir / "sweep.json"
    if not manifest.exists():
        raise ValueError(f"{out_dir}: no sweep.json (not a sweep directory)")
    return spec_from_dict(json.loads(manifest.read_text())["spec"])


def read_dataset(out_dir: str | Path):
    """The Dataset (:func:`to_dataset`) of a gridded sweep directory, built from its Parquet parts."""
    out_dir = Path(out_dir)
    return to_dataset(_manifest_spec(out_dir), read_results(out_dir))


def write_dataset(out_dir: str | Path, spec: SweepSpec | None = None) -> Path | None:
    """(Re)write ``OUT/results.zarr`` from the parts of a gridded sweep (written aside, then swapped in);
    returns its path, or None when the sweep has no grid or no part yet."""
    import shutil

    out_dir = Path(out_dir)
    spec = _manifest_spec(out_dir) if spec is None else spec
    if not spec.grid or not _done_ranges(out_dir):
        return None
    dataset = to_dataset(spec, read_results(out_dir))
    target = out_dir / DATASET_NAME
    temporary = out_dir / f".{DATASET_NAME}.{os.getpid()}.tmp"
    shutil.rmtree(temporary, ignore_errors=True)
    dataset.to_zarr(temporary, mode="w", consolidated=False)
    old = out_dir / f".{DATASET_NAME}.{os.getpid()}.old"
    if target.exists():
        os.replace(target, old)
    os.replace(temporary, target)
    shutil.rmtree(old, ignore_errors=True)
    return target


# --------------------------------------------------------------------------
# running
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class SweepSummary:
    """What a call of :func:`run_sweep` did: cases in the sweep, already done before, computed now,
    failed (in the whole directory), wall time [s] of this call, and where ("serial", "local:N" or the address)."""

    n_cases: int
    skipped: int
    computed: int
    failed: int
    wall_time_s: float
    where: str
    out_dir: Path
    compute_s: float = 0.0   # sum over the chunks of the time spent computing them, where they ran [s]
    workers: int = 1         # worker threads that computed (1 for serial)
    reasons: tuple = ()      # failed cases by exception type: (type, count, first case, its error), see failure_reasons

    @property
    def throughput(self) -> float:
        """Cases per second computed by this call."""
        return self.computed / self.wall_time_s if self.wall_time_s > 0 else math.inf

    @property
    def utilisation(self) -> float:
        """Share of the workers' time spent computing cases: ``compute_s / (workers wall)``."""
        return self.compute_s / (self.workers * self.wall_time_s) if self.wall_time_s > 0 else 0.0

    @property
    def overhead_per_case(self) -> float:
        """Worker time not spent computing, per case [s]: ``(workers wall - compute_s) / computed``
        (scheduling, transfer, writing parts, idle workers at the start and end, other jobs on the machine)."""
        return (self.workers * self.wall_time_s - self.compute_s) / self.computed if self.computed else 0.0


def _progress_bar(total: int, initial: int, enabled: bool | None, name: str):
    if enabled is None:
        enabled = sys.stderr.isatty()  # only on a terminal: logs and CI stay clean
    if not enabled:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, initial=initial, desc=name, unit="case", file=sys.stderr)


def run_sweep(spec: SweepSpec, out_dir: str | Path, *, scheduler: str | None = None, workers: int = 2,
              serial: bool = False, client=None, progress: bool | None = None,
              max_chunks: int | None = None) -> SweepSummary:
    """Run the cases of ``spec`` that ``out_dir`` does not hold yet.

    ``serial`` computes in this process (no dask); otherwise ``client`` (a
    ``dask.distributed.Client``), else a new client of ``scheduler`` (an
    address such as ``tcp://127.0.0.1:8786``), else a ``LocalCluster`` of
    ``workers`` single-threaded worker processes.  ``max_chunks`` stops after
    that many chunks (a partial run; the rest is computed by the next call).
    ``progress``: None shows a bar only when stderr is a terminal.
    """
    out_dir = Path(out_dir)
    check_inputs(spec, _resolve(spec.function))  # fail early, in the client, before the directory is made
    _prepare(out_dir, spec)
    done = _done_ranges(out_dir)
    chunks = missing_chunks(spec.n_cases, done, spec.chunk_size)
    skipped = spec.n_cases - sum(stop - start for start, stop in chunks)
    if max_chunks is not None:
        chunks = chunks[:max_chunks]
    bar = _progress_bar(spec.n_cases, skipped, progress, spec.name)
    start_time = time.perf_counter()
    computed = 0
    raw = spec.source
    own_client = None
    last_dataset = [time.perf_counter()]

    compute_s, threads = 0.0, 1

    def written(chunk_cases: int, chunk_compute_s: float) -> None:
        nonlocal computed, compute_s
        computed += chunk_cases
        compute_s += chunk_compute_s
        if bar is not None:
            bar.update(chunk_cases)
        if spec.grid and time.perf_counter() - last_dataset[0] >= DATASET_EVERY_S:
            write_dataset(out_dir, spec)
            last_dataset[0] = time.perf_counter()

    where = "serial" if serial else "nothing left to compute" if not chunks else ""
    try:
        if serial:
            for start, stop in chunks:
                chunk = run_chunk(raw, start, stop)
                _write_part(out_dir, spec, chunk)
                written(stop - start, chunk["compute_s"])
        elif chunks:
            import dask
            from dask.distributed import Client, LocalCluster, as_completed

            if client is None:
                if scheduler:
                    own_client = Client(scheduler)
                    where = scheduler
                else:
                    with dask.config.set(LOCAL_CLUSTER_CONFIG):
                        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                               dashboard_address="127.0.0.1:0", host="127.0.0.1")
                    own_client = Client(cluster)
                    where = f"local:{workers}"
                client = own_client
            else:
                where = str(client.scheduler.address)
            # a bounded window of tasks in flight: a sweep of millions of chunks does not flood the scheduler
            threads = sum(client.nthreads().values())
            window = max(IN_FLIGHT_MIN, IN_FLIGHT_PER_THREAD * threads)
            pending = iter(chunks)
            running = as_completed()
            for start, stop in itertools.islice(pending, window):
                running.add(client.submit(run_chunk, raw, start, stop, pure=False))
            for future in running:
                chunk = future.result()  # a task that itself fails (not a case) stops the sweep; parts stay
                _write_part(out_dir, spec, chunk)
                written(len(chunk["case"]), chunk["compute_s"])
                future.release()
                following = next(pending, None)
                if following is not None:
                    running.add(client.submit(run_chunk, raw, *following, pure=False))
    finally:
        if bar is not None:
            bar.close()
        if computed or (spec.grid and not (out_dir / DATASET_NAME).exists()):
            write_dataset(out_dir, spec)  # also after an interruption: the Dataset holds what the parts hold
        if own_client is not None:
            cluster = own_client.cluster
            own_client.close()
            if cluster is not None:
                cluster.close()
    wall = time.perf_counter() - start_time
    failed, reasons = 0, ()
    if _done_ranges(out_dir):
        columns = read_results(out_dir)
        failed = int(sum(bool(e) for e in columns["error"]))
        reasons = failure_reasons(columns)
    return SweepSummary(spec.n_cases, skipped, computed, failed, wall, where, out_dir, compute_s, threads, reasons)


def failure_reasons(columns: dict) -> tuple[tuple[str, int, int, str], ...]:
    """The failed cases of :func:`read_results` columns grouped by exception type, most frequent first:
    ``(type, count, first case, its error text)``."""
    groups: dict[str, list] = {}
    for case, error in zip(columns["case"], columns["error"]):
        if error:
            kind = error.split(":", 1)[0]
            groups.setdefault(kind, [0, int(case), error])[0] += 1
    return tuple((kind, count, case, text) for kind, (count, case, text)
                 in sorted(groups.items(), key=lambda item: (-item[1][0], item[1][1])))


def main(args) -> int:
    """``ballbench sweep`` (registered in validation/cli.py)."""
    try:
        spec = load_spec(args.spec)
        if args.chunk_size is not None:
            if args.chunk_size < 1:
                raise ValueError(f"--chunk-size must be >= 1, got {args.chunk_size}")
            spec = spec_from_dict({**spec.source, "chunk_size": args.chunk_size})
        if args.workers < 1:
            raise ValueError(f"--workers must be >= 1, got {args.workers}")
        out_dir = Path(args.out) if args.out else Path("ballbench-sweeps") / spec.name
        progress = False if args.no_progress else None
        summary = run_sweep(spec, out_dir, scheduler=args.scheduler, workers=args.workers, serial=args.serial,
                            progress=progress)
    except ValueError as error:
        raise SystemExit(f"ballbench sweep: {error}") from None
    who = "this process" if args.serial else "workers"
    busy = (f"; {who} computing {100 * summary.utilisation:.0f} % of the time, overhead "
            f"{1e3 * summary.overhead_per_case:.3f} ms per case" if summary.computed else "")
    print(f"{spec.name}: {summary.n_cases} cases, {summary.skipped} already done, {summary.computed} computed in "
          f"{summary.wall_time_s:.2f} s ({summary.throughput:.1f} cases/s, {summary.where}), "
          f"{summary.failed} failed{busy}; results: {out_dir}/part-*.parquet"
          + (f", gridded: {out_dir / DATASET_NAME} (xarray Dataset)" if spec.grid else ""))
    for kind, count, case, text in summary.reasons:
        print(f"  {count} failed with {kind}; the first, case {case}: {text}")
    if summary.n_cases and summary.failed == summary.n_cases:
        print(f"ballbench sweep: every case failed; see the reasons above and the spec {args.spec}", file=sys.stderr)
        return 1
    return 0


def add_parser(sub) -> None:
    """Register ``ballbench sweep`` on the CLI's sub-parsers."""
    p = sub.add_parser("sweep", help="run a parameter sweep (TOML spec) on dask; resumable Parquet output")
    p.add_argument("spec", help="sweep spec (TOML, docs/sweeps.md)")
    p.add_argument("--out", help="output directory (default: ./ballbench-sweeps/<name>)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", help="address of a running dask scheduler, e.g. tcp://127.0.0.1:8786")
    where.add_argument("--serial", action="store_true", help="compute in this process, no dask")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    p.add_argument("--chunk-size", type=int, help="cases per task (overrides the spec)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar (default: bar only on a terminal)")
    p.set_defaults(func=main)
