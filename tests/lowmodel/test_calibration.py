"""lowmodel.calibration: fits with intervals, the contact law, the calibration file (``ballbench calibrate``'s spec and
CSV input: tests/validation/studies/test_calibrate.py)."""
import json
import math

import numpy as np
import pytest

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel import calibration
from ballbench.lowmodel.errors import ConvergenceError
from hypothesis import given, strategies as st
from pathlib import Path
from tests.property_support import SETTINGS, call, positive, real
import tempfile


def test_linear_fit_matches_ordinary_least_squares():
    # independent reference: OLS covariance s^2 (X^T X)^-1 by normal equations
    rng = np.random.default_rng(5)
    force = np.linspace(20.0, 200.0, 15)
    x = np.column_stack([force ** (2 / 3), force])
    y = x @ [1.3e-7, 3e-11] + rng.normal(0, 3e-9, force.size)
    law = cal.fit_contact_law(force, y)
    beta = np.linalg.solve(x.T @ x, x.T @ y)
    s2 = np.sum((y - x @ beta) ** 2) / (force.size - 2)
    se = np.sqrt(np.diag(s2 * np.linalg.inv(x.T @ x)))
    assert law.hertz_constant.value == pytest.approx(beta[0], rel=1e-9)
    assert law.bulk_compliance.value == pytest.approx(beta[1], rel=1e-6, abs=1e-9 * abs(beta[1]))
    assert law.hertz_constant.std_error == pytest.approx(se[0], rel=1e-6)
    assert law.bulk_compliance.std_error == pytest.approx(se[1], rel=1e-6)
    from scipy import stats

    half = stats.t.ppf(0.975, force.size - 2) * se[0]
    assert law.hertz_constant.ci_high - law.hertz_constant.value == pytest.approx(half, rel=1e-6)


def test_exact_data_recover_hertz():
    geometry = hertz.ball_in_groove(5e-3, 0.56)
    force = np.linspace(50, 150, 5)
    contact = hertz.solve_load(geometry, force)
    law = cal.fit_contact_law(force, contact.delta * (1 + 1e-12 * np.sin(force)), semi_axes=contact.a,
                              ball_radius=5e-3)
    assert law.hertz_constant.value == pytest.approx(hertz.hertz_constant(geometry), rel=1e-9)
    assert abs(law.bulk_compliance.value) < 1e-9 * hertz.hertz_constant(geometry)
    assert law.psi.value == pytest.approx(hertz.psi_constant(geometry, 5e-3), rel=1e-12)


def test_too_few_points_and_bad_input():
    with pytest.raises(ValueError, match=">= 3 distinct loads"):
        cal.fit_contact_law([1.0, 2.0], [1e-6, 2e-6])
    with pytest.raises(ValueError, match="forces must be finite and > 0 N"):
        cal.fit_contact_law([0.0, 1.0, 2.0], [1e-6, 1e-6, 2e-6])
    with pytest.raises(ValueError, match="ball_radius"):
        cal.fit_contact_law([1.0, 2.0, 3.0], [1e-6, 1.5e-6, 2e-6], semi_axes=[1e-4, 1.2e-4, 1.3e-4])
    with pytest.raises(ValueError, match="two distinct speeds"):
        cal.fit_friction_coefficient([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="confidence"):
        cal.fit_friction_coefficient([1.0, 2.0, 3.0], [0.1, 0.2, 0.3], confidence=95)


def test_calibration_file_round_trip_and_errors(tmp_path):
    constant = cal.Constant(1.0, 0.1, 0.8, 1.2, "1", "test", 0.95, 5, 0.01, 0.9)
    path = cal.save(cal.Calibration({"g": {"x": constant}}, ("note",)), tmp_path / "c.json")
    loaded = cal.load(path)
    assert loaded.get("g", "x") == constant and loaded.notes == ("note",)
    with pytest.raises(KeyError, match="no group 'h'"):
        loaded.get("h", "x")
    document = json.loads(path.read_text())
    document["version"] = 99
    (tmp_path / "v.json").write_text(json.dumps(document))
    with pytest.raises(ValueError, match="version 99"):
        cal.load(tmp_path / "v.json")
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ValueError, match="invalid JSON"):
        cal.load(tmp_path / "bad.json")
    with pytest.raises(ValueError, match="does not exist"):
        cal.load(tmp_path / "none.json")


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_fit_errors_name_their_parameters():
    with pytest.raises(ValueError, match="forces"):
        calibration.fit_contact_law([1.0, 1.0, 2.0], [1e-6, 1e-6, 1.6e-6])
    with pytest.raises(ValueError, match="n_points"):
        calibration.fit_least_squares(lambda p: p, [1.0, 2.0, 3.0], n_points=3)
    with pytest.raises(ValueError, match="normal_force"):  # was RuntimeWarning "Mean of empty slice"
        calibration.fit_friction_coefficient([], [])
    with pytest.raises(ValueError, match="x must"):  # was a 0/0 RuntimeWarning
        calibration.fit_line_through_origin([0.0, 0.0, 0.0], [1.0, 2.0, 3.0])


@pytest.mark.filterwarnings("error")
def test_fit_from_a_start_decades_off_is_not_returned_as_the_fit():
    t = np.linspace(0.0, 1.0, 8)

    def residual(p):
        return p[0] - np.exp(t)

    with pytest.raises(ConvergenceError, match="away from a minimum"):  # returned p0 = -3.56e-127 as the fit
        calibration.fit_least_squares(residual, [-3.56e-127], n_points=8)
    fit = calibration.fit_least_squares(residual, [1.0], n_points=8)
    assert fit.params[0] == pytest.approx(np.mean(np.exp(t)), rel=1e-12)


@pytest.mark.filterwarnings("error")
def test_law_force_options():
    with pytest.raises(ValueError, match="max_iterations"):  # was UnboundLocalError
        calibration.law_force([1e-6], 1e-6, 0.0, max_iterations=0)
    with pytest.raises(ValueError, match="max_iterations"):  # True was taken as 1
        calibration.law_force([1e-6], 1e-6, 0.0, max_iterations=True)
    with pytest.raises(ValueError, match="approach"):  # overflow and NaN with RuntimeWarnings
        calibration.law_force([1e300], 1e-9, 1e-6)


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("change", [
    lambda d: d["constants"]["g"].update(C=None),          # was TypeError: 'NoneType' object is not iterable
    lambda d: d["constants"]["g"]["C"].update(value="1"),  # was TypeError in math.isfinite
    lambda d: d["constants"]["g"]["C"].update(unit=5),     # was accepted
    lambda d: d["constants"]["g"]["C"].update(n_points=True),  # was accepted
    lambda d: d.update(version=True),                      # was accepted as version 1
    lambda d: d.update(notes=3),                           # was TypeError: 'int' object is not iterable
    lambda d: d.update(constants=[]),                      # was AttributeError
])
def test_calibration_file_fields_of_the_wrong_type(tmp_path, change):
    import json

    constant = calibration.Constant(2.5e-7, 1e-9, 2.4e-7, 2.6e-7, "m N^-2/3", "fe")
    path = calibration.save(calibration.Calibration({"g": {"C": constant}}), tmp_path / "c.json")
    assert calibration.load(path).constants["g"]["C"] == constant
    document = json.loads(path.read_text())
    change(document)
    path.write_text(json.dumps(document))
    with pytest.raises(ValueError, match="c.json"):
        calibration.load(path)


@pytest.mark.filterwarnings("error")
def test_law_force_of_a_tiny_negative_bulk_compliance():
    force, _ = calibration.law_force([8.5e-4], 5.96e-8, -3.3e-186)  # s* overflowed (RuntimeWarning)
    assert force[0] == pytest.approx((8.5e-4 / 5.96e-8) ** 1.5, rel=1e-12)


@pytest.mark.filterwarnings("error")
def test_fit_friction_coefficient_names_normal_force():
    normal = np.array([1.0, 2.0])
    with pytest.raises(ValueError, match="normal_force"):  # 2 rows for 2 parameters: named n_points, p0
        calibration.fit_friction_coefficient(normal, 0.1 * normal, [0.0, 1.0])
    tiny = np.array([8.6e-210, 1.7e-209, 3.1e-209])
    # the singular value^2 underflowed (a divide by zero, then a ValueError naming normal_force); forces outside
    # 1e-100..1e100 are now fitted divided by a power of two: the mu of the same data in N
    scaled = tiny * 1e209
    friction = np.array([0.1, 0.2, 0.31]) * scaled
    fitted = calibration.fit_friction_coefficient(tiny, friction * 1e-209)["mu"]
    assert fitted.value == pytest.approx(float(scaled @ friction / (scaled @ scaled)), rel=1e-9)  # least squares


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


# lengths [m] and counts: the documented range, a little beyond (zero, negative, huge, tiny) and a bool
length = st.one_of(positive(1e-9, 1.0), st.sampled_from([0.0, -1e-3, 1e300, 5e-324]))


forces_list = st.lists(st.one_of(real(-1.0, 1e4), st.just(0.0)), min_size=0, max_size=8)


json_value = st.recursive(st.one_of(st.none(), st.booleans(), st.integers(-5, 5), st.floats(), st.text(max_size=3)),
                          lambda inner: st.one_of(st.lists(inner, max_size=2),
                                                  st.dictionaries(st.text(max_size=3), inner, max_size=2)),
                          max_leaves=4)


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
def _no_warning(function, *args, **kwargs):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return function(*args, **kwargs)


def test_non_finite_residual_is_named_not_scipy_text():
    # was scipy's "Residuals are not finite in the initial point."
    with pytest.raises(ValueError, match=r"residual returns nan at index 1 of 3 at p0"):
        _no_warning(cal.fit_least_squares, lambda p: np.array([p[0] - 1.0, np.nan, p[0]]), [1.0], n_points=3)
    with pytest.raises(ValueError, match="sum of squares overflows"):  # was an OverflowWarning-free scipy failure
        _no_warning(cal.fit_least_squares, lambda p: 1e200 * np.array([p[0] - 1.0, p[0] - 2.0]), [2.0], n_points=2)

    # NaN only on the way to the minimum: the trust region steps around it, the fit stops short and says why
    def residual(p):
        return np.array([p[0] - 1.0, p[0] - 1.2, np.nan if p[0] < 1.15 else 0.0])

    with pytest.raises(cal.ConvergenceError, match="NaN or inf at p") as caught:
        _no_warning(cal.fit_least_squares, residual, [2.0], n_points=3)
    assert caught.value.reason.startswith("not stationary")


def test_friction_fit_of_forces_near_the_float_limit():
    # forces of 1e300 N: the sum of squares overflowed and the ConvergenceError carried scipy's own message; the
    # fit of f = mu F does not depend on the force unit, so 1e300 N gives the mu of the same data in N
    normal = np.array([1.0, 2.0, 3.0, 4.0])
    friction = np.array([0.1, 0.2, 0.31, 0.4])
    plain = cal.fit_friction_coefficient(normal, friction)["mu"]
    huge = _no_warning(cal.fit_friction_coefficient, 1e300 * normal, 1e300 * friction)["mu"]
    assert huge.value == pytest.approx(plain.value, rel=1e-12)
    assert huge.std_error == pytest.approx(plain.std_error, rel=1e-9)
    assert huge.rms_residual == pytest.approx(1e300 * plain.rms_residual, rel=1e-9)
    k = _no_warning(cal.fit_line_through_origin, 1e300 * normal, -1e300 * friction)
    assert k.value == pytest.approx(cal.fit_line_through_origin(normal, -friction).value, rel=1e-12)


def test_speed_fit_with_speeds_that_determine_no_slope():
    # speeds [0, 1e-300, ...] m/s: warned of overflow and returned mu_v = -4.8e296 s/m with an infinite covariance
    normal, friction = [1.0, 2.0, 3.0, 4.0], [0.1, 0.2, 0.31, 0.4]
    for speeds in ([0.0, 1e-300, 2e-300, 3e-300], [0.0, 0.0, 0.0, 1e-300]):
        with pytest.raises(ValueError, match="speed"):
            _no_warning(cal.fit_friction_coefficient, normal, friction, speeds)
    with pytest.raises(ValueError, match="x, y"):  # a slope below the float range (was 0 +- 0)
        _no_warning(cal.fit_line_through_origin, [1e300, 2e300, 3e300], [-1e-300, -2e-300, -3.1e-300])


@pytest.mark.parametrize("x, y", [([1e-200, 2e-200, 3e-200], [1.0, 2.1, 2.9]),
                                  ([1.0, 2.0, 3.0], [1e200, 2.1e200, 2.9e200]),
                                  ([1e-200, 1.0, 3e-200], [1e200, 2.1e200, 2.9e200])])
def test_a_slope_whose_variance_leaves_the_float_range_is_named(x, y):
    # x near 1e-200 against y near 1 raised a bare OverflowError (the Python float to_si**2): the slope's
    # variance (1e396 and beyond) is outside the float range, which the error says, naming x and y
    with pytest.raises(ValueError, match="x, y: the slope y / x .* or its variance is beyond the float range"):
        _no_warning(cal.fit_line_through_origin, x, y)
