"""The FE contact study of a heavy or slender contact: its candidate zone and counter block sized from the Hertz
ellipse (validation.ladder.rungs.candidate_gap_limit, validation.studies.fe_contact.block_half_width;
docs/your_own_bearing.md, "Heavy contacts")."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from scipy.special import ellipe, ellipk

from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import case_file
from ballbench.validation.ladder import rungs
from ballbench.validation.studies import fe_contact

ROOT = Path(__file__).resolve().parents[3]
CATALOGUE = ROOT / "examples" / "catalogue"
TOP_LOAD = 1.5  # the largest load factor of the FE contact study's sweep (fem.hertz_case.LOAD_FACTORS)


def _contact(name: str):
    case = case_file.load(CATALOGUE / f"{name}.toml")
    return rungs.contact_fe(rungs.distinct_contacts(case)[0].contact)


def _slender_reach(e: float) -> float:
    """Hertz's separation at the end of the major semi-axis over the approach, A a^2 / delta = (K - E) / (e^2 K)
    (Johnson 1985 eqs 3.64-3.68), for the eccentricity e = sqrt(1 - (b/a)^2)."""
    m = e * e
    return (ellipk(m) - ellipe(m)) / (m * ellipk(m))


@pytest.mark.parametrize("name", ["guide_15_close", "guide_15_static_limit", "screw_16x5", "guide_30_open"])
def test_the_candidate_zone_reaches_past_the_ellipse_at_the_top_load(name):
    # along the major axis the zone ends where A x^2 = gap_limit delta; Hertz's ellipse at 1.5 times the force
    # has a_top = 1.5^(1/3) a (a ~ F^(1/3)) and its end sits where A a_top^2 = (K - E)/(e^2 K) delta_top, delta_top
    # = 1.5^(2/3) delta: the zone must reach 1.3 a_top (the fixed 1.05 delta of the papers' pairs reached about
    # 1.05 a_top on these slender ellipses and the FE contact ran into its edge)
    contact = _contact(name)
    values = rungs.hertz_values(contact)
    e = math.sqrt(1.0 - (values["b"] / values["a"]) ** 2)
    reach_over_a_top = math.sqrt(contact.fe.gap_limit / (_slender_reach(e) * TOP_LOAD ** (2.0 / 3.0)))
    assert reach_over_a_top == pytest.approx(rungs.CANDIDATE_REACH, rel=0.03)


def test_the_papers_pairs_keep_their_zone_and_block():
    # a contact case with its own [fe] table keeps its gap_limit, and a small ellipse keeps the default block
    # (the mesh cache's key, and the default run's meshes, unchanged)
    for stem in ("lin2019-contact-groove-052", "lin2019-contact-screw", "lin2019-contact-nut"):
        case = case_file.load(ROOT / "validation" / "cases" / "files" / f"{stem}.toml")
        assert rungs.contact_fe(case).fe.gap_limit == case.fe.gap_limit
        geometry = fe_contact.hertz_geometry(case)
        assert fe_contact.block_half_width(case, geometry, hertz.solve_load(geometry, case.force)) is None


def test_the_counter_block_holds_the_candidate_zone_of_a_heavy_contact():
    # 1/8-inch balls in a groove of conformity 0.515 at 171 N (a/R 0.37): the zone reaches past 0.6 R_B / 1.15
    # across the groove, so the default block of 0.6 R_B would cut it; the block grows to 1.15 times the reach
    contact = _contact("guide_15_close")
    values = rungs.hertz_values(contact)
    geometry = fe_contact.hertz_geometry(contact)
    reach = math.sqrt(contact.fe.gap_limit * values["delta"] / min(geometry.A, geometry.B))
    width = fe_contact.block_half_width(contact, geometry, hertz.solve_load(geometry, contact.force))
    assert reach > 0.6 * contact.ball_radius / 1.15
    assert width == pytest.approx(1.15 * reach, rel=1e-12)


def test_an_ellipse_the_fe_pair_cannot_hold_runs_no_fe_study_and_says_why(tmp_path):
    # the guide at its static limit (a/R 0.59): the counter block would have to pass 0.9 r_g across the groove;
    # the contact rung says so, runs no FE level and ends with its findings (before: ERROR, the builder's
    # ValueError "block_half_width must lie in (0, 0.9 r_g]")
    from ballbench.meshes.assemblies.contact_pairs import groove_block_limit
    from ballbench.validation import ladder
    from ballbench.validation.runner import run_scene

    case = case_file.load(CATALOGUE / "guide_15_static_limit.toml")
    contact = _contact("guide_15_static_limit")
    geometry = fe_contact.hertz_geometry(contact)
    width = fe_contact.block_half_width(contact, geometry, hertz.solve_load(geometry, contact.force))
    assert width > groove_block_limit(contact.ball_radius, contact.conformity)
    (scene,) = [s for s in ladder.case_scenes(case, "g", top="FE") if s.name == "g-contact"]
    result = run_scene(scene, "quick", tmp_path)
    assert not result.error and result.status() == "findings"
    assert any(note.startswith("FE study not run: the FE pair's counter block") for note in result.notes)
    assert not any(o.family == "FE" for o in result.outputs)
