"""Richardson extrapolation (validation/references/richardson.py) on sequences whose limit is known by
construction: f(h) = f0 + C h^p (+ a higher-order term), never through a model."""
import pytest

from ballbench.validation.references.richardson import extrapolate


@pytest.mark.parametrize("ratio", [1.25, 1.5, 2.0])
@pytest.mark.parametrize("order", [1.0, 2.0, 3.0])
def test_exact_power_law_gives_its_limit_and_order(ratio, order):
    sizes = [1.0, 1.0 / ratio, 1.0 / ratio**2]
    values = [7.0 + 0.3 * h**order for h in sizes]
    e = extrapolate(sizes, values)
    assert e.observed
    assert e.order == pytest.approx(order, rel=1e-9)
    assert e.value == pytest.approx(7.0, rel=1e-12)
    assert e.uncertainty > 0 and e.finest == values[-1]


def test_varying_refinement_ratios():  # Celik et al. 2008 fixed point for r21 != r32
    sizes = [1.0, 0.8, 0.5]
    values = [2.0 - 0.4 * h**2 for h in sizes]
    e = extrapolate(sizes, values)
    assert e.order == pytest.approx(2.0, rel=1e-9) and e.value == pytest.approx(2.0, rel=1e-12)


def test_uncertainty_covers_the_limit_with_a_higher_order_term():
    sizes = [1.0, 0.8, 0.64]
    values = [1.0 + 0.05 * h**2 + 0.02 * h**3 for h in sizes]
    e = extrapolate(sizes, values)
    assert abs(e.value - 1.0) <= e.uncertainty
    assert e.relative_uncertainty < 0.05


def test_oscillating_sequence_falls_back_to_the_formal_order_with_safety_3():
    e = extrapolate([1.0, 0.8, 0.64], [1.02, 0.99, 1.005])
    assert not e.observed and "oscillating" in e.note and e.order == 2.0


def test_two_meshes_use_the_formal_order():
    e = extrapolate([1.0, 0.5], [1.3, 1.075])
    assert e.value == pytest.approx(1.0, rel=1e-12) and not e.observed


@pytest.mark.parametrize("sizes, values", [([1.0], [1.0]), ([1.0, 1.0], [1.0, 2.0]), ([1.0, 0.5], [1.0, float("nan")])])
def test_bad_input_is_refused(sizes, values):
    with pytest.raises(ValueError):
        extrapolate(sizes, values)
