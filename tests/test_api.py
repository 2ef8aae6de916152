"""The public API at the top (``import ballbench``): light to import, a case file to engineer's results."""
import math
import subprocess
import sys

import pytest

import ballbench


def test_import_and_results_stay_light(tmp_path):
    # importing ballbench, loading a case and computing its friction pull in none of the heavy libraries
    code = ("import sys, ballbench\n"
            "bare = sorted({n.split('.')[0] for n in sys.modules} & {'numpy', 'scipy'})\n"
            "case = ballbench.load_case(sys.argv[1])\n"
            "ballbench.friction(case), ballbench.contact(case)\n"
            "heavy = sorted({n.split('.')[0] for n in sys.modules} & {'gmsh', 'pyvista', 'vtk', 'matplotlib'})\n"
            "print(','.join(bare), ','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code, str(_write(tmp_path, "linear-guide"))], capture_output=True,
                         text=True, check=True)
    assert out.stdout.split() == []


def test_version_is_read_on_first_use():
    # importlib.metadata was most of the import time; the version is read when asked for, and is the installed one
    from importlib.metadata import version

    assert ballbench.__version__ == version("ballbench")
    out = subprocess.run([sys.executable, "-c", "import sys, ballbench; print('importlib.metadata' in sys.modules)"],
                         capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False"]


def test_models_one_attribute_deep_take_si_and_refuse_mm():
    geometry = ballbench.hertz.ball_in_groove(3.175e-3, 0.52)
    assert ballbench.hertz.solve_load(geometry, 500.0).a > 0
    with pytest.raises(ValueError, match="ball_radius"):
        ballbench.hertz.ball_in_groove(3.175, 0.52)
    with pytest.raises(AttributeError):
        ballbench.not_a_model  # noqa: B018


def test_a_case_file_to_friction_force_and_contact(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text(ballbench.template("linear-guide"))
    case = ballbench.load_case(path)
    result = ballbench.friction(case)
    # the friction force is the drive's power over the carriage speed (bearing_results), and B2B contact adds
    assert result.friction_force == pytest.approx(result.power / case.guide.groove_velocity, rel=1e-12)
    assert result.friction_force > result.friction_force_free > 0
    assert result.friction_increase == pytest.approx(result.friction_force / result.friction_force_free - 1)
    worst = max(result.contacts, key=lambda c: c.normal_force)
    assert worst.p0 == pytest.approx(1.5 * worst.normal_force / (math.pi * worst.a * worst.b), rel=1e-12)
    assert ballbench.contact(case).a == pytest.approx(worst.a, rel=1e-9)  # the same most loaded contact
    data = result.to_dataset()
    assert data["normal_force"].shape == (case.n_balls, 4)
    with pytest.raises(TypeError, match="LinearGuideCase"):
        ballbench.friction(ballbench.load_case(_write(tmp_path, "contact")))


def _write(tmp_path, kind):
    path = tmp_path / f"{kind}.toml"
    path.write_text(ballbench.template(kind))
    return path


def test_screw_friction_torque(tmp_path):
    case = ballbench.load_case(_write(tmp_path, "ball-screw"))
    result = ballbench.friction(case)
    assert result.friction_torque == pytest.approx(result.power / abs(case.screw.nut_speed), rel=1e-12)
    assert result.friction_torque > 0 and len(result.b2b_forces) == len(case.deviations) - 1
    assert sum(result.axial_shares) == pytest.approx(case.axial_load, rel=1e-9)


def test_ladder_of_a_contact_case_up_to_the_bem(tmp_path):
    case = ballbench.load_case(_write(tmp_path, "contact"))
    (result,) = ballbench.ladder(case, "quick", levels="BEM", name="mine")
    assert result.name == "mine-contact" and not result.error
    families = {o.family for o in result.outputs}
    assert families == {"analytical", "BEM"}
    # the reference is the finest BEM grid; it is not checked against itself, the coarser grid is
    assert [o.level for o in result.outputs if o.family == "BEM"] == ["64 x 64"] * 4
    with pytest.raises(ValueError, match="levels must be one of"):
        ballbench.ladder(case, "quick", levels="FEM")


def test_a_limit_study_may_leave_the_plausible_ranges_on_purpose():
    from ballbench.lowmodel import checks

    with pytest.raises(ValueError, match="pitch_radius"):
        checks.plausible("pitch_radius", 5.0)
    with checks.beyond_plausible():
        assert checks.plausible("pitch_radius", 5.0) == 5.0
        with pytest.raises(ValueError, match="pitch_radius"):
            checks.plausible("pitch_radius", float("nan"))
    with pytest.raises(ValueError):
        checks.plausible("pitch_radius", 5.0)
