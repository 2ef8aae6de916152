"""Edge inputs of the ball-screw half of lowmodel (issue 10 item 8): each case failed before its fix
(OverflowError, ZeroDivisionError, IndexError, a NaN or inf result, a warning, an error naming no parameter,
or nonsense accepted), found by tests/test_properties_screw.py."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import halfspace
from ballbench.lowmodel.contact import screw_contact as sc
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import groove, helix
from ballbench.lowmodel.screw import friction_torque as ft
from ballbench.lowmodel.screw import kinematics as kin
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import screw_b2b as b2b
from ballbench.lowmodel.screw import screw_b2b_traction as traction
from ballbench.lowmodel.screw import screw_ball as sb

TINY = 5e-324  # the smallest float
TABLE4 = dict(pitch_radius=16.5e-3, lead=20e-3)  # lin2019 Table 4


pytestmark = pytest.mark.filterwarnings("error")  # every warning fails the test


# --- helix ------------------------------------------------------------------------------------------------
def test_helix_curvature_and_torsion_at_extreme_radii():
    """Were OverflowError (r_m = 1e300: r_m**2) and ZeroDivisionError (r_m = 5e-324: r_m**2 = 0)."""
    assert helix.curvature(1e300, 0.0) == pytest.approx(1e-300, rel=1e-15)   # a circle: 1 / r_m
    assert helix.torsion(1e300, 1e300) == pytest.approx(2 * math.pi / 1e300 / (1 + 4 * math.pi**2), rel=1e-14)
    with pytest.raises(ValueError, match="pitch_radius"):
        helix.curvature(TINY, 0.0)   # 1 / r_m beyond the float range
    # the same numbers as r_m / (r_m^2 + h^2) for a real screw
    h = TABLE4["lead"] / (2 * math.pi)
    assert helix.curvature(**TABLE4) == pytest.approx(TABLE4["pitch_radius"] / (TABLE4["pitch_radius"] ** 2 + h**2),
                                                      rel=1e-15)


def test_ball_centre_azimuths_is_scale_free():
    """Were OverflowError (1e300 m) and ZeroDivisionError (5e-324 m); scaling every length by a power of two
    gives the same bits (the FE meshes of meshes.assemblies use it: chaotic at the ulp level)."""
    table4 = helix.ball_centre_azimuths(16.5e-3, 20e-3, 2 * 2.778e-3)
    for scale in (2.0**900, 2.0**-900):
        assert helix.ball_centre_azimuths(16.5e-3 * scale, 20e-3 * scale, 2 * 2.778e-3 * scale) == table4
    assert helix.ball_centre_azimuths(1e300, 0.0, 1e300) == pytest.approx(2 * math.asin(0.5), rel=1e-14)
    assert helix.ball_centre_azimuths(TINY, 0.0, TINY) == pytest.approx(2 * math.asin(0.5), rel=1e-14)


def test_helix_positions_and_velocities_that_overflow_raise():
    """Were inf or NaN with an overflow warning."""
    with pytest.raises(ValueError, match="theta, pitch_radius, lead"):
        helix.ball_centre(1e300, TINY, 1e300, 1.0)
    with pytest.raises(ValueError, match="theta, pitch_radius, lead"):
        helix.contact_point(1e300, TINY, 1e300, 1e-3, 0.7, "nut")
    with pytest.raises(ValueError, match="orbital_speed"):
        helix.ball_centre_velocity(1e300, 1.0, 1e300, 1e300)
    with pytest.raises(ValueError, match="lead_angle, pitch_radius"):
        helix.lead_from_angle(math.nextafter(0.5 * math.pi, 0.0), 1e300)


def test_rotation_z_and_frame_products_check_their_inputs():
    """rotation_z(inf) was NaN with a warning, rotation_z('x') a numpy error naming nothing; to_global and
    to_frenet of a 2-vector failed in einsum."""
    for bad in (math.inf, "x", None):
        with pytest.raises(ValueError, match="phi"):
            helix.rotation_z(bad)
    with pytest.raises(ValueError, match="vector_frenet"):
        helix.to_global(np.eye(3), [1.0, 2.0])
    with pytest.raises(ValueError, match="frame"):
        helix.to_frenet(np.eye(2), [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="frame .* and vector_global"):
        helix.to_frenet(np.stack([np.eye(3)] * 2), np.zeros((3, 3)))


# --- grooves ----------------------------------------------------------------------------------------------
def test_helical_groove_refuses_what_its_frames_cannot_build():
    """A lead whose lead angle rounds to 90 deg was accepted (the groove failed later, naming ``lead_angle``); a
    nut groove with R_P < R_B was accepted (contact_frame: numpy 'Singular matrix'); R_P / R_B = 1e312 overflowed
    in the fundamental forms (warning)."""
    with pytest.raises(ValueError, match="lead must give a lead angle below pi/2"):
        groove.helical_groove(1e-3, 0.56, 16.5e-3, 1e300, 0.7)
    with pytest.raises(ValueError, match="pitch_radius must exceed the groove radius"):
        groove.helical_groove(1e6, 0.56, 1e-12, 0.02, 0.7, "nut")
    with pytest.raises(ValueError, match="groove: the fundamental forms"):
        groove.contact_frame(groove.helical_groove(1e-12, 0.56, 1e300, 0.0, 1e-16))


def test_groove_radius_and_straight_curvature_check_their_inputs():
    """groove_radius(-1 m) returned -1.12 m; straight_groove_curvatures(5e-324 m) returned -inf."""
    with pytest.raises(ValueError, match="ball_radius"):
        groove.groove_radius(-1.0, 0.56)
    with pytest.raises(ValueError, match="conformity"):
        groove.groove_radius(1e-3, 0.4)
    with pytest.raises(ValueError, match="ball_radius"):
        groove.straight_groove_curvatures(TINY, 0.50001)
    assert groove.straight_groove_curvatures(5e-3, 0.52) == (-1.0 / (0.52 * 2 * 5e-3), 0.0)


@pytest.mark.parametrize("iterations", [2.5, True, 0, -1])
def test_groove_newton_iterations_are_counts(iterations):
    """counter_height and profile_coordinates: 2.5 was a TypeError, True, 0 and -1 were accepted."""
    flank = groove.helical_groove(2.778e-3, 0.56, 16.5e-3, 20e-3, 0.785)
    with pytest.raises(ValueError, match="iterations"):
        groove.counter_height(flank, 0.0, 0.0, iterations=iterations)
    with pytest.raises(ValueError, match="iterations"):
        groove.profile_coordinates(flank, [[0.016, 0.0, 0.0]], iterations=iterations)


# --- contact in a helical groove -------------------------------------------------------------------------
def test_preload_load_and_hertz_pressure_check_their_inputs():
    """preload_contact_load(1e300 N at 1e-16 rad) returned inf; hertz_pressure(a = 0) warned (0 / 0) and a
    negative semi-axis or pressure was accepted."""
    with pytest.raises(ValueError, match="preload"):
        sc.preload_contact_load(1e300, 2, 0.0, 1e-16)
    grid = halfspace.hertz_surface_grid(1e-4, 5e-5, 8, 1.3)
    for a, b, p0, name in ((0.0, 5e-5, 1e9, "a"), (-1e-4, 5e-5, 1e9, "a"), (1e-4, 5e-5, -1.0, "p0")):
        with pytest.raises(ValueError, match=name):
            sc.hertz_pressure(grid, a, b, p0)
    field = sc.hertz_pressure(grid, 1e-300, 5e-5, 1e9)   # a needle: zero pressure off its axis, no warning
    assert np.all(np.isfinite(field)) and field.max() <= 1e9


# --- kinematics ---------------------------------------------------------------------------------------------
def test_kinematics_parts_check_their_inputs():
    """ball_angular_velocity(True) was a TypeError; orbital_speed / ball_spin_speed with r_b <= 0 or
    r_b / r_m = 0 raised ZeroDivisionError or returned inf / NaN; centrifugal_force overflowed to inf."""
    with pytest.raises(ValueError, match="spin_speed"):
        kin.ball_angular_velocity(True, -1.0)
    with pytest.raises(ValueError, match="ball_radius"):
        kin.orbital_speed(1.0, -1.0, 0.0, 0.7, 0.7, 0.3)
    with pytest.raises(ValueError, match="ball_radius"):
        kin.ball_spin_speed(1.0, 0.0, -1.0, 0.7, 0.1, 0.3)
    with pytest.raises(ValueError, match="orbital_speed_rad_s, ball_radius"):
        kin.ball_spin_speed(1.0, TINY, 1e6, 0.7, 0.1, 0.3)
    with pytest.raises(ValueError, match="ball_mass, pitch_radius, orbital_speed"):
        kin.centrifugal_force(1e300, 0.02, 1e6)
    # the eq-by-eq helpers agree with kinematics() (wang2022 Table A1)
    state = kin.kinematics(20.7e-3, 3.572e-3, 20e-3, 200.0, math.radians(45.0))
    beta = kin.pitch_angle(math.radians(45.0), 3.572e-3, 20.7e-3)
    orbit = kin.orbital_speed(200.0, 3.572e-3, 20.7e-3, math.radians(45.0), math.radians(45.0), beta)
    assert orbit == pytest.approx(float(state.orbital_speed), rel=1e-14)
    spin = kin.ball_spin_speed(orbit, 3.572e-3, 20.7e-3, math.radians(45.0), float(state.lead_angle), beta)
    assert spin == pytest.approx(float(state.spin_speed), rel=1e-14)


def test_slide_roll_ratio_refuses_negative_speeds_and_no_entrainment():
    """slide_roll_ratio_magnitude(-1, 0) was -inf, (1, 0) inf, (1, 5e-324) inf with an overflow warning;
    absolute_velocity_measures of opposite velocities returned S = inf."""
    with pytest.raises(ValueError, match="sliding_speed"):
        kin.slide_roll_ratio_magnitude(-1.0, 1.0)
    for entrainment in (0.0, TINY):
        with pytest.raises(ValueError, match="sliding_speed, entrainment"):
            kin.slide_roll_ratio_magnitude(1.0, entrainment)
    assert kin.slide_roll_ratio_magnitude(0.0, 0.0) == 0.0   # a contact at rest
    with pytest.raises(ValueError, match="raceway_velocity, ball_velocity"):
        kin.absolute_velocity_measures([-1.0, 0, 0], [1.0, 0, 0], raceway_is_driver=True)
    with pytest.raises(ValueError, match="velocity_2"):
        kin.entrainment_velocity([1.0, 0, 0], [1.0, 0])


# --- friction torque (sun2021 eq 20) ---------------------------------------------------------------------
def test_friction_torque_at_extreme_sliding_speeds():
    """sliding_B = (-1, 0, 1e300) m/s gave |sliding_B| = inf (overflow warning) and a torque of 0; only the
    direction counts, so it must equal the torque of (0, 0, 1).  mu = Q = 1e300 gave NaN."""
    common = dict(ball_count=10, lead_angle=0.1, pitch_radius=0.016, ball_radius=3e-3, contact_angle_B=0.7)
    along_b = ft.friction_torque(0.1, 100.0, [0.0, 0.0, 1.0], **common)
    assert along_b > 0.0
    assert ft.friction_torque(0.1, 100.0, [-1.0, 0.0, 1e300], **common) == pytest.approx(along_b, rel=1e-15)
    assert ft.friction_torque(0.1, 100.0, [0.0, 0.0, TINY], **common) == along_b
    with pytest.raises(ValueError, match="friction_coefficient, load_B"):
        ft.friction_torque(1e300, 1e300, [1.0, 0.0, 0.0], **common)
    with pytest.raises(ValueError, match="surface_speed, pitch_radius"):
        ft.screw_angular_speed(-1.0, TINY)


# --- ball-to-ball complementarity ----------------------------------------------------------------------------
def test_fischer_burmeister_at_huge_arguments():
    """phi(0, 1e300) was -inf with an overflow warning; it is 0 (the complementarity holds)."""
    phi, d_a, d_b = b2b.fischer_burmeister(0.0, 1e300)
    assert float(phi) == 0.0 and float(d_a) == 1.0 and float(d_b) == 0.0
    assert float(b2b.fischer_burmeister(-1e300, -1e300)[0]) < 0.0
    with pytest.raises(ValueError, match="a must be finite"):
        b2b.fischer_burmeister(math.nan, 1.0)


# --- load distribution ----------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def table():
    module = sb.screw_module(oversize=1e-6)
    return module, ld.axial_stiffness(module, 200.0, 5), ld.bar_sections(module)


def test_load_distribution_checks_and_reports(table):
    """bar_sections(nut_outer_radius=1e300) raised OverflowError; distribute with E = 5e-324 Pa raised
    ZeroDivisionError, with E = 1e-300 Pa scipy's RuntimeError (brentq out of iterations), with
    lead_error = 1e16 m scipy's 'f(a) and f(b) must have different signs' (bracket); a non-converged fixed
    point was returned silently; max_iterations=True and a negative lead were accepted."""
    module, stiffness, sections = table
    with pytest.raises(ValueError, match="nut_outer_radius"):
        ld.bar_sections(module, nut_outer_radius=1e300)
    args = ([0.0, 1.0], 100.0, stiffness, sections, module.lead)
    with pytest.raises(ValueError, match="youngs_modulus"):
        ld.distribute(*args, TINY)
    with pytest.raises(ValueError, match="max_iterations"):
        ld.distribute(*args, 2.1e11, max_iterations=True)
    with pytest.raises(ValueError, match="lead"):
        ld.distribute([0.0, 1.0], 100.0, stiffness, sections, -1e-3, 2.1e11)
    soft = ld.distribute(*args, 1e-300)   # bars of no stiffness: the ball at the loaded end carries everything
    assert soft[0] == pytest.approx(100.0, rel=1e-12) and abs(soft[1]) < 1e-12
    with pytest.raises(ConvergenceError):
        ld.distribute(*args, 2.1e11, tolerance=1e-300, max_iterations=1)
    for error in (1e-5, -1e-5):   # a nut whose lead is shorter or longer than the screw's (-1e-5: was the bracket)
        loads = ld.distribute([0.0, 1.0, 2.0], 100.0, stiffness, sections, module.lead, 2.1e11, lead_error=error)
        assert loads.sum() == pytest.approx(100.0, rel=1e-9)
        assert np.all(loads >= -1e-12 * 100.0)   # pchip at its end node: rounding of 1e-15 N
        assert (loads[0] > loads[2]) == (error > 0)   # a positive error unloads the far balls (docstring)
    huge = ld.distribute([0.0, 1.0, 2.0], 100.0, stiffness, sections, module.lead, 2.1e11, lead_error=1e16)
    assert huge[0] == pytest.approx(100.0, rel=1e-9)   # was scipy's bracket error: the first ball takes it all


# --- one ball and the sampled-traction patches --------------------------------------------------------------
def test_screw_module_refuses_a_lead_angle_of_90_degrees():
    """lead = 1e300 m was accepted; ball_contacts then failed naming ``lead_angle``, not a parameter it has."""
    with pytest.raises(ValueError, match="lead must give a lead angle below pi/2"):
        sb.screw_module(lead=1e300)


def test_ball_contacts_name_the_conformity_below_the_friction_map():
    """conformity 0.5005 at 0.3 rad: the solves raised 'b_over_a must lie in [0.02, 1]' from inside the
    friction model, naming no parameter of theirs."""
    module = sb.screw_module(conformity=0.5005, lead=0.0, nominal_angle=0.3)
    with pytest.raises(ValueError, match="module: conformity = 0.5005 gives a Hertz axis ratio"):
        sb.ball_contacts(module)


def test_ball_indices_are_checked(table):
    """profile_2d and hertz_patches with ball 1 of a single ball raised IndexError; True was taken as ball 1."""
    module = table[0]
    contacts = sb.ball_contacts(module, 0.0)
    state = sb.solve_balls(contacts, 50.0)
    for ball in (1, -1, True):
        with pytest.raises(ValueError, match="ball"):
            sb.profile_2d(contacts, ball, 0, 0.7)
        with pytest.raises(ValueError, match="ball"):
            traction.hertz_patches(state, contacts, ball)
    with pytest.raises(ValueError, match="contact"):
        sb.profile_2d(contacts, 0, 4, 0.7)
    with pytest.raises(ValueError, match="axial_load"):
        sb.reference_force(contacts, 1.7e308)


def test_nut_speed_range_and_gap_count():
    """nut_speed = 1e-300 rad/s was accepted and the B2B solve warned (overflow of the friction Jacobian, which
    scales like 1 / speed); check_gaps(None, 1.0) was a TypeError and (None, -1) numpy's 'negative dimensions'."""
    with pytest.raises(ValueError, match="nut_speed must satisfy"):
        sb.screw_module(nut_speed=1e-300)
    assert sb.screw_module(nut_speed=-1e-100).nut_speed == -1e-100
    for count in (1.0, -1, True):
        with pytest.raises(ValueError, match="count"):
            b2b.check_gaps(None, count)


def test_screw_module_and_solves_refuse_what_breaks_the_model(table):
    """mu = 1e300 was accepted (the solve 'converged' with a power balance off by 3e4 relative: residuals are
    scaled by mu F); an axial load of 1e300 N overflowed (warning) in the solve; a conformity next to 0.5 failed
    in Hertz naming its internal curvatures; saturation() of a state without loaded contacts: numpy's
    'zero-size array' error."""
    with pytest.raises(ValueError, match="friction_coefficient"):
        sb.screw_module(friction_coefficient=1e300)
    contacts = sb.ball_contacts(table[0], 0.0)
    with pytest.raises(ValueError, match="axial_load: its Hertz approach"):
        sb.solve_balls(contacts, 1e300)
    with pytest.raises(ValueError, match="module: no Hertz point contact"):
        sb.ball_contacts(sb.screw_module(conformity=math.nextafter(0.5, 1.0)))
    state = sb.solve_balls(contacts, 50.0)
    empty = sb.ScrewBallState(**{**state.__dict__, "normal_force": np.zeros_like(state.normal_force)})
    assert b2b.saturation(empty) == 0.0


def test_distribute_refuses_positions_that_swamp_the_table(table):
    """positions = [1e300] rad: scipy's 'f(a) and f(b) must have different signs' (the table's micrometre range
    is lost beside offsets of 1e288 m)."""
    module, stiffness, sections = table
    with pytest.raises(ValueError, match="positions, lead, lead_error, youngs_modulus"):
        ld.distribute([1e300], 1.0, stiffness, sections, 0.0625, 1e9)


def test_groove_contact_names_the_grid_margin():
    """A coarse BEM grid whose contact reaches the grid edge: halfspace's error named its own 'half_width'."""
    with pytest.raises(ValueError, match="margin"):
        sc.groove_contact(2.778e-3, 0.56, 16.5e-3, 20e-3, 0.785, 100.0, youngs_modulus=2.1e11, poisson_ratio=0.3,
                          n=16, margin=1.0001)


def test_b2b_solution_does_not_depend_on_the_speed_scale():
    """Quasi-static: scaling the nut speed scales every velocity and leaves the forces.  At 2e-13 rad/s the B2B
    slip floor (1e-14 R_B in m/s, absolute) bent the friction direction: the power balance was off by 1.3e-5;
    the floor is now 1e-14 R_B |omega_N|."""
    states = []
    for speed in (2 * math.pi, 2e-13):
        module = sb.screw_module(oversize=1e-6, nut_speed=speed)
        states.append(b2b.solve(sb.ball_contacts(module, np.radians([0.0, 2.0])), 50.0))
    for state in states:
        assert abs(state.input_power - state.total_loss) <= 1e-8 * state.total_loss
    assert states[1].b2b_force[0] == pytest.approx(states[0].b2b_force[0], rel=1e-6)
    assert states[1].total_loss / 2e-13 == pytest.approx(states[0].total_loss / (2 * math.pi), rel=1e-6)


def test_axial_stiffness_names_max_load(table):
    """max_load = 1e16 N: the error named solve_balls' axial_load, not a parameter of axial_stiffness."""
    with pytest.raises(ValueError, match="max_load: axial_load: its Hertz approach"):
        ld.axial_stiffness(table[0], 1e16, 4)


def test_groove_newton_solves_say_when_they_do_not_converge():
    """counter_height and profile_coordinates returned the last Newton iterate without a word when it had not
    converged (a point 0.5 m off a 25 mm screw's flank gave a height 0.35 m off the surface); now
    ConvergenceError with the residual [m]; converged points are unchanged."""
    import numpy as np

    from ballbench.lowmodel.errors import ConvergenceError
    from ballbench.lowmodel.geometry import groove

    screw = groove.helical_groove(3.175e-3, 0.56, 25e-3, 10e-3, np.radians(45.0), "screw")
    assert groove.counter_height(screw, [0.0], [0.0])[0] == pytest.approx(0.0, abs=1e-15)
    with pytest.raises(ConvergenceError, match="counter_height") as error:
        groove.counter_height(screw, [0.5], [0.0])
    assert error.value.residual > 0.1
    with pytest.raises(ConvergenceError, match="counter_height"):
        groove.counter_height(screw, [1e-3], [0.0], iterations=1)
    point = screw.surface(np.array([screw.contact_theta]), np.array([0.1]))
    assert groove.profile_coordinates(screw, point)[0][0] == pytest.approx(0.1, abs=1e-12)
    with pytest.raises(ConvergenceError, match="profile_coordinates"):
        groove.profile_coordinates(screw, point, iterations=1)


# --- shapes at the public entry points: a message naming the parameter, not numpy's --------------------------
def test_ball_contacts_names_a_deviation_of_the_wrong_shape():
    """Were numpy's 'zero-size array to reduction operation minimum' ([]) and 'operands could not be broadcast'
    (a 2-D array)."""
    module = sb.screw_module()
    for bad in ([], np.zeros((2, 2))):
        with pytest.raises(ValueError, match="deviation must be one theta"):
            sb.ball_contacts(module, bad)
    assert sb.ball_contacts(module, [0.0, 0.01]).n_balls == 2


def test_solve_balls_takes_one_load_and_gives_one_nut_shift_per_ball():
    """An array load was 'The truth value of an array ... is ambiguous'; two balls gave the mean of their nut
    shifts, where the docs (docs/ball_screw.md) promise one per ball when each ball's load is prescribed."""
    module = sb.screw_module(oversize=1.7e-6)
    contacts = sb.ball_contacts(module, [0.0, 0.01])
    with pytest.raises(ValueError, match="axial_load must be a single number"):
        sb.solve_balls(contacts, [25.0, 25.0])
    both = sb.solve_balls(contacts, 25.0)
    singles = [sb.solve_balls(sb.ball_contacts(module, theta), 25.0).nut_shift for theta in (0.0, 0.01)]
    assert np.shape(both.nut_shift) == (2,)
    assert both.nut_shift == pytest.approx(singles, rel=1e-12)
    assert singles[0] != pytest.approx(singles[1], rel=1e-3)  # the deviation moves the ball: the mean was neither


def test_whole_screw_takes_a_constant_deviation_function(table):
    """A deviation function returning one number gave one ball's contacts for n balls, and the error blamed
    axial_load ('must be a scalar (total) or have shape (1,)')."""
    from ballbench.lowmodel.screw import whole_screw as ws

    module, stiffness, sections = table
    options = dict(n_balls=6, axial_load=150.0, steps=1, stiffness=stiffness, sections=sections)
    constant = ws.simulate(module, deviation=lambda phi: 0.01, **options)
    assert np.all(constant.deviation == 0.01)
    same = ws.simulate(module, deviation=lambda phi: np.full(np.shape(phi), 0.01), **options)
    assert np.array_equal(constant.b2b_force, same.b2b_force)
    with pytest.raises(ValueError, match=r"deviation\(phi\) must return"):
        ws.simulate(module, deviation=lambda phi: np.zeros(3), **options)
    with pytest.raises(ValueError, match="deviation must be a function"):
        ws.simulate(module, deviation=0.01, **options)
