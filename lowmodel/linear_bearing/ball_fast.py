"""The compiled path of the linear-bearing ball and B2B solves: their data as flat arrays, and batches.

:func:`solve_free` (balls alone, lin2019 eq 4) and :func:`solve_chains` (open B2B chains, eqs 4-10) run the
kernels of :mod:`lowmodel.linear_bearing.ball_kernels` on many independent cases at once: a one-case solve of
:mod:`lowmodel.linear_bearing.ball` or :mod:`lowmodel.linear_bearing.b2b` is a batch of one, a Monte Carlo chunk
a batch of many, and both give the same numbers to the last bit.  Both return None where the kernels are
not available (:func:`lowmodel.kernels.load`: no numba, or switched off); then the callers run their numpy
code.  A case whose kernel solve fails (``status`` not 0) is solved again by the caller's numpy path, which
has the continuation and names the failure.
"""
from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks, kernels
from ballbench.lowmodel.b2b_chain import COMPLEMENTARITY_SCALE
from ballbench.lowmodel.linear_bearing.contacts import BallContacts, contacts_from_forces

__all__ = ["compiled", "geometry", "solve_free", "solve_chains", "CaseStates", "KERNELS", "empty_states",
           "store_state", "case_contacts", "case_reference_forces"]

KERNELS = "linear_bearing.ball_kernels"


@dataclass(frozen=True)
class CaseStates:
    """Converged states of ``m`` cases of ``n`` balls from the kernels [SI] (the fields of
    :class:`lowmodel.linear_bearing.ball.BallState`); cases with ``status != 0`` hold no state.

    status, iterations, residual, input_power : (m,);  ball : (m, n, 4) v_B, omega_x, omega_y, epsilon;
    contact : (m, n, 4, 7) spin, slide, c/a, friction force, friction moment, eq A6 loss, friction loss;
    pair : (m, n - 1, 3) F_B2B, B2B slip, B2B loss (zeros for balls alone)
    """

    status: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    input_power: np.ndarray
    ball: np.ndarray
    contact: np.ndarray
    pair: np.ndarray


def compiled():
    """The kernel module (:mod:`lowmodel.linear_bearing.ball_kernels`), or None (the numpy path runs)."""
    return kernels.load(KERNELS)


def geometry(contacts: BallContacts) -> np.ndarray:
    """(n, 4, FIELDS), read-only, cached on ``contacts`` (:attr:`BallContacts.kernel_geometry`): the layout of
    :mod:`lowmodel.linear_bearing.ball_kernels`."""
    return contacts.kernel_geometry


def _scalars(contacts: BallContacts, reference) -> np.ndarray:
    reference = np.atleast_1d(np.asarray(reference, dtype=float))
    scalars = np.empty((reference.size, 4))
    scalars[:, 0] = contacts.groove_velocity
    scalars[:, 1] = contacts.ball_radius
    scalars[:, 2] = contacts.friction_coefficient
    scalars[:, 3] = reference
    return scalars


def _tables():
    from ballbench.lowmodel.contact.ellipse_friction import patch_table

    nodes_x, _, mid_x, mid_y, flat = patch_table()
    return nodes_x, mid_x, mid_y.size, flat


def empty_states(m: int, b: int) -> CaseStates:
    """:class:`CaseStates` of ``m`` cases of ``b`` balls, all zero (status 0)."""
    return CaseStates(np.zeros(m, dtype=np.int64), np.zeros(m, dtype=np.int64), np.zeros(m), np.zeros(m),
                      np.zeros((m, b, 4)), np.zeros((m, b, 4, 7)), np.zeros((m, max(b - 1, 0), 3)))


def solve_free(contacts: BallContacts, balls_per_case: int, reference_force, *, tolerance: float,
               max_iterations: int) -> CaseStates | None:
    """Cases of ``balls_per_case`` balls (balls ``c b .. c b + b - 1`` of ``contacts`` are case ``c``), every
    ball alone (lin2019 eq 4, :func:`lowmodel.linear_bearing.ball.solve`); ``reference_force`` [N] the unit of
    each case's force residuals, (m,) or a scalar for one case.  None without kernels."""
    module = compiled()
    if module is None:
        return None
    scalars = _scalars(contacts, reference_force)
    out = empty_states(scalars.shape[0], balls_per_case)
    module.solve_free_cases(geometry(contacts), balls_per_case, scalars, float(tolerance), int(max_iterations),
                            *_tables(), out.status, out.iterations, out.residual, out.ball, out.contact,
                            out.input_power)
    return out


_SCRATCH = threading.local()


def _workspace(module, balls_per_case: int) -> np.ndarray:
    """The chain Newton's scratch (``ball_kernels.workspace_size``), kept per thread and reused by later solves of
    chains as long or shorter: the first touch of fresh memory of this size costs more than the block LU."""
    size = module.workspace_size(balls_per_case)
    work = getattr(_SCRATCH, "work", None)
    if work is None or work.size < size:
        work = np.empty(size)
        _SCRATCH.work = work
    return work


def solve_chains(contacts: BallContacts, balls_per_case: int, live, reference_force, *, tolerance: float,
                 max_iterations: int) -> CaseStates | None:
    """Cases of open B2B chains of ``balls_per_case`` balls (lin2019 eqs 4-10; the first two attempts of
    :func:`lowmodel.linear_bearing.b2b.solve`); ``live`` (b,) bool, pair (j, j+1) of every case touches;
    ``reference_force`` as :func:`solve_free`.  None without kernels."""
    module = compiled()
    if module is None:
        return None
    scalars = _scalars(contacts, reference_force)
    out = empty_states(scalars.shape[0], balls_per_case)
    module.solve_chain_cases(geometry(contacts), balls_per_case, np.asarray(live, dtype=np.bool_),
                             scalars, COMPLEMENTARITY_SCALE, float(tolerance), int(max_iterations), *_tables(),
                             out.status, out.iterations, out.residual, out.ball, out.contact, out.pair,
                             out.input_power, _workspace(module, balls_per_case))
    return out


def warm_up(module) -> None:
    """Compile (or load from the cache) the kernels for the argument types of :func:`solve_free` and
    :func:`solve_chains`."""
    contacts = contacts_from_forces(np.full((2, 4), np.pi / 4), 100.0, 4e-4, 0.2, ball_radius=5e-3,
                                    friction_coefficient=0.1, groove_velocity=0.01)
    scalars = _scalars(contacts, 100.0)
    out = empty_states(1, 2)
    module.solve_free_cases(geometry(contacts), 2, scalars, 1e-12, 2, *_tables(), out.status, out.iterations,
                            out.residual, out.ball, out.contact, out.input_power)
    module.solve_chain_cases(geometry(contacts), 2, np.array([True, False]), scalars, COMPLEMENTARITY_SCALE, 1e-12, 2,
                             *_tables(), out.status, out.iterations, out.residual, out.ball, out.contact, out.pair,
                             out.input_power, np.empty(0))


def store_state(states: CaseStates, case: int, state) -> None:
    """Write the fields of ``state`` (a :class:`lowmodel.linear_bearing.ball.BallState`) into case ``case`` of
    ``states`` and mark it solved (status 0)."""
    states.status[case] = 0
    states.iterations[case] = state.iterations
    states.residual[case] = state.residual
    states.input_power[case] = state.input_power
    states.ball[case, :, 0] = state.ball_velocity
    states.ball[case, :, 1:3] = state.omega
    states.ball[case, :, 3] = state.velocity_deviation
    for k, field in enumerate((state.spin, state.slide, state.c_over_a, state.friction_force, state.friction_moment,
                               state.friction_loss_table, state.friction_loss)):
        states.contact[case, :, :, k] = field
    for k, field in enumerate((state.b2b_force, state.b2b_slip, state.b2b_friction_loss)):
        states.pair[case, :, k] = field


def case_contacts(contacts: BallContacts, balls_per_case: int, case: int) -> BallContacts:
    """The contacts of case ``case`` alone: balls ``case b .. case b + b - 1``."""
    part = slice(case * balls_per_case, (case + 1) * balls_per_case)
    return BallContacts(contacts.contact_angles[part], contacts.normal_forces[part], contacts.semi_major[part],
                        contacts.b_over_a[part], contacts.ball_radius, contacts.friction_coefficient,
                        contacts.groove_velocity)


def case_reference_forces(contacts: BallContacts, balls_per_case: int) -> np.ndarray:
    """(m,) N: the largest normal force of each case, the unit of its force residuals (as a one-case solve);
    ValueError unless ``balls_per_case`` divides the number of balls."""
    b = checks.count("balls_per_case", balls_per_case, 1)
    if contacts.n_balls % b:
        raise ValueError(f"balls_per_case = {b} must divide the number of balls, {contacts.n_balls}")
    return contacts.normal_forces.reshape(contacts.n_balls // b, b * 4).max(axis=1)
