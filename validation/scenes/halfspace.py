"""Scenes for the half-space contact solver (BEM; lowmodel.contact.halfspace) against exact Hertz."""
from __future__ import annotations

from ballbench.lowmodel.contact import halfspace, hertz
from ballbench.validation.cases import lin2019
from ballbench.validation.scene import scene

MODEL = "lowmodel.contact.halfspace"
STEEL = lin2019.STEEL.keywords  # lin2019 Table 1 steel
BALL_RADIUS = lin2019.GUIDE.ball_radius
LOAD = 100.0  # N
TOLERANCE = 5e-3  # docs/halfspace.md: p0, semi-axes and approach within 0.5 % at the default grid
CASES = {
    "ball on flat": lambda: hertz.ball_on_flat(BALL_RADIUS, **STEEL),
    "ball on ball": lambda: hertz.ball_on_ball(BALL_RADIUS, **STEEL),
    "ball in groove f = 0.52": lambda: hertz.ball_in_groove(BALL_RADIUS, 0.52, **STEEL),
    "ball in groove f = 0.56": lambda: hertz.ball_in_groove(BALL_RADIUS, 0.56, **STEEL),
    "ball in groove f = 0.60": lambda: hertz.ball_in_groove(BALL_RADIUS, 0.60, **STEEL),
}
SOURCE = "exact Hertz, lowmodel.contact.hertz (Johnson 1985 Sec 4.2)"


def _solve(geometry, n):
    contact = hertz.solve_load(geometry, LOAD)
    grid = halfspace.hertz_surface_grid(float(contact.a), float(contact.b), n)
    gap = halfspace.quadratic_gap(grid, geometry.A, geometry.B)
    return contact, lambda: halfspace.solve(gap, grid, geometry.contact_modulus, force=LOAD)


def _quantities(contact, result):
    return {"p0": (result.central_pressure, float(contact.p0), "Pa"),
            "a": (result.semi_axis_a, float(contact.a), "m"),
            "b": (result.semi_axis_b, float(contact.b), "m"),
            "delta": (result.approach, float(contact.delta), "m")}


@scene("halfspace-hertz",
       "BEM (Love coefficients, DC-FFT, Polonsky-Keer CG) on the Hertz gap, 100 N, steel, 256 x 256: central "
       "pressure, fitted semi-axes and approach against exact Hertz; grid convergence of the groove f = 0.56",
       kind="low-order", cost_s=3.0)
def halfspace_hertz(run):
    n = 128 if run.fidelity == "quick" else 256
    for name, build in CASES.items():
        contact, model = _solve(build(), n)
        result, time_s = run.time(model, budget_s=0.0, max_repeat=1)
        for quantity, (value, reference, unit) in _quantities(contact, result).items():
            run.check(model=MODEL, family="BEM", level=f"{n} x {n}", quantity=f"{quantity}, {name}, {n} x {n}",
                      unit=unit, value=value,
                      reference=reference, source=SOURCE, tolerance=TOLERANCE, time_s=time_s)
    levels = (32, 64, 128) if run.fidelity != "fine" else (32, 64, 128, 256, 512)
    errors = []
    times = []
    geometry = CASES["ball in groove f = 0.56"]()
    for level in run.progress(levels, desc="grid levels"):
        contact, model = _solve(geometry, level)
        result, time_s = run.time(model, budget_s=0.0, max_repeat=1)
        times.append(time_s)
        errors.append({q: abs(v / r - 1) for q, (v, r, _) in _quantities(contact, result).items()})
    for quantity in ("p0", "a", "b", "delta"):
        worst = min(errors[i][quantity] / errors[i + 1][quantity] for i in range(len(levels) - 1))
        run.check(model=MODEL, family="BEM", level=f"{levels[-2]} x {levels[-2]} to {levels[-1]} x {levels[-1]}",
                  quantity=f"smallest error ratio per grid halving, {quantity}, groove 0.56", unit="1",
                  value=worst, reference=2.0, relation="ge", source="docs/halfspace.md: the error halves or better",
                  tolerance=0.0, time_s=float(sum(times)),
                  note="levels " + ", ".join(str(n) for n in levels) + "; errors "
                  + ", ".join(f"{e[quantity]:.2e}" for e in errors))
    run.note("The fitted semi-axes are those of the Hertz field with the same pressure-weighted second moments "
             "(<x^2> = a^2/5); the central pressure is read at the initial contact point (bilinear in the cell "
             "centres).  Hertz is the reference, computed without the BEM.")
