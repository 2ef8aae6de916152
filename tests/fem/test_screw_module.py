"""FE ball-screw module (fem.screw_module): exact helical gap, frames, statics, FE-informed B2B."""
import math

import numpy as np
import pytest

from ballbench.fem import screw_module as sm
from ballbench.lowmodel.bearing_results import axial_shares
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import helix
from ballbench.validation.cases import lin2019
from ballbench.validation.references import screw_statics as statics
from ballbench.validation.studies import fe_b2b_screw as study

T4 = lin2019.SCREW

THETA = math.radians(2.0)
ANGLES = sm.flank_angles_tilted(T4.nominal_angle, THETA)
GEOMETRY = sm.screw_module_geometry(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead, ANGLES, 1.5e-6)


def test_tilted_reading_and_frames():
    # lin2019 Fig 17 as the low-order model reads it: both screw flanks at beta_0 + theta, the nut's at beta_0
    np.testing.assert_allclose(ANGLES, T4.nominal_angle + np.array([THETA, THETA, 0.0, 0.0]), rtol=0, atol=1e-15)
    centre = GEOMETRY.ball_centre
    np.testing.assert_allclose(centre, [T4.pitch_radius, 0.0, 0.0], atol=1e-18)
    cs3 = helix.cs3_frame(0.0, GEOMETRY.lead_angle)
    for i in range(4):
        e1, e2, e3 = GEOMETRY.frame(i)
        # normal profile: the contact normal passes through the ball centre and lies in x3-z3
        point = GEOMETRY.contact_point(i)
        np.testing.assert_allclose(point + T4.ball_radius * e3, centre, atol=1e-12)
        assert abs(e3 @ cs3[:, 1]) < 1e-12
        # eq 37: the contact angle of the undeformed contact point, from -x3 (screw) / +x3 (nut)
        assert GEOMETRY.loaded_angle(i, point - centre) == pytest.approx(ANGLES[i], abs=1e-12)
    # screw contacts towards the axis (-x3), SL on -z3; nut contacts outward, NR on +z3 (lin2019 eq 37)
    local = GEOMETRY.to_ball_frame(np.array([GEOMETRY.contact_point(i) - centre for i in range(4)]))
    assert local[0, 0] < 0 and local[0, 2] < 0 and local[2, 0] > 0 and local[2, 2] > 0


def test_exact_gap_is_hertz_to_leading_order_and_carries_the_oversize():
    for i, body in enumerate(("screw", "screw", "nut", "nut")):
        curvature = hertz.ball_in_screw_groove(T4.ball_radius, T4.conformity, T4.pitch_radius, ANGLES[i],
                                               GEOMETRY.lead_angle, body)
        local = np.array([[0.0, 0.0], [2e-5, 0.0], [0.0, 2e-5], [-1.5e-5, 1e-5]])
        gap, surface = GEOMETRY.gap(i, local)
        assert gap[0] == pytest.approx(-1.5e-6, abs=1e-15)  # the oversize: an interference fit
        np.testing.assert_allclose(gap[1:] + 1.5e-6, curvature.A * local[1:, 0] ** 2 + curvature.B * local[1:, 1] ** 2,
                                   rtol=3e-3)
        np.testing.assert_allclose(np.linalg.norm(surface, axis=1), T4.ball_radius, rtol=1e-12)


def test_exact_gap_follows_a_tangential_shift():
    # a ball shifted by t along e1 touches the flank where the slopes agree: x = t R_B / (r_g - R_B)
    x = np.linspace(-2e-4, 2e-4, 4001)
    local = np.column_stack([x, np.zeros_like(x)])
    shift = 1e-6
    gap, _ = GEOMETRY.gap(1, local, shift)
    expected = shift * T4.ball_radius / (GEOMETRY.groove_radius - T4.ball_radius)
    assert abs(x[np.argmin(gap)] - expected) < 3e-7


def test_flank_normals_are_the_contact_normal_at_the_contact():
    for i in range(4):
        point = GEOMETRY.contact_point(i) - GEOMETRY.ball_centre
        np.testing.assert_allclose(GEOMETRY.flank_normals(i, point[None, :])[0], GEOMETRY.normals[i], atol=1e-9)


def test_bad_input():
    with pytest.raises(ValueError, match="contact_angles"):
        sm.screw_module_geometry(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead, ANGLES[:3])
    with pytest.raises(ValueError, match="oversize"):
        sm.screw_module_geometry(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead, ANGLES, -1e-6)
    with pytest.raises(ValueError, match="gap_limit"):
        sm.build_screw_model("missing.msh", GEOMETRY, gap_limit=0.0)
    with pytest.raises(ValueError, match="silhouette"):
        GEOMETRY.gap(0, np.array([[T4.ball_radius, 0.0]]))


def test_hertz_statics_reference():
    contacts, _, state = study.low_order(lin2019.TABLE5_A)
    shares = axial_shares(contacts, state)
    assert shares.sum() == pytest.approx(50.0, rel=1e-8)  # the touching state's 50 N on the screw
    forces = statics.hertz_statics(contacts, 0, 25.0)
    # theta = 0 without friction: the half-turn about y3 maps SL <-> NR and SR <-> NL
    assert forces[0] == pytest.approx(forces[2], rel=1e-3) and forces[1] == pytest.approx(forces[3], rel=1e-3)
    # the axial load: screw contacts along z_hat (at the nominal angles; the ball's micrometre shift turns the
    # normals by ~0.1 deg, 0.4 % of the axial component)
    angle = T4.nominal_angle
    axial = (forces[0] - forces[1]) * math.sin(angle) * math.cos(GEOMETRY.lead_angle)
    assert axial == pytest.approx(25.0, rel=1e-2)
    assert statics.hertz_statics(contacts, 0, 30.0)[0] > forces[0]  # more load, more on the loaded diagonal


def test_hertz_statics_of_both_cases_converge():
    """Both balls of Table 4 cases (a) and (b) at their axial shares: balanced to the solver tolerance (MINPACK's
    "not making good progress" at a 4e-12 N residual, case b ball 1, was once taken for a failure)."""
    for case in ("a", "b"):
        contacts, _, state = study.low_order(lin2019.TABLE5[case])
        shares = axial_shares(contacts, state)
        for ball in range(2):
            forces = statics.hertz_statics(contacts, ball, shares[ball])
            assert np.all(forces > 0.0)
            residual = statics.statics_residual(contacts, ball, forces, shares[ball])
            assert np.abs(residual).max() < 1e-2 * shares[ball]  # rigid-flank statics: the same balance, roughly


def test_statics_checks_of_the_scene_reject_wrong_forces():
    # the scene's physics checks on a module's forces (ball 1, theta = 0: four flanks at one angle):
    # forces built from the frictionless statics by hand pass; the mutants of docs/mutations.md do not
    contacts, _, _ = study.low_order(lin2019.TABLE5_A)
    beta = contacts.contact_angles[0, 0]
    assert np.allclose(contacts.contact_angles[0], beta)
    share, preload = 24.7, 17.0
    light = preload
    heavy = light + share / (math.sin(beta) * math.cos(contacts.module.lead_angle))  # screw's push along z_hat
    forces = np.array([heavy, light, heavy, light])  # (SL, SR, NR, NL)
    np.testing.assert_allclose(statics.statics_residual(contacts, 0, forces, share), 0.0, atol=1e-12 * share)
    assert statics.half_turn_asymmetry(forces) == 0.0
    wrong = {"load with the wrong sign": (forces[[1, 0, 3, 2]], share),
             "another ball's share": (forces, 1.03 * share),
             "nut contacts NR, NL swapped": (forces[[0, 1, 3, 2]], share),
             "screw and nut contacts swapped": (forces[[3, 2, 1, 0]], share)}
    for name, (f, s) in wrong.items():
        assert np.abs(statics.statics_residual(contacts, 0, f, s)).max() > 1e-2 * share, name
    assert statics.half_turn_asymmetry(forces[[0, 1, 3, 2]]) > 0.5
    # ball 2 (theta 2 deg, screw flanks tilted): the same forces do not balance at its angles
    assert np.abs(statics.statics_residual(contacts, 1, forces, share)).max() > 1e-2 * share


@pytest.fixture(scope="module")
def quick_modules():
    contacts, _, state = study.low_order(lin2019.TABLE5_A)
    shares = axial_shares(contacts, state)
    case = lin2019.TABLE5_A
    models, results, _ = study.solve_fe_level(case, case.fe.levels["quick"][0], shares)
    return case, contacts, state, shares, models, results


@pytest.mark.slow
def test_module_statics_and_fe_informed_b2b(quick_modules):
    case, contacts, state, shares, models, results = quick_modules
    for ball, (model, result) in enumerate(zip(models, results)):
        forces = np.array([c.normal_force for c in result.contacts])
        on_ball = -(forces[:, None] * model.geometry.normals)
        np.testing.assert_allclose(on_ball.sum(axis=0), 0.0, atol=1e-9 * forces.max())  # ball equilibrium
        assert on_ball[:2, 2].sum() == pytest.approx(shares[ball], rel=1e-9)  # the screw's axial push
        # indeterminate, preloaded: near the frictionless Hertz statics (the scene reports the difference)
        np.testing.assert_allclose(forces, statics.hertz_statics(contacts, ball, shares[ball]), rtol=0.08)
        assert result.pin_force < 1e-9
        shift = np.degrees([c.contact_angle for c in result.contacts]) - np.degrees(model.geometry.contact_angles)
        assert np.all(np.abs(shift) < 0.5)
    informed = study.fe_informed(case, models, results)
    assert informed.power_balance < 1e-6
    assert 1.6 < informed.b2b_force[0] < 2.3  # Table 5 (a): 1.80 N ANSYS, 1.92 N low-order


@pytest.mark.slow
def test_show_screw_module_writes_pngs(tmp_path):
    from ballbench.validation import show

    paths = show.show("fe-b2b-screw-a", tmp_path, fidelity="quick", solve=True)
    assert [p.name for p in paths] == ["pressure.png", "stress.png", "3d_assembly.png", "3d_pressure_overview.png",
                                       "3d_pressure_contacts.png", "3d_stress.png", "3d_helix.png"]
    for path in paths:
        assert path.exists() and path.stat().st_size > 10_000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
