"""The spec of ``ballbench calibrate SPEC``: fit the low-order constants from FE results and measurements.

The fits and the file live in :mod:`ballbench.lowmodel.calibration`; this
module checks a spec, reads the data it names (CSV files; the FE load sweeps
through :mod:`.fe_laws`), runs the fits and writes the calibration file.  The
command and the ``--calibration FILE`` option of ``validate``: :mod:`.command`.

Spec (TOML; docs/calibration.md)::

    output = "calibration.json"          # relative to the spec's folder (or --out)
    confidence = 0.95

    [contact.ball-groove-0.56]           # one table per contact type
    fe_scene = "<scene>"                 # FE load sweep of the contact case of that scene ...
    # fe_case = "my_guide.toml"          # ... or of a case file's contact (its most loaded one), relative to the spec
    fidelity = "quick"                   # ... at this mesh level
    load_factors = [0.5, 0.75, 1.0, 1.25, 1.5]
    # data = "groove056.csv"             # ... or measured/cached: force [N], approach [m], a [m]
    # ball_radius = 5e-3                 # [m], with data (for Psi)

    [friction]
    data = "friction.csv"                # normal_force [N], friction_force [N] (or friction_torque + lever_arm),
                                         # optional speed [m/s]
    [k_f]
    conformity = 0.56                    # friction map of a ball in a groove of this conformity
    fit_range = 0.5                      # least squares over |c/a| <= fit_range

CSV files: ``#`` lines are comments; the first other line is the header,
each column ``name [unit]`` (units in :data:`CSV_UNITS`); a bad cell raises
ValueError naming the file, line and column.
"""
from __future__ import annotations

import csv
import re
from dataclasses import replace
from pathlib import Path

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import case_file, lin2019
from ballbench.validation.cases.toml_files import read_toml
from ballbench.validation.studies.calibration.fe_laws import (case_contact, check_load_factors, contact_law,
                                                              fe_contact_law, fe_contact_scenes, hertz_references)

__all__ = ["read_csv", "read_friction_csv", "read_load_approach_csv", "write_load_approach_csv", "kf_constants",
           "run_spec", "check_spec", "CSV_UNITS", "BALL_RADIUS_RANGE", "FIDELITIES"]

# quantity -> {unit: SI factor}
CSV_UNITS = {
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3},
    "length": {"m": 1.0, "mm": 1e-3, "um": 1e-6},
    "torque": {"N m": 1.0, "N mm": 1e-3},
    "speed": {"m/s": 1.0, "mm/s": 1e-3},
}
COLUMNS = {"normal_force": "force", "friction_force": "force", "friction_torque": "torque", "lever_arm": "length",
           "speed": "speed", "force": "force", "approach": "length", "a": "length"}
# a ball radius [m] outside this range is most likely given in mm (0.2 mm to 200 mm ball diameter)
BALL_RADIUS_RANGE = (1e-4, 0.1)
FIDELITIES = ("quick", "default", "fine")
_HEADER = re.compile(r"^\s*([a-z_]+)\s*\[([^\]]+)\]\s*$")


# --------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------
def read_csv(path: str | Path, required: tuple[str, ...], optional: tuple[str, ...] = (),
             positive: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
    """Columns of a CSV with ``name [unit]`` headers, converted to SI: ``{name: (n,) array}``.

    Every cell must be a finite number, and > 0 in the ``positive`` columns (the shared
    :mod:`lowmodel.checks`; the message names the file, line and column)."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file")
    with open(path, newline="") as handle:
        rows = [(k + 1, row) for k, row in enumerate(csv.reader(handle))]
    rows = [(line, row) for line, row in rows if row and not row[0].lstrip().startswith("#") and any(c.strip()
                                                                                                    for c in row)]
    if not rows:
        raise ValueError(f"{path}: no header line (columns 'name [unit]')")
    header_line, header = rows[0]
    names, factors, units_of = [], [], {}
    for column, cell in enumerate(header, start=1):
        match = _HEADER.match(cell)
        if not match:
            raise ValueError(f"{path}, line {header_line}, column {column}: header {cell.strip()!r} must be "
                             "'name [unit]', e.g. 'normal_force [N]'")
        name, unit = match.group(1), match.group(2).strip()
        if name not in COLUMNS or name not in required + optional:
            raise ValueError(f"{path}, line {header_line}, column {column}: unknown column {name!r}; this file takes "
                             f"{list(required)} and optionally {list(optional)}")
        units = CSV_UNITS[COLUMNS[name]]
        if unit not in units:
            raise ValueError(f"{path}, line {header_line}, column {column}: unit {unit!r} of {name!r} must be one "
                             f"of {list(units)}")
        if name in names:
            raise ValueError(f"{path}, line {header_line}, column {column}: column {name!r} repeats")
        names.append(name)
        factors.append(units[unit])
        units_of[name] = unit
    missing = [n for n in required if n not in names]
    if missing:
        raise ValueError(f"{path}, line {header_line}: missing column(s) {missing}")
    values = {n: [] for n in names}
    for line, row in rows[1:]:
        if len(row) != len(names):
            raise ValueError(f"{path}, line {line}: {len(row)} cells, the header has {len(names)} columns")
        for column, (name, cell, factor) in enumerate(zip(names, row, factors), start=1):
            try:
                value = float(cell)
            except ValueError:
                raise ValueError(f"{path}, line {line}, column {column} ({name}): {cell.strip()!r} is not a "
                                 "number") from None
            try:
                check = checks.positive if name in positive else checks.finite
                value = check(name, value, units_of[name])
            except ValueError as error:
                raise ValueError(f"{path}, line {line}, column {column}: {error}") from None
            values[name].append(value * factor)
    if not rows[1:]:
        raise ValueError(f"{path}: no data rows under the header (line {header_line})")
    return {name: np.array(v) for name, v in values.items()}


def read_friction_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Friction measurements: ``normal_force``, ``friction_force`` [N] (or ``friction_torque`` [N m] with
    ``lever_arm`` [m]: friction force = torque / lever arm) and optionally ``speed`` [m/s]."""
    data = read_csv(path, ("normal_force",), ("friction_force", "friction_torque", "lever_arm", "speed"),
                    positive=("normal_force", "lever_arm"))
    if ("friction_force" in data) == ("friction_torque" in data):
        raise ValueError(f"{path}: give exactly one of the columns friction_force, friction_torque")
    if "friction_torque" in data:
        if "lever_arm" not in data:
            raise ValueError(f"{path}: friction_torque needs a lever_arm [m] column (force = torque / lever arm)")
        data["friction_force"] = data.pop("friction_torque") / data.pop("lever_arm")
    return data


def read_load_approach_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Load-approach data of one contact: ``force`` [N], ``approach`` [m], optional ``a`` [m] (major semi-axis)."""
    return read_csv(path, ("force", "approach"), ("a",), positive=("force", "approach", "a"))


def write_load_approach_csv(path: str | Path, forces, approaches, semi_axes, comment: str = "") -> Path:
    path = Path(path)
    with open(path, "w", newline="") as handle:
        for line in comment.splitlines():
            handle.write(f"# {line}\n")
        writer = csv.writer(handle)
        writer.writerow(["force [N]", "approach [m]", "a [m]"])
        for row in zip(forces, approaches, semi_axes):
            writer.writerow([repr(float(v)) for v in row])
    return path



# --------------------------------------------------------------------------
# spec
# --------------------------------------------------------------------------
def _contact(name: str, table: dict, base: Path, out_dir: Path, confidence: float, log) -> dict:
    reference_c = reference_psi = None
    if "fe_scene" in table or "fe_case" in table:
        fidelity = table.get("fidelity", "quick")
        factors = table.get("load_factors", (0.5, 0.75, 1.0, 1.25, 1.5))
        if "fe_case" in table:
            law, sweep = contact_law(case_contact(base / table["fe_case"]), fidelity, factors, confidence=confidence,
                                     label=table["fe_case"])
        else:
            law, sweep = fe_contact_law(table["fe_scene"], fidelity, factors, confidence=confidence)
        radius, source = sweep["ball_radius"], sweep["source"]
        cache = write_load_approach_csv(out_dir / f"{name}.load_approach.csv", sweep["force"], sweep["approach"],
                                        sweep["a"], comment=f"ballbench calibrate: {source}\nball_radius {radius!r} m")
        log(f"{name}: {source} in {sweep['wall_time_s']:.1f} s; data cached in {cache}")
        return law.constants()
    path = (base / table["data"]).resolve()
    data = read_load_approach_csv(path)
    radius = table.get("ball_radius")
    if "a" in data and radius is None:
        raise ValueError(f"contact.{name}: the data carry 'a'; give ball_radius [m] for Psi (lin2019 eq 15)")
    if "conformity" in table:  # Hertz reference of a ball in a straight groove
        geometry = hertz.ball_in_groove(radius, table["conformity"])
        reference_c, reference_psi = hertz_references(geometry, radius)
    source = f"{path.name}, {data['force'].size} loads {data['force'].min():g}-{data['force'].max():g} N"
    law = cal.fit_contact_law(data["force"], data["approach"], semi_axes=data.get("a"), ball_radius=radius,
                              confidence=confidence, source=source, hertz_constant=reference_c, psi=reference_psi)
    return law.constants()


def _friction(table: dict, base: Path, confidence: float) -> dict:
    path = (base / table["data"]).resolve()
    data = read_friction_csv(path)
    source = f"{path.name}, {data['normal_force'].size} rows"
    return cal.fit_friction_coefficient(data["normal_force"], data["friction_force"], data.get("speed"),
                                        confidence=confidence, source=source)


def kf_constants(conformity: float, fit_range: float = 0.5, *, confidence: float = 0.95,
                 points: int = 201) -> dict:
    """k_f of lin2019 eq 14 for a ball in a groove of ``conformity`` (R_B 5 mm, steel: b/a does not depend on
    the load or the size): the exact slope at c/a = 0 and least squares over ``|c/a| <= fit_range`` (continuous,
    and discrete on ``points`` values of the tabulated friction map, with its interval)."""
    from ballbench.lowmodel.contact import ellipse_friction as ef
    if not (0.0 < fit_range):
        raise ValueError(f"k_f.fit_range must be > 0, got {fit_range!r}")
    guide = lin2019.GUIDE
    contact = hertz.solve_load(hertz.groove_geometry(replace(guide, conformity=conformity)), lin2019.VERTICAL_FORCE)
    ratio = float(contact.b / contact.a)
    exact = float(ef.k_f_exact(ratio))
    continuous = float(ef.k_f_least_squares(ratio, fit_range))
    kappa = np.linspace(-fit_range, fit_range, points)
    kappa = kappa[kappa != 0.0]
    discrete = cal.fit_line_through_origin(kappa, ef.friction(kappa, ratio).force, confidence=confidence,
                                           source=f"friction map (lowmodel.contact.ellipse_friction), b/a = "
                                                  f"{ratio:.5f}, {kappa.size} points |c/a| <= {fit_range:g}")
    where = f"conformity {conformity:g} (b/a = {ratio:.5f})"
    return {
        "least_squares": cal.Constant(continuous, 0.0, continuous, continuous, "1",
                                      f"continuous least squares over |c/a| <= {fit_range:g} (exact integrals), "
                                      f"{where}", confidence),
        "least_squares_map": discrete,
        "exact": cal.Constant(exact, 0.0, exact, exact, "1", f"exact slope at c/a = 0 (R_D closed form), {where}",
                              confidence),
    }


def _unknown_keys(where: str, table, allowed: set) -> None:
    if not isinstance(table, dict):
        raise ValueError(f"{where} must be a table")
    if set(table) - allowed:
        raise ValueError(f"{where}: unknown key(s) {sorted(set(table) - allowed)}; allowed {sorted(allowed)}")


def check_spec(spec: dict, spec_path: str | Path) -> None:  # noqa: C901 - one branch per key of the calibration spec, each naming its error
    """ValueError naming the key for any mistake in a calibrate spec, before any fit or FE sweep runs (so a typo
    in the last table does not surface after minutes of FE): keys, FE scene, fidelity, load factors, data files,
    ball radius [m] (a radius outside BALL_RADIUS_RANGE is most likely in mm), conformity, confidence, k_f."""
    base = Path(spec_path).parent
    _unknown_keys(str(spec_path), spec, {"output", "confidence", "contact", "friction", "k_f"})
    if not set(spec) & {"contact", "friction", "k_f"}:
        raise ValueError(f"{spec_path}: nothing to calibrate (give [contact.<name>], [friction] or [k_f])")
    checks.bounded("confidence", spec.get("confidence", 0.95), 0.0, 1.0, note="a probability such as 0.95")
    contacts = spec.get("contact", {})
    _unknown_keys("contact", contacts, set(contacts))
    for name, table in contacts.items():
        where = f"contact.{name}"
        _unknown_keys(where, table, {"fe_scene", "fe_case", "fidelity", "load_factors", "data", "ball_radius",
                                     "conformity"})
        if sum(key in table for key in ("fe_scene", "fe_case", "data")) != 1:
            raise ValueError(f"{where}: give exactly one of 'fe_scene' (FE load sweep of a scene's contact), "
                             "'fe_case' (of a case file's contact) or 'data' (CSV file)")
        if "fe_scene" in table or "fe_case" in table:
            if "fe_case" in table:
                if not isinstance(table["fe_case"], str):
                    raise ValueError(f"{where}.fe_case must be the path of a case file, got {table['fe_case']!r}")
                try:
                    case_file.load(base / table["fe_case"])
                except case_file.CaseFileError as error:
                    raise ValueError(f"{where}.fe_case: {error}") from None
            elif table["fe_scene"] not in (scenes := fe_contact_scenes()):
                raise ValueError(f"{where}.fe_scene must be one of {sorted(scenes)}, got {table['fe_scene']!r}")
            if table.get("fidelity", "quick") not in FIDELITIES:
                raise ValueError(f"{where}.fidelity must be quick, default or fine, got {table['fidelity']!r}")
            check_load_factors(table.get("load_factors", (0.5, 0.75, 1.0, 1.25, 1.5)))
            extra = set(table) & {"data", "ball_radius", "conformity"}
            if extra:
                raise ValueError(f"{where}: {sorted(extra)} belong to a 'data' contact; the FE case sets them")
        else:
            if set(table) & {"fidelity", "load_factors"}:
                raise ValueError(f"{where}: fidelity and load_factors belong to an 'fe_scene' or 'fe_case' contact")
            if not (base / table["data"]).is_file():
                raise ValueError(f"{where}.data: no such file {base / table['data']}")
            if "ball_radius" in table:
                checks.bounded(f"{where}.ball_radius", table["ball_radius"], *BALL_RADIUS_RANGE, "m",
                               lower_closed=True, upper_closed=True, note="metres: 5 mm is 5e-3")
            if "conformity" in table:
                if "ball_radius" not in table:
                    raise ValueError(f"{where}: conformity needs ball_radius [m] (the Hertz reference)")
                checks.conformity(f"{where}.conformity", table["conformity"])
    if "friction" in spec:
        table = spec["friction"]
        _unknown_keys("friction", table, {"data"})
        if "data" not in table:
            raise ValueError(f"friction: needs 'data' (a CSV file), got keys {sorted(table)}")
        if not (base / table["data"]).is_file():
            raise ValueError(f"friction.data: no such file {base / table['data']}")
    if "k_f" in spec:
        table = spec["k_f"]
        _unknown_keys("k_f", table, {"conformity", "fit_range"})
        if "conformity" not in table:
            raise ValueError(f"k_f: needs 'conformity' and optionally 'fit_range', got keys {sorted(table)}")
        checks.conformity("k_f.conformity", table["conformity"])
        checks.positive("k_f.fit_range", table.get("fit_range", 0.5), note="the largest |c/a| of the fit")


def run_spec(spec_path: str | Path, output: str | Path | None = None, log=print) -> tuple[Path, cal.Calibration]:
    """Run the fits of a calibrate spec and write the calibration file; returns (path, calibration).

    The whole spec is checked first (:func:`check_spec`)."""
    spec_path = Path(spec_path)
    spec = read_toml(spec_path)
    check_spec(spec, spec_path)
    confidence = spec.get("confidence", 0.95)
    base = spec_path.parent
    target = Path(output) if output else base / spec.get("output", "calibration.json")
    target.parent.mkdir(parents=True, exist_ok=True)
    calibration = cal.Calibration({}, (f"ballbench calibrate {spec_path.name}",))
    for name, table in spec.get("contact", {}).items():
        calibration = calibration.merged(name, _contact(name, table, base, target.parent, confidence, log))
    if "friction" in spec:
        calibration = calibration.merged("friction", _friction(spec["friction"], base, confidence))
    if "k_f" in spec:
        table = spec["k_f"]
        calibration = calibration.merged("k_f", kf_constants(table["conformity"], table.get("fit_range", 0.5),
                                                             confidence=confidence))
    cal.save(calibration, target)
    for group, constants in calibration.constants.items():
        for name, c in constants.items():
            ref = "" if c.reference is None else f"  (uncalibrated {c.reference:.6g})"
            log(f"{group:>20} {name:<18} {c.value:.6g} {c.unit}  {100 * c.confidence:.0f} % interval "
                f"[{c.ci_low:.6g}, {c.ci_high:.6g}]{ref}")
    log(f"calibration written to {target}")
    return target, calibration
