"""``ballbench sweep SPEC.toml``: the command (registered in validation/cli.py, docs/sweeps.md)."""
from __future__ import annotations

import sys
from pathlib import Path

from ballbench.validation.sweep.cases import check_inputs
from ballbench.validation.sweep.execution import run_sweep
from ballbench.validation.sweep.spec import load_spec, spec_from_dict
from ballbench.validation.sweep.storage import DATASET_NAME
from ballbench.validation.usage import UsageError, check_writable_folder


def main(args) -> int:
    """``ballbench sweep`` (registered in validation/cli.py): a mistake in the spec or the options is a wrong use
    (UsageError, exit 2) found before the output folder is made; exit 1 when every case failed."""
    try:
        spec = load_spec(args.spec)
        if args.chunk_size is not None:
            if args.chunk_size < 1:
                raise ValueError(f"--chunk-size must be >= 1, got {args.chunk_size}")
            spec = spec_from_dict({**spec.source, "chunk_size": args.chunk_size})
        if args.workers < 1:
            raise ValueError(f"--workers must be >= 1, got {args.workers}")
        check_inputs(spec)  # names and values of the inputs, before the output folder exists
    except ValueError as error:
        raise UsageError(f"sweep: {error}") from None
    out_dir = Path(args.out) if args.out else Path("ballbench-sweeps") / spec.name
    check_writable_folder(out_dir, "--out")
    progress = False if args.no_progress else None
    try:
        summary = run_sweep(spec, out_dir, scheduler=args.scheduler, workers=args.workers, serial=args.serial,
                            progress=progress)
    except ValueError as error:  # e.g. a different spec in the same folder
        raise UsageError(f"sweep: {error}") from None
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
