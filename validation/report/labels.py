"""Point labels that do not collide: a greedy placement in display space.

Each label goes to the first free spot around its point, trying rings of
growing distance and, on each ring, the directions in :data:`DIRECTIONS`
(right first, as a reader scans); a spot is free when the label's box lies
inside the axes and overlaps no placed label, no point marker and no box the
caller names (lines, notes, legends).  A label set off from its point gets a
thin leader line.  When no spot is free (a panel too crowded), the spot with
the least overlap is taken.  Labels are placed in the order given.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

DIRECTIONS = (0, 35, -35, 90, -90, 145, -145, 180, 65, -65, 115, -115)  # degrees, in order of preference
RINGS = (1.0, 5.0, 12.0, 22.0, 36.0, 54.0, 78.0, 108.0, 145.0, 190.0, 250.0, 330.0)  # gap to the marker [pt]
LEADER_PT = 4.0  # a label farther than this from its marker gets a leader line [pt]


def _overlap(boxes: np.ndarray, others: np.ndarray) -> np.ndarray:
    """Overlap area of every box (n, 4) with every other (m, 4) as (n, m); boxes are (x0, y0, x1, y1)."""
    if others.size == 0:
        return np.zeros((len(boxes), 0))
    width = np.minimum(boxes[:, None, 2], others[None, :, 2]) - np.maximum(boxes[:, None, 0], others[None, :, 0])
    height = np.minimum(boxes[:, None, 3], others[None, :, 3]) - np.maximum(boxes[:, None, 1], others[None, :, 1])
    return np.clip(width, 0, None) * np.clip(height, 0, None)


def _candidates(anchor: np.ndarray, half: np.ndarray, marker: float, scale: float) -> np.ndarray:
    """Label boxes (k, 4) around ``anchor`` [px]: the rings of :data:`RINGS` times :data:`DIRECTIONS`."""
    boxes = []
    for ring in RINGS:
        for angle in DIRECTIONS:
            u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
            # the distance along u at which the box (half sizes ``half``) clears the marker square
            reach = min((half[i] + marker) / abs(u[i]) if abs(u[i]) > 1e-9 else math.inf for i in (0, 1))
            centre = anchor + u * (reach + ring * scale)
            boxes.append((*(centre - half), *(centre + half)))
    return np.array(boxes)


def line_boxes(axes, xs: Sequence[float], ys: Sequence[float], *, step_px: float = 6.0,
               half_px: float = 1.5) -> np.ndarray:
    """Small boxes along the polyline (data coordinates) every ``step_px`` pixels: obstacles for labels."""
    path = axes.transData.transform(np.column_stack([xs, ys]))
    boxes = []
    for a, b in zip(path[:-1], path[1:]):
        n = max(1, int(np.hypot(*(b - a)) / step_px))
        for t in np.linspace(0.0, 1.0, n + 1):
            x, y = a + t * (b - a)
            boxes.append((x - half_px, y - half_px, x + half_px, y + half_px))
    return np.array(boxes).reshape(-1, 4)


def artist_boxes(artists, renderer) -> np.ndarray:
    """The display boxes (k, 4) of ``artists`` (texts, legends) as label obstacles."""
    boxes = [a.get_window_extent(renderer) for a in artists]
    return np.array([(b.x0, b.y0, b.x1, b.y1) for b in boxes]).reshape(-1, 4)


def place_labels(axes, anchors: Sequence[tuple[float, float]], texts: Sequence[str], renderer, *,
                 fontsize: float = 7.0, marker_pt: float = 4.0, avoid: np.ndarray | None = None,
                 colour: str = "0.1") -> np.ndarray:
    """Write ``texts[i]`` next to ``anchors[i]`` (data coordinates) without collisions; returns the label boxes
    (n, 4) in display pixels.  ``marker_pt``: half size of the point markers [pt]; ``avoid``: further obstacle
    boxes (k, 4) in display pixels.  The axes limits must be final before the call."""
    scale = axes.figure.dpi / 72.0
    frame = axes.get_window_extent(renderer)
    inner = np.array([frame.x0, frame.y0, frame.x1, frame.y1]) + np.array([2, 2, -2, -2]) * scale
    anchors = np.asarray(anchors, dtype=float).reshape(-1, 2)
    points = axes.transData.transform(anchors)
    marker = marker_pt * scale
    taken = [np.column_stack([points - marker, points + marker])]
    if avoid is not None and len(avoid):
        taken.append(np.asarray(avoid, dtype=float).reshape(-1, 4))
    placed = []
    for xy, anchor, text in zip(anchors, points, texts):
        probe = axes.text(0, 0, text, fontsize=fontsize)
        extent = probe.get_window_extent(renderer)
        probe.remove()
        half = np.array([extent.width, extent.height]) / 2 + 1.0 * scale
        boxes = _candidates(anchor, half, marker, scale)
        outside = ((inner[0] - boxes[:, 0]).clip(0) + (boxes[:, 2] - inner[2]).clip(0)
                   + (inner[1] - boxes[:, 1]).clip(0) + (boxes[:, 3] - inner[3]).clip(0))
        cost = _overlap(boxes, np.vstack(taken)).sum(axis=1) + 1e6 * outside
        free = np.flatnonzero(cost == 0)
        chosen = int(free[0]) if free.size else int(np.argmin(cost))
        box = boxes[chosen]
        offset = ((box[:2] + box[2:]) / 2 - anchor) / scale
        far = RINGS[chosen // len(DIRECTIONS)] > LEADER_PT
        arrow = dict(arrowstyle="-", color="0.55", lw=0.5, shrinkA=1.0, shrinkB=marker_pt) if far else None
        axes.annotate(text, xy=tuple(xy), xytext=tuple(offset),
                      textcoords="offset points", ha="center", va="center", fontsize=fontsize, color=colour,
                      arrowprops=arrow, annotation_clip=False)
        placed.append(box - np.array([1.0, 1.0, -1.0, -1.0]) * scale)  # the text's own box, without the margin
        taken.append(box[None, :])
    return np.array(placed).reshape(-1, 4)
