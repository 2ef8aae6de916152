"""Run scenes: time, check, collect; never let one scene's crash hide the others."""
from __future__ import annotations

import sys
import time
import traceback
from pathlib import Path
from typing import Iterable

from ballbench.validation.scene import Run, Scene, SceneResult


def run_scene(scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = True) -> SceneResult:
    """Run one scene; an exception becomes a failed result carrying its message."""
    run = Run(scene, fidelity, out_dir, show_progress=show_progress)
    start = time.perf_counter()
    error = ""
    try:
        scene.function(run)
    except Exception as exc:  # a scene failure is a result, not a crash of the suite
        error = f"{type(exc).__name__}: {exc}"
        traceback.print_exc(file=sys.stderr)
    wall = time.perf_counter() - start
    if not error and not run._outputs:
        error = "scene recorded no checked output"
    return run.result(wall, error)


def run_scenes(scenes: Iterable[Scene], fidelity: str, out_dir: Path, *, show_progress: bool = True) -> list[SceneResult]:
    scenes = list(scenes)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    results = []
    iterator = scenes
    bar = None
    if show_progress:
        from tqdm.auto import tqdm

        bar = tqdm(scenes, desc="scenes", unit="scene", file=sys.stderr)
        iterator = bar
    for scene in iterator:
        if bar is not None:
            bar.set_postfix_str(scene.name)
        result = run_scene(scene, fidelity, out_dir, show_progress=show_progress)
        status = "PASS" if result.passed else "FAIL"
        message = f"{status} {scene.name} ({result.wall_time_s:.2f} s){' ' + result.error if result.error else ''}"
        if bar is not None:
            bar.write(message, file=sys.stderr)
        else:
            print(message, file=sys.stderr)
        results.append(result)
    return results
