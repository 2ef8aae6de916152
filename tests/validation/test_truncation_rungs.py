"""Heavy contacts in the ladder (docs/truncation.md): the FE module sized from the contact ellipse, a truncated
ellipse named by every rung (DOES NOT APPLY or a finding), never a ValueError."""
from __future__ import annotations

import math

from ballbench.lowmodel import bearing_results, truncation
from ballbench.validation import ladder
from ballbench.validation.cases import case_file
from ballbench.validation.ladder import rungs
from ballbench.validation.ladder.common import truncations
from ballbench.validation.runner import run_scenes
from tests import paths


def _template_guide(tmp_path, force: str):
    """``ballbench init linear-guide`` (1/8-inch balls, f 0.52, BL/BR 43/47 deg) at ``vertical_force = force``."""
    text = case_file.template("linear-guide")
    assert 'vertical_force = "' in text
    start = text.index('vertical_force = "') + len('vertical_force = "')
    text = text[:start] + force + text[text.index('"', start):]
    path = tmp_path / "heavy.toml"
    path.write_text(text)
    return case_file.load(path)


def test_module_fe_sizes_caps_and_lands_from_a_heavy_ellipse(tmp_path):
    # 450 N: ball 2 BR's ellipse ends 0.2 deg before the convention's shoulder (not truncated), a / R_B = 0.476:
    # the default 30 deg cap and the 0.25 R_B land left the ellipse's zone reaching past the flank (the FE's
    # ValueError "a ball quadrature point projects outside its flank")
    case = _template_guide(tmp_path, "450 N")
    found = truncations(case)
    assert found and not any(t.truncated for t in found)
    fe = rungs.module_fe(case).fe
    radius, conformity = case.guide.ball_radius, case.guide.conformity
    result = bearing_results.guide_result(case)
    a_max = max(c.a for c in result.contacts if c.normal_force > 0)
    assert fe.min_cap_angle >= math.asin(rungs.CAP_MARGIN * a_max / radius) - 1e-12
    assert fe.land_depth < truncation.SHOULDER_DEPTH
    for t in found:  # every flank of the module runs past its ellipse's zone (CAP_MARGIN a)
        zone_end = t.contact_angle + math.asin(rungs.CAP_MARGIN * t.a / radius)
        assert truncation.shoulder_angle(radius, conformity, t.rigid_angle, fe.land_depth) >= zone_end - 1e-12


def test_module_fe_keeps_the_sizes_of_scenes_whose_ellipses_fit():
    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    fe = rungs.module_fe(case).fe
    assert fe.min_cap_angle is None and fe.land_depth is None  # the builders' defaults: the same meshes as before


def test_truncated_ellipse_is_named_by_the_rungs(tmp_path):
    # 500 N: ball 2 BR's ellipse ends at 47 + 29.6 = 76.6 deg, past the shoulder at 75.6 deg
    case = _template_guide(tmp_path, "500 N")
    scenes = {s.name: s for s in ladder.case_scenes(case, "g", top="FE-informed")}
    results, _ = run_scenes([scenes["g-b2b-fe"], scenes["g-balls"]], "quick", tmp_path / "out", show_progress=False)
    fe, balls = results
    assert fe.status() == "not applicable", fe.error  # before: ValueError ... projects outside its flank
    assert "ball 2 BR" in fe.not_applicable and "76.6 deg" in fe.not_applicable and "75.6 deg" in fe.not_applicable
    (check,) = [o for o in balls.outputs if "major semi-axis" in o.quantity]
    assert not check.passed and "ball 2 BR" in check.quantity
    assert math.degrees(check.value) > math.degrees(check.reference)
