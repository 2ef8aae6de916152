"""Case files: a linear guide, a ball screw or a single contact as TOML, read into the Case types (SI).

Every quantity carries its unit (``"3.175 mm"``, ``"2 deg"``, ``"500 N"``, ``{ value = 3.175, unit = "mm" }``;
validation.cases.units).  The whole file is checked before any work: an unknown key (with "did you mean"), a missing
one, a unit of the wrong dimension or a missing unit, a value outside its physical range (a conformity of 0.5, a
negative load) or outside the plausible range of real bearings (a radius of metres, an elastic modulus of Pa:
lowmodel.checks.PLAUSIBLE); a :class:`CaseFileError` names the file, the line, the key and the range.

The keys of each kind are declared once (:data:`SCHEMA`, :mod:`.case_schema`); :func:`template` writes the commented
file of ``ballbench init`` from the same declarations, and :func:`load` reads it back.  docs/cases.md lists the keys.

    >>> from ballbench.validation.cases import case_file
    >>> case = case_file.loads(case_file.template("linear-guide"), "g.toml")
    >>> case.guide.ball_radius, case.vertical_force                      # SI: m, N
    (0.0015875, 50.0)
"""
from __future__ import annotations

import difflib
import re
import tomllib
from pathlib import Path

from ballbench.lowmodel import bearing, checks, model_inputs
from ballbench.lowmodel.bearing import BallScrew, Fit, LinearGuide, Lubricant, Material
from ballbench.validation.cases import units
from ballbench.validation.cases.case_schema import KINDS, MODEL_CHECKS, OPTIONAL_TABLES, SCHEMA, Key
from ballbench.validation.cases.case import (BallScrewCase, ContactCase, ContactFe, LinearGuideCase,
                                             MeshLevels, ModuleFe, ModuleLevel, PairLevel)

__all__ = ["KINDS", "SCHEMA", "CaseFileError", "Key", "load", "loads", "template", "describe"]


class CaseFileError(ValueError):
    """A mistake in a case file: the message names the file, the line (where it can be found), the key and what
    the key takes."""


_HEADERS = {
    "linear-guide": "A linear guide: balls between a rail (bottom groove) and a carriage (top groove), lin2019 Sec 2.",
    "ball-screw": "A ball screw: two balls of one turn between screw and nut grooves, lin2019 Sec 3.",
    "contact": "One ball against a counter body under a normal force (Hertz, BEM, FE).",
}


# --------------------------------------------------------------------------
# reading
# --------------------------------------------------------------------------
def _lines(text: str) -> dict[tuple[str, str], int]:
    """(table, key) -> 1-based line of its assignment, from a line scan of the TOML text (headers ``[a]``,
    ``[a.b]``; ``key =`` and dotted ``a.key =`` assignments)."""
    where: dict[tuple[str, str], int] = {}
    table = ""
    header = re.compile(r"^\s*\[\s*([A-Za-z0-9_.\-\"' ]+?)\s*\]\s*(#.*)?$")
    assign = re.compile(r"^\s*([A-Za-z0-9_\-.\"']+)\s*=")
    for number, line in enumerate(text.splitlines(), start=1):
        match = header.match(line)
        if match:
            table = match.group(1).replace('"', "").replace("'", "").replace(" ", "")
            where.setdefault((table, ""), number)
            continue
        match = assign.match(line)
        if match:
            key = match.group(1).replace('"', "").replace("'", "")
            full = f"{table}.{key}" if table else key
            head, _, last = full.rpartition(".")
            where.setdefault((head, last), number)
    return where


class _Reader:
    def __init__(self, text: str, path: str):
        self.path = path
        self.lines = _lines(text)

    def error(self, table: str, key: str, message: str) -> CaseFileError:
        line = self.lines.get((table, key)) or self.lines.get((table, ""))
        return CaseFileError(f"{self.path}" + (f", line {line}" if line else "") + f": {message}")

    def check(self, table: str, key: str, function, *args):
        """``function(*args)`` (a model's check of ``table.key``), its ValueError a CaseFileError at that key."""
        try:
            return function(*args)
        except ValueError as error:
            raise self.error(table, key, str(error)) from None

    def value(self, table: str, key: Key, raw):
        where = f"{table}.{key.name}" if table else key.name
        try:
            return _convert(where, key, raw)
        except ValueError as error:
            raise self.error(table, key.name, str(error)) from None


def _convert(where: str, key: Key, raw):  # noqa: C901 - one dispatch over the key kinds of the case schema
    """The SI value of ``raw`` for ``key`` (ValueError naming ``where``)."""
    if key.dimension == "text":
        if not isinstance(raw, str) or not raw.strip():
            raise ValueError(f"{where} must be text, got {raw!r}")
        if key.check == "choice" and raw not in key.choices:
            close = difflib.get_close_matches(raw, key.choices, n=1, cutoff=0.5)
            raise ValueError(f"{where} must be one of {', '.join(repr(c) for c in key.choices)}, got {raw!r}"
                             + (f" (did you mean {close[0]!r}?)" if close else ""))
        return raw
    if key.dimension == "count":
        return checks.count(where, raw, 1)
    if key.dimension == "fit":
        if not (isinstance(raw, dict) and set(raw) == {"target", "method"}
                and all(isinstance(v, str) for v in raw.values())):
            raise ValueError(f'{where} must be {{ target = "...", method = "..." }}, got {raw!r}')
        return Fit(raw["target"], raw["method"])
    if key.dimension == "list":
        if not (isinstance(raw, list) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw)):
            raise ValueError(f"{where} must be a list of numbers, got {raw!r}")
        return tuple(float(checks.finite(where, v)) for v in raw)
    if key.dimension == "targets":
        if not (isinstance(raw, dict) and all(k in ("a", "b", "p0", "delta") for k in raw)):
            raise ValueError(f"{where} must be a table of a, b, p0, delta tolerances, got {raw!r}")
        return tuple((k, float(checks.bounded(f"{where}.{k}", v, 0.0, 1.0))) for k, v in raw.items())
    if key.dimension == "levels":
        return raw  # read with the fe table (it needs the kind)
    if key.dimension == "angle list":
        if not isinstance(raw, list) or not raw:
            raise ValueError(f'{where} must be a list of angles, one per ball, e.g. ["0 deg", "2 deg"], got {raw!r}')
        values = tuple(units.quantity(v, "angle", f"{where}[{k}]") for k, v in enumerate(raw))
        for k, v in enumerate(values):
            bearing.check_field(key.described, v, f"{where}[{k}]")
        return values
    value = units.quantity(raw, key.dimension, where)
    if isinstance(value, list):
        raise ValueError(f"{where} takes one value, got a list")
    _check(where, key, value)
    return value


def _check(where: str, key: Key, value: float) -> None:
    """The check of ``key``'s value: its description field's (lowmodel.bearing.check_field), else the key's own."""
    if key.described:
        bearing.check_field(key.described, value, where)
        return
    unit = units.SI_UNIT.get(key.dimension, "")
    unit = "" if unit == "1" else unit
    if key.check == "positive":
        checks.positive(where, value, unit)
    elif key.check == "finite":
        checks.finite(where, value, unit)
    elif key.check == "non-negative":
        checks.non_negative(where, value, unit)


def _table(reader: _Reader, data: dict, kind: str, table: str, *, required: bool) -> dict:
    """The SI values of one table of a ``kind`` file: unknown keys, alternatives, missing keys."""
    keys = SCHEMA[kind][table]
    raw = data if table == "" else data.get(table)
    if raw is None:
        if required:
            raise reader.error("", "", f"missing table [{table}] (a {kind} file has "
                                       f"{', '.join(f'[{t}]' for t in SCHEMA[kind] if t)})")
        return {}
    if not isinstance(raw, dict):
        raise reader.error("", table, f"{table} must be a table [{table}]")
    names = {k.name: k for k in keys}
    allowed = set(names) | ({t for t in SCHEMA[kind] if t} if table == "" else set())
    for name in raw:
        if name not in allowed:
            close = difflib.get_close_matches(name, sorted(allowed), n=2, cutoff=0.6)
            where = f"{table}.{name}" if table else name
            raise reader.error(table, name, f"unknown key {where!r}" + (
                f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else "") +
                f"; [{table or 'top level'}] takes {', '.join(sorted(allowed))}")
    values = {}
    for name, value in raw.items():
        if name in names:
            values[name] = reader.value(table, names[name], value)
    for key in keys:
        if key.alternative_of and key.name in values:
            if key.alternative_of in values:
                raise reader.error(table, key.name, f"give {table}.{key.alternative_of} or {table}.{key.name}, "
                                                    "not both")
            target = names[key.alternative_of]
            value = values.pop(key.name) * key.scale
            try:
                _check(f"{table}.{key.name} / 2", target, value)
            except ValueError as error:
                raise reader.error(table, key.name, str(error)) from None
            values[key.alternative_of] = value
    for key in keys:
        if key.required and not key.alternative_of and key.name not in values:
            others = [k.name for k in keys if k.alternative_of == key.name]
            raise reader.error(table, "", f"missing key {table + '.' if table else ''}{key.name} ({key.help}"
                                          + (f"; or {', '.join(others)}" if others else "") + ")")
    return values


def _material(values: dict) -> Material:
    return Material(values["youngs_modulus"], values["poisson_ratio"])


def _levels(reader: _Reader, table: dict, level_type: str) -> MeshLevels | None:
    given = {f: table.get(f) for f in ("quick", "default", "fine")}
    if all(v is None for v in given.values()):
        return None
    out = {}
    for fidelity, raw in given.items():
        where = f"fe.{fidelity}"
        if not isinstance(raw, list) or not raw:
            raise reader.error("fe", fidelity, f"{where} must list the mesh levels of every fidelity (quick, "
                                               "default, fine), each a list of tables")
        levels = []
        for k, entry in enumerate(raw):
            if not isinstance(entry, dict):
                raise reader.error("fe", fidelity, f"{where}[{k}] must be a table, got {entry!r}")
            try:
                levels.append(_level(f"{where}[{k}]", entry, level_type))
            except ValueError as error:
                raise reader.error("fe", fidelity, str(error)) from None
        out[fidelity] = tuple(levels)
    return MeshLevels(**out)


def _level(where: str, entry: dict, level_type: str):
    if level_type == "pair":
        allowed = {"n", "growth"}
        if set(entry) != allowed:
            raise ValueError(f"{where} must be {{ n = elements across b, growth = rate }}, got keys {sorted(entry)}")
        return PairLevel(float(checks.positive(f"{where}.n", entry["n"])),
                         float(checks.bounded(f"{where}.growth", entry["growth"], 1.0, 3.0, upper_closed=True)))
    allowed = {"h_contact", "growth", "fine_radius", "h_max"}
    if not set(entry) <= allowed or not {"h_contact", "growth"} <= set(entry):
        raise ValueError(f"{where} must be {{ h_contact = \"30 um\", growth = 1.4 }} (optionally fine_radius, h_max), "
                         f"got keys {sorted(entry)}")
    h = checks.positive(f"{where}.h_contact", units.quantity(entry["h_contact"], "length", f"{where}.h_contact"), "m")
    growth = float(checks.bounded(f"{where}.growth", entry["growth"], 1.0, 3.0, upper_closed=True))
    fine, h_max = (checks.positive(f"{where}.{k}", units.quantity(entry[k], "length", f"{where}.{k}"), "m")
                   if k in entry else None for k in ("fine_radius", "h_max"))  # None: the mesh builder's
    return ModuleLevel(h, growth, fine, h_max)


def _screw(values: dict, material: Material, lubricant: Lubricant | None) -> BallScrew:
    extra = {k: values[k] for k in ("oversize", "oversize_fit", "ball_count", "ball_mass", "preload", "screw_speed")
             if k in values}
    return BallScrew(ball_radius=values["ball_radius"], pitch_radius=values["pitch_radius"], lead=values["lead"],
                     nominal_angle=values["nominal_angle"], conformity=values["conformity"], material=material,
                     friction_coefficient=values["friction_coefficient"], nut_speed=values["nut_speed"],
                     lubricant=lubricant, **extra)


def _lubricant(tables: dict) -> Lubricant | None:
    lub = tables.get("lubricant")
    return Lubricant(lub["viscosity"], lub["density"], lub.get("roughness")) if lub else None


def _build(reader: _Reader, data: dict):  # noqa: C901 - one dispatch over the three case kinds and their tables
    kind = data.get("kind")
    if kind not in KINDS:
        close = difflib.get_close_matches(str(kind), KINDS, n=1, cutoff=0.5) if isinstance(kind, str) else []
        raise reader.error("", "kind", f"kind must be one of {', '.join(repr(k) for k in KINDS)}"
                                       + (f", got {kind!r}" if kind is not None else " (the first line of the file)")
                                       + (f" (did you mean {close[0]!r}?)" if close else ""))
    top = _table(reader, data, kind, "", required=True)
    tables = {t: _table(reader, data, kind, t, required=t not in OPTIONAL_TABLES[kind]) for t in SCHEMA[kind] if t}
    for (table, key), (check, *others) in MODEL_CHECKS.get(kind, {}).items():
        values = tables[table]
        reader.check(table, key, check, values[key], *(values[k] for k in others), f"{table}.{key}")
    material = _material(tables["material"])
    fe_raw = data.get("fe", {})
    name = top["name"]
    try:
        if kind == "linear-guide":
            g, load, dev = tables["guide"], tables["load"], tables["deviations"]
            guide = LinearGuide(g["ball_radius"], g["conformity"], g["nominal_angle"], material,
                                g["friction_coefficient"], g["groove_velocity"], _lubricant(tables))
            f, levels = tables["fe"], _levels(reader, fe_raw, "module")
            fe = None if levels is None else ModuleFe(levels, f.get("gap_limit", 6e-6), f.get("fine_ellipse"))
            deviations = (dev["bottom_left"], dev["bottom_right"], dev["top_right"], dev["top_left"])
            body, carriage_load = _carriage(reader, tables.get("carriage"), guide, deviations)
            case = LinearGuideCase(guide, load["vertical_force"], load["side_force_ratio"], deviations,
                                   load.get("n_balls", 2), name=name, fe=fe, carriage=body,
                                   carriage_load=carriage_load)
            reader.check("load", "side_force_ratio", model_inputs.four_point_contact, case.side_forces,
                         case.vertical_force, case.contact_angles, "load.side_force_ratio")  # every ball's
            return case
        if kind == "ball-screw":
            screw = _screw(tables["screw"], material, _lubricant(tables))
            load = tables["load"]
            f, levels = tables["fe"], _levels(reader, fe_raw, "module")
            fe = None if levels is None else ModuleFe(levels, f.get("gap_limit", 5e-6), None, f.get("body_depth"))
            nut, nut_load, deviation = _nut(reader, tables.get("nut"), screw)
            return BallScrewCase(screw, load["axial_load"], load["deviations"], load.get("reading", "tilted"),
                                 name=name, fe=fe, nut=nut, nut_load=nut_load, nut_deviation=deviation)
        c = tables["contact"]
        pair = c["pair"]
        if (pair == "groove") != ("conformity" in c):
            raise reader.error("contact", "conformity", "contact.conformity is given for (and only for) pair = "
                                                        "\"groove\"")
        screw = None
        if pair in ("screw", "nut"):
            if not tables.get("screw"):
                raise reader.error("contact", "pair", f"pair = {pair!r} needs a [screw] table (the helical groove)")
            s = {**tables["screw"], "ball_radius": c["ball_radius"]}
            for key in SCHEMA["contact"]["screw"]:
                if key.required and not key.alternative_of and key.name not in s:
                    raise reader.error("screw", "", f"missing key screw.{key.name} ({key.help})")
            screw = _screw(s, material, None)
        elif tables.get("screw"):
            raise reader.error("screw", "", f"[screw] belongs to a screw or nut pair, not pair = {pair!r}")
        fe = None
        levels = _levels(reader, fe_raw, "pair")
        if levels is not None:
            f = tables["fe"]
            if "fine_zone" not in f or "zone" not in f:
                raise reader.error("fe", "", "explicit levels need fe.fine_zone and fe.zone")
            fe = ContactFe(levels, f["fine_zone"], f["zone"], f.get("gap_limit", 1.05),
                           fine_targets=f.get("fine_targets", ()))
        return ContactCase(pair, c["ball_radius"], material, c["force"], c.get("conformity"), screw, name=name, fe=fe)
    except CaseFileError:
        raise
    except ValueError as error:  # a check across keys (e.g. a pitch radius inside the groove)
        raise reader.error("", "", str(error)) from None


def _carriage(reader: _Reader, table: dict | None, guide: LinearGuide, deviations: tuple):
    """The whole carriage of a ``[carriage]`` table (lowmodel.linear_bearing.carriage): gothic rows of the guide's
    four-point balls at ``nominal_angle + deviations``, or four two-point rows at ``nominal_angle``; and its load."""
    if not table:
        return None, None
    from ballbench.lowmodel.linear_bearing import carriage  # the carriage model: only for a file with one

    if table["rows"] == "gothic":
        if "height" not in table:
            raise reader.error("carriage", "height", 'rows = "gothic" needs carriage.height (y of the rows)')
        rows = carriage.gothic_rows(half_width=table["half_width"], height=table["height"],
                                    contact_angles=[guide.nominal_angle + d for d in deviations])
    else:
        if "upper" not in table or "lower" not in table:
            raise reader.error("carriage", "upper", 'rows = "four-row" needs carriage.upper and carriage.lower')
        rows = carriage.four_rows(half_width=table["half_width"], upper=table["upper"], lower=table["lower"],
                                  contact_angle=guide.nominal_angle)
    body = carriage.Carriage(guide, rows, table["balls_per_row"], table["pitch"], table.get("oversize", 0.0),
                             table.get("relief_length", 0.0), table.get("relief_depth", 0.0))
    load = carriage.Load(table.get("lateral_force", 0.0), table.get("vertical_force", 0.0),
                         table.get("pitch_moment", 0.0), table.get("yaw_moment", 0.0), table.get("roll_moment", 0.0))
    return body, load


def _nut(reader: _Reader, table: dict | None, screw):
    """The whole nut of a ``[nut]`` table (lowmodel.screw.nut), its axial load and the screw-side deviation."""
    if not table:
        return None, 0.0, (0.0, 4)
    from ballbench.lowmodel.screw import contacts, nut  # the nut model: only for a file with one

    double = table["arrangement"] == "double"
    if double != ("preload" in table):
        raise reader.error("nut", "preload", "nut.preload (the spacer's force) is given for, and only for, "
                                             'arrangement = "double" (a single nut is preloaded by screw.oversize)')
    module = contacts.module(screw)
    if table.get("balls", 0) > nut.capacity(module, table["turns"]):
        raise reader.error("nut", "balls", f"nut.balls {table['balls']} do not fit in {table['turns']} turns (at "
                                           f"most {nut.capacity(module, table['turns'])})")
    body = nut.Nut(module if not double else contacts.module(screw, 0.0), table["turns"], table.get("balls", 0),
                   table["arrangement"], table.get("preload", 0.0), table.get("nut_outer_radius"),
                   table.get("flange", "loaded end"))
    return body, table["axial_load"], (table.get("deviation_amplitude", 0.0), table.get("deviation_cycles", 4))


def loads(text: str, path: str = "<case>"):
    """The case of the TOML ``text`` (``path`` names it in errors): a LinearGuideCase, BallScrewCase or
    ContactCase in SI units.  CaseFileError for any mistake, before any work."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise CaseFileError(f"{path}: not valid TOML: {error}") from None
    return _build(_Reader(text, str(path)), data)


def load(path: str | Path):
    """The case of the TOML file ``path`` (see :func:`loads`)."""
    path = Path(path)
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise CaseFileError(f"{path}: no such file") from None
    except IsADirectoryError:
        raise CaseFileError(f"{path} is a folder; give a case file (ballbench init linear-guide > my.toml)") from None
    except (OSError, UnicodeDecodeError) as error:
        raise CaseFileError(f"{path}: cannot read: {getattr(error, 'strerror', None) or error}") from None
    return loads(text, str(path))


def kind_of(path: str | Path) -> str | None:
    """The ``kind`` of a TOML file, or None when it is not a readable case file."""
    try:
        kind = tomllib.loads(Path(path).read_text()).get("kind")
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None
    return kind if kind in KINDS else None


# --------------------------------------------------------------------------
# writing
# --------------------------------------------------------------------------
def _range_text(key: Key, kind: str = "", table: str = "") -> str:
    model = MODEL_CHECKS.get(kind, {}).get((table, key.name), (None,))[0]
    if model is not None and model.__name__ in model_inputs.RANGES:  # else the field's range (below)
        return model_inputs.RANGES[model.__name__]
    if key.described:
        unit = bearing.FIELDS[key.described][1]
        shown = "um" if key.described == "oversize" else {"m": "mm", "Pa": "GPa", "rad": "deg"}.get(unit, unit)
        return bearing.range_text(key.described, shown, units.factor(shown) if shown else 1.0)
    return {"positive": "> 0", "non-negative": ">= 0"}.get(key.check, "")


def describe(kind: str) -> list[tuple[str, str, str, str]]:
    """``(key, dimension, what, range)`` of every key of ``kind`` (docs/cases.md's table)."""
    rows = []
    for table, keys in SCHEMA[kind].items():
        for key in keys or ():
            rows.append((f"{table}.{key.name}" if table else key.name, key.dimension, key.help,
                         _range_text(key, kind, table)))
    return rows


def template(kind: str) -> str:
    """The commented case file of ``ballbench init KIND``: every key a run needs, with an example value, its unit
    and its range; it loads as it is (a compact guide with 1/8-inch balls, a 32 x 10 ball screw, a ball in a
    groove)."""
    checks.choice("kind", kind, KINDS)
    units_line = "Quantities carry units: \"3.175 mm\", \"2 deg\", \"500 N\", \"210 GPa\", \"1 rev/s\" (SI inside)."
    out = [f"# ballbench case file: {_HEADERS[kind]}",
           f"# {units_line}",
           "# Check and run it: ballbench validate THIS.toml; pictures: ballbench show THIS.toml (docs/cases.md).", ""]
    for table, keys in SCHEMA[kind].items():
        shown = [k for k in (keys or ()) if k.in_template and table not in OPTIONAL_TABLES[kind]]
        if not shown:
            continue
        if table:
            out += ["", f"[{table}]"]
        for key in shown:
            line = f"{key.name} = {key.example}"
            notes = [key.help]
            rng = _range_text(key, kind, table)
            if rng:
                notes.append(rng)
            alternatives = [k for k in keys if k.alternative_of == key.name]
            for alt in alternatives:
                notes.append(f"or {alt.name}")
            out.append(f"{line:<32} # {'; '.join(notes)}")
    for table, intro in _optional_intros(kind).items():  # optional, so commented out: the file loads without them
        out += ["", f"# [{table}] (optional): {intro}"]
        for key in SCHEMA[kind][table]:
            if key.in_template:
                line = f"# {key.name} = {key.example}"
                out.append(f"{line:<32} # {key.help}" + ("" if key.required else " (optional)"))
    if kind == "contact":
        out += ["",
                "# pair = \"screw\" or \"nut\": add a [screw] table (pitch_radius, lead, nominal_angle, conformity,",
                "# friction_coefficient, nut_speed) as in 'ballbench init ball-screw'; conformity belongs to a groove."]
    out += ["", "# [fe] (optional): FE mesh levels; without it 'validate' chooses them from the contact ellipses."]
    if kind == "ball-screw":
        at = next(i for i, line in enumerate(out) if line.startswith("axial_load ="))
        out[at + 1:at + 1] = _preload_loss_comment("\n".join(out) + "\n")
    return "\n".join(out) + "\n"


def _optional_intros(kind: str) -> dict[str, str]:
    """The optional tables the template shows commented out, each with its one-line introduction."""
    speed = "groove_velocity" if kind == "linear-guide" else "nut_speed"
    intros = {"lubricant": f"an oil; it adds the EHL rung (scene <stem>-ehl, docs/ehl.md) at {speed}",
              "carriage": "the whole carriage; it adds the scene <stem>-whole (ball loads, stiffness, friction over "
                          "travel; docs/carriage.md)",
              "nut": "the whole nut; it adds the scene <stem>-whole (ball loads along the nut, friction torque over "
                     "rotation, stiffness; docs/nut.md)"}
    return {table: intro for table, intro in intros.items() if table in SCHEMA[kind]}


def _preload_loss_comment(text: str) -> list[str]:
    """The template's comment on the range of lin2019's ball-screw model: below the preload loss of the values as
    written (lowmodel.screw.preload.preload_loss of the case's balls: frictionless four-point contacts, Hertz's law
    lin2019 eq 53)."""
    from ballbench.lowmodel.screw import b2b as screw_b2b  # the models: reading a case file does not load them
    from ballbench.lowmodel.screw import preload

    loss = preload.preload_loss(screw_b2b.contacts(loads(text, "<template>"))).axial_load
    pad = " " * 32
    return [f"{pad} # lin2019's four-point model applies below the preload loss: {loss:.0f} N for",
            f"{pad} # the values as written (frictionless, Hertz eq 53; it grows like oversize^1.5;",
            f"{pad} # 'ballbench validate' prints yours); above it the balls go over to two-point",
            f"{pad} # contact and its rungs may not apply (docs/ball_screw.md, 'Preload loss')"]
