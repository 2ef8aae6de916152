"""The FE two-ball module pictures of ``ballbench show fe-b2b-*`` on tiny synthetic inputs (no FE solve).

``patch_figure``: one colour scale for all contact panels (0 to the largest FE pressure, one colour bar) and the
red ellipse named for what it is (the moment ellipse of ``fem.postprocess``, not a fit).  ``cut_figure``: each cut
element drawn flat in its own value (no lighting, no smoothing) and framed to the cut.
"""
from __future__ import annotations

import itertools
import math
from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.figure import Figure

from ballbench.validation.figures.fe_module import FAINT_SHARE, cut_figure, patch_figure

A, B = 0.3e-3, 0.08e-3  # m, semi-axes of the synthetic patches


def _contact(name: str, p0: float):
    """A Hertz-like patch of peak ``p0`` [Pa] on a node grid [m], with negative (tensile) values outside."""
    x, y = np.meshgrid(np.linspace(-0.5e-3, 0.5e-3, 41), np.linspace(-0.2e-3, 0.2e-3, 17))
    xy = np.column_stack([x.ravel(), y.ravel()])
    inside = 1.0 - (xy[:, 0] / A) ** 2 - (xy[:, 1] / B) ** 2
    pressure = np.where(inside > 0, p0 * np.sqrt(np.clip(inside, 0, None)), -0.1 * p0)
    ellipse = SimpleNamespace(x0=0.0, y0=0.0, a=A, b=B)
    return SimpleNamespace(name=name, normal_force=p0 / 1e7, contact_angle=math.radians(45.0), local_nodes=xy,
                           nodal_pressure=pressure, ellipse=ellipse)


def _results(peaks):
    return [SimpleNamespace(contacts=[_contact(f"C{i}", p) for i, p in enumerate(row)]) for row in peaks]


PEAKS_MPA = [(1000.0, 400.0), (200.0, 700.0)]


@pytest.fixture
def figure():
    results = _results([[p * 1e6 for p in row] for row in PEAKS_MPA])
    fig = patch_figure(results, [[(A, B)] * 2] * 2, xlim=0.5, ylim=0.2, heading="synthetic")
    assert isinstance(fig, Figure)  # the object API: no pyplot figure manager, no backend switch
    return fig


def test_pressure_panels_share_one_colour_scale_up_to_the_largest_pressure(figure):
    panels = [ax for ax in figure.axes if ax.get_label() != "<colorbar>"]
    assert len(panels) == 4 and len(figure.axes) == 5  # one colour bar for the figure
    top = max(max(row) for row in PEAKS_MPA)  # the grid holds each patch centre: the peak is a node value
    for ax in panels:
        (contours,) = [c for c in ax.collections if hasattr(c, "levels")]
        assert contours.norm.vmin == 0.0 and contours.norm.vmax == pytest.approx(top, rel=1e-12)
        assert contours.levels[0] == 0.0 and contours.levels[-1] == pytest.approx(top, rel=1e-12)


def test_panel_titles_give_the_peak_and_flag_faint_panels(figure):
    titles = [ax.get_title() for ax in figure.axes if ax.get_label() != "<colorbar>"]
    top = max(max(row) for row in PEAKS_MPA)
    for title, peak in zip(titles, [p for row in PEAKS_MPA for p in row]):
        assert f"peak {peak:.0f} MPa" in title
        assert ("of the scale" in title) == (peak < FAINT_SHARE * top)


def test_red_ellipse_is_named_the_moment_ellipse_not_a_fit(figure):
    (legend,) = figure.legends
    labels = [t.get_text() for t in legend.get_texts()]
    assert labels[1].startswith("FE moment ellipse") and "second moments" in labels[1]
    texts = labels + [figure.get_suptitle()]
    assert "moment ellipse" in figure.get_suptitle()
    assert not any("fit" in text.lower() for text in texts)


def _cube():
    """The unit cube [0, 1e-3]^3 m in six tetrahedra (Kuhn), corner k at (k & 1, k >> 1 & 1, k >> 2 & 1) mm."""
    points = np.array([[k & 1, (k >> 1) & 1, (k >> 2) & 1] for k in range(8)], dtype=float) * 1e-3
    tets = [[0, p, p + q, 7] for p, q, _ in itertools.permutations((1, 2, 4))]
    return points, np.array(tets)


def test_cut_draws_each_element_value_flat_and_frames_the_cut():
    points, tets = _cube()
    stress = np.array([10.0, 20.0, 30.0, 40.0, 50.0, 60.0])  # MPa, one per tetrahedron
    fig = cut_figure(points, tets, stress, normal=(0, 0, 1), origin=(0, 0, 0.5e-3), title="cube")
    ax = fig.axes[0]
    (mesh,) = ax.collections
    drawn = np.asarray(mesh.get_array())
    assert len(drawn) >= 6 and set(np.round(drawn, 12)) == set(stress)  # every tet crosses z = 0.5 mm
    assert mesh.get_cmap().name == "YlOrRd"
    assert mesh.norm.vmin == 0.0 and mesh.norm.vmax == pytest.approx(np.percentile(stress, 99.9))
    assert ax.get_xlim() == pytest.approx((0.0, 1.0)) and ax.get_ylim() == pytest.approx((0.0, 1.0))
    assert ax.get_title() == "cube"


def test_cut_that_misses_the_mesh_says_so():
    points, tets = _cube()
    with pytest.raises(ValueError, match="misses the mesh"):
        cut_figure(points, tets, np.ones(6), normal=(0, 0, 1), origin=(0, 0, 2e-3), title="cube")
