"""validation.show: the screenshots of an FE scene are written (coarse level)."""
from __future__ import annotations

import pytest

from ballbench.validation import show


def test_show_writes_pngs(tmp_path):
    paths = show.show("fe-hertz-ball-ball", tmp_path, fidelity="quick")
    assert [p.name for p in paths] == ["pressure.png", "displacement.png"]
    for path in paths:
        assert path.exists() and path.stat().st_size > 10_000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_show_refuses_other_scenes(tmp_path):
    with pytest.raises(ValueError, match="fe-hertz"):
        show.show("hertz-sphere-flat", tmp_path)
    with pytest.raises(ValueError, match="fidelity"):
        show.show("fe-hertz-flat", tmp_path, fidelity="ultra")


@pytest.mark.slow
def test_show_fourpoint_module_writes_pngs(tmp_path):
    # FE four-point module at the quick level (111k DOFs) plus one solve for the displacement field
    paths = show.show("fe-b2b-linear-a", tmp_path, fidelity="quick")
    assert [p.name for p in paths] == ["pressure.png", "stress.png"]
    for path in paths:
        assert path.exists() and path.stat().st_size > 10_000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
