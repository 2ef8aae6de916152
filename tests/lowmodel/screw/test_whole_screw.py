"""Static load distribution and the whole-screw simulation (lin2019 Sec 3.4)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import whole_screw as ws


@pytest.fixture(scope="module")
def module():
    return screw_contacts.screw_module(oversize=1.7e-6)


@pytest.fixture(scope="module")
def stiffness(module):
    return ld.axial_stiffness(module, 60.0, points=7)


def test_axial_stiffness_is_the_single_ball_model(module, stiffness):
    state = sb.solve(screw_contacts.ball_contacts(module, 0.0), 33.0)
    assert stiffness.shift(33.0) == pytest.approx(state.nut_shift, rel=2e-3)   # pchip between 7 nodes
    assert stiffness.load(stiffness.shift(20.0)) == pytest.approx(20.0, rel=1e-9)


def test_distribution_compatibility_and_balance(module, stiffness):
    sections = ld.bar_sections(module)
    psi = np.sort(np.random.default_rng(1).uniform(0.0, 4 * math.pi, 12))
    loads = ld.distribute(psi, 400.0, stiffness, sections, module.lead, module.youngs_modulus)
    assert loads.sum() == pytest.approx(400.0, rel=1e-10)
    assert np.all(np.diff(loads) < 0.0)          # the balls nearest the loaded end carry most
    # compatibility, recomputed by a plain loop: shift difference = bar shortening between the balls
    z = module.lead * psi / (2 * math.pi)
    e = module.youngs_modulus
    handed = 0.0
    for j in range(1, len(psi)):
        handed += loads[j - 1]
        strain = (400.0 - handed) / (e * sections.screw_area) + handed / (e * sections.nut_area)
        expected = stiffness.shift(loads[j]) - stiffness.shift(loads[j - 1])
        assert expected == pytest.approx(strain * (z[j] - z[j - 1]), rel=1e-6)
    stiff_bars = ld.BarSections(1e6, 1e6)
    equal = ld.distribute(psi, 400.0, stiffness, stiff_bars, module.lead, module.youngs_modulus)
    np.testing.assert_allclose(equal, 400.0 / 12, rtol=1e-6)


def test_lead_error_shifts_the_load_to_the_loaded_end(module, stiffness):
    sections = ld.bar_sections(module)
    psi = np.linspace(0.2, 12.0, 10)
    base = ld.distribute(psi, 300.0, stiffness, sections, module.lead, module.youngs_modulus)
    error = ld.distribute(psi, 300.0, stiffness, sections, module.lead, module.youngs_modulus, lead_error=2e-7)
    assert error.sum() == pytest.approx(300.0, rel=1e-10)
    assert error[0] > base[0] and error[-1] < base[-1]
    # compatibility with the lead error, recomputed by a plain loop (as in the test above)
    z = module.lead * psi / (2 * math.pi)
    e = module.youngs_modulus
    handed = 0.0
    for j in range(1, len(psi)):
        handed += error[j - 1]
        strain = (300.0 - handed) / (e * sections.screw_area) + handed / (e * sections.nut_area)
        expected = strain * (z[j] - z[j - 1]) + 2e-7 * (psi[j] - psi[j - 1]) / (2 * math.pi)
        got = stiffness.shift(error[j]) - stiffness.shift(error[j - 1])
        assert got == pytest.approx(expected, rel=1e-6)


def test_short_simulation(module, stiffness):
    history = ws.simulate(module, n_balls=12, axial_load=300.0, duration=0.05, steps=5, stiffness=stiffness)
    assert history.time.shape == (6,)
    assert np.all(history.power_error < 1e-8)
    assert np.all(history.b2b_force >= 0.0)
    np.testing.assert_allclose(history.spacing.sum(axis=1), 4 * math.pi, rtol=1e-12)
    assert np.all(history.spacing >= history.contact_spacing * (1 - 1e-12))
    assert np.all(history.groove_torque > 0.0)
    # touching pairs have (numerically) equal orbit speeds
    touching = history.b2b_force > 0.0
    ahead = np.roll(history.orbit_speed, -1, axis=1)
    assert np.all(np.abs((ahead - history.orbit_speed)[touching]) < 1e-8 * module.nut_speed)


def test_bad_input(module, stiffness):
    with pytest.raises(ValueError, match="n_balls"):
        ws.simulate(module, n_balls=50, steps=1, stiffness=stiffness)
    with pytest.raises(ValueError, match="total_load"):
        ld.distribute([0.1, 0.2], 1e4, stiffness, ld.bar_sections(module), module.lead, module.youngs_modulus)
    with pytest.raises(ValueError, match="nut_outer_radius"):
        ld.bar_sections(module, nut_outer_radius=0.01)
