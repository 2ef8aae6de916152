"""What the tests of the compiled kernels share: the kernel module with the kernels on, and one call on both paths."""
import pytest

from ballbench.lowmodel import kernels


def kernels_on(name: str):
    """Generator for a fixture: the kernel module ``name`` loaded with the kernels on (skips without numba); the
    kernels return to their default afterwards."""
    pytest.importorskip("numba")
    kernels.use_kernels(True)
    module = kernels.load(name)
    assert module is not None, kernels.load_errors
    yield module
    kernels.use_kernels(None)


def both(function, *args, **kwargs):
    """``(numpy path's result, compiled path's result)`` of one call; the kernels are on afterwards."""
    kernels.use_kernels(False)
    try:
        reference = function(*args, **kwargs)
    finally:
        kernels.use_kernels(True)
    return reference, function(*args, **kwargs)
