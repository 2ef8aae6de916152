"""The whole nut (lowmodel.screw.nut; docs/nut.md): a single nut's load distribution, a double nut's preload and
lift-off, the friction torque over rotation by lin2019 Sec 3.4's whole-screw path."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import nut as nuts
from ballbench.lowmodel.screw import whole_screw

MODULE = screw_contacts.screw_module(oversize=1.7e-6)  # lin2019 Table 4's screw, its Sec 3.4 preload


def _hertz_diagonal():
    """Hertz's law of one two-point ball along the nominal diagonal, written out from the module (preload.py's
    closed form of a preloaded pair): the approaches ``C_i F^(2/3)`` of its SL and NR contacts add up to the axial
    shift projected on the diagonal, ``u sin beta_0 cos alpha``, and ``q = F sin beta_0 cos alpha``."""
    contacts = screw_contacts.ball_contacts(screw_contacts.screw_module(oversize=0.0), 0.0)
    constant = float(contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2])
    factor = math.sin(MODULE.nominal_angle) * math.cos(MODULE.lead_angle)
    return constant, factor


def test_a_double_nut_by_hertz_lifts_off_at_two_to_the_three_halves_the_preload():
    """Two halves pressed apart by F_pr: under an axial load half A approaches and B recedes by the same shift; B
    lifts off when A carries 2^(3/2) F_pr (Hertz: A's approach doubles) (1e-9), and then carries the whole load.
    The preloaded stiffness is both halves', ``2 n dq/du = 2 n (3/2) q / u`` at ``q = F_pr / n`` (1e-5: the
    state's central difference)."""
    nut = nuts.Nut(MODULE, turns=2, balls=20, arrangement="double", preload=300.0)
    law = nuts.ball_law(MODULE, "hertz")
    assert nuts.lift_off(nut, law) == pytest.approx(2 ** 1.5 * 300.0, rel=1e-9)
    at_lift = nuts.double_nut(nut, 2 ** 1.5 * 300.0 * (1 + 1e-12), law)
    assert at_lift.lifted and at_lift.half_loads[1] == pytest.approx(0.0, abs=1e-6)
    below = nuts.double_nut(nut, 500.0, law)
    assert not below.lifted and below.half_loads[0] - below.half_loads[1] == pytest.approx(500.0, rel=1e-10)
    constant, factor = _hertz_diagonal()
    q = 300.0 / 20
    u = constant * (q / factor) ** (2 / 3) / factor
    # the two halves' shifts from the preloaded state are equal and opposite: A's approach grows by the shift
    assert constant * (below.half_loads[0] / 20 / factor) ** (2 / 3) / factor == pytest.approx(u + below.shift,
                                                                                                 rel=1e-9)
    assert constant * (below.half_loads[1] / 20 / factor) ** (2 / 3) / factor == pytest.approx(u - below.shift,
                                                                                                 rel=1e-9)
    rest = nuts.double_nut(nut, 0.0, law)
    assert rest.half_loads == pytest.approx([300.0, 300.0], rel=1e-12)
    assert rest.stiffness == pytest.approx(2 * 20 * 1.5 * q / u, rel=1e-5)
    past = nuts.double_nut(nut, 2000.0, law)
    assert past.lifted and past.half_loads == pytest.approx([2000.0, 0.0], rel=1e-10, abs=1e-9)


def test_the_exact_two_point_ball_lifts_off_near_hertz_and_its_halves_balance():
    """With the exact flank arcs (the frictionless statics of lowmodel.screw.preload) the contact lines turn under
    load: the lift-off load departs from 2^(3/2) F_pr by well under a percent at this preload, and every state
    balances its load (1e-10)."""
    nut = nuts.Nut(MODULE, turns=2, balls=20, arrangement="double", preload=300.0)
    law = nuts.ball_law(MODULE, "exact", max_load=4 * 2 ** 1.5 * 300.0 / 20)
    lift = nuts.lift_off(nut, law)
    assert lift / (2 ** 1.5 * 300.0) == pytest.approx(1.0, abs=1e-2) and lift != pytest.approx(2 ** 1.5 * 300.0,
                                                                                               rel=1e-6)
    for load in (0.0, 200.0, lift, 1.5 * lift):
        state = nuts.double_nut(nut, load, law)
        assert state.balance < nuts.BALANCE_TOLERANCE and state.lifted == (load >= lift)


def test_a_single_nut_spreads_its_load_from_the_loaded_end_and_balances_it():
    """A single nut (oversize preload): the balls nearest the loaded end carry most (screw in tension, nut in
    compression: the bars' strains add towards the loaded end), the loads fall monotonically along the nut and sum
    to the axial load (1e-10)."""
    nut = nuts.Nut(MODULE, turns=3)
    assert nut.balls == nuts.capacity(MODULE, 3) - 1
    state = nuts.distribution(nut, 1500.0)
    assert state.ball_loads.sum() == pytest.approx(1500.0, rel=1e-10)
    assert np.all(np.diff(state.ball_loads) < 0.0) and state.shift > 0.0
    assert state.z == pytest.approx(MODULE.lead * state.positions / (2 * math.pi), rel=1e-15)


def test_the_shift_at_the_flange_is_ball_screw_and_nut_in_series_for_both_flanges():
    """The nut's shift at its flange, written out by a plain loop: the first ball's own shift, the screw's stretch
    from its loaded section to it (F_a z_1 / (E A_s)) and the nut's between that ball's groove and the flange (held at
    the loaded end F_a z_1 / (E A_n); at the far end, the last ball's z, the integral of S(z) / (E A_n) from z_1 on).
    Held at the far end the load is the more even (both bars stretch the same way)."""
    spreads = []
    for flange in ("loaded end", "far end"):
        nut = nuts.Nut(MODULE, turns=3, flange=flange)
        table = nuts.ball_table(MODULE, 3.0 * 1500.0 / nut.balls)
        state = nuts.distribution(nut, 1500.0, table)
        e, sections, q, z = MODULE.youngs_modulus, nut.sections, state.ball_loads, state.z
        nut_part = 1500.0 * z[0] / (e * sections.nut_area)
        if flange == "far end":
            nut_part, handed = 0.0, 0.0
            for j in range(1, len(z)):
                handed += q[j - 1]
                nut_part += handed * (z[j] - z[j - 1]) / (e * sections.nut_area)
        expected = abs(float(table.shift(q[0]))) + 1500.0 * z[0] / (e * sections.screw_area) + nut_part
        assert state.shift == pytest.approx(expected, rel=1e-9), flange
        assert state.ball_loads.sum() == pytest.approx(1500.0, rel=1e-10)
        spreads.append(np.ptp(q))
    assert spreads[1] < spreads[0]
    with pytest.raises(ValueError, match="flange"):
        nuts.Nut(MODULE, flange="middle")


def test_the_nut_path_is_lin2019s_whole_screw():
    """A nut of lin2019's 37 balls in two turns gives the whole-screw simulation's histories (1e-12 relative)."""
    nut = nuts.Nut(MODULE, turns=2, balls=37)
    ours = nuts.friction_over_rotation(nut, 1500.0, steps=6, duration=0.06, amplitude=math.radians(3.0), cycles=4)
    theirs = whole_screw.simulate(MODULE, n_balls=37, axial_load=1500.0, steps=6, duration=0.06,
                                  amplitude=math.radians(3.0), cycles=4)
    for name in ("groove_torque", "b2b_torque", "b2b_force", "axial_load", "positions"):
        assert getattr(ours, name) == pytest.approx(getattr(theirs, name), rel=1e-12, abs=1e-15), name


def test_bad_nuts_name_their_parameter():
    with pytest.raises(ValueError, match="preload"):
        nuts.Nut(MODULE, arrangement="double")
    with pytest.raises(ValueError, match="preload"):
        nuts.Nut(MODULE, preload=100.0)
    with pytest.raises(ValueError, match="balls"):
        nuts.Nut(MODULE, turns=2, balls=nuts.capacity(MODULE, 2) + 1)
    with pytest.raises(ValueError, match="arrangement"):
        nuts.Nut(MODULE, arrangement="triple")
    with pytest.raises(ValueError, match="four-point"):
        nuts.friction_over_rotation(nuts.Nut(MODULE, arrangement="double", preload=100.0), 100.0)


def test_the_catalogue_screws_nuts_balance_from_a_light_load_to_past_the_preload_loss():
    """Every screw of examples/catalogue (12 to 63 mm, 2-7.1 mm balls, oversize 0.5-5 um) in a three-turn single nut
    at 50 N (far below the preload forces: the frictionless statics judge the balance against them) and 6000 N
    (past most of their preload losses): the balls' loads balance the load (BALANCE_TOLERANCE_SINGLE) and fall
    from the loaded end.  Before the frictionless ball table, lin2019's table stopped past the preload loss on 7 of
    these 14; the 40 x 20 screw's light load stopped the frictionless statics' own check."""
    from ballbench.validation.cases import case_file
    from tests import paths

    for path in sorted((paths.ROOT / "examples" / "catalogue").glob("screw_*.toml")):
        module = screw_contacts.module(case_file.load(path).screw)
        nut = nuts.Nut(module, turns=3)
        for load in (50.0, 6000.0):
            state = nuts.distribution(nut, load)
            assert state.balance <= nuts.BALANCE_TOLERANCE_SINGLE, (path.name, load)
            assert np.all(np.diff(state.ball_loads) <= 1e-9 * load), (path.name, load)
