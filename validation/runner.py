"""Run scenes: time, check, collect; never let one scene's crash hide the others."""
from __future__ import annotations

import sys
import time
import traceback
from pathlib import Path
from typing import Callable, Iterable

from ballbench.validation.scene import Run, Scene, SceneResult


def run_scene(scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = False,
              progress_lines: bool = False, should_stop: Callable[[], bool] | None = None) -> SceneResult:
    """Run one scene; an exception becomes a failed result carrying its message.

    The traceback of a failing scene goes to ``<out>/<scene>/error.txt`` (an
    artifact of the report), not to the terminal.  Ctrl-C inside the scene, or a stop request
    (``should_stop()`` true at one of the scene's steps, :meth:`Run.checkpoint`), returns a result marked
    ``interrupted``.  ``progress_lines``: one line per step on stderr when there is no bar.
    """
    run = Run(scene, fidelity, out_dir, show_progress=show_progress, progress_lines=progress_lines,
              should_stop=should_stop)
    start = time.perf_counter()
    error = ""
    interrupted = False
    try:
        scene.function(run)
    except KeyboardInterrupt:
        interrupted = True
        error = "interrupted by the user (Ctrl-C) before the scene finished"
    except Exception as exc:  # a scene failure is a result, not a crash of the suite
        error = f"{type(exc).__name__}: {exc}"
        try:
            path = run.path("error.txt")
            path.write_text(traceback.format_exc())
            run.add_artifact(path)
        except OSError:
            pass
    wall = time.perf_counter() - start
    if not error and not run.outputs:
        error = "scene recorded no checked output"
    return run.result(wall, error, interrupted)


def run_scenes(scenes: Iterable[Scene], fidelity: str, out_dir: Path, *, show_progress: bool = False,
               on_result: Callable[[SceneResult], None] | None = None,
               should_stop: Callable[[], bool] = lambda: False,
               progress_lines: bool = False) -> tuple[list[SceneResult], bool]:
    """Run ``scenes`` in order; returns ``(results, stopped)``.

    ``on_result`` is called after each scene (e.g. to print its status line);
    a scene stops at its next step and the loop before the next scene when ``should_stop()`` is true or a
    scene was interrupted (``stopped`` is then True, also when the request came during the last scene).
    """
    scenes = list(scenes)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    results: list[SceneResult] = []
    bar = None
    if show_progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(scenes), desc="scenes", unit="scene", file=sys.stderr)
    stopped = False
    try:
        for scene in scenes:
            if should_stop():
                stopped = True
                break
            if bar is not None:
                bar.set_postfix_str(scene.name)
            if progress_lines and bar is None:
                print(f"ballbench: scene {len(results) + 1} of {len(scenes)}: {scene.name}", file=sys.stderr,
                      flush=True)
            result = run_scene(scene, fidelity, out_dir, show_progress=show_progress, progress_lines=progress_lines,
                               should_stop=should_stop)
            results.append(result)
            if bar is not None:
                bar.update()
            if on_result is not None:
                if bar is not None:
                    with bar.external_write_mode():
                        on_result(result)
                else:
                    on_result(result)
            if result.interrupted:
                stopped = True
                break
        if should_stop():  # a stop requested while the last scene ran is still a stop (exit 130)
            stopped = True
    finally:
        if bar is not None:
            bar.close()
    return results, stopped
