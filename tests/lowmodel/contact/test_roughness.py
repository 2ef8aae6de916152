"""WM raceway roughness (lowmodel.contact.roughness) against the WM closed forms (rms, line spectrum)."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ehl, halfspace, roughness
from ballbench.lowmodel.contact import halfspace as hs
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, call, positive, real

D, G, L, LS = 2.47, 0.41e-9, 554e-6, 20e-6


def line_amplitudes(fractal_dimension, seed=0):
    """Amplitudes of the profile along x (the ridge m = M) at the WM frequencies, Hann-windowed DFT."""
    frequency, _ = roughness.wm_line_spectrum(fractal_dimension, G, L, LS)
    x = np.arange(0.0, 200 * L, LS / 8)
    z = ehl.weierstrass_mandelbrot_surface(x, np.zeros_like(x), fractal_dimension, G, L, cutoff_length=LS,
                                           seed=seed)
    window = np.hanning(x.size)
    return np.array([2.0 * abs(np.sum(window * (z - z.mean()) * np.exp(-2j * math.pi * f * x))) / window.sum()
                     for f in frequency])


def fitted_dimension(amplitudes, gamma=1.5):
    slope = np.polyfit(np.arange(amplitudes.size) * math.log(gamma), np.log(amplitudes), 1)[0]
    return 3.0 + slope  # amplitude ~ gamma^((D - 3) n)


@pytest.mark.parametrize("fractal_dimension", [2.47, 2.3])
def test_line_spectrum_matches_closed_form_and_rejects_a_wrong_dimension(fractal_dimension):
    measured = line_amplitudes(fractal_dimension)
    _, expected = roughness.wm_line_spectrum(fractal_dimension, G, L, LS)
    assert np.allclose(measured, expected, rtol=0.03)
    assert fitted_dimension(measured) == pytest.approx(fractal_dimension, abs=0.01)
    # a surface of another dimension is told apart: its fitted D misses by far more than 0.01
    other = 2.47 if fractal_dimension != 2.47 else 2.6
    _, wrong = roughness.wm_line_spectrum(other, G, L, LS)
    assert not np.allclose(measured, wrong, rtol=0.03)


def test_rms_matches_closed_form_over_seeds():
    grid = halfspace.surface_grid(L / 2, L / 2, 128, 128)
    samples = [roughness.raceway_roughness(grid, D, G, seed=s) for s in range(12)]
    ensemble = math.sqrt(np.mean([np.mean(r.heights**2) for r in samples]))
    assert samples[0].rms == pytest.approx(roughness.wm_rms(D, G, L, 2 * grid.dx))
    # one sample of the domain size holds only a few of the longest waves: 12 seeds agree to ~10 %
    assert ensemble == pytest.approx(samples[0].rms, rel=0.12)
    assert abs(float(samples[0].heights.mean())) < 1e-18


def test_rms_closed_form_limits():
    # a single level (L_s just below L / gamma^0): sigma = C sqrt(M / 2)
    single = roughness.wm_rms(D, G, L, L / 1.2)
    assert single == pytest.approx(roughness.wm_amplitude(D, G, L) * math.sqrt(10 / 2), rel=1e-12)
    # sigma ~ G^(D-2)
    assert roughness.wm_rms(D, 2 * G, L, LS) / roughness.wm_rms(D, G, L, LS) == pytest.approx(2**0.47, rel=1e-12)
    # 0.41 nm over the sun2021 domain: a few tenths of a micron (docs/mixed_lubrication.md)
    assert 0.3e-6 < roughness.wm_rms(D, G, L, LS) < 0.8e-6


@pytest.mark.parametrize("kwargs, match", [
    (dict(fractal_dimension=3.0), "fractal_dimension"),
    (dict(roughness_scale=-1.0), "roughness_scale"),
    (dict(cutoff_length=1e-3), "cutoff_length"),
    (dict(gamma=1.0), "gamma"),
])
def test_bad_inputs(kwargs, match):
    args = dict(fractal_dimension=D, roughness_scale=G, sample_length=L, cutoff_length=LS)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        roughness.wm_rms(**args)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_wm_amplitude_names_sample_length():
    with pytest.raises(ValueError, match="sample_length"):  # named cutoff_length, not a parameter
        roughness.wm_amplitude(2.5, 0.55, 5e-324)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


# lengths [m] and counts: the documented range, a little beyond (zero, negative, huge, tiny) and a bool
length = st.one_of(positive(1e-9, 1.0), st.sampled_from([0.0, -1e-3, 1e300, 5e-324]))


small_cells = st.one_of(st.integers(1, 24), st.sampled_from([0, -2, True]))


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
