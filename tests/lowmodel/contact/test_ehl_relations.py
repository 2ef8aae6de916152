"""Closed-form EHL relations of sun2021 (eqs 16, 17, 23), Hamrock-Dowson film, Weierstrass-Mandelbrot surface."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ehl


def test_roelands_limits_and_slope():
    eta0 = 0.05  # Pa s, sun2021 Table 1
    assert ehl.roelands_viscosity(0.0, eta0) == pytest.approx(eta0, rel=1e-15)
    alpha = ehl.roelands_pressure_viscosity_coefficient(eta0)
    # (ln 0.05 + 9.67) 0.68 5.1e-9, by hand: 6.67427 * 3.468e-9
    assert alpha == pytest.approx((math.log(0.05) + 9.67) * 0.68 * 5.1e-9, rel=1e-12)
    assert 2.0e-8 < alpha < 2.5e-8
    dp = 1e3
    slope = math.log(ehl.roelands_viscosity(dp, eta0) / eta0) / dp
    assert slope == pytest.approx(alpha, rel=1e-4)
    # monotone, cavitated pressure taken as ambient
    p = np.linspace(0, 2e9, 50)
    assert np.all(np.diff(ehl.roelands_viscosity(p, eta0)) > 0)
    assert ehl.roelands_viscosity(-1e6, eta0) == pytest.approx(eta0)


def test_dowson_higginson_limits():
    rho0 = 970.0
    assert ehl.dowson_higginson_density(0.0, rho0) == pytest.approx(rho0)
    assert ehl.dowson_higginson_density(1e15, rho0) == pytest.approx(rho0 * (1 + 0.6 / 1.7), rel=1e-5)
    assert ehl.dowson_higginson_density(1e9, rho0) == pytest.approx(rho0 * (1 + 0.6 / 2.7), rel=1e-12)


def test_eyring_newtonian_limit_and_saturation():
    tau_newton = 0.05 * 1e-3 / 1e-6  # eta du / h = 50 Pa << tau0
    assert ehl.eyring_shear_stress(0.05, 1e-3, 1e-6, 5e6) == pytest.approx(tau_newton, rel=1e-9)
    assert ehl.eyring_shear_stress(0.05, -1e-3, 1e-6, 5e6) == pytest.approx(-tau_newton, rel=1e-9)
    high = ehl.eyring_shear_stress(100.0, 1.0, 1e-7, 5e6)
    assert high < 100.0 * 1.0 / 1e-7 and high == pytest.approx(5e6 * math.asinh(1e9 / 5e6))
    with pytest.raises(ValueError, match="film_thickness"):
        ehl.eyring_shear_stress(0.05, 1.0, 0.0, 5e6)


def test_hamrock_dowson_circular_case_by_hand():
    # circular contact, R = 10 mm, E' = 2.2e11 Pa, eta0 = 0.05, alpha = 2e-8, u = 1 m/s, F = 100 N
    film = ehl.hamrock_dowson_film(1.0, 100.0, 0.01, 0.01, 2.2e11, 0.05, 2e-8)
    U, G, W = 0.05 / (2.2e11 * 0.01), 2e-8 * 2.2e11, 100.0 / (2.2e11 * 1e-4)
    k = 1.0339
    assert film["h_c"] == pytest.approx(0.01 * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1 - 0.61 * math.exp(-0.73 * k)))
    assert film["h_min"] < film["h_c"]
    assert 0.1e-6 < film["h_c"] < 2e-6  # sub-micron to micron films of steel EHL
    # h_c ~ u^0.67
    faster = ehl.hamrock_dowson_film(2.0, 100.0, 0.01, 0.01, 2.2e11, 0.05, 2e-8)
    assert faster["h_c"] / film["h_c"] == pytest.approx(2**0.67, rel=1e-12)


def test_weierstrass_mandelbrot_is_seeded_and_scales():
    x, y = np.meshgrid(np.linspace(-1e-4, 1e-4, 33), np.linspace(-1e-4, 1e-4, 33), indexing="ij")
    kwargs = dict(sample_length=5e-4, cutoff_length=1e-6)
    z1 = ehl.weierstrass_mandelbrot_surface(x, y, 2.47, 1e-9, seed=3, **kwargs)
    z2 = ehl.weierstrass_mandelbrot_surface(x, y, 2.47, 1e-9, seed=3, **kwargs)
    z3 = ehl.weierstrass_mandelbrot_surface(x, y, 2.47, 1e-9, seed=4, **kwargs)
    assert np.array_equal(z1, z2) and not np.array_equal(z1, z3)
    assert z1[16, 16] == 0.0  # origin
    # amplitude ~ G^(D-2): doubling G scales z by 2^(D-2)
    z4 = ehl.weierstrass_mandelbrot_surface(x, y, 2.47, 2e-9, seed=3, **kwargs)
    assert np.allclose(z4, z1 * 2**0.47, rtol=1e-12, atol=0)
    with pytest.raises(ValueError, match="fractal_dimension"):
        ehl.weierstrass_mandelbrot_surface(x, y, 3.2, 1e-9, **kwargs)
