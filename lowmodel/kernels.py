"""Compiled kernels: where they are loaded, when they are used, and the numpy path beside them.

The low-order models are numpy code whose cost for a small system (a two-ball state has 16 unknowns) is
per-call overhead of small array operations, not arithmetic (docs/speed.md).  Where a kernel
compiled with numba beats that by a wide margin, a module holds it beside the numpy code it mirrors
(:mod:`lowmodel.linear_bearing.ball_kernels`: the ball equilibrium of lin2019 eq 4, the B2B chain of
eqs 5-10 and the damped Newton of :func:`lowmodel.solvers.newton`, as loops; :mod:`lowmodel.screw.ball_kernels`:
the ball-screw ball of eqs 36-54 with the offset-ellipse friction of A4-A11, the screw B2B chain of eqs 56-61
and the same Newton).  The rules:

* ``import ballbench.lowmodel`` never imports numba (a test checks it): a kernel module is imported by
  :func:`load` at the first solve that uses it.
* numba is optional (the ``fast`` extra; docs/speed.md says why): when it is missing, when
  ``BALLBENCH_KERNELS=numpy`` is set, when :func:`use_kernels` turned it off, or when a kernel fails to
  compile, the models run their numpy code, which gives the same results (to round-off; tests compare
  both paths).
* The compiled machine code is cached on disk (``cache=True``) in ``$NUMBA_CACHE_DIR`` if set, else in
  ``lowmodel.cache.cache_dir("numba")`` (``~/.cache/ballbench/numba``), so the compile cost (seconds)
  is paid once per machine and kernel version, not once per process; :func:`load_seconds` reports what
  the first use in this process cost (compile, or load from the cache).  numba keys a kernel's cache on its own
  source file, but a kernel calls other modules' (the compiled Newtons inline the loop of
  :mod:`lowmodel.newton_kernels`; :mod:`lowmodel.screw.ring_kernels` calls :mod:`lowmodel.screw.ball_kernels`): so
  ballbench's cache is one folder per version of all kernel sources (:func:`sources_key`, a hash of every
  ``*_kernels.py``), and an edit of any kernel compiles them all anew instead of loading a stale caller.
"""
from __future__ import annotations

import hashlib
import importlib
import os
import time
from pathlib import Path

from ballbench.lowmodel.cache import cache_dir

__all__ = ["load", "use_kernels", "kernels_enabled", "load_seconds", "sources_key", "ENVIRONMENT_VARIABLE"]

ENVIRONMENT_VARIABLE = "BALLBENCH_KERNELS"  # "numpy" (or "0", "off"): never use the compiled kernels
_LOADED: dict = {}  # module name -> module, or None where it could not be had
_SECONDS: dict = {}  # module name -> seconds of its first load (import and warm-up calls)
_STATE = {"enabled": None}  # None: decided by the environment variable


def kernels_enabled() -> bool:
    """True unless :func:`use_kernels` (False) or ``BALLBENCH_KERNELS=numpy`` switched the kernels off."""
    if _STATE["enabled"] is not None:
        return bool(_STATE["enabled"])
    return os.environ.get(ENVIRONMENT_VARIABLE, "").strip().lower() not in ("numpy", "0", "off", "false", "no")


def use_kernels(enabled: bool | None) -> None:
    """Switch the compiled kernels on (True), off (False: the numpy path) or back to the environment (None)."""
    if enabled is not None and not isinstance(enabled, bool):
        raise ValueError(f"enabled must be True, False or None, got {enabled!r}")
    _STATE["enabled"] = enabled


def load(name: str):
    """The kernel module ``ballbench.lowmodel.<name>``, or None: kernels off, numba missing, or the module
    failed to import or to compile its warm-up (then the numpy path runs; the failure is kept in
    ``load_errors``).  The module's ``warm_up()`` is called once (compiles, or loads from the disk cache)."""
    if not kernels_enabled():
        return None
    if name in _LOADED:
        return _LOADED[name]
    start = time.perf_counter()
    module = None
    try:
        _cache_location()
        module = importlib.import_module(f"ballbench.lowmodel.{name}")
        module.warm_up()
    except Exception as error:  # ImportError (no numba), numba's typing and lowering errors: the numpy path
        load_errors[name] = f"{type(error).__name__}: {error}"
        module = None
    _LOADED[name] = module
    _SECONDS[name] = time.perf_counter() - start
    return module


load_errors: dict = {}


def load_seconds(name: str) -> float | None:
    """Wall seconds the first :func:`load` of ``name`` took in this process (compile or cache load), or None."""
    return _SECONDS.get(name)


def sources_key(folder: Path = Path(__file__).parent) -> str:
    """16 hex digits of a hash of every kernel source (``*_kernels.py`` below ``folder``, by path and content): the
    version of the compiled code that ballbench's numba cache is kept under."""
    digest = hashlib.sha256()
    for path in sorted(folder.rglob("*_kernels.py")):
        digest.update(path.relative_to(folder).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def _cache_location() -> None:
    """numba's cache directory: ``$NUMBA_CACHE_DIR`` if set, else ballbench's cache, one folder per
    :func:`sources_key` (read when numba is first imported; a numba imported before keeps its own setting)."""
    if "NUMBA_CACHE_DIR" not in os.environ:
        os.environ["NUMBA_CACHE_DIR"] = str(cache_dir("numba") / sources_key())
