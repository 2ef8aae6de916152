"""A check as the report shows it: engineering units, formatted numbers, one-line summaries.

JSON and CSV keep SI values; everything a reader sees (report.md, report.html,
JUnit, the terminal) goes through :func:`row` and :func:`check_line`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

from ballbench.validation.scene import Output, SceneResult

# SI unit -> ((threshold, factor, display unit), ...) from the largest: the first whose threshold <= |x|
_ENGINEERING = {
    "m": ((1e-3, 1e3, "mm"), (0.0, 1e6, "um")),
    "Pa": ((0.0, 1e-6, "MPa"),),
    "N": ((1.0, 1.0, "N"), (0.0, 1e3, "mN")),
    "W": ((1.0, 1.0, "W"), (0.0, 1e3, "mW")),
    "m/s": ((1.0, 1.0, "m/s"), (0.0, 1e3, "mm/s")),
    "N/m": ((0.0, 1e-6, "N/um"),),
    "s": ((1.0, 1.0, "s"), (1e-3, 1e3, "ms"), (0.0, 1e6, "us")),
    "rad": ((0.0, 180.0 / math.pi, "deg"),),  # angles as an engineer reads them (contact angles, truncation)
}
DIMENSIONLESS = ("1", "-", "")  # shown without a unit after the number and as "-" in a unit column
UNDECLARED = "undeclared"  # the family of a check that declares none (results.json of an older version)
STATUS_WORDS = {"pass": "PASS", "known gap": "PASS (known gap)",
                "findings": "PASS, FINDINGS (models outside their accuracy here)",
                "not applicable": "DOES NOT APPLY (outside the model's limits on this case)",
                "inconclusive": "INCONCLUSIVE (no conclusive reference at this fidelity)", "fail": "FAIL",
                "error": "ERROR"}


# what a finding means for the reader (report.md/html and the CLI; docs/your_own_bearing.md, "Reading the verdict")
FINDINGS_MEANING = ("a model outside its declared accuracy on this geometry: a result of the validation, not a "
                    "failure of the software; where it matters, use the higher rung it was judged against")


def engineering(unit: str, *numbers: float) -> tuple[float, str]:
    """(factor, display unit) for showing ``numbers`` (SI ``unit``) in one engineering unit."""
    if unit not in _ENGINEERING:
        return 1.0, unit
    finite = [abs(x) for x in numbers if math.isfinite(x) and x != 0.0]
    magnitude = max(finite) if finite else 0.0
    for threshold, factor, shown in _ENGINEERING[unit]:
        if magnitude >= threshold:
            return factor, shown
    return _ENGINEERING[unit][-1][1:]


def fmt_number(x: float, digits: int = 5) -> str:
    """``digits`` significant figures; plain notation from 1e-3 to 1e6, else ``1.234e-09``."""
    if isinstance(x, str):
        return x
    if not math.isfinite(x):
        return str(x)
    if x == 0.0:
        return "0"
    rounded = float(f"{x:.{digits}g}")  # so that 0.999999 counts as 1.0000, not 0.99999..
    if 1e-3 <= abs(rounded) < 1e7:
        before = math.floor(math.log10(abs(rounded))) + 1
        return f"{x:.{max(0, digits - before)}f}"
    return f"{x:.{digits - 1}e}"


def count(n: int, noun: str) -> str:
    """``"1 scene"``, ``"35 scenes"``: a count with its noun (regular plural)."""
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def fmt_time(t: float) -> str:
    """A duration [s] in us, ms or s with three significant figures."""
    if not math.isfinite(t):
        return str(t)
    if t < 1e-3:
        return f"{t * 1e6:.3g} us"
    if t < 1.0:
        return f"{t * 1e3:.3g} ms"
    return f"{t:.3g} s"


def fmt_percent(rel_error: float) -> str:
    if not math.isfinite(rel_error):
        return str(rel_error)
    if rel_error == 0.0:
        return "0 %"
    value = rel_error * 100
    return f"{value:.3g} %" if value >= 1e-3 else f"{value:.2e} %"


def fmt_ratio(o: Output) -> str:
    """Error as a multiple of the tolerance (1 = at tolerance)."""
    if o.kind == "budget":
        return ""
    met = "0 (bound met)" if o.relation != "eq" else "0 (exact)"  # a bound that holds has error 0 too
    if o.tolerance == 0:
        return met if o.rel_error == 0 else "bound missed" if o.relation != "eq" else "not exact"
    r = o.error_over_tolerance
    if r == 0:
        return met
    return f"{r:.2g}" if r >= 1e-3 else f"{r:.1e}"


def ratio_text(r: float) -> str:
    """A worst error / tolerance of a summary (0: exact; inf: a tolerance-0 bound missed)."""
    if r == 0:
        return "0 (exact)"
    if not math.isfinite(r):
        return "bound missed"
    return f"{r:.2g}"


def family_of(o: Output) -> str:
    """The model family the check declared, or :data:`UNDECLARED`."""
    return o.family or UNDECLARED


def status_word(status: str) -> str:
    """A scene status as the report and the terminal write it (``PASS (known gap)``, ...)."""
    return STATUS_WORDS[status]


@dataclass(frozen=True)
class Row:
    """An output as the report shows it (engineering units, formatted)."""

    model: str
    quantity: str
    value: str
    reference: str
    unit: str
    error: str
    tolerance: str
    ratio: str
    status: str
    source: str
    time: str
    note: str

    @property
    def value_with_unit(self) -> str:
        return f"{self.value} {self.unit}" if self.unit else self.value

    @property
    def reference_with_unit(self) -> str:
        return f"{self.reference} {self.unit}" if self.unit else self.reference


def row(o: Output) -> Row:
    """``o`` in engineering units: value and reference (with ``>=``/``<=`` for a bound), error and tolerance."""
    factor, unit = engineering(o.unit, o.value, o.reference)
    unit = "" if unit in DIMENSIONLESS else unit
    value = fmt_number(o.value * factor)
    reference = {"eq": "", "ge": ">= ", "le": "<= "}[o.relation] + fmt_number(o.reference * factor)
    if o.kind == "budget":
        tolerance = "budget"
        error = "" if o.passed else fmt_percent(o.rel_error) + " over"
    elif o.tolerance == 0:
        tolerance = "bound" if o.relation != "eq" else "exact"
        error = fmt_percent(o.rel_error)
    else:
        tolerance = fmt_percent(o.tolerance)
        error = fmt_percent(o.rel_error)
    note = o.note
    if o.why:
        note = (note + "; " if note else "") + "why this tolerance/scale: " + o.why
    return Row(o.model, o.quantity, value, reference, unit, error, tolerance, fmt_ratio(o), o.status, o.source,
               fmt_time(o.time_s), note)


def worst_ratio(outputs: Sequence[Output]) -> float:
    """The largest error / tolerance of the accuracy checks (0 when there are none)."""
    ratios = [o.error_over_tolerance for o in outputs if o.kind == "accuracy"]
    return max(ratios) if ratios else 0.0


def worst_ratio_text(outputs: Sequence[Output]) -> str:
    """The summary's worst error / tolerance; a 0 says whether it is exact agreement or bounds that hold."""
    worst = worst_ratio(outputs)
    if worst != 0:
        return ratio_text(worst)
    relations = {o.relation == "eq" for o in outputs if o.kind == "accuracy"}
    if not relations:
        return "-"
    return {frozenset({True}): "0 (exact)", frozenset({False}): "0 (bounds met)"}.get(
        frozenset(relations), "0 (exact; bounds met)")


def scene_budget_text(r: SceneResult) -> str:
    """The scene's wall-time budget and whether the run stayed under it (``-`` without a budget)."""
    if not math.isfinite(r.budget_s):
        return "-"
    return f"{fmt_time(r.budget_s)} ({'over' if r.wall_time_s > r.budget_s else 'under'})"


def check_line(o: Output, *, level: bool = False) -> str:
    """One check as a line: quantity, model (``level``: and its level), value and reference with unit, source, error
    and tolerance."""
    r = row(o)
    tolerance = f"tolerance {r.tolerance}" if o.kind == "accuracy" else "budget"
    model = f"{o.model}, {o.level}" if level and o.level else o.model
    return (f"  {o.quantity} [{model}]: {r.value_with_unit} vs reference {r.reference_with_unit} ({o.source}): "
            f"error {r.error or '0 %'}, {tolerance}")


# what a scene that does not apply means for the reader (report, CLI; docs/your_own_bearing.md, "Reading the verdict")
NOT_APPLICABLE_MEANING = ("the scene's model has no state on this case, or the case lies outside what the rung can "
                          "model (a contact ellipse reaching its groove's shoulder): a limit named with the case's "
                          "number against it, not a failure of the software, and no validation of that rung here")


# what an inconclusive scene means for the reader (report, CLI; docs/your_own_bearing.md, "Reading the verdict")
INCONCLUSIVE_MEANING = ("the reference (an FE mesh study) is too uncertain at this fidelity to judge the models "
                        "against it: no conclusive reference, so those models are not judged (no finding, no "
                        "failure); the reason names the fidelity or [fe] levels that settle it")


def passing_lines(result: SceneResult, status: str) -> list[str]:
    """What a passing scene with findings, known gaps, no conclusive reference or a model that does not apply adds
    under its status line on the terminal."""
    if status == "not applicable":
        return [f"  does not apply: {result.not_applicable}"]
    if status == "inconclusive":
        return [f"  inconclusive: {result.inconclusive}"]
    if status == "findings":
        return [f"  findings: {FINDINGS_MEANING}"] + [f"{check_line(o, level=True)}: outside accuracy"
                                                      for o in result.outputs_with("outside accuracy")]
    if status == "known gap":
        return [f"  known gap (declared, see the report): {o.quantity}: {row(o).value_with_unit} vs published "
                f"{row(o).reference_with_unit}" for o in result.outputs_with("known gap")]
    return []


def failure_lines(result: SceneResult, *, strict: bool = False, strict_time: bool = False, limit: int = 5) -> list[str]:
    """One line per failed check: quantity, model, value, reference, error and tolerance."""
    strict_fails = ("known gap", "outside accuracy") if strict else ()
    bad = [o for o in result.outputs if o.status in ("fail", "unexpected pass", *strict_fails)
           or (strict_time and o.status == "over budget")]
    lines = []
    if strict and result.not_applicable and not result.error:
        lines.append(f"  does not apply (--strict): {result.not_applicable}")
    if strict and result.inconclusive and not result.error and not result.not_applicable:
        lines.append(f"  inconclusive (--strict): {result.inconclusive}")
    for o in bad[:limit]:
        what = {"unexpected pass": "known gap now PASSES (remove its declaration)",
                "known gap": "known gap (--strict)", "outside accuracy": "outside accuracy (--strict)",
                "over budget": "over budget (--strict-time)"}.get(o.status, "")
        lines.append(check_line(o) + (f"; {what}" if what else ""))
    if strict_time and result.wall_time_s > result.budget_s:
        lines.append(f"  scene wall time {fmt_time(result.wall_time_s)} over its budget {fmt_time(result.budget_s)} "
                     "(--strict-time)")
    if strict_time and result.over_memory:
        lines.append(memory_line(result) + " (--strict-time)")
    if len(bad) > limit:
        lines.append(f"  ... and {len(bad) - limit} more failed checks (report.md)")
    return lines


def memory_line(result: SceneResult) -> str:
    """The line that says a scene's own peak memory is above its declaration (docs/validation.md, "Memory")."""
    return (f"  scene peak memory {result.scene_peak_memory_gb:.1f} GB over its declared "
            f"{result.declared_memory_gb:.1f} GB")


def memory_lines(result: SceneResult, *, strict_time: bool = False) -> list[str]:
    """The line of a scene above its declared memory while that is only reported (with ``strict_time``
    :func:`failure_lines` says it)."""
    if not result.over_memory or strict_time:
        return []
    return [memory_line(result) + " (reported; --strict-time fails it)"]
