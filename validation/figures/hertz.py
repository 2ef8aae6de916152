"""Pictures of the Hertz scenes."""
from __future__ import annotations

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
