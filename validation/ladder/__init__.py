"""The validation ladder of a case of one's own, its one home: ``ballbench validate my_guide.toml`` runs it on one's
own bearing with the same harness, report, ``show`` pictures and VTU as the paper scenes.  :mod:`.rungs` holds the
rungs, the governing and distinct contacts and the mesh levels chosen from a case; :mod:`.balls`,
:mod:`.contact`, :mod:`.ehl`, :mod:`.b2b_fe` and :mod:`.stick_slip` build one scene each, :mod:`.common` holds
their shared tolerances and checks.  The run logic of the stick/slip and EHL rungs lives in studies
(studies.case_stick_slip, studies.case_ehl).

This package is a factory, not a scene module: it builds :class:`~ballbench.validation.scene.Scene` objects from a
case (they are not registered; the CLI runs them beside or instead of the registered scenes).  A case file gives:

* ``<stem>-balls`` (linear guide, ball screw): the low-order numerical model of the balls, touching and free:
  loads, angles, ellipses and pressures per ball and contact, the friction force [N] or torque [N m] with and
  without B2B contact, the friction increase, the B2B forces (lowmodel.bearing_results); power balance and statics
  checks; for a guide the analytical B2B model (lin2019 eq 30) against the numerical one;
* ``<stem>-whole`` (linear guide with a ``[carriage]``; rung ``low-order``): the rigid carriage under its
  external load (lowmodel.linear_bearing.carriage): ball loads per row, displacement, 5 x 5 stiffness,
  load-deflection curves, the static limit, the rows' friction at the load and over a ball pitch of travel
  (ladder.whole); of a ball screw with a ``[nut]``: the whole nut (ladder.whole_nut);
* ``<stem>-contact``: each distinct contact geometry at its largest load (ladder.rungs.distinct_contacts: one for
  a guide, whose rail and carriage grooves share a conformity, the screw and the nut side of a screw; the case's own
  contact) up the ladder: exact Hertz, the BEM on
  the exact gap on two or three grids, the FE on three or more meshes sized from its ellipse, the finest FE level
  with its uncertainty (references.uncertainty, Eca and Hoekstra) as the reference, every model's error against it
  and its run time; its fields (fields.vtu) and 3D screenshots;
* ``<stem>-ehl`` (ball screw or linear guide with a ``[lubricant]``; rung ``EHL``): each distinct contact lubricated
  at its load and the entrainment speed of the case's kinematics: the EHL solve's central and minimum film, U, G, W,
  k, the pressure against Hertz, its grid convergence, Hamrock-Dowson judged against the solve (studies.case_ehl);
* ``<stem>-stick-slip`` (linear guide, ball screw; rung ``stick-slip``): the balls with stick/slip contacts against
  full slip on the same cells (studies.case_stick_slip); the touching balls' stick/slip fields (NPZ, VTU) and picture;
* ``<stem>-b2b-fe`` (linear guide, ball screw; rung ``FE-informed``): the FE modules of the two balls on meshes from
  their ellipses, the FE-informed B2B force per level, the finest with its uncertainty the reference of the
  analytical and low-order B2B forces; the modules' fields and screenshots.

Every model judged against a higher rung is a *finding* check (``run.check(finding=True)``): a miss says the model is
outside its declared accuracy on this geometry (status ``outside accuracy``; docs/your_own_bearing.md, "Reading the
verdict"), not that the software failed; the solvers' own checks (power balance, statics, load balance) stay
pass/fail.  A reference too uncertain to judge at the run's fidelity ends the scene ``inconclusive`` (run.inconclusive,
the models not judged; docs/verification.md).

A scene whose model has no state on the case raises NotApplicable (status ``not applicable``, with the reason): the
FE screw module where lin2019's state leaves a contact unloaded (b2b_fe); every ball-screw scene where lin2019's
model finds no state (past the preload loss, or below it where friction unloads a contact first;
common.within_model_limits, around each scene function and show hook), but ``<stem>-contact``, which then runs on
the loads of the frictionless statics (lowmodel.screw.preload; the contact module).  :func:`limits` says before
any work where a ball screw's axial load stands against its preload loss.

``top`` (``--levels``) names the highest rung to run; ``deadline`` (``--budget``, a ``time.monotonic()`` value)
stops refining a mesh study when the next level's predicted time would pass it.

Modules: ``balls`` (``<stem>-balls``), ``contact`` (``<stem>-contact``), ``ehl`` (``<stem>-ehl``), ``b2b_fe``
(``<stem>-b2b-fe``), ``stick_slip`` (``<stem>-stick-slip``), ``common``
(tolerances, tables and checks they share); this file names the scenes of a case and builds them.
"""
from __future__ import annotations

import functools
import re
from dataclasses import replace
from pathlib import Path

from ballbench.validation.cases.case import ContactCase, LinearGuideCase
from ballbench.validation.ladder.b2b_fe import b2b_fe_scene, show_module
from ballbench.validation.ladder.balls import balls_scene
from ballbench.validation.ladder.common import limited, limits_lines
from ballbench.validation.ladder.contact import contact_scene, show_contact
from ballbench.validation.ladder.ehl import ehl_scene
from ballbench.validation.ladder.rungs import rungs_up_to
from ballbench.validation.ladder.stick_slip import stick_slip_scene
from ballbench.validation.ladder.whole import whole_scene
from ballbench.validation.ladder.whole_nut import nut_scene
from ballbench.validation.ladder.whole_show import show_whole
from ballbench.validation.scene import NotApplicable, Scene

__all__ = ["case_scenes", "scene_names", "show_case", "slug", "limits"]

BUDGET_S = {"quick": 900.0, "default": 1800.0, "fine": 7200.0}  # wall-time budget of a generated FE scene [s]
LOW_BUDGET_S = {"quick": 60.0, "default": 60.0, "fine": 60.0}   # of a generated scene without FE [s]
# <stem>-whole: the friction over travel (ladder.whole.TRAVEL_STEPS steps) solves stick/slip chains, and a chain
# without a state is parted and solved again (docs/carriage.md, "Cost")
WHOLE_BUDGET_S = {"quick": 240.0, "default": 600.0, "fine": 1200.0}
# the stick/slip rung's resident memory at the default fidelity [GB]: the FE compliance condensation of the case's
# groove (8 x 32 cells, P2; docs/your_own_bearing.md)
STICK_SLIP_MEMORY_GB = 6.0


def slug(path: str | Path) -> str:
    """The scene-name prefix of a case file: its stem in lower case, letters, digits and '-'."""
    text = re.sub(r"[^a-z0-9]+", "-", Path(path).stem.lower()).strip("-")
    return text or "case"


def _kind(case) -> str:
    return ("contact" if isinstance(case, ContactCase) else "linear-guide" if isinstance(case, LinearGuideCase)
            else "ball-screw")


def _lubricated(case) -> bool:
    from ballbench.validation.studies import case_ehl

    return case_ehl.applies(case)


def _whole(case) -> bool:
    """Whether the case describes a whole bearing: a carriage or a nut."""
    return getattr(case, "carriage", None) is not None or getattr(case, "nut", None) is not None


def scene_names(case, stem: str, top: str = "stick-slip") -> list[str]:
    """The names of the scenes :func:`case_scenes` builds."""
    rungs = rungs_up_to(top)
    names = [] if isinstance(case, ContactCase) else [f"{stem}-balls"]
    if "low-order" in rungs and _whole(case):
        names.append(f"{stem}-whole")
    names.append(f"{stem}-contact")
    if "EHL" in rungs and _lubricated(case):
        names.append(f"{stem}-ehl")
    if "FE-informed" in rungs and not isinstance(case, ContactCase):
        names.append(f"{stem}-b2b-fe")
    if "stick-slip" in rungs and not isinstance(case, ContactCase):
        names.append(f"{stem}-stick-slip")
    return names


def case_scenes(case, stem: str, *, top: str = "stick-slip", deadline: float | None = None) -> list[Scene]:
    """The scenes of ``case`` (a LinearGuideCase, BallScrewCase or ContactCase) named ``<stem>-...``, up to the
    rung ``top`` (ladder.rungs.RUNGS)."""
    rungs = rungs_up_to(top)
    kind = _kind(case)
    fe = "FE" in rungs
    scenes = []
    if kind != "contact":
        what = "linear guide" if kind == "linear-guide" else "ball screw"
        scenes.append(Scene(f"{stem}-balls", f"{case.name}: the balls of the {what} by the low-order numerical model "
                            "(loads, angles, ellipses, pressures, friction with and without B2B contact)",
                            functools.partial(balls_scene, case=case, rungs=rungs), tags=("case",), kind="low-order",
                            cost_s=5.0, budget_s=LOW_BUDGET_S, case=case))
    if "low-order" in rungs and getattr(case, "nut", None) is not None:
        scenes.append(Scene(f"{stem}-whole", f"{case.name}: the whole nut (ball loads along it, stiffness, friction "
                            "torque over rotation; a double nut's preload and lift-off; the FE rung of an elastic "
                            "nut)", functools.partial(nut_scene, case=case, rungs=rungs), tags=("case",),
                            kind="FE" if fe else "low-order", cost_s=60.0 if fe else 30.0, budget_s=WHOLE_BUDGET_S,
                            case=case, show=functools.partial(show_whole, case)))
    if "low-order" in rungs and getattr(case, "carriage", None) is not None:
        scenes.append(Scene(f"{stem}-whole", f"{case.name}: the whole carriage under its external load (ball loads "
                            "per row, displacement, stiffness, load-deflection, friction over travel; the FE rung of "
                            "an elastic carriage)",
                            functools.partial(whole_scene, case=case, rungs=rungs), tags=("case",),
                            kind="FE" if fe else "low-order", cost_s=90.0 if fe else 60.0, budget_s=WHOLE_BUDGET_S,
                            case=case, show=functools.partial(show_whole, case)))
    # ladder.rungs.distinct_contacts: the screw and the nut side; the FE on both except at the quick level
    n_contacts = 2 if kind == "ball-screw" else 1
    scenes.append(Scene(f"{stem}-contact", f"{case.name}: each distinct contact at its largest load up the ladder ("
                        + ", ".join(r for r in rungs if r in ("analytical", "BEM", "FE")) + ")",
                        functools.partial(contact_scene, case=case, rungs=rungs, deadline=deadline), tags=("case",),
                        kind="FE" if fe else "low-order", cost_s=(120.0 if fe else 5.0) * n_contacts,
                        budget_s=({f: t * (1 if f == "quick" else n_contacts) for f, t in BUDGET_S.items()} if fe
                                  else LOW_BUDGET_S),
                        case=case, show=functools.partial(show_contact, case) if fe else None))
    if "EHL" in rungs and _lubricated(case):
        scenes.append(Scene(f"{stem}-ehl", f"{case.name}: each distinct contact lubricated (smooth isothermal EHL on "
                            "the exact groove gap at the case's entrainment speed): film, U, G, W, pressure, "
                            "Hamrock-Dowson against the solve", functools.partial(ehl_scene, case=case),
                            tags=("case",), kind="low-order", cost_s=25.0 * n_contacts,
                            budget_s={"quick": 60.0, "default": 120.0, "fine": 900.0}, case=case))
    if "FE-informed" in rungs and kind != "contact":
        scenes.append(Scene(f"{stem}-b2b-fe", f"{case.name}: FE modules of the two balls and the FE-informed B2B "
                            "force per mesh level, the finest the reference of the analytical and low-order models",
                            functools.partial(b2b_fe_scene, case=case, deadline=deadline), tags=("case",), kind="FE",
                            cost_s=300.0, budget_s=BUDGET_S, case=case, show=functools.partial(show_module, case)))
    if "stick-slip" in rungs and kind != "contact":
        scenes.append(Scene(f"{stem}-stick-slip", f"{case.name}: the balls with stick/slip contacts against full "
                            "slip on the same cells (Lambda, stick fraction, forces, spin moments, B2B force)",
                            functools.partial(stick_slip_scene, case=case), tags=("case",), kind="low-order",
                            cost_s=150.0, budget_s={"quick": 300.0, "default": 900.0, "fine": 3600.0}, case=case,
                            memory_gb=STICK_SLIP_MEMORY_GB))
    if kind != "contact":  # lin2019's model has no state past a screw's preload loss or a guide's full sliding
        scenes = [replace(s, function=limited(s.function, case),
                          show=None if s.show is None else limited(s.show, case)) for s in scenes]
    return scenes


def limits(case, stem: str, top: str = "stick-slip") -> list[str]:
    """Lines for the reader before any work: the case's model limits (a ball screw's preload loss, and the scenes
    that do not apply past it; common.limits_lines)."""
    return limits_lines(case, scene_names(case, stem, top))


def show_case(case, stem: str, out_dir: Path, fidelity: str = "default", *, solve: bool = False, on_skip=None,
              on_missing=None) -> list[Path]:
    """``ballbench show my_case.toml``: the pictures of every generated scene that has them, drawn from the fields
    ``validate`` saved in ``out_dir/<scene>/``.  A scene that does not apply to the case (NotApplicable) is skipped:
    ``on_skip(scene_name, reason)`` is told; one that saved nothing is skipped too, ``on_missing(scene_name,
    error)`` told, or with ``solve`` solved at ``fidelity`` first (``ballbench show --solve``)."""
    paths = []
    for scene in case_scenes(case, stem):
        if scene.show is not None:
            try:
                paths += scene.show(Path(out_dir) / scene.name, fidelity, solve)
            except NotApplicable as skipped:
                if on_skip is not None:
                    on_skip(scene.name, skipped.reason)
            except FileNotFoundError as missing:
                if solve or on_missing is None:
                    raise
                on_missing(scene.name, missing)
    return paths
