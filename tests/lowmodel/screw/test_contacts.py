"""lowmodel.screw.contacts: the ball-screw module and the contacts of its balls (lin2019 Sec 3.1), bad input."""
import math

import numpy as np
import pytest

from ballbench.lowmodel import checks
from ballbench.lowmodel.screw import b2b as b2b
from ballbench.lowmodel.screw import b2b_traction as traction
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import load_distribution as ld

# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.fixture(scope="module")
def table():
    module = screw_contacts.screw_module(oversize=1e-6)
    return module, ld.axial_stiffness(module, 200.0, 5), ld.bar_sections(module)


@pytest.mark.filterwarnings("error")
def test_screw_module_refuses_a_lead_angle_of_90_degrees():
    """lead = 1e300 m was accepted; ball_contacts then failed naming ``lead_angle``, not a parameter it has.  The
    plausible range of a lead (lowmodel.bearing) refuses it first; past it (a limit study) the module's own check."""
    with pytest.raises(ValueError, match=r"lead must lie in \[0, 0.5\] m \(the plausible range"):
        screw_contacts.screw_module(lead=1e300)
    with checks.beyond_plausible(), pytest.raises(ValueError, match="lead must give a lead angle below pi/2"):
        screw_contacts.screw_module(lead=1e300)


@pytest.mark.filterwarnings("error")
def test_ball_contacts_name_the_conformity_below_the_friction_map():
    """conformity 0.5005 at 0.3 rad: the solves raised 'b_over_a must lie in [0.02, 1]' from inside the
    friction model, naming no parameter of theirs."""
    module = screw_contacts.screw_module(conformity=0.5005, lead=0.0, nominal_angle=0.3)
    with pytest.raises(ValueError, match="module: conformity = 0.5005 gives a Hertz axis ratio"):
        screw_contacts.ball_contacts(module)


@pytest.mark.filterwarnings("error")
def test_ball_indices_are_checked(table):
    """profile_2d and hertz_patches with ball 1 of a single ball raised IndexError; True was taken as ball 1."""
    module = table[0]
    contacts = screw_contacts.ball_contacts(module, 0.0)
    state = sb.solve(contacts, 50.0)
    for ball in (1, -1, True):
        with pytest.raises(ValueError, match="ball"):
            screw_contacts.profile_2d(contacts, ball, 0, 0.7)
        with pytest.raises(ValueError, match="ball"):
            traction.hertz_patches(state, contacts, ball)
    with pytest.raises(ValueError, match="contact"):
        screw_contacts.profile_2d(contacts, 0, 4, 0.7)
    with pytest.raises(ValueError, match="axial_load"):
        sb.reference_force(contacts, 1.7e308)


@pytest.mark.filterwarnings("error")
def test_nut_speed_range_and_gap_count():
    """nut_speed = 1e-300 rad/s was accepted and the B2B solve warned (overflow of the friction Jacobian, which
    scales like 1 / speed); check_gaps(None, 1.0) was a TypeError and (None, -1) numpy's 'negative dimensions'."""
    with pytest.raises(ValueError, match="nut_speed must satisfy"):
        screw_contacts.screw_module(nut_speed=1e-300)
    assert screw_contacts.screw_module(nut_speed=-1e-100).nut_speed == -1e-100
    for count in (1.0, -1, True):
        with pytest.raises(ValueError, match="count"):
            b2b.check_gaps(None, count)


@pytest.mark.filterwarnings("error")
def test_screw_module_and_solves_refuse_what_breaks_the_model(table):
    """mu = 1e300 was accepted (the solve 'converged' with a power balance off by 3e4 relative: residuals are
    scaled by mu F); an axial load of 1e300 N overflowed (warning) in the solve; a conformity next to 0.5 failed
    in Hertz naming its internal curvatures; saturation() of a state without loaded contacts: numpy's
    'zero-size array' error."""
    with pytest.raises(ValueError, match="friction_coefficient"):
        screw_contacts.screw_module(friction_coefficient=1e300)
    contacts = screw_contacts.ball_contacts(table[0], 0.0)
    with pytest.raises(ValueError, match="axial_load: its Hertz approach"):
        sb.solve(contacts, 1e300)
    with pytest.raises(ValueError, match="module: no Hertz point contact"):
        screw_contacts.ball_contacts(screw_contacts.screw_module(conformity=math.nextafter(0.5, 1.0)))
    state = sb.solve(contacts, 50.0)
    empty = sb.ScrewBallState(**{**state.__dict__, "normal_force": np.zeros_like(state.normal_force)})
    assert b2b.saturation(empty) == 0.0


# --- shapes at the public entry points: a message naming the parameter, not numpy's --------------------------
def test_ball_contacts_names_a_deviation_of_the_wrong_shape():
    """Were numpy's 'zero-size array to reduction operation minimum' ([]) and 'operands could not be broadcast'
    (a 2-D array)."""
    module = screw_contacts.screw_module()
    for bad in ([], np.zeros((2, 2))):
        with pytest.raises(ValueError, match="deviation must be one theta"):
            screw_contacts.ball_contacts(module, bad)
    assert screw_contacts.ball_contacts(module, [0.0, 0.01]).n_balls == 2


@pytest.mark.parametrize("reading", screw_contacts.DEVIATION_READINGS)
def test_ball_contacts_of_many_balls_are_those_of_each_ball_alone(reading):
    """ball_contacts builds all balls at once (the arc centres of each flank in one call of the geometry core): every
    array equals, at 0 difference, the contacts of each ball built alone, and the arc centres equal the core's
    groove.flank_arc_centre of each flank at each ball's contact angle, one angle per call."""
    from ballbench.lowmodel.geometry import groove

    module = screw_contacts.screw_module(oversize=1.7e-6)
    theta = np.radians(3.0) * np.sin(np.linspace(0.0, 7.0, 37)) + np.radians(0.37)
    many = screw_contacts.ball_contacts(module, theta, reading)
    for j in range(theta.size):
        alone = screw_contacts.ball_contacts(module, float(theta[j]), reading)
        for name in ("contact_angles", "arc_centres", "hertz_constant", "semi_major_unit", "b_over_a", "deviation"):
            assert np.array_equal(getattr(many, name)[j], getattr(alone, name)[0]), name
        for i in range(4):
            flank = groove.HelicalGroove(module.ball_radius, module.conformity, module.pitch_radius, module.lead,
                                         module.nominal_angle, ("screw", "screw", "nut", "nut")[i],
                                         ("left", "right", "right", "left")[i])
            centre = groove.flank_arc_centre(module.ball_radius, flank.groove_radius,
                                             float(many.contact_angles[j, i]), flank.sign_u, flank.sign_w)
            assert np.array_equal(many.arc_centres[j, i], centre)
            at_angle = groove.HelicalGroove(module.ball_radius, module.conformity, module.pitch_radius, module.lead,
                                            float(many.contact_angles[j, i]), flank.body, flank.flank)
            assert np.array_equal(many.arc_centres[j, i], at_angle.arc_centre)


def test_flank_arc_centre_of_an_array_is_the_centre_of_each_angle():
    from ballbench.lowmodel.geometry import groove

    angles = np.linspace(0.3, 1.2, 1001)
    for sign_u, sign_w in ((-1.0, 1.0), (1.0, -1.0)):
        centres = groove.flank_arc_centre(2.778e-3, 3.11e-3, angles, sign_u, sign_w)
        assert centres.shape == (angles.size, 2)
        assert np.array_equal(centres, np.array([groove.flank_arc_centre(2.778e-3, 3.11e-3, float(a), sign_u, sign_w)
                                                 for a in angles]))
        # the formula itself, one angle at a time (math.cos / math.sin of each angle)
        assert np.array_equal(centres, np.array([-(3.11e-3 - 2.778e-3) * np.array([sign_u * math.cos(a),
                                                                                  sign_w * math.sin(a)])
                                                 for a in angles.tolist()]))


def test_nut_flanks_of_two_modules_in_turn_are_each_modules_own():
    """ball_contacts keeps the nut flanks' numbers (Hertz C, a / F^(1/3), b/a and arc centres at beta_0) per module and
    ball count: two modules of the same ball count built in turn each get their own, equal at 0 difference to Hertz
    at beta_0 (hertz_direct; the spline is exact at its nodes, beta_0 among them) and to the core's arc centre, for
    any deviation and either reading; the screw flanks follow each call's deviation (SR = SL's Hertz numbers when
    tilted, as computed alone)."""
    from ballbench.lowmodel.geometry import groove

    modules = (screw_contacts.screw_module(oversize=1.7e-6),
               screw_contacts.screw_module(nominal_angle=math.radians(40.0), conformity=0.55))
    theta = np.radians(3.0) * np.sin(np.linspace(0.0, 7.0, 37))
    for reading in screw_contacts.DEVIATION_READINGS:
        for module in (*modules, modules[0]):
            for deviation in (theta, -0.5 * theta):
                contacts = screw_contacts.ball_contacts(module, deviation, reading)
                for i, (body, flank) in enumerate((("nut", "right"), ("nut", "left")), start=2):
                    hertz = screw_contacts.hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                                        module.lead_angle, module.nominal_angle, body,
                                                        module.youngs_modulus, module.poisson_ratio)
                    for array, value in zip((contacts.hertz_constant, contacts.semi_major_unit, contacts.b_over_a),
                                            hertz):
                        assert np.all(array[:, i] == value), (reading, i)
                    core = groove.HelicalGroove(module.ball_radius, module.conformity, module.pitch_radius,
                                                module.lead, module.nominal_angle, body, flank)
                    assert np.all(contacts.arc_centres[:, i] == core.arc_centre), (reading, i)
                for j in (0, 17):
                    alone = screw_contacts.ball_contacts(module, float(deviation[j]), reading)
                    for name in ("hertz_constant", "semi_major_unit", "b_over_a", "arc_centres"):
                        assert np.array_equal(getattr(contacts, name)[j], getattr(alone, name)[0]), name
