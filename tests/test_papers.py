"""Published inputs as data (validation.papers): SI units, frozen, read by the scenes (issue 8 item 5)."""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest

from ballbench.validation.papers import lin2017, lin2019, wang2022

ROOT = Path(__file__).resolve().parents[1]


def test_lin2019_tables_in_si():
    t1 = lin2019.TABLE1
    assert (t1.ball_radius, t1.groove_velocity, t1.youngs_modulus) == (0.005, 0.01, 2.1e11)
    assert lin2019.CASE.theta == math.radians(2.0) and lin2019.CASE.side_force_ratio == -0.6
    t4 = lin2019.TABLE4
    assert (t4.ball_radius, t4.pitch_radius, t4.lead) == (2.778e-3, 16.5e-3, 20e-3)
    assert t4.youngs_modulus == 2.1e11  # "210 N/mm^2" is a typo for 210 GPa


def test_wang2022_radii_are_half_the_printed_diameters():
    a1 = wang2022.TABLE_A1
    assert a1.pitch_radius == pytest.approx(20.7e-3, rel=1e-15)
    assert a1.ball_radius == pytest.approx(3.175e-3, rel=1e-15)
    assert a1.screw_speed == pytest.approx(2000 * 2 * math.pi / 60, rel=1e-15)


@pytest.mark.parametrize("table", [lin2019.TABLE1, lin2019.TABLE4, lin2019.CASE, lin2019.PRINTED, lin2017.CASES,
                                   wang2022.TABLE_A1, wang2022.TABLE1, wang2022.TABLE2])
def test_tables_are_frozen(table):
    field = dataclasses.fields(table)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(table, field, 0.0)


def test_printed_tables_are_read_only():
    with pytest.raises(TypeError):
        wang2022.TABLE2.wei_scalars["U_A"] = 0.0


def test_lin2017_case_angles():
    angles = lin2017.case1_angles([0.0, 0.1])
    assert angles.shape == (2, 4)
    assert angles[1] == pytest.approx([math.pi / 4, math.pi / 4, math.pi / 4 + 0.1, math.pi / 4 - 0.1])
    assert lin2017.case2_angles(0.1) == pytest.approx([math.pi / 4] * 2 + [math.pi / 4 + 0.1, math.pi / 4])


def test_fe_scenes_are_data_and_names_are_not_parsed():
    from ballbench.validation.scene import registry
    from ballbench.validation.scenes import fe_hertz

    names = {entry.name for entry in fe_hertz.FE_SCENES}
    assert names == {name for name in registry() if name.startswith("fe-")}
    assert fe_hertz.fe_scene("fe-hertz-groove-052").conformity == 0.52
    with pytest.raises(ValueError, match="FE scenes"):
        fe_hertz.fe_scene("hertz-sphere-flat")
    with pytest.raises(ValueError, match="pair"):
        fe_hertz.FeScene("x", "x", "cylinder", fe_hertz.LEVELS)
    with pytest.raises(ValueError, match="conformity"):
        fe_hertz.FeScene("x", "x", "groove", fe_hertz.LEVELS)
    source = (ROOT / "validation" / "scenes" / "fe_hertz.py").read_text()
    assert "scene_name[" not in source and "int(scene_name" not in source


def test_table1_constants_declared_once():
    """No scene module re-declares lin2019 Table 1's E, Psi or the Table 3 forces as literals."""
    for path in (ROOT / "validation" / "scenes").glob("*.py"):
        code = "\n".join(line.split("#")[0] for line in path.read_text().splitlines())
        for literal in ("2.1e11", "5.307e-4", "reference=4.01", "reference=3.96", "reference=3.74",
                        "41.4e-3", "6.35e-3"):
            assert literal not in code, (path.name, literal)
