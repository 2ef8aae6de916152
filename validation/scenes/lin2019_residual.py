"""Discriminating checks of the numerical B2B model: its state against an independent residual of lin2019 eqs 1-8.

The reference (``validation/references/lin2019.py``) re-evaluates every term of
the ball equilibrium at the model's motion from raw inputs (E, nu, R_B,
conformity, loads, v, mu) with Johnson's Legendre-form Hertz solution and
adaptive Cartesian quadrature of eqs A4-A5; it never calls ``lowmodel``.  Tight
tolerances (1e-6 where the reference quadrature is good to about 1e-9) make
these checks see a wrong axis ratio (Hamrock-Brewe), a wrong friction map, a
missing or mis-signed B2B friction and a wrong B2B loss, which the 3 % band on
F_B2B against the paper's 4.01 N cannot (docs/mutations.md).
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.linear_bearing import b2b
from ballbench.validation.cases import lin2019
from ballbench.validation.references import lin2019 as reference
from ballbench.validation.scene import scene

MODEL = "lowmodel.linear_bearing.b2b"
B2B = dict(model=MODEL, family="low-order numerical")
# lin2019 Table 1 and the Sec 2.4 case (a): theta = 2 deg, rho = -0.6
CASE = lin2019.TABLE3_A
TABLE1 = CASE.guide.keywords
VERTICAL = CASE.vertical_force
THETA, RHO = CASE.theta, CASE.side_force_ratio


@scene("lin2019-b2b-residual", "Numerical B2B model, lin2019 Table 3 case (a): F_B2B, groove friction, B2B friction "
       "and loss against an independent residual of eqs 1-8 (Legendre-form Hertz, adaptive quadrature of A4-A5)",
       kind="low-order", cost_s=2.0, case=CASE)
def b2b_residual(run):
    contacts = b2b.contacts(CASE)
    b2b.solve(contacts, [0.0])  # warm-up: loads the friction map outside the timing
    state, time_s = run.time(b2b.solve, contacts, [0.0])
    sides = np.array([RHO, -RHO]) * VERTICAL
    rows, friction, slip = reference.residual(state.ball_velocity, state.omega, state.b2b_force,
                                              angles=contacts.contact_angles, side_forces=sides,
                                              vertical_force=VERTICAL, **TABLE1)
    source = "lin2019 eqs 1-8, A4-A7 at the model's motion (validation/references/lin2019.py)"
    force = float(state.b2b_force[0])
    run.check(**B2B, quantity="F_B2B against the z-force balance of ball 1 (independent friction)", unit="N",
              value=force, reference=float(friction[0].sum()), source=source, tolerance=1e-6, time_s=time_s,
              note="reference quadrature good to ~1e-9; the model's friction map to ~1e-9 here")
    run.check(**B2B, quantity="worst residual of eqs 4 and 8 (3 rows x 2 balls) / (mu max F)", unit="1",
              value=float(np.max(np.abs(rows))), reference=0.0, scale=1.0, source=source, tolerance=1e-6,
              why="the residual is already divided by mu max F (force rows) and v (velocity rows): zero on the scale 1",
              time_s=time_s, note="moment rows see the B2B friction moment (eqs 6, 8)")
    mu_f = TABLE1["friction_coefficient"] * float(contacts.normal_forces.max())
    run.check(**B2B, quantity="worst groove friction force against independent eq A4 / (mu max F)", unit="1",
              value=float(np.max(np.abs(state.friction_force - friction))) / mu_f, reference=0.0, scale=1.0,
              why="the error is already divided by mu max F: zero judged on the scale 1", source=source,
              tolerance=1e-6, time_s=time_s)
    run.check(**B2B, quantity="B2B friction loss against mu F_B2B |dv| (eqs 5, 7)", unit="W",
              value=float(state.b2b_friction_loss[0]),
              reference=TABLE1["friction_coefficient"] * force * float(slip[0]), source="lin2019 eqs 5 and 7 with "
              "dv from the model's omega", tolerance=1e-12, time_s=time_s)
    run.note(f"F_B2B = {force:.9f} N, independent z balance {float(friction[0].sum()):.9f} N; residual rows "
             f"{np.array2string(rows.ravel(), precision=2)} (units mu max F); B2B slip {slip[0] * 1e3:.6f} mm/s.")
