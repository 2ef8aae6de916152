"""Half-space contact (BEM: Love coefficients, DC-FFT, Polonsky-Keer CG) against exact Hertz and closed forms."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import halfspace as hs, hertz
from ballbench.lowmodel.errors import ConvergenceError
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, SLOW, call, one_bad, positive, real

STEEL = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.28}
LOAD = 100.0  # N


def test_dcfft_equals_direct_sum_without_wraparound():
    grid = hs.surface_grid(1e-4, 0.7e-4, 12, 9)
    kernel = hs.influence_coefficients(12, 9, grid.dx, grid.dy)
    rng = np.random.default_rng(1)
    pressure = rng.random((12, 9))
    direct = np.zeros((12, 9))
    for i in range(12):
        for j in range(9):
            for k in range(12):
                for m in range(9):
                    direct[i, j] += kernel[i - k + 11, j - m + 8] * pressure[k, m]
    fast = hs.deformation(pressure, grid, 1.0)
    assert np.max(np.abs(fast - direct)) < 1e-13 * np.max(np.abs(direct))


def test_fft_paths_agree_with_the_direct_sum(monkeypatch):
    # the single-precision transforms of the CG increments (ducc0) are within 1e-6 of the direct sum, and the
    # scipy.fft fallback (no ducc0) is exact; a wrong normalisation or a periodic wrap-around fails both
    nx, ny = 10, 7
    grid = hs.surface_grid(1e-4, 0.7e-4, nx, ny)
    kernel = hs.influence_coefficients(nx, ny, grid.dx, grid.dy)
    pressure = np.random.default_rng(2).random((nx, ny))
    direct = np.array([[sum(kernel[i - k + nx - 1, j - m + ny - 1] * pressure[k, m]
                            for k in range(nx) for m in range(ny)) for j in range(ny)] for i in range(nx)])
    spectrum = hs._kernel_spectrum(nx, ny, grid.dx, grid.dy)
    scale = np.max(np.abs(direct))
    single = hs._convolve(spectrum, pressure, spectrum.astype(np.float32))
    assert single.dtype == np.float32 and np.max(np.abs(single - direct)) < 1e-6 * scale
    monkeypatch.setattr(hs, "_ducc_fft", lambda: None)
    assert np.max(np.abs(hs._convolve(spectrum, pressure) - direct)) < 1e-13 * scale


def test_love_coefficient_centre_of_square_closed_form():
    # centre of a uniformly loaded square of side 2c: int int dA / r = 8 c ln(1 + sqrt 2) (polar integration)
    c = 3e-5
    kernel = hs.influence_coefficients(4, 4, 2 * c, 2 * c)
    assert kernel[3, 3] == pytest.approx(8 * c * math.log(1 + math.sqrt(2)) / math.pi, rel=1e-13)
    # far field: a point load, area / (pi r)
    far = hs.influence_coefficients(64, 64, 2 * c, 2 * c)[63 + 60, 63]
    assert far == pytest.approx((2 * c) ** 2 / (math.pi * 60 * 2 * c), rel=1e-4)
    # symmetry of the rectangle kernel
    rect = hs.influence_coefficients(8, 6, 2e-5, 5e-5)
    assert np.allclose(rect, rect[::-1, :], rtol=1e-14) and np.allclose(rect, rect[:, ::-1], rtol=1e-14)


def _solve_hertz(geometry, n, **kwargs):
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), float(contact.b), n)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    return contact, hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, **kwargs)


def _errors(contact, result):
    return {"p0": result.central_pressure / float(contact.p0) - 1,
            "a": result.semi_axis_a / float(contact.a) - 1,
            "b": result.semi_axis_b / float(contact.b) - 1,
            "delta": result.approach / float(contact.delta) - 1}


GEOMETRIES = {
    "ball on flat": hertz.ball_on_flat(5e-3, **STEEL),
    "ball on ball": hertz.ball_on_ball(5e-3, **STEEL),
    "groove 0.52": hertz.ball_in_groove(5e-3, 0.52, **STEEL),
    "groove 0.56": hertz.ball_in_groove(5e-3, 0.56, **STEEL),
    "groove 0.60": hertz.ball_in_groove(5e-3, 0.60, **STEEL),
}


@pytest.mark.parametrize("name", list(GEOMETRIES))
def test_default_grid_matches_exact_hertz_to_half_a_percent(name):
    contact, result = _solve_hertz(GEOMETRIES[name], 256)
    for quantity, error in _errors(contact, result).items():
        assert abs(error) < 5e-3, (quantity, error)
    assert result.force == pytest.approx(LOAD, rel=1e-12)
    # Hertz contact area pi a b, staircase of the edge O(dx/a)
    assert result.contact_area == pytest.approx(math.pi * float(contact.a * contact.b), rel=2e-2)
    assert result.max_pressure >= result.central_pressure


def test_error_halves_or_better_with_each_refinement():
    geometry = GEOMETRIES["groove 0.56"]
    errors = [_errors(*_solve_hertz(geometry, n)) for n in (32, 64, 128)]
    for quantity in ("p0", "a", "b", "delta"):
        values = [abs(e[quantity]) for e in errors]
        assert values[1] <= values[0] / 2 and values[2] <= values[1] / 2, (quantity, values)


def test_rotated_gap_gives_the_rotated_ellipse():
    geometry = GEOMETRIES["groove 0.60"]
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), float(contact.a), 192)
    for angle_deg in (0.0, 7.5, 30.0, -50.0):
        gap = hs.quadratic_gap(grid, geometry.A, geometry.B, math.radians(angle_deg))
        result = hs.solve(gap, grid, geometry.contact_modulus, force=LOAD)
        assert math.degrees(result.ellipse_angle) == pytest.approx(angle_deg, abs=0.01)
        assert result.semi_axis_a == pytest.approx(float(contact.a), rel=5e-3)
        assert result.semi_axis_b == pytest.approx(float(contact.b), rel=5e-3)


def test_approach_control_agrees_with_load_control():
    geometry = GEOMETRIES["groove 0.56"]
    contact, by_load = _solve_hertz(geometry, 96)
    by_approach = hs.solve(hs.quadratic_gap(by_load.grid, geometry.A, geometry.B), by_load.grid,
                           geometry.contact_modulus, approach=by_load.approach)
    assert by_approach.force == pytest.approx(LOAD, rel=1e-6)
    assert np.max(np.abs(by_approach.pressure - by_load.pressure)) < 1e-5 * by_load.max_pressure


def test_complementarity_of_the_solution():
    geometry = GEOMETRIES["ball on flat"]
    _, result = _solve_hertz(geometry, 64, tolerance=1e-12)
    assert np.all(result.pressure >= 0.0) and np.all(result.separation >= 0.0)
    in_contact = result.pressure > 0
    loaded_gap = hs.quadratic_gap(result.grid, geometry.A, geometry.B) + result.deformation - result.approach
    assert np.max(np.abs(loaded_gap[in_contact])) < 1e-9 * result.approach
    assert np.min(loaded_gap[~in_contact]) > -1e-9 * result.approach


def test_bad_input_and_non_convergence():
    geometry = GEOMETRIES["ball on flat"]
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), n=32)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    with pytest.raises(ValueError, match="exactly one"):
        hs.solve(gap, grid, geometry.contact_modulus)
    with pytest.raises(ValueError, match="force"):
        hs.solve(gap, grid, geometry.contact_modulus, force=-1.0)
    with pytest.raises(ValueError, match="contact_modulus"):
        hs.solve(gap, grid, float("nan"), force=LOAD)
    with pytest.raises(ValueError, match="gap"):
        hs.solve(gap[:-1], grid, geometry.contact_modulus, force=LOAD)
    with pytest.raises(ValueError, match="gap must be finite"):
        hs.solve(np.full_like(gap, np.nan), grid, geometry.contact_modulus, force=LOAD)
    with pytest.raises(ValueError, match="edge of the grid"):
        hs.solve(gap, grid, geometry.contact_modulus, force=20 * LOAD)
    with pytest.raises(ValueError, match="margin"):
        hs.hertz_surface_grid(1e-4, margin=0.9)
    with pytest.raises(ValueError, match="nx"):
        hs.surface_grid(1e-4, nx=2)
    with pytest.raises(ConvergenceError) as caught:
        hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, max_iterations=2)
    assert caught.value.residual > 0


def test_rough_height_map_route():
    # sun2021 eq 9: gap = c_g + c_r with a fractal raceway (lowmodel.contact.ehl); rough contact is patchy,
    # carries the same load on less area at higher peak pressure, and keeps complementarity
    from ballbench.lowmodel.contact import ehl

    geometry = GEOMETRIES["ball on flat"]
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), n=96, margin=1.5)
    X, Y = grid.coordinates()
    roughness = ehl.weierstrass_mandelbrot_surface(X, Y, 2.47, 1e-10, 4 * float(contact.a),
                                                   cutoff_length=2 * grid.dx, seed=1)
    assert 0.02 * float(contact.delta) < np.ptp(roughness) < float(contact.delta)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B) + roughness
    result = hs.solve(gap - gap.min(), grid, geometry.contact_modulus, force=LOAD, tolerance=1e-10)
    assert result.force == pytest.approx(LOAD, rel=1e-12)
    smooth = hs.solve(hs.quadratic_gap(grid, geometry.A, geometry.B), grid, geometry.contact_modulus, force=LOAD)
    assert result.contact_area < smooth.contact_area
    assert result.max_pressure > smooth.max_pressure
    loaded = gap - gap.min() + result.deformation - result.approach
    in_contact = result.pressure > 0
    assert np.max(np.abs(loaded[in_contact])) < 1e-7 * float(contact.delta)
    assert np.min(loaded[~in_contact]) > -1e-7 * float(contact.delta)


def _full_grid_only(monkeypatch):
    # the reference: the same solver without the coarse-grid box and start (every grid is "small")
    monkeypatch.setattr(hs, "_BOX_MIN_CELLS", 10**9)


def test_box_solve_equals_the_full_grid_solve(monkeypatch):
    # the CG on the box around the coarse grid's contact is the same problem: same pressure as the full grid
    geometry = GEOMETRIES["groove 0.56"]
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), float(contact.b), 160, margin=1.6)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    boxed = hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, tolerance=1e-12)
    box, start = hs._coarse_start(gap, grid, geometry.contact_modulus, LOAD, None, 1e-12, None)
    assert box != hs._FULL and start is not None  # the box path is the one tested
    _full_grid_only(monkeypatch)
    full = hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, tolerance=1e-12)
    assert np.max(np.abs(boxed.pressure - full.pressure)) < 1e-8 * full.max_pressure
    assert boxed.approach == pytest.approx(full.approach, rel=1e-10)


def test_contact_outside_the_coarse_box_is_found(monkeypatch):
    # an asperity of one fine cell that the coarse grid (every 4th cell) does not see, far from the main contact:
    # the box misses it, the check on the full grid finds the interpenetration and the full grid takes over
    geometry = GEOMETRIES["ball on flat"]
    contact = hertz.solve_load(geometry, LOAD)
    grid = hs.hertz_surface_grid(float(contact.a), n=160, margin=2.0)
    gap = hs.quadratic_gap(grid, geometry.A, geometry.B)
    gap[6, 7] = 0.0  # index 6, 7: not on the coarse lattice 1, 5, 9, ...
    box, _ = hs._coarse_start(gap, grid, geometry.contact_modulus, LOAD, None, 1e-10, None)
    assert box != hs._FULL and not (box[0].start <= 6 < box[0].stop and box[1].start <= 7 < box[1].stop)
    result = hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, tolerance=1e-10)
    assert result.pressure[6, 7] > 0.0
    loaded = gap + result.deformation - result.approach
    assert np.min(loaded[result.pressure == 0]) > -1e-7 * result.approach
    _full_grid_only(monkeypatch)
    full = hs.solve(gap, grid, geometry.contact_modulus, force=LOAD, tolerance=1e-10)
    assert np.max(np.abs(result.pressure - full.pressure)) < 1e-5 * full.max_pressure


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_surface_grid_refuses_nonsense_cells():
    for nx in (2, True, 8.0):  # 2 failed later naming nx in asperity_contact; 8.0 was accepted
        with pytest.raises(ValueError, match="nx"):
            hs.SurfaceGrid(nx, 8, 1e-6, 1e-6)
    with pytest.raises(ValueError, match="dx"):
        hs.SurfaceGrid(8, 8, 0.0, 1e-6)
    with pytest.raises(ValueError, match="nx"):
        hs.surface_grid(1e-3, nx=8.0)
    with pytest.raises(ValueError, match="half_width_x"):  # the cell size underflowed to 0
        hs.surface_grid(5e-324, nx=4)
    with pytest.raises(ValueError, match="margin"):  # was ZeroDivisionError
        hs.hertz_surface_grid(5e-324, n=4, square_cells=True)


@pytest.mark.filterwarnings("error")
def test_halfspace_float_range():
    grid = hs.surface_grid(2e-4, 2e-4, 16, 16)
    with pytest.raises(ValueError, match="contact_modulus"):  # was inf with a RuntimeWarning
        hs.deformation(np.full((16, 16), 1e9), grid, 5e-324)
    gap = hs.quadratic_gap(grid, 1e300, 5e3)
    with pytest.raises(ValueError, match="gap"):  # overflowed the float32 CG increments (RuntimeWarning)
        hs.solve(gap, grid, 1e11, force=1.0)
    with pytest.raises(ValueError, match="force"):
        hs.solve(hs.quadratic_gap(grid, 5e3, 5e3), grid, 5e-324, force=1.0)
    with pytest.raises(ValueError, match="A = "):
        hs.quadratic_gap(hs.surface_grid(1e200, 1e200, 4, 4), 1e300, 1.0)


@pytest.mark.filterwarnings("error")
def test_influence_coefficients_of_a_subnormal_cell():
    with pytest.raises(ValueError, match="dx"):  # dy / dx = inf: 0 * inf in the kernel (RuntimeWarning)
        hs.influence_coefficients(8, 8, 5e-324, 1e-3)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


# lengths [m] and counts: the documented range, a little beyond (zero, negative, huge, tiny) and a bool
length = st.one_of(positive(1e-9, 1.0), st.sampled_from([0.0, -1e-3, 1e300, 5e-324]))


cells = st.one_of(st.integers(-1, 64), st.just(True))


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
