"""lowmodel.screw.preload: the preload loss of four-point ball-screw contacts (docs/ball_screw.md, 'Preload loss')."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from ballbench.lowmodel.screw import contacts as sc
from ballbench.lowmodel.screw import preload


def _nominal(oversize: float, pitch_radius: float = 0.02):
    module = sc.screw_module(ball_radius=3.175e-3, conformity=0.54, pitch_radius=pitch_radius, lead=0.01,
                             nominal_angle=math.radians(45.0), oversize=oversize)
    return sc.ball_contacts(module, 0.0)


@pytest.mark.parametrize("oversize, tolerance", [(0.1e-6, 2e-3), (0.5e-6, 6e-3)])
def test_the_preload_loss_of_a_nominal_ball_is_the_preloaded_pair_s_closed_form(oversize, tolerance):
    # small oversize: the closed form (4 delta_0 / (C_S + C_N))^(3/2) sin beta_0 cos alpha, from the linearised
    # geometry; the exact arcs depart from it like oversize / groove size
    contacts = _nominal(oversize)
    loss = preload.preload_loss(contacts)
    assert loss.axial_load == pytest.approx(preload.nominal_preload_loss(contacts), rel=tolerance)
    assert loss.contact in ("SR", "NL")  # the receding diagonal unloads, not the loaded SL-NR
    forces = loss.normal_forces[0]
    # the loaded diagonal carries 2^(3/2) times its preload force (C_S + C_N) F^(2/3) = 2 delta_0 (eq 53)
    preload_force = (2 * oversize / (contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2])) ** 1.5
    assert forces[0] == pytest.approx(2 ** 1.5 * preload_force, rel=3 * tolerance)
    assert min(forces[1], forces[3]) == pytest.approx(0.0, abs=1e-6 * forces[0])


def test_the_preload_loss_grows_like_the_oversize_to_the_three_halves():
    small, large = (preload.preload_loss(_nominal(o)).axial_load for o in (0.2e-6, 0.4e-6))
    assert large / small == pytest.approx(2 ** 1.5, rel=5e-3)


def test_a_ball_without_oversize_loses_its_preload_at_once():
    loss = preload.preload_loss(_nominal(0.0))
    assert loss.axial_load == 0.0 and loss.contact in ("SR", "NL")


def test_two_balls_under_one_nut_shift_add_their_loads():
    contacts = _nominal(1e-6)
    one = preload.preload_loss(contacts)
    module = contacts.module
    two = preload.preload_loss(sc.ball_contacts(module, np.array([0.0, 0.0])))
    assert two.axial_load == pytest.approx(2 * one.axial_load, rel=1e-9)
    assert two.nut_shift == pytest.approx(one.nut_shift, rel=1e-9)
    # a deviated ball loses a contact at another shift: the pair's loss is not twice the nominal one
    deviated = preload.preload_loss(sc.ball_contacts(replace(module), np.array([0.0, math.radians(2.0)])))
    assert deviated.axial_load != pytest.approx(2 * one.axial_load, rel=1e-3)


# ---------------------------------------------------------------- frictionless_statics at a given axial load
def _independent_balance(contacts, state):
    """Each ball's sum_i F_i e_i [N] and the screw flanks' axial force [N], rebuilt from the arc centres."""
    module = contacts.module
    arcs = contacts.arc_centres.copy()
    arcs[:, :, 1] += state.nut_shift * math.cos(module.lead_angle) * np.array([0.0, 0.0, 1.0, 1.0])
    d = state.centres[:, None, :] - arcs
    e = d / np.linalg.norm(d, axis=-1)[..., None]
    approach = np.linalg.norm(d, axis=-1) + module.ball_radius + module.oversize - module.groove_radius
    balance = np.sum(state.normal_force[..., None] * e, axis=1)
    axial = -math.cos(module.lead_angle) * np.sum(state.normal_force[:, :2] * e[:, :2, 1])
    return approach, balance, axial


def test_at_the_preload_loss_the_statics_are_those_of_preload_loss():
    # the four-point frictionless statics preload_loss solves, found again from its axial load
    contacts = sc.ball_contacts(_nominal(1.5e-6).module, np.array([0.0, math.radians(2.0)]))
    loss = preload.preload_loss(contacts)
    state = preload.frictionless_statics(contacts, loss.axial_load)
    assert state.nut_shift == pytest.approx(loss.nut_shift, rel=1e-7)
    np.testing.assert_allclose(state.normal_force, loss.normal_forces, rtol=0, atol=1e-6 * loss.normal_forces.max())
    assert state.approach.min() == pytest.approx(0.0, abs=1e-6 * contacts.module.oversize)


def test_below_the_preload_loss_a_nominal_ball_is_the_preloaded_pair():
    # small oversize: each diagonal (C_S + C_N) F^(2/3) = 2 delta_0 +- s, F_a = (F_+ - F_-) sin beta_0 cos alpha
    contacts = _nominal(0.1e-6)
    loss = preload.preload_loss(contacts)
    load = 0.5 * loss.axial_load
    state = preload.frictionless_statics(contacts, load)
    assert np.all(state.loaded)  # four-point
    module = contacts.module
    k = contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2]
    s = abs(state.nut_shift) * math.cos(module.lead_angle) * math.sin(module.nominal_angle)
    loaded, receding = (((2 * module.oversize + s) / k) ** 1.5, ((2 * module.oversize - s) / k) ** 1.5)
    forces = state.normal_force[0]
    assert forces[0] == pytest.approx(loaded, rel=2e-3) and forces[1] == pytest.approx(receding, rel=2e-3)
    assert (loaded - receding) * math.sin(module.nominal_angle) * math.cos(module.lead_angle) == pytest.approx(
        load, rel=4e-3)


@pytest.mark.parametrize("factor", [1.5, 4.0])
def test_past_the_preload_loss_a_nominal_ball_rides_its_loaded_diagonal(factor):
    # two-point contact: the ball centre lies between the arc centres of SL and of the shifted NR, so
    # F_SL = F_NR = F along that line, tan beta = (dz / dx) of C_SL - C_NR(u), and the axial balance is
    # F_a = F sin beta cos alpha, i.e. F = F_a / (sin beta cos alpha); the two approaches add up to
    # |C_SL - C_NR(u)| + 2 (R_B + delta_0 - r_g) = (C_S + C_N) F^(2/3) (eq 53)
    contacts = _nominal(1.5e-6)
    module = contacts.module
    load = factor * preload.preload_loss(contacts).axial_load
    state = preload.frictionless_statics(contacts, load)
    assert state.loaded[0].tolist() == [True, False, True, False]
    nut = contacts.arc_centres[0, 2] + np.array([0.0, state.nut_shift * math.cos(module.lead_angle)])
    dx, dz = contacts.arc_centres[0, 0] - nut
    beta = math.atan2(dz, dx)
    force = load / (math.sin(beta) * math.cos(module.lead_angle))
    forces = state.normal_force[0]
    assert forces[0] == pytest.approx(force, rel=1e-9) and forces[2] == pytest.approx(force, rel=1e-9)
    assert state.contact_angle[0, 0] == pytest.approx(beta, rel=1e-9)
    assert state.contact_angle[0, 2] == pytest.approx(beta, rel=1e-9)
    span = math.hypot(dx, dz) + 2 * (module.ball_radius + module.oversize - module.groove_radius)
    k = contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2]
    assert k * force ** (2.0 / 3.0) == pytest.approx(span, rel=1e-9)


def test_the_statics_of_deviated_balls_balance_every_ball_and_the_load():
    contacts = sc.ball_contacts(_nominal(1.5e-6).module, np.array([0.0, math.radians(2.0)]))
    load = 450.0
    state = preload.frictionless_statics(contacts, load)
    approach, balance, axial = _independent_balance(contacts, state)
    np.testing.assert_allclose(approach, state.approach, rtol=0, atol=1e-15)
    assert np.max(np.abs(balance)) <= 1e-9 * state.normal_force.max()
    assert axial == pytest.approx(load, rel=1e-9)
    # the open contacts carry nothing, the others Hertz's law (eq 53)
    assert np.all(state.normal_force[approach <= 0] == 0.0) and not np.all(state.loaded)
    on = approach > 0
    np.testing.assert_allclose(state.normal_force[on], (approach[on] / contacts.hertz_constant[on]) ** 1.5,
                               rtol=1e-12)
    assert state.force_residual <= preload.STATICS_TOLERANCE and state.load_residual <= preload.STATICS_TOLERANCE


def test_the_statics_refuse_a_negative_load():
    with pytest.raises(ValueError, match="axial_load"):
        preload.frictionless_statics(_nominal(1e-6), -1.0)
