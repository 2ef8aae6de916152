"""Property-based test of the contact / sun2021 / calibration half of lowmodel's public API (issue 10 item 8).

Covers the public functions of lowmodel.contact.{halfspace, ehl, roughness, mixed, traction,
ellipse_friction_offset}, the parts of hertz and ellipse_friction that tests/test_properties.py does not call,
lowmodel.calibration, lowmodel.linear_bearing.b2b_traction and lowmodel.solvers.  Random finite inputs in the
documented ranges and a little beyond (negative, zero, huge, tiny, grids of 1-2 cells) give finite outputs or a
ValueError / ConvergenceError naming a parameter; never NaN, never a warning (property_support.call).
Solves run on 4-32 cell grids under the SLOW settings, drawn by ``one_bad``: all inputs in range, or one of
them out of range, so that most draws reach the solve (1-3 cell grids: test_halfspace_grids).
"""
from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballbench.lowmodel import calibration, quadrature, solvers
from ballbench.lowmodel.contact import ehl, hertz, mixed, roughness, traction
from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import ellipse_friction_offset as offset
from ballbench.lowmodel.contact import halfspace as hs
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import b2b_traction as bt
from tests.property_support import SETTINGS, SLOW, call, positive, real

# lengths [m] and counts: the documented range, a little beyond (zero, negative, huge, tiny) and a bool
length = st.one_of(positive(1e-9, 1.0), st.sampled_from([0.0, -1e-3, 1e300, 5e-324]))
cells = st.one_of(st.integers(-1, 64), st.just(True))
small_cells = st.one_of(st.integers(1, 24), st.sampled_from([0, -2, True]))
modulus = st.one_of(positive(1e6, 1e13), st.sampled_from([0.0, -1e11, 1e300]))
speed = st.one_of(real(-10.0, 10.0), st.sampled_from([0.0, 1e-300, 1e300, -1e300]))


def one_bad(valid: dict, bad: dict):
    """Keyword dicts: every value drawn from ``valid`` (the documented ranges), and in half the cases one of them
    replaced by a draw from ``bad`` (zero, negative, huge, tiny, a bool count), so that the solves run often."""
    keys = sorted(bad)
    return st.fixed_dictionaries(valid).flatmap(lambda kw: st.sampled_from([None] * len(keys) + keys).flatmap(
        lambda key: st.just(kw) if key is None else bad[key].map(lambda value: {**kw, key: value})))


# --- hertz (the parts tests/test_properties.py does not call) -------------------------------------------------
@SETTINGS
@given(e1=modulus, nu1=real(-1.2, 0.6), e2=st.one_of(st.none(), modulus), nu2=st.one_of(st.none(), real(-1.2, 0.6)),
       k1=st.tuples(real(-1e6, 1e6), real(-1e6, 1e6)), k2=st.tuples(real(-1e6, 1e6), real(-1e6, 1e6)),
       angle=real(-10.0, 10.0), radius=length, other=st.one_of(st.none(), length), delta=real(-1e-6, 1e-2))
def test_hertz_curvatures(e1, nu1, e2, nu2, k1, k2, angle, radius, other, delta):
    call(hertz.contact_modulus, e1, nu1, e2, nu2)
    geometry = call(hertz.from_curvatures, k1, k2, angle=angle, youngs_modulus=e1, poisson_ratio=nu1,
                    youngs_modulus_2=e2, poisson_ratio_2=nu2)
    if geometry is not None:
        call(hertz.solve_approach, geometry, delta)
        call(hertz.solve_load, geometry, [0.0, abs(delta) * 1e9])
        call(hertz.psi_constant, geometry, radius)
        call(hertz.hertz_constant, geometry)
    geometry = call(hertz.ball_on_ball, radius, other, youngs_modulus=e1, poisson_ratio=nu1, youngs_modulus_2=e2,
                    poisson_ratio_2=nu2)
    if geometry is not None:
        call(hertz.solve_approach, geometry, delta)


@SETTINGS
@given(kw=one_bad(
    dict(radius=positive(1e-4, 0.02), conformity=real(0.505, 0.6), pitch_ratio=real(3.0, 20.0), alpha=real(0.3, 1.2),
         lead=real(0.0, 0.5), body=st.sampled_from(["screw", "nut"]), plane=st.sampled_from(["normal", "axial"])),
    # (a radius or pitch radius of 1e300 m overflows in the geometry core, lowmodel.geometry.groove.contact_frame:
    # another engineer's file, reported there; not drawn here)
    dict(radius=st.sampled_from([0.0, -1e-3, 5e-324]), conformity=st.sampled_from([0.5, 0.45, 1.05]),
         pitch_ratio=st.sampled_from([0.0, -1.0]), alpha=st.sampled_from([0.0, -0.2, 1.8]),
         lead=st.sampled_from([-0.2, 1.6]), body=st.just("bolt"), plane=st.just("other"))))
def test_hertz_screw_groove(kw):
    geometry = call(hertz.ball_in_screw_groove, kw["radius"], kw["conformity"], kw["pitch_ratio"] * kw["radius"],
                    kw["alpha"], kw["lead"], kw["body"], profile_plane=kw["plane"])
    if geometry is not None:
        call(hertz.solve_load, geometry, [0.0, 1.0, 1e4])


# --- ellipse friction (the parts tests/test_properties.py does not call) ----------------------------------------
@SETTINGS
@given(beta=st.one_of(real(-0.1, 1.2), st.sampled_from([0.0, 0.02, 1.0, 5e-324])), stacked=st.booleans(),
       level=st.one_of(st.integers(-1, 7), st.just(True)))
def test_ellipse_friction_rest(beta, stacked, level):
    if 0.0 < beta <= 1.0:  # a closure over the tabulated map; it is evaluated at slip angles
        at = call(ef.friction_angle_at, beta, stacked=stacked)
        if at is not None:
            call(at, np.full(np.shape(beta), 2.5))  # phi of the shape of b_over_a (its docstring)
    else:
        call(ef.friction_angle_at, beta, stacked=stacked)
    call(quadrature.tanh_sinh, level)


@SLOW
@given(kw=one_bad(dict(n_uniform=st.integers(9, 13), n_cluster=st.integers(1, 3), n_beta=st.integers(4, 6)),
                  dict(n_uniform=st.sampled_from([8, -1, True, 9.0]), n_cluster=st.sampled_from([0, True]),
                       n_beta=st.sampled_from([3, 4.0]))))
def test_friction_map_small(kw):
    call(ef.friction_map, kw["n_uniform"], kw["n_cluster"], kw["n_beta"], use_cache=False)


# --- ellipse friction with an offset velocity centre -------------------------------------------------------------
@SETTINGS
@given(spin=speed, minor=speed, major=speed, beta=st.one_of(real(-0.1, 1.2), st.sampled_from([0.02, 1.0, 0.0])),
       level=st.one_of(st.integers(-1, 6), st.just(True)), c=real(-1e3, 1e3), d=real(-1e3, 1e3))
def test_friction_offset(spin, minor, major, beta, level, c, d):
    call(offset.friction_offset, spin, minor, major, beta, level=level)
    call(offset.friction_offset, [spin, 0.0], [minor, 0.0], [major, 0.0], beta)
    call(offset.friction_centre, c, d, beta, level=level)


# --- half-space contact ----------------------------------------------------------------------------------------
@SETTINGS
@given(hx=length, hy=st.one_of(st.none(), length), nx=cells, ny=st.one_of(st.none(), cells),
       a=length, b=st.one_of(st.none(), length), margin=real(-1.0, 5.0), square=st.booleans())
def test_halfspace_grids(hx, hy, nx, ny, a, b, margin, square):
    call(hs.surface_grid, hx, hy, nx, ny)
    call(hs.hertz_surface_grid, a, b, nx, margin, square)
    call(hs.SurfaceGrid, nx, 1 if ny is None else ny, hx, 1e-3 if hy is None else hy)
    if isinstance(nx, int) and not isinstance(nx, bool) and 1 <= nx <= 16:
        call(hs.influence_coefficients, nx, nx, hx, 1e-3 if hy is None else hy)


@SLOW
@given(kw=one_bad(
    dict(n=st.sampled_from([4, 8, 16, 32]), A=positive(100.0, 1e4), B=positive(100.0, 1e4), angle=real(-3.2, 3.2),
         e_star=positive(1e10, 1e12), force=positive(1e-3, 10.0), use_force=st.booleans(), pressure=real(0.0, 1e9)),
    dict(A=st.sampled_from([0.0, -50.0, 1e300, 5e-324]), e_star=st.sampled_from([0.0, -1e11, 1e300, 5e-324]),
         force=st.sampled_from([0.0, -1.0, 1e300, 5e-324]), pressure=st.sampled_from([-1e9, 1e300]))))
def test_halfspace_solve(kw):
    grid = hs.surface_grid(2e-4, 2e-4, kw["n"], kw["n"])
    gap = call(hs.quadratic_gap, grid, kw["A"], kw["B"], kw["angle"])
    field = np.full((grid.nx, grid.ny), kw["pressure"])
    call(hs.deformation, field, grid, kw["e_star"])
    call(hs.pressure_ellipse, np.abs(field), grid)
    call(hs.pressure_ellipse, np.zeros_like(field), grid)
    if gap is None:
        return
    control = {"force": kw["force"]} if kw["use_force"] else {"approach": kw["force"] * 1e-7}
    result = call(hs.solve, gap, grid, kw["e_star"], max_iterations=300, **control)
    if result is not None:
        assert np.all(result.pressure >= 0.0)
        if kw["use_force"]:
            assert result.force == pytest.approx(kw["force"], rel=1e-6)


# --- roughness and the Weierstrass-Mandelbrot surface ---------------------------------------------------------
@SETTINGS
@given(D=real(1.9, 3.1), G=length, L=length, Ls=length, gamma=real(0.5, 3.0),
       ridges=st.one_of(st.integers(-1, 12), st.just(True)), seed=st.one_of(st.integers(0, 2**31), st.just(-1)))
def test_roughness(D, G, L, Ls, gamma, ridges, seed):
    call(roughness.wm_amplitude, D, G, L, gamma=gamma, ridges=ridges)
    call(roughness.wm_rms, D, G, L, Ls, gamma=gamma)
    call(roughness.wm_line_spectrum, D, G, L, Ls, gamma=gamma, ridges=ridges)
    call(ehl.wm_parameters, D, G, L, Ls, gamma, ridges)
    call(ehl.wm_top_level, L, Ls, gamma)
    x = np.linspace(-1e-4, 1e-4, 5)
    if L < 1.0 and Ls > 1e-7 * L:  # few enough levels to evaluate
        call(ehl.weierstrass_mandelbrot_surface, x, x[::-1], D, G, L, cutoff_length=Ls, gamma=gamma, ridges=ridges,
             seed=seed)


@SETTINGS
@given(n=small_cells, D=real(1.9, 3.1), G=length, L=st.one_of(st.none(), length), Ls=st.one_of(st.none(), length),
       gamma=real(0.5, 3.0), ridges=st.one_of(st.integers(-1, 12), st.just(True)))
def test_raceway_roughness(n, D, G, L, Ls, gamma, ridges):
    grid = call(hs.surface_grid, 1e-4, 1e-4, n, n)
    if grid is None or (L is not None and L > 1.0) or (Ls is not None and Ls < 1e-9):
        return
    result = call(roughness.raceway_roughness, grid, D, G, sample_length=L, cutoff_length=Ls, gamma=gamma,
                  ridges=ridges)
    if result is not None:
        assert abs(float(np.mean(result.heights))) <= 1e-9 * max(float(np.abs(result.heights).max()), 1e-300)


# --- EHL closed forms ------------------------------------------------------------------------------------------
@SETTINGS
@given(p=st.one_of(real(-1e10, 1e12), st.just(1e300)), eta0=st.one_of(positive(1e-6, 1e3), st.sampled_from(
    [0.0, -0.05, 1e-300, 1e300])), rho0=st.one_of(positive(1.0, 1e4), st.just(-1.0)), du=speed,
       h=st.one_of(positive(1e-10, 1e-3), st.sampled_from([0.0, -1e-7])), tau0=st.one_of(positive(1e3, 1e9),
                                                                                          st.just(0.0)))
def test_ehl_laws(p, eta0, rho0, du, h, tau0):
    call(ehl.roelands_viscosity, [p, 0.0], eta0)
    call(ehl.roelands_pressure_viscosity_coefficient, eta0)
    call(ehl.dowson_higginson_density, [p, -p], rho0)
    call(ehl.eyring_shear_stress, eta0, du, h, tau0)


@SETTINGS
@given(u=speed, load=real(-1.0, 1e5), rx=length, ry=length, e_prime=modulus, eta0=positive(1e-4, 1.0),
       alpha=st.one_of(positive(1e-9, 1e-7), st.just(0.0)))
def test_hamrock_dowson(u, load, rx, ry, e_prime, eta0, alpha):
    call(ehl.hamrock_dowson_film, u, load, rx, ry, e_prime, eta0, alpha)


@SETTINGS
@given(qa=real(-1.0, 1e3), qf=real(-1e3, 1e3), q=st.one_of(real(-1.0, 1e3), st.just(0.0)), mu_a=real(-0.1, 1.5))
def test_ehl_friction_coefficient(qa, qf, q, mu_a):
    call(ehl.friction_coefficient, qa, qf, q, mu_a)


RX = 0.01  # a 20 N point contact of R = 10 mm (tests/test_mixed.py's case), on 16-32 cell grids


def _ehl_case(n):
    geometry = hertz.from_curvatures((1 / RX, 1 / RX), (0.0, 0.0), youngs_modulus=2.1e11, poisson_ratio=0.3)
    a = float(hertz.solve_load(geometry, 20.0).a)
    grid = hs.SurfaceGrid(n, n, 5.5 * a / n, 5.0 * a / n, -1.25 * a, 0.0)
    X, Y = grid.coordinates()
    return geometry.contact_modulus, grid, (X**2 + Y**2) / (2 * RX)


EHL_VALID = dict(n=st.sampled_from([16, 24, 32]), load=real(5.0, 25.0), u=real(0.5, 2.0), eta0=real(0.02, 0.1),
                 film=real(1e-7, 5e-7), du=real(-1.0, 1.0), tau0=positive(1e6, 1e8))
EHL_BAD = dict(load=st.sampled_from([0.0, -1.0, 1e-17, 1e6]), u=st.sampled_from([0.0, -1.0, 1e-300, 1e300]),
               eta0=st.sampled_from([0.0, 1e300, 1e-300]), film=st.sampled_from([0.0, 1e-300, 1.0]),
               du=st.sampled_from([0.0, 1e300]), tau0=st.sampled_from([0.0, 1e-300]))


@SLOW
@given(kw=one_bad(EHL_VALID, EHL_BAD))
def test_ehl_solve(kw):
    e_star, grid, gap = _ehl_case(kw["n"])
    solution = call(ehl.solve_reynolds, gap, grid, e_star, kw["load"], kw["u"], kw["eta0"], initial_film=kw["film"],
                    max_iterations=40)
    if solution is not None:
        assert solution.force == pytest.approx(kw["load"], rel=1e-4) and np.all(solution.film > 0.0)
        call(ehl.film_traction, solution, kw["du"], kw["eta0"], kw["tau0"])


# --- mixed lubrication ------------------------------------------------------------------------------------------
@SLOW
@given(kw=one_bad(dict(EHL_VALID, rough=real(0.0, 1e-6), coupled=st.booleans(), mu_a=real(0.0, 0.3)),
                  dict(EHL_BAD, rough=st.sampled_from([1e300, -1.0]), mu_a=st.sampled_from([-0.1, 1e300]))))
def test_mixed(kw):
    e_star, grid, gap = _ehl_case(kw["n"])
    heights = kw["rough"] * np.cos(np.arange(grid.nx * grid.ny).reshape(grid.nx, grid.ny))
    call(mixed.asperity_contact, gap * 0.0 + 1e-7, heights, grid, e_star)
    contact = call(mixed.solve, gap, heights, grid, e_star, kw["load"], kw["u"], kw["eta0"],
                   initial_film=kw["film"], coupled=kw["coupled"], max_iterations=4, ehl_iterations=30)
    if contact is not None:
        assert contact.film_load + contact.asperity_load == pytest.approx(kw["load"], rel=0.02)
        call(mixed.mixed_friction, contact, kw["du"], kw["eta0"], kw["tau0"], kw["mu_a"])


# --- sampled tractions ----------------------------------------------------------------------------------------
@SETTINGS
@given(n_radial=small_cells, n_angular=small_cells, k=st.integers(0, 5), force=real(-1.0, 1e3),
       normal_scale=st.one_of(real(0.0, 2.0), st.just(1.0)), index=st.integers(-1, 3))
def test_traction_patches(n_radial, n_angular, k, force, normal_scale, index):
    samples = call(traction.ellipse_samples, n_radial, n_angular)
    if samples is not None:
        assert abs(float(np.sum(samples[2])) - 1.0) <= 1e-12
    normals = np.tile([0.0, normal_scale, 0.0], (k, 1))
    patch = traction.TractionPatch(np.zeros((k, 3)), normals, np.full(k, force), False, "BL")
    try:  # check_patch names the patch's array (points, normals, forces) in its errors (its docstring)
        checked = call(traction.check_patch, patch, index)
    except AssertionError as error:
        assert any(f": {name} " in str(error) for name in ("points", "normals", "forces")), error
        checked = None
    if checked is not None:
        for reference in (force, 0.0, -1.0, 5e-324):
            stacked = call(traction.stack_patches, [[checked], [checked]], 1, reference, 1.0)
            if stacked is not None:
                assert np.allclose(stacked.load, checked.forces[0] / reference)
                assert stacked.ball.tolist() == [0] * k + [1] * k


@SETTINGS
@given(targets=st.lists(real(-10.0, 10.0), min_size=1, max_size=4), tolerance=st.one_of(positive(1e-14, 1e-6),
       st.sampled_from([0.0, math.inf])), iterations=st.one_of(st.integers(0, 30), st.just(True)))
def test_free_ball_starts(targets, tolerance, iterations):
    """Each ball alone solves x_b^3 = t_b (one real root: Newton converges from 1 unless t_b = 0 stalls it)."""
    target = np.asarray(targets)[:, None]

    def evaluate(states, ball):
        x = states[ball]
        return x**3 - target[ball], np.diag(3.0 * x**2)

    free = call(traction.free_ball_starts, evaluate, np.ones((len(targets), 1)), tolerance=tolerance,
                max_iterations=iterations, what="ball")
    if free is not None:
        assert np.all(np.abs(free[0] ** 3 - target) <= tolerance)


# --- calibration -----------------------------------------------------------------------------------------------
forces_list = st.lists(st.one_of(real(-1.0, 1e4), st.just(0.0)), min_size=0, max_size=8)


@SETTINGS
@given(forces=forces_list, c=positive(1e-9, 1e-5), cb=real(-1e-9, 1e-8), noise=real(0.0, 1e-9),
       confidence=st.one_of(real(0.5, 0.999), st.sampled_from([0.0, 1.0, 1.5])), radius=st.one_of(st.none(), length))
def test_fit_contact_law(forces, c, cb, noise, confidence, radius):
    f = np.asarray(forces, dtype=float)
    approaches = c * np.cbrt(np.abs(f)) ** 2 + cb * f + noise * np.cos(np.arange(f.size))
    semi_axes = None if radius is None else 1e-4 * np.cbrt(np.abs(f))
    call(calibration.fit_contact_law, f, approaches, semi_axes=semi_axes, ball_radius=radius, confidence=confidence)


@SETTINGS
@given(u=st.one_of(real(-1e-3, 1e-3), st.sampled_from([0.0, 1e300])), c=st.one_of(positive(1e-9, 1e-5), st.sampled_from(
    [0.0, -1e-6])), cb=st.one_of(real(-1e-6, 1e-6), st.just(0.0)), tolerance=st.one_of(positive(1e-15, 1e-6),
                                                                                      st.just(0.0)),
       iterations=st.one_of(st.integers(0, 60), st.just(True)))
def test_law_force(u, c, cb, tolerance, iterations):
    call(calibration.law_force, [u, 0.5 * u], c, cb, tolerance=tolerance, max_iterations=iterations)


@SETTINGS
@given(normal=forces_list, mu=real(-0.1, 1.0), with_speed=st.booleans(), confidence=real(0.0, 1.2),
       x=st.lists(real(-10.0, 10.0), max_size=6))
def test_fit_friction(normal, mu, with_speed, confidence, x):
    f = np.asarray(normal, dtype=float)
    speeds = np.linspace(0.0, 1.0, f.size) if with_speed else None
    call(calibration.fit_friction_coefficient, f, mu * f, speeds, confidence=confidence)
    y = -0.8 * np.asarray(x) + 1e-3 * np.sin(np.arange(len(x)))
    call(calibration.fit_line_through_origin, x, y, confidence=confidence)


@SETTINGS
@given(p0=st.lists(real(-10.0, 10.0), min_size=1, max_size=3), n=st.integers(-1, 8), confidence=real(0.0, 1.2),
       scale=st.one_of(st.none(), st.sampled_from([-1.0, 0.0]), positive(1e-3, 1e3)))
def test_fit_least_squares(p0, n, confidence, scale):
    t = np.linspace(0.0, 1.0, max(n, 0))

    def residual(p):
        return sum(pi * t**i for i, pi in enumerate(p)) - np.exp(t)

    call(calibration.fit_least_squares, residual, p0, n_points=n, confidence=confidence, x_scale=scale)


def test_calibration_file_round_trip():
    law = calibration.fit_contact_law([1.0, 2.0, 4.0, 8.0], [1e-6, 1.6e-6, 2.5e-6, 4.0e-6])
    cal = calibration.Calibration({"ball-ball": {"C": law.hertz_constant}})
    with tempfile.TemporaryDirectory() as folder:
        path = calibration.save(cal, Path(folder) / "c.json")
        assert calibration.load(path).constants["ball-ball"]["C"].value == law.hertz_constant.value
        Path(folder, "bad.json").write_text("{not json")
        with pytest.raises(ValueError, match="bad.json"):
            calibration.load(Path(folder) / "bad.json")


# --- FE-informed B2B with sampled tractions ----------------------------------------------------------------------
@SLOW
@given(kw=one_bad(
    dict(rho=real(-0.9, 0.9), ball=st.integers(0, 1), n_radial=st.integers(1, 6), n_angular=st.integers(4, 16),
         planar=st.booleans(), mu=real(0.01, 0.5), velocity=st.sampled_from([-0.5, 0.01, 2.0]),
         gap=st.one_of(real(0.0, 1e-4), st.none())),
    dict(ball=st.sampled_from([-1, 2, True]), n_radial=st.sampled_from([0, -1, True]), mu=st.sampled_from([0.0, -0.1]),
         velocity=st.sampled_from([0.0, 1e300]), gap=st.sampled_from([-1e-4, 1e300]),
         radius=st.sampled_from([0.0, -5e-3, 5e-324]))))
def test_b2b_traction(kw):
    contacts = b2b.module_contacts(math.radians(2.0), kw["rho"], n_balls=2, friction_coefficient=0.1)
    patches = [call(bt.hertz_patches, contacts, j, n_radial=kw["n_radial"], n_angular=kw["n_angular"],
                    planar=kw["planar"]) for j in (kw["ball"], 1 - kw["ball"] if kw["ball"] in (0, 1) else 0)]
    if patches[0] is None or patches[1] is None:
        return
    state = call(bt.solve, patches, ball_radius=kw.get("radius", contacts.ball_radius), friction_coefficient=kw["mu"],
                 groove_velocity=kw["velocity"], gaps=None if kw["gap"] is None else [kw["gap"]], max_iterations=60)
    if state is not None:
        assert abs(state.power_balance) <= bt.POWER_BALANCE_TOLERANCE


# --- generic solvers -------------------------------------------------------------------------------------------
def _quadratic(c):
    """x^2 = c: a root for c >= 0, none (a minimum of |r| at x = 0) for c < 0."""
    return lambda x: (x * x - c, np.diag(2.0 * x))


@SETTINGS
@given(c=real(-10.0, 10.0), x0=real(-100.0, 100.0), size=st.integers(1, 4),
       tolerance=st.one_of(positive(1e-14, 1e-2), st.sampled_from([0.0, -1.0, math.nan, math.inf])),
       iterations=st.one_of(st.integers(0, 80), st.sampled_from([True, 2.5])))
def test_newton(c, x0, size, tolerance, iterations):
    try:
        x, residual, count = solvers.newton(_quadratic(c), np.full(size, x0), tolerance=tolerance,
                                            max_iterations=iterations, what="x^2 = c")
    except ValueError as error:
        assert "tolerance" in str(error) or "max_iterations" in str(error), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual) and "x^2 = c" in str(error)
        return
    # never an unconverged point, never an accepted nonsense option
    assert 0.0 < tolerance < math.inf and iterations is not True and isinstance(iterations, int)
    assert np.max(np.abs(x * x - c)) <= tolerance and count <= iterations  # (c < -tolerance: never here)
    assert np.all(np.isfinite(residual))


@SETTINGS
@given(fold=real(0.05, 2.0), initial=st.one_of(positive(1e-3, 1.0), st.sampled_from([0.0, -0.25, math.nan])),
       min_step=st.one_of(positive(1e-6, 0.5), st.sampled_from([0.0, -1.0])),
       max_steps=st.one_of(st.integers(0, 50), st.just(True)))
def test_continuation(fold, initial, min_step, max_steps):
    """Root of x^2 = 1 - s / fold from x = 1 at s = 0: exists up to s = fold (a fold there)."""
    def solve_at(s, x0):
        return solvers.newton(_quadratic(1.0 - s / fold), x0, tolerance=1e-12, max_iterations=30, what="fold")

    try:
        x, residual, path = solvers.continuation(solve_at, np.array([1.0]), what="fold", initial_step=initial,
                                                 min_step=min_step, max_steps=max_steps)
    except ValueError as error:
        assert any(name in str(error) for name in ("initial_step", "min_step", "max_steps")), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual) and error.last_converged is not None
        assert error.last_converged[1] <= fold + 1e-12  # never beyond the fold
        return
    assert fold >= 1.0 and path[-1].parameter == 1.0 and abs(x[0] ** 2 - (1.0 - 1.0 / fold)) <= 1e-12


@SETTINGS
@given(c=real(0.0, 10.0), attempts=st.one_of(st.integers(-1, 4), st.just(True)))
def test_solve_with_restarts(c, attempts):
    """The positive root of x^2 = c: a converged negative root is rejected and restarted from -x."""
    def restart(x):
        return None if x[0] >= 0.0 else (-x, float(-x[0]))

    try:
        x, _, _ = solvers.solve_with_restarts(_quadratic(c), np.array([-3.0]), restart, tolerance=1e-12,
                                              max_iterations=60, what="root", attempts=attempts)
    except ValueError as error:
        assert "attempts" in str(error), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual)
        return
    assert x[0] >= 0.0 and abs(x[0] ** 2 - c) <= 1e-12


json_value = st.recursive(st.one_of(st.none(), st.booleans(), st.integers(-5, 5), st.floats(), st.text(max_size=3)),
                          lambda inner: st.one_of(st.lists(inner, max_size=2),
                                                  st.dictionaries(st.text(max_size=3), inner, max_size=2)),
                          max_leaves=4)


@SETTINGS
@given(where=st.sampled_from(["format", "version", "notes", "constants", "group", "record", "value", "unit",
                              "confidence", "n_points", "extra"]), value=json_value)
def test_calibration_file_with_one_wrong_field(where, value):
    """load() of a file with one field replaced by any JSON value: a Calibration, or a ValueError naming the file."""
    import json

    cal = calibration.Calibration({"ball-ball": {"C": calibration.Constant(2.5e-7, 1e-9, 2.4e-7, 2.6e-7, "m N^-2/3",
                                                                          "fe", 0.95, 4, 1e-9, 2.49e-7)}})
    with tempfile.TemporaryDirectory() as folder:
        path = calibration.save(cal, Path(folder) / "c.json")
        document = json.loads(path.read_text())
        record = document["constants"]["ball-ball"]["C"]
        if where in ("format", "version", "notes", "constants"):
            document[where] = value
        elif where == "group":
            document["constants"]["ball-ball"] = value
        elif where == "record":
            document["constants"]["ball-ball"]["C"] = value
        else:
            record[where] = value
        path.write_text(json.dumps(document))
        try:
            loaded = calibration.load(path)
        except ValueError as error:
            assert str(path) in str(error), error
            return
        for constant in (c for group in loaded.constants.values() for c in group.values()):
            values = (constant.value, constant.std_error, constant.ci_low, constant.ci_high)
            assert all(math.isfinite(v) for v in values)
            assert isinstance(constant.unit, str) and isinstance(constant.source, str)
