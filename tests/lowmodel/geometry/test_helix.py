"""lowmodel.geometry.helix: Frenet frame of the ball-centre helix, contact points (wang2022 eqs 9-15)."""
import numpy as np
import pytest

from ballbench.lowmodel.geometry import helix

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
