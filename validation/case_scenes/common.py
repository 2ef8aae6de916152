"""What the scenes of a case file share (validation.case_scenes): the tolerances they judge by, the number format of
their tables, the per-contact table and the power-balance check of a low-order or FE-informed state."""
from __future__ import annotations

import math

REFERENCE_UNCERTAINTY = 0.01  # the extrapolated FE reference must be known to 1 % to judge models against it
B2B_TOLERANCE = {"linear-guide": 0.07, "ball-screw": 0.10}  # lin2019's own claims, docs/fe_b2b.md
POWER_TOLERANCE = 1e-6  # docs/fe_b2b.md: energy conservation incl. the B2B loss
# a B2B force below this share of the friction scale mu N (N: the ball load) is "near zero" and judged on that
# share instead of on itself (lin2019 Table 3 case (b): 0.13 % of case (a)); above it the relative error counts
NEAR_ZERO_B2B = 0.05
# Hamrock-Dowson's film against the numerical EHL solve: the 15 % the ehl-hamrock-dowson and sun2021-ehl scenes
# judge the solver by (docs/ehl.md, "Checks": the fit itself scatters by about 10 %)
HAMROCK_DOWSON_TOLERANCE = 0.15
EHL_LOAD_TOLERANCE = 1e-4  # load balance of the EHL solve (sun2021 eq 19), as those scenes check it

__all__ = ["B2B_TOLERANCE", "EHL_LOAD_TOLERANCE", "HAMROCK_DOWSON_TOLERANCE", "NEAR_ZERO_B2B", "POWER_TOLERANCE",
           "REFERENCE_UNCERTAINTY", "contact_table", "fmt", "power_check"]


def fmt(value: float, digits: int = 4) -> str:
    """``value`` with ``digits`` significant digits, as the tables of the case scenes show numbers."""
    return f"{value:.{digits}g}"


def contact_table(run, result, what: str) -> None:
    """The per-ball, per-contact table of a GuideResult or ScrewResult (studies.bearing_results) and its CSV."""
    run.table(f"Per ball and contact ({what}, {result.model})",
              ("ball", "contact", "F [N]", "angle [deg]", "a [mm]", "b [mm]", "p0 [MPa]", "approach [um]"),
              [(c.ball, c.contact, fmt(c.normal_force), fmt(math.degrees(c.contact_angle)), fmt(c.a * 1e3),
                fmt(c.b * 1e3), fmt(c.p0 / 1e6), fmt(c.approach * 1e6)) for c in result.contacts])
    run.write_csv("contacts.csv", result.table())


def power_check(run, model: str, state, time_s: float, what: str) -> None:
    """Check the relative power balance of a low-order state (input power against every loss incl. B2B)."""
    balance = (state.input_power - state.total_loss) / state.input_power
    run.check(model=model, family="low-order numerical", quantity=f"power balance (input - losses)/input, {what}",
              unit="1", value=balance, reference=0.0, scale=1.0, tolerance=POWER_TOLERANCE, time_s=time_s,
              source="energy conservation incl. the B2B loss (lin2019 eq 7); docs/fe_b2b.md: 1e-6",
              why="the value is itself a relative power error: zero judged on the scale 1")
