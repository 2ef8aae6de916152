"""``ballbench show CASE.toml`` for ``<stem>-whole``: the whole carriage's or nut's pictures drawn again from the
tables its validate run saved in ``<out>/<stem>-whole/`` (balls.csv, load_deflection.csv, friction_over_travel.csv,
rigid_elastic.csv; ball_loads.csv, bar_elastic.csv, stiffness.csv, torque.csv, halves.csv), into ``*.png`` beside
them."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES

__all__ = ["show_whole"]


def _read(path: Path) -> dict[str, np.ndarray]:
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {key: np.array([_value(row[key]) for row in rows]) for key in (rows[0] if rows else {})}


def _value(text: str):
    try:
        return float(text)
    except ValueError:
        return {"True": True, "False": False}.get(text, text)


def _carriage(folder: Path, figures) -> list:
    drawn = []
    if (folder / "balls.csv").exists():
        table = _read(folder / "balls.csv")
        rows, balls = int(table["row"].max()), int(table["ball"].max())
        names = list(dict.fromkeys(table["contact"]))
        force = table["normal_force_N"].reshape(rows, balls, len(names))
        z = table["z_m"].reshape(rows, balls, len(names))[0, :, 0]
        drawn.append((figures.ball_loads(z, force, [f"row {r + 1}" for r in range(rows)],
                                         names if len(names) == 4 else list(CONTACT_NAMES)), "ball_loads.png"))
    if (folder / "load_deflection.csv").exists():
        table = _read(folder / "load_deflection.csv")
        curve = np.column_stack([table[n] for n in ("u_x", "u_y", "phi_x", "phi_y", "phi_z")])
        drawn.append((figures.load_deflection(table["factor"], curve, "the case's carriage load"),
                      "load_deflection.png"))
    if (folder / "friction_over_travel.csv").exists():
        table = _read(folder / "friction_over_travel.csv")
        drawn.append((figures.friction_over_travel(table["travel_m"], table["force_N"], table["force_alone_N"],
                                                   table["complete"].astype(bool), table["u_y_m"],
                                                   table["parted"].astype(bool) if "parted" in table else None),
                      "friction_over_travel.png"))
    if (folder / "rigid_elastic.csv").exists():
        table = _read(folder / "rigid_elastic.csv")
        rows, balls = int(table["row"].max()), int(table["ball"].max())
        drawn.append((figures.rigid_elastic(table["z_m"][:balls], table["rigid_N"].reshape(rows, balls),
                                            table["elastic_N"].reshape(rows, balls),
                                            [f"row {r + 1}" for r in range(rows)]), "rigid_elastic.png"))
    return drawn


def _nut(folder: Path, figures, name: str) -> list:
    drawn = []
    if (folder / "ball_loads.csv").exists():
        table = _read(folder / "ball_loads.csv")
        drawn.append((figures.ball_loads(table["z_m"], table["axial_load_N"], name), "ball_loads.png"))
    if (folder / "bar_elastic.csv").exists():
        table = _read(folder / "bar_elastic.csv")
        drawn.append((figures.bar_elastic(table["z_m"], table["bar_N"], table["elastic_N"],
                                          table["elastic_coarse_N"]), "bar_elastic.png"))
    if (folder / "stiffness.csv").exists():
        table = _read(folder / "stiffness.csv")
        drawn.append((figures.load_shift(table["axial_load_N"], table["shift_m"], "single nut"), "stiffness.png"))
    if (folder / "torque.csv").exists():
        table = _read(folder / "torque.csv")
        drawn.append((figures.torque_over_rotation(table["nut_angle_rad"], table["groove_torque_Nm"],
                                                   table["b2b_torque_Nm"]), "torque.png"))
    if (folder / "halves.csv").exists():
        table = _read(folder / "halves.csv")
        halves = np.column_stack([table["half_a_N"], table["half_b_N"]])
        drawn.append((figures.preload_diagram(table["axial_load_N"], halves, float(table["lift_off_N"][0])),
                      "preload.png"))
    return drawn


def show_whole(case, scene_dir, fidelity: str = "default", solve: bool = False) -> list[Path]:
    """The scene's pictures drawn again from its saved tables (``fidelity``, ``solve``: unused, the tables hold
    what the run computed: run ``ballbench validate CASE.toml`` to compute them again); FileNotFoundError where it
    saved none."""
    del fidelity, solve  # the saved tables are the run's answer; drawing them again needs neither
    folder = Path(scene_dir)
    if getattr(case, "nut", None) is not None:
        from ballbench.validation.figures import nut as figures  # matplotlib: only when drawing

        drawn = _nut(folder, figures, case.name)
    else:
        from ballbench.validation.figures import carriage as figures

        drawn = _carriage(folder, figures)
    if not drawn:
        raise FileNotFoundError(f"{folder}: no table of the whole bearing saved (run 'ballbench validate' on the "
                                "case first)")
    paths = []
    for fig, name in drawn:
        fig.savefig(folder / name, dpi=120, bbox_inches="tight")
        paths.append(folder / name)
    return paths
