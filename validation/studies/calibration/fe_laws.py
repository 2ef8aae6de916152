"""The contact laws of ``ballbench calibrate`` fitted on FE (docs/calibration.md): the FE load sweep of a contact
case (a registered scene's, or a case file's most loaded contact) and the law ``U = C F^(2/3) + C_b F``,
``a = Psi R^(1/3) F^(1/3)`` fitted to it (lowmodel.calibration), with the pair's Hertz C and Psi as references."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import ContactCase, case_file
from ballbench.validation.ladder import rungs
from ballbench.validation.scene import registry

__all__ = ["check_load_factors", "fe_contact_scenes", "fe_load_sweep", "hertz_references", "contact_law",
           "fe_contact_law", "case_contact"]


def check_load_factors(load_factors) -> np.ndarray:
    """The load factors of an FE load sweep as an array; ValueError unless >= 3 values in (0, 1.5]."""
    factors = np.asarray(load_factors, dtype=float)
    if factors.ndim != 1 or factors.size < 3 or np.any(factors <= 0.0) or np.any(factors > 1.5):
        raise ValueError("load_factors must be >= 3 values in (0, 1.5] (the FE candidate zone holds the contact up "
                         f"to 1.5 times the scene's force), got {list(np.atleast_1d(load_factors))}")
    return factors


def fe_contact_scenes() -> dict:
    """The registered scenes that run a single contact with FE settings: ``{scene name: ContactCase}`` (the
    scene's own ``case``; what ``fe_scene`` of a spec may name)."""
    return {name: entry.case for name, entry in registry().items()
            if isinstance(entry.case, ContactCase) and entry.case.fe is not None}


def fe_load_sweep(scene_name: str, fidelity: str = "quick", load_factors=(0.5, 0.75, 1.0, 1.25, 1.5)) -> dict:
    """FE load sweep of the contact case of scene ``scene_name`` (:func:`fe_contact_scenes`):
    ``force`` [N], ``approach`` [m], ``a`` [m] at every load (studies.fe_contact.load_sweep).

    One mesh and one condensation (the checked level of the case at ``fidelity``),
    then a contact solve and a Hertz-field fit per load.  Returns also
    ``ball_radius`` [m], the Hertz ``geometry`` and the wall time [s].
    """
    from ballbench.validation.studies import fe_contact

    cases = fe_contact_scenes()
    if scene_name not in cases:
        raise ValueError(f"fe_scene must be one of {sorted(cases)}, got {scene_name!r}")
    return fe_contact.load_sweep(cases[scene_name], fidelity, check_load_factors(load_factors))



def hertz_references(geometry, ball_radius):
    """(Hertz C [m N^-2/3], lin2019 eq 53; Psi [-], lin2019 eq 15) of the Hertz ``geometry`` and ``ball_radius`` [m]."""
    return hertz.hertz_constant(geometry), hertz.psi_constant(geometry, ball_radius)


def contact_law(case, fidelity: str = "quick", load_factors=(0.5, 0.75, 1.0, 1.25, 1.5), *,
                confidence: float = 0.95, label: str = "") -> tuple[cal.ContactLaw, dict]:
    """The contact law ``U = C F^(2/3) + C_b F``, ``a = Psi R^(1/3) F^(1/3)`` fitted to the FE load sweep of the
    :class:`ContactCase` ``case`` at ``fidelity`` (studies.fe_contact.load_sweep), with the pair's Hertz C and Psi
    as references; returns (law, sweep with its ``source`` text, which names ``label`` or the case)."""
    from ballbench.validation.studies.fe_contact import load_sweep

    sweep = load_sweep(case, fidelity, check_load_factors(load_factors))
    radius = sweep["ball_radius"]
    reference_c, reference_psi = hertz_references(sweep["geometry"], radius)
    source = (f"FE {label or case.name} {fidelity} level (n = b/h = {sweep['level'][0]:g}, growth "
              f"{sweep['level'][1]:g}, {sweep['ndofs']} DOFs), {sweep['force'].size} loads "
              f"{sweep['force'].min():g}-{sweep['force'].max():g} N")
    law = cal.fit_contact_law(sweep["force"], sweep["approach"], semi_axes=sweep["a"], ball_radius=radius,
                              confidence=confidence, source=source, hertz_constant=reference_c, psi=reference_psi)
    return law, {**sweep, "source": source}


def fe_contact_law(scene_name: str, fidelity: str = "quick", load_factors=(0.5, 0.75, 1.0, 1.25, 1.5), *,
                   confidence: float = 0.95) -> tuple[cal.ContactLaw, dict]:
    """:func:`contact_law` of the contact case of scene ``scene_name`` (:func:`fe_contact_scenes`)."""
    cases = fe_contact_scenes()
    if scene_name not in cases:
        raise ValueError(f"fe_scene must be one of {sorted(cases)}, got {scene_name!r}")
    return contact_law(cases[scene_name], fidelity, load_factors, confidence=confidence, label=scene_name)


def case_contact(path: str | Path):
    """The contact an ``fe_case`` of a spec names: the case file's own contact, or the most loaded contact of a
    linear guide or ball screw, with the FE levels of its file or chosen from its Hertz ellipse
    (ladder.rungs.contact_fe; docs/cases.md)."""
    return rungs.contact_fe(rungs.governing_contact(case_file.load(path)))
