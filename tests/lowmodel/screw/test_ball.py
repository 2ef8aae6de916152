"""Single ball in a four-point-contact ball screw (lin2019 Sec 3.1, eqs 34-55, A9-A11)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ellipse_friction_offset as eo
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import ball as bb, contacts as bearing_contacts
from ballbench.lowmodel.screw import ball as sb, contacts as screw_contacts, b2b as b2b, b2b_traction as traction
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, angle as any_angle, angle_limits, call, mostly, positive, real

DEG = math.pi / 180.0


@pytest.fixture(scope="module")
def preloaded():
    module = screw_contacts.screw_module(oversize=1e-6)
    contacts = screw_contacts.ball_contacts(module, 2.0 * DEG)
    return module, contacts, sb.solve(contacts, 25.0)


def test_profile_eq48_literal_equals_arc():
    """eq 48 from the core's exact helical surface (projected into CS3) is the closed-form arc used by the solver."""
    module = screw_contacts.screw_module()
    contacts = screw_contacts.ball_contacts(module, np.array([0.0, 3.0 * DEG]))
    gamma = np.linspace(20 * DEG, 70 * DEG, 7)
    for shift in (0.0, 3e-6):
        arcs, tangents = screw_contacts.arc_profile(contacts, gamma, shift)
        for ball in range(2):
            for contact in range(4):
                for azimuth in (0.0, 1.3):
                    literal = screw_contacts.profile_2d(contacts, ball, contact, gamma, azimuth=azimuth,
                                                        nut_shift=shift)
                    np.testing.assert_allclose(literal, arcs[ball, contact], atol=1e-15)
                step = 1e-7
                fd = (screw_contacts.profile_2d(contacts, ball, contact, gamma + step, nut_shift=shift)
                      - screw_contacts.profile_2d(contacts, ball, contact, gamma - step, nut_shift=shift)) / (2 * step)
                np.testing.assert_allclose(tangents[ball, contact], fd, atol=1e-10)


def _paper_z_axes(beta):
    """z_i of lin2019 eq 54's f_z columns (x3, z3 components); NL corrected (see docs/ball_screw.md)."""
    sl, sr, nr, nl = beta
    return np.array([[-math.sin(sl), math.cos(sl)], [math.sin(sr), math.cos(sr)], [math.sin(nr), -math.cos(nr)],
                     [-math.sin(nl), -math.cos(nl)]])


def _eq54(beta, force, f_y, f_z, moment, radius, nl_literal=False):
    """lin2019 eq 54, matrix form as printed (rows F_x, F_y, F_z, M_x, M_y, M_z)."""
    sl, sr, nr, nl = beta
    s, c = np.sin(beta), np.cos(beta)
    normal = np.array([[c[0], c[1], -c[2], -c[3]], [0] * 4, [s[0], -s[1], -s[2], s[3]], [0] * 4, [0] * 4, [0] * 4])
    along = np.array([[0] * 4, [1] * 4, [0] * 4, [radius * s[0], -radius * s[1], -radius * s[2], radius * s[3]],
                      [0] * 4, [-radius * c[0], -radius * c[1], radius * c[2], radius * c[3]]])
    across = np.array([[-s[0], s[1], s[2], (s[3] if nl_literal else -s[3])], [0] * 4,
                       [c[0], c[1], -c[2], -c[3]], [0] * 4, [radius] * 4, [0] * 4])
    spin = np.array([[0] * 4, [0] * 4, [0] * 4, [c[0], c[1], -c[2], -c[3]], [0] * 4, [s[0], -s[1], -s[2], s[3]]])
    return normal @ force + along @ f_y + across @ f_z + spin @ moment


def test_eq55_conditions_and_eq54_matrix_hold_at_the_solution(preloaded):
    module, contacts, state = preloaded
    beta = state.contact_angle[0]
    radius = module.ball_radius
    centre = state.centre[0]
    # eqs 49-52: contact point on the literal eq 48 profile at gamma = beta, normal through the ball centre
    _, tangents = screw_contacts.arc_profile(contacts, beta, state.nut_shift)   # eq 52 (tested above); (1, 4, 4, 2)
    for i in range(4):
        point = screw_contacts.profile_2d(contacts, 0, i, beta[i], nut_shift=state.nut_shift)              # eq 49
        tangent = tangents[0, i, i]
        normal = (centre - point) / np.linalg.norm(centre - point)
        assert abs(normal @ tangent) / np.linalg.norm(tangent) < 1e-9                      # eq 50
        delta = radius + module.oversize - np.linalg.norm(centre - point)                   # eq 53
        if state.normal_force[0, i] > 0:
            assert delta == pytest.approx(contacts.hertz_constant[0, i] * state.normal_force[0, i] ** (2 / 3),
                                          rel=1e-9)
        else:
            assert delta <= 0.0
    # eq 54 in the paper's matrix form, forces from the state
    force = state.normal_force[0]
    f_y = state.friction_force[0, :, 1]
    axes = _paper_z_axes(beta)
    f_z = np.einsum("ij,ij->i", state.friction_force[0][:, [0, 2]], axes)
    np.testing.assert_allclose(state.friction_force[0][:, [0, 2]], f_z[:, None] * axes, atol=1e-14)
    inward = -np.stack([np.cos(beta) * [-1, -1, 1, 1], np.sin(beta) * [-1, 1, 1, -1]], axis=-1)
    moment = np.einsum("ij,ij->i", state.friction_moment[0][:, [0, 2]], inward)   # M_O about the inward normal
    scale = module.friction_coefficient * force.max()
    residual = _eq54(beta, force, f_y, f_z, moment, radius)
    assert np.max(np.abs(residual[:3])) < 1e-8 * scale
    assert np.max(np.abs(residual[3:])) < 1e-8 * scale * radius
    # the printed NL entry (+sin beta_NL in F_x) is inconsistent with its own moment row: it misses here
    literal = _eq54(beta, force, f_y, f_z, moment, radius, nl_literal=True)
    assert abs(literal[0]) > 1e3 * 1e-8 * scale


@pytest.mark.parametrize("oversize, theta, load", [(1e-6, 0.0, 25.0), (1e-6, 3.0 * DEG, -25.0), (0.0, 2.0 * DEG, 25.0),
                                                  (3e-6, -2.0 * DEG, 5.0)])
def test_power_balance(oversize, theta, load):
    module = screw_contacts.screw_module(oversize=oversize)
    state = sb.solve(screw_contacts.ball_contacts(module, theta), load)
    assert state.groove_loss > 0.0
    assert abs(state.input_power - state.groove_loss) < 1e-8 * state.groove_loss
    # every contact dissipates (friction opposes the slip)
    assert np.all(state.friction_loss >= 0.0)
    assert state.axial_load == load


def test_jacobian_against_finite_differences(preloaded):
    module, contacts, state = preloaded
    scales = sb.Scales(1e-6, abs(module.nut_speed), 10.0, 2.0)
    rng = np.random.default_rng(5)
    z = np.concatenate([state.centre[0] / 1e-6, [state.orbit_speed[0] / scales.orbit], state.omega[0] / 10.0])
    z = z + 0.05 * rng.normal(size=6)
    shift = state.nut_shift / 1e-6
    terms = sb.ball_terms(z[None], shift, contacts, scales)
    step = 1e-6
    for k in range(7):
        up, down = z.copy(), z.copy()
        shift_up, shift_down = shift, shift
        if k < 6:
            up[k] += step
            down[k] -= step
        else:
            shift_up, shift_down = shift + step, shift - step
        plus = sb.ball_terms(up[None], shift_up, contacts, scales)
        minus = sb.ball_terms(down[None], shift_down, contacts, scales)
        fd = (plus.residual[0] - minus.residual[0]) / (2 * step)
        np.testing.assert_allclose(terms.jacobian[0, :, k], fd, atol=1e-6 * np.abs(terms.jacobian).max())
        fd_axial = (plus.axial[0] - minus.axial[0]) / (2 * step)
        assert terms.axial_gradient[0, k] == pytest.approx(fd_axial, abs=1e-6 * np.abs(terms.jacobian).max())


def test_slip_field_equals_eq44_and_A9_A11():
    """Centre slip and spin of every contact against the paper's printed velocity fields."""
    module = screw_contacts.screw_module(oversize=1e-6)
    contacts = screw_contacts.ball_contacts(module, 2.0 * DEG)
    scales = sb.Scales(1e-6, 1.0, 1.0, 1.0)
    rng = np.random.default_rng(9)
    unknowns = np.concatenate([rng.normal(size=2) * 0.3, rng.normal(size=4) * [3.0, 20.0, 5.0, 20.0]])
    terms = sb.ball_terms(unknowns[None], 0.2, contacts, scales)
    w_b, w_x, w_y, w_z = unknowns[2:]
    w_n = module.nut_speed
    radius, r_p, lead = module.ball_radius, module.pitch_radius, module.lead
    big_l = math.hypot(2 * math.pi * r_p, lead)                             # eq 45
    e = terms.contact_direction[0]
    beta = np.arctan2(np.array([-1, 1, 1, -1]) * e[:, 1], np.array([-1, -1, 1, 1]) * e[:, 0])
    cos, sin = np.cos(beta), np.sin(beta)
    k = 2 * math.pi * r_p / big_l
    # (centre slip along y, coefficient of z_i in dv_y, centre slip along z_i, coefficient of y_i in dv_z)
    paper = {
        0: ((big_l**2 - 4 * math.pi**2 * radius * r_p * cos[0]) / (2 * math.pi * big_l) * w_b
            - (cos[0] * w_z - sin[0] * w_x) * radius,
            -((k * w_b + w_z) * sin[0] + w_x * cos[0]),
            radius * w_y + radius * lead / big_l * w_b,
            (k * w_b * sin[0] + w_x * cos[0] + w_z * sin[0])),                                      # eq 44
        1: ((big_l**2 - 4 * math.pi**2 * radius * r_p * cos[1]) / (2 * math.pi * big_l) * w_b
            - (cos[1] * w_z + sin[1] * w_x) * radius,
            ((k * w_b + w_z) * sin[1] - cos[1] * w_x),
            radius * w_y + radius * lead / big_l * w_b,
            -(k * w_b * sin[1] - cos[1] * w_x + sin[1] * w_z)),                                     # A9
        2: ((big_l**2 + 4 * math.pi**2 * radius * r_p * cos[2]) / (2 * math.pi * big_l) * (w_b - w_n)
            + (cos[2] * w_z - sin[2] * w_x) * radius,
            ((k * (w_b - w_n) + w_z) * sin[2] + w_x * cos[2]),
            radius * w_y + radius * lead / big_l * (w_b - w_n),
            -(k * (w_b - w_n) * sin[2] + w_x * cos[2] + w_z * sin[2])),                             # A10
        3: ((big_l**2 + 4 * math.pi**2 * radius * r_p * cos[3]) / (2 * math.pi * big_l) * (w_b - w_n)
            + (cos[3] * w_z + sin[3] * w_x) * radius,
            -((k * (w_b - w_n) + w_z) * sin[3] - w_x * cos[3]),
            radius * w_y + radius * lead / big_l * (w_b - w_n),
            (k * (w_b - w_n) * sin[3] - w_x * cos[3] + w_z * sin[3])),                              # A11
    }
    for i in range(4):
        centre_y, coeff_z, centre_z, coeff_y = paper[i]
        scale = abs(w_n) * r_p
        assert terms.slip_minor[0, i] == pytest.approx(centre_y, abs=1e-12 * scale)
        assert terms.slip_major[0, i] == pytest.approx(centre_z, abs=1e-12 * scale)
        # dv_minor = slip_minor - spin X,  dv_major = slip_major + spin Y  (X along z_i, Y along y_i)
        assert -terms.spin[0, i] == pytest.approx(coeff_z, abs=1e-12 * abs(w_n))
        assert terms.spin[0, i] == pytest.approx(coeff_y, abs=1e-12 * abs(w_n))


def test_linear_bearing_limit(monkeypatch):
    """lead = 0 and R_P -> infinity (a straight groove): the single-ball state equals lin2019 Sec 2.1's model.

    Both use the exact friction quadrature (the bearing model's tabulated map is accurate to 3e-7 only); the
    difference falls like R_B/R_P and is below 1e-8 (relative) at R_P = 1e10 R_B.
    """

    def exact(b_over_a):
        def evaluate(phi):  # unit slip speed along phi: (spin, slide) = (cos phi, sin phi)
            cos, sin = np.cos(phi), np.sin(phi)
            r = _slip(eo.friction_offset(cos, sin, 0.0, b_over_a))
            # (force, moment, loss) x (value, d/d phi), as bearing_ball's map; d loss/d phi is not used
            return np.stack([np.stack([r.force, r.dforce_dslide * cos - r.dforce_dspin * sin], axis=-1),
                             np.stack([r.moment, r.dmoment_dslide * cos - r.dmoment_dspin * sin], axis=-1),
                             np.stack([r.loss, np.full_like(r.loss, np.nan)], axis=-1)], axis=-2)
        return evaluate

    monkeypatch.setattr(bearing_contacts, "_friction_angle_function", exact)
    speed, radius = 0.01, 2.778e-3
    errors = []
    for ratio in (1e6, 1e10):
        module = screw_contacts.screw_module(pitch_radius=ratio * radius, lead=0.0, nut_speed=speed / (ratio * radius),
                                 oversize=2e-6)
        contacts = screw_contacts.ball_contacts(module, 2.0 * DEG)
        state = sb.solve(contacts, 20.0)
        bearing = bearing_contacts.contacts_from_forces(state.contact_angle, state.normal_force, state.semi_major,
                                          contacts.b_over_a, ball_radius=radius, friction_coefficient=0.1,
                                          groove_velocity=speed)
        linear = bb.solve(bearing)
        # frames: (x, y, z) of the bearing = (z3, x3, y3); BL, BR, TR, TL = SL, SR, NR, NL
        velocity = state.orbit_speed[0] * module.helix_radius
        omega = np.array([state.orbit_speed[0] + state.omega[0, 2], state.omega[0, 0]])
        error = max(abs(velocity - linear.ball_velocity[0]) / speed,
                    float(np.max(np.abs(omega - linear.omega[0]))) * radius / speed,
                    abs(state.omega[0, 1]) * radius / speed,
                    float(np.max(np.abs(state.friction_force[0, :, 1] - linear.friction_force[0])))
                    / (0.1 * state.normal_force.max()))
        errors.append(error)
    assert errors[1] < 1e-8
    assert errors[0] / errors[1] == pytest.approx(1e4, rel=0.05)   # O(R_B / R_P)


class _slip:
    """friction_offset in the SlipFriction form of the bearing model (force along the rolling direction)."""

    def __init__(self, r):
        self.force = r.force_minor
        self.moment = r.moment
        self.loss = r.loss
        self.dforce_dspin, self.dforce_dslide = r.jacobian[..., 1, 0], r.jacobian[..., 1, 1]
        self.dmoment_dspin, self.dmoment_dslide = r.jacobian[..., 2, 0], r.jacobian[..., 2, 1]


def test_zero_preload_reaches_a_third_contact():
    """Exact fit (no preload): the axial load loads one diagonal and friction pushes the ball onto a third flank."""
    module = screw_contacts.screw_module(oversize=0.0)
    state = sb.solve(screw_contacts.ball_contacts(module, 0.0), 25.0)
    loaded = state.normal_force[0] > 0
    assert loaded.sum() == 3
    assert abs(state.input_power - state.groove_loss) < 1e-8 * state.groove_loss


def test_deviation_slows_the_ball(preloaded):
    module, _, state_2 = preloaded
    state_0 = sb.solve(screw_contacts.ball_contacts(module, 0.0), 25.0)
    assert state_2.orbit_speed[0] < state_0.orbit_speed[0]


def test_bad_input():
    with pytest.raises(ValueError, match="oversize"):
        screw_contacts.screw_module(oversize=-1e-6)
    with pytest.raises(ValueError, match="nut_speed"):
        screw_contacts.screw_module(nut_speed=0.0)
    with pytest.raises(ValueError, match="conformity"):
        screw_contacts.screw_module(conformity=0.5)
    with pytest.raises(ValueError, match="reading"):
        screw_contacts.ball_contacts(screw_contacts.screw_module(), 0.01, reading="twisted")
    with pytest.raises(ValueError, match="deviation"):
        screw_contacts.ball_contacts(screw_contacts.screw_module(), math.radians(20))
    with pytest.raises(ValueError, match="axial_load"):
        sb.solve(screw_contacts.ball_contacts(screw_contacts.screw_module()), float("nan"))
    with pytest.raises(ConvergenceError):
        sb.solve(screw_contacts.ball_contacts(screw_contacts.screw_module(oversize=1e-6)), 25.0, max_iterations=1)


def test_hertz_table_matches_direct_solution():
    module = screw_contacts.screw_module()
    angles = module.nominal_angle + np.radians([-14.9, -3.0, -0.1234, 0.0, 2.0, 3.0, 7.77, 14.9])
    for body in ("screw", "nut"):
        contacts = screw_contacts.ball_contacts(module, angles - module.nominal_angle, reading="tilted")
        column = 0 if body == "screw" else 2
        for j, angle in enumerate(angles):
            if body == "nut":
                angle = module.nominal_angle
            direct = screw_contacts.hertz_direct(module.ball_radius, module.conformity, module.pitch_radius,
                                                 module.lead_angle, float(angle), body, module.youngs_modulus,
                                                 module.poisson_ratio)
            got = (contacts.hertz_constant[j, column], contacts.semi_major_unit[j, column],
                   contacts.b_over_a[j, column])
            np.testing.assert_allclose(got, direct, rtol=1e-9)


def test_friction_level_of_the_screw_model():
    """The screw model's quadrature level (FRICTION_LEVEL) against level 6 at the Table 4 axis ratios."""
    rng = np.random.default_rng(4)
    w, un, um = np.ones(2000), rng.normal(size=2000) * 2, rng.normal(size=2000) * 0.5
    for ratio in (sb.FRICTION_LEVEL["coarse_min_b_over_a"], 0.215, 0.249):
        coarse = eo.friction_offset(w, un, um, ratio, level=sb.FRICTION_LEVEL["coarse"])
        fine = eo.friction_offset(w, un, um, ratio, level=6)
        for name in ("force_major", "force_minor", "moment", "loss"):
            assert np.max(np.abs(getattr(coarse, name) - getattr(fine, name))) < 3e-8


def test_kinematics_agree_with_wang2022_frenet_velocities():
    """wang2022's ball motion (eqs 18-21, screw turning, nut translating) fed to this model's kinematics.

    In the screw's frame wang2022's nut turns at -omega and advances -omega h (a screw motion), the orbit
    rate relative to the screw is omega_m - omega and the spin relative to CS1 = CS3 is the same vector
    (CS3 (x3, y3, z3) = Frenet (-n, t, b)).  Slip velocities are frame-independent, so the slip at the
    nut contact A (this model's NR) and the screw contact B (SL) must equal wang2022's V_SA and -V_SB.
    """
    from ballbench.lowmodel.screw import kinematics

    omega = 2.0 * math.pi
    for lead, alpha in ((20e-3, 45 * DEG), (10e-3, 40 * DEG), (0.0, 45 * DEG)):
        wang = kinematics.kinematics(16.5e-3, 2.778e-3, lead, omega, alpha)
        module = screw_contacts.screw_module(lead=lead, nominal_angle=alpha, nut_speed=-omega, oversize=1e-6)
        contacts = screw_contacts.ball_contacts(module, 0.0)
        scales = sb.Scales(1e-6, 1.0, 1.0, 1.0)
        spin_t, spin_n, spin_b = np.asarray(wang.ball_angular_velocity)
        unknowns = np.array([[0.0, 0.0, float(wang.orbital_speed) - omega, -spin_n, spin_t, spin_b]])
        terms = sb.ball_terms(unknowns, 0.0, contacts, scales)

        def slip_vector(i):
            e = terms.contact_direction[0, i]
            major = np.array([e[1], 0.0, -e[0]])
            return terms.slip_minor[0, i] * np.array([0.0, 1.0, 0.0]) + terms.slip_major[0, i] * major

        def to_cs3(frenet):
            t, n, b = np.asarray(frenet)
            return np.array([-n, t, b])

        scale = omega * 16.5e-3
        np.testing.assert_allclose(slip_vector(2), to_cs3(wang.sliding_velocity_nut), atol=1e-12 * scale)
        np.testing.assert_allclose(slip_vector(0), -to_cs3(wang.sliding_velocity_screw), atol=1e-12 * scale)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


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
       reading=mostly(st.sampled_from(["tilted", "rotated"]), "sideways"), gamma=any_angle,
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
