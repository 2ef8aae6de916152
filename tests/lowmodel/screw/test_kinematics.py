"""lowmodel.screw.kinematics and lowmodel.ball_bearing.harris against wang2022 (Tables 1-2, eqs 1-30, Sec 3.4
trends)."""
import numpy as np
import pytest

from ballbench.lowmodel.ball_bearing import harris

from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.screw import kinematics as sk, kinematics as screw
import math
from ballbench.lowmodel.screw import kinematics as kin
from hypothesis import given
from tests.property_support import SETTINGS, angle, call, positive, real
from tests.property_support import length, speed, lead_angle, contact_angle, ball_fraction

RPM = 2 * np.pi / 60
# wang2022 Table A1 (d_m and d_b are diameters; r_m, r_b radii)
TABLE_A1 = dict(pitch_radius=41.4e-3 / 2, ball_radius=6.35e-3 / 2, lead=20e-3, screw_speed=2000 * RPM,
                contact_angle_nut=np.radians(45.0))
HALF_UNIT = 0.0005  # Table 2 prints 3 decimals

# wang2022 Table 2, present model
TABLE2_PRESENT = {
    "nut_velocity": [-0.101, 0.000, -0.659],
    "screw_velocity": [3.820, 0.071, -0.587],
    "ball_velocity_nut": [-0.056, -0.032, -0.691],
    "ball_velocity_screw": [3.764, 0.032, -0.627],
    "sliding_velocity_nut": [0.045, -0.032, -0.032],
    "sliding_velocity_screw": [0.056, 0.040, 0.040],
    "entrainment_nut": 2.140,
    "entrainment_screw": 2.146,
    "slide_roll_nut": 0.030,
    "slide_roll_screw": 0.037,
}
# wang2022 Table 2, Wei's model: vectors as printed, and the U, S they lead to
TABLE2_WEI_VECTORS = {
    "nut": [-0.101, 0.000, -0.659], "screw": [3.820, -0.071, -0.587],
    "ball_nut": [1.789, 0.000, -0.659], "ball_screw": [1.919, 0.000, -0.659],
}
TABLE2_WEI = {"sliding_velocity_nut": [1.890, 0.000, 0.000], "sliding_velocity_screw": [1.901, -0.072, 0.072],
              "entrainment_nut": 1.071, "entrainment_screw": 2.937, "slide_roll_nut": 1.766,
              "slide_roll_screw": 0.648}


@pytest.fixture(scope="module")
def table2():
    return sk.kinematics(**TABLE_A1)


@pytest.mark.parametrize("name", list(TABLE2_PRESENT))
def test_table2_present_model(table2, name):
    np.testing.assert_allclose(getattr(table2, name), TABLE2_PRESENT[name], atol=HALF_UNIT, rtol=0)


@pytest.mark.parametrize("name", list(TABLE2_PRESENT))
def test_table2_with_printed_lead_angle(name):
    """Table A1 prints psi = 8.74 deg; with it instead of arctan(L / 2 pi r_m) Table 2 still holds."""
    result = sk.kinematics(**TABLE_A1, lead_angle=np.radians(8.74))
    np.testing.assert_allclose(getattr(result, name), TABLE2_PRESENT[name], atol=HALF_UNIT, rtol=0)


def test_table2_wei_measures_from_table_vectors():
    """Wei's U, V_S, S follow from the table's own absolute vectors through eqs 1-6 (to rounding)."""
    v = {key: np.array(value) for key, value in TABLE2_WEI_VECTORS.items()}
    u_a, s_vec_a, s_a = sk.absolute_velocity_measures(v["nut"], v["ball_nut"], raceway_is_driver=False)
    u_b, s_vec_b, s_b = sk.absolute_velocity_measures(v["screw"], v["ball_screw"], raceway_is_driver=True)
    # inputs carry +-0.0005 each: sums of two carry +-0.001, ratios a little more
    np.testing.assert_allclose(s_vec_a, TABLE2_WEI["sliding_velocity_nut"], atol=2 * HALF_UNIT)
    np.testing.assert_allclose(s_vec_b, TABLE2_WEI["sliding_velocity_screw"], atol=2 * HALF_UNIT)
    assert u_a == pytest.approx(TABLE2_WEI["entrainment_nut"], abs=2 * HALF_UNIT)
    assert u_b == pytest.approx(TABLE2_WEI["entrainment_screw"], abs=2 * HALF_UNIT)
    assert s_a == pytest.approx(TABLE2_WEI["slide_roll_nut"], abs=3e-3)
    assert s_b == pytest.approx(TABLE2_WEI["slide_roll_screw"], abs=3e-3)


def test_wei_raceway_and_centre_velocities_match_table2(table2):
    """The parts of Wei's column the equations define: raceway velocities and the ball-centre velocity."""
    wei = sk.wei_ball_centre_kinematics(**TABLE_A1)
    np.testing.assert_allclose(wei.nut_velocity, TABLE2_WEI_VECTORS["nut"], atol=HALF_UNIT)
    # Wei's printed screw n-component has the opposite sign of eq 17 (the paper's correction)
    np.testing.assert_allclose(wei.screw_velocity * [1, -1, 1], TABLE2_WEI_VECTORS["screw"], atol=HALF_UNIT)
    mean_ball = 0.5 * (np.array(TABLE2_WEI_VECTORS["ball_nut"]) + TABLE2_WEI_VECTORS["ball_screw"])
    np.testing.assert_allclose(wei.ball_velocity_nut, mean_ball, atol=HALF_UNIT)


def test_sliding_velocity_is_frame_independent(table2):
    """Eqs 5-6 with relative (27-30) or absolute velocities give the same sliding velocity."""
    np.testing.assert_allclose(table2.sliding_velocity_nut, table2.ball_velocity_nut - table2.nut_velocity,
                               atol=1e-15)
    np.testing.assert_allclose(table2.sliding_velocity_screw, table2.screw_velocity - table2.ball_velocity_screw,
                               atol=1e-15)


def test_printed_closed_forms_eqs_17_23_to_26(table2):
    r_m, r_b, omega = TABLE_A1["pitch_radius"], TABLE_A1["ball_radius"], TABLE_A1["screw_speed"]
    alpha, psi, h = TABLE_A1["contact_angle_nut"], table2.lead_angle, TABLE_A1["lead"] / (2 * np.pi)
    ca, sa, cp, sp = np.cos(alpha), np.sin(alpha), np.cos(psi), np.sin(psi)
    wm = table2.orbital_speed
    np.testing.assert_allclose(table2.screw_velocity, omega * np.array(
        [(r_m - r_b * ca) * cp, r_b * sa * sp, -(r_m - r_b * ca) * sp]), rtol=1e-13)  # eq 17
    np.testing.assert_allclose(table2.convected_velocity_nut, [
        wm * (r_m + r_b * ca) * cp + (wm - omega) * h * sp, -wm * r_b * sa * sp,
        -wm * (r_m + r_b * ca) * sp + (wm - omega) * h * cp], rtol=1e-13)  # eq 25
    np.testing.assert_allclose(table2.convected_velocity_screw, [
        wm * (r_m - r_b * ca) * cp + (wm - omega) * h * sp, wm * r_b * sa * sp,
        -wm * (r_m - r_b * ca) * sp + (wm - omega) * h * cp], rtol=1e-13)  # eq 26
    w_t, w_n, w_b = table2.ball_angular_velocity
    np.testing.assert_allclose(table2.ball_velocity_nut_rel,
                               [r_b * (w_n * sa + w_b * ca), -w_t * r_b * sa, -w_t * r_b * ca], atol=1e-15)  # eq 23
    np.testing.assert_allclose(table2.ball_velocity_screw_rel,
                               [-r_b * (w_n * sa + w_b * ca), w_t * r_b * sa, w_t * r_b * ca], atol=1e-15)  # eq 24


def test_convected_velocity_is_time_derivative_of_contact_points(table2):
    """V^e = d/dt R_O(A,B) at fixed position in CS1 (eqs 13-14 differentiated), and V_Bs = omega k x R_OB."""
    p = TABLE_A1
    psi, omega, wm, step = table2.lead_angle, p["screw_speed"], table2.orbital_speed, 1e-7
    frame = helix.frenet_frame(0.0, psi)
    for body, convected in (("nut", table2.convected_velocity_nut), ("screw", table2.convected_velocity_screw)):
        def position(time, body=body):
            return helix.contact_point(wm * time, p["pitch_radius"], p["lead"], p["ball_radius"],
                                       p["contact_angle_nut"], body, omega * time)

        derivative = (position(step) - position(-step)) / (2 * step)
        np.testing.assert_allclose(helix.to_frenet(frame, derivative), convected, atol=1e-7)
    point_b = helix.contact_point(0.0, p["pitch_radius"], p["lead"], p["ball_radius"], p["contact_angle_nut"],
                                  "screw")
    np.testing.assert_allclose(helix.to_frenet(frame, np.cross([0, 0, omega], point_b)), table2.screw_velocity,
                               atol=1e-14)


def test_centrifugal_force_about_two_percent_of_27_newton():
    """wang2022 Sec 3.3: at 3000 rpm F_n is about 2 % of the 27 N mean contact load."""
    result = sk.kinematics(**{**TABLE_A1, "screw_speed": 3000 * RPM})
    force = result.centrifugal_force(1.05e-3, TABLE_A1["pitch_radius"])
    assert force == pytest.approx(0.02 * 27.0, rel=0.25)  # "about 2 %": 1.5 to 2.5 %
    assert force == pytest.approx(1.05e-3 * TABLE_A1["pitch_radius"] * result.orbital_speed**2, rel=1e-15)


# --------------------------------------------------------------------------
# lead -> 0: ball bearing, Harris, wang2022 Table 1
# --------------------------------------------------------------------------
BEARING = dict(pitch_radius=0.085, ball_radius=0.005, contact_angle=np.radians(45.0))  # 61830: d_m 170, D 10 mm


def test_table1_present_and_harris():
    present = sk.kinematics(BEARING["pitch_radius"], BEARING["ball_radius"], 0.0, 3600 * RPM,
                            BEARING["contact_angle"])
    reference = harris.kinematics(BEARING["pitch_radius"], BEARING["ball_radius"], 3600 * RPM,
                                  BEARING["contact_angle"])
    for value in (present.entrainment_nut, present.entrainment_screw, reference.entrainment_outer,
                  reference.entrainment_inner):
        assert value == pytest.approx(15.994, abs=HALF_UNIT)
    assert reference.slide_roll_outer == 0.0 and reference.slide_roll_inner == 0.0
    assert abs(present.slide_roll_nut) < 1e-14 and abs(present.slide_roll_screw) < 1e-14  # round-off only


def test_table1_wei_defined_parts():
    """Wei: S_A = 2 exactly (nut at rest), U_A + U_B = omega r_m (1 - gamma) = 7.971 + 22.740 (ball term cancels)."""
    wei = sk.wei_ball_centre_kinematics(BEARING["pitch_radius"], BEARING["ball_radius"], 0.0, 3600 * RPM,
                                        BEARING["contact_angle"])
    assert wei.slide_roll_nut == 2.0
    assert wei.entrainment_nut + wei.entrainment_screw == pytest.approx(7.971 + 22.740, abs=2 * HALF_UNIT)


@pytest.mark.parametrize("geometry", [
    dict(pitch_radius=20.7e-3, ball_radius=3.175e-3, contact_angle_nut=np.radians(45)),
    dict(pitch_radius=0.085, ball_radius=0.005, contact_angle_nut=np.radians(30)),
    dict(pitch_radius=0.012, ball_radius=0.004, contact_angle_nut=np.radians(60)),
])
def test_lead_to_zero_limit_is_harris(geometry):
    omega = np.array([-300.0, 10.0, 500.0])
    result = sk.kinematics(lead=0.0, screw_speed=omega, **geometry)
    reference = harris.kinematics(geometry["pitch_radius"], geometry["ball_radius"], omega,
                                  geometry["contact_angle_nut"])
    np.testing.assert_allclose(result.slide_roll_nut, 0.0, atol=1e-14)
    np.testing.assert_allclose(result.slide_roll_screw, 0.0, atol=1e-14)
    np.testing.assert_allclose(result.entrainment_nut, reference.entrainment_outer, rtol=1e-14)
    np.testing.assert_allclose(result.entrainment_screw, reference.entrainment_inner, rtol=1e-14)
    np.testing.assert_allclose(result.orbital_speed, reference.cage_speed, rtol=1e-14)
    # continuous limit: a tiny lead gives a tiny slide-roll ratio
    small = sk.kinematics(lead=1e-9, screw_speed=omega, **geometry)
    assert np.all(small.slide_roll_screw < 1e-5) and np.all(small.slide_roll_nut < 1e-5)


def test_harris_outer_ring_rotating_symmetry():
    """Harris with the outer ring turning and the inner at rest: same entrainment, cage speed by (1 + gamma)."""
    r_m, r_b, alpha, w = 0.05, 0.006, np.radians(20), 100.0
    inner = harris.kinematics(r_m, r_b, w, alpha)
    outer = harris.kinematics(r_m, r_b, 0.0, alpha, outer_speed=w)
    gamma = r_b * np.cos(alpha) / r_m
    assert outer.entrainment_inner == pytest.approx(inner.entrainment_inner, rel=1e-14)
    assert outer.cage_speed == pytest.approx(w * (1 + gamma) / 2, rel=1e-14)
    assert inner.ball_spin_speed == pytest.approx(r_m / (2 * r_b) * (1 - gamma**2) * w, rel=1e-14)


# --------------------------------------------------------------------------
# Sec 3.4 trends (Figs 5-9)
# --------------------------------------------------------------------------
def _elasticity(parameter, name, relative_step=1e-4):
    """d ln(quantity) / d ln(parameter) at Table A1, central difference."""
    def at(factor):
        return getattr(sk.kinematics(**{**TABLE_A1, parameter: TABLE_A1[parameter] * factor}), name)

    up, down = at(1 + relative_step), at(1 - relative_step)
    return float((np.log(up) - np.log(down)) / (np.log(1 + relative_step) - np.log(1 - relative_step)))


def test_speed_entrainment_linear_slide_roll_constant():
    speeds = np.linspace(100, 5000, 12) * RPM
    result = sk.kinematics(**{**TABLE_A1, "screw_speed": speeds})
    for name in ("entrainment_nut", "entrainment_screw"):
        np.testing.assert_allclose(getattr(result, name) / speeds, getattr(result, name)[0] / speeds[0], rtol=1e-13)
    for name in ("slide_roll_nut", "slide_roll_screw"):
        np.testing.assert_allclose(getattr(result, name), getattr(result, name)[0], rtol=1e-13)
    # Fig 5: nut side slightly below screw side
    assert np.all(result.slide_roll_nut < result.slide_roll_screw)
    assert np.all(result.entrainment_nut < result.entrainment_screw)


def test_lead_raises_slide_roll_and_barely_moves_entrainment():
    leads = np.linspace(2e-3, 40e-3, 20)
    result = sk.kinematics(**{**TABLE_A1, "lead": leads})
    assert np.all(np.diff(result.slide_roll_nut) > 0) and np.all(np.diff(result.slide_roll_screw) > 0)
    assert result.slide_roll_screw[-1] > 10 * result.slide_roll_screw[0]
    assert np.all(np.diff(result.entrainment_screw) > 0)  # Fig 7: screw side rises slightly
    assert np.all(np.diff(result.entrainment_nut) < 0)  # nut side falls slightly
    for name in ("entrainment_nut", "entrainment_screw"):
        assert abs(_elasticity("lead", name)) < 0.02


def test_nominal_diameter_lowers_slide_roll_and_raises_entrainment():
    radii = np.linspace(12e-3, 50e-3, 20)
    result = sk.kinematics(**{**TABLE_A1, "pitch_radius": radii})
    assert np.all(np.diff(result.slide_roll_nut) < 0) and np.all(np.diff(result.slide_roll_screw) < 0)
    assert np.all(np.diff(result.entrainment_nut) > 0) and np.all(np.diff(result.entrainment_screw) > 0)
    for name in ("entrainment_nut", "entrainment_screw"):
        assert _elasticity("pitch_radius", name) > 0.9  # nearly proportional (conclusion 5)
    for name in ("slide_roll_nut", "slide_roll_screw"):
        assert _elasticity("pitch_radius", name) < -0.9


def test_contact_angle_and_ball_diameter_effects_are_weak():
    """Figs 6, 9: both weak next to lead and nominal diameter (elasticities at Table A1)."""
    strong = min(abs(_elasticity("lead", "slide_roll_nut")), abs(_elasticity("pitch_radius", "slide_roll_screw")))
    for parameter in ("contact_angle_nut", "ball_radius"):
        for name in ("slide_roll_nut", "slide_roll_screw"):
            assert abs(_elasticity(parameter, name)) < 0.5 * strong
        for name in ("entrainment_nut", "entrainment_screw"):
            assert abs(_elasticity(parameter, name)) < 0.1
    angles = np.radians(np.linspace(30, 60, 13))
    result = sk.kinematics(**{**TABLE_A1, "contact_angle_nut": angles})
    # Fig 6: S_B falls a little, S_A rises even less, U rises slightly on both sides
    assert np.all(np.diff(result.slide_roll_screw) < 0) and np.all(np.diff(result.slide_roll_nut) > 0)
    assert np.ptp(result.slide_roll_nut) < np.ptp(result.slide_roll_screw)
    assert np.all(np.diff(result.entrainment_nut) > 0) and np.all(np.diff(result.entrainment_screw) > 0)
    balls = np.linspace(1.5e-3, 5e-3, 12)
    result = sk.kinematics(**{**TABLE_A1, "ball_radius": balls})
    # Fig 9: U falls slightly, S rises slightly on both sides
    assert np.all(np.diff(result.entrainment_nut) < 0) and np.all(np.diff(result.entrainment_screw) < 0)
    assert np.all(np.diff(result.slide_roll_nut) > 0) and np.all(np.diff(result.slide_roll_screw) > 0)


def test_relative_velocities_tangent_to_contact():
    """No normal approach: every relative surface velocity and the sliding velocity is normal to R_O'(A,B)."""
    rng = np.random.default_rng(0)
    count = 50
    r_b, alpha_o, alpha_i = rng.uniform(1e-3, 4e-3, count), rng.uniform(0.4, 1.2, count), rng.uniform(0.4, 1.2, count)
    result = sk.kinematics(rng.uniform(0.01, 0.05, count), r_b, rng.uniform(0, 0.06, count),
                           rng.uniform(-400, 400, count), alpha_o, alpha_i)
    normal_a, normal_b = helix.contact_offset(r_b, alpha_o, "nut"), helix.contact_offset(r_b, alpha_i, "screw")
    for vector, normal in ((result.nut_velocity_rel, normal_a), (result.ball_velocity_nut_rel, normal_a),
                           (result.sliding_velocity_nut, normal_a), (result.screw_velocity_rel, normal_b),
                           (result.ball_velocity_screw_rel, normal_b), (result.sliding_velocity_screw, normal_b)):
        speed = np.linalg.norm(vector, axis=-1)
        np.testing.assert_allclose(np.einsum("...i,...i", vector, normal) / (r_b * speed), 0.0, atol=1e-13)


def test_single_equation_helpers_match_kinematics(table2):
    p = TABLE_A1
    beta = sk.pitch_angle(p["contact_angle_nut"], p["ball_radius"], p["pitch_radius"])
    omega_m = sk.orbital_speed(p["screw_speed"], p["ball_radius"], p["pitch_radius"], p["contact_angle_nut"],
                               p["contact_angle_nut"], beta)
    spin = sk.ball_spin_speed(omega_m, p["ball_radius"], p["pitch_radius"], p["contact_angle_nut"],
                              table2.lead_angle, beta)
    assert beta == pytest.approx(float(table2.pitch_angle), rel=1e-14)
    assert omega_m == pytest.approx(float(table2.orbital_speed), rel=1e-14)
    assert spin == pytest.approx(float(table2.spin_speed), rel=1e-14)
    np.testing.assert_allclose(sk.ball_angular_velocity(spin, beta), table2.ball_angular_velocity, rtol=1e-14)
    u, sliding, s = sk.absolute_velocity_measures(table2.nut_velocity_rel, table2.ball_velocity_nut_rel,
                                                  raceway_is_driver=False)
    assert u == pytest.approx(float(table2.entrainment_nut), rel=1e-14)
    assert s == pytest.approx(float(table2.slide_roll_nut), rel=1e-13)
    np.testing.assert_allclose(sliding, table2.sliding_velocity_nut, atol=1e-16)


def test_vectorised_equals_scalar_calls():
    rng = np.random.default_rng(3)
    params = dict(pitch_radius=rng.uniform(0.01, 0.05, 7), ball_radius=rng.uniform(0.001, 0.004, 7),
                  lead=rng.uniform(0, 0.04, 7), screw_speed=rng.uniform(-400, 400, 7),
                  contact_angle_nut=rng.uniform(0.5, 1.0, 7), contact_angle_screw=rng.uniform(0.5, 1.0, 7))
    batch = sk.kinematics(**params)
    for index in range(7):
        single = sk.kinematics(**{key: value[index] for key, value in params.items()})
        for name in ("entrainment_nut", "slide_roll_screw", "ball_velocity_screw", "orbital_speed"):
            np.testing.assert_allclose(getattr(batch, name)[index], getattr(single, name), rtol=1e-14)


@pytest.mark.parametrize("override, name", [
    ({"pitch_radius": -0.02}, "pitch_radius"),
    ({"pitch_radius": np.nan}, "pitch_radius"),
    ({"ball_radius": 0.0}, "ball_radius"),
    ({"ball_radius": 0.03}, "ball_radius"),
    ({"lead": -0.01}, "lead"),
    ({"screw_speed": np.inf}, "screw_speed"),
    ({"contact_angle_nut": 0.0}, "contact_angle_nut"),
    ({"contact_angle_nut": np.radians(90)}, "contact_angle_nut"),
    ({"contact_angle_screw": -0.2}, "contact_angle_screw"),
    ({"lead_angle": np.radians(-1)}, "lead_angle"),
    ({"yaw_angle": np.nan}, "yaw_angle"),
])
def test_bad_input_names_parameter(override, name):
    with pytest.raises(ValueError, match=name):
        sk.kinematics(**{**TABLE_A1, **override})


@pytest.mark.parametrize("call, name", [
    (lambda: harris.kinematics(0.05, 0.06, 10.0, 0.3), "ball_radius"),
    (lambda: harris.kinematics(0.05, 0.006, 10.0, 1.7), "contact_angle"),
    (lambda: harris.kinematics(0.05, 0.006, np.nan, 0.3), "inner_speed"),
    (lambda: sk.centrifugal_force(-1e-3, 0.02, 90.0), "ball_mass"),
])
def test_bad_input_other_functions(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_kinematics_at_huge_speed():
    """1e300 rad/s gave NaN (overflowing squares); every velocity is linear in the speed, S is not."""
    args = (16.5e-3, 2.778e-3, 20e-3)
    huge = screw.kinematics(*args, 1e300, math.radians(45))
    unit = screw.kinematics(*args, 1.0, math.radians(45))
    for name in huge.__dataclass_fields__:
        assert np.all(np.isfinite(getattr(huge, name))), name
    assert float(huge.slide_roll_nut) == pytest.approx(float(unit.slide_roll_nut), rel=1e-12)
    assert float(huge.entrainment_screw) == pytest.approx(1e300 * float(unit.entrainment_screw), rel=1e-12)
    with pytest.raises(ValueError, match="screw_speed"):
        screw.kinematics(*args, 1.7e308, math.radians(45))


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


TINY = 5e-324  # the smallest float


@pytest.mark.filterwarnings("error")
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


@pytest.mark.filterwarnings("error")
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


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(pitch=positive(1e-4, 10.0), ball=positive(1e-5, 1.0), lead=real(-0.01, 1.0), speed=real(-1e300, 1e300),
       alpha=angle, alpha_i=angle)
def test_screw_kinematics(pitch, ball, lead, speed, alpha, alpha_i):
    call(screw.kinematics, pitch, ball, lead, speed, alpha, alpha_i)
    call(screw.wei_ball_centre_kinematics, pitch, ball, lead, speed, alpha, alpha_i)
    call(harris.kinematics, pitch, ball, speed, alpha)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


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
