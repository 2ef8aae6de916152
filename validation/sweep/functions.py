"""Case functions for sweeps (``function = "ballbench.validation.sweep.functions:<name>"`` in a spec).

Each takes scalar inputs as keywords (SI units) and returns a dict of scalar
outputs; the vectorised ones broadcast arrays.  Defaults: lin2019 Table 1
(R_B 5 mm, conformity 0.56, N_y 100 N, v 0.01 m/s, mu 0.1, steel).
"""
from __future__ import annotations

import functools
import math

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b, b2b_analytical
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import lin2019

__all__ = ["two_ball_numerical", "two_ball_deviations", "two_ball_analytical", "with_psi", "calibrated_psi",
           "whole_screw_fourier", "fourier_deviation", "FOURIER_HARMONICS", "EQUIVALENCE_SPEC"]

# keyword defaults of the case functions (lin2019 Table 1, cases.lin2019)
TABLE1 = dict(vertical_force=lin2019.VERTICAL_FORCE, **lin2019.GUIDE.keywords)
NOMINAL = lin2019.GUIDE.nominal_angle  # beta_0 [rad], lin2019 Sec 2.4

# the spec of the sweep-equivalence scene: lin2019 Sec 2.4 two-ball case by the low-order numerical model, a grid
# in (theta, rho) that reaches past the four-point limit (those cases fail with their reason) times seeded random
# top-groove deviations
EQUIVALENCE_SPEC = {
    "name": "sweep-equivalence",
    "function": "ballbench.validation.sweep.functions:two_ball_numerical",
    "chunk_size": 7,  # does not divide the case count: a short last chunk
    "outputs": ["epsilon_1", "epsilon_2", "b2b_force", "friction_increase"],
    "grid": {"theta": {"linspace": [-3.0, 3.0, 3], "unit": "deg"}, "rho": {"values": [-0.95, -0.6, 0.3]}},
    "random": {"draws": 5, "seed": 13, "inputs": {
        "top_tr": {"distribution": "normal", "mean": 0.0, "sigma": 0.5, "unit": "deg"},
        "top_tl": {"distribution": "uniform", "low": -1.0, "high": 1.0, "unit": "deg"}}},
}


@functools.lru_cache(maxsize=8)
def _load(path: str) -> cal.Calibration:
    return cal.load(path)


def calibrated_psi(calibration: str, conformity: float) -> float:
    """Psi [(m^2/N)^(1/3)] of the group ``ball-groove-<conformity>`` of a calibration file (``ballbench calibrate``)."""
    return _load(str(calibration)).value(f"ball-groove-{conformity:g}", "psi")


def with_psi(contacts: bearing_contacts.BallContacts, psi: float) -> bearing_contacts.BallContacts:
    """The same contacts with the semi-axes of ``a = psi R_B^(1/3) F^(1/3)`` (lin2019 eq 15) instead of Hertz's;
    the axis ratio b/a stays Hertz's."""
    if not (math.isfinite(psi) and psi > 0.0):
        raise ValueError(f"psi must be finite and > 0 (m^2/N)^(1/3), got {psi!r}")
    forces = contacts.normal_forces
    return bearing_contacts.contacts_from_forces(contacts.contact_angles, forces,
                                             psi * contacts.ball_radius ** (1 / 3) * forces ** (1 / 3),  # eq 15
                                             contacts.b_over_a, ball_radius=contacts.ball_radius,
                                             friction_coefficient=contacts.friction_coefficient,
                                             groove_velocity=contacts.groove_velocity)


def _two_ball(contacts: bearing_contacts.BallContacts) -> dict:
    free = bearing_ball.solve(contacts)  # balls apart (lin2019 eq 4)
    state = b2b.solve(contacts, [0.0])  # balls touching (eqs 5-10)
    return {"epsilon_1": float(free.velocity_deviation[0]), "epsilon_2": float(free.velocity_deviation[1]),
            "b2b_force": float(state.b2b_force[0]),
            "baseline_loss": float(free.groove_loss), "total_loss": float(state.total_loss),
            "friction_increase": float(state.total_loss / free.groove_loss - 1.0),  # lin2019 Fig 9(c) ratio - 1
            "iterations": float(state.iterations)}


def two_ball_numerical(theta: float, rho: float, *, top_tr: float = 0.0, top_tl: float = 0.0,
                       calibration: str | None = None, **table1) -> dict:
    """Two balls of the lin2019 Sec 2.4 case (Fig 7) by the low-order numerical model.

    ``theta`` [rad]: bottom groove ``Delta beta_BL = -theta``, ``Delta beta_BR = +theta``;
    ``rho = N_x/N_y`` of ball 1 (ball 2: ``-rho``); ``top_tr``, ``top_tl`` [rad] top-groove deviations.
    Returns epsilon_1, epsilon_2 of the free balls (Fig 8), ``b2b_force`` [N] of the touching balls
    (Fig 9a), ``baseline_loss``/``total_loss`` [W] and ``friction_increase`` = total/baseline - 1 (Fig 9c).
    Outside four-point contact ValueError; no full-sliding state ConvergenceError.
    ``calibration``: a calibration file whose ``ball-groove-<conformity>`` Psi sets the contact size.
    """
    options = {**TABLE1, **table1}
    contacts = b2b.contacts(lin2019.module_case(theta, rho, top=(top_tr, top_tl), **options))
    if calibration:
        contacts = with_psi(contacts, calibrated_psi(calibration, options["conformity"]))
    return _two_ball(contacts)


two_ball_numerical.keywords = tuple(TABLE1)  # what **table1 passes on (checked before a sweep runs)


def two_ball_deviations(d1_bl: float, d1_br: float, d1_tr: float, d1_tl: float,
                        d2_bl: float, d2_br: float, d2_tr: float, d2_tl: float, *, rho: float = 0.0,
                        **table1) -> dict:
    """Two touching balls whose four contact angles each deviate by ``dj_<contact>`` [rad] from 45 deg.

    Ball 1 (behind) carries ``N_x = rho N_y``, ball 2 ``-rho N_y`` (lin2019 Sec 2.4 loading); normal
    forces lin2017 eq 36.  Outputs as :func:`two_ball_numerical` (the tolerance Monte Carlo of docs/sweeps.md).
    Vectorised: array inputs (broadcast) give array outputs, every case equal to its scalar call.
    """
    options = {**TABLE1, **table1}
    vertical = options.pop("vertical_force")
    deviations = [d1_bl, d1_br, d1_tr, d1_tl, d2_bl, d2_br, d2_tr, d2_tl]
    if all(np.ndim(d) == 0 for d in (*deviations, rho)):
        angles = NOMINAL + np.array([deviations[:4], deviations[4:]], dtype=float)
        sides = np.array([rho, -rho]) * vertical
        contacts = bearing_contacts.ball_contacts(angles, sides, vertical, **options)
        return _two_ball(contacts)
    # arrays (a vectorised sweep chunk): every case's two balls in one BallContacts, solved as one batch; each
    # case equal to the scalar call to the last bit (b2b.solve_cases, ball.solve_cases)
    *deviations, rho = np.broadcast_arrays(*(np.asarray(d, dtype=float) for d in (*deviations, rho)))
    angles = NOMINAL + np.stack(deviations, axis=-1).reshape(-1, 2, 4)
    sides = (np.stack([rho, -rho], axis=-1) * vertical).reshape(-1)
    contacts = bearing_contacts.ball_contacts(angles.reshape(-1, 4), sides, vertical, **options)
    free = bearing_ball.solve_cases(contacts, 2)  # balls apart (lin2019 eq 4)
    touching = b2b.solve_cases(contacts, 2, [0.0])  # balls touching (eqs 5-10)
    m = rho.size
    baseline = np.ascontiguousarray(free.contact[..., 6]).reshape(m, 8).sum(axis=1)  # as BallState.groove_loss
    total = np.ascontiguousarray(touching.contact[..., 6]).reshape(m, 8).sum(axis=1) + touching.pair[:, 0, 2]
    shape = rho.shape
    return {"epsilon_1": free.ball[:, 0, 3].reshape(shape), "epsilon_2": free.ball[:, 1, 3].reshape(shape),
            "b2b_force": touching.pair[:, 0, 0].reshape(shape), "baseline_loss": baseline.reshape(shape),
            "total_loss": total.reshape(shape), "friction_increase": (total / baseline - 1.0).reshape(shape),
            "iterations": touching.iterations.astype(float).reshape(shape)}


two_ball_deviations.keywords = tuple(TABLE1)


def two_ball_analytical(theta, rho, *, top_tr=0.0, top_tl=0.0, k_f: float = b2b_analytical.K_F_PAPER,
                        psi: float | None = None, calibration: str | None = None,
                        ball_radius: float = TABLE1["ball_radius"], conformity: float = TABLE1["conformity"],
                        normal_load: float = TABLE1["vertical_force"],
                        groove_velocity: float = TABLE1["groove_velocity"],
                        friction_coefficient: float = TABLE1["friction_coefficient"],
                        youngs_modulus: float = TABLE1["youngs_modulus"],
                        poisson_ratio: float = TABLE1["poisson_ratio"]) -> dict:
    """Vectorised analytical model (lin2019 eqs 22, 30, 32, 33) of the same case; ``psi`` default: Hertz
    (lowmodel.contact.hertz.psi_constant, lin2019 eq 15).  Outputs epsilon_1, epsilon_2, b2b_force [N],
    b2b_friction_loss [W]; arrays broadcast with ``theta`` [rad] and ``rho``.  ``calibration``: a calibration
    file; its ``ball-groove-<conformity>`` Psi replaces Hertz's (an explicit ``psi`` wins)."""
    if psi is None and calibration:
        psi = calibrated_psi(calibration, conformity)
    if psi is None:
        geometry = hertz.ball_in_groove(ball_radius, conformity, youngs_modulus=youngs_modulus,
                                        poisson_ratio=poisson_ratio)
        psi = hertz.psi_constant(geometry, ball_radius)
    case = b2b_analytical.two_ball_case(theta, rho, normal_load=normal_load, groove_velocity=groove_velocity,
                                        friction_coefficient=friction_coefficient, psi=psi, ball_radius=ball_radius,
                                        k_f=k_f, delta_beta_top=(top_tr, top_tl))
    return {"epsilon_1": case.epsilon_1, "epsilon_2": case.epsilon_2, "b2b_force": case.b2b_force,
            "b2b_friction_loss": case.b2b_friction_loss}


# --------------------------------------------------------------------------
# whole ball screw with a random contact-angle deviation theta(phi)
# --------------------------------------------------------------------------
FOURIER_HARMONICS = 4  # harmonics k = 1..4 of the two loaded turns (period 4 pi / k of the screw azimuth)


def fourier_deviation(cosines, sines):
    """theta(phi) [rad] = sum_k a_k cos(k phi / 2) + b_k sin(k phi / 2), k = 1..K: a deviation of the screw
    groove's contact angle that repeats every two turns (the loaded length, lin2019 Sec 3.4), ``cosines`` a_k and
    ``sines`` b_k [rad]; lin2019 Fig 19's "four cycles over the two turns" is the single term b_4."""
    a = np.asarray(cosines, dtype=float)
    b = np.asarray(sines, dtype=float)
    k = np.arange(1, a.size + 1)

    def theta(phi):
        phase = 0.5 * np.multiply.outer(np.asarray(phi, dtype=float), k)
        return np.cos(phase) @ a + np.sin(phase) @ b

    return theta


@functools.lru_cache(maxsize=4)
def _screw_setup(calibration: str | None, n_balls: int, axial_load: float):
    """Module (lin2019 Table 4, preload fitted on Table 5 a), contact laws and axial stiffness table, once per
    worker process."""
    from ballbench.lowmodel.screw import load_distribution as ld
    laws = screw_contacts.GrooveContactLaws.from_calibration(_load(calibration)) if calibration else None
    module = screw_contacts.module(lin2019.SCREW)
    stiffness = ld.axial_stiffness(module, 3.0 * max(axial_load, 1.0) / n_balls, contact_law=laws)
    return module, laws, stiffness


def whole_screw_fourier(a1: float = 0.0, b1: float = 0.0, a2: float = 0.0, b2: float = 0.0, a3: float = 0.0,
                        b3: float = 0.0, a4: float = 0.0, b4: float = 0.0, *,
                        n_balls: int = lin2019.WHOLE_SCREW_BALLS, axial_load: float = lin2019.WHOLE_SCREW_AXIAL_LOAD,
                        duration: float = lin2019.WHOLE_SCREW_DURATION, steps: int = 50,
                        calibration: str | None = None) -> dict:
    """One ball screw of lin2019 Sec 3.4 (37 balls, 1500 N, 2 s = two nut turns; lowmodel.screw.whole_screw) whose
    screw groove deviates by theta(phi) = sum_k a_k cos(k phi/2) + b_k sin(k phi/2) [rad], k = 1..4
    (:func:`fourier_deviation`); Table 4 with the preload fitted on Table 5 (a), tilted reading.

    Outputs [N m, %]: ``peak_b2b_torque`` and ``mean_b2b_torque`` (B2B friction torque on the nut over the
    ``steps`` + 1 instants), ``mean_groove_torque``, ``peak_increase`` = max B2B / ball-groove torque [%],
    ``mean_increase`` = mean B2B / mean ball-groove torque [%], ``max_b2b_force`` [N], ``max_groups``,
    ``contact_share`` (share of instants with any B2B contact), ``max_deviation`` [rad] of theta over the screw.
    ``calibration``: a calibration file with the groups ``screw-groove``, ``nut-groove`` (calibrated contact laws).
    """
    from ballbench.lowmodel.screw import whole_screw as ws

    module, laws, stiffness = _screw_setup(calibration, int(n_balls), float(axial_load))
    theta = fourier_deviation([a1, a2, a3, a4], [b1, b2, b3, b4])
    history = ws.simulate(module, n_balls=int(n_balls), axial_load=axial_load, duration=duration, steps=int(steps),
                          reading="tilted", stiffness=stiffness, deviation=theta, contact_law=laws)
    b2b_torque, groove_torque = history.b2b_torque, history.groove_torque
    grid = np.linspace(0.0, 4.0 * math.pi, 721)
    return {"peak_b2b_torque": float(b2b_torque.max()), "mean_b2b_torque": float(b2b_torque.mean()),
            "mean_groove_torque": float(groove_torque.mean()),
            "peak_increase": float(100.0 * np.max(b2b_torque / groove_torque)),
            "mean_increase": float(100.0 * b2b_torque.mean() / groove_torque.mean()),
            "max_b2b_force": float(history.b2b_force.max()),
            "max_groups": float(max(history.groups(k) for k in range(history.time.size))),
            "contact_share": float(np.mean(np.any(history.b2b_force > 0.0, axis=1))),
            "max_deviation": float(np.max(np.abs(theta(grid))))}
