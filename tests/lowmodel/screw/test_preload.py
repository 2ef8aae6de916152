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
