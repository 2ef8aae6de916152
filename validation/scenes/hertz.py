"""Scenes for exact Hertz point contact (lowmodel.contact.hertz)."""
from __future__ import annotations

import warnings

import numpy as np

from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import lin2019
from ballbench.validation.references.hertz import (contact_modulus, ellipse_quadrature, groove_half_curvatures,
                                                   sphere_closed_form)
from ballbench.validation.references.published.lin2019 import PSI
from ballbench.validation.scene import scene

MODEL = "lowmodel.contact.hertz"
HERTZ = dict(model=MODEL, family="analytical")
STEEL = lin2019.STEEL.keywords  # lin2019 Table 1
BALL_RADIUS = lin2019.GUIDE.ball_radius  # m, lin2019 Table 1
LOAD = lin2019.VERTICAL_FORCE  # N, lin2019 Table 1 (N_y)


def _check_sphere(run, geometry, equivalent_radius: float, source: str) -> None:
    contact, time_s = run.time(hertz.solve_load, geometry, LOAD)
    reference = sphere_closed_form(LOAD, equivalent_radius, contact_modulus(**STEEL))  # raw E, nu only
    units = {"a": "m", "b": "m", "delta": "m", "p0": "Pa"}
    for quantity, unit in units.items():
        run.check(**HERTZ, quantity=quantity, unit=unit, value=float(getattr(contact, quantity)),
                  reference=reference[quantity], source=source, tolerance=1e-10, time_s=time_s)
    run.check(**HERTZ, quantity="stiffness", unit="N/m", value=float(contact.stiffness),
              reference=1.5 * LOAD / reference["delta"], source=source + "; dF/d(delta) = 3F/(2 delta)",
              tolerance=1e-10, time_s=time_s)


@scene("hertz-sphere-flat", "Ball (R = 5 mm) on a flat, 100 N, steel: exact Hertz against the closed form",
       kind="analytical", cost_s=0.1)
def hertz_sphere_flat(run):
    geometry = hertz.ball_on_flat(BALL_RADIUS, **STEEL)
    _check_sphere(run, geometry, BALL_RADIUS, "Johnson (1985) eqs 4.22-4.25, R = R_B")


@scene("hertz-ball-ball", "Ball on ball (the B2B contact, R = 5 mm each), 100 N: exact Hertz against the closed form",
       kind="analytical", cost_s=0.1)
def hertz_ball_ball(run):
    geometry = hertz.ball_on_ball(BALL_RADIUS, **STEEL)
    _check_sphere(run, geometry, BALL_RADIUS / 2, "Johnson (1985) eqs 4.22-4.25, R = R_B/2")


@scene("hertz-groove-conformity",
       "Ball in a straight groove, conformity 0.5005 to 0.6, 100 N: exact Hertz against direct quadrature "
       "of the pressure-displacement relation; no warning, NaN or non-monotone semi-axis",
       kind="analytical", cost_s=1.0)
def hertz_groove_conformity(run):
    count = {"quick": 12, "default": 40, "fine": 200}[run.fidelity]
    # denser near 0.5, where the ellipse elongates fastest
    conformity = 0.5 + np.geomspace(0.0005, 0.1, count)
    worst = {"A": 0.0, "B": 0.0, "delta": 0.0, "force": 0.0}
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
        # references from the raw inputs (E, nu, R_B, f, F): the model's pressure field (a, b, p0) must
        # produce the raw curvatures with the raw E* (Boussinesq) and carry the load
        raw_a, raw_b = groove_half_curvatures(BALL_RADIUS, f)
        reference = ellipse_quadrature(float(contact.a), float(contact.b), float(contact.p0), contact_modulus(**STEEL))
        worst["A"] = max(worst["A"], abs(reference["A"] / raw_a - 1), abs(geometry.A / raw_a - 1))
        worst["B"] = max(worst["B"], abs(reference["B"] / raw_b - 1), abs(geometry.B / raw_b - 1))
        worst["delta"] = max(worst["delta"], abs(reference["delta"] / float(contact.delta) - 1))
        worst["force"] = max(worst["force"], abs(reference["force"] / LOAD - 1))
        semi_a.append(float(contact.a))
        semi_b.append(float(contact.b))
    time_s = float(np.median(times))
    source = ("Boussinesq quadrature of the Hertz pressure with E* from E, nu; A, B from R_B and f "
              "(validation/references/hertz.py)")
    for quantity, label in (("A", "curvature A across groove"), ("B", "curvature B along groove"),
                            ("delta", "approach delta"), ("force", "load 2 pi a b p0 / 3")):
        run.check(**HERTZ, quantity=f"worst rel. error of {label} over sweep", unit="1",
                  value=worst[quantity], reference=0.0, scale=1.0, source=source, tolerance=1e-9,
                  why="the value is itself a relative error: zero judged on the scale 1",
                  time_s=time_s, note="value is itself the worst relative error; reference 0 on scale 1")
    semi_a, semi_b = np.array(semi_a), np.array(semi_b)
    non_monotone = int(np.sum(np.diff(semi_a) >= 0) + np.sum(np.diff(semi_b) <= 0))
    non_finite = int(np.sum(~np.isfinite(semi_a)) + np.sum(~np.isfinite(semi_b)))
    run.check(**HERTZ, quantity="non-monotone steps of a (falling) and b (rising)", unit="count",
              value=non_monotone, reference=0.0, scale=1.0, source="Hertz theory: a falls, b rises with conformity",
              why="a count: zero judged on the scale of one",
              tolerance=0.0, time_s=time_s)
    run.check(**HERTZ, quantity="warnings + non-finite values", unit="count",
              value=caught_warnings + non_finite, reference=0.0, scale=1.0,
              source="stability requirement (docs/hertz.md)",
              why="a count: zero judged on the scale of one",
              tolerance=0.0, time_s=time_s)
    run.note(f"Sweep: {count} conformities geometrically spaced from 0.5005 to 0.6, R_B = 5 mm, F = 100 N, "
             f"E = 210 GPa, nu = 0.28; b/a from {semi_b[0] / semi_a[0]:.4f} to {semi_b[-1] / semi_a[-1]:.4f}.")
    from ballbench.validation.figures.hertz import semi_axes_vs_conformity

    run.save_figure(semi_axes_vs_conformity(conformity, semi_a / BALL_RADIUS, semi_b / BALL_RADIUS),
                    "semi_axes_vs_conformity.png")


@scene("lin2019-table1-psi", "Psi of lin2019 eq 15 recomputed from Hertz theory for the Table 1 geometry",
       kind="analytical", cost_s=0.1)
def lin2019_table1_psi(run):
    def model():
        geometry = hertz.ball_in_groove(BALL_RADIUS, lin2019.GUIDE.conformity, **STEEL)
        return hertz.psi_constant(geometry, BALL_RADIUS)

    psi, time_s = run.time(model)
    printed = PSI
    half_unit = 0.0005e-4 / printed  # the table prints 4 significant figures
    run.check(**HERTZ, quantity="Psi", unit="(m^2/N)^(1/3)", value=psi, reference=printed,
              source="lin2019 Table 1", tolerance=half_unit, time_s=time_s,
              note="tolerance = half a unit of the last printed digit")
    run.note("The paper's Psi is the major semi-axis constant of the ball/groove contact "
             "(conformity 0.56, R_B = 5 mm, E = 210 GPa, nu = 0.28): a = Psi R_B^(1/3) F^(1/3). "
             f"Recomputed: {psi:.6e}; the ball-ball contact would give "
             f"{hertz.psi_constant(hertz.ball_on_ball(BALL_RADIUS, **STEEL), BALL_RADIUS):.4e}.")
