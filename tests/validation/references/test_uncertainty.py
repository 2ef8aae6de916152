"""Eca and Hoekstra's least-squares uncertainty (validation/references/uncertainty.py) on studies whose answer is known
by hand or from a published table, never through a model."""
import math

import pytest

from ballbench.validation.references.richardson import extrapolate
from ballbench.validation.references.uncertainty import SAFETY_TRUSTED, SAFETY_UNTRUSTED, eca_hoekstra

# the contact study of a 1/8-inch ball in a groove of conformity 0.52 at 500 N (ballbench init linear-guide,
# --quick): three FE levels n = b/h 5.5, 6.6, 7.92 whose semi-axis a agrees within 0.2 %
CONTACT_N = (5.5, 6.6, 7.92)
CONTACT_A_UM = (771.3, 771.4, 772.4)
CONTACT_P0_MPA = (3634.08, 3632.17, 3624.49)


def test_celik_2008_table_1_three_meshes_in_the_asymptotic_range():
    # Celik et al. 2008, J. Fluids Eng. 130, 078001, Table 1, phi = the dimensionless reattachment length on
    # N = 4500, 8000, 18000 cells (2D: r_32 = 1.333, r_21 = 1.5): p = 1.53, phi_ext^21 = 6.1685, GCI_fine^21 = 2.17 %.
    # Monotone, 0.5 <= p < 2: the least-squares fit through three points is Richardson's, F_s = 1.25, sigma = 0,
    # and U of the finest mesh is Roache's GCI
    sizes = [(1 / 4500) ** 0.5, (1 / 8000) ** 0.5, (1 / 18000) ** 0.5]
    u = eca_hoekstra(sizes, [5.863, 5.972, 6.063])
    assert u.order == pytest.approx(1.53, abs=0.01)
    assert u.extrapolated == pytest.approx(6.1685, abs=2e-3)
    assert u.relative_uncertainty == pytest.approx(0.0217, abs=5e-5)
    assert u.safety == SAFETY_TRUSTED and u.sigma == pytest.approx(0.0, abs=1e-12) and u.fit == "phi_0 + alpha h^p"
    assert u.value == 6.063


def test_an_exact_power_law_on_four_meshes_by_hand():
    # phi = 2 + 0.5 h^1.5 on h = 1, 0.8, 0.64, 0.512: the fit recovers p = 1.5 and phi_0 = 2, sigma = 0, so
    # U = 1.25 eps = 1.25 * 0.5 * 0.512^1.5 (eq 20)
    sizes = [1.0, 0.8, 0.64, 0.512]
    values = [2.0 + 0.5 * h ** 1.5 for h in sizes]
    u = eca_hoekstra(sizes, values)
    assert u.order == pytest.approx(1.5, rel=1e-6) and u.extrapolated == pytest.approx(2.0, abs=1e-9)
    assert u.sigma < 1e-9 and u.safety == SAFETY_TRUSTED
    assert u.uncertainty == pytest.approx(1.25 * 0.5 * 0.512 ** 1.5, rel=1e-6)
    assert u.data_range == pytest.approx((values[0] - values[-1]) / 3)


def test_a_power_law_with_noise_on_six_meshes_covers_the_exact_value():
    # phi = 2 + 0.5 h^1.5 + 0.001 (-1)^k on h = 0.8^k, k = 0..5: the exact value is 2, the finest mesh is off by
    # 0.5 * 0.8^7.5 - 0.001 = 0.09279; the fit recovers p and phi_0 within the noise, sigma is of the noise's size
    # (amplitude 0.001, three fitted parameters on six points), and U covers the true error without tripling it
    sizes = [0.8 ** k for k in range(6)]
    values = [2.0 + 0.5 * h ** 1.5 + 1e-3 * (-1) ** k for k, h in enumerate(sizes)]
    u = eca_hoekstra(sizes, values)
    true_error = abs(values[-1] - 2.0)
    assert true_error == pytest.approx(0.5 * 0.8 ** 7.5 - 1e-3)
    assert u.order == pytest.approx(1.5, abs=0.05) and u.extrapolated == pytest.approx(2.0, abs=1e-3)
    assert 5e-4 < u.sigma < 2e-3 and u.safety == SAFETY_TRUSTED
    assert true_error <= u.uncertainty <= 1.25 * true_error + 2 * u.sigma + 2e-3


def test_three_levels_with_an_untrusted_order_take_the_formal_order_fit_by_hand():
    # phi = 0, 1, 3 on h = 1, 1/2, 1/4 (increments growing: p < 0.5): the formal-order fit phi_0 + alpha h^2.
    # Unweighted through x = h^2 = 1, 0.25, 0.0625: mean x = 0.4375, mean phi = 4/3, Sxx = 0.4921875,
    # Sxy = sum (x - 0.4375)(phi - 4/3) = 0.5625 (-4/3) - 0.1875 (-1/3) - 0.375 (5/3) = -1.3125, c1 = -2.666667,
    # c0 = 4/3 + 2.666667 * 0.4375 = 2.5; residuals phi - fit = 0.166667, -0.833333, 0.666667: sigma (1 dof) =
    # sqrt(3 * (1/3) * (0.027778 + 0.694444 + 0.444444)) = 1.080123.  Weighted (w ~ 1/h = 1, 2, 4: fit 2.8 - 3.2 x,
    # residuals 0.4, -1, 0.4, sigma = sqrt(3 (0.16 + 2 + 0.64) / 7) = 1.095445) it is larger: the unweighted fit is
    # kept.  eps = |fit(h_3) - c0| = 0.166667, the finest residual 0.666667; sigma < Delta_phi = 1.5: eq 20 with F_s 3,
    # U = 3 * 0.166667 + 1.080123 + 0.666667 = 2.246790.  The choice of delta_1 by its sigma would extrapolate the
    # growing increments linearly instead
    u = eca_hoekstra([1.0, 0.5, 0.25], [0.0, 1.0, 3.0])
    assert u.fit == "phi_0 + alpha h^2" and not u.weighted and u.safety == SAFETY_UNTRUSTED and u.order < 0.5
    assert u.extrapolated == pytest.approx(2.5) and u.sigma == pytest.approx(1.080123, abs=1e-6)
    assert u.error == pytest.approx(1 / 6) and u.uncertainty == pytest.approx(2.246790, abs=1e-6)


def test_a_high_observed_order_falls_back_to_the_fixed_order_fits_by_hand():
    # phi = 1, 0.1, 0.01 on h = 1, 1/2, 1/4 (coarse to fine, increments shrinking tenfold: p = log2(10) = 3.3, above
    # the formal order 2): the fixed-order fits decide.  phi = c0 + c1 h^2 by unweighted least squares through
    # x = h^2 = 1, 0.25, 0.0625 and phi = 1, 0.1, 0.01: mean x = 0.4375, mean phi = 0.37, Sxx = 0.4921875,
    # Sxy = 0.54; c1 = 1.097143, c0 = 0.37 - 0.48 = -0.11; eps = c1 x_3 = 0.068571; fit(x_3) = -0.041429, so the
    # residual of the finest mesh is 0.051429; residuals 0.012857, -0.064286, 0.051429 with 1 degree of freedom:
    # sigma = sqrt(0.0069429) = 0.083324 < Delta_phi = 0.495, F_s = 3 (p outside [0.5, 2.1)):
    # U = 3 eps + sigma + residual = 0.205714 + 0.083324 + 0.051429 = 0.340467 (eq 20)
    u = eca_hoekstra([1.0, 0.5, 0.25], [1.0, 0.1, 0.01])
    assert u.order == pytest.approx(math.log2(10.0), rel=1e-3)
    assert u.fit == "phi_0 + alpha h^2" and not u.weighted and u.safety == SAFETY_UNTRUSTED
    assert u.data_range == pytest.approx(0.495)
    assert u.extrapolated == pytest.approx(-0.11, abs=1e-6)
    assert u.error == pytest.approx(0.068571, abs=1e-6) and u.sigma == pytest.approx(0.083324, abs=1e-6)
    assert u.uncertainty == pytest.approx(0.340467, abs=1e-6)


def test_the_contact_study_that_agrees_within_0_2_percent_is_conclusive():
    # the GCI with the observed orders (12.6 from a, 17 / 8.6 / 9.3 for the study's other quantities) trusts none of
    # them and puts a at 0.88 % and the study's worst quantity at 1.2 % against the 1 % bound; the levels agree
    # within 0.2 %: Eca-Hoekstra's fixed-order fit bounds a at about 0.5 %
    sizes = [1.0 / n for n in CONTACT_N]
    for values in (CONTACT_A_UM, CONTACT_A_UM[::-1]):
        u = eca_hoekstra(sizes, values)
        spread = (max(values) - min(values)) / values[-1]
        assert u.relative_uncertainty < 0.01, (values, u)
        assert u.relative_uncertainty < 4 * spread
        assert u.safety == SAFETY_UNTRUSTED  # the erratic order is not trusted ...
        assert u.fit != "phi_0 + alpha h^p"  # ... and does not set the estimate
    assert extrapolate(sizes, CONTACT_A_UM).note.endswith("F_s 3")
    # the same study's p0 [MPa] (levels.csv of that run), its worst quantity: spread 0.27 %, increments growing
    u = eca_hoekstra(sizes, CONTACT_P0_MPA)
    assert u.order < 0.5 and u.fit == "phi_0 + alpha h^2" and u.relative_uncertainty < 0.01


def test_levels_that_scatter_by_tens_of_percent_stay_uncertain():
    # FE-informed B2B forces 0.633, 1.104, 0.971 N on three module levels (h = b/n, n = 1.25, 1.5625, 1.95):
    # oscillating, the fixed-order fits with F_s 3; far above the 5 % bound of the B2B reference
    u = eca_hoekstra([1 / 1.25, 1 / 1.5625, 1 / 1.95], [0.633, 1.104, 0.971])
    assert math.isnan(u.order) and u.safety == SAFETY_UNTRUSTED
    assert u.relative_uncertainty > 0.2


def test_identical_levels_have_no_uncertainty():
    u = eca_hoekstra([3.0, 2.0, 1.0], [5.0, 5.0, 5.0])
    assert u.uncertainty == 0.0 and u.relative_uncertainty == 0.0 and u.value == 5.0


def test_sigma_above_the_data_range_takes_eq_21():
    # five levels scattered about a flat mean with one small step: the fits' standard deviation exceeds the data
    # range (max - min) / (n - 1), eq 21 multiplies by 3 sigma / Delta_phi
    sizes = [1.0, 0.9, 0.8, 0.7, 0.6]
    values = [1.0, 1.08, 0.92, 1.07, 0.95]
    u = eca_hoekstra(sizes, values)
    assert u.sigma >= u.data_range and u.safety == SAFETY_UNTRUSTED
    assert u.uncertainty > 3 * u.sigma


@pytest.mark.parametrize("sizes, values, match", [
    ([1.0, 0.5], [1.0, 2.0], ">= 3 meshes"),
    ([1.0, 1.0, 0.5], [1.0, 2.0, 3.0], "decrease"),
    ([1.0, 0.5, 0.25], [1.0, math.nan, 3.0], "finite"),
])
def test_bad_studies_are_refused(sizes, values, match):
    with pytest.raises(ValueError, match=match):
        eca_hoekstra(sizes, values)
