"""Every gmsh builder of meshes/ across the parameter range, and every builder's mesh cache."""
from __future__ import annotations

import math

import pytest

from ballbench.meshes.assemblies import ball_screw_module, fourpoint_module, screw_pair
from ballbench.meshes.parts import groove_segment, rail
from tests.meshes.mesh_support import BETA, CONF, LEAD, R_B, R_P, R_RAIL
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


def test_builders_over_the_parameter_range():
    """Every builder meshes across conformity 0.51-0.7, contact angle 30-60 deg, lead 0-40 mm,
    screw/nut, both profile planes, one and two balls (coarse; 14.7 s CPU with the deep default bodies, 11.7 s
    with the former 2 R_B, 2026-11-23)."""
    import itertools
    for conformity, beta, lead, body, plane in itertools.product((0.51, 0.6, 0.7), (30, 45, 60), (0.0, 5e-3, 40e-3),
                                                                  ("screw", "nut"), ("normal", "axial")):
        screw_pair.ball_in_screw_groove_pair(R_B, conformity, R_P, lead, math.radians(beta), body, h_contact=2e-4,
                                          growth=1.6, profile_plane=plane, cache=False)
    for conformity, beta in itertools.product((0.51, 0.7), (30, 60)):
        groove_segment.screw_groove_segment(R_B, conformity, R_P, LEAD, math.radians(beta), "nut", cache=False)
        for n_balls in (1, 2):
            ball_screw_module.ball_screw_module(R_B, conformity, R_P, LEAD, math.radians(beta), n_balls=n_balls,
                                             cache=False)
            fourpoint_module.fourpoint_module(R_RAIL, conformity, math.radians(beta), (0.03, -0.03, 0.02, 0.0),
                                              n_balls=n_balls, cache=False)


@pytest.mark.parametrize("build", [
    lambda: rail.rail_segment(R_RAIL, CONF, BETA, h_contact=5e-4),
    lambda: groove_segment.screw_groove_segment(R_B, CONF, R_P, LEAD, BETA, "nut"),
    lambda: fourpoint_module.fourpoint_module(R_RAIL, CONF, BETA),
    lambda: ball_screw_module.ball_screw_module(R_B, CONF, R_P, LEAD, BETA),
], ids=["rail", "segment", "fourpoint", "ballscrew"])
def test_every_builder_hits_its_cache(build, monkeypatch):
    first = build()
    stamp = first.stat().st_mtime_ns

    def refuse(*args, **kwargs):
        raise AssertionError("gmsh was started for a cached mesh")

    monkeypatch.setattr(gmsh, "initialize", refuse)
    second = build()
    assert second == first and second.stat().st_mtime_ns == stamp
