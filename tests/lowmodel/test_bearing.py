"""lowmodel.bearing: the bearing as a model type (descriptions in SI, each field checked once) and the models'
constructors that take it (``b2b.contacts``, ``screw.contacts.module``, ``screw.b2b.contacts``,
``b2b_analytical.from_case``, ``hertz.pair_geometry``); lowmodel.bearing_results: the front door on them."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ballbench.lowmodel import bearing, bearing_results, checks
from ballbench.lowmodel.bearing import (BallScrew, ContactLoadCase, GuideLoadCase, LinearGuide, Lubricant, Material,
                                        ScrewLoadCase)
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove
from ballbench.lowmodel.linear_bearing import b2b, b2b_analytical, fourpoint
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts

STEEL = Material(2.1e11, 0.28)
# lin2019 Table 1 and Tables 2-3 case (a), written out here in SI (not read from the case files)
GUIDE = LinearGuide(ball_radius=5e-3, conformity=0.56, nominal_angle=math.pi / 4, material=STEEL,
                    friction_coefficient=0.1, groove_velocity=0.01)
THETA = math.radians(2.0)
CASE = GuideLoadCase(GUIDE, vertical_force=100.0, side_force_ratio=-0.6, deviations=(-THETA, THETA, 0.0, 0.0))
# lin2019 Table 4 with an oversize, and Table 5 case (a)
SCREW = BallScrew(ball_radius=2.778e-3, pitch_radius=16.5e-3, lead=20e-3, nominal_angle=math.pi / 4,
                  conformity=0.56, material=STEEL, friction_coefficient=0.1, nut_speed=2 * math.pi, oversize=1.7e-6)
SCREW_CASE = ScrewLoadCase(SCREW, axial_load=100.0, deviations=(0.0, THETA))


def test_guide_contacts_are_lin2017_eq36_with_hertz_of_the_groove():
    contacts = b2b.contacts(CASE)
    angles = math.pi / 4 + np.array([-THETA, THETA, 0.0, 0.0])
    for ball, side in enumerate((-60.0, 60.0)):  # ball 0 carries N_x = rho N_y, ball 1 -rho N_y
        forces = fourpoint.normal_forces(side, 100.0, angles)
        ellipse = hertz.solve_load(hertz.ball_in_groove(5e-3, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28),
                                   forces)
        np.testing.assert_array_equal(contacts.normal_forces[ball], forces)
        np.testing.assert_array_equal(contacts.semi_major[ball], ellipse.a)
        np.testing.assert_array_equal(contacts.contact_angles[ball], angles)
    assert (contacts.ball_radius, contacts.friction_coefficient, contacts.groove_velocity) == (5e-3, 0.1, 0.01)


def test_the_keyword_entry_point_is_the_description_built_from_its_keywords():
    by_keywords = b2b.module_contacts(THETA, -0.6)  # lin2019 Table 1 defaults
    by_case = b2b.contacts(CASE)
    for field in ("contact_angles", "normal_forces", "semi_major", "b_over_a"):
        np.testing.assert_array_equal(getattr(by_keywords, field), getattr(by_case, field))
    general = bearing_contacts.ball_contacts(np.tile(CASE.contact_angles, (2, 1)), [-60.0, 60.0], 100.0,
                                             **GUIDE.keywords)
    np.testing.assert_array_equal(general.normal_forces, by_case.normal_forces)


def test_any_four_deviations_give_contacts_and_a_result():
    case = dataclasses.replace(CASE, deviations=(-0.02, 0.01, 0.0, 0.005))
    np.testing.assert_array_equal(b2b.contacts(case).contact_angles[1],
                                  math.pi / 4 + np.array([-0.02, 0.01, 0.0, 0.005]))
    result = bearing_results.friction(case)
    assert result.friction_force == pytest.approx(result.power / GUIDE.groove_velocity, rel=1e-12)
    assert result.friction_force > 0 and len(result.contacts) == 8


def test_the_screw_module_is_built_from_the_screw():
    module = screw_contacts.module(SCREW)
    assert module == screw_contacts.screw_module(oversize=1.7e-6)  # Table 4 defaults by keywords
    assert screw_contacts.module(SCREW, oversize=1e-6).oversize == 1e-6
    contacts = screw_b2b.contacts(SCREW_CASE)
    reference = screw_contacts.ball_contacts(module, np.array([0.0, THETA]), reading="tilted")
    np.testing.assert_array_equal(contacts.hertz_constant, reference.hertz_constant)
    np.testing.assert_array_equal(contacts.deviation, [0.0, THETA])
    rotated = screw_b2b.contacts(SCREW_CASE, reading="rotated")
    assert not np.array_equal(rotated.contact_angles, contacts.contact_angles)
    with pytest.raises(ValueError, match="nut_speed"):
        screw_contacts.module(dataclasses.replace(SCREW, nut_speed=None))


def test_the_analytical_model_takes_the_case_whole():
    psi = hertz.psi_constant(hertz.ball_in_groove(5e-3, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28), 5e-3)
    expected = b2b_analytical.two_ball_case(THETA, -0.6, normal_load=100.0, groove_velocity=10e-3,
                                            friction_coefficient=0.1, psi=psi, ball_radius=5e-3)
    assert float(b2b_analytical.from_case(CASE).b2b_force) == float(expected.b2b_force)
    # a guide of another nominal contact angle is the analytical model at that angle, not at lin2019's 45 deg
    steeper = dataclasses.replace(CASE, guide=dataclasses.replace(GUIDE, nominal_angle=math.radians(40.0)))
    at_40 = b2b_analytical.two_ball_case(THETA, -0.6, normal_load=100.0, groove_velocity=10e-3,
                                         friction_coefficient=0.1, psi=psi, ball_radius=5e-3,
                                         nominal_contact_angle=math.radians(40.0))
    assert float(b2b_analytical.from_case(steeper).b2b_force) == pytest.approx(float(at_40.b2b_force), rel=1e-14)
    assert float(at_40.b2b_force) != pytest.approx(float(expected.b2b_force), rel=1e-3)


def test_pair_geometry_of_each_pair():
    force = 50.0
    flat = ContactLoadCase("flat", 5e-3, STEEL, force)
    assert hertz.pair_geometry(flat) == hertz.ball_on_flat(5e-3, youngs_modulus=2.1e11, poisson_ratio=0.28)
    assert hertz.pair_geometry(GUIDE.contact(force)) == hertz.groove_geometry(GUIDE)
    nut = SCREW.contact("nut", force)
    frame = groove.contact_frame(groove.helical_groove(2.778e-3, 0.56, 16.5e-3, 20e-3, math.pi / 4, "nut"))
    assert hertz.pair_geometry(nut).A == pytest.approx(
        hertz.from_curvatures((1 / 2.778e-3,) * 2, (frame.curvature_major, frame.curvature_minor)).A, rel=1e-15)


def test_front_door_results_of_plain_descriptions():
    guide = bearing_results.friction(CASE)
    assert guide.case == "GuideLoadCase" and len(guide.b2b_forces) == 1
    worst, contact = bearing_results.most_loaded(CASE, guide)
    assert worst.normal_force == max(c.normal_force for c in guide.contacts) == contact.force
    assert float(bearing_results.contact(CASE).a) == float(hertz.solve_load(hertz.groove_geometry(GUIDE),
                                                                            worst.normal_force).a)
    screw = bearing_results.friction(SCREW_CASE)
    assert sum(screw.axial_shares) == pytest.approx(100.0, rel=1e-9)
    _, nut = bearing_results.most_loaded(SCREW_CASE, screw, pair="nut")
    assert nut.pair == "nut"
    with pytest.raises(TypeError, match="GuideLoadCase or ScrewLoadCase"):
        bearing_results.friction(GUIDE)


@pytest.mark.parametrize("build, name", [
    (lambda: Material(2.1e2, 0.3), "youngs_modulus"),            # GPa read as Pa
    (lambda: Material(2.1e11, 0.6), "poisson_ratio"),
    (lambda: dataclasses.replace(GUIDE, ball_radius=5.0), "ball_radius"),   # mm read as m
    (lambda: dataclasses.replace(GUIDE, conformity=0.5), "conformity"),
    (lambda: dataclasses.replace(GUIDE, nominal_angle=45.0), "nominal_angle"),  # deg read as rad
    (lambda: dataclasses.replace(GUIDE, friction_coefficient=-0.1), "friction_coefficient"),
    (lambda: dataclasses.replace(CASE, vertical_force=0.0), "vertical_force"),
    (lambda: dataclasses.replace(CASE, deviations=(-2.0, 2.0, 0.0, 0.0)), "deviations BL"),  # deg read as rad
    (lambda: dataclasses.replace(CASE, deviations=(0.0, 0.0)), "deviations"),
    (lambda: dataclasses.replace(CASE, n_balls=0), "n_balls"),
    (lambda: dataclasses.replace(SCREW, pitch_radius=16.5), "pitch_radius"),
    (lambda: dataclasses.replace(SCREW, oversize=2e-3), "oversize"),
    (lambda: dataclasses.replace(SCREW_CASE, deviations=()), "deviations"),
    (lambda: dataclasses.replace(SCREW_CASE, reading="bent"), "reading"),
    (lambda: Lubricant(0.1, 870.0, roughness=1e-3), "roughness"),
    (lambda: ContactLoadCase("groove", 5e-3, STEEL, 10.0), "conformity"),
    (lambda: ContactLoadCase("nut", 5e-3, STEEL, 10.0), "screw"),
])
def test_bad_fields_are_refused_naming_the_field(build, name):
    with pytest.raises(ValueError, match=name):
        build()


def test_limit_studies_leave_the_plausible_ranges_but_not_the_physical_ones():
    with checks.beyond_plausible():
        assert dataclasses.replace(SCREW, pitch_radius=5.0).pitch_radius == 5.0
        with pytest.raises(ValueError, match="conformity"):
            dataclasses.replace(GUIDE, conformity=0.5)


def test_every_field_is_checked_by_the_one_table():
    described = {f.name for t in (Material, Lubricant, LinearGuide, GuideLoadCase, BallScrew, ScrewLoadCase,
                                  ContactLoadCase) for f in dataclasses.fields(t)}
    # every scalar field of the descriptions has its check (parts, tuples and texts are checked by their types)
    unchecked = described - set(bearing.FIELDS) - {"material", "lubricant", "guide", "screw", "deviations",
                                                   "oversize_fit", "reading", "pair"}
    assert not unchecked, unchecked
    assert bearing.range_text("conformity") == "in (0.5, 1)"
    assert bearing.range_text("ball_radius", "mm", 1e-3) == "plausible 0.1 to 100 mm"


def test_the_keyword_entry_point_keeps_its_range_up_to_the_four_point_limit():
    # lin2019-stability sweeps theta to 40 deg: past a real bearing's 20 deg, inside the geometry's 45 deg
    contacts = b2b.module_contacts(math.radians(30.0), 0.0)
    expected = math.pi / 4 + np.array([-1.0, 1.0]) * math.radians(30.0)
    np.testing.assert_array_equal(contacts.contact_angles[0, :2], expected)
    with pytest.raises(ValueError, match="theta"):
        b2b.module_contacts(math.radians(46.0), 0.0)
    with pytest.raises(ValueError, match="deviations BL"):   # the description itself: a real bearing's range
        dataclasses.replace(CASE, deviations=(-math.radians(30), math.radians(30), 0.0, 0.0))
    with pytest.raises(ValueError, match="ball_radius"):     # mm for m, refused by the keyword entry point too
        b2b.module_contacts(THETA, -0.6, ball_radius=5.0)
