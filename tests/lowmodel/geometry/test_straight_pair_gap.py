"""groove.straight_pair_initial_gap: the exact gap of a ball against a flat, a ball and a straight groove tends to
Hertz's quadratic A x^2 + B y^2 with the curvatures of straight_groove_curvatures near the touching point."""
import pytest

from ballbench.lowmodel.geometry import groove

R = 5e-3


@pytest.mark.parametrize("pair, conformity, a_coef, b_coef", [
    ("flat", None, 1 / (2 * R), 1 / (2 * R)),
    ("ball", None, 1 / R, 1 / R),
    ("groove", 0.52, 1 / (2 * R) - 1 / (2 * 2 * 0.52 * R), 1 / (2 * R)),  # x across the groove of radius 2 f R
])
def test_small_offsets_give_hertz_quadratic(pair, conformity, a_coef, b_coef):
    gap = groove.straight_pair_initial_gap(R, pair, conformity)
    x = 1e-6
    assert gap(x, 0.0) == pytest.approx(a_coef * x * x, rel=1e-6)
    assert gap(0.0, x) == pytest.approx(b_coef * x * x, rel=1e-6)
    assert gap(0.0, 0.0) == 0.0


def test_bad_pair_is_named():
    with pytest.raises(ValueError, match="pair"):
        groove.straight_pair_initial_gap(R, "nut")
