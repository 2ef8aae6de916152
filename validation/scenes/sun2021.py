"""Scenes for the dry non-Hertzian contact of sun2021 (Sec 2.2, Sec 4.1-4.2, Figs 7-9).

Model: lowmodel.contact.screw_contact (BEM of lowmodel.contact.halfspace on the exact
helical gap of the geometry core, against full-tensor, profile-frame and helix-free Hertz).
Inputs in the paper's units are converted to SI here.
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel.contact import screw_contact
from ballbench.lowmodel.geometry import helix
from ballbench.validation.scene import scene

MODEL = "lowmodel.contact.screw_contact"

# sun2021 Table 1, SI.  TODO(lead): move to validation/papers/sun2021.py once issue8-val's
# parameters-as-data folder is on main (declared once, here until then).
TABLE_1 = dict(pitch_radius=16e-3,  # "screw radius r" = ball-centre radius: atan(L0 / 2 pi r) = 5.68 deg
               ball_radius=2.9765e-3, groove_radius=3.215e-3,  # r_S = r_N
               lead=10e-3, contact_angle=math.radians(40.26), preload=1500.0, ball_count=168,
               youngs_modulus=200e9, poisson_ratio=0.3, lubricant_density=970.0, viscosity=0.05)
HELIX_ANGLES_DEG = (5.68, 13.97, 21.71)  # sun2021 Sec 4.2 and Fig 9
POINTS = {"A": ("screw", "left"), "B": ("nut", "right")}  # A on the screw, B diametrically opposite on the nut


def _conformity() -> float:
    return TABLE_1["groove_radius"] / (2.0 * TABLE_1["ball_radius"])


def _load() -> float:
    # sun2021 eq 1 at the Table 1 helix angle, held for the parameter study (the paper's Hertz central
    # pressure "does not change with the helix angle", Sec 4.2: the load is fixed)
    lead_angle = float(helix.lead_angle(TABLE_1["lead"], TABLE_1["pitch_radius"]))
    return screw_contact.preload_contact_load(TABLE_1["preload"], TABLE_1["ball_count"], lead_angle,
                                              TABLE_1["contact_angle"])


def _contact(helix_angle_deg: float, point: str, n: int):
    body, flank = POINTS[point]
    lead = float(helix.lead_from_angle(math.radians(helix_angle_deg), TABLE_1["pitch_radius"]))
    return screw_contact.groove_contact(TABLE_1["ball_radius"], _conformity(), TABLE_1["pitch_radius"], lead,
                                        TABLE_1["contact_angle"], _load(), body, flank,
                                        youngs_modulus=TABLE_1["youngs_modulus"],
                                        poisson_ratio=TABLE_1["poisson_ratio"], n=n)


def _difference_figure(results, filename_title):
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(2, len(results), figsize=(4.2 * len(results), 7.5), squeeze=False)
    for column, ((angle, point), contact) in enumerate(results.items()):
        grid = contact.bem.grid
        extent = [grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6]
        top = axes[0, column].imshow(contact.bem.pressure / 1e6, origin="lower", extent=extent, aspect="equal")
        axes[0, column].set_title(f"{point}, helix {angle} deg: BEM p [MPa]\ntheta_s = "
                                  f"{math.degrees(contact.bem_angle):.3f} deg")
        figure.colorbar(top, ax=axes[0, column], shrink=0.8)
        difference = (contact.bem.pressure - contact.hertz_field("flat_helix")) / 1e6
        bound = float(np.max(np.abs(difference)))
        bottom = axes[1, column].imshow(difference, origin="lower", extent=extent, aspect="equal", cmap="RdBu_r",
                                        vmin=-bound, vmax=bound)
        axes[1, column].set_title("BEM - helix-free Hertz [MPa]")
        figure.colorbar(bottom, ax=axes[1, column], shrink=0.8)
        for row in range(2):
            axes[row, column].set_xlabel("y, along the track [um]")
            axes[row, column].set_ylabel("x, across the groove [um]")
    figure.suptitle(filename_title)
    return figure


@scene("sun2021-dry-contact",
       "sun2021 Table 1 ball screw (preload 1500 N, eq 1 load), helix 5.68/13.97/21.71 deg, points A (screw) "
       "and B (nut): BEM on the exact helical gap against full-tensor Hertz (central pressure, rotation); "
       "Fig 9 trends; Figs 7-8 difference maps; which part of the difference is a misoriented Hertz")
def sun2021_dry_contact(run):
    n = {"quick": 96, "default": 192, "fine": 384}[run.fidelity]
    results = {}
    times = []
    for angle in run.progress(HELIX_ANGLES_DEG, desc="helix angles"):
        for point in POINTS:
            contact, time_s = run.time(_contact, angle, point, n, budget_s=0.0, max_repeat=1)
            results[(angle, point)] = contact
            times.append(time_s)
            label = f"{point}, helix {angle} deg"
            run.check(model=MODEL, quantity=f"central pressure {label}", unit="Pa",
                      value=contact.bem.central_pressure, reference=float(contact.hertz.p0),
                      source="full-tensor Hertz (exact curvatures of the swept groove, lowmodel.geometry.groove)",
                      tolerance=5e-3, time_s=time_s,
                      note="BEM on the exact gap; the higher-order gap terms are all that separates the two")
            run.check(model=MODEL, quantity=f"ellipse rotation theta_s {label}", unit="deg",
                      value=math.degrees(contact.bem_angle), reference=math.degrees(contact.hertz_angle),
                      scale=1.0, tolerance=0.01, time_s=time_s,
                      source="principal directions of the exact curvature tensor (issue 14: to 0.01 deg)",
                      note="angle of the major axis from the profile tangent toward the track; tolerance 0.01 "
                           "on a 1-deg scale = 0.01 deg")
    first, last = HELIX_ANGLES_DEG[0], HELIX_ANGLES_DEG[-1]
    total_s = float(sum(times))
    pressure = {k: v.bem.central_pressure for k, v in results.items()}
    run.check(model=MODEL, quantity="Fig 9a: central pressure at A falls with helix angle, p(21.71) - p(5.68)",
              unit="Pa", value=pressure[(last, "A")] - pressure[(first, "A")], reference=0.0, relation="le",
              scale=1e6, tolerance=0.0, time_s=total_s, source="sun2021 Sec 4.2, Fig 9a (trend)")
    run.check(model=MODEL, quantity="Fig 9b: central pressure at B rises with helix angle, p(21.71) - p(5.68)",
              unit="Pa", value=pressure[(last, "B")] - pressure[(first, "B")], reference=0.0, relation="ge",
              scale=1e6, tolerance=0.0, time_s=total_s, source="sun2021 Sec 4.2, Fig 9b (trend)")
    errors = {k: v.bem.central_pressure / float(v.flat_helix.p0) - 1.0 for k, v in results.items()}
    run.check(model=MODEL, quantity="Fig 9c: |error of A| - |error of B| against helix-free Hertz at 21.71 deg",
              unit="1", value=abs(errors[(last, "A")]) - abs(errors[(last, "B")]), reference=0.0,
              relation="ge", scale=1.0, tolerance=0.0, time_s=total_s,
              source="sun2021 Sec 4.2, Fig 9c (error of A larger)")
    for point in POINTS:
        run.check(model=MODEL, quantity=f"Fig 9c: error at {point} grows, |e(21.71)| - |e(5.68)|", unit="1",
                  value=abs(errors[(last, point)]) - abs(errors[(first, point)]), reference=0.0, relation="ge",
                  scale=1.0, tolerance=0.0, time_s=total_s, source="sun2021 Sec 4.2, Fig 9c (errors increase)")
        angles = [abs(results[(a, point)].bem_angle) for a in HELIX_ANGLES_DEG]
        run.check(model=MODEL, quantity=f"Fig 9d: theta_s at {point} grows with helix angle (smallest step)",
                  unit="deg", value=math.degrees(min(np.diff(angles))), reference=0.0, relation="ge", scale=1.0,
                  tolerance=0.0, time_s=total_s, source="sun2021 Sec 4.2, Fig 9d (trend)")
    lines = []
    for (angle, point), contact in results.items():
        bem = contact.bem
        p0 = float(contact.hertz.p0)
        lines.append(
            f"{point} {angle} deg: Q {contact.force:.2f} N, BEM p_c {bem.central_pressure / 1e6:.2f} MPa; Hertz "
            f"full tensor {p0 / 1e6:.2f}, profile frame {float(contact.forced.p0) / 1e6:.2f}, helix-free "
            f"{float(contact.flat_helix.p0) / 1e6:.2f} MPa; error vs helix-free {100 * errors[(angle, point)]:+.3f} %; "
            f"theta_s {math.degrees(contact.bem_angle):+.4f} deg (full-tensor Hertz "
            f"{math.degrees(contact.hertz_angle):+.4f}); max |p_BEM - p_Hertz| / p0: full tensor "
            f"{np.max(np.abs(bem.pressure - contact.hertz_field('hertz'))) / p0:.3f}, profile frame "
            f"{np.max(np.abs(bem.pressure - contact.hertz_field('forced'))) / p0:.3f}, helix-free "
            f"{np.max(np.abs(bem.pressure - contact.hertz_field('flat_helix'))) / p0:.3f}")
    for line in lines:
        run.note(line)
    run.note("Separation of effects: the full-tensor Hertz ellipse already carries the whole rotation (BEM and "
             "full-tensor angles agree to < 0.01 deg), and the BEM's central pressure differs from it only by the "
             "higher-order terms of the exact gap (< 0.1 %).  The trends of Fig 9 (A falls, B rises, error of A "
             "larger, theta_s grows) come from the helix changing the curvature tensor, which a helix-free Hertz "
             "misses; theta_s is a fraction of a degree here.  The largest pointwise differences sit at the contact "
             "edge, where the Hertz field has an infinite slope and the grid a staircase, as sun2021 Figs 7-8 say.")
    run.note("Load: sun2021 eq 1 at the Table 1 helix angle 5.68 deg, held over the helix-angle study (eq 2 needs "
             "sun2021 ref [20]; static, friction and inertia left out).  With eq 1 re-evaluated at each helix angle "
             "the load grows by 1/cos(alpha) (+6.6 % at 21.71 deg) and both central pressures rise.")
    run.note("sun2021 gives no number for Figs 7-9 in the text (figures missing); the trends are checked, the "
             "magnitudes are not comparable.  TODO(lead): declare magnitudes as known gaps once the issue8-val "
             "known-gap mechanism is on main.")
    run.save_figure(_difference_figure({k: v for k, v in results.items() if k[1] == "A"},
                                       "sun2021 Fig 8 analogue (point A)"), "fig8_point_A.png")
    run.save_figure(_difference_figure({k: v for k, v in results.items() if k[0] == HELIX_ANGLES_DEG[-1]},
                                       "sun2021 Fig 7 analogue (21.71 deg)"), "fig7_21deg.png")
