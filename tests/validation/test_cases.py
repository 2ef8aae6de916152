"""The papers' setups as data (validation.cases) and their printed results (validation.references.published):
SI units, frozen, declared once, complete enough to build the models."""
from __future__ import annotations

import dataclasses
import math

import pytest

from ballbench.lowmodel.bearing import BallScrew, Material
from ballbench.validation.cases import (ContactCase, ContactFe, LinearGuideCase, MeshLevels, PairLevel, lin2017,
                                        lin2019, sun2021, wang2022)
from ballbench.validation.references.published import lin2019 as printed_lin2019
from ballbench.validation.references.published import wang2022 as printed_wang2022
from tests import paths

ROOT = paths.ROOT


def test_lin2019_cases_in_si():
    guide = lin2019.GUIDE
    assert (guide.ball_radius, guide.groove_velocity, guide.material.youngs_modulus) == (0.005, 0.01, 2.1e11)
    assert lin2019.TABLE3_A.theta == math.radians(2.0) and lin2019.TABLE3_A.side_force_ratio == -0.6
    assert lin2019.TABLE3_B.deviations == (-lin2019.THETA, lin2019.THETA, -lin2019.THETA, lin2019.THETA)
    screw = lin2019.SCREW
    assert (screw.ball_radius, screw.pitch_radius, screw.lead) == (2.778e-3, 16.5e-3, 20e-3)
    assert screw.material.youngs_modulus == 2.1e11  # "210 N/mm^2" is a typo for 210 GPa
    assert lin2019.TABLE5_B.deviations == (0.0, math.radians(3.0)) and lin2019.TABLE5_B.axial_load == 50.0


def test_the_fitted_oversize_is_what_its_fit_gives():
    """cases.lin2019.SCREW carries the oversize fitted on Table 5 (a)'s printed low-order force; fitting again
    (studies.screw_two_ball.fit_oversize, the fit OVERSIZE_FIT describes) gives it to the fit's tolerance 1e-12 m."""
    from ballbench.validation.studies.screw_two_ball import fit_oversize, two_ball

    refit = fit_oversize(lin2019.TABLE5_A, printed_lin2019.TABLE5_A.f_b2b_numerical)
    assert abs(refit - lin2019.SCREW.oversize) <= 1e-12
    assert "1.92 N" in lin2019.OVERSIZE_FIT.target and "brentq" in lin2019.OVERSIZE_FIT.method
    force = two_ball(lin2019.TABLE5_A)[1].b2b_force[0]
    assert force == pytest.approx(printed_lin2019.TABLE5_A.f_b2b_numerical, abs=1e-6)


def test_wang2022_radii_are_half_the_printed_diameters():
    screw = wang2022.SCREW
    assert screw.pitch_radius == pytest.approx(20.7e-3, rel=1e-15)
    assert screw.ball_radius == pytest.approx(3.175e-3, rel=1e-15)
    assert screw.screw_speed == pytest.approx(2000 * 2 * math.pi / 60, rel=1e-15)
    assert math.degrees(screw.lead_angle) == pytest.approx(math.degrees(printed_wang2022.LEAD_ANGLE), abs=0.005)


def test_sun2021_screw_and_its_derived_values():
    screw = sun2021.SCREW
    assert screw.conformity == sun2021.GROOVE_RADIUS / (2.0 * sun2021.BALL_RADIUS)
    assert screw.screw_speed * screw.pitch_radius == pytest.approx(sun2021.SURFACE_SPEED, rel=1e-15)
    assert math.degrees(screw.lead_angle) == pytest.approx(5.68, abs=0.005)  # the printed helix angle
    assert screw.material.contact_modulus == pytest.approx(200e9 / (2 * (1 - 0.3**2)), rel=1e-15)


@pytest.mark.parametrize("value", [lin2019.GUIDE, lin2019.SCREW, lin2019.TABLE3_A, lin2019.TABLE5_A, lin2017.CASES,
                                   wang2022.SCREW, sun2021.SCREW, lin2019.CONTACT_GROOVE_056,
                                   printed_lin2019.PRINTED, printed_wang2022.TABLE1, printed_wang2022.TABLE2])
def test_cases_and_references_are_frozen(value):
    field = dataclasses.fields(value)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(value, field, 0.0)


def test_printed_tables_are_read_only():
    with pytest.raises(TypeError):
        printed_wang2022.TABLE2.wei_scalars["U_A"] = 0.0


def test_lin2017_case_angles():
    angles = lin2017.case1_angles([0.0, 0.1])
    assert angles.shape == (2, 4)
    assert angles[1] == pytest.approx([math.pi / 4, math.pi / 4, math.pi / 4 + 0.1, math.pi / 4 - 0.1])
    assert lin2017.case2_angles(0.1) == pytest.approx([math.pi / 4] * 2 + [math.pi / 4 + 0.1, math.pi / 4])


def test_bad_case_data_is_refused_with_the_field_named():
    with pytest.raises(ValueError, match="youngs_modulus"):
        Material(-1.0, 0.3)
    with pytest.raises(ValueError, match="poisson_ratio"):
        Material(2e11, 0.6)
    with pytest.raises(ValueError, match="conformity"):
        ContactCase("groove", 5e-3, lin2019.STEEL, 100.0, name="x")
    with pytest.raises(ValueError, match="pair"):
        ContactCase("cylinder", 5e-3, lin2019.STEEL, 100.0, name="x")
    with pytest.raises(ValueError, match="screw"):
        ContactCase("nut", 5e-3, lin2019.STEEL, 100.0, name="x")
    with pytest.raises(ValueError, match="deviations"):
        LinearGuideCase(lin2019.GUIDE, 100.0, 0.0, (0.0, 0.0), name="x")
    with pytest.raises(ValueError, match="at least one level"):
        MeshLevels(quick=(), default=(PairLevel(6, 1.3),), fine=(PairLevel(6, 1.3),))
    with pytest.raises(ValueError, match="zone"):
        ContactFe(lin2019.PAIR_LEVELS, "ellipse", (1.2, 1.3))
    with pytest.raises(ValueError, match="fidelity"):
        lin2019.PAIR_LEVELS["ultra"]
    with pytest.raises(ValueError, match="conformity"):
        from ballbench.lowmodel.screw.contacts import module

        module(BallScrew(ball_radius=3e-3, pitch_radius=20e-3, lead=10e-3, nominal_angle=math.pi / 4))


def test_contact_scenes_run_their_case():
    """The FE contact scenes carry their ContactCase (what calibrate and show read); no name is parsed."""
    from ballbench.validation.studies.calibration.fe_laws import fe_contact_scenes
    from ballbench.validation.scene import registry

    cases = fe_contact_scenes()
    assert cases["fe-hertz-groove-052"].conformity == 0.52
    assert cases["fe-hertz-nut"].screw is lin2019.SCREW
    assert {name for name, entry in registry().items() if isinstance(entry.case, ContactCase)} == set(cases)
    for name in cases:
        assert registry()[name].show is not None, name
    assert registry()["fe-b2b-screw-a"].case is lin2019.TABLE5_A


def test_paper_numbers_declared_once():
    """No scene, study or figure module re-declares a paper's input or printed result as a literal."""
    for folder in ("scenes", "studies", "figures", "ladder"):
        for path in (ROOT / "validation" / folder).rglob("*.py"):
            code = "\n".join(line.split("#")[0] for line in path.read_text().splitlines())
            for literal in ("2.1e11", "200e9", "5.307e-4", "reference=4.01", "reference=3.96", "reference=3.74",
                            "41.4e-3", "6.35e-3", "2.778e-3", "16.5e-3", "2.9765e-3", "0.50265"):
                assert literal not in code, (path.name, literal)
