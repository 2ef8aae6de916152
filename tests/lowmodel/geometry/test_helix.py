"""lowmodel.geometry.helix: Frenet frame of the ball-centre helix, contact points (wang2022 eqs 9-15)."""
import numpy as np
import pytest

from ballbench.lowmodel.geometry import helix
import math
from hypothesis import given, strategies as st
from tests.property_support import EXTREME, SETTINGS, call, mostly, real
from tests.property_support import length, speed, lead_angle, contact_angle, ball_fraction

R_M = 20.7e-3  # m, wang2022 Table A1 (d_m / 2)
LEAD = 20e-3  # m
R_B = 3.175e-3  # m (d_b / 2)


def _numerical_frame(theta, radius, lead, step=2e-3):
    """Frenet frame, curvature and torsion from finite differences of the helix."""
    def point(angle):
        return helix.ball_centre(angle, radius, lead)

    d1 = (point(theta + step) - point(theta - step)) / (2 * step)
    d2 = (point(theta + step) - 2 * point(theta) + point(theta - step)) / step**2
    d3 = (point(theta + 2 * step) - 2 * point(theta + step) + 2 * point(theta - step) - point(theta - 2 * step)) / (
        2 * step**3)
    speed = np.linalg.norm(d1)
    tangent = d1 / speed
    cross = np.cross(d1, d2)
    kappa = np.linalg.norm(cross) / speed**3
    tau = np.dot(cross, d3) / np.linalg.norm(cross) ** 2
    binormal = cross / np.linalg.norm(cross)
    normal = np.cross(binormal, tangent)
    return np.stack([tangent, normal, binormal], axis=-1), kappa, tau


def test_lead_angle_table_a1():
    # wang2022 Table A1: L = 20 mm, d_m = 41.4 mm -> psi = 8.74 deg (printed)
    assert abs(np.degrees(helix.lead_angle(LEAD, R_M)) - 8.74) < 0.005


@pytest.mark.parametrize("lead", [0.0, 5e-3, LEAD, 60e-3])
def test_frame_orthonormal_right_handed(lead):
    theta = np.linspace(-7.0, 7.0, 29)
    frame = helix.frenet_frame(theta, helix.lead_angle(lead, R_M))
    assert frame.shape == (29, 3, 3)
    gram = np.einsum("...ki,...kj->...ij", frame, frame)
    np.testing.assert_allclose(gram, np.broadcast_to(np.eye(3), gram.shape), atol=1e-15)
    np.testing.assert_allclose(np.linalg.det(frame), 1.0, atol=1e-14)


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.5, -4.0])
@pytest.mark.parametrize("lead", [5e-3, LEAD, 60e-3])
def test_frame_curvature_torsion_match_finite_differences(theta, lead):
    frame_fd, kappa_fd, tau_fd = _numerical_frame(theta, R_M, lead)
    frame = helix.frenet_frame(theta, helix.lead_angle(lead, R_M))
    np.testing.assert_allclose(frame, frame_fd, atol=1e-5)
    h = lead / (2 * np.pi)
    # known helix curvature r/(r^2+h^2) and torsion h/(r^2+h^2)
    assert helix.curvature(R_M, lead) == pytest.approx(R_M / (R_M**2 + h**2), rel=1e-14)
    assert helix.torsion(R_M, lead) == pytest.approx(h / (R_M**2 + h**2), rel=1e-14)
    assert kappa_fd == pytest.approx(float(helix.curvature(R_M, lead)), rel=1e-5)
    assert tau_fd == pytest.approx(float(helix.torsion(R_M, lead)), rel=1e-4)


def test_lead_zero_is_a_circle():
    assert helix.torsion(R_M, 0.0) == 0.0
    assert helix.curvature(R_M, 0.0) == pytest.approx(1 / R_M)
    frame = helix.frenet_frame(0.0, 0.0)
    np.testing.assert_allclose(frame, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=0)


def test_frame_at_theta_zero_is_eq15():
    psi = helix.lead_angle(LEAD, R_M)
    c, s = np.cos(psi), np.sin(psi)
    np.testing.assert_allclose(helix.frenet_frame(0.0, psi), [[0, -1, 0], [c, 0, -s], [s, 0, c]], atol=1e-16)


def test_frame_angular_velocity_is_darboux_vector():
    """dT/dtheta = W x T with W = k (the frame turns about the axis at theta')."""
    psi = helix.lead_angle(LEAD, R_M)
    theta, step = 0.9, 1e-6
    frame = helix.frenet_frame(theta, psi)
    derivative = (helix.frenet_frame(theta + step, psi) - helix.frenet_frame(theta - step, psi)) / (2 * step)
    omega_frenet = helix.frame_angular_velocity(1.0, psi)
    omega_global = helix.to_global(frame, omega_frenet)
    np.testing.assert_allclose(omega_global, [0, 0, 1], atol=1e-15)
    for column in range(3):
        np.testing.assert_allclose(derivative[:, column], np.cross(omega_global, frame[:, column]), atol=1e-8)
    # Darboux vector (tau t + kappa b) ds/dtheta
    ds = np.hypot(R_M, LEAD / (2 * np.pi))
    np.testing.assert_allclose(omega_frenet, [helix.torsion(R_M, LEAD) * ds, 0, helix.curvature(R_M, LEAD) * ds],
                               rtol=1e-14)


def test_contact_points_eqs_13_14():
    theta, alpha, phi = np.linspace(-3, 3, 13), np.radians(40.0), 0.3
    psi = helix.lead_angle(LEAD, R_M)
    h = LEAD / (2 * np.pi)
    ca, sa, sp, cp = np.cos(alpha), np.sin(alpha), np.sin(psi), np.cos(psi)
    ct, st = np.cos(theta), np.sin(theta)
    nut = np.stack([R_M * ct + R_B * (ca * ct + sa * st * sp), R_M * st + R_B * (ca * st - sa * ct * sp),
                    (theta - phi) * h + R_B * sa * cp], axis=-1)  # wang2022 eq 13
    screw = np.stack([R_M * ct - R_B * (ca * ct + sa * st * sp), R_M * st - R_B * (ca * st - sa * ct * sp),
                      (theta - phi) * h - R_B * sa * cp], axis=-1)  # wang2022 eq 14
    np.testing.assert_allclose(helix.contact_point(theta, R_M, LEAD, R_B, alpha, "nut", phi), nut, atol=1e-16)
    np.testing.assert_allclose(helix.contact_point(theta, R_M, LEAD, R_B, alpha, "screw", phi), screw, atol=1e-16)
    # both contacts lie on the ball
    centre = helix.ball_centre(theta, R_M, LEAD, phi)
    np.testing.assert_allclose(np.linalg.norm(nut - centre, axis=-1), R_B, rtol=1e-14)


def test_to_frenet_inverts_to_global():
    rng = np.random.default_rng(1)
    frame = helix.frenet_frame(rng.uniform(-5, 5, 10), rng.uniform(0, 1.2, 10))
    vector = rng.normal(size=(10, 3))
    np.testing.assert_allclose(helix.to_frenet(frame, helix.to_global(frame, vector)), vector, atol=1e-15)


def test_ball_centre_velocity_is_time_derivative():
    omega, omega_m, step = 200.0, 90.0, 1e-7
    psi = helix.lead_angle(LEAD, R_M)

    def centre(time):
        return helix.ball_centre(omega_m * time, R_M, LEAD, omega * time)

    velocity_global = (centre(step) - centre(-step)) / (2 * step)
    expected = helix.to_frenet(helix.frenet_frame(0.0, psi), velocity_global)
    np.testing.assert_allclose(helix.ball_centre_velocity(omega_m, omega, R_M, LEAD), expected, atol=1e-7)


@pytest.mark.parametrize("call, name", [
    (lambda: helix.lead_angle(-1e-3, R_M), "lead"),
    (lambda: helix.lead_angle(LEAD, 0.0), "pitch_radius"),
    (lambda: helix.lead_angle(LEAD, np.nan), "pitch_radius"),
    (lambda: helix.frenet_frame(np.nan, 0.1), "theta"),
    (lambda: helix.frenet_frame(0.0, -0.1), "lead_angle"),
    (lambda: helix.frenet_frame(0.0, np.pi / 2), "lead_angle"),
    (lambda: helix.contact_offset(-R_B, 0.7, "nut"), "ball_radius"),
    (lambda: helix.contact_offset(R_B, 0.0, "nut"), "contact_angle"),
    (lambda: helix.contact_offset(R_B, np.radians(95), "nut"), "contact_angle"),
    (lambda: helix.contact_offset(R_B, 0.7, "cage"), "body"),
    (lambda: helix.ball_centre(0.0, R_M, LEAD, np.inf), "screw_angle"),
])
def test_bad_input_names_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_broadcasting_balls_by_geometries():
    theta = np.linspace(0, 2 * np.pi, 6)[:, None]  # balls
    leads = np.array([0.0, 10e-3, 20e-3, 40e-3])  # geometries
    points = helix.contact_point(theta, R_M, leads, R_B, np.radians(45), "screw")
    assert points.shape == (6, 4, 3)
    single = helix.contact_point(theta[2, 0], R_M, leads[3], R_B, np.radians(45), "screw")
    np.testing.assert_allclose(points[2, 3], single, rtol=1e-15)
    assert helix.frame_angular_velocity(np.ones((6, 1)), helix.lead_angle(leads, R_M)).shape == (6, 4, 3)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


TINY = 5e-324  # the smallest float


TABLE4 = dict(pitch_radius=16.5e-3, lead=20e-3)  # lin2019 Table 4


@pytest.mark.filterwarnings("error")
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


@pytest.mark.filterwarnings("error")
def test_ball_centre_azimuths_is_scale_free():
    """Were OverflowError (1e300 m) and ZeroDivisionError (5e-324 m); scaling every length by a power of two
    gives the same bits (the FE meshes of meshes.assemblies use it: chaotic at the ulp level)."""
    table4 = helix.ball_centre_azimuths(16.5e-3, 20e-3, 2 * 2.778e-3)
    for scale in (2.0**900, 2.0**-900):
        assert helix.ball_centre_azimuths(16.5e-3 * scale, 20e-3 * scale, 2 * 2.778e-3 * scale) == table4
    assert helix.ball_centre_azimuths(1e300, 0.0, 1e300) == pytest.approx(2 * math.asin(0.5), rel=1e-14)
    assert helix.ball_centre_azimuths(TINY, 0.0, TINY) == pytest.approx(2 * math.asin(0.5), rel=1e-14)


@pytest.mark.filterwarnings("error")
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


@pytest.mark.filterwarnings("error")
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


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


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
