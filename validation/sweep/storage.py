"""Where a sweep's results live: Parquet parts, the manifest, and the xarray Dataset (Zarr) of a gridded sweep.

Every finished chunk is written at once to ``OUT/part-<start>-<stop>.parquet``
(written to a temporary name and renamed, so a killed sweep never leaves a half
file); a restarted sweep reads the part names and computes only the cases no
part holds.  ``OUT/sweep.json`` keeps the spec; a restart with a different
spec (other than ``chunk_size``) is refused.  Each row holds ``case``, the
swept inputs (SI units), the outputs (null where the case failed) and
``error``.

Gridded sweeps (a ``[grid]`` table) also land in ``OUT/results.zarr`` (Zarr
format 3): one dimension per grid axis with the axis values as coordinates,
plus ``draw`` when the spec has random draws; data variables: the outputs, the
random inputs, ``error`` (str) and ``done`` (bool).  The Parquet parts stay the
record a restart resumes from (atomic per chunk); :func:`read_dataset` builds
the same Dataset from them.
"""
from __future__ import annotations

import json
import os
import re
import shutil
from pathlib import Path

import numpy as np

from ballbench.validation.sweep.spec import SweepSpec, spec_from_dict

DATASET_NAME = "results.zarr"  # xarray Dataset of a gridded sweep (Zarr store)
_PART = re.compile(r"^part-(\d{12})-(\d{12})\.parquet$")


def write_part(out_dir: Path, spec: SweepSpec, chunk: dict) -> Path:
    """Write the computed ``chunk`` (:func:`~.cases.run_chunk`) as one Parquet part, atomically."""
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


def done_ranges(out_dir: Path) -> list[tuple[int, int]]:
    """The case ranges ``[start, stop)`` of the parts in ``out_dir``, sorted."""
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


def prepare(out_dir: Path, spec: SweepSpec) -> None:
    """Make ``out_dir`` and its manifest ``sweep.json``; ValueError when it holds another sweep."""
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


def manifest_spec(out_dir: Path) -> SweepSpec:
    """The spec that ``out_dir/sweep.json`` keeps."""
    manifest = out_dir / "sweep.json"
    if not manifest.exists():
        raise ValueError(f"{out_dir}: no sweep.json (not a sweep directory)")
    return spec_from_dict(json.loads(manifest.read_text())["spec"])


def read_dataset(out_dir: str | Path):
    """The Dataset (:func:`to_dataset`) of a gridded sweep directory, built from its Parquet parts."""
    out_dir = Path(out_dir)
    return to_dataset(manifest_spec(out_dir), read_results(out_dir))


def write_dataset(out_dir: str | Path, spec: SweepSpec | None = None) -> Path | None:
    """(Re)write ``OUT/results.zarr`` from the parts of a gridded sweep (written aside, then swapped in);
    returns its path, or None when the sweep has no grid or no part yet."""
    out_dir = Path(out_dir)
    spec = manifest_spec(out_dir) if spec is None else spec
    if not spec.grid or not done_ranges(out_dir):
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
