"""Property-based test of the ball-screw half of lowmodel's public API (issue 10 item 8, hypothesis).

Random finite inputs in the documented ranges (and a little beyond: negative, zero, the extreme floats,
angles at their limits, lead 0) give finite outputs, or a ValueError / ConvergenceError whose message names
a parameter of the call; never NaN, never a warning (:func:`property_support.call`).  Covers
``geometry.helix``, ``geometry.groove``, ``contact.screw_contact`` and ``screw.*`` except what
test_properties.py already calls (``kinematics.kinematics``, ``wei_ball_centre_kinematics``, ``harris``).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballbench.lowmodel.contact import halfspace
from ballbench.lowmodel.contact import screw_contact as sc
from ballbench.lowmodel.geometry import groove, helix
from ballbench.lowmodel.screw import friction_torque as ft
from ballbench.lowmodel.screw import kinematics as kin
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel import b2b_chain
from ballbench.lowmodel.screw import b2b as b2b
from ballbench.lowmodel.screw import b2b_traction as traction
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import whole_screw
from tests.property_support import SETTINGS, SLOW, call, positive, real
from tests.lowmodel.test_properties import angle

EXTREME = [0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e-16, 1e16, 1e300, 1.7976931348623157e308, -1e-3, -1.0]
angle_limits = (5e-324, 1e-16, math.nextafter(0.5 * math.pi, 0.0), 0.5 * math.pi, 0.0, -0.1, 2.0)


def mostly(valid, *invalid):
    """``valid`` draws with about one in eight from ``invalid`` (bad or extreme values): most calls get through
    the input checks to the computation, and every check still sees its bad inputs."""
    return st.integers(0, 7).flatmap(lambda i: st.sampled_from(invalid) if i == 7 else valid)


# lengths [m] (real screws: mm), speeds [rad/s or m/s], forces [N]: physical draws, the extreme floats,
# zero and negatives among the rest
length = mostly(positive(1e-4, 0.1), *EXTREME)
speed = mostly(real(-1e3, 1e3), *EXTREME, -1e300)
force = mostly(real(0.0, 1e4), *EXTREME)
lead_angle = mostly(real(0.0, 1.4), *angle_limits)   # [0, pi/2)
contact_angle = st.one_of(mostly(real(0.2, 1.3), *angle_limits), angle)   # (0, pi/2); angle: test_properties
conformity = mostly(real(0.505, 0.7), 0.5, math.nextafter(0.5, 1.0), 0.5005, math.nextafter(1.0, 0.0), 1.0, 0.0)
count = mostly(st.integers(1, 40), -1, 0, True, False, 2.0, 3.5)
ball_fraction = mostly(real(0.05, 0.3), 0.5, 1.0, 2.0, 1e300, 1e-300)   # ball radius / pitch radius


# --- geometry core: helix ------------------------------------------------------------------------------
@SETTINGS
@given(pitch_radius=length, lead=length, theta=mostly(real(-100.0, 100.0), *EXTREME), omega=speed,
       fraction=ball_fraction, alpha=contact_angle, psi=lead_angle, spacing=mostly(real(0.0, 2.0), 2.0, 3.0))
def test_helix(pitch_radius, lead, theta, omega, fraction, alpha, psi, spacing):
    ball_radius = pitch_radius * fraction
    spacing *= pitch_radius   # (0, 2 R_P], its end, and beyond
    call(helix.helix_parameter, lead)
    call(helix.lead_angle, lead, pitch_radius)
    call(helix.lead_from_angle, psi, pitch_radius)
    call(helix.curvature, pitch_radius, lead)
    call(helix.torsion, pitch_radius, lead)
    call(helix.ball_centre, theta, pitch_radius, lead, omega)
    call(helix.ball_centre_velocity, omega, -omega, pitch_radius, lead)
    call(helix.ball_centre_velocity, omega, 1.0, pitch_radius, lead, lead_angle=psi)
    frame = call(helix.frenet_frame, theta, psi)
    call(helix.cs3_frame, theta, psi)
    call(helix.rotation_z, theta)
    call(helix.axis_in_frenet, psi)
    call(helix.frame_angular_velocity, omega, psi)
    offset = call(helix.contact_offset, ball_radius, alpha, "nut")
    if frame is not None and offset is not None:
        assert np.allclose(call(helix.to_frenet, frame, call(helix.to_global, frame, offset)), offset,
                           rtol=1e-12, atol=1e-12 * float(np.max(np.abs(offset))))
    call(helix.contact_point, theta, pitch_radius, lead, ball_radius, alpha, "screw", omega)
    step = call(helix.ball_centre_azimuths, pitch_radius, lead, spacing)
    if step is not None:   # the chord of the returned azimuth step is the spacing
        p = lead / (2.0 * math.pi)
        chord = math.hypot(2.0 * pitch_radius * math.sin(0.5 * step), p * step)
        assert chord == pytest.approx(spacing, rel=1e-9, abs=1e-300)


@SETTINGS
@given(bad=st.sampled_from([math.nan, math.inf, "x", None, True, [1.0, 2.0]]))
def test_helix_rejects_non_numbers(bad):
    """Non-finite, non-numeric and wrongly shaped inputs: a ValueError naming the parameter."""
    scalar = bad if np.ndim(bad) == 0 else "x"
    for function, args in ((helix.rotation_z, (scalar,)), (helix.to_global, (np.eye(3), bad)),
                           (helix.to_frenet, (bad, [1.0, 0.0, 0.0])), (helix.lead_angle, (scalar, 1.0)),
                           (helix.contact_offset, (1e-3, 0.5, bad))):
        assert call(function, *args) is None   # call() returns None only after a ValueError naming a parameter


# --- geometry core: grooves ----------------------------------------------------------------------------
@SLOW
@given(pitch_radius=length, fraction=ball_fraction, conf=conformity, lead=length, alpha=contact_angle, psi=lead_angle,
       body=mostly(st.sampled_from(["screw", "nut"]), "ball"), plane=st.sampled_from(["normal", "axial"]),
       deviation=mostly(real(-0.1, 0.1), -0.3, 0.3), iterations=count)
def test_grooves(pitch_radius, fraction, conf, lead, alpha, psi, body, plane, deviation, iterations):
    ball_radius = pitch_radius * fraction
    call(groove.groove_radius, ball_radius, conf)
    call(groove.straight_groove_curvatures, ball_radius, conf)
    call(groove.gothic_arch, ball_radius, conf, alpha, deviation, -deviation)
    call(groove.groove_curvatures_helical, ball_radius, conf, pitch_radius, alpha, psi, body, plane)
    flank = call(groove.helical_groove, ball_radius, conf, pitch_radius, lead, alpha, body, "right", plane)
    if flank is None:
        return
    frame = call(groove.contact_frame, flank)
    if frame is not None:   # the exact frame is orthonormal and the ball centre lies R_B from the contact
        np.testing.assert_allclose(frame.rotation @ frame.rotation.T, np.eye(3), atol=1e-9)
    r = flank.ball_radius
    call(groove.counter_height, flank, [0.0, 0.1 * r], [0.0, -0.1 * r], iterations=iterations)
    points = call(flank.surface, [flank.contact_theta, flank.contact_theta + 0.05], [0.0, 0.01])
    if points is not None:
        call(groove.profile_coordinates, flank, points, iterations=iterations)
        call(groove.surface_residual, flank, points)
        call(groove.surface_residual, flank, points, radius=deviation)


# --- contact: ball in a helical groove -----------------------------------------------------------------
@SETTINGS
@given(preload=force, balls=count, psi=lead_angle, alpha=contact_angle, a=length, b=length, p0=force,
       rotation=mostly(real(-4.0, 4.0), *EXTREME))
def test_screw_contact(preload, balls, psi, alpha, a, b, p0, rotation):
    call(sc.preload_contact_load, preload, balls, psi, alpha)
    grid = halfspace.hertz_surface_grid(1e-4, 5e-5, 8, 1.3)
    field = call(sc.hertz_pressure, grid, a, b, p0, rotation, (0.1 * a, 0.0))
    if field is not None:
        assert np.all(field >= 0.0) and np.all(field <= p0)


@SETTINGS
@given(ball_radius=mostly(positive(1e-4, 1e-2), *EXTREME), conf=mostly(real(0.51, 0.6), 0.5, 1.0),
       lead=mostly(real(0.0, 0.05), *EXTREME), alpha=mostly(real(0.3, 1.2), *angle_limits),
       load=mostly(real(1.0, 1e3), *EXTREME), body=st.sampled_from(["screw", "nut"]))
def test_groove_contact(ball_radius, conf, lead, alpha, load, body):
    call(sc.groove_contact, ball_radius, conf, 6.0 * ball_radius, lead, alpha, load, body, youngs_modulus=2.1e11,
         poisson_ratio=0.3, n=16)


# --- screw kinematics: the parts kinematics() does not call through its public name ---------------------
@SETTINGS
@given(omega=speed, fraction=ball_fraction, pitch_radius=length, alpha_o=contact_angle, alpha_i=contact_angle,
       psi=lead_angle, beta=contact_angle, sliding=speed, entrainment=speed, mass=length)
def test_kinematics_parts(omega, fraction, pitch_radius, alpha_o, alpha_i, psi, beta, sliding, entrainment, mass):
    ball_radius = pitch_radius * fraction
    call(kin.pitch_angle, alpha_o, ball_radius, pitch_radius)
    orbit = call(kin.orbital_speed, omega, ball_radius, pitch_radius, alpha_o, alpha_i, beta)
    spin = call(kin.ball_spin_speed, omega, ball_radius, pitch_radius, alpha_o, psi, beta)
    call(kin.ball_angular_velocity, omega, beta)
    call(kin.ball_angular_velocity, True if spin is None else spin, beta, psi)
    call(kin.centrifugal_force, mass, pitch_radius, omega if orbit is None else orbit)
    call(kin.entrainment_velocity, [sliding, 0.0, entrainment], [entrainment, omega, 0.0])
    ratio = call(kin.slide_roll_ratio_magnitude, sliding, entrainment)
    if ratio is not None:
        assert ratio >= 0.0
    call(kin.slide_roll_ratio, [sliding, omega, 0.0], entrainment)
    call(kin.absolute_velocity_measures, [sliding, 0.0, omega], [entrainment, 0.0, 0.0], raceway_is_driver=True)


@SETTINGS
@given(surface=speed, pitch_radius=length, fraction=ball_fraction, lead=length, alpha=contact_angle,
       mu=mostly(real(0.0, 0.5), -0.1, 1e300), load=force, sliding=st.tuples(speed, speed, speed), balls=count,
       psi=lead_angle)
def test_friction_torque(surface, pitch_radius, fraction, lead, alpha, mu, load, sliding, balls, psi):
    ball_radius = pitch_radius * fraction
    call(ft.screw_angular_speed, surface, pitch_radius)
    call(ft.contact_speeds, surface, pitch_radius, ball_radius, lead, alpha)
    torque = call(ft.friction_torque, mu, load, sliding, ball_count=balls, lead_angle=psi, pitch_radius=pitch_radius,
                  ball_radius=ball_radius, contact_angle_B=alpha)
    if torque is not None:   # |M| <= n mu Q (r + r_b cos beta): the friction force mu Q_B has no larger lever
        assert torque <= balls * mu * load * (pitch_radius + ball_radius * math.cos(alpha)) * (1.0 + 1e-12)


# --- one ball, two balls and the sampled-traction model (lin2019 Sec 3) ---------------------------------
module_kwargs = st.fixed_dictionaries({
    "ball_radius": positive(1e-3, 5e-3), "conformity": real(0.5005, 0.7), "lead": real(0.0, 0.05),
    "nominal_angle": real(0.3, 1.2), "nut_speed": real(-20.0, 20.0), "friction_coefficient": real(1e-3, 0.5),
    "oversize": real(0.0, 2e-6)})
# one parameter of the module at a bad or extreme value, in about half the draws
SPOILERS = [None] * 10 + [("ball_radius", v) for v in (0.0, 5e-324, 1e300, -1e-3)] + [
    ("conformity", v) for v in (0.5, math.nextafter(0.5, 1.0), 1.0)] + [("lead", v) for v in (-1e-3, 1e300, 5e-324)] + [
    ("nominal_angle", v) for v in angle_limits] + [("nut_speed", v) for v in (0.0, 1e-300, 1e300)] + [
    ("friction_coefficient", v) for v in (0.0, -0.1, 1e300, 1e-300)] + [("oversize", v) for v in (-1e-9, 1.0)]


@SETTINGS
@given(kwargs=module_kwargs, spoiler=st.sampled_from(SPOILERS),
       deviation=st.lists(mostly(real(-0.05, 0.05), -0.3, 0.3), min_size=1, max_size=3),
       reading=mostly(st.sampled_from(["tilted", "rotated"]), "sideways"), gamma=angle,
       index=mostly(st.integers(0, 3), -1, 4, True, 1.0), load=mostly(real(1.0, 500.0), -1.0, 0.0, 1e300))
def test_screw_ball(kwargs, spoiler, deviation, reading, gamma, index, load):
    module = call(screw_contacts.screw_module, **(kwargs if spoiler is None else {**kwargs, spoiler[0]: spoiler[1]}))
    if module is None:
        return
    call(screw_contacts.flank_angles, module.nominal_angle, deviation, reading)
    contacts = call(screw_contacts.ball_contacts, module, deviation, reading)
    if contacts is None:
        return
    call(screw_contacts.arc_profile, contacts, gamma, load * 1e-9)
    call(screw_contacts.profile_2d, contacts, index, index, gamma, 0.1, load * 1e-9)
    call(sb.reference_force, contacts, load)
    call(sb.continuation_start, contacts, load)
    call(sb.free_rolling_guess, contacts)
    call(b2b.pair_geometry, module)
    call(b2b.b2b_angle_eq56, module)
    call(b2b.check_gaps, [load * 1e-3] * index if isinstance(index, int) and 0 <= index < 50 else None, index)
    single = call(screw_contacts.ball_contacts, module, deviation[0], reading)
    if single is None:
        return
    state = call(sb.solve, single, load, tolerance=1e-9, max_iterations=60)
    if state is not None:   # the nut puts in what friction dissipates (lin2019 Sec 3.1 power balance)
        assert abs(state.input_power - state.total_loss) <= 1e-6 * abs(state.total_loss)
        call(b2b.saturation, state)
    state = call(b2b.solve, contacts, load * len(deviation), tolerance=1e-9, max_iterations=60)
    if state is not None:
        assert abs(state.input_power - state.total_loss) <= 1e-6 * abs(state.total_loss)
        assert np.all(state.b2b_force >= 0.0)
        patches = call(traction.hertz_patches, state, contacts, index if isinstance(index, int) else 0,
                       n_radial=4, n_angular=8)
        if patches is not None and any(p.top for p in patches):
            free = call(traction.solve, [patches], module, max_iterations=60)
            if free is not None:
                assert free.power_balance <= traction.POWER_BALANCE_TOLERANCE


@SETTINGS
@given(a=mostly(real(-1e3, 1e3), *EXTREME, -1e300), b=mostly(real(-1e3, 1e3), *EXTREME, -1e300))
def test_fischer_burmeister(a, b):
    result = call(b2b_chain.fischer_burmeister, a, b)
    if result is not None:   # phi = 0 only on the complementarity set (eqs 60-61): < 0 outside, > 0 inside
        phi = float(result[0])
        scale = 1e-13 * max(abs(a), abs(b), 1.0)
        if min(a, b) < -scale:
            assert phi < 0.0
        elif min(a, b) > scale:
            assert phi > 0.0


# --- load distribution and the whole screw ---------------------------------------------------------------
@lru_cache(maxsize=1)
def _stiffness():
    module = screw_contacts.screw_module(oversize=1e-6)
    return module, ld.axial_stiffness(module, 200.0, 5), ld.bar_sections(module)


@SETTINGS
@given(positions=st.lists(mostly(real(0.0, 4.0 * math.pi), *EXTREME), min_size=0, max_size=8),
       total=mostly(real(0.0, 500.0), *EXTREME), lead=length, modulus=mostly(positive(1e9, 1e12), *EXTREME),
       lead_error=mostly(real(-1e-5, 1e-5), *EXTREME), tolerance=mostly(st.just(1e-10), 0.0, -1.0, 1e-300),
       iterations=mostly(st.just(50), -1, 0, 1, True, 2.0), screw_radius=length, outer=mostly(real(0.03, 0.1),
                                                                                              *EXTREME))
def test_load_distribution(positions, total, lead, modulus, lead_error, tolerance, iterations, screw_radius, outer):
    module, stiffness, sections = _stiffness()
    call(ld.bar_sections, module, screw_radius=screw_radius, nut_outer_radius=outer)
    call(stiffness.load, stiffness.shifts.mean())
    loads = call(ld.distribute, positions, total, stiffness, sections, lead, modulus, lead_error=lead_error,
                 tolerance=tolerance, max_iterations=iterations)
    if loads is not None:   # the balls carry the axial load between them
        assert loads.shape == (len(positions),)
        assert math.isclose(float(np.sum(loads)), total, rel_tol=1e-6, abs_tol=1e-9)


@SLOW
@given(max_load=mostly(real(1.0, 500.0), *EXTREME), points=mostly(st.integers(4, 8), -1, 0, 3, True, 4.0))
def test_axial_stiffness(max_load, points):
    module = _stiffness()[0]
    table = call(ld.axial_stiffness, module, max_load, points)
    if table is not None:
        assert np.all(np.diff(table.shifts) > 0.0) or np.all(np.diff(table.shifts) < 0.0)


@pytest.mark.slow
@SLOW
@given(n_balls=mostly(st.integers(2, 12), -1, 0, 1, True, 2.0, 100), load=mostly(real(0.0, 1000.0), *EXTREME),
       duration=mostly(real(0.01, 2.0), *EXTREME), steps=mostly(st.integers(1, 3), 0, True),
       amplitude=mostly(real(0.0, 0.05), -0.01, 0.2), cycles=mostly(st.integers(0, 6), -1, True),
       lead_error=mostly(real(-1e-5, 1e-5), *EXTREME))
def test_whole_screw(n_balls, load, duration, steps, amplitude, cycles, lead_error):
    module, stiffness, sections = _stiffness()
    history = call(whole_screw.simulate, module, n_balls=n_balls, axial_load=load, duration=duration, steps=steps,
                   amplitude=amplitude, cycles=cycles, lead_error=lead_error, stiffness=stiffness, sections=sections)
    if history is not None:
        assert np.allclose(history.axial_load.sum(axis=1), load, rtol=1e-6)
