"""What a validation case is: a bearing, its loads and deviations, and its FE settings, as frozen data in SI.

A case is what a scene runs, and what a case file (TOML, read at the edge through one units parser) will
give for a user's own bearing: every model of the ladder (Hertz and the analytical models, the low-order
numerical models, BEM, FE per contact, FE-informed B2B) is built from the case alone
(:mod:`ballbench.validation.studies`).  Three kinds:

* :class:`ContactCase`: one ball against a flat, a ball, a straight groove or the groove of a ball screw,
  under a normal force;
* :class:`LinearGuideCase`: balls of a :class:`LinearGuide` between a bottom and a top groove, each with
  four contact angle deviations and its vertical and side load (lin2017, lin2019 Sec 2);
* :class:`BallScrewCase`: balls of a :class:`BallScrew` under an axial load, each with its screw-side
  contact angle deviation (lin2019 Sec 3).

Fields are SI (m, rad, N, Pa, s, kg); the comment or docstring beside a field names the unit.  A field a
paper does not give is ``None``; a model that needs it says so (``ValueError`` naming the case and field)
instead of guessing.  Published results are not case data: they live in
:mod:`ballbench.validation.references.published`.  FE mesh levels (:class:`MeshLevels`) belong to the case
because they depend on its contact ellipses; the coarsest level runs at ``quick``, the listed levels of a
fidelity run from coarse to fine and the last one is checked.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from ballbench.lowmodel import checks

FIDELITIES = ("quick", "default", "fine")
PAIRS = ("flat", "ball", "groove", "screw", "nut")
FINE_ZONES = ("capsule", "ellipse")
READINGS = ("tilted", "rotated")


def missing(case_name: str, field: str, needed_by: str) -> ValueError:
    """The error of a model that needs a field the case leaves ``None``."""
    return ValueError(f"case {case_name!r} gives no {field}; {needed_by} needs it")


# --------------------------------------------------------------------------
# parts
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Material:
    """Elastic constants of ball and raceways (one steel for both bodies in every paper case)."""

    youngs_modulus: float  # E [Pa]
    poisson_ratio: float   # nu [-]

    def __post_init__(self):
        checks.positive("youngs_modulus", self.youngs_modulus, "Pa")
        checks.bounded("poisson_ratio", self.poisson_ratio, -1.0, 0.5)

    @property
    def keywords(self) -> dict[str, float]:
        """``youngs_modulus`` and ``poisson_ratio`` as keyword arguments of the lowmodel constructors."""
        return {"youngs_modulus": self.youngs_modulus, "poisson_ratio": self.poisson_ratio}

    @property
    def pair(self) -> tuple[float, float]:
        """``(E [Pa], nu)``: the ``materials`` argument of the FE models."""
        return (self.youngs_modulus, self.poisson_ratio)

    @property
    def contact_modulus(self) -> float:
        """E* [Pa] of two bodies of this material (Johnson 1985 eq 4.22, lowmodel.contact.hertz)."""
        from ballbench.lowmodel.contact import hertz

        return hertz.contact_modulus(self.youngs_modulus, self.poisson_ratio)


@dataclass(frozen=True)
class Lubricant:
    """An oil at ambient pressure (sun2021 Table 1)."""

    viscosity: float  # eta_0 [Pa s]
    density: float    # rho_0 [kg/m^3]
    roughness: float | None = None  # composite RMS roughness sigma = sqrt(Rq_1^2 + Rq_2^2) of the surfaces [m]

    def __post_init__(self):
        checks.positive("viscosity", self.viscosity, "Pa s")
        checks.positive("density", self.density, "kg/m^3")
        if self.roughness is not None:  # a raceway's RMS roughness is well under 10 um (ground: 0.05-0.3 um)
            checks.bounded("roughness", self.roughness, 0.0, 1e-5, "m", upper_closed=True,
                           note="an RMS roughness of 0.1 um is 1e-7 m")


@dataclass(frozen=True)
class Fit:
    """How a case value was fitted, so that it can be fitted again (a test does) and read in the report.

    ``target``: the published number the fit reproduces (text with value and source); ``method``: the
    solver, its bracket and tolerance.
    """

    target: str
    method: str


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
    builder's default).
    """

    levels: MeshLevels
    gap_limit: float
    fine_ellipse: tuple | None = None
    body_depth: float | None = None

    def __post_init__(self):
        checks.positive("gap_limit", self.gap_limit, "m")


# --------------------------------------------------------------------------
# bearings
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class LinearGuide:
    """A linear ball guide: ball and grooves, material, friction, the speed of the top groove and an optional oil."""

    ball_radius: float           # R_B [m]
    conformity: float            # f = groove radius / ball diameter [-]
    nominal_angle: float         # beta_0 [rad], nominal contact angle of all four contacts
    material: Material
    friction_coefficient: float  # mu [-], Coulomb friction of every contact
    groove_velocity: float       # v [m/s], top groove against the bottom one
    lubricant: Lubricant | None = None  # an oil: the EHL rung (validation.studies.case_ehl)

    def __post_init__(self):
        checks.positive("ball_radius", self.ball_radius, "m")
        checks.conformity("conformity", self.conformity)
        checks.contact_angle("nominal_angle", self.nominal_angle)
        checks.non_negative("friction_coefficient", self.friction_coefficient)

    @property
    def keywords(self) -> dict[str, float]:
        """Ball, grooves, friction, speed and material as keyword arguments of lowmodel.linear_bearing."""
        return dict(ball_radius=self.ball_radius, conformity=self.conformity,
                    friction_coefficient=self.friction_coefficient, groove_velocity=self.groove_velocity,
                    **self.material.keywords)


@dataclass(frozen=True)
class LinearGuideCase:
    """Balls of a linear guide under load (lin2019 Sec 2.4, Fig 7): every ball carries ``N_y`` and a side
    force; ball 1 (behind) ``+rho N_y``, ball 2 ``-rho N_y``, alternating (the yaw load of Fig 7).

    ``deviations``: (BL, BR, TR, TL) contact angle deviations [rad] from ``beta_0``, the same for every ball.
    """

    name: str
    guide: LinearGuide
    vertical_force: float    # N_y [N] on every ball
    side_force_ratio: float  # rho = N_x / N_y of ball 1 [-]
    deviations: tuple        # (BL, BR, TR, TL) [rad]
    n_balls: int = 2
    fe: ModuleFe | None = None

    def __post_init__(self):
        checks.positive("vertical_force", self.vertical_force, "N")
        if len(self.deviations) != 4:
            raise ValueError(f"deviations must be (BL, BR, TR, TL) [rad], got {self.deviations!r}")
        checks.count("n_balls", self.n_balls, 1)

    @property
    def theta(self) -> float:
        """The bottom groove deviation theta [rad] of lin2019 Sec 2.4 (``BL = -theta``, ``BR = +theta``)."""
        bl, br = self.deviations[:2]
        if bl != -br:
            raise ValueError(f"case {self.name!r}: the bottom deviations {bl!r}, {br!r} are not (-theta, +theta)")
        return br

    @property
    def top_deviations(self) -> tuple[float, float]:
        """(TR, TL) deviations [rad]."""
        return tuple(self.deviations[2:])

    @property
    def contact_angles(self):
        """(4,) loaded-free contact angles (BL, BR, TR, TL) [rad]: ``beta_0 + deviations``."""
        import numpy as np

        return self.guide.nominal_angle + np.asarray(self.deviations, dtype=float)

    def side_force(self, ball: int) -> float:
        """N_x [N] of ball ``ball`` (0: behind, ``+rho N_y``; 1: ``-rho N_y``; alternating)."""
        return (1.0 if ball % 2 == 0 else -1.0) * self.side_force_ratio * self.vertical_force


@dataclass(frozen=True)
class BallScrew:
    """A ball screw: ball, grooves, helix, material and drive (fields a paper leaves out are None).

    ``oversize``: the ball's oversize [m], the preload by interference (every contact of a centred ball
    approaches by it); ``oversize_fit``: how it was fitted when the paper gives no preload.
    """

    ball_radius: float                         # R_B [m]
    pitch_radius: float                        # R_P [m], radius of the ball-centre helix
    lead: float                                # L [m] per turn
    nominal_angle: float                       # beta_0 [rad], nominal contact angle
    conformity: float | None = None            # f = groove radius / ball diameter [-]
    material: Material | None = None
    friction_coefficient: float | None = None  # mu [-]
    nut_speed: float | None = None             # omega_N [rad/s], nut driven, screw at rest (lin2019)
    screw_speed: float | None = None           # omega [rad/s], screw driven (wang2022)
    oversize: float = 0.0                      # [m]
    oversize_fit: Fit | None = None
    ball_mass: float | None = None             # [kg]
    ball_count: int | None = None              # loaded balls of the nut [-]
    preload: float | None = None               # axial preload of a double nut [N] (sun2021)
    lubricant: Lubricant | None = None

    def __post_init__(self):
        checks.positive("ball_radius", self.ball_radius, "m")
        checks.positive("pitch_radius", self.pitch_radius, "m")
        checks.non_negative("lead", self.lead, "m")
        checks.contact_angle("nominal_angle", self.nominal_angle)
        if self.conformity is not None:
            checks.conformity("conformity", self.conformity)
        checks.non_negative("oversize", self.oversize, "m")

    @property
    def lead_angle(self) -> float:
        """alpha = atan(L / (2 pi R_P)) [rad] (lowmodel.geometry.helix)."""
        from ballbench.lowmodel.geometry import helix

        return float(helix.lead_angle(self.lead, self.pitch_radius))

    def need(self, *fields: str, by: str) -> None:
        """ValueError naming the first of ``fields`` that is None (``by``: the model that needs them)."""
        for name in fields:
            if getattr(self, name) is None:
                raise missing(f"ball screw R_P {self.pitch_radius * 1e3:g} mm", name, by)


@dataclass(frozen=True)
class BallScrewCase:
    """Balls of a ball screw under an axial load, each with its screw-side deviation theta (lin2019 Sec 3.3).

    ``reading``: how theta deviates the flanks (docs/ball_screw.md: ``"tilted"``, both screw flanks at
    ``beta_0 + theta``, or ``"rotated"``).
    """

    name: str
    screw: BallScrew
    axial_load: float   # [N] on the screw, shared by the balls
    deviations: tuple   # theta of each ball [rad]
    reading: str = "tilted"
    fe: ModuleFe | None = None

    def __post_init__(self):
        checks.non_negative("axial_load", self.axial_load, "N")
        checks.choice("reading", self.reading, READINGS)
        if not self.deviations:
            raise ValueError("deviations must give theta [rad] of at least one ball")


@dataclass(frozen=True)
class ContactCase:
    """One ball against a counter body under a normal force.

    ``pair``: ``"flat"``, ``"ball"`` (a ball of the same radius), ``"groove"`` (a straight groove of
    ``conformity``), ``"screw"`` or ``"nut"`` (the helical groove of ``screw``, on its flank at the nominal
    contact angle).
    """

    name: str
    pair: str
    ball_radius: float  # R_B [m]
    material: Material
    force: float        # normal force [N]
    conformity: float | None = None
    screw: BallScrew | None = None
    fe: ContactFe | None = None

    def __post_init__(self):
        checks.choice("pair", self.pair, PAIRS)
        checks.positive("ball_radius", self.ball_radius, "m")
        checks.positive("force", self.force, "N")
        if (self.pair == "groove") != (self.conformity is not None):
            raise ValueError("conformity is given for (and only for) a groove pair")
        if (self.pair in ("screw", "nut")) != (self.screw is not None):
            raise ValueError("screw is given for (and only for) a screw or nut pair")
        if self.screw is not None and not math.isclose(self.screw.ball_radius, self.ball_radius, rel_tol=0.0):
            raise ValueError("ball_radius must be the screw's ball_radius")
