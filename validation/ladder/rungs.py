"""The validation ladder of a case of one's own: every model that applies, from Hertz to FE, as functions of the
case (docs/cases.md, "Validate your own bearing").

Rungs, bottom to top (:data:`RUNGS`):

* ``analytical``: exact Hertz of the most loaded contact (lowmodel.contact.hertz); the analytical B2B model of a
  linear guide (lin2019 eq 30);
* ``low-order``: the low-order numerical models of the balls (lowmodel.linear_bearing.b2b, lowmodel.screw.b2b):
  loads, angles, ellipses, friction force or torque, B2B forces (lowmodel.bearing_results);
* ``BEM``: the half-space contact on the exact gap of the most loaded contact (lowmodel.contact.halfspace; the
  helical grooves through lowmodel.contact.screw_contact), on grids of ``n x n`` cells;
* ``EHL`` (a ball screw whose file gives a ``[lubricant]``): each distinct contact lubricated, the smooth
  isothermal EHL solve on the exact helical gap (lowmodel.contact.ehl, sun2021 eqs 14-19; its deflection is the
  BEM's half-space) at the entrainment speed of the case's kinematics, the reference of the Hamrock-Dowson film
  (studies.case_ehl);
* ``FE``: the contact of the most loaded contact in FE (studies.fe_contact) on three or more meshes whose sizes
  follow its Hertz ellipse (``h = b / n``, :func:`contact_fe`), the finest level with its uncertainty over the
  levels (references.uncertainty): the reference every model of the contact is judged against;
* ``FE-informed``: the FE modules of the two balls (fem.fourpoint, fem.screw_module) on meshes sized from the
  smallest ellipse of the module (:func:`module_fe`), their contact pressures fed to the B2B model
  (studies.fe_b2b_linear, studies.fe_b2b_screw); the finest FE-informed B2B force is the reference of the
  analytical and low-order B2B forces;
* ``stick-slip``: the case's balls with stick/slip ball-to-groove contacts (lowmodel.contact.rolling_friction on
  two half-spaces) against lin2019's full slip on the same cells (studies.case_stick_slip): whether full slip holds
  on the case, at its declared accuracy (docs/b2b_rolling.md, 'Validity of full slip').

The mesh levels of a case without an ``[fe]`` table are chosen here from its ellipses; a case file's ``[fe]``
table (the paper cases) is used as it is.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ballbench.lowmodel import bearing_results, truncation
from ballbench.meshes.parts.ball import DEFAULT_CAP_ANGLE
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove
from ballbench.validation.ladder.common import truncations
from ballbench.validation.cases.case import (BallScrewCase, ContactCase, ContactFe, LinearGuideCase, MeshLevels,
                                             ModuleFe, ModuleLevel, PairLevel, named)

__all__ = ["RUNGS", "rungs_up_to", "governing_contact", "distinct_contacts", "DistinctContact", "contact_fe",
            "module_fe", "module_cap_angle", "module_land_depth", "CAP_MARGIN", "MODULE_SLAB", "hertz_values",
           "bem_values", "BEM_GRIDS", "FE_TOLERANCES", "BEM_TOLERANCE", "HERTZ_TOLERANCES", "QUANTITIES",
           "predicted_time", "predicted_memory", "available_memory", "BYTES_PER_DOF", "SCREW_MODULE_BYTES_PER_DOF",
           "QUICK_DOF_CAP", "SCREW_QUICK_RATIOS",
           "SCREW_QUICK_GROWTH", "screw_quick_levels"]

RUNGS = ("analytical", "low-order", "BEM", "EHL", "FE", "FE-informed", "stick-slip")
QUANTITIES = (("a", "m"), ("b", "m"), ("p0", "Pa"), ("delta", "m"))
# n x n cells of the BEM per fidelity (coarse to fine; the finest is the BEM's reported level)
BEM_GRIDS = {"quick": (64, 128), "default": (128, 256), "fine": (128, 256, 512)}
# contact mesh levels n = b / h (a constant refinement ratio per study, for the extrapolation) and growth; the FE
# post-processing needs >= 5 elements across b (fem.postprocess), the papers' contacts run at n = 5.5-8 (docs/fem.md)
CONTACT_LEVELS = {"quick": ((5.5, 6.6, 7.92), 1.4), "default": ((5.5, 6.875, 8.59375), 1.35),
                  "fine": ((5.5, 6.875, 8.59375, 10.7421875), 1.3)}
# the quick study of a helical screw or nut contact of a case file (docs/your_own_bearing.md, "Memory and time of
# the FE rung"): the growth of the papers' screw scenes at quick (validation/cases/files/lin2019-contact-screw.toml),
# levels n = 5.5 r^k with the largest ratio r of SCREW_QUICK_RATIOS whose finest level has at most QUICK_DOF_CAP P2
# DOFs on its mesh; the cap is the largest level of the papers' screw scenes below --fine (fe-hertz-screw default,
# 334k DOFs, docs/fem.md)
SCREW_QUICK_GROWTH = 1.6
SCREW_QUICK_RATIOS = (1.2, 1.15, 1.1)
QUICK_DOF_CAP = 334_000
# the candidate zone of a case file's FE contact (ContactFe.gap_limit, in units of the Hertz approach delta at the
# case's force): it reaches CANDIDATE_REACH a along the major axis at the largest load of the study's sweep
# (fem.hertz_case.LOAD_FACTORS), by Hertz's separation A x^2 + B y^2, and never less than the papers' 1.05 delta
# (docs/your_own_bearing.md, "Heavy contacts")
CANDIDATE_REACH = 1.3
# peak resident memory of an FE contact level per P2 DOF [bytes]: the largest measured ratio of peak RSS to the
# finest level's DOFs (docs/your_own_bearing.md, "Memory and time of the FE rung")
BYTES_PER_DOF = 22.2e3
# the same for the modules of a ball screw's FE-informed B2B study (both balls' modules held at once; per DOF of
# their sum): the largest measured ratio on the catalogue (docs/your_own_bearing.md, "Memory and time of the FE rung")
SCREW_MODULE_BYTES_PER_DOF = 14.5e3
# module mesh levels h = b_max / n over the contacts of the module; the papers' modules run at h_contact 25-50 um
# for b = 40-70 um, n = 1-2.5 (validation/cases/files/lin2019-table*.toml); n = 1 was far from converged on
# 1/8-inch balls (docs/your_own_bearing.md, "Measured"), so the studies start at n = 1.25
# the module's ball caps hold the contact ellipse out to CAP_MARGIN a (the pressure's edge and about two cells
# beyond it at the module levels' growth): module_cap_angle
CAP_MARGIN = 1.25
# the candidate zone of a case file's FE module (ModuleFe.gap_limit): this many times the largest approach of the
# low-order state (a screw's plus its oversize).  Two held the guides of the catalogue; the slender ellipse of a
# screw of conformity 0.515 (examples/catalogue/screw_16x5.toml, b/a 0.1) reached the edge of that zone and runs in
# four (docs/your_own_bearing.md, "Heavy contacts"); a larger zone adds candidates, not a different answer
MODULE_ZONE = {"guide": 2.0, "screw": 4.0}
# the fine zone of each contact of a case file's screw module (one module per ball): the elliptic slab (1.3 a, 1.3 b,
# 0.5 b) about its Hertz ellipse, each contact at its own b / h (ModuleFe.per_contact).  A screw's ellipses are
# slender (a / b up to 10): a ball-shaped zone about the contact point left the ends of the major axis, where the
# contact's position on its flank is decided, in the growth zone (docs/your_own_bearing.md, "How the FE-informed B2B
# force converges with h").  A guide's module keeps the slabs (0.6 a, 1.3 b, 0.5 b) of docs/fe_b2b.md
MODULE_SLAB = (1.3, 1.3, 0.5)
MODULE_LEVELS = {"quick": ((1.25, 1.5625, 1.953125), 1.45), "default": ((1.5625, 1.953125, 2.44140625), 1.4),
                 "fine": ((1.5625, 1.953125, 2.44140625, 3.0517578125), 1.35)}
# What each model of the contact must reach against the FE reference, with the source of the number:
# the FE levels the accuracy docs/fem.md states for its levels (validation/scenes/fe_hertz.py checks the same
# numbers against Hertz), Hertz and the BEM the agreement docs/fem.md and docs/halfspace.md show for the papers'
# contacts at the default level.  A contact where Hertz misses is a contact outside Hertz's assumptions: the ladder
# shows it, the tolerance is not widened.
FE_TOLERANCES = {"quick": {"a": 0.03, "b": 0.03, "p0": 0.04, "delta": 0.03},
                 "default": {"a": 0.005, "b": 0.005, "p0": 0.01, "delta": 0.005},
                 "fine": {"a": 0.003, "b": 0.003, "p0": 0.005, "delta": 0.002}}
HERTZ_TOLERANCES = {"a": 0.005, "b": 0.005, "p0": 0.01, "delta": 0.005}
BEM_TOLERANCE = 0.005


def rungs_up_to(top: str) -> tuple[str, ...]:
    """The rungs from the bottom up to ``top`` (one of :data:`RUNGS`)."""
    if top not in RUNGS:
        raise ValueError(f"levels must be one of {', '.join(RUNGS)}, got {top!r}")
    return RUNGS[:RUNGS.index(top) + 1]


def predicted_time(times: list[float], sizes: list[float], next_size: float) -> float:
    """Wall time [s] of the next mesh level from the last measured one: ``t (h / h_next)^3`` (the DOFs of a 3D
    fine zone grow like ``h^-3``; the solve at least like the DOFs)."""
    return times[-1] * (sizes[-1] / next_size) ** 3


def predicted_memory(ndofs: int, bytes_per_dof: float = BYTES_PER_DOF) -> float:
    """Peak resident memory [bytes] of an FE level of ``ndofs`` P2 DOFs: ``bytes_per_dof * ndofs`` (the measured
    ratio, docs/your_own_bearing.md: :data:`BYTES_PER_DOF` for a contact level and a guide's module,
    :data:`SCREW_MODULE_BYTES_PER_DOF` for a screw's modules)."""
    return bytes_per_dof * float(ndofs)


def available_memory() -> float:
    """The memory the machine has available now [bytes] (psutil, which dask.distributed installs)."""
    import psutil

    return float(psutil.virtual_memory().available)


# --------------------------------------------------------------------------
# the governing contact of a case
# --------------------------------------------------------------------------
def governing_contact(case, result=None) -> ContactCase:
    """The most loaded contact of ``case`` as a :class:`ContactCase` (itself for a ContactCase): the largest normal
    force of the low-order touching state (``result``: its lowmodel.bearing_results result, computed when None;
    lowmodel.bearing_results.most_loaded)."""
    if isinstance(case, ContactCase):
        return case
    if not isinstance(case, (LinearGuideCase, BallScrewCase)):
        raise TypeError(f"a case is a ContactCase, LinearGuideCase or BallScrewCase, got {type(case).__name__}")
    worst, contact = bearing_results.most_loaded(case, result)
    where = "" if isinstance(case, LinearGuideCase) else f", {contact.pair} groove"
    return named(contact, f"{case.name}: most loaded contact (ball {worst.ball} {worst.contact}{where}, "
                          f"{worst.normal_force:.4g} N)")


@dataclass(frozen=True)
class DistinctContact:
    """One contact geometry of a case, run at the load of its most loaded contact.

    ``label``: what it is in words (``"groove"``, ``"screw side"``, ``"nut side"``, ``"contact"``); ``contact``:
    the :class:`ContactCase` at that load; ``members``: the contacts of the low-order state with this geometry
    (``"ball 1 BL"``, ...); ``why``: why those share it (the reader's table of the ``-contact`` scene)."""

    label: str
    contact: ContactCase
    members: tuple[str, ...]
    why: str


def distinct_contacts(case, result=None, *, frictionless: bool = False) -> tuple[DistinctContact, ...]:
    """The distinct contact geometries of ``case``, each at the largest normal force among its contacts, the most
    loaded first.  ``frictionless`` (a ball screw): the loads of the frictionless statics of its balls at its axial
    load (lowmodel.bearing_results.screw_frictionless_contacts; two-point contact past the preload loss) instead of
    lin2019's friction model's state (``result``), for the contact rung where that model has no state
    (docs/ball_screw.md, "Preload loss").  A guide's ``result`` may be its lin2017 eq 36 loads alone
    (lowmodel.bearing_results.guide_contacts), which lin2019's friction does not change.

    A contact's geometry is the ball radius, the groove's conformity and, for a helical groove, the side: a linear
    guide has one conformity for the rail (BL, BR) and the carriage (TL, TR) grooves (docs/fourpoint.md; the case's
    ``conformity``), so its four contacts are one geometry; in a ball screw the screw-side contacts (S*) touch a
    groove cut in the shaft and the nut-side ones (N*) a groove cut in the bore: their curvatures along the helix
    differ (docs/ball_screw.md, helical groove curvatures), two geometries.  A ContactCase is its own one."""
    if frictionless and not isinstance(case, BallScrewCase):
        raise ValueError(f"frictionless loads are those of a ball screw's balls (lowmodel.screw.preload), got a "
                         f"{type(case).__name__}")
    if isinstance(case, ContactCase):
        return (DistinctContact("contact", case, (case.name,), "the case file's own contact"),)
    if isinstance(case, LinearGuideCase):
        result = result or bearing_results.guide_contacts(case)  # eq 36's loads: the same under either law
        guide = case.guide
        contact = governing_contact(case, result)
        members = tuple(f"ball {c.ball} {c.contact}" for c in result.contacts)
        return (DistinctContact("groove", contact, members,
                                f"rail (BL, BR) and carriage (TL, TR) grooves have the one conformity "
                                f"{guide.conformity:g} and ball radius of the case: one contact geometry, run at the "
                                "largest load"),)
    if isinstance(case, BallScrewCase):
        if frictionless:
            loads = bearing_results.screw_frictionless_contacts(case)
        else:
            loads = (result or bearing_results.screw_result(case)).contacts
        words = ", frictionless statics" if frictionless else ""
        screw = case.screw
        found = []
        for pair, prefix in (("screw", "S"), ("nut", "N")):
            side = [c for c in loads if c.contact.startswith(prefix)]
            worst = max(side, key=lambda c: c.normal_force)
            if not worst.normal_force > 0:
                continue  # no loaded contact on this side: nothing to run
            contact = named(screw.contact(pair, worst.normal_force),
                            f"{case.name}: most loaded {pair}-side contact (ball {worst.ball} {worst.contact}, "
                            f"{worst.normal_force:.4g} N{words})")
            found.append(DistinctContact(f"{pair} side", contact, tuple(f"ball {c.ball} {c.contact}" for c in side),
                                         f"the {pair}-side contacts share the {pair} groove's curvatures (the "
                                         f"screw's conformity, pitch radius {screw.pitch_radius * 1e3:.4g} mm); "
                                         "run at the largest load of the side"
                                         + (" of the frictionless statics (lowmodel.screw.preload)" if frictionless
                                            else "")))
        return tuple(sorted(found, key=lambda d: -d.contact.force))
    raise TypeError(f"a case is a ContactCase, LinearGuideCase or BallScrewCase, got {type(case).__name__}")


# --------------------------------------------------------------------------
# mesh levels from the ellipses
# --------------------------------------------------------------------------
def contact_fe(case: ContactCase) -> ContactCase:
    """``case`` with FE settings: its own ``fe`` when given, else levels from its Hertz ellipse
    (:data:`CONTACT_LEVELS`, ``h = b / n``) and a fine zone (docs/fem.md, "Fine zones"): the elliptic slab
    (1.2 a, 1.3 b, 0.8 b) of a slender ellipse (b/a < 0.5) of a straight groove; for a helical screw or nut groove
    the slab (1.2 a, 1.3 b, 0.5 b) of a slender ellipse (else the capsule (1.2 b, 1.0 a)) and quick levels whose
    finest mesh stays within :data:`QUICK_DOF_CAP` (:func:`screw_quick_levels`); else the capsule of the papers'
    pairs."""
    if case.fe is not None:
        return case
    from ballbench.validation.studies import fe_contact

    geometry = fe_contact.hertz_geometry(case)
    gap_limit = candidate_gap_limit(geometry, case.force)
    levels = MeshLevels(**{f: tuple(PairLevel(n, growth) for n in ns) for f, (ns, growth) in CONTACT_LEVELS.items()})
    if case.pair == "groove" and geometry.axis_ratio < 0.5:
        fe = ContactFe(levels, "ellipse", (1.2, 1.3, 0.8))
    elif case.pair in ("screw", "nut"):
        fe = (ContactFe(levels, "ellipse", (1.2, 1.3, 0.5)) if geometry.axis_ratio < 0.5 else
              ContactFe(levels, "capsule", (1.2, 1.0)))
        fe = replace(fe, levels=replace(levels, quick=screw_quick_levels(replace(case, fe=fe))))
    else:
        fe = ContactFe(levels, "capsule", (1.3, 0.0 if geometry.axis_ratio > 0.8 else 1.1))
    return replace(case, fe=replace(fe, gap_limit=gap_limit))


def candidate_gap_limit(geometry: hertz.HertzGeometry, force: float) -> float:
    """The candidate zone of an FE contact study of ``geometry`` at ``force`` [N], as ContactFe.gap_limit (a
    multiple of the Hertz approach delta at ``force``): the initial gap ``min(A, B) (CANDIDATE_REACH a_top)^2``
    at the end of the major semi-axis grown by :data:`CANDIDATE_REACH`, ``a_top`` Hertz's at the largest load of
    the sweep (fem.hertz_case.LOAD_FACTORS: the zone must hold the contact there), and at least the 1.05 of the
    papers' pairs.  A slender ellipse ends where Hertz's separation is close to delta (``A a^2 / delta =
    (K(e) - E(e)) / (e^2 K(e))`` tends to 1, Johnson 1985 eqs 3.64-3.68), so the fixed 1.05 delta reaches barely
    past it at 1.5 times the force, and the FE contact, a few per cent longer than Hertz's, reached the zone's edge
    (docs/your_own_bearing.md, "Heavy contacts")."""
    from ballbench.fem.hertz_case import LOAD_FACTORS

    top = max(LOAD_FACTORS) * force
    reach = CANDIDATE_REACH * float(hertz.solve_load(geometry, top).a)
    delta = float(hertz.solve_load(geometry, force).delta)
    return max(ContactFe.gap_limit, min(geometry.A, geometry.B) * reach * reach / delta)


def screw_quick_levels(case: ContactCase) -> tuple:
    """The quick levels of a helical screw or nut contact ``case`` (with its fine zone in ``case.fe``): three levels
    ``n = n_1 r^k`` (``n_1`` the first quick level of :data:`CONTACT_LEVELS`, growth :data:`SCREW_QUICK_GROWTH`), ``r``
    the largest of :data:`SCREW_QUICK_RATIOS` whose finest level has at most :data:`QUICK_DOF_CAP` P2 DOFs on its
    mesh (meshed and counted, studies.fe_contact.level_dofs; the meshes are cached for the solve), else the smallest
    ratio (the scene's memory guard then decides what runs)."""
    from ballbench.validation.studies import fe_contact

    first = CONTACT_LEVELS["quick"][0][0]
    pair = fe_contact.pair_model(case)
    for ratio in SCREW_QUICK_RATIOS:
        levels = tuple(PairLevel(first * ratio ** k, SCREW_QUICK_GROWTH) for k in range(3))
        if fe_contact.level_dofs(pair, levels[-1]) <= QUICK_DOF_CAP:
            break
    return levels


def module_fe(case, result=None):
    """``case`` (LinearGuideCase or BallScrewCase) with module FE settings: its own ``fe`` when given, else levels
    ``h = b_max / n`` (:data:`MODULE_LEVELS`) over the Hertz ellipses of the low-order touching state
    (``result``), the candidate zone to :data:`MODULE_ZONE` times the largest approach (plus the oversize), for a
    guide the elliptic slabs (0.6 a, 1.3 b, 0.5 b) of docs/fe_b2b.md, for a screw the slabs :data:`MODULE_SLAB` with
    each contact at its own ``b / h``; the ball caps and the grooves' lands from the largest ellipse where the builders'
    defaults are too small for it (:func:`module_cap_angle`, :func:`module_land_depth`, docs/truncation.md)."""
    if case.fe is not None:
        return case

    if result is None:  # a guide's eq 36 loads are the same under either law
        result = (bearing_results.guide_contacts(case) if isinstance(case, LinearGuideCase)
                  else bearing_results.friction(case))
    loaded = [c for c in result.contacts if c.normal_force > 0]
    b_max = max(c.b for c in loaded)
    approach = max(c.approach for c in loaded)
    bearing = case.guide if isinstance(case, LinearGuideCase) else case.screw
    cap = module_cap_angle(max(c.a for c in loaded), bearing.ball_radius)
    land = module_land_depth(truncations(case, result), bearing.ball_radius, bearing.conformity)
    levels = MeshLevels(**{f: tuple(ModuleLevel(b_max / n, growth, None) for n in ns)
                           for f, (ns, growth) in MODULE_LEVELS.items()})
    if isinstance(case, LinearGuideCase):
        return replace(case, fe=ModuleFe(levels, MODULE_ZONE["guide"] * approach, (0.6, 1.3, 0.5), min_cap_angle=cap,
                                         land_depth=land))
    return replace(case, fe=ModuleFe(levels, MODULE_ZONE["screw"] * approach + case.screw.oversize, MODULE_SLAB,
                                     min_cap_angle=cap, land_depth=land, per_contact=True))


def module_cap_angle(a: float, ball_radius: float) -> float | None:
    """The ball caps (the mortar zones) a module needs for the largest Hertz semi-major axis ``a`` [m] of its
    contacts: the ellipse's half-angle seen from the ball centre, ``asin(a / R_B)``, with the zone ``CAP_MARGIN a``
    (docs/truncation.md); None where the builders' default cap of 30 deg holds it already (every scene whose
    ellipse fits keeps its mesh)."""
    need = math.asin(min(1.0, CAP_MARGIN * a / ball_radius))
    return need if need > DEFAULT_CAP_ANGLE else None


def module_land_depth(found, ball_radius: float, conformity: float) -> float | None:
    """The land depth (units of ``R_B``) a module's grooves need so that every flank runs past its contact's zone,
    the ellipse out to ``CAP_MARGIN a`` (:func:`lowmodel.truncation.land_depth` at ``beta + asin(CAP_MARGIN a /
    R_B)``), for the contacts' truncation checks ``found`` (ladder.common.truncations); None where the shoulder
    convention's 0.25 leaves that room already (every scene whose ellipses fit keeps its mesh).  A flank past
    the convention's shoulder changes no contact whose ellipse ends before that shoulder (a truncated one does
    not reach the FE: ladder.common.not_truncated); docs/truncation.md."""
    need = min((truncation.land_depth(ball_radius, conformity, t.rigid_angle,
                                      min(math.pi / 2, t.contact_angle + math.asin(min(1.0, CAP_MARGIN * t.a
                                                                                     / ball_radius))))
                for t in found), default=truncation.SHOULDER_DEPTH)
    return max(0.0, need) if need < truncation.SHOULDER_DEPTH else None


# --------------------------------------------------------------------------
# Hertz and BEM of a contact
# --------------------------------------------------------------------------
def hertz_values(case: ContactCase) -> dict:
    """Exact Hertz of ``case``: a, b [m], p0 [Pa], delta [m]."""
    from ballbench.validation.studies import fe_contact

    contact = hertz.solve_load(fe_contact.hertz_geometry(case), case.force)
    return {q: float(getattr(contact, q)) for q, _ in QUANTITIES}


def bem_values(case: ContactCase, n: int) -> dict:
    """Half-space contact (BEM) of ``case`` on the exact gap of its bodies, ``n x n`` cells over 1.3 times the
    Hertz semi-axes: a, b [m] (the Hertz field of the same pressure moments), p0 [Pa] (central pressure), delta [m]."""
    from ballbench.lowmodel.contact import halfspace, screw_contact
    from ballbench.validation.studies import fe_contact

    material = case.material.keywords
    if case.pair in ("screw", "nut"):
        radius, conformity, pitch_radius, lead, nominal_angle, pair = hertz.helical_pair(case)
        result = screw_contact.groove_contact(radius, conformity, pitch_radius, lead, nominal_angle, case.force, pair,
                                              n=n, **material).bem
    else:
        geometry = fe_contact.hertz_geometry(case)
        contact = hertz.solve_load(geometry, case.force)
        grid = halfspace.hertz_surface_grid(float(contact.a), float(contact.b), n, 1.3)
        x, y = grid.coordinates()
        gap = groove.straight_pair_initial_gap(case.ball_radius, case.pair, case.conformity)(x, y)
        result = halfspace.solve(gap - gap.min(), grid, geometry.contact_modulus, force=case.force)
    return {"a": result.semi_axis_a, "b": result.semi_axis_b, "p0": result.central_pressure,
            "delta": result.approach}


def timed(function, *args, **kwargs):
    """``(function(*args, **kwargs), wall time [s])``."""
    start = time.perf_counter()
    value = function(*args, **kwargs)
    return value, time.perf_counter() - start


def relative(value: float, reference: float) -> float:
    return value / reference - 1.0 if reference else math.inf


def finite(values) -> bool:
    return bool(np.all(np.isfinite(np.asarray(list(values), dtype=float))))
