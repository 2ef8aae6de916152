"""Scenes for exact Hertz point contact (lowmodel.contact.hertz)."""
from __future__ import annotations

import warnings

import numpy as np

from ballbench.lowmodel.contact import hertz
from ballbench.validation.papers.lin2019 import TABLE1
from ballbench.validation.reference_hertz import ellipse_quadrature, sphere_closed_form
from ballbench.validation.scene import scene

MODEL = "lowmodel.contact.hertz"
STEEL = TABLE1.material  # lin2019 Table 1
BALL_RADIUS = TABLE1.ball_radius  # m, lin2019 Table 1
LOAD = TABLE1.vertical_force  # N, lin2019 Table 1 (N_y)


def _check_sphere(run, geometry, equivalent_radius: float, source: str) -> None:
    contact, time_s = run.time(hertz.solve_load, geometry, LOAD)
    reference = sphere_closed_form(LOAD, equivalent_radius, geometry.contact_modulus)
    units = {"a": "m", "b": "m", "delta": "m", "p0": "Pa"}
    for quantity, unit in units.items():
        run.check(model=MODEL, quantity=quantity, unit=unit, value=float(getattr(contact, quantity)),
                  reference=reference[quantity], source=source, tolerance=1e-10, time_s=time_s)
    run.check(model=MODEL, quantity="stiffness", unit="N/m", value=float(contact.stiffness),
              reference=1.5 * LOAD / reference["delta"], source=source + "; dF/d(delta) = 3F/(2 delta)",
              tolerance=1e-10, time_s=time_s)


@scene("hertz-sphere-flat", "Ball (R = 5 mm) on a flat, 100 N, steel: exact Hertz against the closed form")
def hertz_sphere_flat(run):
    geometry = hertz.ball_on_flat(BALL_RADIUS, **STEEL)
    _check_sphere(run, geometry, BALL_RADIUS, "Johnson (1985) eqs 4.22-4.25, R = R_B")


@scene("hertz-ball-ball", "Ball on ball (the B2B contact, R = 5 mm each), 100 N: exact Hertz against the closed form")
def hertz_ball_ball(run):
    geometry = hertz.ball_on_ball(BALL_RADIUS, **STEEL)
    _check_sphere(run, geometry, BALL_RADIUS / 2, "Johnson (1985) eqs 4.22-4.25, R = R_B/2")


@scene("hertz-groove-conformity",
       "Ball in a straight groove, conformity 0.5005 to 0.6, 100 N: exact Hertz against direct quadrature "
       "of the pressure-displacement relation; no warning, NaN or non-monotone semi-axis")
def hertz_groove_conformity(run):
    count = {"quick": 12, "default": 40, "fine": 200}[run.fidelity]
    # denser near 0.5, where the ellipse elongates fastest
    conformity = 0.5 + np.geomspace(0.0005, 0.1, count)
    worst = {"A": 0.0, "B": 0.0, "delta": 0.0}
    semi_a, semi_b, times = [], [], []
    caught_warnings = 0
    for f in run.progress(conformity, desc="conformity sweep"):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")

            def model(f=f):
                return hertz.solve_load(hertz.ball_in_groove(BALL_RADIUS, f, **STEEL), LOAD)

            contact, time_s = run.time(model)
        caught_warnings += len(caught)
        times.append(time_s)
        geometry = hertz.ball_in_groove(BALL_RADIUS, f, **STEEL)
        reference = ellipse_quadrature(float(contact.a), float(contact.b), float(contact.p0),
                                       geometry.contact_modulus)
        worst["A"] = max(worst["A"], abs(reference["A"] / geometry.A - 1))
        worst["B"] = max(worst["B"], abs(reference["B"] / geometry.B - 1))
        worst["delta"] = max(worst["delta"], abs(reference["delta"] / float(contact.delta) - 1))
        semi_a.append(float(contact.a))
        semi_b.append(float(contact.b))
    time_s = float(np.median(times))
    source = "Boussinesq quadrature of the Hertz pressure (validation/reference_hertz.py)"
    for quantity, label in (("A", "curvature A across groove"), ("B", "curvature B along groove"),
                            ("delta", "approach delta")):
        run.check(model=MODEL, quantity=f"worst rel. error of {label} over sweep", unit="1",
                  value=worst[quantity], reference=0.0, scale=1.0, source=source, tolerance=1e-9,
                  time_s=time_s, note="value is itself the worst relative error; reference 0 on scale 1")
    semi_a, semi_b = np.array(semi_a), np.array(semi_b)
    non_monotone = int(np.sum(np.diff(semi_a) >= 0) + np.sum(np.diff(semi_b) <= 0))
    non_finite = int(np.sum(~np.isfinite(semi_a)) + np.sum(~np.isfinite(semi_b)))
    run.check(model=MODEL, quantity="non-monotone steps of a (falling) and b (rising)", unit="count",
              value=non_monotone, reference=0.0, scale=1.0, source="Hertz theory: a falls, b rises with conformity",
              tolerance=0.0, time_s=time_s)
    run.check(model=MODEL, quantity="warnings + non-finite values", unit="count",
              value=caught_warnings + non_finite, reference=0.0, scale=1.0, source="stability requirement (issue 2)",
              tolerance=0.0, time_s=time_s)
    run.note(f"Sweep: {count} conformities geometrically spaced from 0.5005 to 0.6, R_B = 5 mm, F = 100 N, "
             f"E = 210 GPa, nu = 0.28; b/a from {semi_b[0] / semi_a[0]:.4f} to {semi_b[-1] / semi_a[-1]:.4f}.")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6, 4))
    axes.semilogy(conformity, semi_a / BALL_RADIUS, label="a / R_B (across groove)")
    axes.semilogy(conformity, semi_b / BALL_RADIUS, label="b / R_B (along groove)")
    axes.set_xlabel("conformity [-]")
    axes.set_ylabel("semi-axis / ball radius [-]")
    axes.set_title("Hertz ellipse, R_B = 5 mm, F = 100 N")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    run.save_figure(figure, "semi_axes_vs_conformity.png")


@scene("lin2019-table1-psi", "Psi of lin2019 eq 15 recomputed from Hertz theory for the Table 1 geometry")
def lin2019_table1_psi(run):
    def model():
        geometry = hertz.ball_in_groove(BALL_RADIUS, TABLE1.conformity, **STEEL)
        return hertz.psi_constant(geometry, BALL_RADIUS)

    psi, time_s = run.time(model)
    printed = TABLE1.psi
    half_unit = 0.0005e-4 / printed  # the table prints 4 significant figures
    run.check(model=MODEL, quantity="Psi", unit="(m^2/N)^(1/3)", value=psi, reference=printed,
              source="lin2019 Table 1", tolerance=half_unit, time_s=time_s,
              note="tolerance = half a unit of the last printed digit")
    run.note("The paper's Psi is the major semi-axis constant of the ball/groove contact "
             "(conformity 0.56, R_B = 5 mm, E = 210 GPa, nu = 0.28): a = Psi R_B^(1/3) F^(1/3). "
             f"Recomputed: {psi:.6e}; the ball-ball contact would give "
             f"{hertz.psi_constant(hertz.ball_on_ball(BALL_RADIUS, **STEEL), BALL_RADIUS):.4e}.")
