"""The whole-screw Monte Carlo case function and its example spec (docs/sweeps.md)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.validation import sweep
from ballbench.validation.sweep import functions
from tests import paths
from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz

EXAMPLE = paths.ROOT / "examples" / "whole_screw_monte_carlo.toml"
DEG = math.pi / 180.0


def test_fourier_deviation_closed_form():
    phi = np.linspace(0.0, 4 * math.pi, 17)
    theta = functions.fourier_deviation([0.1, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.2])
    np.testing.assert_allclose(theta(phi), 0.1 * np.cos(phi / 2) + 0.2 * np.sin(2 * phi), atol=1e-15)
    np.testing.assert_allclose(theta(phi + 4 * math.pi), theta(phi), atol=1e-14)  # repeats every two turns


def test_single_harmonic_is_the_papers_sine_and_no_deviation_gives_no_b2b():
    """b_4 alone is whole_screw.simulate's amplitude sin(2 phi) (lin2019 Sec 3.4, four cycles over two turns);
    catches a harmonic numbered or scaled wrongly.  theta = 0: identical balls never press on each other."""
    from ballbench.lowmodel.screw import whole_screw as ws

    module, _, stiffness = functions._screw_setup(None, 37, 1500.0)
    out = functions.whole_screw_fourier(b4=3 * DEG, steps=3)
    history = ws.simulate(module, n_balls=37, axial_load=1500.0, duration=2.0, steps=3, amplitude=3 * DEG, cycles=4,
                          stiffness=stiffness)
    assert out["peak_b2b_torque"] == pytest.approx(history.b2b_torque.max(), rel=1e-9)
    assert out["mean_groove_torque"] == pytest.approx(history.groove_torque.mean(), rel=1e-9)
    assert out["max_deviation"] == pytest.approx(3 * DEG, rel=1e-6)
    zero = functions.whole_screw_fourier(steps=2)
    assert zero["peak_b2b_torque"] == 0.0 and zero["max_groups"] == 0.0 and zero["mean_groove_torque"] > 0.0


def test_example_spec_runs_two_screws(tmp_path):
    spec = sweep.load_spec(EXAMPLE)
    assert spec.n_cases == 40 and set(spec.random) == {f"{c}{k}" for c in "ab" for k in range(1, 5)}
    small = sweep.spec_from_dict({**spec.source, "fixed": {**spec.source["fixed"], "steps": 2},
                                  "random": {**spec.source["random"], "draws": 2}})
    summary = sweep.run_sweep(small, tmp_path / "out", serial=True, progress=False)
    assert summary.computed == 2 and summary.failed == 0
    result = sweep.read_results(tmp_path / "out")
    assert np.all(np.isfinite(result["mean_groove_torque"])) and np.all(result["peak_increase"] >= 0.0)


def test_calibration_file_reaches_the_whole_screw(tmp_path):
    """``calibration = FILE`` puts the FE screw/nut groove laws (cached quick-level sweeps) into every ball."""
    from ballbench.validation.studies.calibration import spec as calibration_spec

    data = paths.DATA
    spec = tmp_path / "spec.toml"
    spec.write_text("\n".join(
        f'[contact."{group}"]\ndata = "{data / f"fe_{body}_quick.load_approach.csv"}"\nball_radius = 2.778e-3\n'
        for group, body in (("screw-groove", "screw"), ("nut-groove", "nut"))))
    path, _ = calibration_spec.run_spec(spec, tmp_path / "c.json", log=lambda *_: None)
    hertz = functions.whole_screw_fourier(b4=3 * DEG, steps=2)
    calibrated = functions.whole_screw_fourier(b4=3 * DEG, steps=2, calibration=str(path))
    _, laws, _ = functions._screw_setup(str(path), 37, 1500.0)
    assert laws is not None and laws.nut.bulk_compliance.value < 0
    assert calibrated["mean_groove_torque"] != pytest.approx(hertz["mean_groove_torque"], rel=1e-6)


def test_sweep_functions_take_a_calibration_file(tmp_path):
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.validation.sweep import functions

    geometry = hertz.ball_in_groove(5e-3, 0.56)
    psi_hertz = hertz.psi_constant(geometry, 5e-3)
    contacts = b2b.module_contacts(math.radians(2.0), -0.6)
    np.testing.assert_allclose(functions.with_psi(contacts, psi_hertz).semi_major, contacts.semi_major, rtol=1e-12)
    constant = cal.Constant(1.01 * psi_hertz, 1e-6, 0.0, 1.0, "(m^2/N)^(1/3)", "test")
    path = cal.save(cal.Calibration({"ball-groove-0.56": {"psi": constant}}), tmp_path / "c.json")
    plain = functions.two_ball_analytical(math.radians(2.0), -0.6)
    calibrated = functions.two_ball_analytical(math.radians(2.0), -0.6, calibration=str(path))
    assert calibrated["b2b_force"] == pytest.approx(plain["b2b_force"] / 1.01, rel=1e-12)  # eq 30: 1/Psi
    numerical = functions.two_ball_numerical(math.radians(2.0), -0.6, calibration=str(path))
    assert numerical["b2b_force"] != functions.two_ball_numerical(math.radians(2.0), -0.6)["b2b_force"]
    with pytest.raises(KeyError, match="ball-groove-0.6"):
        functions.two_ball_analytical(0.01, 0.1, calibration=str(path), conformity=0.6)
