"""ballbench: validate and calibrate low-order friction models of ball bearings
and ball screws against finite-element analysis and published numbers.

The four layers install under this namespace from the project's top-level
folders (pyproject ``package-dir``): ``ballbench.lowmodel`` (``lowmodel/``),
``ballbench.meshes`` (``meshes/``), ``ballbench.fem`` (``fem/``) and
``ballbench.validation`` (``validation/``).  Layers and the import rule:
docs/architecture.md.  Importing this package imports none of them.

The small public API (docs/cases.md, "Python"): every function imports what it
needs when called, so ``import ballbench`` stays light (no numpy work, no gmsh,
pyvista, vtk or matplotlib)::

    import ballbench
    case = ballbench.load_case("my_guide.toml")     # SI inside, units only in the file
    result = ballbench.friction(case)               # GuideResult / ScrewResult (frozen dataclasses)
    result.friction_force, result.friction_increase, result.b2b_forces, result.contacts[0].p0
    contact = ballbench.contact(case)               # exact Hertz of the most loaded contact
    results = ballbench.ladder(case, "quick", levels="BEM")   # the validation ladder: SceneResult per scene
    ballbench.hertz.ball_in_groove(3.175e-3, 0.52)  # the models, one attribute deep (SI floats)
"""
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


def __getattr__(name):
    if name == "__version__":  # read on first use: importlib.metadata is most of this package's import time
        return _version()
    if name in _MODULES:
        import importlib

        return importlib.import_module(_MODULES[name])
    raise AttributeError(f"module 'ballbench' has no attribute {name!r}")


def load_case(path):
    """The case of the TOML case file ``path`` (``ballbench init KIND`` writes one): a LinearGuideCase,
    BallScrewCase or ContactCase in SI units (ballbench.validation.cases.case).  Every key is checked before any
    work; a mistake raises ValueError (CaseFileError) naming the file, line, key and range (docs/cases.md)."""
    from ballbench.validation.cases import case_file

    return case_file.load(path)


def template(kind: str) -> str:
    """The commented case file of ``kind`` ("linear-guide", "ball-screw" or "contact"), as ``ballbench init``
    writes it."""
    from ballbench.validation.cases import case_file

    return case_file.template(kind)


def friction(case):
    """What an engineer reads from a linear guide or ball screw case: per ball and contact the loads, angles,
    Hertz ellipses and pressures; the carriage friction force [N] (GuideResult) or the friction torque on the nut
    [N m] (ScrewResult) with and without ball-to-ball contact, the friction increase and the B2B forces, by the
    low-order numerical models (validation.studies.bearing_results; ``.to_dataset()`` gives xarray)."""
    from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
    from ballbench.validation.studies import bearing_results

    if isinstance(case, LinearGuideCase):
        return bearing_results.guide_result(case)
    if isinstance(case, BallScrewCase):
        return bearing_results.screw_result(case)
    raise TypeError(f"friction takes a LinearGuideCase or BallScrewCase (ballbench.load_case), got "
                    f"{type(case).__name__}")


def contact(case):
    """Exact Hertz (lowmodel.contact.hertz.HertzContact: a, b, p0, approach in SI) of the contact of a
    ContactCase, or of the most loaded contact of a linear guide or ball screw (validation.ladder.rungs)."""
    from ballbench.lowmodel.contact import hertz as _hertz
    from ballbench.validation.ladder import rungs
    from ballbench.validation.studies import fe_contact

    governing = rungs.governing_contact(case)
    return _hertz.solve_load(fe_contact.hertz_geometry(governing), governing.force)


def ladder(case, fidelity: str = "quick", *, levels: str = "stick-slip", out_dir=None, budget_s=None,
           name: str = "case"):
    """Run the validation ladder on ``case`` (validation.ladder) up to the rung ``levels`` (one of
    validation.ladder.rungs.RUNGS) at ``fidelity`` ("quick", "default" or "fine"); returns the SceneResult of
    each scene (checks with error and run time per model, tables of the engineer's results).  ``out_dir``: where
    the scenes write their files and the report (a temporary folder, deleted afterwards, when None);
    ``budget_s``: stop refining mesh studies when their next level is predicted to end after this wall time."""
    import tempfile
    import time
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
