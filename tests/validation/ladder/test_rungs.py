"""The ladder of a case of one's own (validation.ladder): its rungs (ladder.rungs.distinct_contacts: the contact
geometries of a case the ``-contact`` scene runs; the FE rung's memory and levels) and the scenes it builds
(docs/your_own_bearing.md, "The ladder")."""
from __future__ import annotations

import json

import numpy as np
import pytest

from ballbench.validation import cli
from ballbench.validation.cases import case_file
from ballbench.lowmodel import bearing_results
from ballbench.validation.ladder import rungs
from tests import paths


def test_a_guide_has_one_contact_geometry_run_at_its_largest_load():
    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    (only,) = rungs.distinct_contacts(case)
    result = bearing_results.guide_result(case)
    assert only.label == "groove" and len(only.members) == len(result.contacts)
    assert only.contact.force == max(c.normal_force for c in result.contacts)
    assert only.contact.conformity == case.guide.conformity


def test_a_screw_has_a_screw_side_and_a_nut_side_each_at_its_largest_load():
    case = case_file.load(paths.ROOT / "examples" / "ball_screw_32x10.toml")
    distinct = rungs.distinct_contacts(case)
    result = bearing_results.screw_result(case)
    assert {d.label for d in distinct} == {"screw side", "nut side"}
    for d in distinct:
        side = [c for c in result.contacts if c.contact[0] == d.contact.pair[0].upper()]
        assert d.contact.force == max(c.normal_force for c in side) and len(d.members) == len(side)
    assert distinct[0].contact.force >= distinct[1].contact.force  # the most loaded first: its fields are saved
    assert distinct[0].contact.force == rungs.governing_contact(case).force


def test_the_frictionless_loads_of_a_screw_are_the_largest_of_its_frictionless_statics():
    # the contact rung's loads past the preload loss (lowmodel.screw.preload.frictionless_statics), per side
    from ballbench.lowmodel.screw import preload
    from ballbench.lowmodel.screw import b2b as screw_b2b

    case = case_file.load(paths.ROOT / "examples" / "ball_screw_32x10.toml")
    distinct = rungs.distinct_contacts(case, frictionless=True)
    state = preload.frictionless_statics(screw_b2b.contacts(case), case.axial_load)
    largest = {"screw": state.normal_force[:, :2].max(), "nut": state.normal_force[:, 2:].max()}
    assert {d.contact.pair: d.contact.force for d in distinct} == largest
    assert all("frictionless" in d.contact.name and "lowmodel.screw.preload" in d.why for d in distinct)
    assert distinct[0].contact.force >= distinct[1].contact.force
    guide = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    with pytest.raises(ValueError, match="frictionless"):
        rungs.distinct_contacts(guide, frictionless=True)
    # a guide's eq 36 loads alone give the contacts of lin2019's state
    assert rungs.distinct_contacts(guide, bearing_results.guide_contacts(guide)) == rungs.distinct_contacts(guide)


def test_the_contact_scene_of_a_screw_runs_both_sides(tmp_path, capsys):
    out = tmp_path / "report"
    cli.main(["validate", str(paths.ROOT / "examples" / "ball_screw_32x10.toml"), "--quick", "--no-progress",
              "--levels", "BEM", "--out", str(out)])
    assert "Traceback" not in capsys.readouterr().err
    scene = next(s for s in json.loads((out / "results.json").read_text())["scenes"] if s["name"].endswith("-contact"))
    hertz = [o for o in scene["outputs"] if o["model"] == "lowmodel.contact.hertz" and o["quantity"] == "a"]
    assert sorted(o["level"] for o in hertz) == ["nut side", "screw side"]
    assert hertz[0]["value"] != hertz[1]["value"]
    assert scene["tables"][0]["title"].startswith("Contacts run") and len(scene["tables"][0]["rows"]) == 2


def test_the_stick_slip_rung_of_a_guide_judges_full_slip_at_its_declared_accuracy(tmp_path):
    # the balls of one's own guide with stick/slip contacts against full slip on the same cells: the B2B force at
    # full slip's 2.5 % (docs/b2b_rolling.md), the friction at 1 %, a power balance per solve, a row per contact
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scenes
    from ballbench.validation.studies.rolling_b2b import FULL_SLIP_TOLERANCE

    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    scenes = [s for s in ladder.case_scenes(case, "g", top="stick-slip") if s.name == "g-stick-slip"]
    assert scenes and "g-stick-slip" in ladder.scene_names(case, "g", top="stick-slip")
    assert "g-stick-slip" not in ladder.scene_names(case, "g", top="FE-informed")
    (result,), _ = run_scenes(scenes, "quick", tmp_path, show_progress=False)
    assert not result.error and result.passed, result
    checks = {o.quantity: o for o in result.outputs}
    b2b = checks["F_B2B"]
    assert b2b.tolerance == FULL_SLIP_TOLERANCE and b2b.finding and b2b.value > 0 and b2b.reference > 0
    assert b2b.value != b2b.reference  # two laws, not one model against itself
    assert checks["power balance |P_in - P_loss| / P_in, worst of the four solves"].status == "pass"
    # the comparison's own grid error: the rung's cells against finer ones, inside the tolerance it is judged by
    from ballbench.lowmodel import full_slip_validity as fsv
    from ballbench.validation.studies import case_stick_slip

    b2b_grid = checks["grid error of F_B2B (full slip - stick/slip) / stick/slip"]
    friction_grid = checks["grid error of the friction force full slip / stick/slip - 1"]
    assert (b2b_grid.tolerance, friction_grid.tolerance) == (FULL_SLIP_TOLERANCE, fsv.TOLERANCE)
    assert b2b.level == b2b_grid.level == "16 x 64 cells" and case_stick_slip.GRID_CELLS["quick"] == (24, 96)
    assert 0.0 < b2b_grid.value < 0.5 * FULL_SLIP_TOLERANCE and b2b_grid.status == friction_grid.status == "pass"
    (title, header, rows), _, (grid_title, _, grid_rows) = result.tables
    assert grid_title.startswith("Grid error") and [r[0] for r in grid_rows] == ["16 x 64", "24 x 96"]
    assert title.startswith("Per contact") and len(rows) == 4 * case.n_balls
    lam = header.index("Lambda")
    assert all(float(r[lam]) > 1.0 for r in rows)
    # the touching balls' stick/slip fields, one VTU per contact with the grid's cells (docs/render3d.md)
    import meshio

    from ballbench.validation.figures import stickslip3d

    vtus = sorted((tmp_path / "g-stick-slip").glob("stickslip_touching_*.vtu"))
    assert len(vtus) == 4 * case.n_balls
    assert {str(v.relative_to(tmp_path)) for v in vtus} <= set(result.artifacts)
    mesh = meshio.read(vtus[0])
    with np.load(tmp_path / "g-stick-slip" / "stickslip_touching.npz") as arrays:  # the solver's grid of contact 0
        cells = arrays["x_0"].size * arrays["y_0"].size
    assert len(mesh.cells[0].data) == cells and set(stickslip3d.VTU_ARRAYS) <= set(mesh.cell_data)


def test_the_stick_slip_rung_without_a_state_on_the_finer_cells_says_so(tmp_path, monkeypatch):
    # the grid error needs the module on finer cells; where it has no state there the rung says so and keeps its
    # checks on its own cells (no ERROR of the scene)
    from ballbench.lowmodel.errors import ConvergenceError
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scenes
    from ballbench.validation.studies import case_stick_slip

    def no_state(*_args, **_kwargs):
        raise ConvergenceError("stick/slip 2-ball B2B contact: Newton did not converge", residual=1.0,
                               iterations=40, tolerance=1e-9)

    monkeypatch.setattr(case_stick_slip, "grid_error", no_state)
    case = case_file.load(paths.ROOT / "examples" / "compact_linear_guide.toml")
    scenes = [s for s in ladder.case_scenes(case, "g", top="stick-slip") if s.name == "g-stick-slip"]
    (result,), _ = run_scenes(scenes, "quick", tmp_path, show_progress=False)
    assert not result.error and result.passed, result
    assert not [o for o in result.outputs if o.quantity.startswith("grid error")]
    assert any("No grid error of the comparison" in n and "24 x 96 cells" in n for n in result.notes)


@pytest.mark.slow
def test_the_stick_slip_rung_runs_on_its_fallback_cells_where_a_law_finds_no_state(tmp_path):
    # the catalogue's 12 x 2 screw: the full-slip chain stalls on 16 x 64 cells (not on 12 x 48, 20 x 80, 24 x 96):
    # the rung runs on FALLBACK_CELLS and says why, instead of an ERROR
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scenes
    from ballbench.validation.studies import case_stick_slip

    case = case_file.load(paths.ROOT / "examples" / "catalogue" / "screw_12x2.toml")
    scenes = [s for s in ladder.case_scenes(case, "s", top="stick-slip") if s.name == "s-stick-slip"]
    (result,), _ = run_scenes(scenes, "quick", tmp_path, show_progress=False)
    assert not result.error and result.passed, result
    fallback = case_stick_slip.FALLBACK_CELLS["quick"]
    checks = {o.quantity: o for o in result.outputs}
    assert checks["F_B2B"].level == f"{fallback[0]} x {fallback[1]} cells"
    assert checks["grid error of F_B2B (full slip - stick/slip) / stick/slip"].status == "pass"
    assert any(n.startswith("On 16 x 64 cells a law found no state") for n in result.notes)


def test_the_quick_level_runs_the_fe_on_the_most_loaded_contact_only(tmp_path):
    # --budget already passed: the FE rung of the screw side starts no level and says so; at quick the nut side has
    # no FE rung at all (one FE study per scene at quick, every contact at the default level)
    from ballbench.validation import ladder
    from ballbench.validation.cases import case_file as files
    from ballbench.validation.runner import run_scenes

    case = files.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-table5-a.toml")
    (scene,) = [s for s in ladder.case_scenes(case, "m", top="FE", deadline=0.0) if s.name == "m-contact"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    title, header, rows = result.tables[0]
    ran = {row[0]: row[header.index("rungs")] for row in rows}
    assert ran == {"screw side": "analytical, BEM, FE", "nut side": "analytical, BEM"}, rows
    assert any("no FE level run" in n for n in result.notes) and any("most loaded contact only" in n
                                                                         for n in result.notes)
    assert not [o for o in result.outputs if o.family == "FE"]


# --------------------------------------------------------------------------
# the FE rung's memory and size (docs/your_own_bearing.md, "Memory and time of the FE rung")
# --------------------------------------------------------------------------
def test_the_dofs_counted_on_a_mesh_are_those_of_its_p2_basis():
    # the memory guard predicts from the mesh alone; the count must be the DOFs the P2 solve assembles
    from ballbench.fem.elasticity import load_pair, vector_basis
    from ballbench.validation.studies import fe_contact

    case = case_file.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-contact-flat.toml")
    pair = fe_contact.pair_model(case)
    level = case.fe.levels["quick"][0]
    path = pair.builder(fe_contact.hertz.solve_load(pair.geometry, case.force).b / level.n, level.growth)
    assert fe_contact.mesh_dofs(path) == vector_basis(load_pair(path), order=2).N
    assert fe_contact.level_dofs(pair, level) == fe_contact.mesh_dofs(path)


def test_an_fe_level_predicted_beyond_the_available_memory_does_not_run(tmp_path, monkeypatch):
    # the guard skips the level (and those above) with a note instead of solving it; no FE solve runs here
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scenes
    from ballbench.validation.studies import fe_contact

    def no_solve(*args, **kwargs):
        raise AssertionError("an FE level ran although its predicted memory exceeds the available memory")

    monkeypatch.setattr(rungs, "available_memory", lambda: 1e9)
    monkeypatch.setattr(rungs, "predicted_memory", lambda ndofs, *_: 2e9 if ndofs > 0 else 0.0)
    monkeypatch.setattr(fe_contact, "solve_level", no_solve)
    case = case_file.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-contact-flat.toml")
    (scene,) = [s for s in ladder.case_scenes(case, "f", top="FE") if s.name == "f-contact"]
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert not result.error, result.error
    assert not [o for o in result.outputs if o.family == "FE"]
    (note,) = [n for n in result.notes if n.startswith("memory: FE levels")]
    assert "2.0 GB" in note and "1.0 GB available" in note and "DOFs" in note


def test_an_fe_level_beyond_the_scene_s_declared_memory_does_not_run(tmp_path, monkeypatch):
    # plenty available on the machine, but more than the scene declares (what a distributed worker reserves)
    from ballbench.validation import ladder
    from ballbench.validation.runner import GB, run_scenes
    from ballbench.validation.studies import fe_contact

    def no_solve(*args, **kwargs):
        raise AssertionError("an FE level ran although its predicted memory exceeds the scene's declared memory")

    case = case_file.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-contact-flat.toml")
    (scene,) = [s for s in ladder.case_scenes(case, "f", top="FE") if s.name == "f-contact"]
    declared = scene.memory_for("quick") * GB
    monkeypatch.setattr(rungs, "available_memory", lambda: 100 * declared)
    monkeypatch.setattr(rungs, "predicted_memory", lambda ndofs, *_: 2 * declared)
    monkeypatch.setattr(fe_contact, "solve_level", no_solve)
    (result,), _ = run_scenes([scene], "quick", tmp_path, show_progress=False)
    assert not result.error, result.error
    assert not [o for o in result.outputs if o.family == "FE"]
    assert any(n.startswith("memory: FE levels") and "declared by the scene" in n for n in result.notes)


def test_the_memory_of_a_level_is_predicted_from_its_dofs():
    assert rungs.predicted_memory(100_000) == rungs.BYTES_PER_DOF * 100_000
    assert rungs.predicted_memory(200_000) == 2 * rungs.predicted_memory(100_000)
    assert 0 < rungs.available_memory()


def test_a_screw_module_meshes_each_contact_in_a_slab_at_its_own_b_over_h():
    """The screw module of a case file: the elliptic slabs rungs.MODULE_SLAB about each contact's ellipse and each
    contact at its own b / h (its b over the largest b of the module's balls); a guide keeps the slabs of
    docs/fe_b2b.md on one size.  The axes of the contacts on one groove scale as Hertz's b ~ F^(1/3) (Johnson 1985
    eq 4.22; the contact angles of a side differ by the deviations only)."""
    from ballbench.validation.studies import fe_b2b_screw

    case = rungs.module_fe(case_file.load(paths.ROOT / "examples" / "catalogue" / "screw_40x20.toml"))
    assert case.fe.fine_ellipse == rungs.MODULE_SLAB and case.fe.per_contact
    assert all(level.fine_radius is None for level in case.fe.levels.quick)
    forces = np.asarray(fe_b2b_screw.low_order(case)[2].normal_force)
    b = fe_b2b_screw.module_axes(case)[:, :, 1]
    for pair in ((0, 1), (2, 3)):  # (SL, SR) on the screw, (NR, NL) on the nut
        np.testing.assert_allclose(b[:, pair[0]] / b[:, pair[1]],
                                   np.cbrt(forces[:, pair[0]] / forces[:, pair[1]]), rtol=1e-2)
    assert np.ptp(b / b.max()) > 0.2  # the module's contacts differ: the sizes do too
    guide = rungs.module_fe(case_file.load(paths.ROOT / "examples" / "catalogue" / "guide_15_light.toml"))
    assert guide.fe.fine_ellipse == (0.6, 1.3, 0.5) and not guide.fe.per_contact


def test_the_quick_study_of_a_screw_contact_keeps_its_finest_level_within_the_cap(monkeypatch):
    # three levels at a constant ratio (a Richardson study), the largest ratio whose finest mesh fits the cap
    from ballbench.validation.studies import fe_contact

    counted = []

    def dofs(pair, level):  # DOFs of a fine zone growing like n^3 (no meshing here)
        counted.append(level)
        return int(120_000 * (level.n / 5.5) ** 3)

    monkeypatch.setattr(fe_contact, "level_dofs", dofs)
    case = case_file.load(paths.ROOT / "examples" / "ball_screw_32x10.toml")
    contact = rungs.distinct_contacts(case)[0].contact
    chosen = rungs.contact_fe(contact)
    quick = chosen.fe.levels["quick"]
    assert len(quick) == 3 and {lv.growth for lv in quick} == {rungs.SCREW_QUICK_GROWTH}
    ratios = [quick[k + 1].n / quick[k].n for k in range(2)]
    assert abs(ratios[0] - ratios[1]) < 1e-12 and ratios[0] > 1
    assert dofs(None, quick[-1]) <= rungs.QUICK_DOF_CAP
    larger = [r for r in rungs.SCREW_QUICK_RATIOS if r > ratios[0] + 1e-12]
    assert all(dofs(None, type(quick[0])(quick[0].n * r * r, quick[0].growth)) > rungs.QUICK_DOF_CAP
               for r in larger)
    assert chosen.fe.fine_zone == "ellipse"  # a slender helical ellipse gets the elliptic slab (docs/fem.md)
    assert chosen.fe.levels["default"] == tuple(rungs.PairLevel(n, g) for n, g in
                                                [(n, rungs.CONTACT_LEVELS["default"][1])
                                                 for n in rungs.CONTACT_LEVELS["default"][0]])


def test_a_paper_contact_keeps_its_own_fe_settings():
    case = case_file.load(paths.ROOT / "validation" / "cases" / "files" / "lin2019-contact-nut.toml")
    assert rungs.contact_fe(case) is case


def test_the_stick_slip_rung_condenses_the_case_s_own_groove(tmp_path, monkeypatch):
    # default level: the FE compliance of a ball of the case's radius in a groove of its conformity and material,
    # over the case's largest ellipses; the condensation replaced by the half-space (operator None), so the FE rung
    # must equal the half-space rung on the same grid, and the arguments are the case's, not lin2019's steel guide
    from ballbench.lowmodel.contact import rolling
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scenes
    from ballbench.lowmodel.linear_bearing import b2b
    from ballbench.validation.studies import case_stick_slip, rolling_b2b

    calls = []

    class HalfSpace:
        ndofs = 1

        def operator(self):
            return None

    def fake(radius, conformity, along, across, cells_along, cells_across, h_factor, material):
        calls.append((radius, conformity, along, across, cells_along, cells_across, h_factor, material))
        return rolling.hertz_grid(along, across, (cells_along, cells_across)), HalfSpace(), 0.0

    monkeypatch.setattr(rolling_b2b, "pair_compliance", fake)
    text = (paths.ROOT / "examples" / "compact_linear_guide.toml").read_text()
    case = case_file.loads(text.replace('youngs_modulus = "210 GPa"', 'youngs_modulus = "200 GPa"'))
    assert case.guide.material.youngs_modulus == 200e9
    assert case_stick_slip.COMPLIANCE["quick"] == ()
    (rung,) = case_stick_slip.compliance_rungs(case, "default")
    contacts = b2b.contacts(case)
    along = float((contacts.semi_major * contacts.b_over_a).max())
    (call,) = calls
    assert call[:2] == (case.guide.ball_radius, case.guide.conformity) and call[7] == (200e9, case.guide.material
                                                                                        .poisson_ratio)
    assert call[2] == pytest.approx(1.4 * along, rel=1e-12) and call[4:6] == (8, 32)
    assert float(rung.fe.touching.b2b_force[0]) == float(rung.half_space.touching.b2b_force[0]) > 0
    (scene,) = [s for s in ladder.case_scenes(case, "g") if s.name == "g-stick-slip"]
    assert scene.memory_for("default") == ladder.STICK_SLIP_MEMORY_GB
    (result,), _ = run_scenes([scene], "default", tmp_path, show_progress=False)
    assert not result.error and result.passed, result
    fe_rows = [o for o in result.outputs if "FE compliance" in o.level and o.family == "BEM"]
    assert {o.quantity for o in fe_rows} >= {"F_B2B", "friction force, balls touching", "friction force, balls apart"}
    title, header, rows = result.tables[-1]
    assert "FE compliance" in title and [r[1] for r in rows] == ["FE compliance", "two half-spaces"]
