"""A sweep spec: parsing and checking (``ballbench sweep SPEC.toml``, docs/sweeps.md).

A spec names a model function, its fixed inputs, the swept ones (grids and
seeded random draws) and the outputs to keep; :func:`spec_from_dict` turns the
TOML table into a :class:`SweepSpec` with every number in SI units (units
through :mod:`ballbench.validation.cases.units`, the parser case files and calibrate specs share), or raises
ValueError naming the key.
"""
from __future__ import annotations

import hashlib
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ballbench.validation.cases.toml_files import read_toml
from ballbench.validation.cases.units import DIMENSIONLESS, dimension_of, quantity, si_factor, split

DISTRIBUTIONS = {"normal": ("mean", "sigma"), "uniform": ("low", "high"), "lognormal": ("mean", "sigma")}
_TOP_KEYS = {"name", "function", "vectorised", "chunk_size", "outputs", "fixed", "grid", "random", "description"}


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
        factor = si_factor(f"fixed.{name}", value.get("unit", ""))
        inner = value["value"]
        if isinstance(inner, list):
            return [_number(f"fixed.{name}.value", v) * factor for v in inner]
        return _number(f"fixed.{name}.value", inner) * factor
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"fixed.{name} must be a finite number, got {value!r}")
    parts = split(value) if isinstance(value, str) else None
    if parts and parts[1]:  # "3.175 mm": a quantity, converted to SI
        return quantity(value, dimension_of(parts[1], f"fixed.{name}"), f"fixed.{name}")
    return value  # numbers, other strings, booleans and lists pass as they are


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
    factor = si_factor(where, axis.get("unit", ""))
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
    factor = si_factor(where, table.get("unit", ""))
    if kind == "lognormal" and table.get("unit", "") not in DIMENSIONLESS:
        raise ValueError(f"{where}: a lognormal input is dimensionless (its mean/sigma are of log x); drop 'unit'")
    return Distribution(kind, a, b, factor)


def spec_from_dict(raw: dict) -> SweepSpec:  # noqa: C901 - one branch per key of the sweep spec, each naming its error
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
