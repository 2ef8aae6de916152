"""What the compiled-kernel benchmarks share (docs/speed.md): timing both paths interleaved, loading a kernel
module, and its first-call cost in fresh processes."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import pytest

from ballbench.lowmodel import kernels


def interleaved(function, repeats: int, block: int = 1) -> tuple[float, float]:
    """Median CPU seconds per call of ``function()`` with the kernels and without them: ``repeats`` alternating
    blocks of ``block`` calls each (a block keeps one path's data in cache, as a loop of solves does)."""
    new, old = [], []
    for _ in range(repeats):
        for enabled, into in ((True, new), (False, old)):
            kernels.use_kernels(enabled)
            function()
            start = time.process_time()
            for _ in range(block):
                function()
            into.append((time.process_time() - start) / block)
    kernels.use_kernels(None)
    return float(np.median(new)), float(np.median(old))


def compiled_module(name: str):
    """The kernel module ``name`` (lowmodel.kernels.load), compiled or loaded; skips the test without numba."""
    pytest.importorskip("numba")
    module = kernels.load(name)
    assert module is not None, kernels.load_errors
    return module


def first_call_seconds(name: str) -> tuple[float, float]:
    """Seconds of ``kernels.load(name)`` in a fresh process: with an empty numba cache (compile) and then from that
    cache (load from disk)."""
    code = ("import time\nfrom ballbench.lowmodel import kernels\nstart = time.perf_counter()\n"
            f"assert kernels.load({name!r}) is not None, kernels.load_errors\n"
            "print(time.perf_counter() - start)")
    with tempfile.TemporaryDirectory() as cache:
        environment = {**os.environ, "NUMBA_CACHE_DIR": cache}
        return tuple(float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                                          env=environment).stdout) for _ in range(2))
