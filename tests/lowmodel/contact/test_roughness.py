"""WM raceway roughness (lowmodel.contact.roughness) against the WM closed forms (rms, line spectrum)."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ehl, halfspace, roughness

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
