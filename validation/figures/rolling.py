"""Figures of the rolling-contact scenes (docs/rolling_contact.md): the creep curve against CONTACT's stored
``tractcurv`` output, the traction fields of lin2019's four contacts against full slip, and the map of full
slip's validity (docs/b2b_rolling.md)."""
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


def map_figure(points):
    """Per product, the largest difference over deviation and load at each (mu, conformity): B2B force and a free
    ball's friction, with the 1 % and 5 % contours; and every point's difference against Lambda.  ``points``:
    lowmodel.full_slip_validity.ValidityPoint s (those with an ``error`` are left out)."""
    fig = figure(figsize=(22, 4.4), layout="constrained")
    axes = fig.subplots(1, 5)
    products = ("linear bearing", "ball screw")
    panels = [(p, key) for p in products for key in ("b2b_difference", "friction_difference")]
    for ax, (product, key) in zip(axes[:4], panels):
        rows = [p for p in points if p.product == product and not p.error]
        mus = sorted({p.parameters["mu"] for p in rows})
        fs = sorted({p.parameters["conformity"] for p in rows})
        value = np.full((len(fs), len(mus)), np.nan)
        for p in rows:
            i, j = fs.index(p.parameters["conformity"]), mus.index(p.parameters["mu"])
            value[i, j] = np.nanmax([value[i, j], 100.0 * abs(getattr(p, key))])
        image = ax.pcolormesh(mus, fs, value, shading="nearest", cmap="viridis", vmin=0.0,
                              vmax=max(5.0, float(np.nanmax(value))))
        if len(mus) > 1 and len(fs) > 1:
            lines = ax.contour(mus, fs, value, levels=[1.0, 5.0], colors=["w", "r"], linewidths=1.5)
            ax.clabel(lines, fmt="%g %%", fontsize=8)
        fig.colorbar(image, ax=ax, label="|full slip / stick-slip - 1| [%]")
        what = "B2B force" if key == "b2b_difference" else "free ball's friction"
        ax.set_title(f"{product}: {what}\n(largest over theta and load)", fontsize=10)
        ax.set_xlabel("friction coefficient mu")
        ax.set_ylabel("conformity")
    ax = axes[4]
    for product, marker in zip(products, ("o", "s")):
        rows = [p for p in points if p.product == product and not p.error]
        ax.semilogx([p.spin_parameter for p in rows], [100 * abs(p.b2b_difference) for p in rows], marker,
                    mfc="none", label=f"{product}: B2B force")
        ax.semilogx([p.spin_parameter for p in rows], [100 * p.friction_difference for p in rows], marker,
                    ms=3, label=f"{product}: free ball's friction")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.axhline(5.0, color="r", lw=0.8, ls="--")
    ax.set_xlabel("smallest spin parameter Lambda of the contacts")
    ax.set_ylabel("|full slip / stick-slip - 1| [%]")
    ax.legend(fontsize=7)
    ax.set_title("every case against Lambda", fontsize=10)
    return fig
