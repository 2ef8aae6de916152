"""Geometry core (lowmodel.geometry) and shared input checks (lowmodel.checks).

References are built here without calling the function judged: explicit rotation
matrices (lin2019 eq 41), lin2017 eq 1 written out, an independent swept-surface
fit for the groove curvatures, the chord of two helix points.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry import fourpoint, groove, helix
from hypothesis import given, strategies as st
from tests.property_support import SLOW, call, mostly, real
from tests.property_support import length, lead_angle, contact_angle, ball_fraction, count

R_B, CONF, R_P, LEAD, BETA = 2.778e-3, 0.56, 16.5e-3, 20e-3, math.radians(45)  # lin2019 Table 4


# --------------------------------------------------------------------------
# helix and frames
# --------------------------------------------------------------------------
def _rot_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@pytest.mark.parametrize("phi", [0.0, 0.3, -2.1, 4.0])
@pytest.mark.parametrize("lead", [0.0, LEAD, 60e-3])
def test_cs3_frame_is_lin2019_eq41(phi, lead):
    """T_CS-CS3 = rot_z(phi) rot_x(alpha) (lin2019 eq 41), alpha = atan(lead / 2 pi R_P) (eq 42)."""
    alpha = math.atan(lead / (2 * math.pi * R_P))
    reference = _rot_z(phi) @ _rot_x(alpha)
    np.testing.assert_allclose(helix.cs3_frame(phi, helix.lead_angle(lead, R_P)), reference, atol=1e-15)
    np.testing.assert_allclose(helix.rotation_z(phi), _rot_z(phi), atol=1e-16)
    # x3 radial through the ball centre, y3 along the helix (finite difference of lin2019 eq 35)
    centre = helix.ball_centre(phi, R_P, lead)
    np.testing.assert_allclose(reference[:, 0], centre * [1, 1, 0] / R_P, atol=1e-15)
    step = 1e-6
    tangent = helix.ball_centre(phi + step, R_P, lead) - helix.ball_centre(phi - step, R_P, lead)
    np.testing.assert_allclose(reference[:, 1], tangent / np.linalg.norm(tangent), atol=1e-9)


def test_cs3_and_frenet_are_one_trihedron():
    """(x3, y3, z3) = (-n, t, b): the same frame, reordered."""
    theta, psi = np.linspace(-3, 3, 7)[:, None], np.linspace(0, 1.2, 5)[None, :]
    frenet, cs3 = helix.frenet_frame(theta, psi), helix.cs3_frame(theta, psi)
    np.testing.assert_array_equal(cs3[..., 0], -frenet[..., 1])
    np.testing.assert_array_equal(cs3[..., 1], frenet[..., 0])
    np.testing.assert_array_equal(cs3[..., 2], frenet[..., 2])


def test_ball_centre_velocity_takes_a_given_lead_angle():
    """wang2022 Table A1 prints psi = 8.74 deg: a given lead angle replaces arctan(h / r_m)."""
    psi = math.radians(8.74)
    velocity = helix.ball_centre_velocity(3.0, 10.0, 20.7e-3, 20e-3, lead_angle=psi)
    h = 20e-3 / (2 * math.pi)
    expected = 3.0 * 20.7e-3 * np.array([math.cos(psi), 0, -math.sin(psi)]) \
        + (3.0 - 10.0) * h * np.array([math.sin(psi), 0, math.cos(psi)])
    np.testing.assert_allclose(velocity, expected, rtol=1e-15, atol=1e-18)


@pytest.mark.parametrize("lead", [0.0, 5e-3, LEAD, 60e-3])
@pytest.mark.parametrize("spacing", [2 * R_B, 3.3 * R_B, R_P])
def test_ball_centre_azimuths_give_the_chord(lead, spacing):
    dphi = helix.ball_centre_azimuths(R_P, lead, spacing)
    chord = np.linalg.norm(helix.ball_centre(dphi / 2, R_P, lead) - helix.ball_centre(-dphi / 2, R_P, lead))
    assert chord == pytest.approx(spacing, rel=1e-13)


def test_ball_centre_azimuths_bad_input():
    with pytest.raises(ValueError, match=r"spacing must lie in \(0, 0\.033\] m"):
        helix.ball_centre_azimuths(R_P, 0.0, 0.04)
    with pytest.raises(ValueError, match="lead"):
        helix.ball_centre_azimuths(R_P, -1e-3, 2 * R_B)


# --------------------------------------------------------------------------
# four-point contact geometry
# --------------------------------------------------------------------------
def test_contact_points_are_lin2017_eq1():
    b = np.radians([40.0, 47.0, 44.0, 52.0])
    expected = 5e-3 * np.array([[-math.sin(b[0]), -math.cos(b[0])], [math.sin(b[1]), -math.cos(b[1])],
                                [math.sin(b[2]), math.cos(b[2])], [-math.sin(b[3]), math.cos(b[3])]])
    np.testing.assert_allclose(fourpoint.contact_points(5e-3, b), expected, rtol=1e-15, atol=1e-18)
    assert fourpoint.CONTACT_NAMES == ("BL", "BR", "TR", "TL")
    for k, name in enumerate(fourpoint.CONTACT_NAMES):
        np.testing.assert_allclose(5e-3 * fourpoint.contact_normal(name, b[k]),
                                   fourpoint.contact_points(5e-3, np.full(4, b[k]))[k], rtol=1e-15)


@pytest.mark.parametrize("args, match", [
    ((-5e-3, np.full(4, 0.7)), "ball_radius"),
    ((5e-3, np.full(3, 0.7)), "trailing axis of 4"),
    ((5e-3, [0.7, 0.7, 1.6, 0.7]), r"contact_angles must lie in \(0, pi/2\) rad"),
])
def test_contact_points_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        fourpoint.contact_points(*args)


# --------------------------------------------------------------------------
# grooves
# --------------------------------------------------------------------------
@pytest.mark.parametrize("deviations", [(0.0, 0.0), (-0.05, 0.08)])
def test_gothic_arch_flanks_touch_the_ball_at_their_contact_angles(deviations):
    """Each flank circle passes through its lin2017 eq 1 contact point with its normal through the ball centre."""
    arch = groove.gothic_arch(5e-3, CONF, BETA, *deviations)
    r_g = 2 * CONF * 5e-3
    for side, beta in (("left", BETA + deviations[0]), ("right", BETA + deviations[1])):
        sign = -1.0 if side == "left" else 1.0
        point = 5e-3 * np.array([sign * math.sin(beta), -math.cos(beta)])
        centre = arch.arc_centre(side)
        assert np.linalg.norm(point - centre) == pytest.approx(r_g, rel=1e-14)
        np.testing.assert_allclose(arch.contact_point(side), point, rtol=1e-15)
        # centre, ball centre (origin) and contact point are collinear
        assert abs(point[0] * centre[1] - point[1] * centre[0]) < 1e-15 * r_g**2


def _fitted_curvatures(body, flank, plane, lead):
    """Independent route: the swept groove written out, its height over the tangent plane fitted.

    Returns (k_uu, k_uv, k_vv) in the basis (profile tangent, normal x profile tangent)."""
    alpha = math.atan(lead / (2 * math.pi * R_P))
    c = np.array([0.0, 0.0, 1.0]) if plane == "axial" else np.array([0.0, -math.sin(alpha), math.cos(alpha)])
    e_r = np.array([1.0, 0.0, 0.0])
    r_g = 2 * CONF * R_B
    outward = -1 if body == "screw" else 1
    side = -1 if flank == "left" else 1
    contact = np.array([R_P + outward * R_B * math.cos(BETA), side * R_B * math.sin(BETA)])  # (rho, along c)
    ball = np.array([R_P, 0.0])
    centre = contact + r_g * (ball - contact) / R_B
    angle0 = math.atan2(*(contact - centre)[::-1])
    p = lead / (2 * math.pi)
    s, phi = np.meshgrid(np.linspace(-2e-5, 2e-5, 21) / r_g, np.linspace(-2e-5, 2e-5, 21) / R_P)
    rho = centre[0] + r_g * np.cos(angle0 + s)
    w = centre[1] + r_g * np.sin(angle0 + s)
    local = rho[..., None] * e_r + w[..., None] * c
    points = np.stack([local[..., 0] * np.cos(phi) - local[..., 1] * np.sin(phi),
                       local[..., 0] * np.sin(phi) + local[..., 1] * np.cos(phi),
                       local[..., 2] + p * phi], axis=-1).reshape(-1, 3)
    origin = contact[0] * e_r + contact[1] * c
    d_s = -r_g * math.sin(angle0) * e_r + r_g * math.cos(angle0) * c
    d_phi = np.cross([0.0, 0.0, 1.0], origin) + p * np.array([0.0, 0.0, 1.0])
    normal = np.cross(d_s, d_phi)
    normal /= np.linalg.norm(normal)
    if normal @ ((ball[0] - contact[0]) * e_r + (ball[1] - contact[1]) * c) < 0:
        normal = -normal
    e1 = d_s / np.linalg.norm(d_s)
    e2 = np.cross(normal, e1)
    rel = points - origin
    u, v, h = rel @ e1, rel @ e2, rel @ normal
    design = np.stack([u * u, 2 * u * v, v * v, u**3, u * u * v, u * v * v, v**3,
                       u**4, u**3 * v, u * u * v * v, u * v**3, v**4], axis=1)
    coef = np.linalg.lstsq(design, -2 * h, rcond=None)[0]
    return coef[:3]


@pytest.mark.parametrize("lead", [0.0, LEAD, 60e-3])
@pytest.mark.parametrize("plane", ["normal", "axial"])
@pytest.mark.parametrize("body", ["screw", "nut"])
@pytest.mark.parametrize("flank", ["left", "right"])
def test_contact_frame_curvatures_by_surface_fit(flank, body, plane, lead):
    """The fundamental-form curvatures and principal angle against a fit of the swept surface
    (replaces the cross-check of two copies of the fundamental-form code; the fit, with
    terms to fourth order over +-20 um, agrees to 6e-10)."""
    frame = groove.contact_frame(groove.helical_groove(R_B, CONF, R_P, lead, BETA, body, flank, plane))
    k_uu, k_uv, k_vv = _fitted_curvatures(body, flank, plane, lead)
    values, vectors = np.linalg.eigh(np.array([[k_uu, k_uv], [k_uv, k_vv]]))
    across = int(np.argmax(np.abs(vectors[0])))  # the principal direction nearest the profile tangent
    assert frame.curvature_major == pytest.approx(values[across], rel=1e-8)
    assert frame.curvature_minor == pytest.approx(values[1 - across], rel=1e-8)
    assert frame.profile_angle == pytest.approx(math.acos(min(1.0, abs(vectors[0, across]))), abs=1e-8)
    if flank == "right":  # groove_curvatures_helical evaluates the right flank
        k1, k2, angle = groove.groove_curvatures_helical(R_B, CONF, R_P, BETA, math.atan(lead / (2 * math.pi * R_P)),
                                                         body, plane)
        assert (k1, k2) == pytest.approx((values[across], values[1 - across]), rel=1e-8)


@pytest.mark.parametrize("body", ["screw", "nut"])
def test_zero_lead_curvatures_are_harris_raceway(body):
    """lead = 0: the torus of a bearing raceway (Harris): (-1/r_g, +-cos b / (R_P -+ R_B cos b))."""
    k1, k2, angle = groove.groove_curvatures_helical(R_B, CONF, R_P, BETA, 0.0, body)
    sign = 1.0 if body == "screw" else -1.0
    assert k1 == pytest.approx(-1.0 / (2 * CONF * R_B), rel=1e-13)
    assert k2 == pytest.approx(sign * math.cos(BETA) / (R_P - sign * R_B * math.cos(BETA)), rel=1e-13)
    assert angle == pytest.approx(0.0, abs=1e-12)


def test_helical_groove_lead_angle_and_helix_are_the_helix_module():
    g = groove.helical_groove(R_B, CONF, R_P, LEAD, BETA)
    assert g.lead_angle == pytest.approx(math.atan(LEAD / (2 * math.pi * R_P)), rel=1e-15)
    phi = np.linspace(-1, 1, 5)
    expected = np.stack([R_P * np.cos(phi), R_P * np.sin(phi), LEAD / (2 * math.pi) * phi], -1)  # lin2019 eq 35
    np.testing.assert_allclose(g.helix(phi), expected, rtol=1e-15, atol=1e-18)
    np.testing.assert_allclose(g.plane_axis, [0.0, -math.sin(g.lead_angle), math.cos(g.lead_angle)], atol=1e-16)


@pytest.mark.parametrize("call, match", [
    (lambda: groove.helical_groove(R_B, 0.5, R_P, LEAD, BETA), r"conformity must lie in \(0\.5, 1\)"),
    (lambda: groove.helical_groove(R_B, 1.0, R_P, LEAD, BETA), r"conformity must lie in \(0\.5, 1\)"),
    (lambda: groove.helical_groove(R_B, CONF, R_P, -1e-3, BETA), r"lead must be finite and >= 0 m"),
    (lambda: groove.helical_groove(R_B, CONF, R_P, LEAD, BETA, flank="top"), "flank must be one of"),
    (lambda: groove.helical_groove(R_B, CONF, R_P, LEAD, BETA, profile_plane="oblique"), "profile_plane"),
    (lambda: groove.helical_groove(R_B, CONF, 3e-3, LEAD, BETA), "pitch_radius must exceed the groove radius"),
    (lambda: groove.groove_curvatures_helical(R_B, CONF, R_P, BETA, -0.1), r"lead_angle must lie in \[0, pi/2\)"),
    (lambda: groove.gothic_arch(5e-3, CONF, BETA, 0.3), r"deviation_left must lie in .* rad \(i\.e\. \[-15, 15\] deg"),
    (lambda: groove.gothic_arch(5e-3, CONF, BETA, land_height=1e-3), "land_height"),
])
def test_groove_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# --------------------------------------------------------------------------
# lowmodel.checks
# --------------------------------------------------------------------------
@pytest.mark.parametrize("call, match", [
    (lambda: checks.positive("ball_radius", -1e-3, "m"), r"ball_radius must be finite and > 0 m, .*got -0\.001$"),
    (lambda: checks.positive("ball_radius", math.nan, "m"), r"ball_radius .*got nan"),
    (lambda: checks.positive("forces", [1.0, 0.0, 2.0], "N"), r"forces .*got 0\.0 \(first offending element .*\(3,\)"),
    (lambda: checks.non_negative("lead", -1.0, "m"), r"lead must be finite and >= 0 m"),
    (lambda: checks.finite("theta", [0.0, math.inf]), r"theta must be finite"),
    (lambda: checks.finite("theta", "abc"), r"theta must be a real number"),
    (lambda: checks.finite("theta", True), r"theta must be a real number, not a boolean"),
    (lambda: checks.contact_angle("contact_angle", math.pi / 2), r"\(0, pi/2\) rad \(i\.e\. \(0, 90\) deg\)"),
    (lambda: checks.lead_angle("lead_angle", -0.1), r"\[0, pi/2\) rad"),
    (lambda: checks.conformity("conformity", 0.5), r"conformity must lie in \(0\.5, 1\) \(groove radius"),
    (lambda: checks.conformity("conformity", 1.2), r"got 1\.2"),
    (lambda: checks.choice("body", "cage", ("nut", "screw")), r"body must be one of \('nut', 'screw'\), got 'cage'"),
    (lambda: checks.choice("body", ["nut"], ("nut", "screw")), r"body must be one of"),
    (lambda: checks.count("n_balls", True, 1), r"n_balls must be an integer \(not a bool"),
    (lambda: checks.count("n_balls", 2.0, 1), r"n_balls must be an integer"),
    (lambda: checks.count("n_balls", 0, 1), r"n_balls must be an integer in \[1, inf\), got 0"),
    (lambda: checks.count("element_order", 3, 1, 2), r"\[1, 2\], got 3"),
    (lambda: checks.trailing_axis("angles", [1.0, 2.0], 4, "(BL, BR, TR, TL)"), r"trailing axis of 4 \(BL"),
    (lambda: checks.bounded("poisson_ratio", 0.5, -1.0, 0.5), r"poisson_ratio must lie in \(-1, 0\.5\); got 0\.5"),
    # integers beyond float range were a bare OverflowError
    (lambda: checks.positive("creepage", 10**400), r"creepage must be finite; got an integer beyond float range"),
    (lambda: checks.finite("forces", [1, 10**400]), r"forces must be finite; .*\(406 characters\)"),
    (lambda: checks.four_angles("angles", [0, 0, 0, 10**400], "(BL, BR, TR, TL)"), r"angles must be four angles"),
])
def test_checks_name_parameter_range_and_value(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_checks_return_floats_for_scalars_and_arrays_for_arrays():
    assert type(checks.positive("x", 2)) is float
    assert type(checks.positive("x", np.float64(2.0))) is float
    array = checks.positive("x", [1, 2])
    assert isinstance(array, np.ndarray) and array.dtype == float
    assert checks.count("n", np.int64(3), 1) == 3 and type(checks.count("n", np.int64(3), 1)) is int
    assert checks.conformity("conformity", 0.56) == 0.56
    assert checks.choice("body", "nut", helix.BODIES) == "nut"


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


TINY = 5e-324  # the smallest float


@pytest.mark.filterwarnings("error")
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


@pytest.mark.filterwarnings("error")
def test_groove_radius_and_straight_curvature_check_their_inputs():
    """groove_radius(-1 m) returned -1.12 m; straight_groove_curvatures(5e-324 m) returned -inf."""
    with pytest.raises(ValueError, match="ball_radius"):
        groove.groove_radius(-1.0, 0.56)
    with pytest.raises(ValueError, match="conformity"):
        groove.groove_radius(1e-3, 0.4)
    with pytest.raises(ValueError, match="ball_radius"):
        groove.straight_groove_curvatures(TINY, 0.50001)
    assert groove.straight_groove_curvatures(5e-3, 0.52) == (-1.0 / (0.52 * 2 * 5e-3), 0.0)


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("iterations", [2.5, True, 0, -1])
def test_groove_newton_iterations_are_counts(iterations):
    """counter_height and profile_coordinates: 2.5 was a TypeError, True, 0 and -1 were accepted."""
    flank = groove.helical_groove(2.778e-3, 0.56, 16.5e-3, 20e-3, 0.785)
    with pytest.raises(ValueError, match="iterations"):
        groove.counter_height(flank, 0.0, 0.0, iterations=iterations)
    with pytest.raises(ValueError, match="iterations"):
        groove.profile_coordinates(flank, [[0.016, 0.0, 0.0]], iterations=iterations)


@pytest.mark.filterwarnings("error")
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


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


conformity = mostly(real(0.505, 0.7), 0.5, math.nextafter(0.5, 1.0), 0.5005, math.nextafter(1.0, 0.0), 1.0, 0.0)


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
