"""Ctrl-C during ``ballbench validate``: the first stops after the current scene, the second at once.

Either way the run's report folder is put beside the earlier report as its partial one (``<out>-partial``,
validation.report_folder) and the earlier report is never touched (docs/validation.md, "The report folder").
"""
from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from pathlib import Path

from ballbench.validation import report_folder
from ballbench.validation.usage import EXIT_INTERRUPTED

__all__ = ["Interrupt", "kept_on_error"]


class Interrupt:
    """SIGINT: the first Ctrl-C stops after the current scene, the second stops at once.

    At once is within a moment even while the main thread is inside a long solver call: Python runs its signal
    handler only between two bytecodes of the main thread, so the signal also wakes a thread of its own
    (``signal.set_wakeup_fd``), which ends the process (``os._exit``) after putting the run's temporary folder
    beside the report as its partial one.  The earlier report in ``out`` is never touched.  ``temp``/``out``:
    the run's folders (None outside a validate run); ``finishing``: the complete report is being put in place, a
    second Ctrl-C then waits for it (a few renames).
    """

    def __init__(self, temp: Path | None = None, out: Path | None = None):
        self.requested = False
        self.previous = None
        self.temp, self.out = temp, out
        self.finishing = False
        self._lock = threading.Lock()
        self._wakeup = None

    def __enter__(self):
        try:
            self.previous = signal.signal(signal.SIGINT, self._handle)
        except ValueError:  # not the main thread (e.g. in some test runners)
            self.previous = None
            return self
        read, write = os.pipe()
        os.set_blocking(write, False)
        try:
            old = signal.set_wakeup_fd(write, warn_on_full_buffer=False)
        except ValueError:
            os.close(read)
            os.close(write)
            return self
        self._wakeup = (read, write, old)
        threading.Thread(target=self._watch, args=(read,), name="ballbench-ctrl-c", daemon=True).start()
        return self

    def _watch(self, read: int) -> None:
        seen = 0
        while True:
            try:
                data = os.read(read, 64)
            except OSError:
                return
            if not data:  # __exit__ closed the other end
                os.close(read)
                return
            seen += data.count(signal.SIGINT)
            if seen >= 2:
                self.stop_now()

    def _handle(self, signum, frame):  # noqa: ARG002 - the signal-handler signature
        if self.requested:
            if self.finishing:
                return
            self.stop_now()
            raise KeyboardInterrupt  # only outside a validate run's folders (stop_now returned)
        self.requested = True
        untouched = self.out is not None and report_folder.is_report(self.out)
        print("\nballbench: Ctrl-C: stopping after the current scene, at its next step (Ctrl-C again to stop now"
              + (f"; the report in {self.out} stays untouched" if untouched else "") + ")", file=sys.stderr, flush=True)

    def stop_now(self) -> None:
        """The second Ctrl-C: the run's folder put beside the report as partial, one line, exit 130 at once."""
        if self.temp is None or self.finishing:
            return
        if not self._lock.acquire(blocking=False):
            if self.finishing:  # the complete report is being put in place (finish)
                return
            self._lock.acquire()  # the other thread's stop_now ends the process; this waits for it
        where = ""
        try:
            if self.temp.is_dir():
                report_folder.write_manifest(self.temp)
                kept = report_folder.put_partial(self.temp, self.out)
                where = f"; what it wrote so far is in {kept} (no report.md: the scenes stopped unfinished)"
        except OSError as error:
            where = f"; its files stay in {self.temp} ({error.strerror or error})"
        untouched = f"; the report in {self.out} is untouched" if report_folder.is_report(self.out) else ""
        try:
            os.write(2, f"\nballbench: stopped at once (second Ctrl-C){where}{untouched}\n".encode())
        finally:
            os._exit(EXIT_INTERRUPTED)

    def finish(self) -> None:
        """The report is complete and is being put in place: from here a second Ctrl-C waits for the few renames
        (a stop_now under way in the other thread ends the process first)."""
        self._lock.acquire()
        self.finishing = True

    def __exit__(self, *exc):
        if self._wakeup is not None:
            _, write, old = self._wakeup
            signal.set_wakeup_fd(old)
            os.close(write)  # the thread reads the end of its pipe and closes it
        if self.previous is not None:
            signal.signal(signal.SIGINT, self.previous)
        return False


@contextlib.contextmanager
def kept_on_error(temp: Path, out: Path):
    """What a run wrote before an exception escaped it (a bug, Ctrl-C outside a scene) is put beside ``out`` as its
    partial report folder, never left as a temporary folder nor written over ``out``."""
    try:
        yield
    except BaseException:
        if temp.is_dir():
            try:
                report_folder.write_manifest(temp)
                kept = report_folder.put_partial(temp, out)
                print(f"ballbench: what the run wrote so far is in {kept}", file=sys.stderr)
            except OSError:
                pass
        raise
