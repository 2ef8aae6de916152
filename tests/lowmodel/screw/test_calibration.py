"""The calibrated contact law ``delta = C F^(2/3) + C_b F`` in the ball-screw models (docs/calibration.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from tests import paths

DEG = math.pi / 180.0
C_B = -1.7e-9  # m/N, the order the FE screw/nut fits give (docs/calibration.md)


def _constant(value, reference=None):
    return cal.Constant(value, 0.0, value, value, "", "test", reference=reference)


def _laws(module, bulk=0.0, c_factor=1.0, psi_factor=1.0):
    """Laws of both grooves = Hertz of the module at beta_0 scaled by the factors, plus ``bulk`` [m/N]."""
    out = []
    for body in ("screw", "nut"):
        c, a_unit, _ = screw_contacts.hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                                   module.lead_angle, module.nominal_angle, body,
                                                   module.youngs_modulus, module.poisson_ratio)
        psi = a_unit / module.ball_radius ** (1 / 3)  # lin2019 eq 15
        out.append(cal.ContactLaw(_constant(c * c_factor, c), _constant(bulk), _constant(psi * psi_factor, psi)))
    return screw_contacts.GrooveContactLaws(*out)


@pytest.mark.parametrize("bulk", [0.0, 2e-10, C_B])
def test_law_force_inverts_the_law(bulk):
    c = 1.6e-7
    force = np.array([0.0, 0.5, 10.0, 100.0, 1500.0])
    approach = c * force ** (2 / 3) + bulk * force  # the law itself, written out
    found, slope = cal.law_force(approach, c, bulk)
    np.testing.assert_allclose(found, force, rtol=1e-12, atol=1e-12)
    with np.errstate(divide="ignore"):
        expected = np.where(force > 0, 1.0 / (2 / 3 * c * force ** (-1 / 3) + bulk), 0.0)  # 1 / (dU/dF)
    np.testing.assert_allclose(slope, expected, rtol=1e-12)
    assert np.all(cal.law_force(np.array([-1e-6, 0.0]), c, bulk)[0] == 0.0)
    hertz, _ = cal.law_force(approach, c, 0.0)
    np.testing.assert_allclose(hertz, (np.maximum(approach, 0) / c) ** 1.5, rtol=1e-12)  # lin2019 eq 53


def test_law_force_refuses_an_approach_beyond_the_monotone_range():
    c, bulk = 1.6e-7, C_B
    s_star = 2 * c / (3 * abs(bulk))
    with pytest.raises(ValueError, match="approach must be below"):
        cal.law_force(1.01 * c * s_star**2 / 3, c, bulk)
    with pytest.raises(ValueError, match="hertz_constant"):
        cal.law_force(1e-6, -1.0, 0.0)


@pytest.fixture(scope="module")
def module():
    return screw_contacts.screw_module(oversize=1.5e-6)


def test_hertz_equal_law_reproduces_the_hertz_model(module):
    """Catches a law applied with a wrong factor or to the wrong flanks: C_cal = C_H, C_b = 0 changes nothing."""
    thetas = np.array([0.0, 2.0 * DEG])
    plain = screw_b2b.solve(screw_contacts.ball_contacts(module, thetas), 50.0)
    same = screw_b2b.solve(screw_contacts.ball_contacts(module, thetas, contact_law=_laws(module)), 50.0)
    assert same.b2b_force[0] == pytest.approx(plain.b2b_force[0], rel=1e-10)
    np.testing.assert_allclose(same.normal_force, plain.normal_force, rtol=1e-10)


@pytest.mark.parametrize("bulk, c_factor, psi_factor", [(C_B, 1.0, 1.0), (3e-10, 0.97, 1.02)])
def test_solved_contacts_obey_the_calibrated_law(module, bulk, c_factor, psi_factor):
    """Every loaded contact of the B2B solve has delta = C F^(2/3) + C_b F and a = Psi R^(1/3) F^(1/3) of its groove
    (references from the law's constants, not the model); catches a law ignored or a C_b of the wrong sign."""
    laws = _laws(module, bulk, c_factor, psi_factor)
    contacts = screw_contacts.ball_contacts(module, np.array([0.0, 2.0 * DEG]), contact_law=laws)
    state = screw_b2b.solve(contacts, 50.0)
    plain = screw_contacts.ball_contacts(module, np.array([0.0, 2.0 * DEG]))
    loaded = state.normal_force > 0
    force = state.normal_force
    expected = c_factor * plain.hertz_constant * force ** (2 / 3) + bulk * force
    np.testing.assert_allclose(state.approach[loaded], expected[loaded], rtol=1e-10)
    np.testing.assert_allclose(state.semi_major[loaded],
                               (psi_factor * plain.semi_major_unit * np.cbrt(force))[loaded], rtol=1e-12)
    assert abs(state.input_power - state.total_loss) < 1e-8 * state.total_loss  # power balance


def test_stiffer_law_changes_the_axial_stiffness_and_keeps_the_load_sum(module):
    hertz = ld.axial_stiffness(module, 150.0, 7)
    stiffer = ld.axial_stiffness(module, 150.0, 7, contact_law=_laws(module, C_B))
    assert np.all(np.abs(np.diff(stiffer.shifts)) < np.abs(np.diff(hertz.shifts)))  # C_b < 0: stiffer contacts
    sections = ld.bar_sections(module)
    psi = np.linspace(0.2, 4 * math.pi - 0.2, 20)
    for table in (hertz, stiffer):
        loads = ld.distribute(psi, 1000.0, table, sections, module.lead, module.youngs_modulus)
        assert loads.sum() == pytest.approx(1000.0, rel=1e-9)


def test_laws_from_a_calibration_and_bad_factor(module):
    laws = _laws(module, C_B)
    calibration = cal.Calibration({"screw-groove": laws.screw.constants(), "nut-groove": laws.nut.constants()})
    again = screw_contacts.GrooveContactLaws.from_calibration(calibration)
    assert again.nut.bulk_compliance.value == C_B and again.screw.psi.value == laws.screw.psi.value
    with pytest.raises(KeyError, match="no group"):
        screw_contacts.GrooveContactLaws.from_calibration(cal.Calibration({}))
    with pytest.raises(ValueError, match="within a factor 2"):
        screw_contacts.ball_contacts(module, 0.0, contact_law=_laws(module, 0.0, c_factor=3.0))


DATA = paths.DATA


def test_calibration_effect_screw_scene_from_cached_fe_sweeps(tmp_path, monkeypatch):
    """The scene on the FE load sweeps of fe-hertz-screw / fe-hertz-nut (quick level, cached CSVs) given as a
    calibration file: every check passes and the report shows Hertz beside the calibrated values."""
    from ballbench.validation.studies.calibration import command
    from ballbench.validation.studies.calibration import spec as calibration_spec
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import registry

    spec = tmp_path / "spec.toml"
    spec.write_text("\n".join(
        f'[contact."{group}"]\ndata = "{DATA / f"fe_{body}_quick.load_approach.csv"}"\nball_radius = 2.778e-3\n'
        for group, body in (("screw-groove", "screw"), ("nut-groove", "nut"))))
    path, calibration = calibration_spec.run_spec(spec, tmp_path / "c.json", log=lambda *_: None)
    assert calibration.value("nut-groove", "bulk_compliance") < 0  # FE: the finite bodies are stiffer than Hertz
    monkeypatch.setenv(command.CALIBRATION_ENV, str(path))
    result = run_scene(registry()["calibration-effect-screw"], "quick", tmp_path)
    assert result.passed, [(o.quantity, o.value, o.reference) for o in result.outputs if not o.passed] or result.error
    text = " ".join(result.notes)
    assert "calibrated same oversize" in text and "Load distribution" in text
    rows = (tmp_path / "calibration-effect-screw" / "load_distribution.csv").read_text().splitlines()
    assert len(rows) == 38
