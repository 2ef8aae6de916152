"""The EHL rung of a case file (studies.case_ehl, validation/case_scenes/ehl.py; docs/your_own_bearing.md)."""
from __future__ import annotations

import math

import pytest

from ballbench.validation import case_scenes
from ballbench.validation.cases import case_file
from ballbench.validation.runner import run_scenes
from ballbench.validation.studies import case_ehl
from tests import paths

OIL = paths.ROOT / "examples" / "ball_screw_32x10_oil.toml"


def test_entrainment_speed_without_lead_is_the_ball_bearings():
    # lead 0: a ball bearing with the inner ring (screw) turning at omega against the outer (nut); pure rolling
    # entrains both contacts at U = (omega R_P / 2)(1 - (r_b cos alpha / R_P)^2) (Harris, Rolling Bearing Analysis,
    # the cage speed (omega/2)(1 - gamma cos alpha) times the inner surface speed relative to it)
    case = case_file.loads(OIL.read_text().replace('lead = "10 mm"', 'lead = "0 mm"'), "oil.toml")
    s = case.screw
    gamma = s.ball_radius / s.pitch_radius * math.cos(s.nominal_angle)
    expected = abs(s.nut_speed) * s.pitch_radius / 2.0 * (1.0 - gamma**2)
    speeds = case_ehl.entrainment_speeds(case)
    assert math.isclose(speeds["screw"], expected, rel_tol=1e-12)
    assert math.isclose(speeds["nut"], expected, rel_tol=1e-12)


def test_lubricated_example_ehl_scene_at_quick(tmp_path):
    case = case_file.load(OIL)
    assert "o-ehl" in case_scenes.scene_names(case, "o")
    (scene,) = [s for s in case_scenes.case_scenes(case, "o", top="EHL") if s.name == "o-ehl"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert result.error == ""
    own = [o for o in result.outputs if o.family == "EHL"]
    # load balance, p >= 0 and the grid change of h_c and h_min on the screw side and the nut side, each met
    assert len(own) == 8 and all(o.passed and not o.finding for o in own), own
    grid = [o for o in own if o.quantity.startswith("grid change")]
    assert {(o.level, o.quantity) for o in grid} == {
        (f"{side}, 128 x 32 cells", f"grid change of {q}, 128 x 32 against 64 x 16 cells")
        for side in ("screw side", "nut side") for q in ("central film h_c", "minimum film h_min")}
    # the solve's own grid uncertainty (the coarser level's grid, 64 x 16): 0.5-1.3 % on this example, under the
    # stated 5 % and not zero (a second solve on the same grid would give 0)
    assert all(o.relation == "le" and o.reference == case_ehl.GRID_TOLERANCE == 0.05 for o in grid)
    assert all(1e-3 < o.value < 0.02 for o in grid), grid
    judged = [o for o in result.outputs if o.family == "analytical"]
    assert {(o.level.split(",")[0], o.quantity) for o in judged} == {
        (side, q) for side in ("screw side", "nut side") for q in ("central film h_c", "minimum film h_min")}
    # Hamrock-Dowson against the solve, the project's 15 % for that comparison, a finding when it misses; on this
    # lightly loaded case (Moes M 42-60) it is within it
    assert all(o.finding and o.tolerance == 0.15 and o.passed for o in judged), judged
    for o in judged:  # the judged value is the Hamrock-Dowson film, the reference the solve's (a positive film)
        assert o.reference > 0 and o.value > 0
    (table,) = [t for t in result.tables if t[0] == "EHL per distinct contact"]
    assert [row[0] for row in table[2]] == ["screw side", "nut side"]
    # the film-to-roughness ratio of the file's composite roughness (0.14 um): h_min of the solve over sigma
    header, rows = table[1], table[2]
    column, h_min = header.index("Lambda = h_min / sigma (solve)"), header.index("h_min solve [nm]")
    for row in rows:
        assert math.isclose(float(row[column]), float(row[h_min]) / 140.0, rel_tol=2e-3)


HEAVY = (paths.ROOT / "examples" / "ball_screw_32x10.toml").read_text() + (
    '\n[lubricant]\nviscosity = "0.05 Pa s"\ndensity = "870 kg/m^3"\n')


@pytest.mark.slow
def test_unconverged_film_fails_its_grid_check_and_is_not_judged(tmp_path):
    """The preloaded 32 x 10 screw (300 N) with a 0.05 Pa s oil: on the quick grid (128 x 32) h_min is a quarter of
    the 256 x 64 grid's (the coarser 64 x 16 closes the film, so the finer grid is the second one); the grid
    self-check fails naming the contact, both grids, the change and the tolerance and sends the user to a finer
    level, and Hamrock-Dowson is not judged against that solve."""
    case = case_file.loads(HEAVY, "heavy.toml")
    (scene,) = [s for s in case_scenes.case_scenes(case, "h", top="EHL") if s.name == "h-ehl"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert result.error == ""
    grid = [o for o in result.outputs if o.quantity.startswith("grid change of minimum film")]
    assert [o.level for o in grid] == ["screw side, 128 x 32 cells", "nut side, 128 x 32 cells"]
    for o in grid:
        assert o.status == "fail" and not o.finding and o.value > 1.0, o  # h_min moves by more than 100 %
        side = o.level.split(",")[0]
        assert o.quantity.endswith("128 x 32 against 256 x 64 cells")
        for words in (side, "128 x 32 grid", "256 x 64 grid", f"{100 * o.value:.3g} %", "tolerance 5 %",
                      "not grid-converged", "default level", "--fine"):
            assert words in o.note, (words, o.note)
    assert not [o for o in result.outputs if o.family == "analytical"]  # Hamrock-Dowson not judged
    (table,) = [t for t in result.tables if t[0] == "EHL per distinct contact"]
    column = table[1].index("HD checked")
    assert all(row[column].startswith("no: the solve is not grid-converged") for row in table[2])


def test_roughness_key_is_read_in_si_and_checked():
    assert case_file.load(OIL).screw.lubricant.roughness == 0.14e-6
    text = OIL.read_text().replace('roughness = "0.14 um"', 'roughness = "0.14 mm"')
    with pytest.raises(case_file.CaseFileError, match="roughness"):
        case_file.loads(text, "oil.toml")


def test_no_ehl_scene_without_a_lubricant_or_above_the_levels():
    plain = case_file.load(paths.ROOT / "examples" / "ball_screw_32x10.toml")
    assert plain.screw.lubricant is None and not case_ehl.applies(plain)
    assert not any(n.endswith("-ehl") for n in case_scenes.scene_names(plain, "p"))
    assert not any(s.name.endswith("-ehl") for s in case_scenes.case_scenes(plain, "p"))
    guide = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    assert not any(n.endswith("-ehl") for n in case_scenes.scene_names(guide, "g"))
    oil = case_file.load(OIL)
    assert "o-ehl" not in case_scenes.scene_names(oil, "o", top="BEM")
    assert not any(s.name == "o-ehl" for s in case_scenes.case_scenes(oil, "o", top="BEM"))


def test_template_lubricant_block_loads_when_uncommented():
    text = case_file.template("ball-screw")
    assert case_file.loads(text, "t.toml").screw.lubricant is None  # commented out: loads as it is
    block = text[text.index("# [lubricant]"):].split("\n\n")[0]
    lines = [line.removeprefix("# ") for line in block.splitlines() if line.startswith("# ")]
    oil = case_file.loads(text + "\n[lubricant]\n" + "\n".join(lines[1:]) + "\n", "t.toml").screw.lubricant
    assert (oil.viscosity, oil.density, oil.roughness) == (0.1, 870.0, 0.14e-6)
