"""Run scenes: time, check, collect; never let one scene's crash hide the others."""
from __future__ import annotations

import sys
import time
import traceback
from pathlib import Path
from typing import Callable, Iterable

from ballbench.validation.scene import Run, Scene, SceneResult


def run_scene(scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = False) -> SceneResult:
    """Run one scene; an exception becomes a failed result carrying its message.

    The traceback of a failing scene goes to ``<out>/<scene>/error.txt`` (an
    artifact of the report), not to the terminal.  Ctrl-C inside the scene
    returns a result marked ``interrupted``.
    """
    run = Run(scene, fidelity, out_dir, show_progress=show_progress)
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
               should_stop: Callable[[], bool] = lambda: False) -> tuple[list[SceneResult], bool]:
    """Run ``scenes`` in order; returns ``(results, stopped)``.

    ``on_result`` is called after each scene (e.g. to print its status line);
    the loop stops before the next scene when ``should_stop()`` is true or a
    scene was interrupted (``stopped`` is then True).
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
            result = run_scene(scene, fidelity, out_dir, show_progress=show_progress)
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
    finally:
        if bar is not None:
            bar.close()
    return results, stopped
