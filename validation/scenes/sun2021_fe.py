"""sun2021 dry contact at 21.71 deg, A and B: the BEM on the exact gap against our FE on the exact meshed groove.

Two independent models of one contact (sun2021 Table 1 ball screw, eq 1 load,
helix angle 21.71 deg; point A on the screw, B on the nut):

* BEM (lowmodel.contact.screw_contact): half-space contact on the exact
  sphere-helicoid gap of the geometry core, 256 x 256 cells;
* FE (fem.mortar, P2 tetrahedra, mortar contact): the ball cap in the helical
  screw (A) or nut (B) groove block of meshes.assemblies.screw_pair, the groove nodes snapped onto
  the exact helical surface, and the contact gap taken from the meshed surfaces
  themselves (``initial_gap=None``: no Hertz or BEM gap is given to the FE).
  Finite bodies, no half-space assumption.

Both are read in the same contact frame (x the major principal direction of
the groove surface, y the minor; the ball is a sphere, so these are also the
principal directions of the relative curvature).  Rotation theta_s: the major
axis of the pressure-weighted second-moment ellipse measured from the profile
tangent (as in sun2021-dry-contact), computed the same way for both models
(BEM cells; FE quadrature points of the mortar pressure).  Central pressure:
BEM at the contact point; FE the peak of the Hertz field fitted to its mortar
pressure (fem.hertz_case.fit_contact_patch; its centre lies within 0.5 um of
the contact point).
"""
from __future__ import annotations

import math
import time

import numpy as np

from ballbench.lowmodel.geometry import helix
from ballbench.validation.figures import render3d
from ballbench.validation.scene import scene
from ballbench.validation.scenes import sun2021

T1 = sun2021.T1
HELIX_ANGLE_DEG = 21.71  # sun2021 Table 1's largest helix angle (Figs 7-9)
BEM_CELLS = 256
# FE levels (n = b / h_contact, growth away from the fine zone), as the fe-hertz-screw pair; points solved
# (A on the screw, B on the nut: the concave nut block's z window holds ball nodes beside the block, which
# fem.surface.locate_along_z leaves out of the candidate set)
LEVELS = {
    "quick": {"A": [(5.5, 1.6)], "B": [(5.0, 1.8)]},  # B coarser: A and B both at 5.5, 1.6 took 89 s of 90 s
    "default": {"A": [(6.0, 1.45)], "B": [(6.0, 1.45)]},
    "fine": {"A": [(5.5, 1.6), (6.0, 1.45), (6.5, 1.4)], "B": [(5.5, 1.6), (6.0, 1.45), (6.5, 1.4)]},
}
GAP_LIMIT = 1.05  # candidate zone: exact meshed gap <= 1.05 delta_Hertz (the largest gap in contact ~0.7 delta)
PRESSURE_TOLERANCE = 0.01  # issue 14: central pressure within 1 %
ANGLE_TOLERANCE_DEG = 0.1  # issue 14: rotation within 0.1 deg
AXIS_TOLERANCE = 0.01  # the semi-axes: the same 1 % as the pressure (fe-hertz-screw default level: 0.5 %)
ANGLE_WHY = ("an angle difference judged in degrees: 0.1 deg absolute (issue 14) on the scale of 1 deg, while "
             "theta_s itself is only ~0.3 deg")


def second_moment_angle(x: np.ndarray, y: np.ndarray, weight: np.ndarray) -> float:
    """Angle [rad] of the major axis of the ``weight``-weighted second moments of points ``(x, y)`` [m], from x.

    ``0.5 atan2(2 m_xy, m_xx - m_yy)`` about the weighted centroid; the same estimator as
    :func:`ballbench.lowmodel.contact.halfspace.pressure_ellipse` (whose cell-size term is isotropic and
    does not change the angle).
    """
    total = float(np.sum(weight))
    if not total > 0.0:
        raise ValueError("weight must have a positive sum")
    xc, yc = float(np.sum(weight * x)) / total, float(np.sum(weight * y)) / total
    dx, dy = x - xc, y - yc
    mxx, myy, mxy = (float(np.sum(weight * f)) / total for f in (dx * dx, dy * dy, dx * dy))
    return 0.5 * math.atan2(2.0 * mxy, mxx - myy)


def fe_contact(point: str, n: float, growth: float, hertz_contact):
    """FE of the Table 1 contact at ``point`` with the exact meshed gap: dict of p0 [Pa], a, b [m], angle [rad]
    (major axis from the contact frame's x), force [N], ndofs, timings [s] and the quadrature pressure."""
    from ballbench.fem import contact, hertz_case, postprocess
    from ballbench.fem.mortar import build_mortar_model
    from ballbench.meshes.assemblies import screw_pair

    body, flank = sun2021.POINTS[point]
    lead = float(helix.lead_from_angle(math.radians(HELIX_ANGLE_DEG), T1.pitch_radius))
    a, b = float(hertz_contact.a), float(hertz_contact.b)
    start = time.perf_counter()
    path = screw_pair.ball_in_screw_groove_pair(T1.ball_radius, T1.conformity, T1.pitch_radius, lead,
                                                T1.contact_angle, body, h_contact=b / n, growth=growth,
                                                flank=flank, fine_radius=1.2 * b, fine_half_length=1.0 * a)
    meshed = time.perf_counter()
    model = build_mortar_model(path, (T1.youngs_modulus, T1.poisson_ratio), GAP_LIMIT * float(hertz_contact.delta),
                               order=2)  # initial_gap None: the gap of the meshed surfaces
    built = time.perf_counter()
    state = contact.solve_force(model, sun2021.contact_load(), tol=1e-10)
    solved = time.perf_counter()
    fit = hertz_case.fit_contact_patch(model, state)
    postprocess.mesh_check(hertz_case.contact_edge_length(model, state.active), min(fit.a, fit.b))
    xq, matrix = postprocess.force_operator(model.pair.points, model.pair.surfaces["ball_contact"], model.candidates)
    weight = np.asarray(matrix.sum(axis=0)).ravel()  # quadrature weights [m^2]
    pressure_q = (matrix.T @ state.pressure) / np.where(weight > 0, weight, 1.0)  # the P1 mortar pressure at xq
    angle = second_moment_angle(xq[:, 0], xq[:, 1], weight * pressure_q)
    return {"p0": fit.p0, "a": fit.a, "b": fit.b, "centre": (fit.x0, fit.y0), "angle": angle, "force": state.force,
            "ndofs": model.ndofs, "xq": xq, "pressure_q": pressure_q,
            "timings": {"mesh_s": meshed - start, "model_s": built - meshed, "contact_s": solved - built}}


def _profile_figure(results):
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(len(results), 2, figsize=(11, 3.6 * len(results)), squeeze=False)
    for row, (point, (bem, fe)) in enumerate(results.items()):
        grid = bem.bem.grid
        i0, j0 = grid.nx // 2, grid.ny // 2
        for column, (along, across, cells, label) in enumerate(
                ((0, 1, grid.x, "x (major, across the groove)"), (1, 0, grid.y, "y (minor, along the track)"))):
            line = bem.bem.pressure[:, j0] if column == 0 else bem.bem.pressure[i0, :]
            axis = axes[row, column]
            axis.plot(cells * 1e6, line / 1e6, "k-", label="BEM 256 x 256")
            near = np.abs(fe["xq"][:, across]) < float(bem.hertz.b) / 12.0  # a strip of half an FE element
            axis.plot(fe["xq"][near, along] * 1e6, fe["pressure_q"][near] / 1e6, ".", ms=2, label="FE (mortar)")
            axis.set_xlabel(f"{label} [um]")
            axis.set_ylabel("p [MPa]")
            axis.set_title(f"point {point}, helix {HELIX_ANGLE_DEG} deg")
            axis.legend()
    figure.tight_layout()
    return figure


@scene("sun2021-fe-bem",
       "sun2021 Table 1 contact at 21.71 deg, A (screw) and B (nut): BEM on the exact gap against our FE on the "
       "exact meshed helical groove (P2 mortar): central pressure within 1 %, rotation theta_s within 0.1 deg",
       kind="FE", cost_s=300.0, level="n = b/h 6, growth 1.45 (A and B)",
       budget_s={"quick": 400.0, "default": 900.0, "fine": 3000.0})
# cost, meshes cached (model assembly ~95 % of it): quick (A 299k + B 189k P2 DOFs, 4.9 GB) 115 s wall at load
# average ~2.5 (A and B both at 5.5, 1.6: 89 s idle); default (A 409k + B 362k DOFs, 7.2 GB) 268 s wall at ~3.5
def sun2021_fe_bem(run):
    levels = LEVELS[run.fidelity]
    results = {}
    for point, point_levels in levels.items():
        bem, bem_time = run.time(sun2021.dry_contact, HELIX_ANGLE_DEG, point, BEM_CELLS, budget_s=0.0, max_repeat=1)
        theta_bem = bem.bem_angle
        for n, growth in run.progress(point_levels, desc=f"FE levels, point {point}"):
            fe, fe_time = run.time(fe_contact, point, n, growth, bem.hertz, budget_s=0.0, max_repeat=1)
            theta_fe = fe["angle"] - bem.profile_direction
            label = f"{point}, {HELIX_ANGLE_DEG} deg, FE n = b/h {n:g}, growth {growth:g} ({fe['ndofs']} DOFs)"
            run.check(model="fem.mortar", quantity=f"central pressure {label}", unit="Pa", value=fe["p0"],
                      reference=bem.bem.central_pressure, tolerance=PRESSURE_TOLERANCE, time_s=fe_time,
                      source=f"lowmodel.contact.screw_contact BEM {BEM_CELLS} x {BEM_CELLS} on the exact gap",
                      note=f"FE fitted peak {fe['p0'] / 1e6:.2f} MPa at ({fe['centre'][0] * 1e6:.2f}, "
                           f"{fe['centre'][1] * 1e6:.2f}) um; BEM {bem.bem.central_pressure / 1e6:.2f} MPa; "
                           f"full-tensor Hertz {float(bem.hertz.p0) / 1e6:.2f} MPa")
            run.check(model="fem.mortar", quantity=f"rotation theta_s {label}", unit="rad", value=theta_fe,
                      reference=theta_bem, tolerance=ANGLE_TOLERANCE_DEG, scale=math.radians(1.0), why=ANGLE_WHY,
                      time_s=fe_time, source="lowmodel.contact.screw_contact BEM (second-moment ellipse)",
                      note=f"FE {math.degrees(theta_fe):.4f} deg, BEM {math.degrees(theta_bem):.4f} deg, full-tensor "
                           f"Hertz {math.degrees(bem.hertz_angle):.4f} deg; FE major axis "
                           f"{math.degrees(fe['angle']):+.4f} deg from the principal direction")
            for axis in ("a", "b"):
                run.check(model="fem.mortar", quantity=f"semi-axis {axis} {label}", unit="m", value=fe[axis],
                          reference=getattr(bem.bem, f"semi_axis_{axis}"), tolerance=AXIS_TOLERANCE, time_s=fe_time,
                          source="lowmodel.contact.screw_contact BEM (second-moment ellipse)")
            run.note(f"{label}: FE contact force {fe['force']:.4f} N (load control, eq 1 load "
                     f"{sun2021.contact_load():.4f} N); timings "
                     + ", ".join(f"{k} {v:.1f} s" for k, v in fe["timings"].items())
                     + f"; BEM {bem_time:.2f} s")
        results[point] = (bem, fe)
        render3d.surface_artifacts(run, f"bem_{point}", bem.bem.grid.x, bem.bem.grid.y, {
            "pressure_Pa": bem.bem.pressure}, axes=("major axis", "minor axis"),
            title=f"dry BEM at {point}, helix {HELIX_ANGLE_DEG} deg, {BEM_CELLS} x {BEM_CELLS} (the FE's reference)")
    run.save_figure(_profile_figure(results), "fe_bem_profiles.png")
    run.note("The FE gets no gap from the BEM or from Hertz: its gap is that of the meshed sphere and the meshed "
             "helical groove (groove nodes snapped onto the exact surface). Both rotations are read by the same "
             "second-moment estimator; the full-tensor Hertz ellipse lies on the principal frame, so an FE or BEM "
             "angle of 0 from the profile tangent (a Hertz ellipse forced onto the profile frame) fails the check.")
