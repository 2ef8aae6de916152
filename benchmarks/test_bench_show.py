"""Wall and CPU time of ``ballbench show SCENE`` from saved fields, per scene (docs/render3d.md, "Cost").

Target (docs/render3d.md): every FE scene's screenshots written from its saved fields within 20 s on the shared
2-core machine, without an X server, with nothing on stderr.  Each scene runs as its own ``ballbench show``
process (imports included, as a user runs it); the CPU time is that process's user + system time, the load
average the 1-minute one at its start.  The target is judged on the CPU time (the work a scene's pictures need),
since on a shared machine the wall time grows with the other jobs (3-4x at load 8); the wall time is printed
beside it.  The scenes drawn are those with saved fields in the report folder
``BALLBENCH_SHOW_DIR`` (default ``ballbench-report``: run ``ballbench validate SCENE`` first; the scenes without
fields are listed and skipped, never solved here).

Run: BALLBENCH_SHOW_DIR=/path/to/report python -m pytest benchmarks/test_bench_show.py -s
"""
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ballbench.validation import show
from ballbench.validation.figures import render3d

TARGET_S = 20.0


def _saved(out_dir: Path) -> list[str]:
    return [name for name in show.drawable() if render3d.has_fields(out_dir / name)]


def test_show_times():
    out_dir = Path(os.environ.get("BALLBENCH_SHOW_DIR", "ballbench-report"))
    scenes = _saved(out_dir)
    if not scenes:
        pytest.skip(f"no saved fields in {out_dir}")
    missing = sorted(set(show.drawable()) - set(scenes))
    print(f"\nno saved fields in {out_dir} for: {', '.join(missing) or '-'}")
    command = [str(Path(sys.executable).parent / "ballbench"), "show", "--out", str(out_dir)]
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}  # as on a machine without an X server
    print("| scene | pictures | wall [s] | CPU [s] | load average |\n|---|---|---|---|---|")
    slow, noisy = [], []
    for name in scenes:
        load = os.getloadavg()[0]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run([*command, name], capture_output=True, text=True, env=env, check=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        pictures = len([line for line in done.stdout.splitlines() if line.endswith(".png")])
        print(f"| {name} | {pictures} | {wall:.1f} | {cpu:.1f} | {load:.1f} |", flush=True)
        slow += [name] if cpu > TARGET_S else []
        noisy += [f"{name}: {done.stderr.strip()}"] if done.stderr.strip() else []
    assert not noisy, noisy
    assert not slow, f"over {TARGET_S:g} s of CPU time: {slow}"
