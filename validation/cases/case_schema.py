"""The keys of a case file, declared once (:data:`SCHEMA`): per kind and table its keys with their dimension, meaning,
check and template example; the optional tables of each kind and the models' own checks at load time.  Read by
:mod:`.case_file` (loading, the template, the key list of docs/cases.md)."""
from __future__ import annotations

from dataclasses import dataclass

from ballbench.lowmodel import bearing, model_inputs
from ballbench.lowmodel.bearing import PAIRS, READINGS
from ballbench.validation.cases.case import FINE_ZONES

__all__ = ["KINDS", "SCHEMA", "Key", "LUBRICANT_KEYS", "CARRIAGE_ROWS", "NUT_ARRANGEMENTS", "OPTIONAL_TABLES",
           "MODEL_CHECKS"]

KINDS = ("linear-guide", "ball-screw", "contact")


@dataclass(frozen=True)
class Key:
    """One key of a case file: its dimension (validation.cases.units), what it is, whether it is required, the check of
    its value, its example value in the template, and alternatives (another key that gives the same value, e.g. a
    diameter for a radius).

    The check of a key that gives a field of the bearing's description is that field's own
    (``lowmodel.bearing.check_field``: physical and plausible range, defined once there): ``field`` names it, by
    default the key's name when it is a field (:data:`lowmodel.bearing.FIELDS`).  The other keys (names, choices,
    FE settings) carry their own ``check`` (``"positive"``, ``"choice"``, ``"text"``)."""

    name: str
    dimension: str
    help: str
    required: bool = True
    check: str = ""
    field: str = ""
    example: str = ""
    choices: tuple = ()
    alternative_of: str = ""  # this key gives ``alternative_of`` (times ``scale``)
    scale: float = 1.0
    in_template: bool = True

    @property
    def described(self) -> str:
        """The field of lowmodel.bearing whose check applies to this key ("" for none)."""
        return self.field or (self.name if self.name in bearing.FIELDS else "")


def _material_keys():
    return (Key("youngs_modulus", "pressure", "E, elastic modulus of ball and raceways", example='"210 GPa"'),
            Key("poisson_ratio", "dimensionless", "nu, Poisson's ratio", example="0.3"))


def _level_keys(help_text: str):
    """The ``[fe]`` table's mesh levels per fidelity (``quick`` carries the help)."""
    return tuple(Key(name, "levels", help_text if name == "quick" else "", required=False, in_template=False)
                 for name in ("quick", "default", "fine"))


# table -> keys, per kind; "" is the top level
SCHEMA: dict[str, dict[str, tuple[Key, ...]]] = {
    "linear-guide": {
        "": (Key("kind", "text", "what the file describes", check="choice", choices=KINDS, example='"linear-guide"'),
             Key("name", "text", "a name for the report", check="text", example='"my linear guide"')),
        "guide": (
            Key("ball_radius", "length", "R_B, ball radius (1.5875 mm: a 1/8-inch ball)", example='"1.5875 mm"'),
            Key("ball_diameter", "length", "or the ball diameter (1/8-inch ball: \"0.125 in\")", required=False,
                check="positive", alternative_of="ball_radius", scale=0.5, in_template=False),
            Key("conformity", "dimensionless", "f = groove radius / ball diameter",
                example="0.52"),
            Key("nominal_angle", "angle", "beta_0, nominal contact angle of the four contacts", example='"45 deg"'),
            Key("friction_coefficient", "dimensionless", "mu, Coulomb friction of every contact", example="0.1"),
            Key("groove_velocity", "speed", "v, speed of the carriage (top groove) against the rail",
                example='"100 mm/s"')),
        "material": _material_keys(),
        "load": (
            Key("vertical_force", "force", "N_y, vertical load on every ball", example='"50 N"'),
            Key("side_force_ratio", "dimensionless", "rho = N_x / N_y of ball 1 (ball 2: -rho, alternating)",
                example="-0.6"),
            Key("n_balls", "count", "balls in a row (2: the two-ball module of lin2019 Sec 2.4)", required=False,
                example="2")),
        "deviations": (
            Key("bottom_left", "angle", "BL, contact angle deviation from beta_0 (every ball)", field="deviation",
                example='"-2 deg"'),
            Key("bottom_right", "angle", "BR", field="deviation", example='"2 deg"'),
            Key("top_right", "angle", "TR", field="deviation", example='"0 deg"'),
            Key("top_left", "angle", "TL", field="deviation", example='"0 deg"')),
        "fe": (
            Key("gap_limit", "length", "candidate zone: initial gaps up to this", required=False, check="positive",
                in_template=False),
            Key("fine_ellipse", "list", "fine slab of each contact: (k1 a, k2 b, k3 b)", required=False,
                in_template=False),
            *_level_keys("module mesh levels: [{ h_contact, growth, fine_radius, h_max }, ...]")),
    },
    "ball-screw": {
        "": (Key("kind", "text", "what the file describes", check="choice", choices=KINDS, example='"ball-screw"'),
             Key("name", "text", "a name for the report", check="text", example='"my ball screw"')),
        "screw": (
            Key("ball_radius", "length", "R_B, ball radius (a 6.35 mm ball)", example='"3.175 mm"'),
            Key("ball_diameter", "length", "or the ball diameter", required=False, check="positive",
                alternative_of="ball_radius", scale=0.5, in_template=False),
            Key("pitch_radius", "length", "R_P, radius of the ball-centre helix", example='"16.6 mm"'),
            Key("pitch_diameter", "length", "or the pitch (ball-centre) diameter", required=False, check="positive",
                alternative_of="pitch_radius", scale=0.5, in_template=False),
            Key("lead", "length", "L, axial advance per turn",
                example='"10 mm"'),
            Key("nominal_angle", "angle", "beta_0, nominal contact angle",
                example='"45 deg"'),
            Key("conformity", "dimensionless", "f = groove radius / ball diameter (screw and nut)", example="0.55"),
            Key("friction_coefficient", "dimensionless", "mu, Coulomb friction of every contact", example="0.1"),
            Key("nut_speed", "angular speed", "omega_N, nut speed (the nut drives, the screw is at rest)",
                example='"1 rev/s"'),
            Key("oversize", "length", "ball oversize: preload by interference (every contact approaches by it)",
                required=False, example='"1.5 um"'),
            Key("oversize_fit", "fit", "how the oversize was fitted: { target = \"...\", method = \"...\" }",
                required=False, in_template=False),
            Key("ball_count", "count", "loaded balls of the nut", required=False,
                in_template=False),
            Key("ball_mass", "mass", "mass of one ball", required=False, in_template=False),
            Key("preload", "force", "axial preload of a double nut", required=False,
                in_template=False),
            Key("screw_speed", "angular speed", "omega, screw speed (screw driven)", required=False,
                in_template=False)),
        "material": _material_keys(),
        "load": (
            Key("axial_load", "force", "axial load on the screw, shared by the balls",
                example='"100 N"'),
            Key("deviations", "angle list", "theta of each ball: screw-side contact angle deviation",
                field="deviation", example='["0 deg", "2 deg"]'),
            Key("reading", "text", "how theta deviates the flanks (docs/ball_screw.md)", required=False,
                check="choice", choices=READINGS, example='"tilted"')),
        "lubricant": None,  # the oil's keys, shared with the linear guide (filled below)
        "fe": (
            Key("gap_limit", "length", "", required=False, check="positive", in_template=False),
            Key("body_depth", "dimensionless", "screw core and nut outside at R_P -+ body_depth R_B",
                required=False, check="positive", in_template=False),
            *_level_keys("")),
    },
    "contact": {
        "": (Key("kind", "text", "what the file describes", check="choice", choices=KINDS, example='"contact"'),
             Key("name", "text", "a name for the report", check="text", example='"my ball in a groove"')),
        "contact": (
            Key("pair", "text", "the counter body: flat, ball (same radius), groove (straight), screw or nut "
                "(the helical groove of [screw])", check="choice", choices=PAIRS, example='"groove"'),
            Key("ball_radius", "length", "R_B, ball radius",
                example='"3.175 mm"'),
            Key("ball_diameter", "length", "or the ball diameter", required=False, check="positive",
                alternative_of="ball_radius", scale=0.5, in_template=False),
            Key("conformity", "dimensionless", "f = groove radius / ball diameter (groove pair only)",
                required=False, example="0.54"),
            Key("force", "force", "normal force", example='"200 N"')),
        "material": _material_keys(),
        "screw": None,  # the ball-screw table, for screw and nut pairs (filled below)
        "fe": (
            Key("fine_zone", "text", "capsule or ellipse", required=False, check="choice", choices=FINE_ZONES,
                in_template=False),
            Key("zone", "list", "fine-zone factors", required=False, in_template=False),
            Key("gap_limit", "dimensionless", "candidate zone: initial gaps up to this times the Hertz approach",
                required=False, check="positive", in_template=False),
            Key("fine_targets", "targets", "tolerances of the finest level: { a = 0.002, ... }", required=False,
                in_template=False),
            *_level_keys("pair mesh levels: [{ n, growth }, ...]")),
    },
}
LUBRICANT_KEYS = (
    Key("viscosity", "viscosity", "eta_0 at ambient pressure", example='"0.1 Pa s"'),
    Key("density", "density", "rho_0", example='"870 kg/m^3"'),
    Key("roughness", "length", "sigma = sqrt(Rq_1^2 + Rq_2^2), composite RMS roughness (Lambda = h_min / sigma)",
        required=False, example='"0.14 um"'))
SCHEMA["ball-screw"]["lubricant"] = LUBRICANT_KEYS
SCHEMA["linear-guide"]["lubricant"] = LUBRICANT_KEYS
SCHEMA["contact"]["screw"] = tuple(k for k in SCHEMA["ball-screw"]["screw"] if k.name != "ball_radius"
                                   and k.name != "ball_diameter")
CARRIAGE_ROWS = ("gothic", "four-row")  # lowmodel.linear_bearing.carriage.gothic_rows, four_rows
SCHEMA["linear-guide"]["carriage"] = (
    Key("rows", "text", "gothic: two rows of the guide's four-point balls; four-row: four two-point rows at "
        "nominal_angle", check="choice", choices=CARRIAGE_ROWS, example='"gothic"'),
    Key("half_width", "length", "x of the rows' ball centres from the carriage's reference point", check="positive",
        example='"6 mm"'),
    Key("height", "length", "y of the gothic rows' ball centres", required=False, check="finite", example='"2 mm"'),
    Key("upper", "length", "y of the four-row carriage's upper rows", required=False, check="finite",
        in_template=False),
    Key("lower", "length", "y of its lower rows", required=False, check="finite", in_template=False),
    Key("balls_per_row", "count", "loaded balls of each row", example="12"),
    Key("pitch", "length", "ball spacing along the rail (at least the ball diameter)", check="positive",
        example='"3.4 mm"'),
    Key("oversize", "length", "ball oversize: preload (each contact approaches by half of it)", required=False,
        example='"1 um"'),
    Key("relief_length", "length", "end relief (crowning) of the carriage's grooves: its length at each end",
        required=False, check="non-negative", example='"4 mm"'),
    Key("relief_depth", "length", "and its depth at the end ball", required=False, check="non-negative",
        example='"3 um"'),
    Key("lateral_force", "force", "F_x on the carriage", required=False, check="finite", example='"0 N"'),
    Key("vertical_force", "force", "F_y, pressing the carriage onto the rail", required=False, check="finite",
        example='"400 N"'),
    Key("pitch_moment", "torque", "M_x, about the lateral axis", required=False, check="finite", example='"0 N m"'),
    Key("yaw_moment", "torque", "M_y, about the vertical", required=False, check="finite", example='"0 N m"'),
    Key("roll_moment", "torque", "M_z, about the rail", required=False, check="finite", example='"2 N m"'))
NUT_ARRANGEMENTS = ("single", "double")  # lowmodel.screw.nut.ARRANGEMENTS
NUT_FLANGES = ("loaded end", "far end")  # lowmodel.screw.load_distribution.FLANGES
SCHEMA["ball-screw"]["nut"] = (
    Key("arrangement", "text", "single: one nut preloaded by the ball oversize; double: two halves and a spacer's "
        "preload force", check="choice", choices=NUT_ARRANGEMENTS, example='"single"'),
    Key("turns", "count", "loaded turns (of each half of a double nut)", example="3"),
    Key("balls", "count", "balls in the loaded turns (default: as many as fit less one)", required=False,
        in_template=False),
    Key("preload", "force", "a double nut's preload force", required=False, check="positive", in_template=False),
    Key("axial_load", "force", "F_a on the whole nut", check="positive", example='"1500 N"'),
    Key("nut_outer_radius", "length", "the nut as a tube from R_P + R_B to this (default 1.7 R_P)", required=False,
        check="positive", in_template=False),
    Key("flange", "text", "where the nut is held: at the loaded end (screw in tension, nut in compression; default) "
        "or at the far end (both in tension)", required=False, check="choice", choices=NUT_FLANGES,
        in_template=False),
    Key("deviation_amplitude", "angle", "screw-side contact angle deviation over the turns (lin2019 Sec 3.4)",
        required=False, check="non-negative", example='"1 deg"'),
    Key("deviation_cycles", "count", "its periods over the loaded turns", required=False, example="4"))
OPTIONAL_TABLES = {"linear-guide": {"fe", "lubricant", "carriage"}, "ball-screw": {"fe", "lubricant", "nut"},
                   "contact": {"fe", "screw"}}

# what lin2019's models need of a key beyond its field's range: their own checks (lowmodel.model_inputs), at load
# time; kind -> (table, key) -> (check, the other keys of the table it takes after the key's value)
MODEL_CHECKS = {"linear-guide": {("guide", "friction_coefficient"): (model_inputs.guide_friction_coefficient,),
                                 ("guide", "groove_velocity"): (model_inputs.groove_velocity,)},
                "ball-screw": {("screw", "friction_coefficient"): (model_inputs.screw_friction_coefficient,),
                               ("screw", "nut_speed"): (model_inputs.nut_speed,),
                               ("screw", "pitch_radius"): (model_inputs.screw_pitch_radius, "ball_radius",
                                                           "conformity")}}
