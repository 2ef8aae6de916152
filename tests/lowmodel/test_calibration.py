"""Calibration: fits with intervals (lowmodel/calibration.py), CSV input and the spec (validation/calibrate.py)."""
import json
import math

import numpy as np
import pytest

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.validation import calibrate
from tests import paths
from ballbench.lowmodel import calibration
from ballbench.lowmodel.errors import ConvergenceError
from hypothesis import given, strategies as st
from pathlib import Path
from tests.property_support import SETTINGS, call, positive, real
import tempfile

DATA = paths.DATA
FE_CSV = DATA / "fe_groove056_quick.load_approach.csv"


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


def test_intervals_cover_the_truth_in_at_least_90_percent_of_seeds():
    from ballbench.validation.studies.calibration import coverage, synthetic_truth

    shares = coverage(range(100), synthetic_truth())
    assert set(shares) == {"hertz_constant", "bulk_compliance", "psi", "mu", "mu_speed_slope", "k_f"}
    for name, share in shares.items():
        assert share >= 0.90, f"{name}: 95 % interval covers the truth in {100 * share:.0f} % of 100 seeds"


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


def _write(tmp_path, text, name="f.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_friction_csv_units_and_torque(tmp_path):
    path = _write(tmp_path, "# rig 3, 2026-11-20\nnormal_force [kN],friction_torque [N mm],lever_arm [mm],"
                            "speed [mm/s]\n0.1,500,50,10\n0.2,1100,50,20\n")
    data = calibrate.read_friction_csv(path)
    np.testing.assert_allclose(data["normal_force"], [100.0, 200.0])
    np.testing.assert_allclose(data["friction_force"], [10.0, 22.0])  # 0.5 N m / 0.05 m
    np.testing.assert_allclose(data["speed"], [0.01, 0.02])


@pytest.mark.parametrize("text, message", [
    ("normal_force,friction_force [N]\n1,2\n", r"line 1, column 1: header 'normal_force' must be 'name \[unit\]'"),
    ("normal_force [lbf],friction_force [N]\n1,2\n", r"line 1, column 1: unit 'lbf' of 'normal_force'"),
    ("normal_force [N],friction_force [N]\n1,2\n3,x\n", r"line 3, column 2 \(friction_force\): 'x' is not a number"),
    ("normal_force [N],friction_force [N]\n1,2\n3\n", r"line 3: 1 cells, the header has 2 columns"),
    ("# c\nnormal_force [N],speed [m/s]\n1,2\n", "exactly one of the columns friction_force, friction_torque"),
    ("friction_force [N]\n1\n", r"missing column\(s\) \['normal_force'\]"),
    ("normal_force [N],colour [1]\n1,2\n", "unknown column 'colour'"),
    ("normal_force [N],friction_force [N]\n1,nan\n", r"line 2, column 2: friction_force must be finite"),
    ("normal_force [N],friction_force [N]\n", "no data rows"),
    ("normal_force [N],friction_force [N]\n-1,0.1\n", r"line 2, column 1: normal_force must be finite and > 0 N"),
    ("normal_force [N],friction_torque [N m],lever_arm [mm]\n1,0.1,5\n2,0.1,0\n",
     r"line 3, column 3: lever_arm must be finite and > 0 mm"),
])
def test_bad_friction_csv_names_line_and_column(tmp_path, text, message):
    path = _write(tmp_path, text)
    with pytest.raises(ValueError, match=message) as error:
        calibrate.read_friction_csv(path)
    assert str(path) in str(error.value)


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


def test_kf_exact_and_least_squares():
    from ballbench.lowmodel.contact import ellipse_friction as ef

    constants = calibrate.kf_constants(0.56, 0.5)
    exact, ls, ls_map = constants["exact"].value, constants["least_squares"].value, constants["least_squares_map"]
    assert exact > ls  # the cubic term of the force bends the fitted slope below the tangent (lin2019 eq A8)
    ratio = float(hertz.solve_load(hertz.ball_in_groove(5e-3, 0.56), 100.0).b
                  / hertz.solve_load(hertz.ball_in_groove(5e-3, 0.56), 100.0).a)
    g3 = float(ef.cubic_coefficient(ratio))
    assert ls == pytest.approx(exact - 0.6 * 0.5**2 * g3, rel=1e-9)  # k_f - (3/5) c_max^2 g3
    assert ls_map.covers(ls)  # the discrete fit on the tabulated map agrees with the continuous one
    assert abs(ls - 1.38) / 1.38 < 0.01  # lin2019 Sec 2.3.2 reads 1.38 off Fig 5


def test_calibrate_spec_from_cached_fe_data_and_validate_with_it(tmp_path, monkeypatch):
    friction = _write(tmp_path, "normal_force [N],friction_force [N]\n50,5.1\n100,9.9\n150,15.05\n200,19.9\n",
                      "friction.csv")
    spec = _write(tmp_path, f'''
output = "cal.json"
[contact."ball-groove-0.56"]
data = "{FE_CSV}"
ball_radius = 5e-3
conformity = 0.56
[friction]
data = "{friction.name}"
[k_f]
conformity = 0.56
''', "spec.toml")
    lines = []
    path, calibration = calibrate.run_spec(spec, log=lines.append)
    assert path == tmp_path / "cal.json" and path.is_file()
    psi = calibration.get("ball-groove-0.56", "psi")
    geometry = hertz.ball_in_groove(5e-3, 0.56)
    assert psi.reference == pytest.approx(hertz.psi_constant(geometry, 5e-3))
    assert abs(psi.value / psi.reference - 1) < 0.03  # the quick FE level's stated accuracy on a (3 %)
    mu = calibration.get("friction", "mu")
    assert mu.ci_low < 0.1 < mu.ci_high and math.isfinite(mu.std_error)
    assert any("calibration written" in line for line in lines)

    from ballbench.validation import cli

    monkeypatch.setenv(calibrate.CALIBRATION_ENV, "")  # restored after the test
    out = tmp_path / "report"
    code = cli.main(["validate", "calibration-effect", "--calibration", str(path), "--out", str(out),
                     "--no-progress"])
    assert code == 0
    report = json.loads((out / "results.json").read_text())
    assert "the --calibration file" in json.dumps(report)


def test_bad_spec_is_named(tmp_path):
    spec = _write(tmp_path, '[contact.x]\nfe_scene = "fe-hertz-flat"\ndata = "a.csv"\n', "s.toml")
    with pytest.raises(ValueError, match="exactly one of 'fe_scene'"):
        calibrate.run_spec(spec, log=lambda _: None)
    spec = _write(tmp_path, 'colour = 1\n', "t.toml")
    with pytest.raises(ValueError, match="unknown key"):
        calibrate.run_spec(spec, log=lambda _: None)


@pytest.mark.slow
def test_fe_sweep_reproduces_the_cached_data():
    # the quick FE level of fe-hertz-groove-056 (about 10-60 s on the shared machine)
    sweep = calibrate.fe_load_sweep("fe-hertz-groove-056", "quick")
    cached = calibrate.read_load_approach_csv(FE_CSV)
    for name in ("force", "approach", "a"):
        np.testing.assert_allclose(sweep[name], cached[name], rtol=1e-6)


def test_roundtrip_scene_passes(tmp_path):
    from ballbench.validation.runner import run_scene
    from ballbench.validation.scene import registry

    result = run_scene(registry()["calibration-roundtrip"], "quick", tmp_path, show_progress=False)
    assert result.passed, (result.error, [(o.quantity, o.value) for o in result.outputs if not o.passed])
    assert len(result.outputs) == 13  # 6 constants, the file round trip, 6 coverages


def test_sweep_cases_take_a_calibration_file(tmp_path):
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.validation import sweep_cases

    geometry = hertz.ball_in_groove(5e-3, 0.56)
    psi_hertz = hertz.psi_constant(geometry, 5e-3)
    contacts = b2b.module_contacts(math.radians(2.0), -0.6)
    np.testing.assert_allclose(sweep_cases.with_psi(contacts, psi_hertz).semi_major, contacts.semi_major, rtol=1e-12)
    constant = cal.Constant(1.01 * psi_hertz, 1e-6, 0.0, 1.0, "(m^2/N)^(1/3)", "test")
    path = cal.save(cal.Calibration({"ball-groove-0.56": {"psi": constant}}), tmp_path / "c.json")
    plain = sweep_cases.two_ball_analytical(math.radians(2.0), -0.6)
    calibrated = sweep_cases.two_ball_analytical(math.radians(2.0), -0.6, calibration=str(path))
    assert calibrated["b2b_force"] == pytest.approx(plain["b2b_force"] / 1.01, rel=1e-12)  # eq 30: 1/Psi
    numerical = sweep_cases.two_ball_numerical(math.radians(2.0), -0.6, calibration=str(path))
    assert numerical["b2b_force"] != sweep_cases.two_ball_numerical(math.radians(2.0), -0.6)["b2b_force"]
    with pytest.raises(KeyError, match="ball-groove-0.6"):
        sweep_cases.two_ball_analytical(0.01, 0.1, calibration=str(path), conformity=0.6)


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
    tiny = np.array([8.6e-210, 1.7e-209])
    with pytest.raises(ValueError, match="normal_force"):  # singular value^2 underflowed: divide by zero
        calibration.fit_friction_coefficient(tiny, 0.0 * tiny)


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
