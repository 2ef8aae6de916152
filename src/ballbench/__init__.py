"""ballbench: validate and calibrate low-order friction models of ball bearings
and ball screws against finite-element analysis and published numbers.

The four layers install under this namespace from the project's top-level
folders (pyproject ``package-dir``): ``ballbench.lowmodel`` (``lowmodel/``),
``ballbench.meshes`` (``meshes/``), ``ballbench.fem`` (``fem/``) and
``ballbench.validation`` (``validation/``).  Layers and the import rule:
docs/architecture.md.  Importing this package imports none of them.

The small public API (docs/cases.md, "Python"): every function imports what it
needs when called, so ``import ballbench`` stays light (no numpy work, no gmsh,
pyvista, vtk or matplotlib).  The models are reached at the model layer
(``friction`` and ``contact`` are ``ballbench.lowmodel.bearing_results``'s, on the
description types of ``ballbench.lowmodel.bearing``); ``load_case`` reads a case
file (the TOML schema of ``ballbench.validation.cases``) into such a description
with a name and FE settings; ``ladder`` runs the validation harness::

    import ballbench
    case = ballbench.load_case("my_guide.toml")     # SI inside, units only in the file
    result = ballbench.friction(case)               # GuideResult / ScrewResult (frozen dataclasses)
    result.friction_force, result.friction_increase, result.b2b_forces, result.contacts[0].p0
    contact = ballbench.contact(case)               # exact Hertz of the most loaded contact
    results = ballbench.ladder(case, "quick", levels="BEM")   # the validation ladder: SceneResult per scene
    ballbench.hertz.ball_in_groove(3.175e-3, 0.52)  # the models, one attribute deep (SI floats)
"""
import time

__all__ = ["load_case", "template", "friction", "contact", "ladder", "hertz", "halfspace", "b2b",
           "b2b_analytical", "screw", "__version__"]

# the model modules one attribute deep (imported on first use, PEP 562)
_MODULES = {
    "hertz": "ballbench.lowmodel.contact.hertz",
    "halfspace": "ballbench.lowmodel.contact.halfspace",
    "b2b": "ballbench.lowmodel.linear_bearing.b2b",
    "b2b_analytical": "ballbench.lowmodel.linear_bearing.b2b_analytical",
    "screw": "ballbench.lowmodel.screw",
}


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ballbench")
    except PackageNotFoundError:  # running from a source tree that was never installed
        return "0+unknown"


# the front door's model functions, defined at the model layer (imported on first use, PEP 562):
# ``friction(case)`` (GuideResult / ScrewResult: per ball and contact the loads, angles, Hertz ellipses and pressures;
# the carriage friction force [N] or the nut's friction torque [N m] with and without ball-to-ball contact, the
# friction increase and the B2B forces) and ``contact(case)`` (exact Hertz of a single contact, or of the most loaded
# contact of a linear guide or ball screw); ``case`` a ballbench.lowmodel.bearing load case or a case file's
_FUNCTIONS = {
    "friction": "ballbench.lowmodel.bearing_results",
    "contact": "ballbench.lowmodel.bearing_results",
}


def __getattr__(name):
    if name == "__version__":  # read on first use: importlib.metadata is most of this package's import time
        return _version()
    if name in _MODULES or name in _FUNCTIONS:
        import importlib

        if name in _MODULES:
            return importlib.import_module(_MODULES[name])
        return getattr(importlib.import_module(_FUNCTIONS[name]), name)
    raise AttributeError(f"module 'ballbench' has no attribute {name!r}")


def load_case(path):
    """The case of the TOML case file ``path`` (``ballbench init KIND`` writes one): a LinearGuideCase,
    BallScrewCase or ContactCase in SI units (ballbench.validation.cases.case: a load case of
    ballbench.lowmodel.bearing with the file's name and FE settings).  Every key is checked before any
    work; a mistake raises ValueError (CaseFileError) naming the file, line, key and range (docs/cases.md)."""
    from ballbench.validation.cases import case_file

    return case_file.load(path)


def template(kind: str) -> str:
    """The commented case file of ``kind`` ("linear-guide", "ball-screw" or "contact"), as ``ballbench init``
    writes it."""
    from ballbench.validation.cases import case_file

    return case_file.template(kind)


def ladder(case, fidelity: str = "quick", *, levels: str = "stick-slip", out_dir=None, budget_s=None,
           name: str = "case"):
    """Run the validation ladder on ``case`` (validation.ladder) up to the rung ``levels`` (one of
    validation.ladder.rungs.RUNGS) at ``fidelity`` ("quick", "default" or "fine"); returns the SceneResult of
    each scene (checks with error and run time per model, tables of the engineer's results).  ``out_dir``: where
    the scenes write their files and the report (a temporary folder, deleted afterwards, when None);
    ``budget_s``: stop refining mesh studies when their next level is predicted to end after this wall time."""
    import tempfile
    from pathlib import Path

    from ballbench.validation.ladder import case_scenes
    from ballbench.validation.report import write_report
    from ballbench.validation.runner import run_scenes

    deadline = time.monotonic() + budget_s if budget_s is not None else None
    scenes = case_scenes(case, name, top=levels, deadline=deadline)
    if out_dir is None:
        with tempfile.TemporaryDirectory() as folder:
            return run_scenes(scenes, fidelity, Path(folder))[0]
    results = run_scenes(scenes, fidelity, Path(out_dir))[0]
    write_report(results, Path(out_dir), fidelity)
    return results
