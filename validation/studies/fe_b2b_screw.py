"""FE screw modules and the FE-informed B2B force of a two-ball ball-screw case (a :class:`BallScrewCase`,
lin2019 Sec 3.3).

One FE screw module per ball (``fem.screw_module``: the ball between a clamped screw segment and a nut segment
carrying the ball's axial share, P2 elasticity, frictionless mortar contact on the exact sphere and helical
flanks, the screw's oversize as an interference fit, loaded contact angles by the geometric update); its contact
tractions feed ``lowmodel.screw.b2b_traction`` (FE-informed B2B).  The ball's axial share: the low-order
touching state's force of the screw contacts on that ball along the screw axis (normal + friction; the shares
add up to the case's axial load).
"""
from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path

import numpy as np

from ballbench.lowmodel.bearing_results import axial_shares, screw_states
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_traction as sbt
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases.case import BallScrewCase
from ballbench.validation.figures import render3d
from ballbench.validation.figures.fe_module import contact_summary, cut_figure, patch_figure
from ballbench.validation.figures.style import save
from ballbench.validation.references.screw_statics import hertz_statics
from ballbench.validation.scene import KnownGap
from ballbench.validation.studies import screw_two_ball
from ballbench.validation.studies.fe_b2b_linear import full_stress
from ballbench.validation.studies.fe_contact import mesh_dofs

# (Table 5 case, h_contact [m]) where the FE-informed F_B2B misses ANSYS's value by more than 10 % (measured)
ANSYS_GAP_LEVELS = {("b", 4.0e-5)}
ANSYS_GAP = KnownGap(
    reason="Case (b) at the 40 um level: F_B2B 2.9815 N, +10.02 % of ANSYS's 2.71 N (the target 10 % is 2.981 N).  "
           "The 40 um level's discretisation error: the same module at the default 30 um gives 2.957 N (+9.1 %), "
           "i.e. the 40 um level lies 0.8 % above it (case a: 1.956 / 1.962 N at 40 / 30 um, -0.3 %; with the "
           "shallow segments 2.003 / 2.001 / 1.986 N at 40 / 30 / 22 um).  The preload is fitted on the paper's "
           "low-order value of case (a), not on ANSYS, and is not refitted here.",
    evidence="levels.csv of `ballbench validate fe-b2b-screw-b --quick` and of the default level (F_B2B per mesh "
             "level); docs/fe_b2b.md (screw half, depth table and results).")

__all__ = ["ANSYS_GAP", "ANSYS_GAP_LEVELS", "low_order", "hertz_ellipse", "module_axes", "solve_fe_level",
           "level_dofs", "fe_informed", "sensitivity", "patch_axes", "show_module"]


def low_order(case: BallScrewCase, oversize: float | None = None):
    """(contacts, free state, touching state) of the low-order model of ``case`` at the preload ``oversize`` [m]
    (default: the screw's)."""
    contacts = screw_b2b.contacts(case, oversize=oversize)
    free, state = screw_states(case, contacts)
    return contacts, free, state


def hertz_ellipse(contacts, ball: int, forces) -> np.ndarray:
    """(4, 3) Hertz (a [m], b [m], p0 [Pa]) of the low-order model's contacts of ``ball`` at the forces (4,) [N]."""
    forces = np.asarray(forces, dtype=float)
    a = contacts.semi_major_unit[ball] * np.cbrt(forces)
    b = contacts.b_over_a[ball] * a
    return np.column_stack([a, b, 1.5 * forces / (math.pi * a * b)])


def module_axes(case: BallScrewCase) -> np.ndarray:
    """(n_balls, 4, 2) Hertz semi-axes (a, b) [m] of the low-order touching state's contacts (SL, SR, NR, NL) of each
    ball (:func:`hertz_ellipse` at its normal forces): what a module's fine slabs are sized from."""
    contacts, _, state = low_order(case)
    forces = np.asarray(state.normal_force, dtype=float)
    return np.stack([hertz_ellipse(contacts, ball, forces[ball])[:, :2] for ball in range(len(forces))])


def _fine_zones(case: BallScrewCase, axes, ball: int) -> dict:
    """The ``fine_ellipses`` and ``size_factors`` of ball ``ball``'s module mesh (``axes`` of :func:`module_axes`):
    the case's ``fine_ellipse`` factors times each contact's (a, b, b), and with ``fe.per_contact`` each contact at
    its ``b`` over the largest ``b`` of the module's balls; none without ``fine_ellipse`` (the level's ball zone)."""
    if case.fe.fine_ellipse is None:
        return {}
    k1, k2, k3 = case.fe.fine_ellipse
    zones = {"fine_ellipses": [(k1 * a, k2 * b, k3 * b) for a, b in axes[ball]]}
    if case.fe.per_contact:
        zones["size_factors"] = [float(b / axes[:, :, 1].max()) for b in axes[ball, :, 1]]
    return zones


def _module_mesh(case: BallScrewCase, level, ball: int, axes):
    """The cached gmsh mesh of the module of ball ``ball`` (its deviation theta) at the ModuleLevel ``level``
    (``axes``: :func:`module_axes`, used where the case has fine slabs)."""
    from ballbench.meshes.assemblies.ball_screw_module import ball_screw_module

    screw, fe = case.screw, case.fe
    theta = case.deviations[ball]
    depth = {} if fe.body_depth is None else {
        "screw_back_radius": screw.pitch_radius - fe.body_depth * screw.ball_radius,
        "nut_back_radius": screw.pitch_radius + fe.body_depth * screw.ball_radius}
    if fe.land_depth is not None:
        depth.update(screw_land_radius=screw.pitch_radius - fe.land_depth * screw.ball_radius,
                     nut_land_radius=screw.pitch_radius + fe.land_depth * screw.ball_radius)
    return ball_screw_module(screw.ball_radius, screw.conformity, screw.pitch_radius, screw.lead,
                             screw.nominal_angle, (theta, theta, 0.0, 0.0), 1, h_contact=level.h_contact,
                             growth=level.growth, fine_radius=level.fine_radius, h_max=level.h_max,
                             min_cap_angle=fe.min_cap_angle, **depth, **_fine_zones(case, axes, ball))


def level_dofs(case: BallScrewCase, level) -> int:
    """The P2 DOFs of the modules of all balls of ``case`` at ``level`` (:func:`solve_fe_level` keeps them all),
    from their meshes alone (meshed or cached; no assembly): what the level's memory is predicted from."""
    axes = module_axes(case) if case.fe.fine_ellipse is not None else None
    return sum(mesh_dofs(_module_mesh(case, level, ball, axes)) for ball in range(len(case.deviations)))


def solve_fe_level(case: BallScrewCase, level, shares, oversize: float | None = None):
    """Mesh, condense and solve one module per ball at the :class:`ModuleLevel` ``level``, ball ``j`` carrying
    the axial share ``shares[j]`` [N]; returns (models, results, timings [s])."""
    from ballbench.fem import screw_module as sm

    screw, fe = case.screw, case.fe
    oversize = screw.oversize if oversize is None else oversize
    timings = {"mesh_s": 0.0, "assembly_s": 0.0, "condense_s": 0.0, "contact_solve_s": 0.0}
    models, results = [], []
    axes = module_axes(case) if fe.fine_ellipse is not None else None
    for ball, theta in enumerate(case.deviations):
        start = time.perf_counter()
        path = _module_mesh(case, level, ball, axes)
        timings["mesh_s"] += time.perf_counter() - start
        geometry = sm.screw_module_geometry(screw.ball_radius, screw.conformity, screw.pitch_radius, screw.lead,
                                            sm.flank_angles_tilted(screw.nominal_angle, theta), oversize)
        model = sm.build_screw_model(path, geometry, materials=screw.material.pair, gap_limit=fe.gap_limit)
        timings["assembly_s"] += model.timings["assembly_s"]
        timings["condense_s"] += model.timings["condense_s"]
        start = time.perf_counter()
        results.append(sm.solve(model, float(shares[ball])))
        timings["contact_solve_s"] += time.perf_counter() - start
        models.append(model)
    return models, results, timings


def fe_informed(case: BallScrewCase, models, results, *, normal: str = "mid", free_balls=None):
    """FE-informed two-ball result (``screw.b2b_traction.module_b2b``) of the solved modules."""
    from ballbench.fem import fourpoint as fp
    patches = [fp.traction_patches(model, result, normal=normal) for model, result in zip(models, results)]
    return sbt.module_b2b(patches, screw_contacts.module(case.screw), **(
        {} if free_balls is None else {"free_balls": free_balls}))


def sensitivity(case: BallScrewCase, models, results, state, contacts, *, fit_case: BallScrewCase,
                fit_force: float) -> list[tuple[str, float]]:
    """F_B2B [N] with Hertz or FE patches, rigid or loaded contact angles, the friction-plane normal, and at the
    oversize at which the low-order model of ``fit_case`` gives ``fit_force`` [N] (the unknown preload):
    ``[(variant, F_B2B), ...]``; ``state``: the low-order touching state of ``contacts``."""
    from ballbench.fem import screw_module as sm
    module = screw_contacts.module(case.screw)
    rows = [("low-order: Hertz ellipses, eqs 34-61 (screw.b2b)", float(state.b2b_force[0]))]
    hertz = [sbt.hertz_patches(state, contacts, ball) for ball in range(2)]
    rows.append(("Hertz samples on planes (screw.b2b_traction; quadrature check)",
                 float(sbt.module_b2b(hertz, module).b2b_force[0])))
    # the normal-force distribution: Hertz ellipses at other forces (frictionless ones: the decoupling)
    shares = axial_shares(contacts, state)
    statics = np.array([hertz_statics(contacts, ball, shares[ball]) for ball in range(2)])
    fe_forces = np.array([[c.normal_force for c in r.contacts] for r in results])
    fe_angles = np.array([[c.contact_angle for c in r.contacts] for r in results])
    for label, forces, angles in (
            ("Hertz ellipses at the frictionless Hertz-statics forces, rigid angles (no FE)", statics,
             contacts.contact_angles),
            ("Hertz ellipses at the FE forces, rigid angles", fe_forces, contacts.contact_angles),
            ("Hertz ellipses at the FE forces, FE loaded angles", fe_forces, fe_angles)):
        variant = dataclasses.replace(state, normal_force=forces, contact_angle=np.asarray(angles),
                                      semi_major=contacts.semi_major_unit * np.cbrt(forces))
        patches = [sbt.hertz_patches(variant, contacts, ball) for ball in range(2)]
        rows.append((label, float(sbt.module_b2b(patches, module).b2b_force[0])))
    for normal in ("mid", "sphere", "contact"):
        rows.append((f"FE tractions, loaded angles, normal '{normal}'",
                     float(fe_informed(case, models, results, normal=normal).b2b_force[0])))
    fitted = screw_two_ball.fit_oversize(fit_case, fit_force)
    contacts_fit, _, state_fit = low_order(case, fitted)
    shares_fit = axial_shares(contacts_fit, state_fit)
    lowered = [sm.solve(sm.with_oversize(model, fitted), float(shares_fit[ball]))
               for ball, model in enumerate(models)]
    rows.append((f"low-order at the oversize fitted on ANSYS's case (a) {fit_force:.2f} N ({fitted * 1e6:.4f} um)",
                 float(state_fit.b2b_force[0])))
    rows.append((f"FE-informed at that oversize ({fitted * 1e6:.4f} um)",
                 float(fe_informed(case, models, lowered).b2b_force[0])))
    rigid = [sm.solve(model, float(shares[ball]), geometric_update=False)
             for ball, model in enumerate(models)]
    rows.append(("FE tractions, rigid contact angles (no geometric update)",
                 float(fe_informed(case, models, rigid).b2b_force[0])))
    return rows


def patch_axes(contacts, results) -> list:
    """Per ball, the (4, 2) Hertz semi-axes (a, b) [m] of the low-order model's contacts at the FE forces."""
    return [hertz_ellipse(contacts, ball, [c.normal_force for c in result.contacts])[:, :2]
            for ball, result in enumerate(results)]


def show_module(case: BallScrewCase, scene_dir, fidelity: str, solve: bool = False) -> list:
    """The ``show`` hook of an FE-informed ball-screw scene, at the case's checked level for ``fidelity`` (quick
    or default): the 3D screenshots of the saved module fields; none saved: FileNotFoundError, or with ``solve``
    the modules solved again and ``pressure.png`` (the four contact patches of both balls with the
    low-order model's Hertz ellipses at the FE forces and the FE moment ellipses) and ``stress.png`` (von Mises
    stress of ball 2's module on the plane through the ball centre normal to the helix, x3-z3, which holds all
    four contacts: SL-NR and SR-NL are the two pairs of opposite contacts)."""
    if fidelity not in ("quick", "default"):
        raise ValueError(f"fidelity must be 'quick' or 'default', got {fidelity!r}")
    if render3d.has_fields(scene_dir):  # the fields saved by validate: the 3D screenshots, no solve
        return render3d.render(scene_dir)
    if not solve:
        raise FileNotFoundError(f"no saved module fields in {scene_dir} (fields.json)")
    contacts, _, state = low_order(case)
    level = case.fe.levels.checked(fidelity)
    models, results, _ = solve_fe_level(case, level, axial_shares(contacts, state))
    target = Path(scene_dir)
    target.mkdir(parents=True, exist_ok=True)
    name = target.name
    pressure = save(patch_figure(results, patch_axes(contacts, results), ylabel="e2 along the groove [mm]",
                                 xlim=0.4, ylim=0.12, heading=f"{name}, h = {level.h_contact * 1e6:.0f} um",
                                 hertz_label="Hertz ellipse at the FE force"), target / "pressure.png")
    model, result = models[1], results[1]
    geometry = model.geometry
    stress = full_stress(model, result, case.screw.material) / 1e6
    cut = cut_figure(model.pair.points, model.pair.tets, stress, normal=geometry.cs3[:, 1],
                     origin=geometry.ball_centre, view_up=geometry.cs3[:, 2], axis_names=("-x3", "z3"),
                     title=f"{name}, ball 2 (theta {math.degrees(case.deviations[1]):g} deg), cut x3-z3 through the "
                           f"ball centre and the four contacts\n{contact_summary(result)}")
    from ballbench.fem.fields import write_module_fields

    write_module_fields(target, models, results, materials=case.screw.material.pair, scene=name, fidelity=fidelity,
                        level={"h_contact_m": level.h_contact, "growth": level.growth,
                               "per_contact": case.fe.per_contact})
    return [pressure, save(cut, target / "stress.png")] + render3d.render(target)
