"""The FE rung of the whole nut (fem.nut_fe; docs/nut.md, "Elastic nut"): the balls' patches read a rigid motion
exactly, the compliance is symmetric and positive, a very stiff nut gives the rigid nut bar, a nut pushed axially
gives the bar's loads, and the elastic nut is softer than the bar."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ballbench.fem import nut_fe
from ballbench.fem import patches as rigid_patches
from ballbench.fem.elasticity import load_pair, vector_basis
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import nut as screw_nut
from ballbench.meshes.parts.nut_body import nut_body

MODULE = screw_contacts.screw_module(ball_radius=1.5875e-3, conformity=0.55, pitch_radius=8e-3, lead=5e-3,
                                     oversize=2e-6)
NUT = screw_nut.Nut(MODULE, turns=2)
# a thin-walled nut of three turns: its wall's strain decides the loads (the bar's sign of it shows)
THIN = screw_nut.Nut(MODULE, turns=3, nut_outer_radius=MODULE.pitch_radius + MODULE.ball_radius + 2.5e-3)
LOAD = 400.0
H_MAX = 2e-3  # the bore's mesh: a third of the patch radius (the default)


def test_the_patches_read_a_rigid_motion_along_the_balls_normals():
    """The operator's rows applied to a rigid motion ``u + phi x r`` give each contact point's motion along
    ``e / |e_z|`` written out from the rigid kinematics (1e-12 of the largest)."""
    shape = nut_fe.nut_shape(NUT)
    radius = nut_fe.default_patch_radius(NUT)
    path = nut_body(inner_radius=shape.inner_radius, outer_radius=shape.outer_radius, start=shape.start,
                    end=shape.end, h_max=H_MAX, h_bore=radius / 3.0)
    pair = load_pair(path, {"nut": 0})
    basis = vector_basis(pair, 2)
    operator, counts, normals = nut_fe.patch_operator(NUT, pair, basis, shape, radius)
    points, _ = nut_fe.contact_points(NUT)
    assert counts.min() >= rigid_patches.MIN_PATCH_NODES
    u, phi = np.array([2e-6, -1e-6, 0.5e-6]), np.array([3e-5, -2e-5, 4e-5])
    field = np.zeros(basis.N)
    motion = u + np.cross(phi, pair.points)
    for c in range(3):
        field[basis.nodal_dofs[c]] = motion[:, c]
    expected = np.einsum("ij,ij->i", u + np.cross(phi, points), normals) / np.abs(normals[:, 2])
    assert operator @ field == pytest.approx(expected, abs=1e-12 * np.abs(expected).max())
    assert np.all(normals[:, 2] < 0.0) and np.all(np.einsum("ij,ij->i", normals, points) > 0.0)  # to the flange, out


def test_a_very_stiff_nut_is_the_rigid_bar_and_a_steel_nut_is_softer():
    """The nut's modulus a million times steel's: the loads of a rigid nut bar (1e-5 of the largest); at steel's
    the compliance is symmetric and positive, the loads balance and the nut is softer than the bar."""
    stiff = nut_fe.compare(NUT, LOAD, h_max=H_MAX, youngs_modulus=MODULE.youngs_modulus * 1e6)
    rigid_bar = screw_nut.Nut(MODULE, turns=2, nut_outer_radius=1e3)   # a nut bar of no compliance to speak of
    expected = screw_nut.distribution(rigid_bar, LOAD, screw_nut.ball_table(MODULE, 3.0 * LOAD / NUT.balls))
    assert stiff.elastic.ball_loads == pytest.approx(expected.ball_loads, abs=1e-5 * expected.ball_loads.max())
    steel = nut_fe.compare(NUT, LOAD, h_max=H_MAX)
    matrix = steel.compliance.matrix
    assert matrix == pytest.approx(matrix.T, abs=1e-15 * np.abs(matrix).max())
    assert np.linalg.eigvalsh(matrix).min() >= -1e-12 * np.abs(matrix).max()
    assert steel.compliance.local <= steel.compliance.boussinesq
    assert steel.elastic.balance <= screw_nut.BALANCE_TOLERANCE_SINGLE
    assert steel.stiffness_elastic < steel.stiffness_bar
    assert steel.compliance.patch_nodes.min() >= rigid_patches.MIN_PATCH_NODES


def test_a_nut_pushed_axially_carries_its_balls_as_the_bar(monkeypatch):
    """Each ball pushing the nut along the axis only (no radial part): the elastic tube's loads are the bar's,
    within 3 % of the largest ball load, and the tube is loaded at the flange's end (the bar's trend: the loaded
    end's ball carries more than the far end's).  The bar with the nut's strain reversed (its force S(z) instead of
    F_a - S(z), an earlier error) is further off."""
    points = nut_fe.contact_points

    def axial(nut):
        at, normals = points(nut)
        return at, np.tile([0.0, 0.0, -1.0], (len(at), 1))

    monkeypatch.setattr(nut_fe, "contact_points", axial)
    result = nut_fe.compare(THIN, LOAD, h_max=H_MAX)
    elastic, bar = result.elastic.ball_loads, result.bar.ball_loads
    error = np.max(np.abs(bar - elastic)) / elastic.max()
    assert error < 0.025
    assert elastic[0] > elastic[-1] and bar[0] > bar[-1]
    z = THIN.module.lead * screw_nut.positions(THIN) / (2 * math.pi)
    sections, e = THIN.sections, THIN.module.youngs_modulus
    reversed_nut = ld.nut_bar_compliance(z, sections.nut_area, e, "far end")  # -int S / (E A_n)
    wrong = screw_nut.distribution(THIN, LOAD, screw_nut.ball_table(MODULE, 3.0 * LOAD / THIN.balls),
                                   nut_compliance=-reversed_nut).ball_loads   # + int S / (E A_n): the old sign
    assert np.max(np.abs(wrong - elastic)) / elastic.max() > 0.03


def test_a_nut_held_at_its_far_end_carries_its_far_balls(monkeypatch):
    """Held at the far end (both in tension) the axially pushed thin nut loads its far balls more than its first,
    the reverse of a nut held at the loaded end, and its bar is the more even distribution; the elastic nut follows
    the far-end bar within 5 % of the largest ball load (4.4 % measured: the clamp at the flange stiffens the balls
    next to it, which the bar leaves out)."""
    points = nut_fe.contact_points
    monkeypatch.setattr(nut_fe, "contact_points", lambda nut: (points(nut)[0], np.tile([0.0, 0.0, -1.0],
                                                                                       (nut.balls, 1))))
    far = nut_fe.compare(dataclasses.replace(THIN, flange="far end"), LOAD, h_max=H_MAX)
    near = nut_fe.compare(THIN, LOAD, h_max=H_MAX)
    assert far.elastic.ball_loads[-1] > far.elastic.ball_loads[0]
    assert near.elastic.ball_loads[0] > near.elastic.ball_loads[-1]
    spread = [np.ptp(r.bar.ball_loads) for r in (far, near)]
    assert spread[0] < spread[1]
    assert np.max(np.abs(far.bar.ball_loads - far.elastic.ball_loads)) < 0.05 * far.elastic.ball_loads.max()
