"""Mutation check (docs/mutations.md): physically meaningful wrong models must fail the validation scenes.

Each mutant replaces one model function (monkeypatch) by a wrong variant; the
scenes listed for it are run in-process at ``quick`` fidelity and at least one
must fail.  The unmutated scenes must pass (else a failure proves nothing).
The list, and the scene that catches each mutant, is docs/mutations.md.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ballbench.lowmodel import kernels
from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.lowmodel.contact import ehl, ellipse_friction, hertz, mixed
from ballbench.lowmodel.linear_bearing import b2b, b2b_analytical
from ballbench.lowmodel.screw import kinematics
from ballbench.validation.runner import run_scene
from ballbench.validation.scene import registry
from tests import paths


def _scaled_result(function, factor, *fields):
    """``function`` whose dataclass result has ``fields`` multiplied by ``factor``."""
    def mutant(*args, **kwargs):
        result = function(*args, **kwargs)
        return dataclasses.replace(result, **{name: getattr(result, name) * factor for name in fields})
    return mutant


def _scaled_value(function, factor):
    def mutant(*args, **kwargs):
        return function(*args, **kwargs) * factor
    return mutant


def _psi(monkeypatch):  # lin2019 eq 15 constant 0.1 % off
    monkeypatch.setattr(hertz, "psi_constant", _scaled_value(hertz.psi_constant, 1.001))


def _k_f_analytical(monkeypatch):  # eq 14 slope 1 % off in the analytical model
    original = b2b_analytical.two_ball_case

    def mutant(*args, k_f=b2b_analytical.K_F_PAPER, **kwargs):
        return original(*args, k_f=1.01 * k_f, **kwargs)
    monkeypatch.setattr(b2b_analytical, "two_ball_case", mutant)


def _k_f_exact(monkeypatch):  # eq 14 slope of the friction integrals 1 % off
    monkeypatch.setattr(ellipse_friction, "k_f_exact", _scaled_value(ellipse_friction.k_f_exact, 1.01))


def _numpy_path(monkeypatch):
    """The B2B mutants patch the numpy code of eqs 5-10 (b2b.b2b_terms); the compiled kernels mirror it and would
    run unmutated (lowmodel.kernels: BALLBENCH_KERNELS=numpy turns them off)."""
    monkeypatch.setenv(kernels.ENVIRONMENT_VARIABLE, "numpy")


def _no_b2b_friction(monkeypatch):  # eqs 6, 8 without the B2B friction (normal force kept)
    _numpy_path(monkeypatch)
    original = b2b.b2b_terms
    monkeypatch.setattr(b2b, "b2b_terms", lambda scaled, forces, mu: original(scaled, forces, 0.0 * mu))


def _b2b_moment_sign(monkeypatch):  # B2B friction moment on the ball in front with the wrong sign
    _numpy_path(monkeypatch)
    original = b2b.b2b_terms

    def mutant(scaled, forces, mu):
        load, block, d_force, slip = original(scaled, forces, mu)
        if scaled.shape[0] == 2:  # the front ball gets pair 0's moment only; its Jacobian rows stay as they were
            load = load.copy()
            load[1, 1:] *= -1.0
        return load, block, d_force, slip
    monkeypatch.setattr(b2b, "b2b_terms", mutant)


def _hamrock_brewe(monkeypatch):  # b/a = 1 / (1.0339 (B/A)^0.636) instead of the exact ratio
    original = hertz.solve_load

    def mutant(geometry, force):
        contact = original(geometry, force)
        ratio = 1.0 / (1.0339 * (geometry.B / geometry.A) ** 0.636)
        return dataclasses.replace(contact, b=np.minimum(contact.a * ratio, contact.a))
    monkeypatch.setattr(hertz, "solve_load", mutant)


def _contact_modulus(monkeypatch):  # E* x 1.5
    monkeypatch.setattr(hertz, "contact_modulus", _scaled_value(hertz.contact_modulus, 1.5))


def _groove_radius(monkeypatch):  # groove radius x 1.01 (conformity x 1.01)
    original = hertz.ball_in_groove
    monkeypatch.setattr(hertz, "ball_in_groove", lambda radius, conformity, **kw: original(radius, 1.01 * conformity,
                                                                                             **kw))


def _eq30(monkeypatch):  # lin2019 eq 30 x 1.02
    monkeypatch.setattr(b2b_analytical, "_force", _scaled_value(b2b_analytical._force, 1.02))


def _lin2017_loss(monkeypatch):  # lin2017 friction loss x (1 + 1e-6)
    monkeypatch.setattr(fourpoint, "solve", _scaled_result(fourpoint.solve, 1.0 + 1e-6, "friction_loss"))


def _wang2022_u_a(monkeypatch):  # wang2022 eq 1 entrainment at the nut x 1.001
    monkeypatch.setattr(kinematics, "kinematics", _scaled_result(kinematics.kinematics, 1.001, "entrainment_nut"))


def _approach(monkeypatch):  # Hertz approach delta x 1.01 (lin2019 eq 53 constant)
    monkeypatch.setattr(hertz, "solve_load", _scaled_result(hertz.solve_load, 1.01, "delta"))


def _spin_moment(monkeypatch):  # lin2019 eq 11 spin moment (3/8) E(e) x 1.01
    monkeypatch.setattr(ellipse_friction, "spin_moment", _scaled_value(ellipse_friction.spin_moment, 1.01))


def _eq22_sign(monkeypatch):  # lin2019 eq 22 with the top-groove deviations entering with the wrong sign
    original = b2b_analytical._weighted
    monkeypatch.setattr(b2b_analytical, "_weighted", lambda bl, br, tr, tl, up, down:
                        original(bl, br, -tr, -tl, up, down))


def _normal_forces(monkeypatch):  # lin2017 eq 36 with the bottom pair swapped
    original = fourpoint.normal_forces
    monkeypatch.setattr(fourpoint, "normal_forces", lambda *args: original(*args)[..., [1, 0, 2, 3]])


def _wm_dimension(monkeypatch):  # sun2021 Sec 2.3 WM raceway with D + 0.1
    original = ehl.weierstrass_mandelbrot_surface
    monkeypatch.setattr(ehl, "weierstrass_mandelbrot_surface",
                        lambda x, y, fractal_dimension, *args, **kwargs: original(x, y, fractal_dimension + 0.1,
                                                                                  *args, **kwargs))


def _smooth_film_shear(monkeypatch):  # sun2021 eqs 22-23 with the smooth film instead of the rough one
    original = mixed.mixed_friction
    monkeypatch.setattr(mixed, "mixed_friction", lambda contact, *args, **kwargs: original(
        dataclasses.replace(contact, rough_film=contact.smooth.film), *args, **kwargs))


# mutant -> (what it is, scenes expected to reject it)
MUTANTS = {
    "Psi x 1.001": (_psi, ["lin2019-table1-psi"]),
    "k_f x 1.01 (analytical eq 30)": (_k_f_analytical, ["lin2019-analytical"]),
    "k_f x 1.01 (exact slope of eq A4)": (_k_f_exact, ["lin2019-kf"]),
    "B2B friction removed": (_no_b2b_friction, ["lin2019-table3-a", "lin2019-b2b-residual"]),
    "B2B friction moment, wrong sign on the front ball": (_b2b_moment_sign, ["lin2019-b2b-residual"]),
    "Hamrock-Brewe b/a instead of the exact ratio": (_hamrock_brewe, ["lin2019-b2b-residual"]),
    "E* x 1.5": (_contact_modulus, ["hertz-sphere-flat"]),
    "groove radius x 1.01": (_groove_radius, ["lin2019-table1-psi"]),
    "eq 30 x 1.02": (_eq30, ["lin2019-analytical"]),
    "lin2017 loss x (1 + 1e-6)": (_lin2017_loss, ["lin2017-eq40"]),
    "wang2022 U_A x 1.001": (_wang2022_u_a, ["wang2022-table2"]),
    "Hertz approach x 1.01": (_approach, ["hertz-sphere-flat"]),
    "eq 11 spin moment x 1.01": (_spin_moment, ["lin2019-kf"]),
    "eq 22 top deviations with the wrong sign": (_eq22_sign, ["lin2019-analytical"]),
    "lin2017 eq 36 bottom forces swapped": (_normal_forces, ["lin2019-table2-a"]),
    "WM fractal dimension + 0.1": (_wm_dimension, ["sun2021-roughness"]),
    "Eyring shear on the smooth film": (_smooth_film_shear, ["sun2021-fig6"]),
}
SCENES = sorted({name for _, names in MUTANTS.values() for name in names})
CHEAP = {"hertz-sphere-flat", "lin2019-table1-psi", "lin2019-table3-a", "wang2022-table2"}  # < 1 s each at quick
_BASELINE: dict = {}


def _run(names, directory):
    scenes = registry()
    return {name: run_scene(scenes[name], "quick", directory / name, show_progress=False) for name in names}


def _baseline(names, tmp_path_factory):
    missing = [name for name in names if name not in _BASELINE]
    if missing:
        _BASELINE.update(_run(missing, tmp_path_factory.mktemp("baseline")))
    return {name: _BASELINE[name] for name in names}


def _cases():
    for label, (_, names) in MUTANTS.items():
        marks = () if set(names) <= CHEAP else (pytest.mark.slow,)
        yield pytest.param(label, marks=marks, id=label)


@pytest.mark.parametrize("label", list(_cases()))
def test_mutant_is_rejected(label, monkeypatch, tmp_path, tmp_path_factory):
    mutate, names = MUTANTS[label]
    baseline = _baseline(names, tmp_path_factory)
    failed = {name: (result.error, [o.quantity for o in result.outputs if not o.passed])
              for name, result in baseline.items() if not result.passed}
    assert not failed, f"unmutated scenes must pass first: {failed}"
    mutate(monkeypatch)
    results = _run(names, tmp_path)
    assert any(not result.passed for result in results.values()), f"{label} passes {names}"


def test_mutant_list_is_documented():

    text = (paths.ROOT / "docs" / "mutations.md").read_text()
    for label, (_, names) in MUTANTS.items():
        assert label in text, label
        assert all(name in text for name in names), label


# --------------------------------------------------------------------------
# the case scenes (validation.ladder): a wrong model is rejected when a check of the scene leaves "pass" (a model
# outside its accuracy is a finding there, not a failure: docs/validation.md, "Findings")
# --------------------------------------------------------------------------
def _nut_bem_on_screw_groove(monkeypatch):  # the BEM of a nut-side contact on the screw's groove
    from ballbench.lowmodel.contact import screw_contact

    original = screw_contact.groove_contact

    def mutant(ball_radius, conformity, pitch_radius, lead, contact_angle, force, body="screw", *args, **kwargs):
        return original(ball_radius, conformity, pitch_radius, lead, contact_angle, force, "screw", *args, **kwargs)
    monkeypatch.setattr(screw_contact, "groove_contact", mutant)


def _soft_half_space(monkeypatch):  # stick/slip on a half-space of a tenth of the steel's shear modulus
    from ballbench.lowmodel.linear_bearing import b2b_rolling

    original = b2b_rolling._material
    monkeypatch.setattr(b2b_rolling, "_material", lambda e, nu: (0.1 * original(e, nu)[0], original(e, nu)[1]))


def _soft_fe_compliance(monkeypatch):  # the case's groove condensed with a tenth of its Young's modulus
    from ballbench.validation.studies import rolling_b2b

    original = rolling_b2b.pair_compliance

    def mutant(*args):
        *head, (youngs_modulus, poisson_ratio) = args
        return original(*head, (0.1 * youngs_modulus, poisson_ratio))
    monkeypatch.setattr(rolling_b2b, "pair_compliance", mutant)


def _screw_gap_on_nut_side(monkeypatch):  # the EHL solve of a nut-side contact on the screw groove's gap
    from ballbench.lowmodel.geometry import groove

    original = groove.pair_initial_gap

    def mutant(ball_radius, conformity, pitch_radius, lead, contact_angle, body="screw", **kwargs):
        return original(ball_radius, conformity, pitch_radius, lead, contact_angle, "screw", **kwargs)
    monkeypatch.setattr(groove, "pair_initial_gap", mutant)


# mutant -> (what it is, case file, rung, scene suffix, the checks (level, quantity) expected to leave "pass")
CASE_MUTANTS = {
    "nut-side BEM on the screw's groove": (_nut_bem_on_screw_groove, "validation/cases/files/lin2019-table5-a.toml",
                                           "BEM", "contact", [("nut side", "b"), ("nut side", "p0")]),
    "stick/slip half-space shear modulus x 0.1": (_soft_half_space, "examples/compact_linear_guide.toml",
                                                  "stick-slip", "stick-slip",
                                                  [("16 x 64 cells", "friction force, balls apart")]),
    "EHL gap of the screw groove on the nut side": (_screw_gap_on_nut_side, "examples/ball_screw_32x10_oil.toml",
                                                    "EHL", "ehl", [("nut side, 128 x 32 cells", "central film h_c")]),
    "FE compliance of the case's groove with E x 0.1": (
        _soft_fe_compliance, "examples/compact_linear_guide.toml", "stick-slip", "stick-slip",
        [("8 x 32 cells, FE compliance P2, h 0.8 cell, 242643 DOFs", "F_B2B"),
         ("8 x 32 cells, FE compliance P2, h 0.8 cell, 242643 DOFs", "friction force, balls apart")]),
}
# the fidelity a case mutant runs at (quick unless named): the FE compliance rung runs from the default level on
CASE_FIDELITY = {"FE compliance of the case's groove with E x 0.1": "default"}


def _case_scene(path, rung, suffix, directory, fidelity="quick"):
    from ballbench.validation import ladder
    from ballbench.validation.cases import case_file
    from ballbench.validation.runner import run_scenes

    (scene,) = [s for s in ladder.case_scenes(case_file.load(paths.ROOT / path), "m", top=rung)
                if s.name == f"m-{suffix}"]
    (result,), _ = run_scenes([scene], fidelity, directory, show_progress=False)
    return {(o.level, o.quantity): o.status for o in result.outputs}, result.error


@pytest.mark.parametrize("label", [pytest.param(k, marks=(pytest.mark.slow,) if v[2] in ("stick-slip", "EHL") else (),
                                                id=k)
                                   for k, v in CASE_MUTANTS.items()])
def test_case_scene_mutant_is_rejected(label, monkeypatch, tmp_path):
    mutate, path, rung, suffix, rejecting = CASE_MUTANTS[label]
    fidelity = CASE_FIDELITY.get(label, "quick")
    statuses, error = _case_scene(path, rung, suffix, tmp_path / "baseline", fidelity)
    assert not error and all(s == "pass" for s in statuses.values()), f"unmutated checks must pass first: {statuses}"
    mutate(monkeypatch)
    statuses, error = _case_scene(path, rung, suffix, tmp_path / "mutant", fidelity)
    assert not error, error
    assert all(statuses[key] != "pass" for key in rejecting), f"{label} passes: {statuses}"


def test_case_mutant_list_is_documented():
    text = (paths.ROOT / "docs" / "mutations.md").read_text()
    for label in CASE_MUTANTS:
        assert label in text, label
