"""Where lin2019's full slip holds (docs/b2b_rolling.md, 'Validity of full slip'): the runs of the scenes
``full-slip-validity-map`` (the map over mu, conformity, deviation and load of both two-ball modules,
:data:`cases.stick_slip.MAP`) and ``full-slip-validity`` (the map's worst case, :data:`cases.stick_slip.WORST`, on
refined grids and on the FE compliance).
"""
from __future__ import annotations

import csv
import dataclasses
import math
import time

import numpy as np

from ballbench.lowmodel import full_slip_validity as fsv
from ballbench.lowmodel.linear_bearing import b2b_rolling as linear_rolling
from ballbench.lowmodel.screw import b2b_rolling as screw_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import lin2019, stick_slip
from ballbench.validation.figures import rolling as figures
from ballbench.validation.studies import fe_b2b_linear, fe_b2b_screw
from ballbench.validation.studies.rolling_b2b import level_name, pair_compliance

__all__ = ["validity_points", "write_points", "record_map", "worst_point", "worst_module", "record_worst"]

STEEL = lin2019.STEEL
WORST_TOLERANCE = 0.05  # the 5 % contour: where full slip is off by more, docs/b2b_rolling.md says so


# --------------------------------------------------------------------------
# the validity map of full slip (lowmodel.full_slip_validity)
# --------------------------------------------------------------------------
def validity_points(level: str, progress=None) -> list:
    """The map's points of both products at ``level`` (:data:`cases.stick_slip.MAP`)."""
    grid = stick_slip.MAP[level]
    thetas = [math.radians(t) for t in grid.theta_deg]
    points = fsv.validity_map("linear", grid.mu, grid.conformity, thetas, grid.linear_load, progress=progress,
                              cells=grid.cells)
    points += fsv.validity_map("screw", grid.mu, grid.conformity, thetas, grid.screw_load, progress=progress,
                               cells=grid.cells, oversize=lin2019.SCREW.oversize)
    return points


def write_points(path, points) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["product", "mu", "conformity", "theta_deg", "load_N", "Lambda_min", "creepage_parameter_min",
                         "stick_fraction_max", "F_B2B_stick_slip_N", "F_B2B_full_slip_N", "b2b_difference_pct",
                         "friction_difference_pct", "friction_increase_pct", "friction_increase_full_slip_pct",
                         "cells", "grid_cells", "grid_error_pct", "time_s", "error"])
        for p in points:
            q = p.parameters
            writer.writerow([p.product, q["mu"], q["conformity"], f"{math.degrees(q['theta']):g}", q["load"],
                             f"{p.spin_parameter:.3f}", f"{p.creepage_parameter:.3f}", f"{p.stick_fraction:.4f}",
                             f"{p.b2b_force:.5f}", f"{p.b2b_force_full_slip:.5f}", f"{100 * p.b2b_difference:+.4f}",
                             f"{100 * p.friction_difference:.4f}", f"{p.friction_increase:.3f}",
                             f"{p.friction_increase_full_slip:.3f}", "x".join(map(str, p.cells)),
                             "x".join(map(str, p.grid_cells)), f"{100 * p.grid_error:.4f}", f"{p.time_s:.2f}",
                             p.error[:200]])


def record_map(run) -> list:
    """The map's points, map.csv, map.png and the checks of the scene ``full-slip-validity-map``."""
    level = "quick" if run.fidelity == "quick" else "default"
    start = time.perf_counter()
    points = validity_points(level, progress=lambda it: run.progress(it, desc="validity map"))
    wall = time.perf_counter() - start
    write_points(run.path("map.csv"), points)
    run.add_artifact(run.path("map.csv"))
    run.save_figure(figures.map_figure(points), "map.png")
    solved = [p for p in points if not p.error]
    failed = len(points) - len(solved)
    for product in ("linear bearing", "ball screw"):
        rows = [p for p in solved if p.product == product]
        worst = max(rows, key=lambda p: p.worst)
        q = worst.parameters
        run.check(model="lowmodel.full_slip_validity", quantity=f"{product}: largest |full slip / stick-slip - 1| "
                  "(B2B force or a free ball's friction)", unit="1", value=worst.worst, reference=0.0, scale=1.0,
                  relation="le", tolerance=WORST_TOLERANCE, time_s=wall, family="BEM",
                  level=level_name(worst.cells),
                  source="the 5 % contour (docs/b2b_rolling.md): where full slip is off by more, the low-order "
                         "model's docs say so",
                  why="an upper bound on a relative difference (zero judged on the scale 1)",
                  note=f"at mu {q['mu']:g}, conformity {q['conformity']:g}, theta {math.degrees(q['theta']):g} deg, "
                       f"load {q['load']:g} N: B2B {100 * worst.b2b_difference:+.2f} %, friction "
                       f"{100 * worst.friction_difference:.2f} %, Lambda {worst.spin_parameter:.1f}, grid error "
                       f"{100 * worst.grid_error:.2f} % (against {level_name(worst.grid_cells)}); {len(rows)} "
                       f"cases solved")
    run.note(f"{len(points)} cases, {failed} without a state of either law (map.csv, column error: the model that "
             "found none and why). Every case compares the laws on two sets of cells; the grid error (column "
             "grid_error_pct) is the change of the differences between them (docs/b2b_rolling.md, 'Grid error of "
             "the comparison').")
    return points


# --------------------------------------------------------------------------
# the worst case of the map (scene full-slip-validity)
# --------------------------------------------------------------------------
def _worst_screw(worst):
    screw = dataclasses.replace(lin2019.SCREW, friction_coefficient=worst.mu, conformity=worst.conformity)
    return dataclasses.replace(lin2019.TABLE5_A, name="full-slip-validity worst case", screw=screw,
                               axial_load=worst.load, deviations=(0.0, math.radians(worst.theta_deg)))


def _worst_guide(worst):
    guide = dataclasses.replace(lin2019.GUIDE, friction_coefficient=worst.mu, conformity=worst.conformity)
    theta = math.radians(worst.theta_deg)
    return dataclasses.replace(lin2019.TABLE3_A, name="full-slip-validity worst case", guide=guide,
                               vertical_force=worst.load, deviations=(-theta, theta, 0.0, 0.0))


def worst_point(cells, worst: stick_slip.WorstCase = stick_slip.WORST) -> fsv.ValidityPoint:
    """Stick/slip against full slip at the worst case on Hertz contacts of ``cells``."""
    theta = math.radians(worst.theta_deg)
    if worst.product == "linear":
        return fsv.linear_point(theta, friction_coefficient=worst.mu, conformity=worst.conformity,
                                vertical_force=worst.load, cells=cells)
    return fsv.screw_point(theta, friction_coefficient=worst.mu, conformity=worst.conformity, axial_load=worst.load,
                           cells=cells, oversize=lin2019.SCREW.oversize)


def worst_module(cells, operator_for=None, worst: stick_slip.WorstCase = stick_slip.WORST):
    """The worst case's two-ball module with stick/slip contacts on ``cells`` (a SurfaceGrid for a fixed grid):
    ``(balls, (largest semi-axis along, across) [m], solve)``."""
    if worst.product == "linear":
        case = _worst_guide(worst)
        guide = case.guide
        contacts = fe_b2b_linear.low_order_contacts(case)
        balls = [linear_rolling.hertz_contacts(contacts, j, cells=cells, guide=guide, operator_for=operator_for)
                 for j in range(2)]
        along = float((contacts.semi_major * contacts.b_over_a).max())
        across = float(contacts.semi_major.max())
        return balls, (along, across), lambda: linear_rolling.module_b2b(balls, guide)
    case = _worst_screw(worst)
    contacts, _, state = fe_b2b_screw.low_order(case)
    balls = [screw_rolling.hertz_contacts(state, contacts, j, cells=cells, operator_for=operator_for)
             for j in range(2)]
    along = float((state.semi_major * contacts.b_over_a).max())
    across = float(state.semi_major.max())
    module = screw_contacts.module(case.screw)
    return balls, (along, across), lambda: screw_rolling.module_b2b(balls, module)


def record_worst(run) -> None:
    """The checks of the scene ``full-slip-validity``: full slip against stick/slip at the map's worst case on
    refined grids, and the FE compliance's effect there."""
    q = stick_slip.WORST
    name = (f"{'linear bearing' if q.product == 'linear' else 'ball screw'}, mu {q.mu:g}, conformity "
            f"{q.conformity:g}, theta {q.theta_deg:g} deg, load {q.load:g} N")
    rows = []
    for cells in run.progress(q.cells[run.fidelity], desc="grids"):
        point = worst_point(cells)
        if point.error:
            raise RuntimeError(f"the worst case has no state on {level_name(cells)}: {point.error}")
        rows.append((cells, point))
        note = (f"{name}: B2B force {100 * point.b2b_difference:+.3f} % (F_B2B {point.b2b_force:.3f} N stick/slip, "
                f"{point.b2b_force_full_slip:.3f} N full slip), free ball's friction "
                f"{100 * point.friction_difference:.3f} %, grid error {100 * point.grid_error:.3f} % (against "
                f"{level_name(point.grid_cells)}), friction increase {point.friction_increase:.1f} / "
                f"{point.friction_increase_full_slip:.1f} %, "
                f"Lambda {point.spin_parameter:.1f}, creepage parameter {point.creepage_parameter:.2f}, stick "
                f"fraction up to {point.stick_fraction:.3f}")
        run.check(model="lowmodel.full_slip_validity", quantity="|full slip / stick-slip - 1|, largest of the B2B "
                  "force and a free ball's friction", unit="1", value=point.worst, reference=0.0, scale=1.0,
                  relation="le", tolerance=WORST_TOLERANCE, time_s=point.time_s, family="BEM",
                  level=level_name(cells), why="an upper bound on a relative difference (zero judged on the scale 1)",
                  source="the validity map: no case of the models' domain reaches 5 % (docs/b2b_rolling.md)",
                  note=note)
    if len(rows) > 1:
        run.note("Grid convergence of the worst case's differences (B2B force, friction): " + "; ".join(
            f"{level_name(c)}: {100 * p.b2b_difference:+.3f} %, {100 * p.friction_difference:.3f} %"
            for c, p in rows))
    for along_cells, across_cells, h_factor in q.compliance[run.fidelity]:
        body = lin2019.GUIDE if q.product == "linear" else lin2019.SCREW
        _, (along, across), _ = worst_module((8, 32))
        cover = stick_slip.LEVELS[q.product].cover
        grid, fe, condense_s = pair_compliance(body.ball_radius, q.conformity, cover[0] * along, cover[1] * across,
                                               along_cells, across_cells, h_factor)
        start = time.perf_counter()
        half = worst_module(grid)[2]()
        on_fe = worst_module(grid, operator_for=lambda _grid, fe=fe: fe.operator())[2]()
        seconds = time.perf_counter() - start + condense_s
        level = f"{level_name((along_cells, across_cells))}, P2, h {h_factor:g} cell, {fe.ndofs} DOFs"
        speed = abs(lin2019.GUIDE.groove_velocity) if q.product == "linear" else abs(lin2019.SCREW.nut_speed)
        drag = [np.array([sum(c.drive_power for c in row) for row in r.free.contacts]) / speed for r in (half, on_fe)]
        for quantity, value, reference in (
                ("F_B2B, stick/slip on the FE compliance", float(on_fe.b2b_force[0]), float(half.b2b_force[0])),
                ("free ball 1's friction (drag), stick/slip on the FE compliance", float(drag[1][0]),
                 float(drag[0][0])),
                ("free ball 2's friction (drag), stick/slip on the FE compliance", float(drag[1][1]),
                 float(drag[0][1]))):
            run.check(model="b2b_rolling stick/slip, FE compliance", quantity=quantity, unit="N" if "F_B2B" in quantity
                      or q.product == "linear" else "N m", value=value, reference=reference, tolerance=0.01,
                      time_s=seconds, family="FE-informed", level=level,
                      source="the same stick/slip solve on the half-space (same grid): the FE rung's effect where "
                             "full slip is worst",
                      note=f"power balance {on_fe.power_balance:.1e}; full slip on the same cells "
                           f"{float(on_fe.full_slip.b2b_force[0]):.4f} N; stick fraction up to "
                           f"{max(c.stick_fraction for row in on_fe.touching.contacts for c in row):.3f}")
