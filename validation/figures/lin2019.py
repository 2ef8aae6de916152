"""Pictures of the lin2019 scenes: the analogues of the paper's Figs 5, 8-10 and 20-21, and the solver maps."""
from __future__ import annotations

import math

import numpy as np

from ballbench.validation.figures.style import figure


def whole_screw_spacing(history):
    """Fig 20 analogue: the angular distance [deg] of each ball to the next over the nut angle, B2B contacts
    marked (``history``: lowmodel.screw.whole_screw.simulate's result)."""
    degrees = np.degrees(history.nut_angle)
    fig = figure(figsize=(9, 4.5))
    ax = fig.subplots()
    spacing = np.degrees(history.spacing)
    for ball in range(spacing.shape[1]):
        ax.plot(degrees, spacing[:, ball], color="0.75", lw=0.6)
    touching = history.b2b_force > 0.0
    steps_idx, balls_idx = np.nonzero(touching)
    ax.scatter(degrees[steps_idx], spacing[steps_idx, balls_idx], s=4, color="k", label="B2B contact")
    ax.set_xlabel("nut rotation angle [deg]")
    ax.set_ylabel("angular distance to the next ball [deg]")
    ax.set_title("lin2019 Fig 20: angular distance between neighbouring balls")
    ax.legend(loc="upper right")
    return fig


def whole_screw_torque(history):
    """Fig 21 analogue: total, ball-to-groove and ball-to-ball friction torque [mN m] over the nut angle."""
    degrees = np.degrees(history.nut_angle)
    fig = figure(figsize=(9, 4.5))
    ax = fig.subplots()
    ax.plot(degrees, 1e3 * history.total_torque, "k", label="total")
    ax.plot(degrees, 1e3 * history.groove_torque, "b--", label="ball-to-groove")
    ax.plot(degrees, 1e3 * history.b2b_torque, "r", label="ball-to-ball")
    ax.set_xlabel("nut rotation angle [deg]")
    ax.set_ylabel("friction torque [mN m]")
    ax.set_title("lin2019 Fig 21: friction torque")
    ax.legend()
    return fig


def friction_vs_c_over_a(kappa_full, kappa_zoom, curves: dict, k_ls: float):
    """Fig 5 analogue: friction force and spin moment of a Hertz ellipse against c/a for each conformity
    (``curves[conformity] = (result over kappa_full, result over kappa_zoom)``, lowmodel.contact.ellipse_friction
    results), and the least-squares slope ``k_ls`` over the shaded fit range |c/a| <= 0.5."""
    fig = figure(figsize=(11, 4.5), layout="constrained")
    full, zoom = fig.subplots(1, 2)
    for conformity, results in curves.items():
        for axes, kappa, result in ((full, kappa_full, results[0]), (zoom, kappa_zoom, results[1])):
            axes.plot(kappa, result.force, label=f"force, conf {conformity}")
            axes.plot(kappa, result.moment, "--", label=f"moment, conf {conformity}")
    zoom.plot(kappa_zoom, -k_ls * kappa_zoom, "k:", label=f"-{k_ls:.3f} c/a (least squares, conf 0.56)")
    zoom.axvspan(-0.5, 0.5, color="0.9", zorder=0)
    for axes in (full, zoom):
        axes.set_xlabel("c/a")
        axes.grid(True, alpha=0.3)
    full.set_ylabel("f_z/(sgn(omega) mu F),  M_O/(sgn(omega) mu F a)")
    zoom.set_ylim(-1.1, 1.1)
    zoom.legend(fontsize=6)
    full.set_title("lin2019 Fig 5(a) equivalent")
    zoom.set_title("Fig 5(b): |c/a| <= 1, fit range shaded")
    return fig


def analytical_maps(rho, theta_deg, case, marker):
    """Figs 8(b) and 9(b) analogues of the analytical model: epsilon_1 - epsilon_2 [%] and F_B2B [N] over
    (rho, theta [deg]) (``case``: lowmodel.linear_bearing.b2b_analytical.two_ball_case on the grid), the Table 3
    case marked at ``marker = (rho, theta [deg])``."""
    fig = figure(figsize=(12, 4.5), layout="constrained")
    left, right = fig.subplots(1, 2)
    image = left.contourf(rho, theta_deg, 100 * (case.epsilon_1 - case.epsilon_2), 21, cmap="RdBu_r")
    fig.colorbar(image, ax=left, label="epsilon_1 - epsilon_2 [%]")
    left.set_title("Fig 8(b) equivalent: analytical eq 33")
    image = right.contourf(rho, theta_deg, case.b2b_force, 21, cmap="viridis")
    fig.colorbar(image, ax=right, label="F_B2B [N]")
    right.set_title("Fig 9(b) equivalent: analytical eq 30 (k_f = 1.38)")
    for axes in (left, right):
        axes.set_xlabel("rho = N_x/N_y")
        axes.set_ylabel("theta [deg]")
        axes.plot([marker[0]], [marker[1]], "k*")
    return fig


def velocity_deviation_maps(rhos, theta_deg, numerical, analytical):
    """Fig 8 analogue: epsilon_1 - epsilon_2 [%] over (rho, theta [deg]), low-order numerical (``numerical``) and
    analytical eq 33 (``analytical``), both (n_theta, n_rho) relative values, NaN outside four-point contact."""
    fig = figure(figsize=(10, 4))
    axes = fig.subplots(1, 2, sharey=True)
    vmax = float(np.nanmax(np.abs(analytical))) * 100
    for ax, values, title in ((axes[0], numerical, "(a) low-order numerical"), (axes[1], analytical,
                                                                                "(b) analytical, eq 33")):
        mesh = ax.pcolormesh(rhos, theta_deg, values * 100, shading="nearest", cmap="RdBu_r", vmin=-vmax, vmax=vmax)
        ax.set_xlabel("side force ratio rho = N_x / N_y")
        ax.set_title(title)
    axes[0].set_ylabel("contact angle deviation theta [deg]")
    fig.colorbar(mesh, ax=axes, label="epsilon_1 - epsilon_2 [%]")
    return fig


def gap_histories(histories: dict, ball_radius: float, analytical_times):
    """Fig 10 analogue: the gap between two balls / R_B over time for each case (``histories[label]``:
    lowmodel.linear_bearing.b2b.simulate_gaps results) and the analytical case (a) line through
    ``analytical_times = (0, contact time, end)`` [s]."""
    fig = figure(figsize=(6, 4))
    ax = fig.subplots()
    for label, history in histories.items():
        ax.plot(history.times, history.gaps[:, 0] / ball_radius, marker="o", ms=3,
                label=f"case ({label})" + (" mitigated top groove" if label == "b" else ""))
    ax.plot(list(analytical_times), [0.1, 0.0, 0.0], ls="--", c="grey", label="case (a), analytical eq 33")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("gap between the balls / R_B")
    ax.set_ylim(bottom=-0.005)
    ax.legend()
    ax.set_title("lin2019 Fig 10: theta = 2 deg, rho = -0.6, low-order numerical velocities")
    return fig


def b2b_maps(rho_grid, theta_grid, force, ratio, stick=None):
    """Fig 9 analogue: F_B2B [N] and total / baseline friction loss over (rho, theta [deg]) grid points, the points
    without a state (NaN) crossed in red, those whose state is the stick/slip law's (``stick``, bool) circled."""
    fig = figure(figsize=(10, 4.6), layout="constrained")
    axes = fig.subplots(1, 2)
    for ax, values, title, label in ((axes[0], force, "(a) F_B2B, low-order numerical", "F_B2B [N]"),
                                     (axes[1], ratio, "(c) total / baseline friction loss", "ratio [-]")):
        mesh = ax.scatter(rho_grid.ravel(), theta_grid.ravel(), c=values.ravel(), s=18, cmap="viridis", marker="s")
        bad = np.isnan(values.ravel())
        ax.scatter(rho_grid.ravel()[bad], theta_grid.ravel()[bad], s=10, marker="x", c="red",
                   label="no state computed (no full-sliding state)")
        if stick is not None and np.any(stick):
            marked = np.asarray(stick).ravel()
            ax.scatter(rho_grid.ravel()[marked], theta_grid.ravel()[marked], s=40, facecolors="none",
                       edgecolors="k", linewidths=0.8, label="stick/slip on a half-space (no full-sliding state)")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), fontsize=7)
        fig.colorbar(mesh, ax=ax, label=label)
        ax.set_xlabel("rho = N_x / N_y")
        ax.set_title(title)
    axes[0].set_ylabel("theta [deg]")
    return fig


def law_row(rho, full, stick_slip, theta_deg: float):
    """One Fig 9 row by both contact laws: F_B2B [N] and total / baseline friction loss against rho, lin2019's full
    sliding (``full`` = (force, ratio), NaN where it has no state) and the stick/slip law (``stick_slip``, likewise)."""
    fig = figure(figsize=(10, 3.8), layout="constrained")
    axes = fig.subplots(1, 2)
    for ax, index, label in ((axes[0], 0, "F_B2B [N]"), (axes[1], 1, "total / baseline friction loss [-]")):
        ax.plot(rho, full[index], "s-", ms=4, label="full sliding (lin2019 eqs 4-10)")
        ax.plot(rho, stick_slip[index], "o--", ms=5, mfc="none", label="stick/slip on a half-space")
        ax.set_xlabel("rho = N_x / N_y")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
    fig.suptitle(f"lin2019 Table 1, theta = {theta_deg:.2f} deg: both laws towards the four-point limit")
    return fig


def converged_region(rho, theta, ratio, converged, ratio_floor: float):
    """The single-ball solver's converged grid points over (rho, theta [deg]) with the spin-capacity ratio 1 and
    ``ratio_floor`` contours and the four-point limit of lin2017 eq 37 (beta_BL = 45 - theta, beta_BR = 45 + theta,
    top at 45 deg)."""
    fig = figure(figsize=(7, 5), layout="constrained")
    axes = fig.subplots()
    axes.scatter(rho[converged], theta[converged], s=8, c="tab:green", marker="s", label="converged")
    axes.scatter(rho[~converged], theta[~converged], s=22, c="tab:red", marker="x", label="ConvergenceError")
    axes.plot([], [], "k-", label="spin-capacity ratio 1")
    axes.plot([], [], "--", c="grey", label=f"spin-capacity ratio {ratio_floor}")
    contour = axes.contour(rho, theta, ratio, levels=[1.0, ratio_floor], colors=["k", "grey"],
                           linestyles=["-", "--"])
    axes.clabel(contour, fmt={1.0: "ratio 1", ratio_floor: f"{ratio_floor}"}, fontsize=7)
    thetas = np.radians(np.linspace(0.0, 40.0, 200))
    axes.plot(-np.tan(math.pi / 4 - thetas), np.degrees(thetas), "b:", label="four-point limit (lin2017 eq 37)")
    axes.plot(np.ones_like(thetas), np.degrees(thetas), "b:")
    axes.set_xlabel("rho = N_x / N_y (ball 1)")
    axes.set_ylabel("theta [deg] (beta_BL = 45 - theta, beta_BR = 45 + theta)")
    axes.set_title("Single ball, lin2019 Table 1: converged region and spin-capacity boundary")
    axes.legend(fontsize=7, loc="upper left")
    return fig
