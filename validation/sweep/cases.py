"""The cases of a sweep and their computation in any process (a dask worker or this one).

Cases are numbered ``0 .. n_cases-1``; case ``i`` is grid point ``i // draws``
(C order over the grid axes in the order of the spec) with random draw
``i % draws`` (the same draws at every grid point: common random numbers).
Random draws come from fixed blocks of :data:`DRAW_BLOCK` draws, block ``k``
seeded by ``SeedSequence(seed, spawn_key=(k,))``: a case's inputs depend only on
the spec and its number, never on the chunking or on the worker that ran it.
A failed case is a result: its outputs are NaN and ``error`` holds
``"ExceptionType: message"``; a non-finite output is a failure too.
"""
from __future__ import annotations

import difflib
import importlib
import inspect
import math
import re
import time
from typing import Callable

import numpy as np

from ballbench.lowmodel import checks
from ballbench.validation.sweep.spec import SweepSpec, spec_from_dict

DRAW_BLOCK = 4096  # random draws per seeded block (fixed: changing it changes every draw)
VECTOR_LEAF = 8  # a vectorised call that raises is halved down to this many cases, then called case by case
# modules of case functions that moved: old module -> new module.  A spec that names the old one is told the new
# path (no alias module keeps the old one importable; docs/sweeps.md, "Case functions")
MOVED_MODULES = {"ballbench.validation.sweep_cases": "ballbench.validation.sweep.functions"}


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


def resolve_function(path: str) -> Callable:
    """The function that ``path`` (``"package.module:function"``) names; ValueError when it cannot be had."""
    module, _, attribute = path.partition(":")
    if module in MOVED_MODULES:
        raise ValueError(f"function {path!r}: the module {module!r} moved to {MOVED_MODULES[module]!r}; write "
                         f"function = \"{MOVED_MODULES[module]}:{attribute}\"")
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
    function = resolve_function(spec.function) if function is None else function
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
    forwarded = getattr(function, "keywords", None)  # the names a function's **keywords pass on (sweep.functions)
    own = {p.name for p in signature.parameters.values() if p.kind is not p.VAR_KEYWORD}
    if forwarded is not None:
        for name in names:
            if name not in own and name not in forwarded:
                close = difflib.get_close_matches(name, sorted(own | set(forwarded)), n=2, cutoff=0.6)
                hint = f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""
                raise ValueError(f"input {name!r} is not a parameter of {spec.function}{hint}; it takes "
                                 f"{', '.join(sorted((own - {'calibration'}) | set(forwarded)))}")
    check_values(spec)


def _values(spec: SweepSpec, name: str) -> np.ndarray | None:
    """Every value the spec gives input ``name`` (SI): the fixed one, the grid axis, or the bounds of a uniform
    draw and the mean of a normal one; None for a non-numeric input."""
    if name in spec.fixed:
        value = spec.fixed[name]
        if isinstance(value, bool) or not isinstance(value, (int, float, list)):
            return None
        try:
            return np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            return None
    if name in spec.grid:
        return np.asarray(spec.grid[name], dtype=float)
    distribution = spec.random.get(name)
    if distribution is None or distribution.kind == "lognormal":
        return None
    if distribution.kind == "uniform":
        return np.array([distribution.first, distribution.second]) * distribution.factor
    return np.array([distribution.first]) * distribution.factor


def check_values(spec: SweepSpec) -> None:
    """ValueError naming the input for a value no case can use, before any case runs: NaN, a conformity outside
    (0.5, 1), a load that is not > 0, a length or angle outside its plausible range (a radius in mm, an angle in
    degrees given as a bare number; lowmodel.checks.PLAUSIBLE), for the inputs of the names the models share."""
    for name in list(spec.fixed) + list(spec.input_names):
        values = _values(spec, name)
        if values is None:
            continue
        where = ("fixed." if name in spec.fixed else "grid." if name in spec.grid else "random.inputs.") + name
        checks.finite(where, values)
        kind = INPUT_KINDS.get(name)
        if kind == "conformity":
            checks.conformity(where, values)
        elif kind == "load":
            checks.positive(where, values, "N")
        elif kind == "coefficient":
            checks.non_negative(where, values)
        elif kind is not None:
            checks.plausible(where, values, kind)


# input names the models share -> what their values must be (check_values)
INPUT_KINDS = {"ball_radius": "ball_radius", "pitch_radius": "pitch_radius", "lead": "lead", "oversize": "oversize",
               "youngs_modulus": "youngs_modulus", "conformity": "conformity", "vertical_force": "load",
               "normal_load": "load", "axial_load": "load", "force": "load", "friction_coefficient": "coefficient",
               "theta": "deviation", "top_tr": "deviation", "top_tl": "deviation",
               **{f"d{ball}_{contact}": "deviation" for ball in (1, 2) for contact in ("bl", "br", "tr", "tl")}}


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
    the process that ran it [s] (not stored; :class:`~.execution.SweepSummary` sums it).
    Vectorised specs call the function once with arrays; when that call raises, the range is halved and each half
    tried again, down to ranges of ``VECTOR_LEAF`` cases that are called one case at a time, so the failing cases
    are named while the others keep the vectorised speed (one failing case in 10,000 costs about 2 log2(10,000)
    vectorised calls and ``VECTOR_LEAF`` single ones, not 10,000 single calls).
    """
    begin = time.perf_counter()
    spec = spec_from_dict(raw)
    function = resolve_function(spec.function)
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
