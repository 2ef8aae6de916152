"""Meshing time of the helical, rail and four-point builders (cache off), with nodes
and tetrahedra per mesh.  Target: the default Table 4 screw pair (20 um at the
contact over the Hertz ellipse box, growth 1.3) in under 5 s.

Run: python -m pytest benchmarks/test_bench_meshes_geometry.py
"""
import math

import pytest

from ballbench.meshes.assemblies import ball_screw_module, fourpoint_module, screw_pair
from ballbench.meshes.parts import groove_segment, rail

meshio = pytest.importorskip("meshio")
pytest.importorskip("gmsh")

R_B, CONF, R_P, LEAD, BETA = 2.778e-3, 0.56, 16.5e-3, 20e-3, math.radians(45.0)  # lin2019 Table 4

CASES = {
    "screw_pair_patch_20um": lambda: screw_pair.ball_in_screw_groove_pair(
        R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=2e-5, growth=1.3, fine_patch=(4.2e-4, 9e-5), cache=False),
    "screw_pair_40um": lambda: screw_pair.ball_in_screw_groove_pair(
        R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=4e-5, growth=1.3, cache=False),
    # the segment and module cases mesh the default deep bodies (R_P -+ 5.25 R_B, since i15; before: 2 R_B,
    # about half the tetrahedra)
    "nut_segment_50um": lambda: groove_segment.screw_groove_segment(
        R_B, CONF, R_P, LEAD, BETA, "nut", h_contact=5e-5, cache=False),
    "rail_50um": lambda: rail.rail_segment(5e-3, CONF, BETA, h_contact=5e-5, cache=False),
    "fourpoint_2_balls_100um": lambda: fourpoint_module.fourpoint_module(
        5e-3, CONF, BETA, (-math.radians(2), math.radians(2), 0.0, 0.0), 2, h_contact=1e-4, cache=False),
    "ball_screw_module_2_balls_100um": lambda: ball_screw_module.ball_screw_module(
        R_B, CONF, R_P, LEAD, BETA, (0.0, math.radians(2), 0.0, 0.0), 2, h_contact=1e-4, cache=False),
}


@pytest.mark.parametrize("case", list(CASES))
def test_meshing_time(benchmark, case, tmp_path, monkeypatch):
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))
    path = benchmark.pedantic(CASES[case], rounds=3, iterations=1)
    mesh = meshio.read(path)
    tets = sum(len(block.data) for block in mesh.cells if block.type.startswith("tetra"))
    median = benchmark.stats.stats.median
    benchmark.extra_info.update(nodes=len(mesh.points), tetrahedra=tets, seconds=median)
    print(f"\n{case}: {median:.2f} s, {len(mesh.points)} nodes, {tets} tetrahedra")
    if case == "screw_pair_patch_20um":
        assert median < 5.0
