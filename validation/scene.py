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
"""
from __future__ import annotations

import math
import statistics
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Callable, Iterable

FIDELITIES = ("quick", "default", "fine")
RELATIONS = ("eq", "ge", "le")


@dataclass(frozen=True)
class Output:
    """One checked number of a scene (a row of the report)."""

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

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


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

    @property
    def passed(self) -> bool:
        return not self.error and bool(self.outputs) and all(o.passed for o in self.outputs)


@dataclass(frozen=True)
class Scene:
    name: str
    description: str
    function: Callable[["Run"], None]
    tags: tuple[str, ...] = ()
    default: bool = True


_REGISTRY: dict[str, Scene] = {}


def scene(name: str, description: str, *, tags: Iterable[str] = (), default: bool = True):
    """Register the decorated function as the scene ``name``.

    ``default=False`` keeps the scene out of a bare ``ballbench validate``
    (it still runs when named).
    """

    def register(function: Callable[["Run"], None]) -> Callable[["Run"], None]:
        if name in _REGISTRY and _REGISTRY[name].function is not function:
            raise ValueError(f"scene {name!r} is registered twice")
        _REGISTRY[name] = Scene(name, description, function, tuple(tags), default)
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

    def __init__(self, scene: Scene, fidelity: str, out_dir: Path, *, show_progress: bool = True):
        if fidelity not in FIDELITIES:
            raise ValueError(f"fidelity must be one of {FIDELITIES}, got {fidelity!r}")
        self.scene = scene
        self.fidelity = fidelity
        self.out_dir = Path(out_dir)
        self.show_progress = show_progress
        self._outputs: list[Output] = []
        self._artifacts: list[str] = []
        self._notes: list[str] = []

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
    ) -> Output:
        """Record ``value`` of ``quantity`` (SI ``unit``) against ``reference``.

        ``tolerance`` is on the relative error defined in the module docstring.
        """
        value = float(value)
        reference = float(reference)
        if not tolerance >= 0.0:
            raise ValueError(f"tolerance must be >= 0, got {tolerance!r}")
        rel_error = relative_error(value, reference, relation=relation, scale=scale)
        passed = bool(math.isfinite(value) and rel_error <= tolerance)
        output = Output(model, quantity, unit, value, reference, source, float(rel_error),
                        float(tolerance), passed, float(time_s), relation, note)
        self._outputs.append(output)
        return output

    # -- artifacts, notes, progress --------------------------------------
    def path(self, filename: str) -> Path:
        """Path for an artifact of this scene (``<out>/<scene>/<filename>``)."""
        directory = self.out_dir / self.scene.name
        directory.mkdir(parents=True, exist_ok=True)
        return directory / filename

    def save_figure(self, figure, filename: str) -> Path:
        """Save a matplotlib figure as PNG next to the report and close it."""
        import matplotlib.pyplot as plt

        target = self.path(filename)
        figure.savefig(target, dpi=120, bbox_inches="tight")
        plt.close(figure)
        self.add_artifact(target)
        return target

    def add_artifact(self, path: Path | str) -> None:
        path = Path(path)
        try:
            self._artifacts.append(str(path.relative_to(self.out_dir)))
        except ValueError:
            self._artifacts.append(str(path))

    def note(self, text: str) -> None:
        """A sentence for the report under this scene's table (conventions, gaps)."""
        self._notes.append(text)

    def progress(self, iterable: Iterable, *, total: int | None = None, desc: str = ""):
        """Wrap a long loop in a progress bar (tqdm on stderr)."""
        if not self.show_progress:
            return iterable
        from tqdm.auto import tqdm

        return tqdm(iterable, total=total, desc=desc or self.scene.name, leave=False)

    def result(self, wall_time_s: float, error: str = "") -> SceneResult:
        return SceneResult(self.scene.name, self.scene.description, self.fidelity,
                           tuple(self._outputs), tuple(self._artifacts), tuple(self._notes),
                           wall_time_s, error)


def registry() -> dict[str, Scene]:
    """All registered scenes, after importing every module of validation.scenes."""
    from ballbench.validation import scenes as _scenes

    _scenes.load_all()
    return dict(_REGISTRY)
