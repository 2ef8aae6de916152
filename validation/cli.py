"""The ``ballbench`` command line.

Exit codes: 0 every scene passed (known gaps and findings allowed: a model outside
its declared accuracy on a case's own geometry), 1 a check failed or a scene raised,
2 wrong use (one line on stderr naming the problem), 130 interrupted by Ctrl-C (a
partial report is written beside the report folder, which stays untouched).

A run writes its report into a temporary folder beside ``--out`` and puts it in place only when complete; it
removes only the files an earlier report wrote (validation.report.folder, docs/validation.md "The report folder").
"""
from __future__ import annotations

import argparse
import difflib
import fnmatch
import os
import sys
import time
from pathlib import Path

from ballbench import __version__
from ballbench.validation import sweep
from ballbench.validation.cases.case_file import KINDS as CASE_KINDS
from ballbench.validation.scene import registry
from ballbench.validation.studies.calibration import command as calibrate_command
from ballbench.validation.ladder.rungs import RUNGS
from ballbench.validation import ladder, runner, show
from ballbench.validation.cases import case_file
from ballbench.validation import report_folder
from ballbench.validation.interrupt import Interrupt, kept_on_error
from ballbench.validation.show import can_show
from ballbench.validation.show import drawable as drawable_scenes

from ballbench.validation.usage import EXIT_FAILED, EXIT_INTERRUPTED, EXIT_OK, EXIT_USAGE, UsageError

__all__ = ["main", "build_parser", "UsageError", "EXIT_OK", "EXIT_FAILED", "EXIT_USAGE", "EXIT_INTERRUPTED"]

MARKER = report_folder.MARKER  # the manifest of every report folder: a re-run removes only the files it lists
DEFAULT_OUT = "ballbench-report"  # the report folder of registered scenes; a case file's is DEFAULT_OUT-<stem>

DESCRIPTION = """Validate low-order friction models of ball bearings and ball screws against
finite-element analysis and the numbers the source papers publish."""

EPILOG = """examples:
  ballbench scenes                      list the scenes with their kind and rough cost
  ballbench validate                    run every default scene ('ballbench scenes' states the cost)
  ballbench validate --fast             a first look: the scenes that are not FE and cost at most 30 s each
  ballbench validate 'lin2019-*'        scenes by name or pattern
  ballbench show fe-hertz-groove-056    pictures of an FE scene's saved fields
  ballbench init linear-guide > g.toml  a commented case file of one's own bearing (docs/cases.md)
  ballbench validate g.toml --quick     the validation ladder on that case into ./ballbench-report-g
  ballbench show g.toml                 its pictures, from the fields that run saved (--solve to solve them)

exit codes: 0 passed (known gaps and findings allowed), 1 a check failed, 2 wrong use, 130 interrupted"""


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line instead of argparse's usage block
        raise UsageError(f"{message} (see '{self.prog} --help')")


FAST_COST_S = 30.0  # --fast keeps the scenes that are not FE and cost at most this [s] at the default fidelity


def _is_fast(scene) -> bool:
    return scene.kind != "FE" and scene.cost_s <= FAST_COST_S


def _is_case_file(name: str) -> bool:
    return name.endswith(".toml") or (Path(name).is_file() and not any(c in name for c in "*?["))


def _load_case(name: str):
    try:
        return case_file.load(name)
    except case_file.CaseFileError as error:
        raise UsageError(str(error)) from None


def _case_scenes(names: list[str], top: str, deadline: float | None):
    """The generated scenes of the case files among ``names`` (validation.ladder); one stem per file."""
    chosen, stems = [], {}
    for name in names:
        stem = ladder.slug(name)
        if stem in stems and stems[stem] != name:
            raise UsageError(f"case files {stems[stem]} and {name} give the same scene names ({stem}-...); "
                             "rename one")
        stems[stem] = name
        chosen += ladder.case_scenes(_load_case(name), stem, top=top, deadline=deadline)
    return chosen


def _limits(names: list[str], top: str) -> list[str]:
    """What the case files among ``names`` say before any work about their models' limits (ladder.limits):
    a ball screw's preload loss against its axial load, the scenes that may not apply."""
    lines = []
    for name in names:
        if _is_case_file(name):
            lines += [f"{name}: {line}" for line in ladder.limits(_load_case(name), ladder.slug(name), top)]
    return lines


def _select(names: list[str], fast: bool = False, top: str = "FE-informed", deadline: float | None = None):
    files = [n for n in names if _is_case_file(n)]
    names = [n for n in names if n not in files]
    generated = _case_scenes(files, top, deadline) if files else []
    if files and not names:
        if fast:
            generated = [s for s in generated if _is_fast(s)]
        return generated
    scenes = registry()
    if not names:
        chosen = [s for s in scenes.values() if s.default]
    else:
        chosen = []
        for pattern in names:
            matched = [s for n, s in scenes.items() if fnmatch.fnmatchcase(n, pattern)]
            if not matched:
                raise UsageError(f"no scene matches {pattern!r}{_did_you_mean(pattern, scenes)}; "
                                 "'ballbench scenes' lists them")
            chosen += [s for s in matched if s not in chosen]
    if fast:
        chosen = [s for s in chosen if _is_fast(s)]
        if not chosen:
            raise UsageError(f"--fast leaves no scene: every selected scene is an FE scene or costs over "
                             f"{FAST_COST_S:.0f} s")
    return sorted(chosen, key=lambda s: s.name)


def _did_you_mean(name: str, names) -> str:
    """``" (did you mean 'x' or 'y'?)"`` for the closest scene names to a misspelt one, else ``""``."""
    close = difflib.get_close_matches(name, sorted(names), n=3, cutoff=0.6)
    return f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""


def _fmt_cost(seconds: float) -> str:
    if seconds < 1.0:
        return "< 1 s"
    if seconds < 90:
        return f"~{seconds:.0f} s"
    return f"~{seconds / 60:.1f} min"


def _cmd_scenes(args) -> int:  # noqa: ARG001 - every command takes the parsed arguments
    scenes = registry()
    width = max((len(n) for n in scenes), default=0)
    print(f"{'scene':<{width}}  {'kind':<10}  {'cost':>8}  {'default level':<22}  description")
    for name in sorted(scenes):
        s = scenes[name]
        flag = "" if s.default else "  [not in the default run]"
        print(f"{name:<{width}}  {s.kind:<10}  {_fmt_cost(s.cost_s):>8}  {(s.level or '-'):<22}  "
              f"{s.description}{flag}")
    default = [s for s in scenes.values() if s.default]
    fast = [s for s in default if _is_fast(s)]
    print(f"\ndefault run: {len(default)} scenes, {_fmt_cost(sum(s.cost_s for s in default))}; "
          f"--fast: {len(fast)} scenes, {_fmt_cost(sum(s.cost_s for s in fast))} "
          "(costs at the default fidelity on an idle 2-core machine; a loaded machine takes longer)")
    return EXIT_OK


def _default_out(names: list[str]) -> Path:
    """The report folder without --out: ``ballbench-report-<stem>`` for one case file alone, so that every case
    file keeps its own report; ``ballbench-report`` for registered scenes and for several case files in one run."""
    files = [n for n in names if _is_case_file(n)]
    if files and len(set(files)) == len(names) == 1:
        return Path(f"{DEFAULT_OUT}-{ladder.slug(files[0])}")
    return Path(DEFAULT_OUT)


def _check_out_dir(out: Path) -> None:
    """Refuse an --out that cannot hold a report, before any work is done."""
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out} is an existing file, not a folder; choose a folder")
    if out.is_dir() and Path.cwd().resolve().is_relative_to(out.resolve()):  # the report is replaced by a rename
        raise UsageError(f"--out {out} is the current folder or holds it; choose a folder inside it")
    if out.is_dir() and any(out.iterdir()) and not report_folder.is_report(out):
        raise UsageError(f"--out {out} is a non-empty folder that is not a ballbench report (no {MARKER}); "
                         "choose a new or empty folder")


def _check_file_target(path: Path, option: str) -> None:
    if path.is_dir():
        raise UsageError(f"{option} {path} is a folder; give a file name")
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        raise UsageError(f"{option} {path}: folder {parent} does not exist")
    if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise UsageError(f"cannot write {option} {path}: permission denied")


def _cmd_validate(args) -> int:
    from ballbench.validation.report import count, failure_lines, status_word, write_report
    from ballbench.validation.report.rows import memory_lines, passing_lines
    fidelity = "quick" if args.quick else "fine" if args.fine else "default"
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be at least 1, got {args.workers}")
    if args.workers is not None and args.scheduler:
        raise UsageError("give --workers (a local cluster) or --scheduler (an existing one), not both")
    if args.budget is not None and not args.budget > 0:
        raise UsageError(f"--budget must be a wall time > 0 s, got {args.budget:g}")
    deadline = time.monotonic() + args.budget if args.budget is not None else None
    if not any(_is_case_file(n) for n in args.scenes) and (args.levels is not None or deadline is not None):
        raise UsageError("--levels and --budget apply to case files (ballbench validate my_guide.toml --levels BEM)")
    scenes = _select(args.scenes, args.fast, args.levels or RUNGS[-1], deadline)
    out_dir = Path(args.out) if args.out is not None else _default_out(args.scenes)
    if out_dir.is_symlink():  # the report replaces the folder the link names, not the link
        out_dir = out_dir.resolve()
    _check_out_dir(out_dir)
    junit = Path(args.junit) if args.junit else None
    if junit is not None:
        _check_file_target(junit, "--junit")
    temp = report_folder.make_temporary(out_dir)
    show_progress = sys.stderr.isatty() and not args.no_progress
    progress_lines = not sys.stderr.isatty() and not args.no_progress  # piped: one line per step
    options = dict(strict=args.strict, strict_time=args.strict_time)

    def on_result(result):
        status = result.status(**options)
        print(f"{status_word(status)} {result.name} ({result.wall_time_s:.1f} s)"
              + (f": {result.error}" if result.error else ""), file=sys.stderr, flush=True)
        for line in failure_lines(result, **options):
            print(line, file=sys.stderr)
        traceback = [a for a in result.artifacts if a.endswith("error.txt")]
        if traceback:
            print(f"  traceback: {out_dir / traceback[0]}", file=sys.stderr)
        for line in passing_lines(result, status) + memory_lines(result, strict_time=args.strict_time):
            print(line, file=sys.stderr)

    print(f"ballbench: {count(len(scenes), 'scene')} at fidelity {fidelity} into {out_dir}", file=sys.stderr,
          flush=True)
    for line in _limits(args.scenes, args.levels or RUNGS[-1]):
        print(f"ballbench: {line}", file=sys.stderr, flush=True)
    with Interrupt(temp, out_dir) as interrupt, kept_on_error(temp, out_dir):
        if args.workers is not None or args.scheduler:
            where = args.scheduler or f"a local cluster of {args.workers} workers"
            print(f"ballbench: scenes as dask.distributed tasks on {where}", file=sys.stderr, flush=True)
            results, stopped = runner.run_scenes_distributed(scenes, fidelity, temp, workers=args.workers or 2,
                                                             scheduler=args.scheduler, on_result=on_result,
                                                             should_stop=lambda: interrupt.requested)
        else:
            results, stopped = runner.run_scenes(scenes, fidelity, temp, show_progress=show_progress,
                                                 on_result=on_result, should_stop=lambda: interrupt.requested,
                                                 progress_lines=progress_lines)
        done = {r.name for r in results if not r.interrupted}
        not_run = [s.name for s in scenes if s.name not in done]
        results = [r for r in results if not r.interrupted]
        paths = write_report(results, temp, fidelity, not_run=not_run if stopped else (), junit=junit, **options)
        report_folder.write_manifest(temp)
        interrupt.finish()  # a second Ctrl-C from here waits for the few renames
        final = report_folder.put_partial(temp, out_dir) if stopped else out_dir
        carried, aside = ([], None) if stopped else report_folder.replace(temp, out_dir)
    paths = {k: final / p.relative_to(temp) if p.is_relative_to(temp) else p for k, p in paths.items()}
    report_folder.say_kept(out_dir, carried, aside)
    statuses = [r.status(**options) for r in results]
    if stopped:
        untouched = f"; the report in {out_dir} is untouched" if report_folder.is_report(out_dir) else ""
        print(f"ballbench: interrupted; partial report of {len(results)} of {len(scenes)} scenes: "
              f"{paths['markdown']}{untouched}", file=sys.stderr)
        return EXIT_INTERRUPTED
    failed = [r.name for r, s in zip(results, statuses) if s in ("fail", "error")]
    gaps, findings = statuses.count("known gap"), statuses.count("findings")
    unfit, unsure = statuses.count("not applicable"), statuses.count("inconclusive")
    # a scene that does not apply or is inconclusive validated nothing: it passes the run but is not counted as passed
    print(f"{len(results) - len(failed) - unfit - unsure} of {len(results)} scenes passed"
          + (f" ({gaps} with known gaps)" if gaps else "")
          + (f" ({findings} with findings: models outside their accuracy here)" if findings else "")
          + (f", {unfit} do not apply to the case (outside the model's limits there)" if unfit else "")
          + (f", {unsure} inconclusive (no conclusive reference at this fidelity; each names what settles it)"
             if unsure else "")
          + f"; report: {paths['markdown']} and {paths['html']}")
    if failed:
        print("failed: " + ", ".join(failed))
        return EXIT_FAILED
    return EXIT_OK


def _show_folder(args, names: list[str]) -> Path:
    """The report folder ``show`` draws from: ``--out``, or the folder ``validate`` writes without it
    (:func:`_default_out`); where that holds no report, its partial one (``-partial``: an interrupted run), and for
    a case file ``./ballbench-report`` when it holds the case's scenes (several case files validated in one run).
    A folder that is no report but holds a scene's folder is one too (fields saved by hand, a copied scene folder).
    No report there: a wrong use naming the validate command, except with --solve (the folder is made)."""
    first = Path(args.out) if args.out is not None else _default_out([args.scene])
    candidates = [first] if args.out is not None or first == Path(DEFAULT_OUT) else [first, Path(DEFAULT_OUT)]
    for index, candidate in enumerate(candidates):
        for folder in (candidate, report_folder.partial(candidate)):
            if folder.is_dir() and (report_folder.is_report(folder) or any((folder / n).is_dir() for n in names)) and (
                    index == 0 or {s["name"] for s in report_folder.scenes_in(folder)} & set(names)):
                if folder != candidate:
                    print(f"ballbench: no complete report in {candidate}; drawing from the partial report {folder}",
                          file=sys.stderr, flush=True)
                return folder
    if first.exists() and not first.is_dir():
        raise UsageError(f"--out {first} is an existing file, not a folder")
    if not args.solve:
        out = f" --out {first}" if args.out is not None else ""
        raise UsageError(f"no ballbench report in {first}: run 'ballbench validate {args.scene}{out}' first, which "
                         "saves the fields show draws (--solve solves those of an FE contact or module scene instead)")
    return first


def _show_out(out_dir: Path, name: str) -> None:
    """--solve: the scene's folder in ``out_dir``, made and checked for writing."""
    try:
        (out_dir / name).mkdir(parents=True, exist_ok=True)
        probe = out_dir / name / f".write-test-{os.getpid()}"
        probe.write_text("")
        probe.unlink()
    except OSError as error:
        raise UsageError(f"cannot write to --out {out_dir}: {error.strerror or error}") from None


def _cmd_show(args) -> int:
    if _is_case_file(args.scene):
        return _show_case(args)
    if not can_show(args.scene):  # the full registry only to say what went wrong
        _show_refused(args.scene)
    out_dir = _show_folder(args, [args.scene])
    fidelity = "quick" if args.quick else "default"
    command = f"ballbench show {args.scene}" + (f" --out {args.out}" if args.out is not None else "")
    if args.solve:
        _show_out(out_dir, args.scene)
    before = _files(out_dir, [args.scene])
    try:
        paths = show.show(args.scene, out_dir, fidelity=fidelity, solve=args.solve)
    except KeyboardInterrupt:
        print("ballbench: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except FileNotFoundError as error:
        print(f"ballbench: nothing saved to draw for {args.scene} in {out_dir}: "
              f"{report_folder.why_nothing_saved(out_dir, args.scene, error, command)}", file=sys.stderr)
        return EXIT_OK
    except (OSError, ValueError, KeyError) as error:  # e.g. a damaged fields.vtu / fields.json
        print(f"ballbench: show {args.scene} failed: {type(error).__name__}: {error} (delete "
              f"{out_dir / args.scene / 'fields.vtu'} and run '{command} --solve' to solve the fields again)",
              file=sys.stderr)
        return EXIT_FAILED
    _drawn(out_dir, paths, [args.scene], before)
    return EXIT_OK


def _files(out_dir: Path, names: list[str]) -> set[Path]:
    """The files in the folders of scenes ``names`` in ``out_dir``."""
    return {p for name in names if (out_dir / name).is_dir() for p in (out_dir / name).rglob("*") if p.is_file()}


def _drawn(out_dir: Path, paths: list[Path], names: list[str], before: set[Path]) -> None:
    """Print the pictures drawn (stdout, one path a line) and add them to the report's manifest with the files
    --solve wrote (those in the scenes' folders that were not there ``before``)."""
    for path in paths:
        print(path)
    written = set(paths) | (_files(out_dir, names) - before)
    if written:
        try:
            report_folder.add_to_manifest(out_dir, sorted(written))
        except (OSError, ValueError):
            pass


def _show_refused(name: str) -> None:
    scenes, drawable = registry(), drawable_scenes()
    if name not in scenes:
        raise UsageError(f"no scene {name!r}{_did_you_mean(name, drawable)}; show draws: {', '.join(drawable)}")
    scene = scenes[name]
    what = "an FE scene that saves no fields to draw" if scene.kind == "FE" else f"{scene.kind} scene"
    what = what if scene.kind == "FE" else ("an " if scene.kind[0] in "aeiou" else "a ") + what
    raise UsageError(f"show draws the saved fields of FE scenes; {name!r} is {what} "
                     f"(show draws: {', '.join(drawable)})")


def _show_case(args) -> int:
    """``ballbench show my_case.toml``: the pictures of the case's generated FE scenes, from the fields its validate
    run saved; says which scenes have none and why."""
    case = _load_case(args.scene)
    stem = ladder.slug(args.scene)
    names = [s.name for s in ladder.case_scenes(case, stem) if s.show is not None]
    out_dir = _show_folder(args, names)
    command = f"ballbench show {args.scene}" + (f" --out {args.out}" if args.out is not None else "")
    if args.solve:
        for name in names:
            _show_out(out_dir, name)
    before = _files(out_dir, names)
    drawn, nothing = {}, []

    def skipped(name, reason):
        nothing.append(name)
        print(f"ballbench: {name}: nothing to draw, it does not apply to this case: {reason}", file=sys.stderr,
              flush=True)

    def missing(name, error):
        nothing.append(name)
        print(f"ballbench: {name}: nothing saved to draw in {out_dir / name}: "
              f"{report_folder.why_nothing_saved(out_dir, name, error, command)}", file=sys.stderr, flush=True)

    try:
        paths = ladder.show_case(case, stem, out_dir, fidelity="quick" if args.quick else "default",
                                 solve=args.solve, on_skip=skipped, on_missing=missing)
    except KeyboardInterrupt:
        print("ballbench: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (OSError, ValueError, KeyError) as error:
        print(f"ballbench: show {args.scene} failed: {type(error).__name__}: {error}", file=sys.stderr)
        return EXIT_FAILED
    for path in paths:
        drawn.setdefault(Path(path).parent.name, []).append(Path(path).name)
    for name, files in drawn.items():
        print(f"ballbench: {name}: drew {', '.join(files)}", file=sys.stderr)
    if not drawn:
        print(f"ballbench: no pictures drawn from {out_dir} ({len(nothing)} of {len(names)} scenes with pictures "
              "have nothing saved, said above)", file=sys.stderr)
    _drawn(out_dir, paths, names, before)
    return EXIT_OK


def _cmd_init(args) -> int:
    sys.stdout.write(case_file.template(args.kind))
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="ballbench", description=DESCRIPTION, epilog=EPILOG,
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"ballbench {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    p = sub.add_parser("scenes", help="list the scenes: kind, rough cost, default mesh level",
                       description="List the scenes: name, kind (analytical, low-order, FE), rough cost at the "
                                   "default fidelity, default mesh level (FE) and description.")
    p.set_defaults(func=_cmd_scenes)

    p = sub.add_parser("validate", help="run scenes and write the report",
                       description="Run scenes and write report.md, report.html, results.json, results.csv and "
                                   "error_vs_time.png into the report folder. The run writes into DIR.incomplete-PID "
                                   "beside it and replaces an earlier report only when complete, removing only the "
                                   "files that report wrote (its manifest, .ballbench-report): files of one's own in "
                                   "it are carried over untouched. Exit code 0 when every scene passes (declared "
                                   "known gaps and findings, models outside their declared accuracy on a case "
                                   "file's geometry, scenes that do not apply and inconclusive ones, without a "
                                   "conclusive reference at the fidelity, allowed), 1 when a check fails, 130 when "
                                   "interrupted (Ctrl-C "
                                   "stops after the current scene and writes a partial report into DIR-partial, "
                                   "leaving DIR untouched; twice stops at once).")
    p.add_argument("scenes", nargs="*", metavar="SCENE",
                   help="scene names or shell patterns such as 'lin2019-*' (default: every default scene), or "
                        "case files (my_guide.toml: the validation ladder on that case, docs/cases.md)")
    p.add_argument("--out", metavar="DIR",
                   help="report folder (default: ./ballbench-report-STEM for one case file STEM.toml, else "
                        "./ballbench-report)")
    level = p.add_mutually_exclusive_group()
    level.add_argument("--quick", action="store_true", help="coarsest level of every scene (what CI runs)")
    level.add_argument("--fine", action="store_true", help="finest level: FE mesh-convergence studies (slow)")
    p.add_argument("--fast", action="store_true",
                   help="a first look: leave out the FE scenes and those costing over 30 s")
    p.add_argument("--strict", action="store_true",
                   help="declared known gaps, findings (models outside their accuracy on a case file's geometry), "
                        "scenes that do not apply and inconclusive scenes (no conclusive reference at the fidelity) "
                        "fail the run too")
    p.add_argument("--strict-time", action="store_true",
                   help="a scene over its wall-time budget or over its declared memory fails (by default "
                        "budgets are only reported, since run time depends on the machine's load)")
    p.add_argument("--junit", metavar="FILE", help="also write JUnit XML (one test case per scene) for CI systems")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bars (they are shown only when stderr is a terminal)")
    p.add_argument("--levels", choices=RUNGS, metavar="RUNG",
                   help="case files: the highest rung of the ladder to run, one of " + ", ".join(RUNGS)
                        + f" (default {RUNGS[-1]}: every rung)")
    p.add_argument("--budget", type=float, metavar="SECONDS",
                   help="case files: stop refining a mesh study when its next level is predicted to end after "
                        "this wall time from the start")
    p.add_argument("--workers", type=int, metavar="N",
                   help="run the scenes as dask.distributed tasks on a local cluster of N single-threaded worker "
                        "processes (results equal a serial run's, timings aside)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the scenes on an existing dask scheduler, e.g. tcp://127.0.0.1:8786 (workers started "
                        "with --nthreads 1, sharing this file system)")
    calibrate_command.add_validate_option(p)  # --calibration FILE (docs/calibration.md)
    p.set_defaults(func=_cmd_validate)

    p = sub.add_parser("show", help="pictures of an FE scene's saved fields",
                       description="Draw the contact pressure and a stress cut of an FE scene (or of a case file's "
                                   "scenes) from the fields that 'ballbench validate' saved in DIR/SCENE/ and write "
                                   "the PNG files there; it never solves unasked: a scene with nothing saved is "
                                   "named with the reason (it errored, did not apply, was not run), and --solve "
                                   "solves its fields first. Exit code 0 when it drew what is saved (also when "
                                   "nothing is, the reason said), 1 when saved fields cannot be read, 2 when DIR "
                                   "holds no report (run 'ballbench validate' first).")
    p.add_argument("scene", metavar="SCENE", help="an FE scene, e.g. fe-hertz-groove-056, or a case file")
    p.add_argument("--out", metavar="DIR",
                   help="report folder of the validate run (default: the one validate writes without --out, "
                        "./ballbench-report-STEM for STEM.toml, else ./ballbench-report)")
    p.add_argument("--solve", action="store_true",
                   help="solve the fields of the scenes that saved none (the FE solve: minutes) and draw them")
    p.add_argument("--quick", action="store_true", help="with --solve: the coarsest mesh level")
    p.set_defaults(func=_cmd_show)

    p = sub.add_parser("init", help="write a commented case file to stdout",
                       description="Write a commented case file of the given kind to stdout: edit its values and "
                                   "run 'ballbench validate FILE.toml' (docs/cases.md).")
    p.add_argument("kind", choices=CASE_KINDS, metavar="KIND", help="one of " + ", ".join(CASE_KINDS))
    p.set_defaults(func=_cmd_init)

    sweep.add_parser(sub)  # ballbench sweep SPEC.toml (docs/sweeps.md)
    calibrate_command.add_parser(sub)  # ballbench calibrate SPEC.toml (docs/calibration.md)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        return args.func(args)
    except UsageError as error:
        print(f"ballbench: error: {error}", file=sys.stderr)
        return EXIT_USAGE
    except BrokenPipeError:
        # the reader went away (e.g. 'ballbench scenes | head'): stop quietly
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        except OSError:
            pass
        return EXIT_OK
    except KeyboardInterrupt:
        print("ballbench: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
