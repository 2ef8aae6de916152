"""The EHL rung of a case file (studies.case_ehl, validation/ladder/ehl.py; docs/your_own_bearing.md)."""
from __future__ import annotations

import math

import pytest

from ballbench.validation import ladder
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
    assert "o-ehl" in ladder.scene_names(case, "o")
    (scene,) = [s for s in ladder.case_scenes(case, "o", top="EHL") if s.name == "o-ehl"]
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
    judged = [o for o in result.outputs if o.family == "analytical" and "film" in o.quantity]
    # the contact ellipses of the state against the grooves' shoulders (docs/truncation.md): well short of them
    (ellipse,) = [o for o in result.outputs if o.quantity.startswith("end of the major semi-axis")]
    assert ellipse.passed and ellipse.value < ellipse.reference
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
    (scene,) = [s for s in ladder.case_scenes(case, "h", top="EHL") if s.name == "h-ehl"]
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
    assert not [o for o in result.outputs if o.family == "analytical" and "film" in o.quantity]  # HD not judged
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
    assert not any(n.endswith("-ehl") for n in ladder.scene_names(plain, "p"))
    assert not any(s.name.endswith("-ehl") for s in ladder.case_scenes(plain, "p"))
    guide = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")  # no [lubricant]
    assert not any(n.endswith("-ehl") for n in ladder.scene_names(guide, "g"))
    oil = case_file.load(OIL)
    assert "o-ehl" not in ladder.scene_names(oil, "o", top="BEM")
    assert not any(s.name == "o-ehl" for s in ladder.case_scenes(oil, "o", top="BEM"))


@pytest.mark.parametrize("kind", ["ball-screw", "linear-guide"])
def test_template_lubricant_block_loads_when_uncommented(kind):
    text = case_file.template(kind)
    assert case_ehl.lubricant(case_file.loads(text, "t.toml")) is None  # commented out: loads as it is
    block = text[text.index("# [lubricant]"):].split("\n\n")[0]
    assert ("groove_velocity" if kind == "linear-guide" else "nut_speed") in block.splitlines()[0]
    lines = [line.removeprefix("# ") for line in block.splitlines() if line.startswith("# ")]
    case = case_file.loads(text + "\n[lubricant]\n" + "\n".join(lines[1:]) + "\n", "t.toml")
    oil = case_ehl.lubricant(case)
    assert (oil.viscosity, oil.density, oil.roughness) == (0.1, 870.0, 0.14e-6)
    assert case_ehl.applies(case) and any(n.endswith("-ehl") for n in ladder.scene_names(case, "t"))


GUIDE = paths.ROOT / "examples" / "compact_linear_guide.toml"
GUIDE_OIL = '\n[lubricant]\nviscosity = "0.1 Pa s"\ndensity = "870 kg/m^3"\nroughness = "0.14 um"\n'


def _guide(deviations=None, speed="200 mm/s", load="40 N", conformity="0.52"):
    text = GUIDE.read_text().replace('"200 mm/s"', f'"{speed}"').replace('"40 N"', f'"{load}"')
    text = text.replace("conformity = 0.52", f"conformity = {conformity}")
    if deviations is not None:
        for key, value in zip(("bottom_left", "bottom_right", "top_right", "top_left"), deviations):
            text = "\n".join(f'{key} = "{value} deg"' if line.startswith(f"{key} =") else line
                             for line in text.splitlines())
    return case_file.loads(text + GUIDE_OIL, "guide.toml")


@pytest.mark.parametrize("bottom, top", [(0.0, 0.0), (5.0, -3.0)])
@pytest.mark.parametrize("speed", ["200 mm/s", "-1.5 m/s"])
def test_guide_entrainment_in_pure_rolling_is_the_rolling_radius_share_of_the_carriage_speed(bottom, top, speed):
    # rail contacts at beta_b = 45 deg + bottom, carriage contacts at beta_t = 45 deg + top, left-right symmetric:
    # pure rolling (lin2017 C_beta = 0) with omega_y = 0, v_B = omega_x R_B cos beta_b, v - v_B = omega_x R_B cos
    # beta_t, so U_e = |v| r_i / (r_b + r_t), r = R_B cos beta the rolling radii: |v| / 2 where they are equal
    case = _guide((bottom, bottom, top, top), speed=speed)
    v = abs(case.guide.groove_velocity)
    r_b, r_t = math.cos(math.radians(45.0 + bottom)), math.cos(math.radians(45.0 + top))
    expected = [v * r_b / (r_b + r_t)] * 2 + [v * r_t / (r_b + r_t)] * 2  # BL, BR, TR, TL
    speeds = case_ehl.guide_entrainment_speeds(case)
    assert speeds.shape == (2, 4)
    for row in speeds:  # both balls (side forces +rho N_y and -rho N_y: rolling does not depend on them)
        for value, hand in zip(row, expected):
            assert math.isclose(value, hand, rel_tol=1e-12)
    if bottom == 0.0:
        assert all(math.isclose(value, v / 2.0, rel_tol=1e-12) for value in speeds.ravel())


def test_guide_entrainment_with_sliding_stays_between_the_rolling_limits():
    # the example's rail grooves 1.5 deg off, both ways (C_beta != 0): lin2017 slides a contact, so U_e departs
    # from v/2, here by under 2 % (1.3 % measured)
    case = _guide()
    speeds = case_ehl.guide_entrainment_speeds(case)
    v = abs(case.guide.groove_velocity)
    assert not all(math.isclose(u, v / 2.0, rel_tol=1e-9) for u in speeds.ravel())
    assert all(abs(u / (v / 2.0) - 1.0) < 0.02 for u in speeds.ravel())


def test_guide_without_speed_has_no_film():
    with pytest.raises(ValueError, match="groove_velocity"):
        case_ehl.guide_entrainment_speeds(_guide(speed="0 m/s"))


def test_lubricated_guide_ehl_scene_at_quick(tmp_path):
    """A light, fast guide (5 N per ball, 2 m/s, conformity 0.54, 0.1 Pa s): the one distinct contact (the most
    loaded of the low-order balls) at its load and its ball's entrainment speed; every self-check met (load balance,
    p >= 0, grid change within 5 % against 64 x 16), Hamrock-Dowson judged within its 15 %."""
    from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES
    from ballbench.lowmodel import bearing_results

    case = _guide(speed="2 m/s", load="5 N", conformity="0.54")
    assert "g-ehl" in ladder.scene_names(case, "g")
    (scene,) = [s for s in ladder.case_scenes(case, "g", top="EHL") if s.name == "g-ehl"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert result.error == ""
    worst = max(bearing_results.guide_result(case).contacts, key=lambda c: c.normal_force)
    label = f"groove, ball {worst.ball} {worst.contact}"
    own = [o for o in result.outputs if o.family == "EHL"]
    assert len(own) == 4 and all(o.passed and o.level == f"{label}, 128 x 32 cells" for o in own), own
    (load,) = [o for o in own if o.quantity.startswith("load balance")]
    assert math.isclose(load.reference, worst.normal_force, rel_tol=1e-12)
    judged = [o for o in result.outputs if o.family == "analytical" and "film" in o.quantity]
    # the contact ellipses of the state against the grooves' shoulders (docs/truncation.md): well short of them
    (ellipse,) = [o for o in result.outputs if o.quantity.startswith("end of the major semi-axis")]
    assert ellipse.passed and ellipse.value < ellipse.reference
    assert len(judged) == 2 and all(o.passed for o in judged), judged
    (table,) = [t for t in result.tables if t[0] == "EHL per distinct contact"]
    header, (row,) = table[1], table[2]
    speed = case_ehl.guide_entrainment_speeds(case)[worst.ball - 1, CONTACT_NAMES.index(worst.contact)]
    assert row[0] == label and math.isclose(float(row[header.index("U_e [m/s]")]), speed, rel_tol=1e-3)
    # the straight groove's radii: R_x = R_B along the track, 1/R_y = 1/R_B - 1/(2 f R_B) across
    r_b = case.guide.ball_radius
    assert math.isclose(float(row[header.index("R_x [mm]")]), r_b * 1e3, rel_tol=1e-3)
    assert math.isclose(float(row[header.index("R_y [mm]")]), 1e3 / (1 / r_b - 1 / (2 * 0.54 * r_b)), rel_tol=1e-3)
