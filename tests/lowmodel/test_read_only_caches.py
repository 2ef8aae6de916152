"""Frozen dataclasses of lowmodel that cache data derived from their arrays hold those arrays read-only.

``@dataclass(frozen=True)`` stops ``obj.x = ...`` but not ``obj.x[0] = ...``; after such an edit a
cached geometry, friction map or interpolant would silently keep the old values.  Each check edits
one array of an object whose caches are filled and asks that whatever happens next agrees with a
fresh object built from the edited values: the in-place edit must be refused (numpy's
"assignment destination is read-only") and :func:`dataclasses.replace` gives the edited object.
Before the fix the edit went through and the next solve returned the stale answer.
"""
from __future__ import annotations

import dataclasses
import gc
import math

import numpy as np
import pytest

from ballbench.lowmodel import quadrature
from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import ball as bb
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts

RADIUS = 5e-3  # lin2019 Table 1
ANGLES = math.pi / 4 + np.array([[-0.035, 0.035, 0.0, 0.0]])  # theta = 2 deg, (BL, BR, TR, TL)
FORCES = np.array([[61.0, 80.0, 70.0, 71.0]])  # N, four-point contact


def _linear_contacts():
    contact = hertz.solve_load(hertz.ball_in_groove(RADIUS, 0.56), FORCES)
    return bearing_contacts.contacts_from_forces(ANGLES, FORCES, contact.a, contact.b / contact.a, ball_radius=RADIUS,
                                   friction_coefficient=0.1, groove_velocity=0.01)


def _edited(obj, name: str, index, factor: float):
    """``obj`` with ``obj.<name>[index] *= factor``: in place if the array lets itself be written (then
    ``obj`` itself, with whatever it cached before), else through :func:`dataclasses.replace`.
    Returns (the edited object, whether the in-place edit was refused with numpy's read-only error)."""
    try:
        getattr(obj, name)[index] *= factor
    except ValueError as error:
        assert "read-only" in str(error)
        values = getattr(obj, name).copy()
        values[index] *= factor
        return dataclasses.replace(obj, **{name: values}), True
    return obj, False


def _fresh_linear(contacts):
    arrays = (np.array(getattr(contacts, f.name)) for f in dataclasses.fields(contacts)[:4])
    return bearing_contacts.BallContacts(*arrays, contacts.ball_radius, contacts.friction_coefficient,
                                         contacts.groove_velocity)


@pytest.mark.parametrize("name, index, factor", [("normal_forces", (0, 0), 1.3), ("semi_major", (0, 1), 1.3),
                                                 ("contact_angles", (0, 0), 1.05), ("b_over_a", (0, 2), 0.9)])
def test_linear_contacts_refuse_in_place_edits_and_replace_solves_fresh(name, index, factor):
    contacts = _linear_contacts()
    before = bb.solve(contacts)  # fills kinematics, friction_at, equilibrium and its scales
    edited, refused = _edited(contacts, name, index, factor)
    state = bb.solve(edited)
    expected = bb.solve(_fresh_linear(edited))
    assert not np.allclose(expected.friction_force, before.friction_force, rtol=1e-6, atol=0.0)  # the edit matters
    for field in ("omega", "slide", "spin", "friction_force", "friction_moment", "friction_loss"):
        np.testing.assert_allclose(getattr(state, field), getattr(expected, field), rtol=1e-9, atol=1e-12 * np.max(
            np.abs(getattr(expected, field))), err_msg=field)
    assert refused, f"BallContacts.{name} took an in-place edit"


def test_linear_contacts_do_not_share_memory_with_the_caller():
    forces = FORCES.copy()
    contact = hertz.solve_load(hertz.ball_in_groove(RADIUS, 0.56), FORCES)
    axes, ratio, angles = contact.a.copy(), contact.b / contact.a, ANGLES.copy()
    contacts = bearing_contacts.BallContacts(angles, forces, axes, ratio, RADIUS, 0.1, 0.01)
    before = bb.solve(contacts)
    for array in (angles, forces, axes, ratio):
        array *= 1.1  # the caller's arrays stay writable and theirs
    np.testing.assert_array_equal(contacts.normal_forces, FORCES)
    np.testing.assert_array_equal(bb.solve(contacts).friction_force, before.friction_force)
    single = contacts.ball(0)  # views of read-only arrays stay read-only
    assert not any(getattr(single, f.name).flags.writeable for f in dataclasses.fields(single)[:4])


def _stiffness():
    loads = np.linspace(0.0, 150.0, 7)  # N
    return ld.AxialStiffness(loads, 2.0e-6 * (loads / 150.0) ** (2.0 / 3.0) + 1.0e-9 * loads / 150.0)  # m


@pytest.mark.parametrize("name, factor", [("loads", 1.2), ("shifts", 0.8)])
def test_axial_stiffness_refuses_in_place_edits(name, factor):
    stiffness = _stiffness()
    shifts = np.array([0.4e-6, 1.1e-6, 1.7e-6])
    before = stiffness.load(shifts)  # fills the pchip interpolant
    edited, refused = _edited(stiffness, name, slice(None), factor)
    expected = ld.AxialStiffness(np.array(edited.loads), np.array(edited.shifts)).load(shifts)
    assert not np.allclose(expected, before, rtol=1e-6)
    np.testing.assert_allclose(edited.load(shifts), expected, rtol=1e-12)
    assert refused, f"AxialStiffness.{name} took an in-place edit"


def test_friction_map_refuses_in_place_edits():
    table = ef.friction_map()
    mine = ef.FrictionMap(table.phi, table.log_b_over_a, table.force.copy(), table.moment, table.loss_direction,
                          0.0, False)
    before = float(mine.splines[0](0.3, -0.5)[0, 0])  # fills the patch set
    edited, refused = _edited(mine, "force", slice(None), 2.0)
    np.testing.assert_allclose(float(edited.splines[0](0.3, -0.5)[0, 0]), 2.0 * before, rtol=1e-12)
    assert refused, "FrictionMap.force took an in-place edit"
    assert not table.force.flags.writeable  # the map of friction_map() is shared by every caller


def test_short_lived_friction_maps_get_their_own_splines():
    """The patch set once lived in a dict keyed on ``id(table)``: a new map at a freed map's address got the
    freed map's splines (19 of 20 maps in this loop)."""
    table = ef.friction_map()
    unit = float(table.splines[0](0.3, -0.5)[0, 0])
    values = []
    for k in range(1, 6):
        scaled = ef.FrictionMap(table.phi, table.log_b_over_a, k * table.force, table.moment, table.loss_direction,
                                0.0, False)
        values.append(float(scaled.splines[0](0.3, -0.5)[0, 0]))
        del scaled
        gc.collect()
    np.testing.assert_allclose(values, unit * np.arange(1, 6), rtol=1e-12)


def test_cached_pair_geometry_refuses_in_place_edits():
    module = screw_contacts.screw_module()
    try:
        pair = screw_b2b.pair_geometry(module)  # lru_cache: every caller with this module shares it
        _, refused = _edited(pair, "chord", 0, 1.1)
        fresh = screw_b2b.pair_geometry.__wrapped__(module)
        np.testing.assert_array_equal(screw_b2b.pair_geometry(module).chord, fresh.chord)
        assert refused, "PairGeometry.chord took an in-place edit"
        with pytest.raises(ValueError, match="read-only"):
            pair.rotation[0, 0] = 0.0
    finally:
        screw_b2b.pair_geometry.cache_clear()  # never leave an edited geometry behind for other tests


def _instances():
    table = ef.friction_map()
    contacts = _linear_contacts()
    bb.solve(contacts)  # caches filled (its friction map is a closure: pickled as it was, this failed)
    return [(contacts, ("contact_angles", "normal_forces", "semi_major", "b_over_a")),
            (_stiffness(), ("loads", "shifts")),
            (ef.FrictionMap(table.phi, table.log_b_over_a, table.force, table.moment, table.loss_direction, 0.0,
                            False), ("phi", "log_b_over_a", "force", "moment", "loss_direction")),
            (screw_b2b.pair_geometry.__wrapped__(screw_contacts.screw_module()), ("chord", "rotation"))]


@pytest.mark.parametrize("how", ["pickle", "deepcopy"])
def test_pickled_and_deep_copied_objects_keep_read_only_arrays(how):
    """pickle and copy.deepcopy rebuild the object without ``__init__`` unless told otherwise: they must
    not hand back writable arrays (nor cached data that an edit of them would leave stale)."""
    import copy
    import pickle

    for obj, names in _instances():
        twin = pickle.loads(pickle.dumps(obj)) if how == "pickle" else copy.deepcopy(obj)
        for name in names:
            np.testing.assert_array_equal(getattr(twin, name), getattr(obj, name))
            assert not getattr(twin, name).flags.writeable, f"{type(obj).__name__}.{name} after {how}"
    contacts = _instances()[0][0]
    twin = pickle.loads(pickle.dumps(contacts)) if how == "pickle" else copy.deepcopy(contacts)
    np.testing.assert_array_equal(bb.solve(twin).friction_force, bb.solve(contacts).friction_force)



def test_cached_quadrature_rule_is_read_only():
    """``quadrature.tanh_sinh`` returns lru_cache'd arrays shared by every caller (the friction map and the offset
    friction integrals): an in-place edit (``nodes *= 2``) would silently change every later integral."""
    for array in quadrature.tanh_sinh(5):
        with pytest.raises(ValueError, match="read-only"):
            array *= 2.0
