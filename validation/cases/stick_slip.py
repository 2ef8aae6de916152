"""The stick/slip B2B ladders of lin2019's two-ball modules as data (docs/b2b_rolling.md): the rolling grids per
fidelity, the FE compliance levels, and the map of full slip's validity with its worst case (SI).

The modules themselves are lin2019's cases (:data:`ballbench.validation.cases.lin2019.TABLE3`, ``TABLE5``, their FE
module levels ``GUIDE_FE``, ``SCREW_FE``); this module adds what the stick/slip rungs need on top of them.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

from ballbench.lowmodel import checks
from ballbench.validation.cases.case import MeshLevels


class ComplianceLevel(NamedTuple):
    """One FE compliance condensed onto a grid (fem.rolling_compliance, P2 ball-in-groove pair)."""

    cells_along: int   # cells along the groove (Kalker's x)
    cells_across: int  # cells across the groove
    h_factor: float    # element size in the pair's fine slab, in cells (min of dx, dy)


@dataclass(frozen=True)
class StickSlipLevels:
    """The stick/slip rungs of one product's two-ball module.

    ``hertz_cells``: per fidelity, (cells along, across) of each contact's own grid (Hertz and FE pressure on
    two half-spaces; the checked level is the last); ``compliance``: per fidelity, the :class:`ComplianceLevel`
    s condensed (one grid holds every contact of the module; each level is a rung); ``cover``: the
    compliance grid's half-widths (along, across) in the largest Hertz semi-axes of the product's cases;
    ``outside``: the largest share of a contact's force in a piecewise-linear tail beyond the grid's inner cells
    (dropped, the force restored).
    """

    hertz_cells: MeshLevels
    compliance: MeshLevels
    cover: tuple[float, float]
    outside: float = 2e-3

    def __post_init__(self):
        for value in self.cover:
            checks.positive("cover", value)
        checks.bounded("outside", self.outside, 0.0, 0.05, lower_closed=True)


_HERTZ = MeshLevels(quick=((16, 64),), default=((20, 80),), fine=((30, 120),))
# The FE pressure reaches about one element beyond Hertz's ellipse (40 um at the quick level: 1.4 b for the linear
# module's b = 102 um, 1.6 b for the screw's b = 65-70 um): the compliance grid covers it.  The quick level keeps
# the default element size (h 0.8 cell) on fewer cells; the fine level condenses two grids (mesh convergence).
_COMPLIANCE = MeshLevels(quick=(ComplianceLevel(6, 24, 1.0),), default=(ComplianceLevel(8, 32, 0.8),),
                         fine=(ComplianceLevel(6, 24, 1.0), ComplianceLevel(8, 32, 0.8)))
LINEAR = StickSlipLevels(_HERTZ, _COMPLIANCE, cover=(1.4, 1.15))
SCREW = StickSlipLevels(_HERTZ, _COMPLIANCE, cover=(1.7, 1.2))
LEVELS = {"linear": LINEAR, "screw": SCREW}


@dataclass(frozen=True)
class ValidityGrid:
    """The map of full slip's validity over lin2019's two-ball modules (lowmodel.full_slip_validity.validity_map):
    friction coefficients, conformities, deviations theta [deg], loads (linear: N_y [N] per ball; screw: the axial
    load [N]) and the cells of every contact's grid (None: lowmodel.full_slip_validity.GRID_LEVELS, refined while
    the grid error could flip a verdict)."""

    mu: tuple
    conformity: tuple
    theta_deg: tuple
    linear_load: tuple
    screw_load: tuple
    cells: tuple | None = None


MAP = {"quick": ValidityGrid(mu=(0.1, 0.5), conformity=(0.52, 0.6), theta_deg=(3.0,), linear_load=(100.0,),
                             screw_load=(50.0,)),
       "default": ValidityGrid(mu=(0.05, 0.1, 0.2, 0.35, 0.5), conformity=(0.51, 0.53, 0.56, 0.6),
                               theta_deg=(1.0, 3.0), linear_load=(10.0, 100.0, 1000.0),
                               screw_load=(10.0, 50.0, 200.0))}
MAP["fine"] = MAP["default"]


@dataclass(frozen=True)
class WorstCase:
    """Where full slip is off the most within the models' domain: found by the map (docs/b2b_rolling.md,
    'Validity of full slip'), refined on ``cells`` per fidelity, with the FE compliance levels ``compliance``."""

    product: str        # "linear" or "screw"
    mu: float
    conformity: float
    theta_deg: float
    load: float         # N_y per ball [N] (linear) or the axial load [N] (screw)
    cells: dict
    compliance: dict


WORST = WorstCase(product="linear", mu=0.5, conformity=0.6, theta_deg=1.0, load=1000.0,
                  cells={"quick": ((16, 64),), "default": ((16, 64), (24, 96)),
                         "fine": ((16, 64), (24, 96), (32, 128))},
                  compliance={"quick": (), "default": (ComplianceLevel(8, 32, 0.8),),
                              "fine": (ComplianceLevel(8, 32, 0.8),)})
