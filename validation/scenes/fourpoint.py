"""Scenes for the rigid four-point rolling/sliding model (lin2017 Secs 2-3, eqs 39-41, Figs 7, 8, 11, 12).

The closed forms of eqs 38-41 appear here only as references; the model
(lowmodel.linear_bearing.fourpoint) works from the general contact geometry.
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.validation.cases.lin2017 import CASES, case1_angles, case2_angles
from ballbench.validation.figures import lin2017 as figures
from ballbench.validation.scene import relative_error, scene

MODEL = "lowmodel.linear_bearing.fourpoint"
RIGID = dict(model=MODEL, family="analytical")
VERTICAL_FORCE = CASES.vertical_force           # N_y [N]; the maps are normalised by it (lin2017: "a fixed N_y")
BALL_RADIUS = CASES.ball_radius                 # m (drops out of v_B and the loss; sets omega)
MU = CASES.friction_coefficient                 # mu_k (drops out of the state; scales forces and loss)
GROOVE_VELOCITY = CASES.groove_velocity         # v [m/s]
THETA_MAX = CASES.angle_range                   # misalignment / deviation range of the checks and maps
MIRROR = {"BL": "BR", "BR": "BL", "TR": "TL", "TL": "TR"}


def _solve(angles, rho):
    return fourpoint.solve(angles, np.asarray(rho) * VERTICAL_FORCE, VERTICAL_FORCE, ball_radius=BALL_RADIUS,
                           friction_coefficient=MU, groove_velocity=GROOVE_VELOCITY)


def _grid(fidelity):
    return {"quick": (21, 41), "default": (101, 201), "fine": (201, 401)}[fidelity]


def _labels(sliding, pure_rolling):
    names = np.array(fourpoint.CONTACT_NAMES)
    return np.array(["rolling" if rolling else "+".join(names[row]) for row, rolling in zip(sliding, pure_rolling)],
                    dtype=object)


def _map(angles_of, angle_values, rho_values):
    """Sliding-state labels and relative loss P / (mu v N_y) on the (angle, rho) grid; NaN / '' off contact."""
    angle_grid, rho_grid = np.meshgrid(angle_values, rho_values, indexing="ij")
    angles = angles_of(angle_grid)
    lower, upper = fourpoint.contact_limits(angles)
    inside = (rho_grid > lower) & (rho_grid < upper)           # lin2017 eq 37
    state = _solve(angles[inside], rho_grid[inside])
    labels = np.full(angle_grid.shape, "", dtype=object)
    labels[inside] = _labels(state.sliding, state.pure_rolling)
    loss = np.full(angle_grid.shape, np.nan)
    loss[inside] = state.friction_loss / (MU * GROOVE_VELOCITY * VERTICAL_FORCE)
    return labels, loss, inside, (lower, upper)


def _worst(values, references, scale=0.0):
    errors = [relative_error(float(v), float(r), scale=scale) for v, r in zip(values, references)]
    k = int(np.argmax(errors))
    return float(values[k]), float(references[k]), k


def _eq38(angles, rho):
    """lin2017 eq 38 (reference only): K / N_y for the four contacts, (..., 4)."""
    bl, br, tr, tl = np.moveaxis(np.asarray(angles), -1, 0)
    return np.stack([
        (np.sin(br) - rho * np.cos(br)) / np.sin(bl + br) / (np.sin(br + tr) + np.sin(tr + tl) + np.sin(tl - br)),
        (np.sin(bl) + rho * np.cos(bl)) / np.sin(bl + br) / (np.sin(bl + tl) + np.sin(tr + tl) + np.sin(tr - bl)),
        (np.sin(tl) - rho * np.cos(tl)) / np.sin(tl + tr) / (np.sin(bl + br) + np.sin(bl + tl) + np.sin(br - tl)),
        (np.sin(tr) + rho * np.cos(tr)) / np.sin(tl + tr) / (np.sin(bl + br) + np.sin(br + tr) + np.sin(bl - tr)),
    ], axis=-1)


def _unimodal_rows(loss, rho_values, lines):
    """Number of rows of ``loss`` (over ``rho_values``) that rise below ``lines[i]`` and fall above it (NaN ignored)."""
    good = 0
    for row, line in zip(loss, lines):
        below = np.isfinite(row) & (rho_values < line)
        above = np.isfinite(row) & (rho_values > line)
        good += bool(np.all(np.diff(row[below]) > 0) and np.all(np.diff(row[above]) < 0))
    return good


@scene("lin2017-eq39", "Two-point sliding line of case study 1 (angular misalignment) against lin2017 eq 39; "
                       "sliding-state map (Fig 7)", kind="analytical", cost_s=0.6)
def lin2017_eq39(run):
    n_theta, n_rho = _grid(run.fidelity)
    thetas = np.linspace(0.0, THETA_MAX, 51 if run.fidelity != "quick" else 11)
    eq39 = -(1 + np.sin(thetas) - np.cos(thetas)) / (1 + np.sin(thetas) + np.cos(thetas))  # lin2017 eq 39
    blue, time_s = run.time(fourpoint.two_point_sliding_ratio, case1_angles(thetas), "TR", "BR")
    value, reference, k = _worst(blue, eq39, scale=1.0)
    run.check(**RIGID, quantity=f"rho on the K_TR = K_BR line (blue), worst of theta in [0, 5] deg "
                                    f"(theta = {math.degrees(thetas[k]):.2f} deg)", unit="1", value=value,
              reference=reference, source="lin2017 eq 39", tolerance=1e-9, scale=1.0, time_s=time_s,
              why="rho is of order 1 (|rho| < 1.1 in Fig 7) and the line passes rho = 0 at theta = 0",
              note="scale 1: rho = 0 at theta = 0")
    red, time_s = run.time(fourpoint.two_point_sliding_ratio, case1_angles(-thetas), "BL", "TL")
    value, reference, k = _worst(red, -(1 - np.sin(thetas) - np.cos(thetas)) / (1 - np.sin(thetas) + np.cos(thetas)),
                                 scale=1.0)
    run.check(**RIGID, quantity=f"rho on the K_BL = K_TL line (red), worst of theta in [-5, 0] deg "
                                    f"(theta = {-math.degrees(thetas[k]):.2f} deg)", unit="1", value=value,
              reference=reference, source="lin2017 eq 39 (theta < 0)", tolerance=1e-9, scale=1.0, time_s=time_s,
              why="rho is of order 1 (|rho| < 1.1 in Fig 7) and the line passes rho = 0 at theta = 0")

    # the solver's state on, just above and just below the line (theta > 0)
    positive = thetas[1:]
    angles = case1_angles(positive)
    step = 1e-7
    (on, above, below), time_states = run.time(lambda: tuple(_solve(angles, blue[1:] + offset)
                                                             for offset in (0.0, step, -step)))
    expected = (np.all(on.sliding == [False, True, True, False], axis=-1)
                & np.all(above.sliding == [False, False, True, False], axis=-1)
                & np.all(below.sliding == [False, True, False, False], axis=-1))
    run.check(**RIGID, quantity="fraction of theta in (0, 5] deg with BR+TR sliding on the line, TR above, "
                                    "BR below (rho +- 1e-7)", unit="1", value=float(np.mean(expected)), reference=1.0,
              source="lin2017 Sec 3.2 (Fig 7: four one-point regions, two-point lines)", tolerance=0.0,
              time_s=time_states)

    # Fig 7 map: symmetry about the origin (with left/right mirrored) and pure rolling at theta = 0
    theta_values = np.linspace(-THETA_MAX, THETA_MAX, n_theta)
    rho_values = np.linspace(-1.1, 1.1, n_rho)
    (labels, loss, inside, limits), time_map = run.time(_map, case1_angles, theta_values, rho_values)
    mirrored = np.vectorize(lambda s: "+".join(sorted((MIRROR.get(c, c) for c in s.split("+")),
                                                      key=lambda c: fourpoint.CONTACT_NAMES.index(c)))
                            if s not in ("", "rolling") else s, otypes=[object])(labels[::-1, ::-1])
    run.check(**RIGID, quantity="fraction of Fig 7 grid points whose state equals the left/right mirror of "
                                    "the state at (-theta, -rho)", unit="1", value=float(np.mean(labels == mirrored)),
              reference=1.0, source="lin2017 Sec 3.2 ('symmetric about the origin')", tolerance=0.0, time_s=time_map)
    zero = n_theta // 2
    rolling = labels[zero][inside[zero]] == "rolling"
    run.check(**RIGID, quantity="fraction of rho with pure rolling at theta = 0", unit="1",
              value=float(np.mean(rolling)), reference=1.0, source="lin2017 Sec 3.2 ('At theta = 0, pure rolling')",
              tolerance=0.0, time_s=time_map)
    run.check(**RIGID, quantity="max friction loss at theta = 0", unit="W",
              value=float(np.nanmax(loss[zero]) * MU * GROOVE_VELOCITY * VERTICAL_FORCE), reference=0.0,
              source="lin2017 Sec 2.2 (pure rolling: no loss)", tolerance=1e-12,
              scale=MU * GROOVE_VELOCITY * VERTICAL_FORCE, time_s=time_map,
              why="pure rolling loses nothing: zero judged against the loss scale mu v N_y")
    one_point = {label for label in labels[inside] if label and "+" not in label and label != "rolling"}
    run.check(**RIGID, quantity="number of one-point sliding regions in Fig 7", unit="1",
              value=float(len(one_point)), reference=4.0, source="lin2017 Sec 3.2 ('The four regions')",
              tolerance=0.0, time_s=time_map)
    blue_line = fourpoint.two_point_sliding_ratio(case1_angles(theta_values), "TR", "BR")
    red_line = fourpoint.two_point_sliding_ratio(case1_angles(theta_values), "BL", "TL")
    fig = figures.state_figure(theta_values, rho_values, labels, limits,
                        [(np.where(theta_values >= 0, blue_line, np.nan), "navy", "K_TR = K_BR (model)"),
                         (np.where(theta_values <= 0, red_line, np.nan), "darkred", "K_BL = K_TL (model)")],
                        r"angular misalignment $\theta$ [deg]",
                        "lin2017 Fig 7: sliding contact(s), case 1 (45 deg, misalignment theta)")
    run.save_figure(fig, "fig7_sliding_states.png")
    run.note("Eq 39 simplifies to rho = -tan(theta/2); the model finds the line as the zero of K_TR - K_BR, "
             "linear in rho at fixed N_y (eq 36), with K from the minors of eq 7's A_v (eq 23).")


@scene("lin2017-eq41", "Ball motion at rho = 0 (TR sliding) against lin2017 eq 41; pure rolling at theta = 0 (eq 11)",
       kind="analytical", cost_s=0.1)
def lin2017_eq41(run):
    thetas = np.linspace(0.0, THETA_MAX, 51 if run.fidelity != "quick" else 11)
    state, time_s = run.time(_solve, case1_angles(thetas), 0.0)
    v = GROOVE_VELOCITY
    eq41 = v / (1 + np.cos(thetas) + np.sin(thetas))                      # lin2017 eq 41
    value, reference, k = _worst(state.ball_velocity, eq41)
    run.check(**RIGID, quantity=f"v_B, worst of theta in [0, 5] deg (theta = {math.degrees(thetas[k]):.2f} deg)",
              unit="m/s", value=value, reference=reference, source="lin2017 eq 41", tolerance=1e-9, time_s=time_s)
    value, reference, k = _worst(state.omega[:, 0], eq41 * math.sqrt(2) / BALL_RADIUS)
    run.check(**RIGID,
              quantity=f"omega_x, worst of theta in [0, 5] deg (theta = {math.degrees(thetas[k]):.2f} deg)",
              unit="rad/s", value=value, reference=reference, source="lin2017 eq 41", tolerance=1e-9, time_s=time_s)
    scale = v / BALL_RADIUS
    worst = int(np.argmax(np.abs(state.omega[:, 1])))
    run.check(**RIGID, quantity="omega_y, largest |value| over theta in [0, 5] deg", unit="rad/s",
              value=float(state.omega[worst, 1]), reference=0.0, source="lin2017 eq 41", tolerance=1e-9,
              scale=scale, time_s=time_s, note="scale v / R_B",
              why="omega_y = 0 judged against the rolling speed scale v / R_B")
    tr_only = np.all(state.sliding[1:] == [False, False, True, False], axis=-1)
    run.check(**RIGID, quantity="fraction of theta in (0, 5] deg with TR sliding alone", unit="1",
              value=float(np.mean(tr_only)), reference=1.0, source="lin2017 Sec 3.2 ('the TR contact point will be "
              "sliding')", tolerance=0.0, time_s=time_s)
    run.check(**RIGID, quantity="v_B at theta = 0 (pure rolling)", unit="m/s", value=float(state.ball_velocity[0]),
              reference=v / 2, source="lin2017 eq 11 / Sec 3.2 ('translates at v/2')", tolerance=1e-12, time_s=time_s)
    run.check(**RIGID, quantity="largest increase of v_B between neighbouring theta (decreasing)", unit="m/s",
              value=float(np.max(np.diff(state.ball_velocity))), reference=0.0, relation="le", scale=v,
              why="a bound at zero judged against the groove speed v",
              source="lin2017 Sec 3.2 ('translational and rotational velocities decrease')", tolerance=0.0,
              time_s=time_s)
    run.note("Eq 11 as printed lacks the factor v of the numerator; eq 41 carries it (v_B = v/2 at theta = 0).")
    run.note("omega_z = 0 is not computed but follows from the model (lin2017 end of Sec 2.4; docs/fourpoint.md).")


@scene("lin2017-eq40", "Friction loss of case study 1 against lin2017 eq 40 (K of eq 38); power balance; "
                       "relative loss map (Fig 8)", kind="analytical", cost_s=0.5)
def lin2017_eq40(run):
    n_theta, n_rho = _grid(run.fidelity)
    theta_values = np.linspace(-THETA_MAX, THETA_MAX, n_theta)
    rho_values = np.linspace(-0.98, 0.98, n_rho)
    theta_grid, rho_grid = np.meshgrid(theta_values, rho_values, indexing="ij")
    angles = case1_angles(theta_grid)
    lower, upper = fourpoint.contact_limits(angles)
    inside = (rho_grid > lower) & (rho_grid < upper)
    state, time_s = run.time(_solve, angles[inside], rho_grid[inside])
    k_sliding = np.min(_eq38(angles[inside], rho_grid[inside]), axis=-1) * VERTICAL_FORCE     # eq 38
    eq40 = k_sliding * 2 * GROOVE_VELOCITY * MU * np.abs(np.sin(theta_grid[inside]))            # eq 40
    scale = MU * GROOVE_VELOCITY * VERTICAL_FORCE
    value, reference, k = _worst(state.friction_loss, eq40, scale=1e-12 * scale)
    run.check(**RIGID, quantity=f"friction loss, worst of {int(inside.sum())} grid points (theta = "
                                    f"{math.degrees(theta_grid[inside][k]):.2f} deg, rho = {rho_grid[inside][k]:.3f})",
              unit="W", value=value, reference=reference, source="lin2017 eq 40 with K_X of eq 38 (smallest)",
              tolerance=1e-9, scale=1e-12 * scale, time_s=time_s,
              why="the loss is 0 at theta = 0: judged there against 1e-12 mu v N_y",
              note="reference 0 at theta = 0 judged against 1e-12 mu v N_y")
    groove = GROOVE_VELOCITY * (state.friction_forces[:, 2] + state.friction_forces[:, 3])
    value, reference, k = _worst(state.friction_loss, groove, scale=1e-12 * scale)
    run.check(**RIGID, quantity="friction loss vs v (f_TR + f_TL), worst grid point", unit="W", value=value,
              reference=reference, source="power balance (work of the groove drive)", tolerance=1e-9,
              scale=1e-12 * scale, why="the loss is 0 at theta = 0: judged there against 1e-12 mu v N_y", time_s=time_s)

    loss = np.full(theta_grid.shape, np.nan)
    loss[inside] = state.friction_loss / scale
    # Fig 8 trends: loss rises with |theta| at fixed rho (central band); at fixed theta it peaks on the eq 39 line
    band = np.abs(rho_values) <= 0.5
    half = n_theta // 2
    rising = np.concatenate([np.diff(loss[half:, band], axis=0).ravel(),
                             np.diff(loss[half::-1, band], axis=0).ravel()])
    run.check(**RIGID, quantity="fraction of steps in |theta| (|rho| <= 0.5) where the loss rises", unit="1",
              value=float(np.mean(rising > 0)), reference=1.0, tolerance=0.0, time_s=time_s,
              source="lin2017 Sec 3.2 ('friction loss increases with increasing angular misalignment')")
    rows = [i for i in range(n_theta) if i != half]
    line = fourpoint.two_point_sliding_ratio(case1_angles(theta_values[rows]), "TR", "BR")
    run.check(**RIGID, quantity="fraction of theta != 0 whose loss over rho peaks at the two-point line "
                                    "(|rho| <= tan 2.5 deg) and falls on both sides", unit="1",
              value=_unimodal_rows(loss[rows], rho_values, line) / len(rows), reference=1.0, tolerance=0.0,
              time_s=time_s,
              source="lin2017 Sec 3.2 ('smaller side load generally gives rise to more friction loss')")
    fig = figures.loss_figure(theta_values, rho_values, loss, r"angular misalignment $\theta$ [deg]",
                       "lin2017 Fig 8: relative friction loss, case 1")
    run.save_figure(fig, "fig8_relative_loss.png")
    run.note("Relative loss P_f / (mu_k v N_y); the loss-of-contact region (eq 37) is left blank.")


@scene("lin2017-case2", "Case study 2 (TR contact angle deviation alpha): K_BL = K_TR, two- and three-point "
                        "sliding, loss trends (lin2017 Figs 11, 12)", kind="analytical", cost_s=0.8)
def lin2017_case2(run):
    n_alpha, n_rho = _grid(run.fidelity)
    alpha_values = np.linspace(-THETA_MAX, THETA_MAX, n_alpha)
    rho_values = np.linspace(-1.1, 1.1, n_rho)
    (labels, loss, inside, limits), time_map = run.time(_map, case2_angles, alpha_values, rho_values)
    alpha_grid, rho_grid = np.meshgrid(alpha_values, rho_values, indexing="ij")
    state = _solve(case2_angles(alpha_grid[inside]), rho_grid[inside])
    value, reference, k = _worst(state.K[:, 0], state.K[:, 2])
    run.check(**RIGID, quantity="K_BL against K_TR, worst grid point", unit="N", value=value, reference=reference,
              source="lin2017 Sec 3.3 ('K_BL = K_TR')", tolerance=1e-12, time_s=time_map)
    half = n_alpha // 2
    nonzero = [i for i in range(n_alpha) if i != half]
    # positive side of the line where BR (alpha > 0) or TL (alpha < 0) takes over: BL+TR slide together
    other = np.where(alpha_values[nonzero] > 0, "BR", "TL")
    line = np.array([fourpoint.two_point_sliding_ratio(case2_angles(a), "BL", o)
                     for a, o in zip(alpha_values[nonzero], other)])
    mask = (rho_grid[nonzero] > line[:, None] + 1e-9) & inside[nonzero]
    run.check(**RIGID, quantity="fraction of contact points above the three-point line with BL+TR sliding",
              unit="1", value=float(np.mean(labels[nonzero][mask] == "BL+TR")), reference=1.0, tolerance=0.0,
              time_s=time_map, source="lin2017 Sec 3.3 ('two-point sliding (BL and TR) ... for a wide range of "
                                      "positive rho')")
    on = _solve(case2_angles(alpha_values[nonzero]), line)
    expected = np.where((alpha_values[nonzero] > 0)[:, None], [True, True, True, False], [True, False, True, True])
    run.check(**RIGID, quantity="fraction of alpha != 0 with three-point sliding on the boundary line", unit="1",
              value=float(np.mean(np.all(on.sliding == expected, axis=-1))), reference=1.0, tolerance=0.0,
              time_s=time_map, source="lin2017 Sec 3.3 ('Three-point sliding happens at the intersection')")
    band = np.abs(rho_values) <= 0.5
    rising = np.concatenate([np.diff(loss[half:, band], axis=0).ravel(),
                             np.diff(loss[half::-1, band], axis=0).ravel()])
    run.check(**RIGID, quantity="fraction of steps in |alpha| (|rho| <= 0.5) where the loss rises", unit="1",
              value=float(np.mean(rising > 0)), reference=1.0, tolerance=0.0, time_s=time_map,
              source="lin2017 Sec 3.3 ('friction loss increases with increasing contact angle deviation')")
    run.check(**RIGID, quantity="fraction of alpha != 0 whose loss over rho peaks at the three-point line "
                                    "(small |rho|) and falls on both sides", unit="1",
              value=_unimodal_rows(loss[nonzero], rho_values, line) / len(nonzero), reference=1.0, tolerance=0.0,
              time_s=time_map, source="lin2017 Sec 3.3 ('smaller side load generally gives rise to more friction "
                                      "loss')")
    lines = [(np.where(alpha_values > 0, fourpoint.two_point_sliding_ratio(case2_angles(alpha_values), "BL", "BR"),
                       np.nan), "navy", "BL+BR+TR (model)"),
             (np.where(alpha_values < 0, fourpoint.two_point_sliding_ratio(case2_angles(alpha_values), "BL", "TL"),
                       np.nan), "black", "BL+TR+TL (model)")]
    fig = figures.state_figure(alpha_values, rho_values, labels, limits, lines,
                               r"TR contact angle deviation $\alpha$ [deg]",
                               "lin2017 Fig 11: sliding contact(s), case 2 (TR deviation alpha)")
    run.save_figure(fig, "fig11_sliding_states.png")
    fig = figures.loss_figure(alpha_values, rho_values, loss, r"TR contact angle deviation $\alpha$ [deg]",
                              "lin2017 Fig 12: relative friction loss, case 2")
    run.save_figure(fig, "fig12_relative_loss.png")
    run.note("On a tie of K the friction forces and loss are unique, the ball motion is not (lin2017 eq 30); "
             "the model reports the centroid of the admissible motions.")
