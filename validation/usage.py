"""The exit-code convention of every ``ballbench`` subcommand and the error of a wrong use.

0 passed; 1 a check failed (a scene failed or raised, every case of a sweep failed, a fit or a picture failed);
2 wrong use (one line on stderr naming the problem, no traceback, nothing run or written); 130 interrupted by
Ctrl-C.  A subcommand raises :class:`UsageError` for a wrong use; ``validation.cli.main`` prints it and returns 2.
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["UsageError", "EXIT_OK", "EXIT_FAILED", "EXIT_USAGE", "EXIT_INTERRUPTED", "check_writable_file",
           "check_writable_folder"]

EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130


class UsageError(Exception):
    """A wrong use of a command: reported as one line, exit code 2."""


def check_writable_file(path: str | Path, option: str) -> Path:
    """UsageError unless ``path`` can be written as a file (its folder exists or can be made, and is writable);
    checked before any work.  Returns the path."""
    path = Path(path)
    if path.is_dir():
        raise UsageError(f"{option} {path} is a folder; give a file name")
    parent = path.parent if str(path.parent) else Path(".")
    existing = parent
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise UsageError(f"{option} {path}: {existing} is not a folder")
    _probe(existing, f"cannot write {option} {path}")
    if path.exists() and not os.access(path, os.W_OK):
        raise UsageError(f"cannot write {option} {path}: permission denied")
    return path


def check_writable_folder(path: str | Path, option: str) -> Path:
    """UsageError unless ``path`` is (or can be made as) a writable folder; checked before any work, nothing is
    created.  Returns the path."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise UsageError(f"{option} {path} is an existing file, not a folder")
    existing = path
    while not existing.exists() and existing != existing.parent:
        existing = existing.parent
    if not existing.is_dir():
        raise UsageError(f"{option} {path}: {existing} is not a folder")
    _probe(existing, f"cannot write to {option} {path}")
    return path


def _probe(folder: Path, message: str) -> None:
    """UsageError with ``message`` unless a file can be made in ``folder`` (made and removed at once: a read-only
    file system or a folder of another user is found even by root, whom ``os.access`` always lets write)."""
    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".ballbench-write-test-"):
            pass
    except OSError as error:
        raise UsageError(f"{message}: {error.strerror or error}") from None
