"""What a validation case is: a load case of :mod:`lowmodel.bearing` with a name for the report and the FE settings
of the ladder's rungs, as frozen data in SI.

The bearing itself (linear guide, ball screw, material, lubricant) and the loads it carries are described once, in
the model layer (:mod:`ballbench.lowmodel.bearing`, with the checks of every field); a validation case *is* such a
load case (a subclass that adds ``name`` and ``fe``, both keyword-only), so every model takes it as it takes the
plain description (``lowmodel.linear_bearing.b2b.contacts(case)``, ``lowmodel.bearing_results.friction(case)``).
Three kinds:

* :class:`ContactCase`: one ball against a flat, a ball, a straight groove or the groove of a ball screw, under a
  normal force (:class:`lowmodel.bearing.ContactLoadCase`);
* :class:`LinearGuideCase`: balls of a linear guide between a bottom and a top groove, each with four contact angle
  deviations and its vertical and side load (:class:`lowmodel.bearing.GuideLoadCase`; lin2017, lin2019 Sec 2);
* :class:`BallScrewCase`: balls of a ball screw under an axial load, each with its screw-side contact angle
  deviation (:class:`lowmodel.bearing.ScrewLoadCase`; lin2019 Sec 3).

What belongs to validation stays here: the name, the FE mesh levels (:class:`MeshLevels`; they depend on the case's
contact ellipses; the coarsest level runs at ``quick``, the listed levels of a fidelity run from coarse to fine and
the last one is checked); the TOML schema is :mod:`.case_file`, the published results
:mod:`ballbench.validation.references.published`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from ballbench.lowmodel import checks
from ballbench.lowmodel.bearing import PAIRS, READINGS, ContactLoadCase, GuideLoadCase, ScrewLoadCase

__all__ = ["FIDELITIES", "PAIRS", "READINGS", "FINE_ZONES", "PairLevel", "ModuleLevel", "MeshLevels", "ContactFe",
           "ModuleFe", "LinearGuideCase", "BallScrewCase", "ContactCase", "named"]

FIDELITIES = ("quick", "default", "fine")
FINE_ZONES = ("capsule", "ellipse")


# --------------------------------------------------------------------------
# parts
# --------------------------------------------------------------------------
class PairLevel(NamedTuple):
    """A mesh level of an FE contact pair (fem.hertz_case)."""

    n: float       # elements across the Hertz minor semi-axis b: h_contact = b / n
    growth: float  # rate of the element size away from the fine zone [-]


class ModuleLevel(NamedTuple):
    """A mesh level of an FE four-point or screw module (one ball between two grooves)."""

    h_contact: float            # element size in the fine zone of every contact [m]
    growth: float               # rate of the element size away from it [-]
    fine_radius: float | None   # radius of the ball-shaped fine zone about each contact point [m]; None: the
    #                             elliptic slabs of the case's ``fine_ellipse`` instead
    h_max: float | None = None  # element size far from the contacts [m]; None: the mesh builder's R_B / 3


@dataclass(frozen=True)
class MeshLevels:
    """FE mesh levels per fidelity, each a tuple of levels from coarse to fine; the last one is checked."""

    quick: tuple
    default: tuple
    fine: tuple

    def __post_init__(self):
        for fidelity in FIDELITIES:
            if not getattr(self, fidelity):
                raise ValueError(f"MeshLevels.{fidelity} must list at least one level")

    def __getitem__(self, fidelity: str) -> tuple:
        if fidelity not in FIDELITIES:
            raise ValueError(f"fidelity must be one of {FIDELITIES}, got {fidelity!r}")
        return getattr(self, fidelity)

    def __contains__(self, fidelity) -> bool:
        return fidelity in FIDELITIES

    def checked(self, fidelity: str):
        """The checked (finest listed) level of ``fidelity``."""
        return self[fidelity][-1]


@dataclass(frozen=True)
class ContactFe:
    """FE settings of one contact pair (P2 tetrahedra, mortar contact; fem.hertz_case).

    ``fine_zone`` ``"capsule"``: the fine zone is a ball of radius ``zone[0] b`` swept along the major axis
    over ``|x| <= zone[1] a`` (``zone[1]`` 0 or None: about the point); ``"ellipse"``: the elliptic slab of
    semi-axes ``(zone[0] a, zone[1] b)`` and half-thickness ``zone[2] b`` (meshes.refinement.ellipse_distance);
    a, b are the Hertz semi-axes at the case's force.  ``gap_limit``: the candidate zone holds the surface points
    whose initial gap is at most ``gap_limit`` times the Hertz approach.  ``fine_targets``: extra relative
    tolerances of the finest ``fine`` level (quantity -> tolerance).
    """

    levels: MeshLevels
    fine_zone: str
    zone: tuple
    gap_limit: float = 1.05
    order: int = 2
    formulation: str = "mortar"
    fine_targets: tuple = ()  # ((quantity, tolerance), ...)

    def __post_init__(self):
        checks.choice("fine_zone", self.fine_zone, FINE_ZONES)
        if len(self.zone) != (3 if self.fine_zone == "ellipse" else 2):
            raise ValueError(f"zone of a {self.fine_zone!r} fine zone has {3 if self.fine_zone == 'ellipse' else 2} "
                             f"factors, got {self.zone!r}")


@dataclass(frozen=True)
class ModuleFe:
    """FE settings of a module (one ball between its grooves, fem.fourpoint / fem.screw_module).

    ``gap_limit`` [m]: the candidate zone holds the surface points whose initial gap is at most this;
    ``fine_ellipse``: the fine zone of each contact as an elliptic slab of semi-axes ``(k1 a, k2 b)`` and
    half-thickness ``k3 b`` about its Hertz ellipse (None: a ball of the level's ``fine_radius``);
    ``body_depth``: screw core and nut outside at ``R_P -+ body_depth R_B`` (screw modules; None: the
    builder's default); ``min_cap_angle`` [rad]: the ball's contact caps (the mortar zones) at least this
    half-angle, up to the builder's limit (None: the builder's default, 30 deg; a heavy contact's ellipse
    needs more, docs/truncation.md); ``land_depth``: the grooves' lands ``land_depth R_B`` from the ball centre
    (None: the builders' 0.25, the shoulder convention of docs/truncation.md; less where a heavy contact's
    ellipse needs a longer flank than that); ``per_contact``: the fine zone of each contact meshed at the level's
    ``h_contact`` times its ellipse's ``b`` over the largest ``b`` of the module (every contact ``b / h`` the same;
    False: every contact at ``h_contact``).
    """

    levels: MeshLevels
    gap_limit: float
    fine_ellipse: tuple | None = None
    body_depth: float | None = None
    min_cap_angle: float | None = None
    land_depth: float | None = None
    per_contact: bool = False

    def __post_init__(self):
        checks.positive("gap_limit", self.gap_limit, "m")
        if self.min_cap_angle is not None:
            checks.bounded("min_cap_angle", self.min_cap_angle, 0.0, math.pi / 2, "rad")
        if self.land_depth is not None:
            checks.bounded("land_depth", self.land_depth, 0.0, 1.0, lower_closed=True)


# --------------------------------------------------------------------------
# the cases: a load case of lowmodel.bearing with a name and FE settings
# --------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class LinearGuideCase(GuideLoadCase):
    """Balls of a linear guide under load (:class:`lowmodel.bearing.GuideLoadCase`) with a name and the FE settings
    of its four-point modules; optionally the whole carriage (``carriage``: a
    :class:`lowmodel.linear_bearing.carriage.Carriage`) under its external load (``carriage_load``: a
    :class:`lowmodel.linear_bearing.carriage.Load`), the scene ``<stem>-whole`` (docs/carriage.md)."""

    name: str
    fe: ModuleFe | None = None
    carriage: object = None
    carriage_load: object = None


@dataclass(frozen=True, kw_only=True)
class BallScrewCase(ScrewLoadCase):
    """Balls of a ball screw under an axial load (:class:`lowmodel.bearing.ScrewLoadCase`) with a name and the FE
    settings of its screw modules; optionally the whole nut (``nut``: a :class:`lowmodel.screw.nut.Nut`) under its
    axial load ``nut_load`` [N] with screw-side deviations ``nut_deviation`` (amplitude [rad], cycles over the
    turns), the scene ``<stem>-whole`` (docs/nut.md)."""

    name: str
    fe: ModuleFe | None = None
    nut: object = None
    nut_load: float = 0.0
    nut_deviation: tuple = (0.0, 4)


@dataclass(frozen=True, kw_only=True)
class ContactCase(ContactLoadCase):
    """One ball against a counter body under a normal force (:class:`lowmodel.bearing.ContactLoadCase`) with a name
    and the FE settings of its contact pair."""

    name: str
    fe: ContactFe | None = None


def named(load_case, name: str, fe=None):
    """The validation case of a lowmodel ``load_case`` (a GuideLoadCase, ScrewLoadCase or ContactLoadCase) with
    ``name`` and the FE settings ``fe``."""
    kind = {GuideLoadCase: LinearGuideCase, ScrewLoadCase: BallScrewCase, ContactLoadCase: ContactCase}
    for base, case_type in kind.items():
        if isinstance(load_case, base):
            values = {f: getattr(load_case, f) for f in base.__dataclass_fields__}
            return case_type(**values, name=name, fe=fe)
    raise TypeError(f"named takes a lowmodel.bearing load case, got {type(load_case).__name__}")
