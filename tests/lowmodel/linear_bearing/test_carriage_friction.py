"""The friction of a whole carriage's rows, at one travel and over a ball pitch of travel
(lowmodel.linear_bearing.carriage_friction; docs/carriage.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.bearing import LinearGuide, Material
from ballbench.lowmodel.linear_bearing import carriage, carriage_friction

GUIDE = LinearGuide(ball_radius=2.381e-3, conformity=0.52, nominal_angle=math.pi / 4, material=Material(210e9, 0.3),
                    friction_coefficient=0.1, groove_velocity=0.1)
ALPHA = math.radians(45.0)
N = 13
PITCH = 5e-3
SHAPE = carriage.gothic_rows(half_width=8e-3, height=5e-3, contact_angles=np.full(4, ALPHA))


def _body(**options):
    return carriage.Carriage(GUIDE, options.pop("rows", SHAPE), balls_per_row=options.pop("balls", N), pitch=PITCH,
                             **options)


def test_the_friction_of_gothic_rows_mirrors_and_says_which_balls_it_leaves_out():
    """The rows' friction (carriage_friction.friction: each row's balls touching in a chain, lin2019 eqs 4-10, on the
    state's contact loads).  Gothic rows at the nominal angle under a vertical load mirror each other: the same friction
    and B2B forces (1e-9), every ball by full sliding.  With an end relief deeper than the preload the end balls
    open every contact: loose, they part the chain; pitched, balls keep one to three contacts and take the stick/slip
    law on them, the chain parted where their number changes (marked)."""
    shape = SHAPE
    body = _body(oversize=2e-6)
    state = carriage.solve(body, carriage.Load(vertical=600.0))
    result = carriage_friction.friction(body, state)
    right, left = result.rows
    assert result.complete and set(right.law) == {"full sliding"}
    assert right.force == pytest.approx(left.force, rel=1e-9) and right.force > 0.0
    assert right.b2b_forces == pytest.approx(left.b2b_forces, rel=1e-9, abs=1e-12)
    assert result.force == pytest.approx(right.force + left.force, rel=1e-15)
    relieved = _body(rows=shape, oversize=3e-6, relief_length=10e-3, relief_depth=5e-6)
    loose = carriage_friction.friction(relieved, carriage.solve(relieved, carriage.Load(vertical=600.0)))
    assert loose.complete  # the end balls open every contact: loose, no load, no friction, and the chain parts there
    assert all(row.law[0] == row.law[-1] == "loose" and row.law[N // 2] == "full sliding" for row in loose.rows)
    assert all(row.b2b_forces[0] == row.b2b_forces[-1] == 0.0 for row in loose.rows)
    partial = carriage_friction.friction(relieved, carriage.solve(relieved, carriage.Load(vertical=600.0, pitch=5.0)))
    # pitched: balls at one end keep one to three contacts: the stick/slip law on them, the chain parted where the
    # number of loaded contacts changes
    row = partial.rows[0]
    assert all(row.law) and row.parted and not partial.complete and "one to three open contacts" in row.reason


def test_two_point_rows_roll_without_spin_and_mirror_top_to_bottom():
    """A four-row carriage's two-point balls (carriage_friction.ball_frame: lin2019's frame, the rail's contact at
    the bottom, a row with the rail above mirrored): pressed down, the upper rows carry the load and their balls roll
    on their load line without spin, a drive force of a fraction of a percent of mu F per ball (Heathcote's
    micro-slip, as a gothic ball on one diagonal); left and right rows mirror each other (1e-6: the stick/slip
    solve's tolerance); lifted by the same force, the lower rows (the rail above, at the mirrored height) carry it and
    give the upper rows' friction (1e-6): the mirror of the frame changes no power."""
    rows = carriage.four_rows(half_width=10e-3, upper=8e-3, lower=2e-3, contact_angle=ALPHA)
    body = _body(rows=rows, balls=3, oversize=1e-6)
    down = carriage.solve(body, carriage.Load(vertical=500.0))
    up = carriage.solve(body, carriage.Load(vertical=-500.0))
    pressed, lifted = carriage_friction.friction(body, down, cells=(12, 48)), \
        carriage_friction.friction(body, up, cells=(12, 48))
    assert pressed.complete and lifted.complete
    upper_right, upper_left, lower_right, lower_left = pressed.rows
    assert set(upper_right.law) == {"stick/slip on a half-space"} and set(lower_left.law) == {"loose"}
    assert upper_right.force == pytest.approx(upper_left.force, rel=1e-6)
    per_ball = upper_right.force / 3 / (GUIDE.friction_coefficient * float(down.normal_force[0].max()))
    assert 0.0 < per_ball < 0.01
    assert np.all(upper_right.b2b_forces == 0.0) or np.max(upper_right.b2b_forces) < 1e-3 * float(
        down.normal_force[0].max())
    assert lifted.rows[2].force == pytest.approx(upper_right.force, rel=1e-6)
    assert lifted.rows[3].force == pytest.approx(upper_left.force, rel=1e-6)
    assert lifted.force == pytest.approx(pressed.force, rel=1e-6)


def test_the_friction_over_a_pitch_of_travel_repeats_and_mirrors_without_ball_to_ball_contact():
    """Over travel the balls advance, leave the groove at one end and enter it at the other: a pitch on, the carriage
    and its friction are as at the start (1e-12).  Under a vertical load with the end relief symmetric along the rail
    the ball positions at travel ``t`` mirror those at ``p - t`` (z -> -z): the carriage's sinking and, every ball
    alone (no B2B contact, each ball's friction its own loads'), the drive force repeat mirrored (1e-9).  With B2B
    contact the chain runs along +z (the groove's velocity) and need not mirror; each step's friction is its own
    carriage state's (a step solved again gives the same force)."""
    body = _body(oversize=3e-6, relief_length=12e-3, relief_depth=1e-6)  # the end balls stay loaded
    load = carriage.Load(vertical=400.0)
    steps = 6
    ripple = carriage_friction.friction_over_travel(body, load, steps=steps)
    assert ripple.travel == pytest.approx(np.arange(steps) * PITCH / steps, rel=1e-15)
    assert ripple.complete[0] and ripple.force.min() > 0.0  # later steps: end balls in the relief partly open
    again = carriage_friction.friction(body, carriage.solve(body, load, travel=PITCH))
    assert again.force == pytest.approx(ripple.force[0], rel=1e-12)
    # t and p - t: steps k and steps - k
    mirrored = np.r_[ripple.force_alone[0], ripple.force_alone[:0:-1]]
    assert ripple.force_alone == pytest.approx(mirrored, rel=1e-9)
    sinking = ripple.displacement[:, 1]
    assert sinking == pytest.approx(np.r_[sinking[0], sinking[:0:-1]], rel=1e-9)
    assert np.ptp(sinking) > 1e-3 * abs(sinking.mean())  # the balls' passage moves the carriage: a ripple to see
    assert ripple.ripple == pytest.approx(np.ptp(ripple.force), rel=1e-15) and ripple.mean > 0.0
    step = carriage_friction.friction(body, carriage.solve(body, load, travel=float(ripple.travel[2])))
    assert step.force == pytest.approx(ripple.force[2], rel=1e-12)


@pytest.mark.slow
def test_a_chain_without_a_state_is_parted_at_its_weakest_ball_and_says_so():
    """The example carriage (examples/compact_linear_guide.toml) three eighths of a pitch on: in its left row a ball
    entering the relief keeps a contact at a thousandth of its load and the seven balls' chain has a state by neither
    law (about 20 s).  The chain is parted at its weakest ball, which is solved alone: its law says ", alone", no B2B
    force acts across it, the row gives the reason and the result is not complete."""
    from ballbench.validation.cases import case_file
    from tests import paths

    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    body = case.carriage
    state = carriage.solve(body, case.carriage_load, travel=0.375 * body.pitch)
    result = carriage_friction.friction(body, state)
    row = result.rows[1]
    alone = [k for k, law in enumerate(row.law) if law.endswith(", alone")]
    assert alone and not result.complete and "no state by either law as one chain" in row.reason
    forces = state.normal_force[1]
    chained = [k for k, law in enumerate(row.law) if law in carriage_friction.LAWS]
    for k in alone:  # the weakest: its least contact load the smallest share among its chain's balls
        ratio = forces[k].min() / forces[k].max()
        assert all(ratio <= forces[j].min() / forces[j].max() for j in chained if abs(j - k) == 1)
        assert all(row.b2b_forces[j] == 0.0 for j in (k - 1, k) if 0 <= j < len(row.b2b_forces))
    assert result.force > 0.0


def test_one_row_of_two_balls_at_the_modules_loads_gives_the_two_ball_modules_friction():
    """The limit of the whole carriage: one gothic row of the example case's two balls, its state holding the
    module's contact loads and Hertz ellipses (lin2017 eq 36 at the case's N_y, N_x and angles: b2b.contacts), gives
    the two-ball module's friction (b2b.solve of the module's contacts) and B2B force (1e-9): the row's contacts are
    lin2019's, contact for contact."""
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.validation.cases import case_file
    from tests import paths

    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    module = b2b.contacts(case)
    module_state = b2b.solve(module)
    right = carriage.gothic_rows(half_width=5.5e-3, height=3e-3, contact_angles=case.contact_angles)[0]
    body = carriage.Carriage(case.guide, (right,), balls_per_row=2, pitch=3.3e-3)
    zero = np.zeros((1, 2, 4))
    a = module.semi_major[None]
    state = carriage.CarriageState(np.zeros(5), carriage.ball_positions(body), np.zeros((1, 2, 2)),
                                   module.normal_forces[None], np.zeros((1, 2, 4, 2)), zero, a,
                                   a * module.b_over_a[None], zero, np.zeros((5, 5)), 0.0, 0)
    result = carriage_friction.friction(body, state)
    speed = abs(case.guide.groove_velocity)
    assert result.complete and result.rows[0].law == ("full sliding",) * 2
    assert result.force == pytest.approx(module_state.input_power / speed, rel=1e-9)
    assert result.rows[0].b2b_forces == pytest.approx(module_state.b2b_force, rel=1e-9)


def _one_ball(forces):
    """One gothic ball at ``forces`` (BL, BR, TR, TL) [N] with Hertz's ellipses: the carriage and its state."""
    from ballbench.lowmodel.contact import hertz

    body = _body(rows=SHAPE[:1], balls=1)
    load = np.asarray(forces, dtype=float)[None, None]
    contact = hertz.solve_load(hertz.groove_geometry(GUIDE), load)
    zero = np.zeros((1, 1, 4))
    return body, carriage.CarriageState(np.zeros(5), np.zeros(1), np.zeros((1, 1, 2)), load, np.zeros((1, 1, 4, 2)),
                                        zero, contact.a, contact.b, contact.p0, np.zeros((5, 5)), 0.0, 0)


def test_balls_with_open_contacts_roll_on_a_diagonal_and_join_the_four_point_law_as_a_contact_vanishes():
    """A ball with open contacts takes the stick/slip law on its loaded ones.  On one diagonal (BL and TR, opposite
    normals) it can roll without spin (Jones's race control): only Heathcote's micro-slip of the conforming grooves
    is left, its drive force below 1 % of mu F (0.35 %).  A three-point ball (TL open) against the same law on four
    contacts with TL at 1e-4 of the others: within 2e-3 (the open contact left out is the limit of a vanishing
    one)."""
    from ballbench.lowmodel.linear_bearing import b2b_rolling

    body, state = _one_ball([100.0, 0.0, 100.0, 0.0])
    diagonal = carriage_friction.friction(body, state)
    assert diagonal.rows[0].law == ("stick/slip on a half-space",) and diagonal.complete
    assert 0.0 < diagonal.force < 0.01 * GUIDE.friction_coefficient * 100.0
    body, state = _one_ball([100.0, 30.0, 100.0, 0.0])
    three = carriage_friction.friction(body, state).force
    _, faint = _one_ball([100.0, 30.0, 100.0, 0.01])
    ball = b2b_rolling.loaded_contacts(SHAPE[0].contact_angles, faint.normal_force[0, 0], faint.a[0, 0],
                                       faint.b[0, 0] / faint.a[0, 0], ball_radius=GUIDE.ball_radius, cells=(12, 48),
                                       guide=GUIDE)
    four = b2b_rolling.solve([ball], ball_radius=GUIDE.ball_radius, friction_coefficient=GUIDE.friction_coefficient,
                             groove_velocity=GUIDE.groove_velocity, start="auto").input_power / GUIDE.groove_velocity
    assert len(ball) == 4 and three == pytest.approx(four, rel=2e-3)
