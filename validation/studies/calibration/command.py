"""The ``ballbench calibrate SPEC`` command and the ``--calibration FILE`` option of ``ballbench validate``
(registered in validation/cli.py; docs/calibration.md)."""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from ballbench.lowmodel import calibration as cal
from ballbench.validation.cases.toml_files import read_toml
from ballbench.validation.studies.calibration.spec import check_spec, run_spec
from ballbench.validation.usage import EXIT_FAILED, UsageError, check_writable_file

__all__ = ["CALIBRATION_ENV", "active_calibration", "add_validate_option", "main", "add_parser"]

CALIBRATION_ENV = "BALLBENCH_CALIBRATION"  # set by `ballbench validate --calibration FILE`


def active_calibration() -> cal.Calibration | None:
    """The calibration given to ``ballbench validate --calibration FILE`` (or ``$BALLBENCH_CALIBRATION``)."""
    path = os.environ.get(CALIBRATION_ENV)
    return cal.load(path) if path else None


def _calibration_file(value: str) -> str:
    try:
        cal.load(value)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    os.environ[CALIBRATION_ENV] = str(Path(value).resolve())  # read by scenes through active_calibration()
    return value


def add_validate_option(parser) -> None:
    """``--calibration FILE`` on ``ballbench validate``: scenes that use calibrated constants load this file."""
    parser.add_argument("--calibration", type=_calibration_file, metavar="FILE",
                        help="calibration file of `ballbench calibrate` used by the scenes that take constants")


def main(args) -> int:
    """``ballbench calibrate SPEC``: the spec and the output file are checked before any fit (UsageError, exit 2);
    a fit that fails is exit 1."""
    spec_path = Path(args.spec)
    try:
        spec = read_toml(spec_path)
        check_spec(spec, spec_path)
    except ValueError as error:
        raise UsageError(f"calibrate: {error}") from None
    target = Path(args.out) if args.out else spec_path.parent / spec.get("output", "calibration.json")
    check_writable_file(target, "--out" if args.out else "output")
    try:
        run_spec(spec_path, args.out)
    except ValueError as error:
        print(f"ballbench calibrate: {error}", file=sys.stderr)
        return EXIT_FAILED
    return 0


def add_parser(sub) -> None:
    p = sub.add_parser("calibrate", help="fit constants (Psi, C, C_b, mu, k_f) with intervals; write a calibration")
    p.add_argument("spec", help="calibration spec (TOML, docs/calibration.md)")
    p.add_argument("--out", help="calibration file to write, relative to the current folder (default: the "
                                 "spec's 'output', relative to the spec's folder)")
    p.set_defaults(func=main)
