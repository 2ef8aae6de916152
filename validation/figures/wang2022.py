"""Pictures of the wang2022 scenes: Fig 4 (centrifugal force), Figs 5-9 (parameter trends), the methods compared."""
from __future__ import annotations

from ballbench.validation.figures.style import figure


def centrifugal_force(speeds_rpm, curves: dict):
    """Fig 4 analogue: ball centrifugal force [N] against screw speed [rpm], one curve per contact angle
    (``curves[alpha in deg] = forces``)."""
    fig = figure(figsize=(6, 4))
    axes = fig.subplots()
    for degrees, forces in curves.items():
        axes.plot(speeds_rpm, forces, label=f"alpha = {degrees} deg")
    axes.set_xlabel("screw speed [rpm]")
    axes.set_ylabel("centrifugal force F_n [N]")
    axes.set_title("wang2022 Fig 4: ball centrifugal force (Table A1)")
    axes.grid(True, alpha=0.3)
    axes.legend()
    return fig


def trend_figure(values, x_label, results, title, x_scale=1.0, nominal=None):
    """Slide-roll ratios and entrainment velocities of nut (A) and screw (B) against one varied input ``values``
    (shown times ``x_scale``; ``nominal``: the Table A1 value, marked)."""
    fig = figure(figsize=(10, 3.8), layout="constrained")
    left, right = fig.subplots(1, 2)
    x = values * x_scale
    left.plot(x, results.slide_roll_nut, label="S_A (nut)")
    left.plot(x, results.slide_roll_screw, "--", label="S_B (screw)")
    left.set_ylabel("slide-roll ratio [-]")
    right.plot(x, results.entrainment_nut, label="U_A (nut)")
    right.plot(x, results.entrainment_screw, "--", label="U_B (screw)")
    right.set_ylabel("entrainment velocity [m/s]")
    for axes in (left, right):
        if nominal is not None:
            axes.axvline(nominal * x_scale, color="0.6", lw=0.8, ls=":", label="Table A1")
        axes.set_xlabel(x_label)
        axes.grid(True, alpha=0.3)
        axes.legend()
    fig.suptitle(title)
    return fig


def methods_figure(leads, present, wei, bearing):
    """U and S of the three methods against the lead [m] (Table A1 otherwise): the present model and Wei's over
    ``leads``, Harris's bearing (``bearing``) at lead 0 only."""
    fig = figure(figsize=(10, 3.8), layout="constrained")
    left, right = fig.subplots(1, 2)
    x = leads * 1e3
    for state, name, style in ((present, "present", "-"), (wei, "Wei (ball at centre velocity)", ":")):
        left.plot(x, state.slide_roll_nut, style, color="C0", label=f"S_A {name}")
        left.plot(x, state.slide_roll_screw, style, color="C1", label=f"S_B {name}")
        right.plot(x, state.entrainment_nut, style, color="C0", label=f"U_A {name}")
        right.plot(x, state.entrainment_screw, style, color="C1", label=f"U_B {name}")
    left.plot([0.0], [float(bearing.slide_roll_outer)], "k*", ms=9, label="Harris (lead 0)")
    right.plot([0.0, 0.0], [float(bearing.entrainment_outer), float(bearing.entrainment_inner)], "k*", ms=9,
               label="Harris (lead 0)")
    left.set_ylabel("slide-roll ratio [-]")
    right.set_ylabel("entrainment velocity [m/s]")
    for axes in (left, right):
        axes.set_xlabel("lead [mm]")
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize=7)
    fig.suptitle("Three methods on the same inputs (Table A1, lead varied)")
    return fig
