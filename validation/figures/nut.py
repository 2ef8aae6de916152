"""Figures of the whole nut (lowmodel.screw.nut; docs/nut.md): the ball loads along the nut, the axial stiffness
curve, a double nut's preload diagram and the friction torque over rotation."""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import figure

__all__ = ["ball_loads", "load_shift", "preload_diagram", "torque_over_rotation", "bar_elastic"]


def ball_loads(z, loads, title: str):
    """Each ball's axial load [N] along the nut (``z`` [m] from its loaded end)."""
    return _line(np.asarray(z) * 1e3, loads, "z from the loaded end of the nut [mm]", "axial ball load q [N]", title,
                 (8, 3.2))


def bar_elastic(z, bar, elastic, coarse=None):
    """Each ball's axial load [N] along the nut (``z`` [m]): the nut as a bar against the elastic nut (FE; and its
    coarser mesh level ``coarse``)."""
    fig = figure(figsize=(8, 3.2), layout="constrained")
    ax = fig.subplots()
    ax.plot(np.asarray(z) * 1e3, bar, "o-", ms=3, label="nut as a bar")
    ax.plot(np.asarray(z) * 1e3, elastic, "s--", ms=3, label="elastic nut (FE)")
    if coarse is not None:
        ax.plot(np.asarray(z) * 1e3, coarse, ":", lw=1, color="grey", label="elastic nut, coarser mesh")
    ax.set_xlabel("z from the loaded end of the nut [mm]")
    ax.set_ylabel("axial ball load q [N]")
    ax.legend(fontsize=7)
    ax.set_title("the nut as a bar against the elastic nut (FE rung)", fontsize=9)
    return fig


def load_shift(loads, shifts, title: str):
    """The nut's axial load [N] against its shift [m] (the axial stiffness curve)."""
    return _line(np.asarray(shifts) * 1e6, loads, "axial shift of the nut against the screw [um]", "axial load [N]",
                 title, (6, 3.4))


def _line(x, y, xlabel: str, ylabel: str, title: str, size):
    fig = figure(figsize=size, layout="constrained")
    ax = fig.subplots()
    ax.plot(x, y, "o-", ms=3)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    return fig


def preload_diagram(loads, halves, lift: float):
    """A double nut's halves' loads [N] (``halves`` (n, 2): A, B) against the axial load [N], lift-off at ``lift``."""
    fig = figure(figsize=(6, 3.4), layout="constrained")
    ax = fig.subplots()
    halves = np.asarray(halves)
    ax.plot(loads, halves[:, 0], "o-", ms=3, label="half A (loaded)")
    ax.plot(loads, halves[:, 1], "s-", ms=3, label="half B (unloading)")
    ax.axvline(lift, color="0.5", ls="--", lw=1, label=f"lift-off {lift:.4g} N")
    ax.set_xlabel("axial load on the screw [N]")
    ax.set_ylabel("load of the half [N]")
    ax.legend(fontsize=7)
    return fig


def torque_over_rotation(angle, groove, b2b):
    """The friction torque [N m] on the nut over its rotation [rad]: ball-to-groove, B2B and their sum."""
    fig = figure(figsize=(8, 3.2), layout="constrained")
    ax = fig.subplots()
    deg = np.degrees(angle)
    ax.plot(deg, np.asarray(groove) + np.asarray(b2b), "-", label="total")
    ax.plot(deg, groove, "--", label="ball-to-groove")
    ax.plot(deg, b2b, ":", label="ball-to-ball")
    ax.set_xlabel("nut rotation [deg]")
    ax.set_ylabel("friction torque [N m]")
    ax.legend(fontsize=7)
    return fig
