"""Pictures of the lin2017 four-point scenes: sliding-state maps (Figs 7, 11) and relative loss maps (Figs 8, 12)
over a contact angle deviation and rho = N_x / N_y."""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import figure


def state_figure(angle_values, rho_values, labels, limits, lines, xlabel, title):
    import matplotlib
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    present = sorted({label for label in labels.ravel() if label}, key=lambda s: (s.count("+"), s))
    palette = matplotlib.colormaps["tab10"].colors
    codes = np.full(labels.shape, np.nan)
    for k, label in enumerate(present):
        codes[labels == label] = k
    fig = figure(figsize=(6.4, 4.8))
    ax = fig.subplots()
    degrees = np.degrees(angle_values)
    ax.pcolormesh(degrees, rho_values, codes.T, cmap=ListedColormap(palette[:len(present)]), vmin=-0.5,
                  vmax=len(present) - 0.5, shading="nearest")
    off = np.where(labels == "", 1.0, np.nan)
    ax.pcolormesh(degrees, rho_values, off.T, cmap=ListedColormap(["0.75"]), shading="nearest")
    ax.plot(degrees, limits[0][:, 0], "k:", degrees, limits[1][:, 0], "k:")
    for (values, color, text) in lines:
        ax.plot(degrees, values, color=color, lw=2.5, ls="--", label=text)
    handles = [Patch(color=palette[k], label=label) for k, label in enumerate(present)]
    handles.append(Patch(color="0.75", label="loss of contact (eq 37)"))
    ax.legend(handles=handles + ax.get_legend_handles_labels()[0], fontsize=7, loc="upper left",
              bbox_to_anchor=(1.01, 1.0))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$\rho = N_x / N_y$")
    ax.set_ylim(rho_values[0], rho_values[-1])
    ax.set_title(title, fontsize=9)
    return fig


def loss_figure(angle_values, rho_values, loss, xlabel, title):
    fig = figure(figsize=(6.0, 4.6))
    ax = fig.subplots()
    image = ax.pcolormesh(np.degrees(angle_values), rho_values, loss.T, shading="nearest", cmap="viridis")
    top = float(np.nanmax(loss))
    if top > 0:
        ax.contour(np.degrees(angle_values), rho_values, loss.T, colors="w", linewidths=0.5,
                   levels=np.linspace(0.1, 0.9, 9) * top)
    fig.colorbar(image, ax=ax, label=r"$P_f / (\mu_k v N_y)$")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$\rho = N_x / N_y$")
    ax.set_title(title, fontsize=9)
    return fig
