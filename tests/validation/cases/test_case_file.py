"""Case files (validation/cases/case_file.py): templates load, every mistake is named before any work (file, line,
key, range, did you mean), the paper cases shipped as files read back to the values lin2019 prints."""
import math

import pytest

from ballbench.validation.cases import case_file, lin2019
from ballbench.validation.cases.case import BallScrewCase, ContactCase, LinearGuideCase


@pytest.mark.parametrize("kind, cls", [("linear-guide", LinearGuideCase), ("ball-screw", BallScrewCase),
                                       ("contact", ContactCase)])
def test_every_template_loads_as_its_case(kind, cls):
    case = case_file.loads(case_file.template(kind), f"{kind}.toml")
    assert isinstance(case, cls)


def _guide(edit: str, new: str) -> str:
    text = case_file.template("linear-guide")
    assert edit in text
    return text.replace(edit, new)


def test_template_values_arrive_in_si():
    case = case_file.loads(_guide('ball_radius = "1.5875 mm"', 'ball_radius = "3.175 mm"'))
    assert case.guide.ball_radius == 3.175e-3
    assert case.guide.nominal_angle == pytest.approx(math.pi / 4, rel=1e-15)
    assert case.vertical_force == 50.0


@pytest.mark.parametrize("edit, new, words", [
    ('ball_radius = "1.5875 mm"', "ball_radius = 3.175", ["guide.ball_radius", "unit"]),       # unit missing
    ('ball_radius = "1.5875 mm"', 'ball_radius = "3.175 m"', ["guide.ball_radius", "3.175e-3"]),  # mm for m
    ('nominal_angle = "45 deg"', "nominal_angle = 45", ["guide.nominal_angle", "unit"]),
    ("conformity = 0.52", "conformity = 0.5", ["guide.conformity"]),
    ("conformity = 0.52", "conformaty = 0.52", ["conformaty", "did you mean 'conformity'"]),
    ('vertical_force = "50 N"', 'vertical_force = "-50 N"', ["load.vertical_force"]),
])
def test_mistakes_name_file_line_and_key(edit, new, words):
    with pytest.raises(case_file.CaseFileError) as error:
        case_file.loads(_guide(edit, new), "g.toml")
    message = str(error.value)
    assert message.startswith("g.toml, line "), message
    for word in words:
        assert word in message, message


def test_paper_cases_read_the_printed_values():
    # the shipped files against lin2019's print (Table 1, Sec 2.4; Table 4, Sec 3.3), not against the loader
    guide = case_file.load(lin2019.FILES / "lin2019-table3-a.toml")
    assert (guide.guide.ball_radius, guide.guide.conformity, guide.guide.friction_coefficient) == (5e-3, 0.56, 0.1)
    assert guide.guide.nominal_angle == pytest.approx(math.radians(45), rel=1e-15)
    assert guide.guide.groove_velocity == pytest.approx(10e-3, rel=1e-15)
    assert (guide.guide.material.youngs_modulus, guide.guide.material.poisson_ratio) == (2.1e11, 0.28)
    assert (guide.vertical_force, guide.side_force_ratio) == (100.0, -0.6)
    assert guide.theta == pytest.approx(math.radians(2), rel=1e-15)
    screw = case_file.load(lin2019.FILES / "lin2019-table5-a.toml")
    assert (screw.screw.ball_radius, screw.screw.pitch_radius, screw.screw.lead) == (2.778e-3, 16.5e-3, 20e-3)
    assert screw.screw.nut_speed == pytest.approx(2 * math.pi, rel=1e-15)
    assert screw.axial_load == 50.0
    assert guide == lin2019.TABLE3_A and screw == lin2019.TABLE5_A  # what the paper scenes run


def _screw(edit: str, new: str) -> str:
    text = case_file.template("ball-screw")
    assert edit in text
    return text.replace(edit, new)


def _refused(text: str, line: int, *words: str) -> str:
    """The CaseFileError of ``text`` (as file "c.toml"): a ValueError of one line naming the file, ``line`` and
    ``words`` (the key, the range)."""
    with pytest.raises(case_file.CaseFileError) as error:
        case_file.loads(text, "c.toml")
    message = str(error.value)
    assert message.startswith(f"c.toml, line {line}: "), message
    assert "\n" not in message, message
    for word in words:
        assert word in message, message
    return message


def _line(text: str, start: str) -> int:
    return next(k for k, line in enumerate(text.splitlines(), start=1) if line.startswith(start))


@pytest.mark.parametrize("value", ['{ value = ' + "9" * 400 + ', unit = "mm" }', '"1e999999999 mm"',
                                   '"-1e999999999 mm"', '{ value = -' + "9" * 400 + ', unit = "mm" }'])
def test_a_number_beyond_the_float_range_is_named(value):
    # a 400-digit integer raised a bare OverflowError, "1e999999999 mm" decimal.Overflow
    text = _guide('ball_radius = "1.5875 mm"', f"ball_radius = {value}")
    _refused(text, _line(text, "ball_radius"), "guide.ball_radius", "float range")


@pytest.mark.parametrize("key", ["h_max", "fine_radius"])
@pytest.mark.parametrize("value", ['"-1 mm"', '"0 mm"'])
def test_fe_level_sizes_must_be_positive(key, value):
    # loaded silently before: a mesh level with a negative or zero element size or fine zone
    levels = "\n".join(f'{f} = [{{ h_contact = "30 um", growth = 1.4, {key} = {value} }}]'
                       for f in ("quick", "default", "fine"))
    text = case_file.template("linear-guide") + "\n[fe]\n" + levels + "\n"
    _refused(text, _line(text, "quick ="), f"fe.quick[0].{key}", "> 0")


def test_fe_level_sizes_load_when_positive():
    levels = "\n".join(f'{f} = [{{ h_contact = "30 um", growth = 1.4, h_max = "0.5 mm", fine_radius = "0.2 mm" }}]'
                       for f in ("quick", "default", "fine"))
    case = case_file.loads(case_file.template("linear-guide") + "\n[fe]\n" + levels + "\n", "c.toml")
    assert (case.fe.levels.quick[0].h_max, case.fe.levels.quick[0].fine_radius) == (5e-4, 2e-4)


@pytest.mark.parametrize("value", ['"1 1/s"', '"60 1/min"'])
def test_an_angular_speed_says_what_turns(value):
    # "1/s" was read as rad/s while "1/min" was refused: both are refused alike, naming the units a speed takes
    text = _screw('nut_speed = "1 rev/s"', f"nut_speed = {value}")
    _refused(text, _line(text, "nut_speed"), "screw.nut_speed", "rad/s", "rev/s", "rpm")


@pytest.mark.parametrize("kind, edit, new, words", [
    ("linear-guide", "friction_coefficient = 0.1", "friction_coefficient = 0", ["guide.friction_coefficient", "> 0"]),
    ("linear-guide", 'groove_velocity = "100 mm/s"', 'groove_velocity = "0 mm/s"', ["guide.groove_velocity",
                                                                                    "nonzero"]),
    ("linear-guide", "side_force_ratio = -0.6", "side_force_ratio = -1.5", ["load.side_force_ratio", "lin2017 eq 37",
                                                                          "(-0.932515, 1)"]),
    ("linear-guide", "side_force_ratio = -0.6", "side_force_ratio = 1.0", ["load.side_force_ratio", "ball 1"]),
    ("ball-screw", "friction_coefficient = 0.1", "friction_coefficient = 0", ["screw.friction_coefficient",
                                                                            "(0, 2]"]),
    ("ball-screw", 'nut_speed = "1 rev/s"', 'nut_speed = "0 rpm"', ["screw.nut_speed", "nonzero"]),
    ("ball-screw", 'axial_load = "100 N"', 'axial_load = "1e9 N"', ["load.axial_load", "[0, 10000000] N"]),
    ("ball-screw", 'pitch_radius = "16.6 mm"', 'pitch_radius = "3 mm"', ["screw.pitch_radius",
                                                                        "exceed the groove radius"]),
])
def test_what_the_models_refuse_is_refused_at_load_time(kind, edit, new, words):
    # loaded before, refused only by ballbench.friction, without file or line: the loader calls the models' own
    # checks (lowmodel.model_inputs, the plausible axial load of lowmodel.checks.PLAUSIBLE)
    text = case_file.template(kind)
    assert edit in text
    text = text.replace(edit, new)
    _refused(text, _line(text, new.split(" =")[0]), *words)


def test_the_side_force_range_is_the_models():
    # the bound of load.side_force_ratio is that of lin2017 eq 37 at beta_0 + deviations: tan(43 deg) below,
    # 1 = tan(45 deg) above for the template's (-2, 2, 0, 0) deg; just inside loads
    inside = -0.99 * math.tan(math.radians(43.0))
    case = case_file.loads(_guide("side_force_ratio = -0.6", f"side_force_ratio = {inside!r}"), "c.toml")
    assert case.side_force_ratio == inside
    text = _guide("side_force_ratio = -0.6", f"side_force_ratio = {-1.01 * math.tan(math.radians(43.0))!r}")
    _refused(text, _line(text, "side_force_ratio"), "ball 1")


def test_the_template_says_what_the_models_take():
    guide, screw = case_file.template("linear-guide"), case_file.template("ball-screw")
    assert "mu, Coulomb friction of every contact; > 0" in guide
    assert "mu, Coulomb friction of every contact; in (0, 2]" in screw
    assert "against the rail; nonzero" in guide
