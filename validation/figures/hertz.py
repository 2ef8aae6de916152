"""Pictures of the Hertz scenes, and of the calibrated contact law beside Hertz's (the calibration scenes)."""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import figure


def semi_axes_vs_conformity(conformity, a_over_radius, b_over_radius,
                            title: str = "Hertz ellipse, R_B = 5 mm, F = 100 N"):
    """Semi-axes a / R_B (across the groove) and b / R_B (along it) of a ball in a straight groove over the
    conformity (log scale)."""
    fig = figure(figsize=(6, 4))
    axes = fig.subplots()
    axes.semilogy(conformity, a_over_radius, label="a / R_B (across groove)")
    axes.semilogy(conformity, b_over_radius, label="b / R_B (along groove)")
    axes.set_xlabel("conformity [-]")
    axes.set_ylabel("semi-axis / ball radius [-]")
    axes.set_title(title)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    return fig


def approach_law(law, c_hertz: float, title: str = "ball in a 0.56 groove, R_B 5 mm"):
    """Approach [um] against load [N]: Hertz ``C F^(2/3)`` (lin2019 eq 53, ``c_hertz`` [m N^-2/3]) and the
    calibrated ``law`` (lowmodel.calibration.ContactLaw)."""
    force = np.linspace(1.0, 200.0, 200)
    fig = figure(figsize=(6, 4))
    ax = fig.subplots()
    ax.plot(force, 1e6 * c_hertz * force ** (2 / 3), label="Hertz, C F^(2/3) (lin2019 eq 53)")
    ax.plot(force, 1e6 * law.approach(force), "--", label="calibrated, C F^(2/3) + C_b F")
    ax.set_xlabel("F [N]")
    ax.set_ylabel("approach [um]")
    ax.legend()
    ax.set_title(title)
    return fig
