"""The calibration scenes at the quick level: calibration-roundtrip records all 13 checks (6 constants, the file round
trip, 6 coverages); calibration-effect-screw without a calibration file fits the laws to the FE load sweeps of both
grooves (~4 min, slow).  Pass/fail: tests/validation/test_scenes.py."""
from __future__ import annotations

import pytest

from tests.scene_support import scene_param


@pytest.mark.parametrize("name", [scene_param("calibration-roundtrip")])
def test_roundtrip_scene_records_every_check(name, quick_scene):
    assert len(quick_scene(name).result.outputs) == 13  # 6 constants, the file round trip, 6 coverages


@pytest.mark.parametrize("name", [scene_param("calibration-effect-screw")])
def test_effect_screw_scene_fits_to_the_fe_sweeps(name, quick_scene):
    assert "fe-hertz-nut quick level" in " ".join(quick_scene(name).result.notes)
