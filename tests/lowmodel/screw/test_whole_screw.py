"""Static load distribution and the whole-screw simulation (lin2019 Sec 3.4)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.screw import load_distribution as ld, ball as sb, contacts as screw_contacts, whole_screw as ws
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import whole_screw
from functools import lru_cache
from hypothesis import given, strategies as st
from tests.property_support import EXTREME, SETTINGS, SLOW, call, mostly, positive, real
from tests.property_support import length


@pytest.fixture(scope="module")
def module():
    return screw_contacts.screw_module(oversize=1.7e-6)


@pytest.fixture(scope="module")
def stiffness(module):
    return ld.axial_stiffness(module, 60.0, points=7)


def test_axial_stiffness_is_the_single_ball_model(module, stiffness):
    state = sb.solve(screw_contacts.ball_contacts(module, 0.0), 33.0)
    assert stiffness.shift(33.0) == pytest.approx(state.nut_shift, rel=2e-3)   # pchip between 7 nodes
    assert stiffness.load(stiffness.shift(20.0)) == pytest.approx(20.0, rel=1e-9)


def test_distribution_compatibility_and_balance(module, stiffness):
    sections = ld.bar_sections(module)
    psi = np.sort(np.random.default_rng(1).uniform(0.0, 4 * math.pi, 12))
    loads = ld.distribute(psi, 400.0, stiffness, sections, module.lead, module.youngs_modulus)
    assert loads.sum() == pytest.approx(400.0, rel=1e-10)
    assert np.all(np.diff(loads) < 0.0)          # the balls nearest the loaded end carry most
    # compatibility, recomputed by a plain loop: shift difference = bar shortening between the balls (the nut held
    # at the loaded end: screw and nut both carry what the balls beyond have not yet handed over)
    z = module.lead * psi / (2 * math.pi)
    e = module.youngs_modulus
    handed = 0.0
    for j in range(1, len(psi)):
        handed += loads[j - 1]
        strain = (400.0 - handed) / (e * sections.screw_area) + (400.0 - handed) / (e * sections.nut_area)
        expected = stiffness.shift(loads[j]) - stiffness.shift(loads[j - 1])
        assert expected == pytest.approx(strain * (z[j] - z[j - 1]), rel=1e-6)
    stiff_bars = ld.BarSections(1e6, 1e6)
    equal = ld.distribute(psi, 400.0, stiffness, stiff_bars, module.lead, module.youngs_modulus)
    np.testing.assert_allclose(equal, 400.0 / 12, rtol=1e-6)


def test_lead_error_shifts_the_load_to_the_loaded_end(module, stiffness):
    sections = ld.bar_sections(module)
    psi = np.linspace(0.2, 12.0, 10)
    base = ld.distribute(psi, 300.0, stiffness, sections, module.lead, module.youngs_modulus)
    error = ld.distribute(psi, 300.0, stiffness, sections, module.lead, module.youngs_modulus, lead_error=2e-7)
    assert error.sum() == pytest.approx(300.0, rel=1e-10)
    assert error[0] > base[0] and error[-1] < base[-1]
    # compatibility with the lead error, recomputed by a plain loop (as in the test above)
    z = module.lead * psi / (2 * math.pi)
    e = module.youngs_modulus
    handed = 0.0
    for j in range(1, len(psi)):
        handed += error[j - 1]
        strain = (300.0 - handed) / (e * sections.screw_area) + (300.0 - handed) / (e * sections.nut_area)
        expected = strain * (z[j] - z[j - 1]) + 2e-7 * (psi[j] - psi[j - 1]) / (2 * math.pi)
        got = stiffness.shift(error[j]) - stiffness.shift(error[j - 1])
        assert got == pytest.approx(expected, rel=1e-6)


def linear_table(stiffness_n_per_m):
    """A ball of linear axial law q = k u (the table's pchip through collinear points is that line)."""
    loads = np.linspace(0.0, 400.0, 5)
    return ld.AxialStiffness(loads, loads / stiffness_n_per_m)


@pytest.mark.parametrize("flange", ld.FLANGES)
def test_two_balls_on_linear_springs_against_the_hand_solution(flange):
    """Two balls of stiffness k, L apart, the load F on the screw before the nut.  By hand (statics of the bars):
    the screw between the balls carries F - q1; the nut carries F - q1 towards a flange at the loaded end, q1 away
    from the loaded end to a far flange, so q1 - q2 = k L ((F - q1) c_s + (F - q1) c_n) or k L ((F - q1) c_s - q1
    c_n), with q1 + q2 = F.  The former sign error (the nut's q1 c_n added) fails both."""
    k, e, force = 1e8, 2e11, 100.0
    sections = ld.BarSections(1e-4, 2e-4)
    c_s, c_n = 1.0 / (e * sections.screw_area), 1.0 / (e * sections.nut_area)
    lead, psi = 0.1, np.array([1.0, 4.0])
    length = lead * 3.0 / (2 * math.pi)
    if flange == "loaded end":
        q1 = force * (1 + k * length * (c_s + c_n)) / (2 + k * length * (c_s + c_n))
    else:
        q1 = force * (1 + k * length * c_s) / (2 + k * length * (c_s + c_n))
    loads = ld.distribute(psi, force, linear_table(k), sections, lead, e, flange=flange)
    np.testing.assert_allclose(loads, [q1, force - q1], rtol=1e-9)
    assert abs(k * length * (c_s + c_n)) > 0.1   # the bars matter here (the test can tell the signs apart)


@pytest.mark.parametrize("flange", ld.FLANGES)
def test_the_nut_bar_as_a_compliance_matrix_gives_the_bar(module, stiffness, flange):
    """distribute with the nut bar's compliance matrix (its groove's moves, nut_bar_compliance) = with the bar."""
    sections = ld.bar_sections(module)
    psi = np.sort(np.random.default_rng(3).uniform(0.0, 4 * math.pi, 15))
    z = module.lead * psi / (2 * math.pi)
    bar = ld.distribute(psi, 500.0, stiffness, sections, module.lead, module.youngs_modulus, flange=flange)
    matrix = ld.nut_bar_compliance(z, sections.nut_area, module.youngs_modulus, flange, length=z.max() + 0.01)
    with_matrix = ld.distribute(psi, 500.0, stiffness, sections, module.lead, module.youngs_modulus, flange=flange,
                                nut_compliance=matrix)
    np.testing.assert_allclose(with_matrix, bar, rtol=1e-9)
    if flange == "loaded end":
        assert np.all(np.diff(bar) < 0.0)   # the balls nearest the loaded end carry most
    with pytest.raises(ValueError, match="nut_compliance"):
        ld.distribute(psi, 500.0, stiffness, sections, module.lead, module.youngs_modulus, nut_compliance=np.eye(3))
    with pytest.raises(ValueError, match="flange"):
        ld.distribute(psi, 500.0, stiffness, sections, module.lead, module.youngs_modulus, flange="middle")


def test_short_simulation(module, stiffness):
    history = ws.simulate(module, n_balls=12, axial_load=300.0, duration=0.05, steps=5, stiffness=stiffness)
    assert history.time.shape == (6,)
    assert np.all(history.power_error < 1e-8)
    assert np.all(history.b2b_force >= 0.0)
    np.testing.assert_allclose(history.spacing.sum(axis=1), 4 * math.pi, rtol=1e-12)
    assert np.all(history.spacing >= history.contact_spacing * (1 - 1e-12))
    assert np.all(history.groove_torque > 0.0)
    # touching pairs have (numerically) equal orbit speeds
    touching = history.b2b_force > 0.0
    ahead = np.roll(history.orbit_speed, -1, axis=1)
    assert np.all(np.abs((ahead - history.orbit_speed)[touching]) < 1e-8 * module.nut_speed)


def test_bad_input(module, stiffness):
    with pytest.raises(ValueError, match="n_balls"):
        ws.simulate(module, n_balls=50, steps=1, stiffness=stiffness)
    with pytest.raises(ValueError, match="total_load"):
        ld.distribute([0.1, 0.2], 1e4, stiffness, ld.bar_sections(module), module.lead, module.youngs_modulus)
    with pytest.raises(ValueError, match="nut_outer_radius"):
        ld.bar_sections(module, nut_outer_radius=0.01)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


TINY = 5e-324  # the smallest float


@pytest.fixture(scope="module")
def table():
    module = screw_contacts.screw_module(oversize=1e-6)
    return module, ld.axial_stiffness(module, 200.0, 5), ld.bar_sections(module)


@pytest.mark.filterwarnings("error")
def test_load_distribution_checks_and_reports(table):
    """bar_sections(nut_outer_radius=1e300) raised OverflowError; distribute with E = 5e-324 Pa raised
    ZeroDivisionError, with E = 1e-300 Pa scipy's RuntimeError (brentq out of iterations), with
    lead_error = 1e16 m scipy's 'f(a) and f(b) must have different signs' (bracket); a non-converged fixed
    point was returned silently; max_iterations=True and a negative lead were accepted."""
    module, stiffness, sections = table
    with pytest.raises(ValueError, match="nut_outer_radius"):
        ld.bar_sections(module, nut_outer_radius=1e300)
    args = ([0.0, 1.0], 100.0, stiffness, sections, module.lead)
    with pytest.raises(ValueError, match="youngs_modulus"):
        ld.distribute(*args, TINY)
    with pytest.raises(ValueError, match="max_iterations"):
        ld.distribute(*args, 2.1e11, max_iterations=True)
    with pytest.raises(ValueError, match="lead"):
        ld.distribute([0.0, 1.0], 100.0, stiffness, sections, -1e-3, 2.1e11)
    soft = ld.distribute(*args, 1e-300)   # bars of no stiffness: the ball at the loaded end carries everything
    assert soft[0] == pytest.approx(100.0, rel=1e-12) and abs(soft[1]) < 1e-12
    with pytest.raises(ConvergenceError):
        ld.distribute(*args, 2.1e11, tolerance=1e-300, max_iterations=1)
    for error in (1e-5, -1e-5):   # a nut whose lead is shorter or longer than the screw's (-1e-5: was the bracket)
        loads = ld.distribute([0.0, 1.0, 2.0], 100.0, stiffness, sections, module.lead, 2.1e11, lead_error=error)
        assert loads.sum() == pytest.approx(100.0, rel=1e-9)
        assert np.all(loads >= -1e-12 * 100.0)   # pchip at its end node: rounding of 1e-15 N
        assert (loads[0] > loads[2]) == (error > 0)   # a positive error unloads the far balls (docstring)
    huge = ld.distribute([0.0, 1.0, 2.0], 100.0, stiffness, sections, module.lead, 2.1e11, lead_error=1e16)
    assert huge[0] == pytest.approx(100.0, rel=1e-9)   # was scipy's bracket error: the first ball takes it all


@pytest.mark.filterwarnings("error")
def test_distribute_refuses_positions_that_swamp_the_table(table):
    """positions = [1e300] rad: scipy's 'f(a) and f(b) must have different signs' (the table's micrometre range
    is lost beside offsets of 1e288 m)."""
    module, stiffness, sections = table
    with pytest.raises(ValueError, match="positions, lead, lead_error, youngs_modulus"):
        ld.distribute([1e300], 1.0, stiffness, sections, 0.0625, 1e9)


@pytest.mark.filterwarnings("error")
def test_axial_stiffness_names_max_load(table):
    """max_load = 1e16 N: the error named solve' axial_load, not a parameter of axial_stiffness."""
    with pytest.raises(ValueError, match="max_load: axial_load: its Hertz approach"):
        ld.axial_stiffness(table[0], 1e16, 4)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@lru_cache(maxsize=1)
def _stiffness():
    module = screw_contacts.screw_module(oversize=1e-6)
    return module, ld.axial_stiffness(module, 200.0, 5), ld.bar_sections(module)


@SETTINGS
@given(positions=st.lists(mostly(real(0.0, 4.0 * math.pi), *EXTREME), min_size=0, max_size=8),
       total=mostly(real(0.0, 500.0), *EXTREME), lead=length, modulus=mostly(positive(1e9, 1e12), *EXTREME),
       lead_error=mostly(real(-1e-5, 1e-5), *EXTREME), tolerance=mostly(st.just(1e-10), 0.0, -1.0, 1e-300),
       iterations=mostly(st.just(50), -1, 0, 1, True, 2.0), screw_radius=length, outer=mostly(real(0.03, 0.1),
                                                                                              *EXTREME))
def test_load_distribution(positions, total, lead, modulus, lead_error, tolerance, iterations, screw_radius, outer):
    module, stiffness, sections = _stiffness()
    call(ld.bar_sections, module, screw_radius=screw_radius, nut_outer_radius=outer)
    call(stiffness.load, stiffness.shifts.mean())
    loads = call(ld.distribute, positions, total, stiffness, sections, lead, modulus, lead_error=lead_error,
                 tolerance=tolerance, max_iterations=iterations)
    if loads is not None:   # the balls carry the axial load between them
        assert loads.shape == (len(positions),)
        assert math.isclose(float(np.sum(loads)), total, rel_tol=1e-6, abs_tol=1e-9)


@SLOW
@given(max_load=mostly(real(1.0, 500.0), *EXTREME), points=mostly(st.integers(4, 8), -1, 0, 3, True, 4.0))
def test_axial_stiffness(max_load, points):
    module = _stiffness()[0]
    table = call(ld.axial_stiffness, module, max_load, points)
    if table is not None:
        assert np.all(np.diff(table.shifts) > 0.0) or np.all(np.diff(table.shifts) < 0.0)


@pytest.mark.slow
@SLOW
@given(n_balls=mostly(st.integers(2, 12), -1, 0, 1, True, 2.0, 100), load=mostly(real(0.0, 1000.0), *EXTREME),
       duration=mostly(real(0.01, 2.0), *EXTREME), steps=mostly(st.integers(1, 3), 0, True),
       amplitude=mostly(real(0.0, 0.05), -0.01, 0.2), cycles=mostly(st.integers(0, 6), -1, True),
       lead_error=mostly(real(-1e-5, 1e-5), *EXTREME))
def test_whole_screw(n_balls, load, duration, steps, amplitude, cycles, lead_error):
    module, stiffness, sections = _stiffness()
    history = call(whole_screw.simulate, module, n_balls=n_balls, axial_load=load, duration=duration, steps=steps,
                   amplitude=amplitude, cycles=cycles, lead_error=lead_error, stiffness=stiffness, sections=sections)
    if history is not None:
        assert np.allclose(history.axial_load.sum(axis=1), load, rtol=1e-6)


def test_solve_takes_one_load_and_gives_one_nut_shift_per_ball():
    """An array load was 'The truth value of an array ... is ambiguous'; two balls gave the mean of their nut
    shifts, where the docs (docs/ball_screw.md) promise one per ball when each ball's load is prescribed."""
    module = screw_contacts.screw_module(oversize=1.7e-6)
    contacts = screw_contacts.ball_contacts(module, [0.0, 0.01])
    with pytest.raises(ValueError, match="axial_load must be a single number"):
        sb.solve(contacts, [25.0, 25.0])
    both = sb.solve(contacts, 25.0)
    singles = [sb.solve(screw_contacts.ball_contacts(module, theta), 25.0).nut_shift for theta in (0.0, 0.01)]
    assert np.shape(both.nut_shift) == (2,)
    assert both.nut_shift == pytest.approx(singles, rel=1e-12)
    assert singles[0] != pytest.approx(singles[1], rel=1e-3)  # the deviation moves the ball: the mean was neither


def test_whole_screw_takes_a_constant_deviation_function(table):
    """A deviation function returning one number gave one ball's contacts for n balls, and the error blamed
    axial_load ('must be a scalar (total) or have shape (1,)')."""
    module, stiffness, sections = table
    options = dict(n_balls=6, axial_load=150.0, steps=1, stiffness=stiffness, sections=sections)
    constant = ws.simulate(module, deviation=lambda phi: 0.01, **options)
    assert np.all(constant.deviation == 0.01)
    same = ws.simulate(module, deviation=lambda phi: np.full(np.shape(phi), 0.01), **options)
    assert np.array_equal(constant.b2b_force, same.b2b_force)
    with pytest.raises(ValueError, match=r"deviation\(phi\) must return"):
        ws.simulate(module, deviation=lambda phi: np.zeros(3), **options)
    with pytest.raises(ValueError, match="deviation must be a function"):
        ws.simulate(module, deviation=0.01, **options)


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_stiffness_load_is_scipys_pchip_to_the_last_bit(stiffness, direction):
    """AxialStiffness.load evaluates the pchip from its coefficients (distribute's root search): the numbers of
    scipy's PchipInterpolator at 0 difference, inside the pieces, at and next to every breakpoint, beyond the table
    (extrapolated), for a table of rising and of falling shifts."""
    from scipy.interpolate import PchipInterpolator

    table = ld.AxialStiffness(stiffness.loads, direction * stiffness.shifts)
    order = np.argsort(table.shifts)
    reference = PchipInterpolator(table.shifts[order], table.loads[order])
    low, high = table.shifts.min(), table.shifts.max()
    rng = np.random.default_rng(7)
    shifts = np.concatenate([rng.uniform(low, high, 20000), table.shifts, np.nextafter(table.shifts, -np.inf),
                             np.nextafter(table.shifts, np.inf), rng.uniform(2 * low - high, 2 * high - low, 479)])
    assert np.array_equal(table.load(shifts), reference(shifts))
    assert np.array_equal(table.load(shifts.reshape(4, -1)), reference(shifts.reshape(4, -1)))
    assert np.shape(table.load(shifts[0])) == () and float(table.load(shifts[0])) == float(reference(shifts[0]))


def test_whole_screw_steps_need_no_free_rolling_start(module, stiffness):
    """After the first step every solve of the whole screw is warm-started: its new contacts never compute the
    free-rolling start (b2b._rolling_start is for a cold start only); the cold start is the free-rolling rates of
    each ball alone (ball.free_rolling_guess of BallContacts.ball) over the solve's scales."""
    from ballbench.lowmodel.screw import b2b

    built = []
    original = screw_contacts.ball_contacts

    def recording(*args, **kwargs):
        built.append(original(*args, **kwargs))
        return built[-1]

    whole_screw.screw_contacts.ball_contacts = recording
    try:
        ws.simulate(module, n_balls=8, axial_load=200.0, steps=3, stiffness=stiffness)
    finally:
        whole_screw.screw_contacts.ball_contacts = original
    built = [contacts for contacts in built if contacts.module == module]   # not a kernel's warm-up
    assert len(built) == 4
    assert "free_rolling" in built[0].solver_memo
    assert not any("free_rolling" in contacts.solver_memo for contacts in built[1:])
    contacts = built[0]
    scales = sb.scales_for(contacts, 100.0)
    start = b2b._rolling_start(contacts, scales)
    for j in range(contacts.n_balls):
        rates = sb.free_rolling_guess(contacts.ball(j))[0]
        assert np.array_equal(start[j], np.concatenate([[rates[0] / scales.orbit], rates[1:] / scales.spin]))



_HISTORY_FIELDS = ("time", "nut_angle", "positions", "spacing", "b2b_force", "deviation", "axial_load", "orbit_speed",
                   "groove_torque", "b2b_torque", "power_error", "iterations")
# two modules with the same number of balls, and two deviations (both readings) of one of them; 37 balls under 1500 N
# close gaps within the 4 steps (B2B forces, changing touching patterns)
_CACHE_CASES = {
    "a": (dict(oversize=1.7e-6), dict(amplitude=math.radians(3.0), cycles=4)),
    "b": (dict(oversize=1.2e-6, nominal_angle=math.radians(40.0), conformity=0.55),
          dict(amplitude=math.radians(3.0), cycles=4)),
    "a-rotated": (dict(oversize=1.7e-6), dict(amplitude=math.radians(2.0), cycles=3, reading="rotated")),
}
_FRESH_RUN = """
import json, sys
import numpy as np
from ballbench.lowmodel import kernels
from ballbench.lowmodel.screw import contacts as screw_contacts, load_distribution, whole_screw
module_options, options, compiled, out = json.loads(sys.argv[1])
kernels.use_kernels(compiled)
module = screw_contacts.screw_module(**module_options)
stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37, points=7)
history = whole_screw.simulate(module, n_balls=37, axial_load=1500.0, duration=0.4, steps=4, stiffness=stiffness,
                               **options)
np.savez(out, **{name: getattr(history, name) for name in %r})
""" % (_HISTORY_FIELDS,)


@pytest.mark.parametrize("compiled", [None, pytest.param(False, marks=pytest.mark.slow)])
def test_whole_screw_in_one_process_is_each_case_in_a_fresh_process(tmp_path, compiled):
    """What the whole screw's steps keep between calls (contacts.ball_contacts: the nut flanks' Hertz numbers and arc
    centres per module and ball count; b2b: the chain layouts per touching pattern, the step weights) must give
    every case its own numbers: two modules of the same ball count and two deviations (both readings) of one module,
    simulated in turn in one process (and the first again after the others), equal array for array at 0 difference
    the histories of each case run alone in a fresh process; on the default path (the compiled kernels where numba
    is installed) and on numpy's (slow)."""
    import json
    import subprocess
    import sys

    from ballbench.lowmodel import kernels

    fresh = {}
    for name, (module_options, options) in _CACHE_CASES.items():
        out = tmp_path / f"{name}.npz"
        subprocess.run([sys.executable, "-c", _FRESH_RUN, json.dumps([module_options, options, compiled, str(out)])],
                       check=True, capture_output=True, text=True)
        fresh[name] = np.load(out)
    kernels.use_kernels(compiled)
    try:
        for name in (*_CACHE_CASES, "a"):
            module_options, options = _CACHE_CASES[name]
            module = screw_contacts.screw_module(**module_options)
            stiffness = ld.axial_stiffness(module, 3.0 * 1500.0 / 37, points=7)
            history = ws.simulate(module, n_balls=37, axial_load=1500.0, duration=0.4, steps=4, stiffness=stiffness,
                                  **options)
            for field in _HISTORY_FIELDS:
                assert np.array_equal(getattr(history, field), fresh[name][field]), (name, field)
    finally:
        kernels.use_kernels(None)
    # the cases differ and close gaps: a cache shared between them, or one pattern's layout for another, would show
    for name in _CACHE_CASES:
        assert len({tuple(row > 0.0) for row in fresh[name]["b2b_force"]}) >= 2, name
    assert not np.array_equal(fresh["a"]["b2b_force"], fresh["b"]["b2b_force"])
    assert not np.array_equal(fresh["a"]["orbit_speed"], fresh["a-rotated"]["orbit_speed"])
