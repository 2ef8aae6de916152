"""Pictures of the sun2021 scenes: the analogues of Figs 6, 7-8 and 10, the WM raceway, FE against BEM profiles."""
from __future__ import annotations

import math

import numpy as np

from ballbench.validation.figures.style import figure


def difference_figure(results: dict, title: str):
    """Figs 7-8 analogue: per ``(helix angle [deg], point)`` of ``results`` (lowmodel.contact.screw_contact
    results), the BEM pressure [MPa] and its difference from the helix-free Hertz field."""
    fig = figure(figsize=(4.2 * len(results), 7.5))
    axes = fig.subplots(2, len(results), squeeze=False)
    for column, ((angle, point), contact) in enumerate(results.items()):
        grid = contact.bem.grid
        extent = [grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6]
        top = axes[0, column].imshow(contact.bem.pressure / 1e6, origin="lower", extent=extent, aspect="equal")
        axes[0, column].set_title(f"{point}, helix {angle} deg: BEM p [MPa]\ntheta_s = "
                                  f"{math.degrees(contact.bem_angle):.3f} deg")
        fig.colorbar(top, ax=axes[0, column], shrink=0.8)
        difference = (contact.bem.pressure - contact.hertz_field("flat_helix")) / 1e6
        bound = float(np.max(np.abs(difference)))
        bottom = axes[1, column].imshow(difference, origin="lower", extent=extent, aspect="equal", cmap="RdBu_r",
                                        vmin=-bound, vmax=bound)
        axes[1, column].set_title("BEM - helix-free Hertz [MPa]")
        fig.colorbar(bottom, ax=axes[1, column], shrink=0.8)
        for row in range(2):
            axes[row, column].set_xlabel("y, along the track [um]")
            axes[row, column].set_ylabel("x, across the groove [um]")
    fig.suptitle(title)
    return fig


def ehl_figure(solution, title: str):
    """Fig 10 analogue: EHL pressure [MPa] and film [nm] over the domain and along the centre line."""
    grid = solution.grid
    fig = figure(figsize=(14, 4.2))
    axes = fig.subplots(1, 3)
    extent = [grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6]
    image = axes[0].imshow(solution.pressure / 1e6, origin="lower", extent=extent, aspect="auto")
    axes[0].set_title("EHL pressure [MPa]")
    fig.colorbar(image, ax=axes[0])
    image = axes[1].imshow(solution.film * 1e9, origin="lower", extent=extent, aspect="auto",
                           vmax=float(np.percentile(solution.film, 30)) * 1e9)
    axes[1].set_title("film h [nm]")
    fig.colorbar(image, ax=axes[1])
    for axis in axes[:2]:
        axis.set_xlabel("y, across the groove [um]")
        axis.set_ylabel("x, entrainment (track) [um]")
    j = grid.ny // 2
    axes[2].plot(grid.x * 1e6, solution.pressure[:, j] / 1e6, label="p [MPa]")
    twin = axes[2].twinx()
    twin.plot(grid.x * 1e6, solution.film[:, j] * 1e9, "r", label="h [nm]")
    twin.set_ylim(0, 4 * solution.central_film * 1e9)
    axes[2].set_xlabel("x, entrainment [um] (y = 0)")
    axes[2].set_title("centre line: pressure (blue), film (red)")
    fig.suptitle(title)
    return fig


def profile_figure(results: dict, helix_angle_deg: float, bem_cells: int):
    """FE against BEM: pressure [MPa] along both axes through the contact centre per point
    (``results[point] = (BEM contact, FE dict of studies.sun2021.fe_contact)``)."""
    fig = figure(figsize=(11, 3.6 * len(results)))
    axes = fig.subplots(len(results), 2, squeeze=False)
    for row, (point, (bem, fe)) in enumerate(results.items()):
        grid = bem.bem.grid
        i0, j0 = grid.nx // 2, grid.ny // 2
        for column, (along, across, cells, label) in enumerate(
                ((0, 1, grid.x, "x (major, across the groove)"), (1, 0, grid.y, "y (minor, along the track)"))):
            line = bem.bem.pressure[:, j0] if column == 0 else bem.bem.pressure[i0, :]
            axis = axes[row, column]
            axis.plot(cells * 1e6, line / 1e6, "k-", label=f"BEM {bem_cells} x {bem_cells}")
            near = np.abs(fe["xq"][:, across]) < float(bem.hertz.b) / 12.0  # a strip of half an FE element
            axis.plot(fe["xq"][near, along] * 1e6, fe["pressure_q"][near] / 1e6, ".", ms=2, label="FE (mortar)")
            axis.set_xlabel(f"{label} [um]")
            axis.set_ylabel("p [MPa]")
            axis.set_title(f"point {point}, helix {helix_angle_deg} deg")
            axis.legend()
    fig.tight_layout()
    return fig


def raceway_figure(grid, heights, title: str):
    """The WM raceway heights [nm] over the domain."""
    fig = figure(figsize=(5, 4.2))
    axis = fig.subplots()
    image = axis.imshow(heights * 1e9, origin="lower",
                        extent=[grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6])
    fig.colorbar(image, ax=axis, label="height [nm]")
    axis.set_title(title)
    return fig


def friction_figure(grid, rows: list, nm_rows: list, published_speed: float, transition):
    """Fig 6 analogue: friction coefficient against screw speed (``rows``: (speed [m/s], u, contact, friction,
    torque) with G in pm; ``nm_rows``: (speed, contact, friction) with G in nm), the published transition speed and
    the model's; pressure [MPa] and rough film [nm] at the slowest speed."""
    fig = figure(figsize=(14, 4.2))
    axes = fig.subplots(1, 3)
    axes[0].semilogx(np.array([r[0] for r in rows]) * 1e3, [r[3].friction_coefficient for r in rows], "o-",
                     label="G in pm")
    if nm_rows:
        axes[0].semilogx([r[0] * 1e3 for r in nm_rows], [r[2].friction_coefficient for r in nm_rows], "s-",
                         label="G in nm")
    axes[0].axvline(published_speed * 1e3, color="k", ls="--", label=f"sun2021 {published_speed * 1e3:.2f} mm/s")
    if transition is not None:
        axes[0].axvline(transition * 1e3, color="r", ls=":", label="rough film closes (here)")
    axes[0].set_xlabel("screw speed [mm/s]")
    axes[0].set_ylabel("friction coefficient (eq 21)")
    axes[0].legend()
    last = rows[0][2]
    extent = [grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6]
    image = axes[1].imshow((last.film.pressure + last.asperity_pressure) / 1e6, origin="lower", extent=extent,
                           aspect="auto")
    axes[1].set_title(f"pressure [MPa], {rows[0][0] * 1e3:.0f} mm/s")
    fig.colorbar(image, ax=axes[1])
    image = axes[2].imshow(last.rough_film * 1e9, origin="lower", extent=extent, aspect="auto",
                           vmax=4.0 * last.smooth.central_film * 1e9)
    axes[2].set_title("rough film [nm]")
    fig.colorbar(image, ax=axes[2])
    for axis in axes[1:]:
        axis.set_xlabel("y, across the groove [um]")
        axis.set_ylabel("x, entrainment [um]")
    fig.tight_layout()
    return fig
