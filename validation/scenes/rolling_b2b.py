"""Scenes of the B2B force with stick/slip ball-to-groove contacts (docs/b2b_rolling.md).

The model ladder of lin2019's two-ball modules side by side: analytical, low-order full slip, FE-informed full
slip, stick/slip on two half-spaces (Hertz and FE pressure) and on the FE compliance, against ANSYS (lin2019
Tables 3 and 5) and the paper's low-order numbers; and where full slip is worst within the models' domain.
The runs live in :mod:`validation.studies.rolling_b2b` and :mod:`validation.studies.full_slip_map`; the
grids and levels in :mod:`validation.cases.stick_slip`.
"""
from __future__ import annotations

from ballbench.validation.cases import lin2019
from ballbench.validation.figures import render3d
from ballbench.validation.scene import scene
from ballbench.validation.studies import full_slip_map as validity
from ballbench.validation.studies import rolling_b2b as study

_BUDGET = study.TIME_BUDGET_S
_LEVEL = "FE module h 30 um; stick/slip on 20 x 80 cells per contact; FE compliance 8 x 32 cells, P2, h 0.8 cell"


@scene("rolling-b2b-linear-a", "B2B force of lin2019's linear-bearing module, case (a), with stick/slip ball-to-groove "
       "contacts: the ladder from the analytical model to stick/slip on the FE compliance against ANSYS 3.96 N",
       kind="FE", cost_s=375.0, budget_s=_BUDGET, level=_LEVEL,
       case=lin2019.TABLE3_A, show=render3d.show_saved)
def rolling_b2b_linear_a(run):
    study.record_ladder(run, "linear", "a")


@scene("rolling-b2b-linear-b", "B2B force of lin2019's linear-bearing module, case (b) (mitigating top groove), with "
       "stick/slip contacts: zero at every rung", kind="FE", cost_s=375.0, budget_s=_BUDGET, level=_LEVEL,
       case=lin2019.TABLE3_B, show=render3d.show_saved)
def rolling_b2b_linear_b(run):
    study.record_ladder(run, "linear", "b")


@scene("rolling-b2b-screw-a", "B2B force of lin2019's ball-screw module, Table 5 case (a), with stick/slip "
       "ball-to-groove contacts: the ladder from the low-order model to stick/slip on the FE compliance against "
       "ANSYS 1.80 N", kind="FE", cost_s=440.0, budget_s=_BUDGET, level=_LEVEL,
       case=lin2019.TABLE5_A, show=render3d.show_saved)
def rolling_b2b_screw_a(run):
    study.record_ladder(run, "screw", "a")


@scene("rolling-b2b-screw-b", "B2B force of lin2019's ball-screw module, Table 5 case (b), with stick/slip contacts: "
       "the ladder against ANSYS 2.71 N", kind="FE", cost_s=440.0, budget_s=_BUDGET, level=_LEVEL,
       case=lin2019.TABLE5_B, show=render3d.show_saved)
def rolling_b2b_screw_b(run):
    study.record_ladder(run, "screw", "b")


@scene("full-slip-validity-map", "Where lin2019's full slip holds: stick/slip against full slip (B2B force, a free "
       "ball's friction) over mu 0.05-0.5, conformity 0.51-0.6, theta 1-3 deg and three loads, linear bearing and "
       "ball screw (the docs' map)", kind="low-order", default=False, cost_s=3600.0,
       budget_s={"quick": 300.0, "default": 7200.0, "fine": 7200.0})
def full_slip_validity_map(run):
    validity.record_map(run)


@scene("full-slip-validity", "Where lin2019's full slip is worst within the models' domain (the validity map's worst "
       "case): stick/slip against full slip on refined grids, and stick/slip on the FE compliance there",
       kind="FE", cost_s=300.0, budget_s={"quick": 120.0, "default": 600.0, "fine": 3000.0})
def full_slip_validity(run):
    validity.record_worst(run)
