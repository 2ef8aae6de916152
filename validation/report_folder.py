"""The report folder: written whole into a temporary sibling, then put in place; only ballbench's own files removed.

A run never writes into the report it replaces (docs/validation.md, "The report folder"):

* it writes into :func:`temporary` (``<out>.incomplete-<pid>``, beside ``<out>``);
* complete, it :func:`replace` s ``<out>`` with it: the files of the earlier report that its manifest does not list
  (a user's ``notes.txt``, a folder of one's own) are moved into the new report first, untouched, then ``<out>`` is
  renamed aside, the new folder renamed to ``<out>``, and from the aside folder only the files the manifest lists are
  removed;
* interrupted, it puts itself at :func:`partial` (``<out>-partial``) the same way, and ``<out>`` stays untouched.

The manifest is the file :data:`MARKER` (``.ballbench-report``), JSON ``{"written_by", "files": [relative POSIX
paths]}``: every file the report wrote (``ballbench show`` adds its pictures).  A report of an earlier version
carries a plain-text marker (or none): its files are then the report's own top-level files and the folders of the
scenes its ``results.json`` names (:func:`owned`).
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from ballbench import __version__
from ballbench.validation.usage import UsageError

__all__ = ["MARKER", "REPORT_FILES", "is_report", "owned", "write_manifest", "add_to_manifest", "temporary",
           "make_temporary", "partial", "put_partial", "replace", "remove_owned", "scenes_in", "say_kept",
           "why_nothing_saved"]

MARKER = ".ballbench-report"
# the top-level files write_report writes (validation.report.write_report)
REPORT_FILES = ("report.md", "report.html", "results.json", "results.csv", "error_vs_time.png", "error_vs_time.csv")


def is_report(folder: Path) -> bool:
    """A folder a ballbench run wrote: it carries the marker (or, before the marker existed, report.md and
    results.json)."""
    folder = Path(folder)
    return (folder / MARKER).is_file() or ((folder / "report.md").is_file() and (folder / "results.json").is_file())


def scenes_in(folder: Path) -> list[dict]:
    """The scene records of ``folder/results.json`` (validation.report, its schema); [] when there is none or it
    cannot be read."""
    try:
        data = json.loads((Path(folder) / "results.json").read_text())
    except (OSError, ValueError):
        return []
    scenes = data.get("scenes", []) if isinstance(data, dict) else []
    return [s for s in scenes if isinstance(s, dict) and isinstance(s.get("name"), str)]


def owned(folder: Path) -> set[str]:
    """The files of report ``folder`` that ballbench wrote, as relative POSIX paths: those its manifest lists, or
    for a report of an earlier version (no manifest) its top-level report files and every file in the folders of
    the scenes its results.json names."""
    folder = Path(folder)
    try:
        data = json.loads((folder / MARKER).read_text())
        files = data["files"]
        if isinstance(files, list):
            return {str(f) for f in files} | {MARKER}
    except (OSError, ValueError, KeyError, TypeError):
        pass
    names = set(REPORT_FILES) | {MARKER}
    for scene in scenes_in(folder):
        directory = folder / scene["name"]
        if directory.is_dir() and not directory.is_symlink():
            names |= set(_files(directory, folder)) | {scene["name"] + "/"}
    return names


def _files(folder: Path, root: Path | None = None) -> list[str]:
    """Every file of ``folder`` and every folder in it (``name/``) as POSIX paths relative to ``root``."""
    folder = Path(folder)
    root = folder if root is None else Path(root)
    names = []
    for path in folder.rglob("*"):
        rel = path.relative_to(root).as_posix()
        if path.is_dir() and not path.is_symlink():
            names.append(rel + "/")
        elif path.name != MARKER:
            names.append(rel)
    return sorted(names)


def write_manifest(folder: Path) -> None:
    """Write the manifest of ``folder``, a folder this run wrote whole: every file and folder in it is the
    report's."""
    folder = Path(folder)
    data = {"written_by": f"ballbench {__version__}",
            "note": "a ballbench report folder; a later run into it removes only the files listed here",
            "files": _files(folder)}
    (folder / MARKER).write_text(json.dumps(data, indent=1) + "\n")


def add_to_manifest(folder: Path, paths) -> None:
    """Add ``paths`` (files ballbench wrote inside ``folder``, e.g. ``ballbench show``'s pictures) to its manifest
    (written new where the folder has none: a folder ``show --solve`` made)."""
    folder = Path(folder)
    files = owned(folder) - {MARKER} if is_report(folder) else set()  # a report without a manifest: its own files
    files |= {Path(p).resolve().relative_to(folder.resolve()).as_posix() for p in paths}
    data = {"written_by": f"ballbench {__version__}",
            "note": "a ballbench report folder; a later run into it removes only the files listed here",
            "files": sorted(files)}
    (folder / MARKER).write_text(json.dumps(data, indent=1) + "\n")


def temporary(out: Path) -> Path:
    """The folder a run writes into before it replaces ``out``: ``<out>.incomplete-<pid>`` beside it."""
    out = Path(out)
    return out.parent / f"{out.name}.incomplete-{os.getpid()}"


def partial(out: Path) -> Path:
    """Where an interrupted run's partial report goes: ``<out>-partial`` beside ``out``."""
    out = Path(out)
    return out.parent / f"{out.name}-partial"


def _folders(mine: set[str]) -> set[str]:
    """The folders (no trailing '/') that the report's entries ``mine`` name or lie in, at any depth."""
    folders = set()
    for name in mine:
        parts = name.rstrip("/").split("/")
        stop = len(parts) if name.endswith("/") else len(parts) - 1
        folders |= {"/".join(parts[:i]) for i in range(1, stop + 1)}
    return folders


def _user_entries(folder: Path, mine: set[str]) -> list[str]:
    """The entries of ``folder`` that are not ballbench's (``mine``): a whole folder when neither it nor any of
    its files is ballbench's, else its entries one by one."""
    folder = Path(folder)
    parents = _folders(mine)
    found = []

    def walk(directory: Path, rel: str):
        for entry in sorted(directory.iterdir()):
            name = f"{rel}{entry.name}"
            if name in mine:
                continue
            if entry.is_dir() and not entry.is_symlink() and name in parents:
                walk(entry, name + "/")
            else:
                found.append(name)

    walk(folder, "")
    return found


def remove_owned(folder: Path, mine: set[str] | None = None) -> list[str]:
    """Remove from ``folder`` the files ballbench wrote (:func:`owned`, or ``mine``) and its folders left empty;
    returns what is left (relative paths), the folder itself removed when nothing is."""
    folder = Path(folder)
    mine = owned(folder) if mine is None else mine
    for name in mine:
        path = folder / name
        if not name.endswith("/") and (path.is_symlink() or path.is_file()):
            path.unlink()
    for name in sorted(_folders(mine), key=lambda n: -n.count("/")):
        path = folder / name
        if path.is_dir() and not path.is_symlink() and not any(path.iterdir()):
            path.rmdir()
    left = sorted(p.name for p in folder.iterdir())
    if not left:
        folder.rmdir()
    return left


def replace(new: Path, out: Path) -> tuple[list[str], Path | None]:
    """Put the report folder ``new`` (complete, its manifest written) at ``out``.

    Where ``out`` holds an earlier report, the entries that are not its own files (:func:`owned`) are moved into
    ``new`` first, untouched (one whose name the new report also uses stays behind); ``out`` is renamed aside,
    ``new`` renamed to ``out`` (the folder is missing only between the two renames), and the earlier report's own
    files are removed from the aside folder.  Returns ``(entries carried over, the aside folder where something
    stayed behind or None)``.  ``out`` must be absent, or a report (:func:`is_report`): the caller checks.
    """
    new, out = Path(new), Path(out)
    if not out.exists():
        new.rename(out)
        return [], None
    mine = owned(out)
    carried = []
    for name in _user_entries(out, mine):
        target = new / name
        if target.exists() or target.is_symlink():
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        (out / name).rename(target)
        carried.append(name)
    aside = out.parent / f"{out.name}.replaced-{os.getpid()}"
    out.rename(aside)
    try:
        new.rename(out)
    except OSError:
        aside.rename(out)
        raise
    left = remove_owned(aside, mine)
    return carried, (aside if left else None)


def make_temporary(out: Path) -> Path:
    """The folder the run writes into (:func:`temporary`), created now: the check that ``--out``'s folder takes
    files (UsageError where it does not)."""
    temp = temporary(out)
    try:
        temp.mkdir(parents=True, exist_ok=False)
    except FileExistsError:  # left by a killed run of a process that had this id
        for child in sorted(temp.rglob("*"), key=lambda p: -len(p.parts)):
            child.rmdir() if child.is_dir() and not child.is_symlink() else child.unlink()
    except OSError as error:
        raise UsageError(f"cannot write to --out {out}: {error.strerror or error}") from None
    return temp


def put_partial(temp: Path, out: Path) -> Path:
    """Put the partial report ``temp`` (its manifest written) beside ``out`` as ``<out>-partial`` (replacing an
    earlier partial report the same way a complete one replaces ``out``); returns where it went."""
    target = partial(out)
    if target.exists() and not (target.is_dir() and (is_report(target) or not any(target.iterdir()))):
        target = target.parent / f"{target.name}-{os.getpid()}"  # a folder of one's own of that name
    replace(temp, target)
    return target


def say_kept(out: Path, carried: list[str], aside: Path | None) -> None:
    """Name the files of one's own a complete run carried from the earlier report into the new one (and where
    those whose names the new report uses stayed)."""
    if carried:
        print(f"ballbench: kept in {out}, untouched (not files of the earlier report): {', '.join(carried)}",
              file=sys.stderr)
    if aside is not None:
        print(f"ballbench: files of one's own in the earlier report whose names the new report uses are kept in "
              f"{aside}", file=sys.stderr)


def why_nothing_saved(out_dir: Path, name: str, error: Exception, command: str) -> str:
    """Why scene ``name`` has no saved fields in the report ``out_dir``, from its results.json and error.txt."""
    try:
        data = json.loads((out_dir / "results.json").read_text())
    except (OSError, ValueError):
        data = {}
    data = data if isinstance(data, dict) else {}
    record = {s["name"]: s for s in scenes_in(out_dir)}.get(name)
    solve = f"'{command} --solve' solves them"
    if record is None:
        if not (out_dir / "results.json").is_file() and (out_dir / MARKER).is_file():  # a run's partial folder
            return f"the validate run stopped at once (a second Ctrl-C) before it wrote its results ({solve})"
        if name in data.get("not_run", []):
            return f"not run: the validate run was interrupted before it ({solve})"
        return f"not in this report, whose run did not include it ({solve})"
    status = record.get("status", "")
    if status == "error":
        traceback = out_dir / name / "error.txt"
        where = f"; traceback: {traceback}" if traceback.is_file() else ""
        return f"the scene ended in an error: {record.get('error', '')}{where}"
    if status == "not applicable":
        return f"the scene does not apply to this case: {record.get('not_applicable', '')}"
    if record.get("interrupted"):
        return f"the scene was interrupted before it saved them ({solve})"
    if record.get("kind") not in (None, "FE"):  # a case file's contact scene run below its FE rung (--levels)
        quick = f" (it ran as a {record['kind']} scene: the run's --levels stopped below FE)"
    else:
        # the registered FE contact scenes (fe-hertz-*) save their fields at the default and fine levels only
        registered = not name.endswith(("-contact", "-b2b-fe"))
        quick = (" (a --quick run of an FE contact scene saves none)" if data.get("fidelity") == "quick" and registered
                 else "")
    # a hook with nothing to solve (render3d.show_saved: BEM / EHL surfaces, stick/slip areas) says to validate; a
    # contact rung that ran no FE study, and said why in its notes (an ellipse the FE pair cannot hold), has none
    unsolvable = [note for note in record.get("notes", []) if "FE study not run:" in note]
    if unsolvable:
        return f"the scene ({status}) ran no FE study: " + unsolvable[0].split("FE study not run: ", 1)[1]
    hint = "" if "ballbench validate" in str(error) else f" ({solve})"
    return f"the scene ({status}) saved no fields here{quick}: {error}{hint}"

