"""The ``ballbench`` command.

    ballbench scenes                       list scenes with a one-line description
    ballbench validate [SCENE ...] [--out DIR] [--quick | --fine] [--calibration FILE]
    ballbench show SCENE [--out DIR]       PNG screenshots of an FE scene's fields
    ballbench calibrate SPEC.toml [--out FILE]   fit constants with intervals (docs/calibration.md)
    ballbench sweep SPEC.toml [--scheduler ADDRESS | --serial]   parameter sweep on dask (docs/sweeps.md)
"""
from __future__ import annotations

import argparse
import fnmatch
import sys
from pathlib import Path

from ballbench.validation.scene import registry


def _select(names: list[str]):
    scenes = registry()
    if not names:
        return [s for s in scenes.values() if s.default]
    chosen = []
    for pattern in names:
        matched = [s for n, s in scenes.items() if fnmatch.fnmatchcase(n, pattern)]
        if not matched:
            raise SystemExit(f"ballbench: no scene matches {pattern!r}; `ballbench scenes` lists them")
        chosen += [s for s in matched if s not in chosen]
    return chosen


def _cmd_scenes(args) -> int:
    scenes = registry()
    width = max((len(n) for n in scenes), default=0)
    for name in sorted(scenes):
        s = scenes[name]
        flag = "" if s.default else "  [not in default run]"
        print(f"{name:<{width}}  {s.description}{flag}")
    return 0


def _cmd_validate(args) -> int:
    from ballbench.validation.report import write_report
    from ballbench.validation.runner import run_scenes

    fidelity = "quick" if args.quick else "fine" if args.fine else "default"
    scenes = sorted(_select(args.scenes), key=lambda s: s.name)
    out_dir = Path(args.out)
    results = run_scenes(scenes, fidelity, out_dir, show_progress=not args.no_progress)
    paths = write_report(results, out_dir, fidelity)
    failed = [r.name for r in results if not r.passed]
    print(f"{len(results) - len(failed)} of {len(results)} scenes passed; report: {paths['markdown']}")
    if failed:
        print("failed: " + ", ".join(failed))
        return 1
    return 0


def _cmd_show(args) -> int:
    scenes = registry()
    if args.scene not in scenes:
        raise SystemExit(f"ballbench: no scene {args.scene!r}; `ballbench scenes` lists them")
    from ballbench.validation import show

    paths = show.show(args.scene, Path(args.out), fidelity="quick" if args.quick else "default")
    for p in paths:
        print(p)
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="ballbench", description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("scenes", help="list scenes")
    p.set_defaults(func=_cmd_scenes)

    p = sub.add_parser("validate", help="run scenes and write the report")
    p.add_argument("scenes", nargs="*", help="scene names or glob patterns (default: all default scenes)")
    p.add_argument("--out", default="ballbench-report", help="output directory (default: ./ballbench-report)")
    level = p.add_mutually_exclusive_group()
    level.add_argument("--quick", action="store_true", help="coarsest fidelity of each scene (CI)")
    level.add_argument("--fine", action="store_true", help="finest fidelity (slow FE levels)")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.set_defaults(func=_cmd_validate)
    from ballbench.validation import calibrate  # issue 13: --calibration FILE, ballbench calibrate

    calibrate.add_validate_option(p)

    p = sub.add_parser("show", help="PNG screenshots of an FE scene's contact fields")
    p.add_argument("scene")
    p.add_argument("--out", default="ballbench-report", help="output directory")
    p.add_argument("--quick", action="store_true", help="coarsest mesh level")
    p.set_defaults(func=_cmd_show)

    from ballbench.validation import sweep  # issue 13: ballbench sweep (validation/sweep.py)

    sweep.add_parser(sub)
    calibrate.add_parser(sub)

    args = parser.parse_args(argv)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
