"""The rigid carriage's load distribution and stiffness (lowmodel.linear_bearing.carriage; docs/carriage.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from ballbench.lowmodel.bearing import LinearGuide, Material
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import carriage

# a compact guide: 4.762 mm balls in grooves of conformity 0.52 (a catalogue size 20 carriage's proportions)
GUIDE = LinearGuide(ball_radius=2.381e-3, conformity=0.52, nominal_angle=math.pi / 4, material=Material(210e9, 0.3),
                    friction_coefficient=0.1, groove_velocity=0.1)
ALPHA = math.radians(45.0)
ROWS = carriage.four_rows(half_width=10e-3, upper=8e-3, lower=2e-3, contact_angle=ALPHA)
N = 13
PITCH = 5e-3


def _body(**options):
    return carriage.Carriage(GUIDE, options.pop("rows", ROWS), balls_per_row=options.pop("balls", N), pitch=PITCH,
                             **options)


def _vertical_reference(force: float, balls: int, oversize: float = 0.0,
                        series: float = 0.0) -> tuple[float, float]:
    """Two upper rows of ``balls`` each, no preload, pure vertical load (the lower rows stay open): the carriage
    sinks by ``u`` with every upper ball alike, ``A = A0 n + (0, -u)``; the exact curvature-centre geometry and
    Hertz's law give the vertical balance ``2 balls Q |e_y| = F``, solved here by brentq (the model's Newton and its
    arrays not involved); ``series`` [m/N] an isotropic compliance of each carriage groove's curvature centre, which
    moves it along the line by ``series Q`` (``2 C Q^(2/3) + series Q`` the approach).  Returns (u [m], Q [N])."""
    constant = hertz.hertz_constant(hertz.groove_geometry(GUIDE))
    a0 = (2 * GUIDE.conformity - 1) * 2 * GUIDE.ball_radius
    n = np.array([-math.cos(ALPHA), -math.sin(ALPHA)])

    def ball(u):
        vector = a0 * n + np.array([0.0, -u])
        length = float(np.hypot(*vector))
        approach = max(length - a0 + oversize, 0.0)
        q = (approach / (2 * constant)) ** 1.5
        if series > 0.0 and approach > 0.0:
            q = brentq(lambda f: 2 * constant * f ** (2 / 3) + series * f - approach, 0.0, q, xtol=1e-30, rtol=1e-15)
        return q, abs(vector[1]) / length

    def excess(u):
        q, ey = ball(u)
        return 2 * balls * q * ey - force

    u = brentq(excess, 0.0, 1e-3, xtol=1e-22, rtol=1e-15)
    return u, ball(u)[0]


def test_a_vertical_load_on_the_upper_rows_matches_the_closed_geometry():
    state = carriage.solve(_body(), carriage.Load(vertical=3e3))
    u, q = _vertical_reference(3e3, N)
    assert state.displacement[1] == pytest.approx(-u, rel=1e-9)
    assert state.normal_force[:2] == pytest.approx(np.full((2, N, 2), q), rel=1e-9)  # both contacts of a ball
    assert np.all(state.normal_force[2:] == 0.0) and np.all(state.approach[2:] < 0.0)
    assert np.max(np.abs(state.displacement[[0, 2, 3, 4]])) < 1e-15  # symmetric: no lateral, pitch, yaw or roll
    # the balance from the state's own outputs: vertical components of the upper balls' loads on their loaded lines
    vertical = np.sum(state.normal_force[..., 1] * np.sin(state.contact_angle[..., 1]))  # carriage contacts
    assert vertical == pytest.approx(3e3, rel=carriage.BALANCE_TOLERANCE)
    assert state.balance < carriage.BALANCE_TOLERANCE


def test_elastic_grooves_in_series_match_the_closed_geometry_and_vanish_in_the_rigid_limit():
    """An elastic carriage (solve's groove_compliance): with each carriage groove's curvature centre on an isotropic
    spring of 2 nm/N (its own 2 x 2 block; the mounting face rigid) every upper ball's approach is Hertz's plus the
    spring's, written out by brentq (1e-9); with a compliance of 1e-22 m/N the rigid carriage's state (1e-9).  The
    elastic state's stiffness is the change of the displacement under a small change of the load (1e-4)."""
    body = _body()
    m = len(carriage.groove_points(body)[0])
    state = carriage.solve(body, carriage.Load(vertical=3e3), groove_compliance=2e-9 * np.eye(2 * m))
    u, q = _vertical_reference(3e3, N, series=2e-9)
    assert state.displacement[1] == pytest.approx(-u, rel=1e-9)
    assert state.normal_force[:2] == pytest.approx(np.full((2, N, 2), q), rel=1e-9)
    assert state.balance < carriage.BALANCE_TOLERANCE
    preloaded = _body(oversize=2e-6)
    load = carriage.Load(lateral=300.0, vertical=1e3, roll=10.0)
    rigid = carriage.solve(preloaded, load)
    stiff = carriage.solve(preloaded, load, groove_compliance=1e-22 * np.eye(2 * m))
    assert stiff.normal_force == pytest.approx(rigid.normal_force, rel=1e-9, abs=1e-9)
    assert stiff.stiffness == pytest.approx(rigid.stiffness, rel=1e-9, abs=1e-9 * np.abs(rigid.stiffness).max())
    rng = np.random.default_rng(3)
    coupling = rng.normal(size=(2 * m, 2 * m)) * 2e-10
    compliance = 1e-9 * np.eye(2 * m) + coupling @ coupling.T  # symmetric positive: an elastic body's
    elastic = carriage.solve(preloaded, load, groove_compliance=compliance)
    assert elastic.balance < carriage.BALANCE_TOLERANCE and not np.allclose(elastic.normal_force, rigid.normal_force)
    h = 1.0
    plus = carriage.solve(preloaded, carriage.Load(lateral=300.0 + h, vertical=1e3, roll=10.0),
                          groove_compliance=compliance)
    minus = carriage.solve(preloaded, carriage.Load(lateral=300.0 - h, vertical=1e3, roll=10.0),
                           groove_compliance=compliance)
    change = (plus.displacement - minus.displacement) / (2 * h)
    assert change == pytest.approx(np.linalg.solve(elastic.stiffness, np.eye(5)[0]), rel=1e-4,
                                   abs=1e-4 * np.abs(change).max())


@pytest.mark.parametrize("load", [carriage.Load(lateral=800.0, vertical=2e3, pitch=40.0, yaw=-25.0, roll=15.0),
                                  carriage.Load(vertical=-1.5e3, roll=-10.0), carriage.Load(pitch=60.0)])
def test_every_load_balances_and_the_stiffness_is_the_derivative_of_the_load(load):
    """The balls' forces and moments on the carriage, summed from the state's outputs (loads, loaded lines, the
    grooves' curvature centres at the balls), balance the external load to 1e-10; the tangent stiffness equals the
    central difference of the generalised force of the balls in each displacement (1e-6)."""
    body = _body(oversize=1.5e-6, relief_length=10e-3, relief_depth=4e-6)
    state = carriage.solve(body, load)
    assert state.balance < 1e-10
    force = np.zeros(5)
    centre_offset = (GUIDE.conformity * 2 - 1) * GUIDE.ball_radius
    for r, row in enumerate(ROWS):
        n = np.array(row.normals[1])  # the carriage contact's outward normal
        sx, sy = np.sign(n)  # the loaded line keeps the row's quadrant
        for k, z in enumerate(state.z):
            angle = state.contact_angle[r, k, 1]
            f = state.normal_force[r, k, 1] * np.array([sx * math.cos(angle), sy * math.sin(angle)])  # on the groove
            cx, cy = np.array([row.x, row.y]) - centre_offset * n  # small displacements: moments about rest
            force += np.array([f[0], f[1], -z * f[1], z * f[0], cx * f[1] - cy * f[0]])
    scale = np.array([1, 1, 1 / body.half_length, 1 / body.half_length, 1 / body.half_length])
    # the lines through the moved ball centres: small displacements against A0 (1e-6 of the largest ball load)
    assert np.max(np.abs((force + load.vector) * scale)) < 1e-6 * np.max(state.normal_force)
    # the stiffness against central differences of the balls' generalised force (tangent: 1e-6)
    steps = np.array([1e-9, 1e-9, 1e-7, 1e-7, 1e-7])
    difference = np.zeros((5, 5))
    for j in range(5):
        shifted = []
        for sign in (1.0, -1.0):
            push = np.zeros(5)
            push[j] = sign * steps[j]
            shifted.append(_balls_force(body, state.displacement + push))
        difference[:, j] = -(shifted[0] - shifted[1]) / (2 * steps[j])
    assert state.stiffness == pytest.approx(difference, rel=1e-6, abs=1e-6 * np.max(np.abs(state.stiffness)))


def _balls_force(body, q):
    """The generalised force of the two-point balls on the carriage at displacement ``q`` from the exact
    curvature-centre geometry and Hertz's law, written out here (the model's arrays and solve not involved): each
    ball on the line of its two grooves' curvature centres."""
    constant = hertz.hertz_constant(hertz.groove_geometry(GUIDE))
    a0 = (2 * GUIDE.conformity - 1) * 2 * GUIDE.ball_radius
    z = carriage.ball_positions(body)
    total = np.zeros(5)
    for row in body.rows:
        n = np.array(row.normals[0])  # towards the rail
        cx, cy = np.array([row.x, row.y]) + (GUIDE.conformity * 2 * GUIDE.ball_radius - GUIDE.ball_radius) * n
        for zk, relief in zip(z, carriage.relief(body, z)):
            d = np.array([q[0] + q[3] * zk - q[4] * cy, q[1] + q[4] * cx - q[2] * zk])
            vector = a0 * n + d
            length = float(np.hypot(*vector))
            load = (max(length - a0 + body.oversize - relief, 0.0) / (2 * constant)) ** 1.5
            f = -load * vector / length
            total += np.array([f[0], f[1], -zk * f[1], zk * f[0], cx * f[1] - cy * f[0]])
    return total


def test_preloaded_opposed_rows_unload_at_two_to_the_three_halves_the_preload():
    """Upper and lower rows alike (45 deg, the same count), preloaded by a small oversize: a vertical load takes the
    lower rows' load off at 2^(3/2) times the vertical preload of the upper rows (Hertz's law of two opposed
    preloaded sets; Harris & Kotzalas, preload).  The exact geometry turns the lines by about delta / A0 (1e-3 here),
    the tolerance."""
    body = _body(oversize=0.05e-6)
    rest = carriage.solve(body, carriage.Load())
    preload = float(np.sum(rest.normal_force[:2, :, 1] * np.sin(rest.contact_angle[:2, :, 1])))

    def lower(force):
        return float(np.max(carriage.solve(body, carriage.Load(vertical=force)).normal_force[2:]))

    lift = brentq(lambda f: lower(f) - 1e-9 * preload, 0.5 * preload, 5 * preload, xtol=1e-9 * preload)
    assert lift / preload == pytest.approx(2 ** 1.5, rel=1e-3)


def test_the_end_relief_unloads_the_end_balls_and_travel_moves_the_balls():
    body = _body(oversize=1e-6, relief_length=12e-3, relief_depth=3e-6)
    state = carriage.solve(body, carriage.Load(vertical=1e3))
    upper = state.normal_force[0, :, 1]
    assert upper[0] < upper[N // 2] and upper[-1] < upper[N // 2]
    assert upper == pytest.approx(upper[::-1], rel=1e-9)  # centred: symmetric along the rail
    moved = carriage.solve(body, carriage.Load(vertical=1e3), travel=0.3 * PITCH)
    assert moved.z == pytest.approx(state.z + 0.3 * PITCH)
    # past half a pitch the leading ball leaves the groove at +G = N PITCH / 2 and enters it at -G; a pitch on, the
    # balls sit as at the start
    wrapped = carriage.ball_positions(body, 0.7 * PITCH)
    assert wrapped[0] == pytest.approx(-0.5 * N * PITCH + 0.2 * PITCH, rel=1e-12)
    assert wrapped[1:] == pytest.approx(state.z[:-1] + 0.7 * PITCH, rel=1e-12)
    assert carriage.ball_positions(body, PITCH) == pytest.approx(state.z, abs=1e-15)
    assert moved.balance < 1e-10 and not np.allclose(moved.normal_force, state.normal_force)


def test_a_load_no_row_can_carry_is_a_convergence_error_and_bad_input_names_its_parameter():
    upper_only = _body(rows=ROWS[:2])
    with pytest.raises(ConvergenceError, match="load balance|no step"):
        carriage.solve(upper_only, carriage.Load(vertical=-1e3))
    with pytest.raises(ValueError, match="pitch"):
        carriage.Carriage(GUIDE, ROWS, balls_per_row=5, pitch=1e-3)
    with pytest.raises(ValueError, match="normals"):
        carriage.Row(0.0, 0.0, ((1.0, 1.0), (0.0, 1.0)), (False, True))
    with pytest.raises(ValueError, match="carriage"):
        carriage.Row(0.0, 0.0, ((1.0, 0.0), (-1.0, 0.0)), (True, True))
    with pytest.raises(ValueError, match="vertical"):
        carriage.Load(vertical=math.nan)
    assert carriage.solve(_body(), carriage.Load()).normal_force.max() == 0.0  # no preload, no load: at rest


@pytest.mark.parametrize("rows", ["gothic", "four-row"])
def test_the_stiffness_is_the_change_of_the_displacement_under_a_small_change_of_the_load(rows):
    """A two-row gothic-arch carriage (lin2019's four-point balls turned to face the rail; each ball's centre free
    in the cross-section) and the four-row one, preloaded: solving again under the load plus a small change of each
    component moves the carriage by ``K^-1`` of it (the condensed stiffness with the balls in equilibrium; central
    differences of whole solves, 1e-4)."""
    shape = (carriage.gothic_rows(half_width=8e-3, height=5e-3, contact_angles=np.full(4, ALPHA))
             if rows == "gothic" else ROWS)
    body = _body(rows=shape, oversize=2e-6)
    base = carriage.Load(lateral=300.0, vertical=1.5e3, pitch=10.0, yaw=-5.0, roll=8.0)
    state = carriage.solve(body, base)
    assert state.balance < 1e-10
    fields = ("lateral", "vertical", "pitch", "yaw", "roll")
    steps = (1.0, 1.0, 0.01, 0.01, 0.01)
    for name, step in zip(fields, steps):
        moved = []
        for sign in (1.0, -1.0):
            values = {f: getattr(base, f) for f in fields}
            values[name] += sign * step
            moved.append(carriage.solve(body, carriage.Load(**values)).displacement)
        change = np.zeros(5)
        change[fields.index(name)] = 2 * step * (-1.0 if name == "vertical" else 1.0)  # vertical presses along -y
        expected = np.linalg.solve(state.stiffness, change)
        assert moved[0] - moved[1] == pytest.approx(expected, rel=1e-4, abs=1e-4 * np.max(np.abs(expected)))


def test_a_gothic_arch_row_balances_each_ball_and_mirrors_under_a_vertical_load():
    shape = carriage.gothic_rows(half_width=8e-3, height=5e-3, contact_angles=np.full(4, ALPHA))
    state = carriage.solve(_body(rows=shape, oversize=1e-6), carriage.Load(vertical=800.0))
    assert state.balance < 1e-10
    right, left = state.normal_force
    assert right == pytest.approx(left[:, [1, 0, 3, 2]], rel=1e-9)  # mirror about the rail's mid-plane: BL <-> BR
    assert np.max(np.abs(state.displacement[[0, 2, 3, 4]])) < 1e-14
    # each ball's four contact forces balance (the ball's statics), from the state's outputs
    resultant = np.einsum("rkc,rkci->rki", state.normal_force, state.line)
    assert np.max(np.abs(resultant)) < 1e-9 * np.max(state.normal_force)


def test_a_catalogue_of_carriages_solves_at_any_travel():
    """Random carriages over the space of real guides (1/8- to 1/4-inch balls, conformity 0.515-0.58, 40-50 deg,
    gothic or four-row, 6-25 balls per row, no preload or 0.5-6 um, end relief up to 8 um deep, all five load
    components up to about 2 kN and its moments) at random travels: every one balances (1e-10).  Before the holding
    of loose balls was let go where it stalls and a preload let go in steps where a carriage without one stalls,
    30 of 1200 such solves stopped (balls at the edge of loose; contacts closing and opening from the linear
    start)."""
    rng = np.random.default_rng(1)
    for _ in range(60):
        radius = float(rng.choice([1.5875e-3, 2.381e-3, 3.175e-3]))
        guide = LinearGuide(ball_radius=radius, conformity=rng.uniform(0.515, 0.58),
                            nominal_angle=math.radians(rng.uniform(40, 50)), material=Material(210e9, 0.3),
                            friction_coefficient=0.1, groove_velocity=0.1)
        if rng.random() < 0.5:
            rows = carriage.gothic_rows(half_width=3 * radius, height=2 * radius,
                                        contact_angles=guide.nominal_angle + np.radians(rng.uniform(-2, 2, 4)))
        else:
            rows = carriage.four_rows(half_width=4 * radius, upper=4 * radius, lower=radius,
                                      contact_angle=guide.nominal_angle)
        balls, pitch = int(rng.integers(6, 26)), 2 * radius * rng.uniform(1.02, 1.2)
        body = carriage.Carriage(guide, rows, balls, pitch, oversize=float(rng.choice([0.0, rng.uniform(5e-7, 6e-6)])),
                                 relief_length=rng.uniform(0, 0.3) * balls * pitch / 2,
                                 relief_depth=rng.uniform(0, 8e-6))
        scale = 2e3 * (radius / 2.381e-3) ** 2
        load = carriage.Load(*(rng.normal(size=5) * rng.uniform(0.05, 1) * np.array(
            [scale, scale, scale * balls * pitch / 4, scale * balls * pitch / 4, scale * radius])))
        for travel in rng.uniform(0, pitch, 2):
            assert carriage.solve(body, load, travel=float(travel)).balance < carriage.BALANCE_TOLERANCE
