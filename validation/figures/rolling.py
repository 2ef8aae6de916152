"""Figures of the rolling-contact scenes (docs/rolling_contact.md): the creep curve against CONTACT's stored
``tractcurv`` output, and the traction fields of lin2019's four contacts against full slip."""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import figure


def creep_figure(creepages, reference, curves: dict):
    """|F_x| / (mu F_N) against the creepage ``creepages`` [-]: the reference points ``reference`` (CONTACT's
    ``tractcurv``) and one line per entry of ``curves`` (label -> values)."""
    fig = figure(figsize=(5.5, 4), layout="constrained")
    ax = fig.add_subplot()
    xi = np.asarray(creepages) * 1e3
    ax.plot(xi, reference, "ko", label="CONTACT tractcurv.ref_out")
    for (label, values), style in zip(curves.items(), ("-", "--", ":")):
        ax.plot(xi, values, style, label=label)
    ax.set_xlabel("creepage xi [1e-3]")
    ax.set_ylabel("|F_x| / (mu F_N)")
    ax.legend()
    ax.grid(alpha=0.3)
    return fig


def contacts_figure(names, results):
    """Per contact (Kalker's frame, leading edge up): the angle between the traction and full slip's (-w/|w|),
    the stick cells, the traction arrows; ``results``: lowmodel.linear_bearing.rolling_contacts results."""
    fig = figure(figsize=(8, 8.5), layout="constrained")
    axes = fig.subplots(len(results), 1)
    image = None
    for ax, name, contact in zip(axes, names, results):
        solution = contact.solution
        X, Y = solution.grid.coordinates()
        p, w = solution.traction, solution.rigid_slip
        cross = -(p[..., 0] * w[..., 1] - p[..., 1] * w[..., 0])
        dot = -(p[..., 0] * w[..., 0] + p[..., 1] * w[..., 1])
        angle = np.where(solution.contact, np.degrees(np.arctan2(cross, dot)), np.nan)
        image = ax.pcolormesh(Y * 1e3, X * 1e3, angle, vmin=-10.0, vmax=10.0, cmap="RdBu_r", shading="nearest")
        if solution.stick.any():
            ax.plot(Y[solution.stick] * 1e3, X[solution.stick] * 1e3, "k.", ms=3)
        step = (slice(None, None, 2), slice(None, None, 4))
        ax.quiver(Y[step] * 1e3, X[step] * 1e3, p[..., 1][step], p[..., 0][step], color="k", width=0.002)
        lateral = contact.lateral_force / (solution.friction_coefficient * contact.motion.normal_force)
        ax.set_title(f"{name}: Lambda {contact.spin_parameter:.0f}, stick {solution.stick_fraction:.1%}, lateral "
                     f"force {lateral:+.3f} mu F", fontsize=9)
        ax.set_aspect("equal")
        ax.set_ylabel("x_K [mm]")
    axes[-1].set_xlabel("y_K (lateral) [mm]; x_K rolling, leading edge up")
    fig.colorbar(image, ax=axes, label="traction direction minus full slip's [deg]")
    return fig
