"""``error_vs_time.png``: error against run time, a summary and one work-precision panel per model family.

The summary draws every point (one per scene, family, model and level),
coloured by family and shaped by status, with each family's front of accuracy
against cost.  Each family panel draws that family's points labelled by scene
(placed so that no two labels collide, :mod:`.labels`), a line through each
model's fidelity levels, as the work-precision diagrams of numerical-methods
benchmarks do, and the FE mesh levels of the scenes' ``convergence.csv``.
Built with matplotlib's object API (no pyplot, no global backend); matplotlib
is imported only when a figure is drawn.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ballbench.validation.report.labels import artist_boxes, line_boxes, place_labels
from ballbench.validation.report.points import (CEILING, FLOOR, error_points, family_order, front_line,
                                                mesh_level_points, model_lines, plotted, write_points)
from ballbench.validation.report.rows import count

# Okabe-Ito colours (safe for the common colour-vision deficiencies) and a line style each, for print
FAMILY_STYLE = {
    "analytical": ("#009E73", "-"),
    "low-order numerical": ("#0072B2", "--"),
    "BEM": ("#56B4E9", "-."),
    "EHL": ("#CC79A7", ":"),
    "FE": ("#000000", "-"),
    "FE-informed": ("#E69F00", "--"),
    "undeclared": ("#999999", ":"),
}
STATUS_MARKER = {"pass": ("o", "passed"), "known gap": ("s", "known gap"), "fail": ("X", "failed"),
                 "unexpected pass": ("D", "known gap that now passes"),
                 "outside accuracy": ("P", "outside its accuracy (a finding)")}
FAIL_EDGE = "#D55E00"
MESH_COLOUR = "0.45"
PANEL_WIDTH_IN, PANEL_HEIGHT_IN, SUMMARY_HEIGHT_IN = 6.5, 4.7, 5.2
DPI = 100


def _style(family: str) -> tuple[str, str]:
    return FAMILY_STYLE.get(family, FAMILY_STYLE["undeclared"])


def _short(model: str) -> str:
    return model.removeprefix("lowmodel.")


def _scatter(axes, points, colour: str, size: float) -> None:
    """The points in ``colour``, marker by status; a failed point also gets a vermillion ring."""
    for status, (marker, _) in STATUS_MARKER.items():
        chosen = [p for p in points if p["status"] == status]
        if chosen:
            failed = status in ("fail", "unexpected pass")
            axes.scatter([p["time_s"] for p in chosen], [plotted(p["error"]) for p in chosen], s=size, c=colour,
                         marker=marker, edgecolors=FAIL_EDGE if failed else "black",
                         linewidths=1.6 if failed else 0.5, zorder=3)


def _frame(axes, *, notes: bool = True) -> list:
    """Log axes with the tolerance line, the marked floor and ceiling; returns the note texts."""
    from matplotlib.ticker import NullFormatter

    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_ylim(FLOOR / 5, CEILING * 5)
    axes.axhline(1.0, color="black", lw=1.0, ls="--", zorder=1)
    axes.axhspan(FLOOR / 5, FLOOR * 2, color="0.9", zorder=0)
    axes.axhspan(CEILING / 2, CEILING * 5, color="0.9", zorder=0)
    axes.grid(True, which="major", alpha=0.3)
    axes.set_xlabel("run time of one model evaluation [s]", fontsize=8)
    axes.tick_params(labelsize=8)
    axes.xaxis.set_minor_formatter(NullFormatter())
    if not notes:
        return []
    return [axes.text(0.01, 0.012, "floor: error 0 (exact, or all bounds met) or below 1e-8",
                      transform=axes.transAxes, fontsize=6.5, va="bottom"),
            axes.text(0.01, 0.988, "ceiling: tolerance-0 bound missed / non-finite", transform=axes.transAxes,
                      fontsize=6.5, va="top")]


def _time_limits(times) -> tuple[float, float]:
    """Log time axis around ``times`` from decade to decade, padded (room to the right for labels): at least a
    decade wide with a labelled tick at each end (a narrower log axis labels its minor ticks on top of each
    other)."""
    times = [t for t in times if t > 0 and math.isfinite(t)] or [1.0]
    return 10.0 ** math.floor(math.log10(min(times) / 1.5)), 10.0 ** math.ceil(math.log10(max(times) * 3.0))


def _summary(axes, legend_axes, points, families) -> None:
    _frame(axes)
    for family in families:
        colour, line = _style(family)
        members = [p for p in points if p["family"] == family]
        _scatter(axes, members, colour, 30)
        axes.step(*front_line(members), where="post", color=colour, ls=line, lw=2, zorder=2,
                  label=f"{family} ({count(len(members), 'point')})")
    axes.set_xlim(*_time_limits([p["time_s"] for p in points]))
    axes.set_ylabel("worst error / tolerance [-]", fontsize=9)
    axes.set_title("All models: each point one (scene, model, level); lines: each family's front", fontsize=10)
    axes.text(0.01, 1.6, "1 = at tolerance", transform=axes.get_yaxis_transform(), fontsize=7)
    legend_axes.axis("off")
    handles, labels = axes.get_legend_handles_labels()
    first = legend_axes.legend(handles, labels, loc="upper left", fontsize=8.5, frameon=False,
                               title="model family (points; front)", title_fontsize=9, alignment="left")
    legend_axes.add_artist(first)
    shapes = [legend_axes.scatter([], [], marker=marker, c="white", edgecolors="black", s=40)
              for marker, _ in STATUS_MARKER.values()]
    present = {p["status"] for p in points}
    chosen = [(h, f"{label} ({sum(p['status'] == s for p in points)})")
              for h, (s, (_, label)) in zip(shapes, STATUS_MARKER.items()) if s in present]
    if chosen:
        legend_axes.legend(*zip(*chosen), loc="lower left", fontsize=8.5, frameon=False, title="status",
                           title_fontsize=9, alignment="left")
    legend_axes.text(0.02, 0.5, "A front joins the points that no other point of its family\nbeats in both run "
                     "time and error: the fastest model\nthat meets an error budget.\n\nBelow, one panel per family: "
                     "each point labelled by\nits scene, a line through each model's fidelity levels.",
                     transform=legend_axes.transAxes, fontsize=8, va="center")


def _text_colour(colour: str) -> str:
    """A family colour dark enough for text (black and grey as dark grey)."""
    return "0.3" if colour in ("#000000", "#999999") else colour


def _scene_labels(lines, mesh) -> tuple[list, list]:
    """One label per model line, at its finest level (the longest evaluation): the scene, and the model when
    the scene has several in the panel; a scene with mesh levels only is labelled at its finest level."""
    per_scene: dict[str, int] = {}
    for members in lines:
        per_scene[members[0]["scene"]] = per_scene.get(members[0]["scene"], 0) + 1
    anchors, texts = [], []
    for members in lines:
        last = members[-1]
        anchors.append((last["time_s"], plotted(last["error"])))
        texts.append(last["scene"] + (f" · {_short(last['model'])}" if per_scene[last["scene"]] > 1 else ""))
    for scene, members in sorted(mesh.items()):
        if scene not in per_scene:
            anchors.append((members[-1]["time_s"], plotted(members[-1]["error"])))
            texts.append(f"{scene} mesh levels")
    order = sorted(range(len(anchors)), key=lambda i: (-anchors[i][1], anchors[i][0]))  # top left first
    return [anchors[i] for i in order], [texts[i] for i in order]


def _family_panel(axes, family, points, levels, renderer) -> None:
    """One family: its points, a line through each model's levels, the FE mesh levels; labels that do not
    collide.  The fidelity levels are named once in a note when every line has the same ones, else at the
    coarsest and the finest point of each line."""
    colour, line = _style(family)
    notes = _frame(axes)
    lines = model_lines(points)
    mesh: dict[str, list] = {}
    for p in sorted(levels, key=lambda p: p["time_s"]):
        mesh.setdefault(p["scene"], []).append(p)
    axes.set_xlim(*_time_limits([p["time_s"] for p in points] + [p["time_s"] for p in levels]))
    stepped = [m for m in lines if len(m) > 1]
    sequences = {tuple(p["level"] or "?" for p in members) for members in stepped}
    if len(sequences) == 1:
        notes.append(axes.text(0.99, 0.075, "levels, left to right: " + ", ".join(sequences.pop()),
                               transform=axes.transAxes, fontsize=7, ha="right", va="bottom", color="0.25"))
    low, high = axes.get_xlim()
    obstacles = [artist_boxes(notes, renderer), line_boxes(axes, [low, high], [1.0, 1.0])]  # the tolerance line
    for members in mesh.values():
        xs, ys = [p["time_s"] for p in members], [plotted(p["error"]) for p in members]
        axes.plot(xs, ys, "o-", color=MESH_COLOUR, ms=3, lw=0.8, zorder=2)
        obstacles.append(line_boxes(axes, xs, ys))
    for members in stepped:
        xs, ys = [p["time_s"] for p in members], [plotted(p["error"]) for p in members]
        axes.plot(xs, ys, color=colour, ls=line, lw=1.3, zorder=2)
        obstacles.append(line_boxes(axes, xs, ys))
    _scatter(axes, points, colour, 36)
    anchors, texts = _scene_labels(lines, mesh)
    avoid = np.vstack(obstacles)
    placed = place_labels(axes, anchors, texts, renderer, fontsize=7, avoid=avoid)
    if sequences:  # several level sequences: name them at the ends of each line
        ends = [p for members in stepped for p in (members[0], members[-1])]
        place_labels(axes, [(p["time_s"], plotted(p["error"])) for p in ends], [p["level"] or "?" for p in ends],
                     renderer, fontsize=6, avoid=np.vstack([avoid, placed]), colour=_text_colour(colour))
    n_scenes = len({p["scene"] for p in points} | set(mesh))
    axes.set_title(f"{family}: {count(len(lines), 'model')} in {count(n_scenes, 'scene')}"
                   + (" (+ FE mesh levels, grey)" if mesh else ""), fontsize=10, color=_text_colour(colour))


def error_figure(data: dict, out_dir: Path | None = None):
    """The figure (a ``matplotlib.figure.Figure``) of ``results.json`` data and the points it draws;
    ``out_dir`` holds the scenes' ``convergence.csv`` (no mesh levels without it)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    points = error_points(data)
    levels = mesh_level_points(data, out_dir) if out_dir is not None else []
    families = family_order([p["family"] for p in points] + [p["family"] for p in levels])
    rows = math.ceil(len(families) / 2)
    height = SUMMARY_HEIGHT_IN + rows * PANEL_HEIGHT_IN + 0.8
    figure = Figure(figsize=(2 * PANEL_WIDTH_IN, height), dpi=DPI)
    canvas = FigureCanvasAgg(figure)
    top, bottom = 1 - 0.95 / height, 0.45 / height
    grid = figure.add_gridspec(rows + 1, 2, height_ratios=(SUMMARY_HEIGHT_IN, *[PANEL_HEIGHT_IN] * rows),
                               left=0.07, right=0.98, top=top, bottom=bottom, hspace=0.42 * 4.7 / PANEL_HEIGHT_IN,
                               wspace=0.2)
    head = grid[0, :].subgridspec(1, 2, width_ratios=(2.1, 1.0), wspace=0.08)
    summary, legend_axes = figure.add_subplot(head[0]), figure.add_subplot(head[1])
    _summary(summary, legend_axes, points, [f for f in families if any(p["family"] == f for p in points)])
    renderer = canvas.get_renderer()
    for k, family in enumerate(families):
        last_alone = k == len(families) - 1 and k % 2 == 0  # an odd count: the last panel takes the whole row
        axes = figure.add_subplot(grid[1 + k // 2, :] if last_alone else grid[1 + k // 2, k % 2])
        _family_panel(axes, family, [p for p in points if p["family"] == family],
                      [p for p in levels if p["family"] == family], renderer)
        if k % 2 == 0:
            axes.set_ylabel("worst error / tolerance [-]", fontsize=9)
    figure.suptitle(f"ballbench run at fidelity {data.get('fidelity', '')}: error against run time "
                    "(1 = at tolerance; below the dashed line passes)", fontsize=12)
    return figure, points


def plot_error_vs_time(data: dict, path: Path, out_dir: Path | None = None) -> list[dict]:
    """Write ``path`` (PNG) and the plotted points beside it (``.csv``); returns the points."""
    figure, points = error_figure(data, out_dir)
    figure.savefig(path, dpi=DPI)
    write_points(points, Path(path).with_suffix(".csv"))
    return points
