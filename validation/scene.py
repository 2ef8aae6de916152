"""Scenes: named validation cases and the record they produce.

A scene is a plain function decorated with :func:`scene`.  It receives a
:class:`Run` and uses it to time model calls and record checked outputs::

    from ballbench.validation.scene import scene

    @scene("hertz-sphere-flat", "Ball on a flat: exact Hertz against the closed form")
    def hertz_sphere_flat(run):
        contact, time_s = run.time(hertz.solve_load, geometry, 100.0)
        run.check(model="lowmodel.contact.hertz", quantity="a", unit="m",
                  value=contact.a, reference=a_closed_form,
                  source="Johnson (1985) eq 4.22", tolerance=1e-10,
                  time_s=time_s)

A scene computes only what its outputs need: no body, mesh region or model
that none of its checks uses.  ``run.fidelity`` is ``"quick"`` (coarsest, for
CI and ``--quick``), ``"default"`` or ``"fine"``.

Error convention (kept stable, see docs/validation.md):

* ``relation="eq"``: ``rel_error = |value - reference| / max(|reference|, scale)``
  where ``scale`` defaults to 0; a zero reference therefore needs an explicit
  ``scale`` (the magnitude against which "zero" is judged).
* ``relation="ge"`` (the paper gives a lower bound, "more than X"):
  ``rel_error = max(0, reference - value) / max(|reference|, scale)``.
* ``relation="le"``: the mirror of ``"ge"``.

A check passes when ``rel_error <= tolerance`` and the value is finite.

Guards (docs/validation.md, "Error convention"): ``tolerance`` must be finite and below 1, and ``scale``
must not exceed ``|reference|`` (a zero reference always needs one), unless
the check says why in ``why=`` (the sentence goes into the report).

Known gaps: ``run.check(..., known_gap=KnownGap(reason, evidence))`` declares
a published number this project does not reproduce, with the reason and the
artifact or check that backs it.  It runs and is reported like any check, is
listed in its own section, and does not fail the run; if it starts to pass it
is reported loudly as an *unexpected pass* (and fails the run, so that the
declaration is removed).  ``--strict`` makes known gaps fail.

Findings: ``run.check(..., finding=True)`` marks a check whose miss is a result of the validation, not a failure
of the software: a model judged against its declared accuracy on a user's own geometry (the case scenes,
docs/your_own_bearing.md, "Reading the verdict").  A missed finding check is reported as *outside accuracy*, its
scene as *findings*; it does not fail the run (``--strict`` makes it fail).  Self-checks of a solver (equilibrium,
power balance) are never findings.

Budgets: ``run.budget(...)`` records a wall time or a throughput against its
target.  Budgets are reported (budget, measured, over or under) and never
decide pass or fail unless ``--strict-time`` is given; so is every scene's own
wall time against ``Scene.budget_s``.

Does not apply: a scene built from a case file (``tags=("case",)``) whose model has no state on that case raises
:class:`NotApplicable` with the reason, from an explicit, tested condition (a contact the FE module needs is
unloaded; the axial load is past the preload loss and lin2019's model stops at its declared limit).  Its status
is ``not applicable``: it passes the run (``--strict`` makes it fail) and the report gives the reason.  A
registered (paper) scene that raises it ends in ``error``: the papers' cases lie inside their models.

Inconclusive: a case file's scene whose reference (an FE mesh study) is too uncertain at the run's fidelity to judge
the models against it calls ``run.inconclusive(reason)``, the reason naming the uncertainty, its bound and the
fidelity or ``[fe]`` levels that settle it; the models judged against that reference are then not checked (no
finding: there is no conclusive reference), the solver's own checks still are.  Its status is ``inconclusive``: it
passes the run (``--strict`` makes it fail); a failed self-check still makes it ``fail``.  A registered (paper)
scene that calls it ends in ``error``: the papers' references are known at the levels those scenes run
(docs/verification.md).
"""
from __future__ import annotations

import csv
import math
import statistics
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Callable, Iterable

from ballbench.validation import scenes as _scenes

FIDELITIES = ("quick", "default", "fine")
RELATIONS = ("eq", "ge", "le")
KINDS = ("analytical", "low-order", "FE")
# model families a check declares (``run.check(family=...)``); the report, the error-budget table and the fronts
# of error_vs_time.png group by them (docs/validation.md, "Model identity")
FAMILIES = ("analytical", "low-order numerical", "BEM", "EHL", "FE", "FE-informed")
# scene statuses that pass a run without --strict (SceneResult.status)
PASSING = ("pass", "known gap", "findings", "not applicable", "inconclusive")
# wall-time budget of a scene at the default fidelity when the scene does not state one [s]
DEFAULT_BUDGET_S = {"analytical": 10.0, "low-order": 60.0, "FE": 120.0}
# the resident memory a scene declares when it declares none [GB] (docs/validation.md, "Memory"): each covers the
# largest own peak of its kind's scenes measured at the default fidelity (runner.SceneMemory)
DEFAULT_MEMORY_GB = {"analytical": 3.5, "low-order": 3.5, "FE": 12.0}


class NotApplicable(Exception):
    """Raised by a case file's scene whose model has no state on the case (module docstring, "Does not apply"):
    ``reason`` names the limit and the number, e.g. the axial load against the preload loss."""

    def __init__(self, reason: str):
        if not isinstance(reason, str) or not reason.strip():
            raise ValueError("NotApplicable needs a reason: the model's limit and the case's number against it")
        super().__init__(reason)
        self.reason = reason


@dataclass(frozen=True)
class KnownGap:
    """A published number the project does not reproduce: why, and what backs the explanation.

    ``reason``: one or two sentences; ``evidence``: the artifact, document
    section or check that backs the reason (e.g. ``"docs/b2b_bearing.md,
    'Validity range'; lin2019-stability spin-capacity checks"``).
    """

    reason: str
    evidence: str

    def __post_init__(self):
        for name in ("reason", "evidence"):
            if not isinstance(getattr(self, name), str) or not getattr(self, name).strip():
                raise ValueError(f"KnownGap.{name} must be a non-empty sentence")


@dataclass(frozen=True)
class Output:
    """One checked number of a scene (a row of the report).

    ``kind`` is ``"accuracy"`` (a model against a reference) or ``"budget"``
    (a wall time or throughput against its target; never decides pass/fail
    unless ``--strict-time``).  ``passed`` is the raw comparison; ``status``
    is what it means for the run.
    """

    model: str
    quantity: str
    unit: str
    value: float
    reference: float
    source: str
    rel_error: float
    tolerance: float
    passed: bool
    time_s: float
    relation: str = "eq"
    note: str = ""
    kind: str = "accuracy"
    scale: float = 0.0
    why: str = ""
    known_gap: KnownGap | None = None
    family: str = ""
    level: str = ""
    finding: bool = False  # a miss is a finding (a model outside its accuracy here), not a failure

    @property
    def status(self) -> str:
        """``pass``, ``fail``, ``outside accuracy``, ``known gap``, ``unexpected pass``, ``within budget`` or
        ``over budget``."""
        if self.kind == "budget":
            return "within budget" if self.passed else "over budget"
        if self.known_gap is not None:
            return "unexpected pass" if self.passed else "known gap"
        if self.finding and not self.passed:
            return "outside accuracy"
        return "pass" if self.passed else "fail"

    @property
    def error_over_tolerance(self) -> float:
        """``rel_error / tolerance`` (1 = at tolerance); for a zero tolerance 0 if met, else inf."""
        if self.tolerance > 0:
            return self.rel_error / self.tolerance
        return 0.0 if self.rel_error == 0 else math.inf

    def as_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["status"] = self.status
        del data["finding"]  # the status carries it ("outside accuracy"); the keys of results.json stay as documented
        gap = data.pop("known_gap")
        data["known_gap_reason"] = gap["reason"] if gap else ""
        data["known_gap_evidence"] = gap["evidence"] if gap else ""
        return data


@dataclass(frozen=True)
class SceneResult:
    name: str
    description: str
    fidelity: str
    outputs: tuple[Output, ...]
    artifacts: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    wall_time_s: float = 0.0
    error: str = ""
    budget_s: float = math.inf
    kind: str = "low-order"
    interrupted: bool = False
    tables: tuple = ()  # ((title, header, rows), ...): results for the reader beside the checks (Run.table)
    peak_memory_gb: float = 0.0  # the process's peak resident memory while the scene ran [GB]; 0 = not measured
    not_applicable: str = ""  # why the scene's model has no state on the case (NotApplicable); "" = it applies
    inconclusive: str = ""  # why the scene's reference is too uncertain to judge at this fidelity (Run.inconclusive)
    # the scene's own peak resident memory: the peak while it ran above the resident memory at its start [GB]
    # (runner.SceneMemory; docs/validation.md, "Memory"); 0 = not measured
    scene_peak_memory_gb: float = 0.0
    declared_memory_gb: float = 0.0  # the memory the scene declares at its fidelity (Scene.memory_for) [GB]

    @property
    def over_memory(self) -> bool:
        """The scene's own measured peak memory is above the memory it declares."""
        return self.declared_memory_gb > 0.0 and self.scene_peak_memory_gb > self.declared_memory_gb

    def outputs_with(self, status: str) -> list[Output]:
        return [o for o in self.outputs if o.status == status]

    @property
    def over_budget(self) -> bool:
        """The scene's wall time or one of its budget rows is over its budget (memory: :attr:`over_memory`)."""
        return self.wall_time_s > self.budget_s or bool(self.outputs_with("over budget"))

    def status(self, *, strict: bool = False, strict_time: bool = False) -> str:
        """``error``, ``fail``, ``not applicable`` (passes: the model has no state on the case, for
        :attr:`not_applicable`), ``inconclusive`` (passes: no conclusive reference at this fidelity, for
        :attr:`inconclusive`), ``findings`` (passes, with models outside their accuracy), ``known gap`` (passes,
        with declared gaps) or ``pass``.

        ``strict``: not applicable, inconclusive, findings and known gaps fail; ``strict_time``: a budget overrun
        fails, of wall time or of memory (:attr:`over_memory`).  An unexpected pass of a known gap always fails
        (remove the declaration); so does a failed self-check of an inconclusive scene.
        """
        if self.error:
            return "error"
        if self.not_applicable:
            return "fail" if strict else "not applicable"
        if not self.outputs and not self.inconclusive:
            return "error"
        if self.outputs_with("fail") or self.outputs_with("unexpected pass"):
            return "fail"
        if strict_time and (self.over_budget or self.over_memory):
            return "fail"
        if self.inconclusive:
            return "fail" if strict else "inconclusive"
        if self.outputs_with("outside accuracy"):
            return "fail" if strict else "findings"
        if self.outputs_with("known gap"):
            return "fail" if strict else "known gap"
        return "pass"

    @property
    def passed(self) -> bool:
        """Passes the default run (findings and known gaps allowed, budgets reported only)."""
        return self.status() in PASSING


@dataclass(frozen=True)
class Scene:
    """A registered scene.

    ``kind``: ``"analytical"`` (closed forms, microseconds), ``"low-order"``
    (numerical low-order models) or ``"FE"``; ``cost_s``: rough wall time at
    the default fidelity on a 2-core machine [s] (shown by ``ballbench
    scenes``); ``budget_s``: wall-time budget per fidelity [s] (reported,
    decides only with ``--strict-time``); ``level``: the default mesh level
    in words (FE scenes); ``show``: the scene's picture hook, ``show(scene_dir, fidelity, solve=False) -> list[Path]``,
    which draws from the fields the scene saved in ``scene_dir`` without re-solving (``ballbench show``): none
    saved, FileNotFoundError, or with ``solve`` the scene's checked level at ``fidelity`` solved first;
    ``case``: the case the scene runs (:mod:`ballbench.validation.cases`), read by ``calibrate`` (FE load
    sweeps of a scene's contact) and the report; None for a scene of many cases; ``memory_gb``: the peak
    resident memory the scene needs at the default fidelity [GB] (:meth:`memory_for`; the distributed runner
    reserves it on a worker), None for its kind's :data:`DEFAULT_MEMORY_GB`.
    """

    name: str
    description: str
    function: Callable[["Run"], None]
    tags: tuple[str, ...] = ()
    default: bool = True
    kind: str = "low-order"
    cost_s: float = 1.0
    budget_s: dict | None = None
    level: str = ""
    show: Callable[[Path, str], list[Path]] | None = None
    case: Any = None
    memory_gb: float | None = None

    def memory_for(self, fidelity: str) -> float:
        """The resident memory the scene declares at ``fidelity`` [GB]: its ``memory_gb`` (else its kind's
        :data:`DEFAULT_MEMORY_GB`), twice that at ``fine``; the distributed runner reserves it on a worker."""
        declared = DEFAULT_MEMORY_GB[self.kind] if self.memory_gb is None else self.memory_gb
        return declared * (2.0 if fidelity == "fine" else 1.0)

    def budget_for(self, fidelity: str) -> float:
        if self.budget_s is None:
            return DEFAULT_BUDGET_S[self.kind] * (5.0 if fidelity == "fine" else 1.0)
        return float(self.budget_s[fidelity])


# every registered scene by name; the scene decorator fills it, registry() loads the scene modules first
REGISTRY: dict[str, Scene] = {}


def scene(name: str, description: str, *, tags: Iterable[str] = (), default: bool = True, kind: str = "low-order",
          cost_s: float = 1.0, budget_s: dict | float | None = None, level: str = "",
          show: Callable[[Path, str], list[Path]] | None = None, case: Any = None, memory_gb: float | None = None):
    """Register the decorated function as the scene ``name`` (see :class:`Scene` for the keywords).

    ``default=False`` keeps the scene out of a bare ``ballbench validate``
    (it still runs when named).  A single ``budget_s`` applies to every fidelity.
    """
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    if not (isinstance(cost_s, (int, float)) and math.isfinite(cost_s) and cost_s > 0):
        raise ValueError(f"cost_s must be a finite time > 0 s, got {cost_s!r}")
    if isinstance(budget_s, (int, float)):
        budget_s = {f: float(budget_s) for f in FIDELITIES}
    if budget_s is not None and set(budget_s) != set(FIDELITIES):
        raise ValueError(f"budget_s must give a time for each of {FIDELITIES}, got {budget_s!r}")
    if memory_gb is not None and not (isinstance(memory_gb, (int, float)) and 0 < memory_gb < 1e4):
        raise ValueError(f"memory_gb must be a resident memory in (0, 1e4) GB, got {memory_gb!r}")

    def register(function: Callable[["Run"], None]) -> Callable[["Run"], None]:
        if name in REGISTRY and REGISTRY[name].function is not function:
            raise ValueError(f"scene {name!r} is registered twice")
        REGISTRY[name] = Scene(name, description, function, tuple(tags), default, kind, float(cost_s), budget_s,
                                level, show, case, None if memory_gb is None else float(memory_gb))
        return function

    return register


def relative_error(value: float, reference: float, *, relation: str = "eq", scale: float = 0.0) -> float:
    """Relative error of ``value`` against ``reference`` (see module docstring)."""
    if relation not in RELATIONS:
        raise ValueError(f"relation must be one of {RELATIONS}, got {relation!r}")
    if not (math.isfinite(value) and math.isfinite(reference)):
        return math.inf
    denominator = max(abs(reference), abs(scale))
    if denominator == 0.0:
        raise ValueError("reference is zero: pass scale > 0, the magnitude that 'zero' is judged against")
    if relation == "eq":
        diff = abs(value - reference)
    elif relation == "ge":
        diff = max(0.0, reference - value)
    else:
        diff = max(0.0, value - reference)
    return diff / denominator


class Run:
    """What a scene function gets: timing, checks, artifacts and progress."""

    def __init__(self, scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = True,
                 progress_lines: bool = False, should_stop: Callable[[], bool] | None = None):
        if fidelity not in FIDELITIES:
            raise ValueError(f"fidelity must be one of {FIDELITIES}, got {fidelity!r}")
        self.scene = scene
        self.fidelity = fidelity
        self.out_dir = Path(out_dir)
        self.show_progress = show_progress
        self.progress_lines = progress_lines and not show_progress
        self.should_stop = should_stop or (lambda: False)
        self._outputs: list[Output] = []
        self._artifacts: list[str] = []
        self._notes: list[str] = []
        self._tables: list[tuple] = []
        self._inconclusive: list[str] = []

    # -- timing -----------------------------------------------------------
    @staticmethod
    def time(function: Callable[..., Any], *args: Any, budget_s: float = 0.2, max_repeat: int = 50, **kwargs: Any):
        """Call ``function(*args, **kwargs)``; return ``(result, wall_time_s)``.

        A call faster than ``budget_s / 5`` is repeated (up to ``max_repeat``
        times within about ``budget_s``) and the median wall time is reported.
        """
        start = time.perf_counter()
        result = function(*args, **kwargs)
        first = time.perf_counter() - start
        if first * 5 > budget_s:
            return result, first
        times = [first]
        repeats = min(max_repeat, max(2, int(budget_s / max(first, 1e-9))))
        for _ in range(repeats - 1):
            start = time.perf_counter()
            function(*args, **kwargs)
            times.append(time.perf_counter() - start)
        return result, statistics.median(times)

    # -- checks -----------------------------------------------------------
    def check(
        self,
        *,
        model: str,
        quantity: str,
        unit: str,
        value: float,
        reference: float,
        source: str,
        tolerance: float,
        time_s: float,
        relation: str = "eq",
        scale: float = 0.0,
        note: str = "",
        why: str = "",
        known_gap: KnownGap | None = None,
        family: str,
        level: str = "",
        finding: bool = False,
    ) -> Output:
        """Record ``value`` of ``quantity`` (SI ``unit``) against ``reference``.

        ``tolerance`` is on the relative error defined in the module docstring.
        A tolerance that is not finite or not below 1, or a ``scale`` larger
        than ``|reference|`` with a tolerance above 0, is rejected (ValueError)
        unless ``why`` says why.
        ``known_gap`` declares the published number as not reproduced.  ``finding=True``: a miss is a finding of
        the validation (status ``outside accuracy``), not a failure (module docstring, "Findings").
        ``family`` (one of :data:`FAMILIES`, required) and ``level`` (the fidelity level within the family in words,
        e.g. ``"h 30 um"``, ``"64 x 64 cells"``; empty for a model without levels) name the model as data.
        """
        if family not in FAMILIES:
            raise ValueError(f"family must be one of {FAMILIES}, got {family!r} ({quantity})")
        value = float(value)
        reference = float(reference)
        scale = float(scale)
        if not tolerance >= 0.0:
            raise ValueError(f"tolerance must be >= 0, got {tolerance!r} ({quantity})")
        if not why.strip():
            if not (math.isfinite(tolerance) and tolerance < 1.0):
                raise ValueError(f"tolerance {tolerance!r} of {quantity!r} is not finite or not below 1: "
                                 "a check that passes (nearly) anything; pass why= to say why it is meant")
            # with tolerance 0 the check demands exact agreement, so the scale cannot make it lax
            if abs(scale) > abs(reference) and tolerance > 0.0:
                raise ValueError(f"scale {scale!r} of {quantity!r} is larger than its reference {reference!r}: "
                                 "pass why= to name the magnitude the error is judged against")
        if known_gap is not None and not isinstance(known_gap, KnownGap):
            raise TypeError("known_gap must be a KnownGap(reason, evidence)")
        if finding and known_gap is not None:
            raise ValueError(f"{quantity!r}: a check is a finding or a known gap, not both")
        rel_error = relative_error(value, reference, relation=relation, scale=scale)
        passed = bool(math.isfinite(value) and rel_error <= tolerance)
        output = Output(model, quantity, unit, value, reference, source, float(rel_error),
                        float(tolerance), passed, float(time_s), relation, note, "accuracy", scale, why.strip(),
                        known_gap, family, level, bool(finding))
        self._outputs.append(output)
        return output

    def budget(self, *, quantity: str, unit: str, value: float, budget: float, source: str, relation: str = "le",
               model: str = "", time_s: float | None = None, note: str = "", family: str = "",
               level: str = "") -> Output:
        """Record a wall time (``relation="le"``: at most ``budget``) or a throughput (``"ge"``: at least).

        Reported as within or over budget; it decides pass/fail only with ``--strict-time``.  ``family`` and
        ``level``: the model's, as in :meth:`check` (optional: a budget row is not a point of a front).
        """
        if family and family not in FAMILIES:
            raise ValueError(f"family must be one of {FAMILIES}, got {family!r} ({quantity})")
        if relation not in ("le", "ge"):
            raise ValueError(f"a budget's relation is 'le' (time) or 'ge' (throughput), got {relation!r}")
        value, budget = float(value), float(budget)
        if not (math.isfinite(budget) and budget > 0):
            raise ValueError(f"budget must be a finite number > 0, got {budget!r} ({quantity})")
        rel_error = relative_error(value, budget, relation=relation)
        output = Output(model or self.scene.name, quantity, unit, value, budget, source, float(rel_error), 0.0,
                        bool(math.isfinite(value) and rel_error == 0.0),
                        float(value if time_s is None else time_s), relation, note, "budget", family=family,
                        level=level)
        self._outputs.append(output)
        return output

    # -- artifacts, notes, progress --------------------------------------
    def path(self, filename: str) -> Path:
        """Path for an artifact of this scene (``<out>/<scene>/<filename>``)."""
        directory = self.out_dir / self.scene.name
        directory.mkdir(parents=True, exist_ok=True)
        return directory / filename

    def save_figure(self, figure, filename: str) -> Path:
        """Save a :class:`matplotlib.figure.Figure` (validation.figures) as PNG next to the report."""
        target = self.path(filename)
        figure.savefig(target, dpi=120, bbox_inches="tight")
        self.add_artifact(target)
        return target

    def write_csv(self, filename: str, rows: list[dict]) -> Path | None:
        """A table (rows of one set of keys, the first row's order) as ``filename`` in the scene's folder, listed
        as an artifact; nothing for no rows."""
        if not rows:
            return None
        path = self.path(filename)
        with open(path, "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
        self.add_artifact(path)
        return path

    def add_artifact(self, path: Path | str) -> None:
        path = Path(path)
        try:
            self._artifacts.append(str(path.relative_to(self.out_dir)))
        except ValueError:
            self._artifacts.append(str(path))

    def note(self, text: str) -> None:
        """A sentence for the report under this scene's table (conventions, gaps)."""
        self._notes.append(text)

    def inconclusive(self, reason: str) -> None:
        """End the scene ``inconclusive`` (module docstring, "Inconclusive"): its reference is too uncertain at this
        fidelity to judge the models against it.  ``reason`` names the uncertainty, its bound and the fidelity or
        ``[fe]`` levels that settle it; the scene goes on (tables, self-checks) but checks no model against that
        reference.  Called more than once (one reference per contact), the reasons are joined."""
        if not isinstance(reason, str) or not reason.strip():
            raise ValueError("Run.inconclusive needs a reason: the uncertainty, its bound and what settles it")
        if "case" not in self.scene.tags:  # the papers' scenes run at levels their references are known at
            raise ValueError(f"only a case file's scene may end inconclusive; {self.scene.name} is a registered "
                             f"(paper) scene: {reason.strip()}")
        self._inconclusive.append(reason.strip())

    @property
    def inconclusive_reasons(self) -> tuple[str, ...]:
        """The reasons given to :meth:`inconclusive` so far."""
        return tuple(self._inconclusive)

    def table(self, title: str, header, rows) -> None:
        """A table of results for the reader (loads, friction forces, ...) shown under the scene's checks; cells
        are text, already in the units the header names."""
        header = tuple(str(h) for h in header)
        rows = tuple(tuple(str(c) for c in row) for row in rows)
        if any(len(row) != len(header) for row in rows):
            raise ValueError(f"table {title!r}: every row needs {len(header)} cells")
        self._tables.append((str(title), header, rows))

    def checkpoint(self) -> None:
        """Raise KeyboardInterrupt when the user asked to stop (the first Ctrl-C of ``ballbench validate``): the
        scene ends at its next step instead of running to its end.  :meth:`progress` calls it before each step."""
        if self.should_stop():
            raise KeyboardInterrupt

    def progress(self, iterable: Iterable, *, total: int | None = None, desc: str = ""):
        """Wrap a long loop: a progress bar (tqdm on stderr) on a terminal, else one line per step on stderr when
        ``progress_lines`` (output piped to a file or a CI log); a stop request (:meth:`checkpoint`) ends the
        scene before the next step."""
        if total is None and hasattr(iterable, "__len__"):
            total = len(iterable)
        if self.show_progress:
            from tqdm.auto import tqdm

            iterable = tqdm(iterable, total=total, desc=desc or self.scene.name, leave=False)
        return self._steps(iterable, total, desc or "steps")

    def _steps(self, iterable: Iterable, total: int | None, label: str):
        start = time.perf_counter()
        for k, item in enumerate(iterable):
            self.checkpoint()
            if self.progress_lines:
                print(f"ballbench: {self.scene.name}: {label}: step {k + 1} of {total if total else '?'} "
                      f"({time.perf_counter() - start:.1f} s)", file=sys.stderr, flush=True)
            yield item
        self.checkpoint()

    @property
    def outputs(self) -> tuple[Output, ...]:
        return tuple(self._outputs)

    def result(self, wall_time_s: float, error: str = "", interrupted: bool = False,
               peak_memory_gb: float = 0.0, not_applicable: str = "",
               scene_peak_memory_gb: float = 0.0) -> SceneResult:
        return SceneResult(self.scene.name, self.scene.description, self.fidelity,
                           tuple(self._outputs), tuple(self._artifacts), tuple(self._notes),
                           wall_time_s, error, self.scene.budget_for(self.fidelity), self.scene.kind, interrupted,
                           tuple(self._tables), peak_memory_gb, not_applicable, " ".join(self._inconclusive),
                           scene_peak_memory_gb, self.scene.memory_for(self.fidelity))


def registry() -> dict[str, Scene]:
    """All registered scenes, after importing every module of validation.scenes."""
    _scenes.load_all()
    return dict(REGISTRY)
