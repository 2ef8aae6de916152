"""``<stem>-ehl`` of a ball-screw or linear-guide case whose file gives a ``[lubricant]`` (rung ``EHL``): each
distinct contact at
its load and the entrainment speed of the case's kinematics (studies.case_ehl), the smooth isothermal EHL solve
(lowmodel.contact.ehl.solve_reynolds, sun2021 eqs 14-19) on the exact groove gap and the Hamrock-Dowson film
(Hamrock & Dowson 1977) with the full-tensor radii: central and minimum film, U, G, W, k, the central and the
largest pressure against the Hertz p0.  Hamrock-Dowson is judged against the solve (a finding when it misses, within
the ellipticity range of its fit and against a grid-converged solve only); the solve's load balance, ``p >= 0`` and
its grid convergence (h_c and h_min on the level's grid against a second grid, studies.case_ehl) are self-checks
(its Reynolds residual is checked inside the solve, lowmodel.contact.ehl.verify); docs/ehl.md."""
from __future__ import annotations

import numpy as np

from ballbench.validation.ladder.common import EHL_LOAD_TOLERANCE, HAMROCK_DOWSON_TOLERANCE, fmt, truncation_check
from ballbench.validation.cases.case import LinearGuideCase

# where to go when the level's grid is not converged: the next level and its grid (studies.case_ehl.GRID_N)
NEXT_LEVEL = {"quick": "the default level (no --quick; 256 x 64 cells) or --fine (512 x 128)",
              "default": "--fine (512 x 128 cells)",
              "fine": ("a grid finer than --fine gives: studies.case_ehl.ehl_contact(case, pair, load, speed, n=512) "
                       "(1024 x 256 cells)")}

__all__ = ["ehl_scene"]

MODEL = "lowmodel.contact.ehl.solve_reynolds"
HD_MODEL = "Hamrock-Dowson (1977) film (lowmodel.contact.ehl.hamrock_dowson_film)"


def ehl_scene(run, *, case) -> None:
    """The scene function of ``<stem>-ehl`` (``case`` a BallScrewCase with a lubricant)."""
    from ballbench.validation.studies import case_ehl

    truncation_check(run, case)  # the EHL solve's gap is the groove's without its shoulder (docs/truncation.md)
    points = case_ehl.contacts(case, run.fidelity, progress=run.progress)
    lo, hi = case_ehl.ELLIPTICITY_RANGE
    for c in points:
        s, r = c.solution, c.reference
        level = f"{c.label}, {c.grid} cells"
        where = f"{fmt(c.load)} N, U_e {fmt(c.speed)} m/s"
        solve = dict(model=MODEL, family="EHL", level=level, time_s=c.time_s, note=where)
        run.check(**solve, quantity="load balance (sun2021 eq 19)", unit="N", value=s.force, reference=c.load,
                  tolerance=EHL_LOAD_TOLERANCE, source="the contact's load (ladder.rungs.distinct_contacts)")
        run.check(**solve, quantity="min pressure (cavitation p >= 0)", unit="Pa", value=float(np.min(s.pressure)),
                  reference=0.0, relation="ge", scale=1e6, tolerance=0.0,
                  why="sign test: tolerance 0, so any negative pressure fails; 1 MPa only names the unit",
                  source="sun2021 eq 18")
        change = c.grid_change
        converged = c.grid_converged
        why_second = ("the next coarser level's grid" if not c.coarser_failure else
                      f"the next finer level's grid; the coarser one gives no film: {c.coarser_failure}")
        tolerance = case_ehl.GRID_TOLERANCE
        for name, key in (("central film h_c", "h_c"), ("minimum film h_min", "h_min")):
            words = (f"{c.label}: {name} changes {100 * change[key]:.3g} % between the {c.grid} grid and the "
                     f"{c.second_grid} grid ({why_second}), tolerance {100 * tolerance:g} %")
            if change[key] > tolerance:
                words += (f": the film is not grid-converged; run {NEXT_LEVEL[run.fidelity]}; Hamrock-Dowson is not "
                          "judged against this solve")
            run.check(model=MODEL, family="EHL", level=level, time_s=c.time_s + c.second_time_s,
                      quantity=f"grid change of {name}, {c.grid} against {c.second_grid} cells", unit="1",
                      value=change[key], reference=tolerance, relation="le", tolerance=0.0,
                      source=f"the same solve on the {c.second_grid} grid (studies.case_ehl; docs/ehl.md, 'On a "
                             "case file')", note=words)
            if change[key] > tolerance:
                run.note(words + ".")
        if not c.within_fit or not converged:
            continue  # said in the table and the note: outside the fit or not grid-converged, not checked
        for name, key, value in (("central film h_c", "h_c", s.central_film),
                                 ("minimum film h_min", "h_min", s.minimum_film)):
            run.check(model=HD_MODEL, family="analytical", level=level, quantity=name, unit="m", value=r[key],
                      reference=value, tolerance=HAMROCK_DOWSON_TOLERANCE, time_s=0.0, finding=True,
                      source=f"the numerical EHL solve ({MODEL}, {c.grid} cells)",
                      note=f"{where}; the 15 % of the ehl-hamrock-dowson and sun2021-ehl scenes (docs/ehl.md)")
    oil = case_ehl.lubricant(case)
    sigma = oil.roughness
    header = ("contact", "load [N]", "U_e [m/s]", "R_x [mm]", "R_y [mm]", "grid", "h_c solve [nm]", "h_c HD [nm]",
              "h_c HD / solve - 1 [%]", "h_min solve [nm]", "h_min HD [nm]", "h_min HD / solve - 1 [%]", "U", "G",
              "W", "k", "second grid", "h_c grid change [%]", "h_min grid change [%]", "HD checked", "p0 Hertz [MPa]",
              "p centre / p0", "p max / p0", "time [s]")
    rows = [(c.label, fmt(c.load), fmt(c.speed), fmt(c.radius_x * 1e3), fmt(c.radius_y * 1e3), c.grid,
             fmt(c.solution.central_film * 1e9), fmt(c.reference["h_c"] * 1e9),
             fmt(100 * (c.reference["h_c"] / c.solution.central_film - 1), 3), fmt(c.solution.minimum_film * 1e9),
             fmt(c.reference["h_min"] * 1e9), fmt(100 * (c.reference["h_min"] / c.solution.minimum_film - 1), 3),
             fmt(c.reference["U"], 3), fmt(c.reference["G"], 4), fmt(c.reference["W"], 3), fmt(c.reference["k"], 3),
             c.second_grid, fmt(100 * c.grid_change["h_c"], 3), fmt(100 * c.grid_change["h_min"], 3),
             _judged(c, lo, hi), fmt(c.p0 / 1e6),
             fmt(c.solution.central_pressure / c.p0, 3), fmt(c.solution.max_pressure / c.p0, 3), fmt(c.time_s, 3))
            for c in points]
    if sigma is not None:  # Lambda = h_min / sigma (Tallian; Hamrock, Fundamentals of Fluid Film Lubrication)
        header += ("Lambda = h_min / sigma (solve)",)
        rows = [row + (fmt(c.solution.minimum_film / sigma, 3),) for row, c in zip(rows, points)]
    run.table("EHL per distinct contact", header, rows)
    run.note(f"Oil eta_0 {fmt(oil.viscosity)} Pa s, rho_0 {fmt(oil.density)} kg/m^3, Roelands alpha "
             f"(lowmodel.contact.ehl); E' = 2 E*.  U = eta_0 U_e / (E' R_x), G = alpha E', W = F / (E' R_x^2), "
             "k = 1.0339 (R_y/R_x)^0.636; R_x along the track, R_y across the groove (full-tensor radii).  "
             + ("U_e: |V_1 + V_2| / 2 of the ball's and the groove's surface speeds relative to the contact, from "
                "the rigid rolling/sliding state of the four-point ball (lin2017 eqs 1, 4, 6, 7; "
                "lowmodel.linear_bearing.fourpoint) at the carriage speed and the case's contact angles, at the most "
                "loaded contact of the low-order balls (studies.case_ehl)." if isinstance(case, LinearGuideCase) else
                "U_e: wang2022 eqs 1-2 (lowmodel.screw.kinematics) at the drive speed and the nominal contact angle "
                "(studies.case_ehl).")
             + "  h_c at the grid point nearest the contact centre, h_min the smallest film on the grid; the exit "
             "pressure spike sharpens with the grid and its peak does not converge (docs/ehl.md); the films do, where "
             "the grid check says so.  Hamrock-Dowson "
             f"is checked where k lies in its fit's range {lo:g}-{hi:g} and the solve is grid-converged: h_c and "
             f"h_min change by at most {100 * case_ehl.GRID_TOLERANCE:g} % from the level's grid to the next "
             "coarser level's (the finer one where the coarser gives no film; docs/ehl.md).  The solve is smooth; "
             + (f"Lambda = h_min / sigma with the file's composite RMS roughness sigma {fmt(sigma * 1e9)} nm (below 1 "
                "boundary, 1-3 mixed, above 3 full-film lubrication: Hamrock, Fundamentals of Fluid Film "
                "Lubrication): a rough surface changes the film itself (docs/mixed_lubrication.md)." if sigma
                is not None else "no lubricant.roughness in the file: no film-to-roughness ratio."))


def _judged(c, lo: float, hi: float) -> str:
    """The table's words on whether Hamrock-Dowson was judged against the solve of contact ``c``."""
    if not c.grid_converged:
        return (f"no: the solve is not grid-converged (h_min {100 * c.grid_change['h_min']:.3g} %, h_c "
                f"{100 * c.grid_change['h_c']:.3g} % against {c.second_grid})")
    return "yes" if c.within_fit else f"no: k outside {lo:g}-{hi:g}"
