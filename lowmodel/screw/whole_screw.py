"""Friction of a whole ball screw with ball-to-ball contact over time (lin2019 Sec 3.4, Figs 19-21).

The balls of the loaded track (two turns, ``4 pi`` of azimuth in the nut) form a
closed chain: the return tube joins the end of the track to its start and is
taken as zero length (lin2019: "connecting the start and end of the return
tube").  Ball ``j`` sits at nut azimuth ``psi_j`` (from the loaded end of the nut)
and at screw azimuth ``phi_j = psi_j + omega_N t``; neighbours touch when
their azimuth difference is the helix chord ``2 R_B``
(:func:`b2b.pair_geometry`), the gap being the excess.

Each time step:

1. the screw-side deviation of every ball from its screw azimuth,
   ``theta_j = amplitude sin(cycles phi_j / turns)`` for ``cycles`` over the ``turns`` (lin2019: two)
   (lin2019 Fig 19 is missing; docs/ball_screw.md);
2. the axial load of every ball from :mod:`lowmodel.screw.load_distribution`;
3. the quasi-static state of all balls with B2B contact of the touching pairs
   (:func:`b2b.solve`, ring, per-ball loads, warm start);
4. the balls advance with their orbit speeds for ``dt``; gaps follow
   ``d gap / dt = omega_B,ahead - omega_B,behind``; a gap that would become
   negative closes (set to 0) and the chain is rescaled to keep the track length
   (contact events inside a step are not resolved; 200 steps as the paper).

Friction torque on the nut: ``T = P_loss / omega_N`` (power balance of each
solve), split into ball-to-groove and B2B parts (Fig 21).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import b2b
from ballbench.lowmodel.screw import contacts as screw_contacts

__all__ = ["ScrewHistory", "simulate", "TRACK_TURNS"]

TRACK_TURNS = 2  # loaded turns of the nut (lin2019 Sec 3.4)


@dataclass(frozen=True)
class ScrewHistory:
    """Time history of the whole-screw simulation (k steps, n balls).

    time : (k,) s; nut_angle : (k,) rad (omega_N t)
    positions : (k, n) rad, nut azimuth of each ball (not wrapped; ring order)
    spacing : (k, n) rad, azimuth between ball j and the next one (ring; ``2 R_B`` chord when touching)
    b2b_force : (k, n) N, force of pair (j, next); deviation : (k, n) rad; axial_load : (k, n) N
    orbit_speed : (k, n) rad/s
    groove_torque, b2b_torque : (k,) N m, friction torque on the nut from ball-to-groove / B2B losses
    power_error : (k,) relative ``|P_in - P_loss| / P_loss`` of each solve
    iterations : (k,) Newton iterations; contact_spacing : rad
    """

    time: np.ndarray
    nut_angle: np.ndarray
    positions: np.ndarray
    spacing: np.ndarray
    b2b_force: np.ndarray
    deviation: np.ndarray
    axial_load: np.ndarray
    orbit_speed: np.ndarray
    groove_torque: np.ndarray
    b2b_torque: np.ndarray
    power_error: np.ndarray
    iterations: np.ndarray
    contact_spacing: float

    @property
    def total_torque(self) -> np.ndarray:
        return self.groove_torque + self.b2b_torque

    def groups(self, step: int) -> int:
        """Number of groups of touching balls (chains of consecutive pairs with B2B force) at ``step``."""
        touching = self.b2b_force[step] > 0.0
        if np.all(touching):
            return 1
        # count runs of True in the ring
        starts = touching & ~np.roll(touching, 1)
        return int(starts.sum())


def _deviation_of(deviation, screw_azimuth: np.ndarray) -> np.ndarray:
    # theta [rad] of each ball from the caller's function: one per ball, or one number for all of them
    theta = checks.real("deviation(phi)", deviation(screw_azimuth))
    if theta.ndim == 0:
        theta = np.full(screw_azimuth.shape, float(theta))
    if theta.shape != screw_azimuth.shape:
        raise ValueError(f"deviation(phi) must return theta [rad] of shape {screw_azimuth.shape} (one per ball) or "
                         f"one number, got shape {theta.shape}")
    return theta


def simulate(module: screw_contacts.ScrewModule, *, n_balls: int = 37, axial_load: float = 1500.0,
             duration: float = 2.0, steps: int = 200, amplitude: float = math.radians(3.0), cycles: int = 4,
             reading: str = "tilted",
             sections: ld.BarSections | None = None, stiffness: ld.AxialStiffness | None = None,
             lead_error: float = 0.0, progress=None, deviation=None,
             contact_law: screw_contacts.GrooveContactLaws | None = None, turns: int = TRACK_TURNS,
             flange: str = "loaded end") -> ScrewHistory:
    """Simulate the whole screw (lin2019 Sec 3.4; defaults: 37 balls, 1500 N, 200 steps over 2 s).

    ``amplitude`` [rad] and ``cycles`` (over the loaded turns) of the screw-side deviation,
    ``reading`` as :func:`ball.flank_angles`; ``sections``/``stiffness`` of the load
    distribution (defaults: :func:`load_distribution.bar_sections`, :func:`load_distribution.axial_stiffness`
    up to 3x the mean ball load); ``lead_error`` [m per turn] of the nut against the screw
    (:func:`load_distribution.distribute`); ``progress`` wraps the step iterator (e.g. a tqdm).
    ``deviation``: a function of the screw azimuth phi [rad] (array) giving theta [rad] in place of the
    sine of ``amplitude`` and ``cycles`` (e.g. a random Fourier series, validation.sweep.functions);
    ``contact_law``: calibrated contact laws of the grooves (:class:`ball.GrooveContactLaws`) for the
    balls and the default ``stiffness``; None: Hertz.  ``turns``: the loaded turns of the track (lin2019: 2; a whole
    nut's, lowmodel.screw.nut), the return tube again of zero length; ``flange`` where the nut is held
    (:data:`load_distribution.FLANGES`).
    """
    n = checks.count("n_balls", n_balls, 2)
    total = checks.non_negative("axial_load", axial_load, "N")
    duration = checks.positive("duration", duration, "s")
    steps = checks.count("steps", steps, 1)
    amplitude = checks.bounded("amplitude", amplitude, 0.0, math.radians(10.0), "rad", lower_closed=True,
                               upper_closed=True, note="i.e. [0, 10] deg")
    cycles = checks.count("cycles", cycles, 0)
    turns = checks.count("turns", turns, 1, 1000)
    if deviation is not None and not callable(deviation):
        raise ValueError(f"deviation must be a function of the screw azimuth phi [rad] giving theta [rad] (or None),"
                         f" got {deviation!r}")
    pair = b2b.pair_geometry(module)
    track = 2.0 * math.pi * turns
    slack = track - n * pair.azimuth_step
    if slack < 0.0:
        raise ValueError(f"n_balls = {n} do not fit in {turns} turns (at most "
                         f"{int(track / pair.azimuth_step)} balls)")
    sections = ld.bar_sections(module) if sections is None else sections
    if stiffness is None:
        stiffness = ld.axial_stiffness(module, 3.0 * max(total, 1.0) / n, contact_law=contact_law)
    gaps = np.full(n, slack / n)                     # evenly distributed (lin2019 Sec 3.4)
    first = 0.5 * gaps[0]
    dt = duration / steps
    omega_n = module.nut_speed
    records = {key: [] for key in ("time", "positions", "spacing", "force", "deviation", "load", "orbit", "groove",
                                   "b2b", "power", "iterations")}
    state = None
    iterator = range(steps + 1)
    if progress is not None:
        iterator = progress(iterator)
    for step in iterator:
        time = step * dt
        positions = first + np.concatenate([[0.0], np.cumsum(gaps[:-1] + pair.azimuth_step)])
        screw_azimuth = positions + omega_n * time
        if deviation is None:
            theta = amplitude * np.sin(cycles / turns * screw_azimuth)   # `cycles` periods over the turns
        else:
            theta = _deviation_of(deviation, screw_azimuth)
        contacts = screw_contacts.ball_contacts(module, theta, reading=reading, contact_law=contact_law)
        loads = ld.distribute(np.mod(positions, track), total, stiffness, sections, module.lead,
                              module.youngs_modulus, lead_error=lead_error, flange=flange)
        touching_gaps = np.where(gaps <= 1e-12, 0.0, gaps)
        state = b2b.solve(contacts, loads, touching_gaps, ring=True, initial=state)
        records["time"].append(time)
        records["positions"].append(positions)
        records["spacing"].append(gaps + pair.azimuth_step)
        records["force"].append(state.b2b_force)
        records["deviation"].append(theta)
        records["load"].append(loads)
        records["orbit"].append(state.orbit_speed)
        records["groove"].append(state.groove_loss / omega_n)
        records["b2b"].append(float(state.b2b_friction_loss.sum()) / omega_n)
        total_loss = state.total_loss
        records["power"].append(abs(state.input_power - total_loss) / total_loss)
        records["iterations"].append(state.iterations)
        if step == steps:
            break
        # advance: ball j's gap to the next ball (ring)
        orbit = state.orbit_speed
        rate = np.concatenate([orbit[1:], orbit[:1]]) - orbit   # omega_B of the ball ahead (ring) - omega_B
        pressed = (gaps <= 1e-12) & (state.b2b_force > 0.0)
        new_gaps = np.where(pressed, 0.0, gaps + rate * dt)
        new_gaps = np.maximum(new_gaps, 0.0)
        open_sum = new_gaps.sum()
        gaps = new_gaps * (slack / open_sum) if open_sum > 0.0 else new_gaps
        first += orbit[0] * dt - omega_n * dt
    return ScrewHistory(np.array(records["time"]), omega_n * np.array(records["time"]),
                        np.array(records["positions"]), np.array(records["spacing"]), np.array(records["force"]),
                        np.array(records["deviation"]), np.array(records["load"]), np.array(records["orbit"]),
                        np.array(records["groove"]), np.array(records["b2b"]), np.array(records["power"]),
                        np.array(records["iterations"]), pair.azimuth_step)
