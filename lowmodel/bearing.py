"""The bearing as a model type: what a linear guide, a ball screw and a single contact are, and the loads they
carry, as frozen dataclasses in SI units (m, rad, N, Pa, s, kg).

Every model of ballbench is built from these descriptions, each by one constructor that takes the description
(docs/architecture.md, "From a case file to a report"):

* :class:`LinearGuide` (ball, grooves, material, friction, speed, an optional oil) and :class:`GuideLoadCase` (its
  balls under load: lin2019 Sec 2.4, Fig 7) -> ``lowmodel.linear_bearing.b2b.contacts``;
* :class:`BallScrew` (ball, grooves, helix, material, drive) and :class:`ScrewLoadCase` (its balls under an axial
  load: lin2019 Sec 3.3) -> ``lowmodel.screw.contacts.module`` and ``lowmodel.screw.b2b.contacts``;
* :class:`ContactLoadCase` (one ball against a flat, a ball, a straight groove or a helical flank under a normal
  force) -> ``lowmodel.contact.hertz.pair_geometry``;
* what an engineer reads of a load case: ``lowmodel.bearing_results.friction`` and ``contact``.

Each field is checked once, here, by :func:`check_field` (:data:`FIELDS`: the physical range and, where a unit
mistake puts a value orders of magnitude off, the plausible range of real bearings, ``lowmodel.checks.PLAUSIBLE``);
the case files (``validation.cases.case_file``) apply the same checks to each key, naming file and line.  A field a
paper does not give is ``None``; a model that needs it says so (:meth:`BallScrew.need`) instead of guessing.

The keyword entry points of the models (``b2b.module_contacts``, ``screw.contacts.screw_module``,
``hertz.ball_in_groove``, ...) stay for the paper figures that sweep one parameter; they build these types or take
their fields.

```python
import math
from ballbench.lowmodel.bearing import GuideLoadCase, LinearGuide, Material
guide = LinearGuide(ball_radius=5e-3, conformity=0.56, nominal_angle=math.radians(45),
                    material=Material(2.1e11, 0.28), friction_coefficient=0.1, groove_velocity=0.01)
case = GuideLoadCase(guide, vertical_force=100.0, side_force_ratio=-0.6,
                     deviations=(-0.0349, 0.0349, 0.0, 0.0))               # lin2019 Table 3 case (a)
from ballbench.lowmodel.linear_bearing import b2b
state = b2b.solve(b2b.contacts(case))
```
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry import helix

__all__ = ["Material", "Lubricant", "Fit", "LinearGuide", "GuideLoadCase", "BallScrew", "ScrewLoadCase",
           "ContactLoadCase", "FIELDS", "check_field", "range_text", "missing", "guide_values", "PAIRS", "READINGS"]

PAIRS = ("flat", "ball", "groove", "screw", "nut")
READINGS = ("tilted", "rotated")

# field -> (range, SI unit, plausible kind): the physical range of each field of the descriptions and, where a unit
# mistake puts a value orders of magnitude off, its key of lowmodel.checks.PLAUSIBLE.  Ranges: "positive" (0, inf),
# "non-negative" [0, inf), "finite", "conformity" (0.5, 1), "contact angle" (0, 90) deg, "poisson" (-1, 0.5),
# "roughness" [0, 10 um], "count" an integer >= 1.
FIELDS: dict[str, tuple[str, str, str]] = {
    "ball_radius": ("positive", "m", "ball_radius"),
    "conformity": ("conformity", "", ""),
    "nominal_angle": ("contact angle", "rad", ""),
    "friction_coefficient": ("non-negative", "", ""),
    "groove_velocity": ("finite", "m/s", ""),
    "youngs_modulus": ("positive", "Pa", "youngs_modulus"),
    "poisson_ratio": ("poisson", "", ""),
    "viscosity": ("positive", "Pa s", ""),
    "density": ("positive", "kg/m^3", ""),
    "roughness": ("roughness", "m", ""),
    "pitch_radius": ("positive", "m", "pitch_radius"),
    "lead": ("non-negative", "m", "lead"),
    "oversize": ("non-negative", "m", "oversize"),
    "nut_speed": ("finite", "rad/s", ""),
    "screw_speed": ("finite", "rad/s", ""),
    "ball_mass": ("positive", "kg", ""),
    "ball_count": ("count", "", ""),
    "preload": ("non-negative", "N", ""),
    "vertical_force": ("positive", "N", ""),
    "side_force_ratio": ("finite", "", ""),
    "n_balls": ("count", "", ""),
    "deviation": ("finite", "rad", "deviation"),
    "axial_load": ("non-negative", "N", "axial_load"),
    "force": ("positive", "N", ""),
}


def check_field(field: str, value, name: str | None = None):
    """``value`` of the description field ``field`` (a key of :data:`FIELDS`) checked against its physical and
    plausible ranges; ValueError naming ``name`` (default ``field``: a case file passes its key) otherwise.  Returns
    the value as a float (an int for a count)."""
    kind, unit, plausible = FIELDS[field]
    name = name or field
    if kind == "count":
        return checks.count(name, value, 1)
    if kind == "positive":
        value = checks.positive(name, value, unit)
    elif kind == "non-negative":
        value = checks.non_negative(name, value, unit)
    elif kind == "finite":
        value = checks.finite(name, value, unit)
    elif kind == "conformity":
        value = checks.conformity(name, value)
    elif kind == "contact angle":
        value = checks.contact_angle(name, value)
    elif kind == "poisson":
        value = checks.bounded(name, value, -1.0, 0.5)
    elif kind == "roughness":  # a raceway's RMS roughness is well under 10 um (ground: 0.05-0.3 um)
        value = checks.bounded(name, value, 0.0, 1e-5, "m", upper_closed=True,
                               note="an RMS roughness of 0.1 um is 1e-7 m")
    if plausible:
        checks.plausible(name, value, plausible)
    return value


def range_text(field: str, shown_unit: str = "", scale: float = 1.0) -> str:
    """The range of ``field`` in words, for a template or a table (``shown_unit``: the unit the plausible range is
    shown in, ``scale`` its SI value)."""
    kind, _, plausible = FIELDS[field]
    if kind == "conformity":
        return "in (0.5, 1)"
    if kind == "contact angle":
        return "in (0, 90) deg"
    if kind == "poisson":
        return "in (-1, 0.5)"
    if plausible and field != "deviation":
        low, high = checks.PLAUSIBLE[plausible][:2]
        return f"plausible {low / scale:.4g} to {high / scale:.4g} {shown_unit}"
    return {"positive": "> 0", "non-negative": ">= 0"}.get(kind, "")


def missing(what: str, field: str, needed_by: str) -> ValueError:
    """The error of a model that needs a field the description leaves ``None``."""
    return ValueError(f"{what} gives no {field}; {needed_by} needs it")


def guide_values(guide, given: dict, defaults: dict | None = None) -> dict:
    """The keyword values of a model that takes a :class:`LinearGuide` or its fields one by one: with ``guide`` its
    fields of the names of ``given`` (``youngs_modulus`` and ``poisson_ratio`` of its material), ValueError where one
    is given beside it; without, the ``given`` values, ``defaults`` where one is None (and ValueError where a value
    without default is None)."""
    if guide is None:
        out = {k: (defaults or {}).get(k) if v is None else v for k, v in given.items()}
        lacking = [k for k, v in out.items() if v is None]
        if lacking:
            raise ValueError(f"give guide (a lowmodel.bearing.LinearGuide) or {', '.join(lacking)}")
        return out
    clash = [k for k, v in given.items() if v is not None]
    if clash:
        raise ValueError(f"give guide or {', '.join(clash)}, not both")
    return {k: getattr(guide.material if k in ("youngs_modulus", "poisson_ratio") else guide, k) for k in given}


def _check_fields(instance, *names: str) -> None:
    """Check the fields ``names`` of a description (None stays None)."""
    for name in names:
        value = getattr(instance, name)
        if value is not None:
            check_field(name, value)


# --------------------------------------------------------------------------
# parts
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Material:
    """Elastic constants of ball and raceways (one steel for both bodies in every paper case)."""

    youngs_modulus: float  # E [Pa]
    poisson_ratio: float   # nu [-]

    def __post_init__(self):
        _check_fields(self, "youngs_modulus", "poisson_ratio")

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
        """E* [Pa] of two bodies of this material: ``E / (2 (1 - nu^2))`` (Johnson 1985 eq 4.22; the same
        arithmetic as ``lowmodel.contact.hertz.contact_modulus``)."""
        from ballbench.lowmodel.contact import hertz  # scipy: reading a case file does not load it

        return hertz.contact_modulus(self.youngs_modulus, self.poisson_ratio)


@dataclass(frozen=True)
class Lubricant:
    """An oil at ambient pressure (sun2021 Table 1)."""

    viscosity: float  # eta_0 [Pa s]
    density: float    # rho_0 [kg/m^3]
    roughness: float | None = None  # composite RMS roughness sigma = sqrt(Rq_1^2 + Rq_2^2) of the surfaces [m]

    def __post_init__(self):
        _check_fields(self, "viscosity", "density", "roughness")


@dataclass(frozen=True)
class Fit:
    """How a value was fitted, so that it can be fitted again (a test does) and read in a report.

    ``target``: the published number the fit reproduces (text with value and source); ``method``: the solver, its
    bracket and tolerance.
    """

    target: str
    method: str


# --------------------------------------------------------------------------
# linear guide
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class LinearGuide:
    """A linear ball guide: ball and grooves, material, friction, the speed of the top groove and an optional oil
    (lin2017 Sec 2, lin2019 Sec 2).  Rail (bottom) and carriage (top) grooves share the conformity."""

    ball_radius: float           # R_B [m]
    conformity: float            # f = groove radius / ball diameter [-]
    nominal_angle: float         # beta_0 [rad], nominal contact angle of all four contacts
    material: Material
    friction_coefficient: float  # mu [-], Coulomb friction of every contact
    groove_velocity: float       # v [m/s], top groove against the bottom one
    lubricant: Lubricant | None = None  # an oil: the EHL rung

    def __post_init__(self):
        _check_fields(self, "ball_radius", "conformity", "nominal_angle", "friction_coefficient", "groove_velocity")

    @property
    def keywords(self) -> dict[str, float]:
        """Ball, grooves, friction, speed and material as the keyword arguments of the lin2019 Sec 2 models
        (``lowmodel.linear_bearing``; the sweeps of one parameter)."""
        return dict(ball_radius=self.ball_radius, conformity=self.conformity,
                    friction_coefficient=self.friction_coefficient, groove_velocity=self.groove_velocity,
                    **self.material.keywords)

    def contact(self, force: float) -> "ContactLoadCase":
        """The ball in this guide's groove under the normal ``force`` [N] (rail and carriage grooves alike)."""
        return ContactLoadCase("groove", self.ball_radius, self.material, force, conformity=self.conformity)


@dataclass(frozen=True)
class GuideLoadCase:
    """Balls of a linear guide under load (lin2019 Sec 2.4, Fig 7): every ball carries ``N_y`` and a side force;
    ball 1 (behind) ``+rho N_y``, ball 2 ``-rho N_y``, alternating (the yaw load of Fig 7).

    ``deviations``: (BL, BR, TR, TL) contact angle deviations [rad] from ``beta_0``, the same for every ball.
    """

    guide: LinearGuide
    vertical_force: float    # N_y [N] on every ball
    side_force_ratio: float  # rho = N_x / N_y of ball 1 [-]
    deviations: tuple        # (BL, BR, TR, TL) [rad]
    n_balls: int = 2

    def __post_init__(self):
        _check_fields(self, "vertical_force", "side_force_ratio", "n_balls")
        if not isinstance(self.deviations, tuple):
            object.__setattr__(self, "deviations", tuple(checks.four_angles("deviations", self.deviations,
                                                                             "(BL, BR, TR, TL)")))
        if len(self.deviations) != 4:
            raise ValueError(f"deviations must be (BL, BR, TR, TL) [rad], got {self.deviations!r}")
        for label, value in zip(("BL", "BR", "TR", "TL"), self.deviations):
            check_field("deviation", value, f"deviations {label}")

    @property
    def theta(self) -> float:
        """The bottom groove deviation theta [rad] of lin2019 Sec 2.4 (``BL = -theta``, ``BR = +theta``)."""
        bl, br = self.deviations[:2]
        if bl != -br:
            raise ValueError(f"the bottom deviations {bl!r}, {br!r} are not (-theta, +theta)")
        return br

    @property
    def top_deviations(self) -> tuple[float, float]:
        """(TR, TL) deviations [rad]."""
        return tuple(self.deviations[2:])

    @property
    def contact_angles(self) -> np.ndarray:
        """(4,) loaded-free contact angles (BL, BR, TR, TL) [rad]: ``beta_0 + deviations``."""
        return self.guide.nominal_angle + np.asarray(self.deviations, dtype=float)

    def side_force(self, ball: int) -> float:
        """N_x [N] of ball ``ball`` (0: behind, ``+rho N_y``; 1: ``-rho N_y``; alternating)."""
        return (1.0 if ball % 2 == 0 else -1.0) * self.side_force_ratio * self.vertical_force

    @property
    def side_forces(self) -> np.ndarray:
        """(n_balls,) N_x [N] of every ball (:meth:`side_force`)."""
        return np.array([self.side_force(j) for j in range(self.n_balls)])


# --------------------------------------------------------------------------
# ball screw
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class BallScrew:
    """A ball screw: ball, grooves, helix, material and drive (fields a paper leaves out are None).

    ``oversize``: the ball's oversize [m], the preload by interference (every contact of a centred ball approaches
    by it); ``oversize_fit``: how it was fitted when the paper gives no preload.
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
        _check_fields(self, *(f.name for f in fields(self) if f.name in FIELDS))

    @property
    def lead_angle(self) -> float:
        """alpha = atan(L / (2 pi R_P)) [rad] (lowmodel.geometry.helix)."""
        return float(helix.lead_angle(self.lead, self.pitch_radius))

    def need(self, *names: str, by: str) -> None:
        """ValueError naming the first of the fields ``names`` that is None (``by``: the model that needs them)."""
        for name in names:
            if getattr(self, name) is None:
                raise missing(f"ball screw R_P {self.pitch_radius * 1e3:g} mm", name, by)

    def contact(self, pair: str, force: float) -> "ContactLoadCase":
        """The ball on this screw's flank of ``pair`` (``"screw"`` or ``"nut"``) at the nominal contact angle under
        the normal ``force`` [N]."""
        checks.choice("pair", pair, ("screw", "nut"))
        return ContactLoadCase(pair, self.ball_radius, self.material, force, screw=self)


@dataclass(frozen=True)
class ScrewLoadCase:
    """Balls of a ball screw under an axial load, each with its screw-side deviation theta (lin2019 Sec 3.3).

    ``reading``: how theta deviates the flanks (docs/ball_screw.md: ``"tilted"``, both screw flanks at
    ``beta_0 + theta``, or ``"rotated"``).
    """

    screw: BallScrew
    axial_load: float   # [N] on the screw, shared by the balls
    deviations: tuple   # theta of each ball [rad]
    reading: str = "tilted"

    def __post_init__(self):
        check_field("axial_load", self.axial_load)
        checks.choice("reading", self.reading, READINGS)
        if not isinstance(self.deviations, tuple):
            try:
                object.__setattr__(self, "deviations", tuple(float(v) for v in self.deviations))
            except (TypeError, ValueError, OverflowError):
                raise ValueError(f"deviations must give theta [rad] of each ball, got {self.deviations!r}") from None
        if not self.deviations:
            raise ValueError("deviations must give theta [rad] of at least one ball")
        for k, value in enumerate(self.deviations):
            check_field("deviation", value, f"deviations[{k}]")

    @property
    def n_balls(self) -> int:
        return len(self.deviations)


# --------------------------------------------------------------------------
# a single contact
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class ContactLoadCase:
    """One ball against a counter body under a normal force.

    ``pair``: ``"flat"``, ``"ball"`` (a ball of the same radius), ``"groove"`` (a straight groove of ``conformity``),
    ``"screw"`` or ``"nut"`` (the helical groove of ``screw``, on its flank at the nominal contact angle).
    """

    pair: str
    ball_radius: float  # R_B [m]
    material: Material
    force: float        # normal force [N]
    conformity: float | None = None
    screw: BallScrew | None = None

    def __post_init__(self):
        checks.choice("pair", self.pair, PAIRS)
        _check_fields(self, "ball_radius", "force", "conformity")
        if (self.pair == "groove") != (self.conformity is not None):
            raise ValueError("conformity is given for (and only for) a groove pair")
        if (self.pair in ("screw", "nut")) != (self.screw is not None):
            raise ValueError("screw is given for (and only for) a screw or nut pair")
        if self.screw is not None and not math.isclose(self.screw.ball_radius, self.ball_radius, rel_tol=0.0):
            raise ValueError("ball_radius must be the screw's ball_radius")
