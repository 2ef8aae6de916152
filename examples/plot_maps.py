"""Maps of lin2019 Figs 8-9 from a finished (or partial) sweep of lin2019_fig8_9*.toml.

    python examples/plot_maps.py ballbench-sweeps/lin2019-fig8-9 [maps.png]

Reads the sweep's xarray Dataset (coordinates theta [rad] and rho; ``validation.sweep.read_dataset``, the same
as ``xarray.open_zarr(DIR / "results.zarr", consolidated=False)``).  Grey cells: failed cases (outside four-point
contact or no full-sliding state; the reason is in the ``error`` variable) or not computed yet (``done`` false).
"""
import sys
from collections import Counter
from pathlib import Path

import numpy as np

from ballbench.validation.sweep import read_dataset


def main(directory: str, target: str | None = None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = read_dataset(directory).transpose("theta", "rho")
    thetas, rhos = data["theta"].values, data["rho"].values

    def grid(name):
        return data[name].values

    panels = [("epsilon_1 - epsilon_2 [%]", 100 * (grid("epsilon_1") - grid("epsilon_2")), "RdBu_r"),
              ("F_B2B [N]", grid("b2b_force"), "viridis")]
    if "friction_increase" in data:
        panels.append(("friction increase total/baseline - 1 [%]", 100 * grid("friction_increase"), "magma"))
    figure, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4.2), layout="constrained")
    for ax, (label, values, cmap) in zip(axes, panels):
        ax.set_facecolor("0.85")
        mesh = ax.pcolormesh(rhos, np.degrees(thetas), np.ma.masked_invalid(values), shading="nearest", cmap=cmap)
        figure.colorbar(mesh, ax=ax, label=label)
        ax.set_xlabel("rho = N_x / N_y")
        ax.set_ylabel("theta [deg]")
    failed = Counter(str(e).split(":")[0] for e in data["error"].values.ravel() if e)
    figure.suptitle(f"{Path(directory).name}: {int(data['done'].sum())} of {data['done'].size} cases, "
                    f"failed {dict(failed) or 0}")
    target = target or str(Path(directory) / "maps.png")
    figure.savefig(target, dpi=120)
    print(f"{target}; failed cases by reason: {dict(failed)}")


if __name__ == "__main__":
    main(*sys.argv[1:3])
