"""The traction's derivative along changes of the rigid slip (lowmodel.contact.rolling.solve(sensitivity_directions=),
rolling_newton.sensitivity; docs/rolling_contact.md, 'Sensitivity').

The reference is the solver itself solved twice: central differences of ``rolling.solve`` at a tight tolerance
(it never calls the sensitivity code), on every way a Newton system is solved (direct dense, dense GMRES, FFT GMRES,
the prepared low-rank form) and in partial stick, where the derivative is that of the stick/slip pattern held.
"""
from __future__ import annotations

import numpy as np
import pytest

from ballbench.lowmodel.contact import rolling, rolling_newton

pytestmark = pytest.mark.filterwarnings("error")

G, NU, MU = 82e9, 0.28, 0.3
A, B, FORCE = 0.5e-3, 1e-3, 100.0
CREEPAGES = (5e-5, -2e-5, 0.1)  # xi, eta, phi [rad/m]: partial stick (tests below assert it)
SCALES = (5e-5, 5e-5, 0.1)  # a unit change of each direction, of the creepages' size


def _contact(cells, dense):
    grid = rolling.hertz_grid(A, B, cells)
    pressure = rolling.hertz_pressure(grid, A, B, FORCE)
    operator = rolling.half_space_operator(grid, G, NU)
    w = rolling.rigid_slip(grid, *CREEPAGES)
    directions = np.stack([rolling.rigid_slip(grid, *(s if i == j else 0.0 for j, s in enumerate(SCALES)))
                           for i in range(3)], axis=-1)
    return grid, pressure, operator, w, directions


def _central(pressure, operator, w, direction, dense, step=1e-6):
    plus = rolling.solve(pressure, operator, MU, w + step * direction, tolerance=1e-14, dense=dense,
                         max_iterations=200)
    minus = rolling.solve(pressure, operator, MU, w - step * direction, tolerance=1e-14, dense=dense,
                          max_iterations=200)
    return (plus.traction - minus.traction) / (2.0 * step)


@pytest.mark.parametrize("cells, dense, path", [((12, 12), True, "direct"), ((20, 20), True, "dense GMRES"),
                                                ((30, 30), False, "FFT GMRES")])
def test_the_sensitivity_equals_central_differences_of_the_solver(cells, dense, path):
    grid, pressure, operator, w, directions = _contact(cells, dense)
    solution = rolling.solve(pressure, operator, MU, w, tolerance=1e-14, dense=dense, max_iterations=200,
                             sensitivity_directions=directions)
    n = int(solution.contact.sum())
    assert {"direct": n <= rolling.DIRECT_CELLS, "dense GMRES": rolling.DIRECT_CELLS < n <= rolling.DENSE_CELLS,
            "FFT GMRES": n > rolling.DENSE_CELLS}[path]
    assert 0.1 < solution.stick_fraction < 0.9
    scale = MU * pressure.max()
    # exact on the direct path; GMRES stops at SENSITIVITY_TOLERANCE (the difference of the central differences'
    # own solves is 1e-10 of the field)
    bound = 1e-8 if path == "direct" else 10.0 * rolling_newton.SENSITIVITY_TOLERANCE
    for j in range(3):
        reference = _central(pressure, operator, w, directions[..., j], dense)
        derivative = solution.traction_sensitivity[..., j]
        # the force, the spin moment and the field: what a ball's equilibrium sums and where it sums it
        assert np.allclose(derivative.sum(axis=(0, 1)), reference.sum(axis=(0, 1)), rtol=bound,
                           atol=0.1 * bound * np.abs(reference).sum(axis=(0, 1)).max())
        assert np.max(np.abs(derivative - reference)) < bound * scale


def test_the_prepared_low_rank_form_gives_the_same_sensitivity():
    grid, pressure, operator, w, directions = _contact((12, 12), True)
    problem = rolling_newton.TangentialProblem(operator, MU * pressure, w, True)
    plain = rolling.solve(pressure, operator, MU, w, tolerance=1e-14, dense=True, sensitivity_directions=directions)
    p = plain.traction.reshape(-1, 2)[problem.cells]
    cells = directions.reshape(-1, 2, 3)[problem.cells]
    prepared = problem.prepare()
    assert prepared.stick_inverse() is not None
    assert np.allclose(rolling_newton.sensitivity(prepared, p, cells),
                       plain.traction_sensitivity.reshape(-1, 2, 3)[problem.cells], rtol=1e-9,
                       atol=1e-9 * np.abs(cells).max() * MU * pressure.max())


def test_full_stick_is_linear():
    # full stick: the traction follows the rigid slip through the inverse compliance, linear in w
    grid, pressure, operator, _, _ = _contact((12, 12), True)
    stuck = rolling.rigid_slip(grid, 1e-9, 0.0, 0.0)
    direction = rolling.rigid_slip(grid, 1.0, 0.0, 0.0)[..., None]
    stick = rolling.solve(pressure, operator, MU, stuck, tolerance=1e-14, sensitivity_directions=direction)
    assert stick.stick_fraction == 1.0
    # linear in w in full stick: the traction at w is w times the sensitivity
    assert np.allclose(stick.traction, 1e-9 * stick.traction_sensitivity[..., 0], rtol=1e-8,
                       atol=1e-12 * np.abs(stick.traction).max())


def test_bad_directions_name_the_parameter():
    grid, pressure, operator, w, _ = _contact((12, 12), True)
    with pytest.raises(ValueError, match="sensitivity_directions"):
        rolling.solve(pressure, operator, MU, w, sensitivity_directions=np.zeros((grid.nx, grid.ny, 3)))
    with pytest.raises(ValueError, match="sensitivity_directions"):
        rolling.solve(pressure, operator, MU, w, sensitivity_directions=np.full((grid.nx, grid.ny, 2, 1), np.nan))


@pytest.mark.parametrize("cells, dense", [((20, 20), True), ((30, 30), False)])  # dense and FFT GMRES
def test_a_first_guess_or_a_kept_preconditioner_changes_nothing_beyond_the_tolerance(cells, dense):
    # a caller's first guess of the sensitivity (initial_sensitivity) and its preconditioner kept from another solve
    # on the same contact (workspace) only shorten the iterative solves: a bad guess, or line inverses built at a
    # far other creepage (another stick/slip pattern), end at the answer of a fresh solve within GMRES's tolerance
    grid, pressure, operator, w, directions = _contact(cells, dense)
    fresh = rolling.solve(pressure, operator, MU, w, tolerance=1e-12, dense=dense, sensitivity_directions=directions)
    workspace = {}
    far = rolling.rigid_slip(grid, -3e-4, 1e-4, -0.3)
    other = rolling.solve(pressure, operator, MU, far, tolerance=1e-12, dense=dense, sensitivity_directions=directions,
                          workspace=workspace)
    assert workspace and abs(other.stick_fraction - fresh.stick_fraction) > 0.1  # built on another pattern
    wrong = 2.0 * fresh.traction_sensitivity + np.roll(fresh.traction_sensitivity, 3, axis=0)
    again = rolling.solve(pressure, operator, MU, w, tolerance=1e-12, dense=dense, sensitivity_directions=directions,
                          initial_sensitivity=wrong, workspace=workspace)
    scale = MU * pressure.max()
    assert np.max(np.abs(again.traction - fresh.traction)) < 1e-10 * scale
    bound = 10.0 * rolling_newton.SENSITIVITY_TOLERANCE
    assert np.max(np.abs(again.traction_sensitivity - fresh.traction_sensitivity)) < bound * scale


def test_bad_first_guesses_and_workspaces_name_the_parameter():
    grid, pressure, operator, w, directions = _contact((12, 12), True)
    with pytest.raises(ValueError, match="initial_sensitivity"):
        rolling.solve(pressure, operator, MU, w, sensitivity_directions=directions,
                      initial_sensitivity=np.zeros((grid.nx, grid.ny, 2, 2)))
    with pytest.raises(ValueError, match="workspace"):
        rolling.solve(pressure, operator, MU, w, workspace=[])


def test_the_product_on_the_contact_cells_equals_the_whole_grid_product():
    grid, pressure, operator, _, _ = _contact((30, 30), False)
    problem = rolling_newton.TangentialProblem(operator, MU * pressure, np.zeros((grid.nx, grid.ny, 2)), False)
    v = np.random.default_rng(1).normal(size=(problem.n, 2))
    field = np.zeros((grid.nx, grid.ny, 2))
    field.reshape(-1, 2)[problem.cells] = v
    whole = operator.apply(field).reshape(-1, 2)[problem.cells]
    assert np.max(np.abs(problem.apply(v) - whole)) <= 1e-13 * np.abs(whole).max()
