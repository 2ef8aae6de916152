"""Figures of the whole carriage (lowmodel.linear_bearing.carriage; docs/carriage.md): the ball loads along the rows
the load-deflection curves and the friction over travel."""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import figure

__all__ = ["ball_loads", "load_deflection", "friction_over_travel", "rigid_elastic"]


def ball_loads(z, normal_force, labels, contacts):
    """The load [N] of each contact of every ball along the rail (``z`` [m], ``normal_force`` (rows, balls,
    contacts)), one panel per row (``labels``), one line per contact (``contacts``: names of the first row's)."""
    rows = normal_force.shape[0]
    fig = figure(figsize=(9, 2.2 * rows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, 1, sharex=True))
    for r, ax in enumerate(axes):
        for c in range(normal_force.shape[2]):
            if np.any(normal_force[r, :, c] > 0):
                ax.plot(np.asarray(z) * 1e3, normal_force[r, :, c], "o-", ms=3, color=f"C{c}", label=contacts[c])
        ax.set_ylabel("Q [N]")
        ax.set_title(labels[r], fontsize=9)
        ax.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("z along the rail [mm]")
    return fig


def load_deflection(factors, displacements, load_words: str):
    """The carriage's displacements (``displacements`` (n, 5): u_x, u_y [m], phi_x, phi_y, phi_z [rad]) against the
    load factor (``factors`` (n,)) times the case's load (``load_words``)."""
    fig = figure(figsize=(9, 3.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    for i, name in enumerate(("u_x", "u_y")):
        left.plot(factors, np.asarray(displacements)[:, i] * 1e6, "o-", ms=3, label=name)
    for i, name in enumerate(("phi_x", "phi_y", "phi_z")):
        right.plot(factors, np.asarray(displacements)[:, 2 + i] * 1e3, "o-", ms=3, label=name)
    left.set_ylabel("translation [um]")
    right.set_ylabel("rotation [mrad]")
    for ax in (left, right):
        ax.set_xlabel(f"load factor ({load_words})")
        ax.legend(fontsize=7)
    return fig


def friction_over_travel(travel, force, force_alone, complete, sinking, parted=None):
    """The carriage's drive force [N] over the balls' travel [m] (``force`` with B2B contact, ``force_alone`` every
    ball alone or None; ``complete`` (steps,) bool: hollow markers where the step is approximate; ``parted`` (steps,)
    bool: crosses where touching balls were solved in separate chains) and the carriage's vertical displacement
    ``sinking`` [m] (the ball passage's ripple)."""
    fig = figure(figsize=(9, 3.4), layout="constrained")
    left, right = fig.subplots(1, 2)
    t = np.asarray(travel) * 1e3
    complete = np.asarray(complete, dtype=bool)
    left.plot(t, force, "-", color="C0", label="with B2B contact")
    left.plot(t[complete], np.asarray(force)[complete], "o", ms=4, color="C0")
    left.plot(t[~complete], np.asarray(force)[~complete], "o", ms=4, mfc="none", color="C0",
              label="approximate (see the crosses, or a ball without a state)")
    if parted is not None and np.any(parted):
        parted = np.asarray(parted, dtype=bool)
        left.plot(t[parted], np.asarray(force)[parted], "x", ms=8, color="C3",
                  label="touching balls in separate chains")
    if force_alone is not None:
        left.plot(t, force_alone, "s--", ms=3, color="C1", label="every ball alone (no B2B)")
    left.set_ylabel("drive force [N]")
    right.plot(t, np.asarray(sinking) * 1e6, "o-", ms=3, color="C2")
    right.set_ylabel("u_y of the carriage [um]")
    for ax in (left, right):
        ax.set_xlabel("travel of the balls [mm]")
    left.legend(fontsize=7)
    return fig


def rigid_elastic(z, rigid, elastic, labels):
    """Each ball's largest contact load [N] along the rail (``z`` [m]; ``rigid``, ``elastic`` (rows, balls)): the
    rigid carriage against the elastic one, one panel per row (``labels``)."""
    rows = np.asarray(rigid).shape[0]
    fig = figure(figsize=(9, 2.2 * rows), layout="constrained")
    axes = np.atleast_1d(fig.subplots(rows, 1, sharex=True))
    for r, ax in enumerate(axes):
        ax.plot(np.asarray(z) * 1e3, np.asarray(rigid)[r], "o-", ms=3, label="rigid carriage")
        ax.plot(np.asarray(z) * 1e3, np.asarray(elastic)[r], "s--", ms=3, label="elastic carriage (FE)")
        ax.set_ylabel("Q max [N]")
        ax.set_title(labels[r], fontsize=9)
        ax.legend(fontsize=7, loc="upper left")
    axes[-1].set_xlabel("z along the rail [mm]")
    return fig
