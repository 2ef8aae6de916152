"""3D screenshots of saved fields (validation.figures.render3d): image regression against stored baselines, a wrong
field must change the picture, and the saved fields' conventions (fem.fields).

The fields are small coarse solves in tests/data/render3d/ (regenerate.py there makes them).  Baselines are the
pictures at a third of their size (3 x 3 pixel means, to keep the repository small) in
tests/baseline_images/render3d/, compared with ``pyvista.compare_images`` (VTK's image difference, as
pytest-pyvista does); ``BALLBENCH_RESET_BASELINES=1`` rewrites them (look at them before committing).  On this
machine two renderings are identical (error 0); the tolerance leaves room for another OpenGL implementation and is
far below what a wrong field does (the tests below).
"""
from __future__ import annotations

import json
import math
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyvista")

from ballbench.validation.figures import render3d  # noqa: E402
from tests import paths

DATA = paths.DATA / "render3d"
BASELINES = paths.BASELINE_IMAGES / "render3d"
ERROR_TOLERANCE = 20.0  # vtkImageDifference's thresholded error (pytest-pyvista's default 500 misses one patch)
PICTURES = {
    "pair": ("3d_assembly.png", "3d_pressure.png", "3d_stress.png"),
    "module": ("3d_assembly.png", "3d_pressure_overview.png", "3d_pressure_contacts.png", "3d_stress.png"),
    "surface": ("3d_bem_A.png",),
    "stickslip": ("3d_stickslip_rolling.png",),
}


def _copy(case: str, target: Path) -> Path:
    directory = target / case
    shutil.copytree(DATA / case, directory, ignore=shutil.ignore_patterns("*.png", "*.py"))
    return directory


def _small(path: Path) -> np.ndarray:
    """The picture at a third of its size (the baselines' size: means of 3 x 3 pixels), RGB."""
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB").reduce(3))


def _error(picture: Path, baseline: np.ndarray) -> float:
    import pyvista as pv

    image = _small(picture)
    assert image.shape == baseline.shape, f"{picture.name}: size {image.shape} against the baseline's {baseline.shape}"
    return float(pv.compare_images(image, baseline))


def _baseline(case: str, name: str) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(BASELINES / f"{case}_{name}").convert("RGB"))


@pytest.fixture(scope="module")
def rendered(tmp_path_factory):
    """The pictures of the three saved cases: {case: [paths]}."""
    target = tmp_path_factory.mktemp("render3d")
    return {case: render3d.render(_copy(case, target)) for case in PICTURES}


@pytest.mark.parametrize("case, name", [(case, name) for case, names in PICTURES.items() for name in names])
def test_pictures_match_their_baselines(rendered, case, name):
    paths = {p.name: p for p in rendered[case]}
    assert sorted(paths) == sorted(PICTURES[case])
    if os.environ.get("BALLBENCH_RESET_BASELINES"):
        from PIL import Image

        BASELINES.mkdir(parents=True, exist_ok=True)
        Image.fromarray(_small(paths[name])).save(BASELINES / f"{case}_{name}", optimize=True)
        pytest.skip("baseline reset")
    assert _error(paths[name], _baseline(case, name)) <= ERROR_TOLERANCE


def test_rendering_twice_gives_the_same_picture(tmp_path):
    first = render3d.render(_copy("surface", tmp_path / "1"))[0]
    second = render3d.render(_copy("surface", tmp_path / "2"))[0]
    assert _error(first, _small(second)) == 0.0


def test_rendering_prints_nothing_on_stderr(tmp_path, capfd):
    render3d.render(_copy("surface", tmp_path))
    captured = capfd.readouterr()
    assert captured.err == "", captured.err
    assert "vtk" not in captured.out.lower()


def _edit_vtu(path: Path, edit) -> None:
    import meshio

    mesh = meshio.read(path)
    edit(mesh)
    mesh.write(path)


def test_a_wrong_pressure_changes_the_pictures(tmp_path):
    """The pair's pressure 30 % higher on one side of the contact, one contact of the module twice as high (a
    field that is not the saved one) must not pass the baselines."""
    pair = _copy("pair", tmp_path)

    def lopsided(mesh):
        name = "contact_pressure_Pa"
        mesh.point_data[name] = mesh.point_data[name] * (1.0 + 0.3 * (mesh.points[:, 0] > 0.0))

    _edit_vtu(pair / "fields.vtu", lopsided)
    paths = {p.name: p for p in render3d.render(pair)}
    assert _error(paths["3d_pressure.png"], _baseline("pair", "3d_pressure.png")) > 2 * ERROR_TOLERANCE
    assert _error(paths["3d_assembly.png"], _baseline("pair", "3d_assembly.png")) <= ERROR_TOLERANCE  # no field

    module = _copy("module", tmp_path)

    def one_contact(mesh):
        name = "contact_pressure_Pa"
        mesh.point_data[name] = mesh.point_data[name] * np.where(mesh.point_data["contact_index"] == 1, 2.0, 1.0)

    _edit_vtu(module / "fields_ball1.vtu", one_contact)
    paths = {p.name: p for p in render3d.module_pictures(module)}
    assert _error(paths["3d_pressure_contacts.png"],
                  _baseline("module", "3d_pressure_contacts.png")) > 2 * ERROR_TOLERANCE


def test_a_wrong_stress_changes_the_pictures(tmp_path):
    module = _copy("module", tmp_path)

    def hotter(mesh):
        name = "von_mises_stress_Pa"
        mesh.cell_data[name] = [values * 1.1 for values in mesh.cell_data[name]]

    _edit_vtu(module / "fields_ball2.vtu", hotter)
    paths = {p.name: p for p in render3d.module_pictures(module)}
    assert _error(paths["3d_stress.png"], _baseline("module", "3d_stress.png")) > 2 * ERROR_TOLERANCE


def _edit_npz(path: Path, edit) -> None:
    with np.load(path) as data:
        arrays = dict(data)
    edit(arrays)
    np.savez_compressed(path, **arrays)


@pytest.mark.parametrize("change", ["traction 20 % lower", "stick area one row longer"])
def test_a_wrong_stick_slip_field_changes_the_picture(tmp_path, change):
    """The saved rolling contacts with the traction of the first contact 20 % lower everywhere, or the stick area
    of the second grown by one row of cells towards the trailing edge (the traction unchanged), must not pass
    the baseline."""
    from ballbench.validation.figures import stickslip3d

    directory = _copy("stickslip", tmp_path)

    def edit(arrays):
        if change.startswith("traction"):
            arrays["traction_0"] = 0.8 * arrays["traction_0"]
        else:
            stick = arrays["stick_1"]
            arrays["stick_1"] = (stick | np.roll(stick, -1, axis=0)) & arrays["contact_1"]

    _edit_npz(directory / "stickslip_rolling.npz", edit)
    picture = stickslip3d.picture(directory / "stickslip_rolling.json")
    assert _error(picture, _baseline("stickslip", "3d_stickslip_rolling.png")) > 2 * ERROR_TOLERANCE


def test_stick_slip_fields_round_trip(tmp_path):
    """write_fields keeps each contact's arrays in Kalker's grid order and its numbers in the meta file."""
    from ballbench.lowmodel.contact import rolling
    from ballbench.validation.figures import stickslip3d

    solution = rolling.steady_rolling(1e-3, 1e-3, 100.0, 80e9, 0.3, 0.3, 1e-4, 0.0, 0.0, (8, 10))
    data, meta, _ = stickslip3d.write_fields(tmp_path, "one", [("c", solution)], scene="s", fidelity="test",
                                             title="t")
    with np.load(data) as arrays:
        assert np.array_equal(arrays["x_0"], solution.grid.x) and np.array_equal(arrays["y_0"], solution.grid.y)
        assert np.array_equal(arrays["traction_0"], solution.traction)
        assert np.array_equal(arrays["stick_0"], solution.stick)
    entry = json.loads(meta.read_text())["contacts"][0]
    assert entry["stick_fraction"] == solution.stick_fraction and entry["ellipse_m"] is None
    with pytest.raises(ValueError, match="ellipses"):
        stickslip3d.write_fields(tmp_path, "two", [("c", solution)], scene="s", fidelity="test", title="t",
                                 ellipses=[])


def test_stick_slip_fields_as_vtu(tmp_path):
    """Each contact's stick/slip field is also a VTU (docs/render3d.md): meshio reads back one quadrilateral per
    grid cell, cell (i, j) the i ny + j-th, with the SI arrays equal to the solution's; the slip direction a unit
    vector along the slip in the slip area and zero in stick."""
    import meshio

    from ballbench.lowmodel.contact import rolling
    from ballbench.validation.figures import stickslip3d

    solutions = [rolling.steady_rolling(1e-3, 1e-3, 100.0, 80e9, 0.3, 0.3, 1e-4, 0.0, 0.0, (8, 10)),
                 rolling.steady_rolling(1e-3, 0.6e-3, 150.0, 80e9, 0.3, 0.3, 5e-4, 0.0, 0.0, (6, 12))]
    paths = stickslip3d.write_fields(tmp_path, "two", [("a", solutions[0]), ("b", solutions[1])], scene="s",
                                     fidelity="test", title="t")
    assert [p.name for p in paths[2:]] == ["stickslip_two_0.vtu", "stickslip_two_1.vtu"]
    meta = json.loads(paths[1].read_text())
    assert [c["vtu"] for c in meta["contacts"]] == ["stickslip_two_0.vtu", "stickslip_two_1.vtu"]
    for path, solution in zip(paths[2:], solutions):
        mesh = meshio.read(path)
        nx, ny = solution.grid.nx, solution.grid.ny
        assert [block.type for block in mesh.cells] == ["quad"] and len(mesh.cells[0].data) == nx * ny
        assert set(stickslip3d.VTU_ARRAYS) <= set(mesh.cell_data)
        cell = {key: np.asarray(mesh.cell_data[key][0]) for key in stickslip3d.VTU_ARRAYS}
        assert np.array_equal(cell["p [Pa]"].reshape(nx, ny), solution.pressure)
        assert np.array_equal(cell["q_x [Pa]"].reshape(nx, ny), solution.traction[..., 0])
        assert np.array_equal(cell["q_y [Pa]"].reshape(nx, ny), solution.traction[..., 1])
        assert np.allclose(cell["|q| [Pa]"].reshape(nx, ny), np.linalg.norm(solution.traction, axis=-1))
        assert np.allclose(cell["mu p [Pa]"].reshape(nx, ny), solution.friction_coefficient * solution.pressure)
        stick = cell["stick [1]"].reshape(nx, ny).astype(bool)
        assert np.array_equal(stick, solution.stick) and np.array_equal(
            cell["contact [1]"].reshape(nx, ny).astype(bool), solution.contact)
        direction = cell["slip direction [1]"].reshape(nx, ny, 3)
        slip = solution.contact & ~solution.stick
        assert slip.any() and np.allclose(np.linalg.norm(direction[slip], axis=-1), 1.0)
        d, v = direction[slip, :2], solution.slip[slip]
        assert np.allclose(d[:, 0] * v[:, 1] - d[:, 1] * v[:, 0], 0.0, atol=1e-12 * np.abs(v).max())
        assert np.all(np.sum(direction[slip, :2] * solution.slip[slip], axis=-1) > 0.0)
        assert not direction[~slip].any()
        # the cell (i, j) sits at the grid's cell centre (x_i, y_j)
        centres = mesh.points[mesh.cells[0].data].mean(axis=1).reshape(nx, ny, 3)
        assert np.allclose(centres[:, 0, 0], solution.grid.x) and np.allclose(centres[0, :, 1], solution.grid.y)


def test_render_needs_saved_fields(tmp_path):
    assert not render3d.has_fields(tmp_path)
    with pytest.raises(FileNotFoundError, match="no saved fields"):
        render3d.render(tmp_path)
    (tmp_path / "fields.json").write_text(json.dumps({"kind": "spline"}))
    with pytest.raises(ValueError, match="unknown kind"):
        render3d.render(tmp_path)


def test_artifacts_turn_a_failure_into_a_note(tmp_path):
    notes = []
    assert render3d.artifacts(tmp_path, notes.append) == []
    assert len(notes) == 1 and "not drawn" in notes[0]


# ----------------------------------------------------------------------------------------------- fem.fields
def test_module_meta_loads_balance_the_applied_loads():
    """The load arrow of each ball's module is the balance of the contact forces on the top rail: lin2017 eq 35's
    (N_x, -N_y) with N_x = +-rho N_y (ball 1 behind: rho N_y), N_y = 100 N (lin2019 Table 1, rho = -0.6)."""
    meta = json.loads((DATA / "module" / "fields.json").read_text())
    for ball, side in zip(meta["balls"], (-0.6, 0.6)):
        assert ball["loaded_body"] == "top_rail"
        assert np.allclose(ball["load_N"], [side * 100.0, -100.0, 0.0], rtol=0.0, atol=1e-6)
        for contact in ball["contacts"]:
            frame = np.asarray(contact["frame"])
            assert np.allclose(frame @ frame.T, np.eye(3), atol=1e-12)
            centre_to_point = np.asarray(contact["point_m"]) - np.asarray(ball["ball_centre_m"])
            assert np.allclose(-frame[2] * ball["ball_radius_m"], centre_to_point, atol=1e-9)  # e3 into the ball
            assert contact["moving"] == contact["name"].startswith("T")


def test_placement_of_two_balls_in_the_linear_module():
    from ballbench.fem.fields import placement
    from ballbench.fem.fourpoint import ModuleGeometry

    geometry = ModuleGeometry(5e-3, 0.52, (math.radians(45.0),) * 4)
    behind, ahead = placement(geometry, 0, 2), placement(geometry, 1, 2)
    assert np.allclose(behind["translation"], [0.0, 0.0, -5e-3]) and np.allclose(ahead["translation"], [0, 0, 5e-3])
    assert behind["keep"] == [{"point_m": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, -1.0]}]
    assert ahead["keep"] == [{"point_m": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}]
    assert placement(geometry, 0, 1)["keep"] == []


def test_placement_of_two_balls_on_the_helix():
    """Ball 2 sits on the helix a chord 2 R_B ahead of ball 1, its module turned and lifted so that the helix maps
    onto itself, and the cut between them passes through the midpoint of the helix, normal to it."""
    from ballbench.fem.fields import placement
    from ballbench.fem.screw_module import screw_module_geometry
    from ballbench.lowmodel.geometry import helix

    radius, pitch_radius, lead = 2.778e-3, 16.5e-3, 20e-3
    geometry = screw_module_geometry(radius, 0.56, pitch_radius, lead, (math.radians(45.0),) * 4)
    ahead = placement(geometry, 1, 2)
    rotation, translation = np.asarray(ahead["rotation"]), np.asarray(ahead["translation"])
    centre_1 = np.asarray(helix.ball_centre(0.0, pitch_radius, lead))
    centre_2 = rotation @ centre_1 + translation
    assert np.linalg.norm(centre_2 - centre_1) == pytest.approx(2 * radius, rel=1e-12)
    phi = math.atan2(centre_2[1], centre_2[0])
    assert np.allclose(centre_2, helix.ball_centre(phi, pitch_radius, lead), atol=1e-15)
    (cut,) = ahead["keep"]
    point, normal = np.asarray(cut["point_m"]), np.asarray(cut["normal"])
    assert (centre_2 - point) @ normal > 0 > (centre_1 - point) @ normal  # keeps ball 2's side
    assert np.linalg.norm(point - centre_1) == pytest.approx(np.linalg.norm(point - centre_2), rel=1e-9)


def test_surface_fields_keep_the_grid_order(tmp_path):
    import meshio

    from ballbench.fem.fields import write_surface_fields

    x, y = np.linspace(-1e-4, 1e-4, 4), np.linspace(-5e-5, 5e-5, 3)
    values = np.arange(12.0).reshape(4, 3)
    vtu, meta = write_surface_fields(tmp_path, "case", x, y, {"pressure_Pa": values}, {"title": "t"})
    mesh = meshio.read(vtu)
    k = 2 * 3 + 1  # (i, j) = (2, 1)
    assert np.allclose(mesh.points[k, :2], [x[2], y[1]])
    assert mesh.point_data["pressure_Pa"][k] == values[2, 1]
    assert json.loads(meta.read_text())["kind"] == "surface"
    with pytest.raises(ValueError, match="shape"):
        write_surface_fields(tmp_path, "bad", x, y, {"pressure_Pa": values.T}, {})
