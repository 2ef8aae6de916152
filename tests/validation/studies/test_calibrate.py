"""validation.studies.calibration (``ballbench calibrate``): friction CSV input, k_f constants, the spec, the FE load
sweep."""
import json
import math
from pathlib import Path

import numpy as np
import pytest
from ballbench.lowmodel.contact import hertz
from ballbench.validation import cli
from ballbench.validation.studies.calibration import command, fe_laws
from ballbench.validation.studies.calibration import spec as calibration_spec

from tests.cli_support import one_error_line
from tests import paths

NUT_DATA = paths.DATA / "fe_nut_quick.load_approach.csv"


def _calibrate_spec(tmp_path, body: str) -> Path:
    (tmp_path / "nut.csv").write_text(NUT_DATA.read_text())
    path = tmp_path / "spec.toml"
    path.write_text(f'output = "{tmp_path / "out" / "calibration.json"}"\n' + body)
    return path


FE_CONTACT = '[contact."ball-groove-0.56"]\nfe_scene = "fe-hertz-groove-056"\n'


@pytest.mark.parametrize("body, expected", [
    (FE_CONTACT + "[k_f]\nconformity = 0.56\nfit_rnage = 0.5\n", "unknown key(s) ['fit_rnage']"),
    (FE_CONTACT + "[friction]\ndata = 'rig.csv'\n", "friction.data: no such file"),
    (FE_CONTACT + "[k_f]\nconformity = 56\n", "k_f.conformity must lie in"),
    ("confidence = 95\n" + FE_CONTACT, "confidence must lie in (0, 1)"),
    ('[contact."ball-groove-0.56"]\nfe_scene = "fe-hertz-groove-056"\nfidelity = "coarse"\n', "fidelity must be"),
    ('[contact.nut]\ndata = "nut.csv"\nball_radius = 3.175\n', "ball_radius must lie in [0.0001, 0.1] m"),
])
def test_calibrate_spec_mistakes_are_found_before_the_fe_sweep(tmp_path, monkeypatch, capsys, body, expected):
    # a typo in the last table used to surface only after the FE load sweep of the first (minutes); a ball
    # radius in mm used to give a Psi 10x off without a word
    monkeypatch.setattr(calibration_spec, "fe_contact_law", lambda *a, **k: pytest.fail("FE started before the check"))
    line = one_error_line(capsys, cli.main(["calibrate", str(_calibrate_spec(tmp_path, body))]))
    assert expected in line
    assert not (tmp_path / "out").exists()


def test_calibrate_spec_in_metres_still_runs(tmp_path, capsys):
    body = '[contact.nut]\ndata = "nut.csv"\nball_radius = 2.778e-3\n'
    assert cli.main(["calibrate", str(_calibrate_spec(tmp_path, body))]) == 0
    assert (tmp_path / "out" / "calibration.json").is_file()


DATA = paths.DATA


FE_CSV = DATA / "fe_groove056_quick.load_approach.csv"


def _write(tmp_path, text, name="f.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_friction_csv_units_and_torque(tmp_path):
    path = _write(tmp_path, "# rig 3, 2026-11-20\nnormal_force [kN],friction_torque [N mm],lever_arm [mm],"
                            "speed [mm/s]\n0.1,500,50,10\n0.2,1100,50,20\n")
    data = calibration_spec.read_friction_csv(path)
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
        calibration_spec.read_friction_csv(path)
    assert str(path) in str(error.value)


def test_kf_exact_and_least_squares():
    from ballbench.lowmodel.contact import ellipse_friction as ef

    constants = calibration_spec.kf_constants(0.56, 0.5)
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
    path, calibration = calibration_spec.run_spec(spec, log=lines.append)
    assert path == tmp_path / "cal.json" and path.is_file()
    psi = calibration.get("ball-groove-0.56", "psi")
    geometry = hertz.ball_in_groove(5e-3, 0.56)
    assert psi.reference == pytest.approx(hertz.psi_constant(geometry, 5e-3))
    assert abs(psi.value / psi.reference - 1) < 0.03  # the quick FE level's stated accuracy on a (3 %)
    mu = calibration.get("friction", "mu")
    assert mu.ci_low < 0.1 < mu.ci_high and math.isfinite(mu.std_error)
    assert any("calibration written" in line for line in lines)

    from ballbench.validation import cli

    monkeypatch.setenv(command.CALIBRATION_ENV, "")  # restored after the test
    out = tmp_path / "report"
    code = cli.main(["validate", "calibration-effect", "--calibration", str(path), "--out", str(out),
                     "--no-progress"])
    assert code == 0
    report = json.loads((out / "results.json").read_text())
    assert "the --calibration file" in json.dumps(report)


def test_bad_spec_is_named(tmp_path):
    spec = _write(tmp_path, '[contact.x]\nfe_scene = "fe-hertz-flat"\ndata = "a.csv"\n', "s.toml")
    with pytest.raises(ValueError, match="exactly one of 'fe_scene'"):
        calibration_spec.run_spec(spec, log=lambda _: None)
    spec = _write(tmp_path, 'colour = 1\n', "t.toml")
    with pytest.raises(ValueError, match="unknown key"):
        calibration_spec.run_spec(spec, log=lambda _: None)


@pytest.mark.slow
def test_fe_sweep_reproduces_the_cached_data():
    # the quick FE level of fe-hertz-groove-056 (about 10-60 s on the shared machine)
    sweep = fe_laws.fe_load_sweep("fe-hertz-groove-056", "quick")
    cached = calibration_spec.read_load_approach_csv(FE_CSV)
    for name in ("force", "approach", "a"):
        np.testing.assert_allclose(sweep[name], cached[name], rtol=1e-6)
