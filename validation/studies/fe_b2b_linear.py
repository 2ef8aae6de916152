"""FE-informed B2B force of a two-ball linear-guide module (a :class:`LinearGuideCase`, lin2019 Sec 2.4-2.5).

The FE four-point module (``fem.fourpoint``: one ball between a clamped bottom rail and a loaded top rail, P2
elasticity, mortar contact on the exact sphere and flank surfaces, loaded contact angles by the geometric update)
is solved for each ball's load (``N_x = +-rho N_y``; the balls share the geometry, hence one condensation); its
contact pressures feed ``lowmodel.linear_bearing.b2b_traction`` (pointwise full-slip Coulomb friction, eqs 4-10).
Mesh levels (the case's :class:`ModuleFe`): ``h_contact`` in the elliptic slab about each of the four contacts,
``growth`` beyond it.
"""
from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b, b2b_traction
from ballbench.lowmodel.linear_bearing import fourpoint as rigid
from ballbench.validation.cases.case import LinearGuideCase
from ballbench.validation.figures import render3d
from ballbench.validation.figures.fe_module import contact_summary, cut_figure, patch_figure
from ballbench.validation.figures.style import save
from ballbench.validation.studies.fe_contact import mesh_dofs

__all__ = ["low_order_contacts", "fine_ellipses", "eq36_hertz", "solve_fe_level", "level_dofs",
           "traction_patches", "fe_informed", "full_stress", "hertz_axes", "sensitivity", "show_module"]


def low_order_contacts(case: LinearGuideCase):
    """The low-order model's contacts (``lowmodel.linear_bearing.b2b.contacts``) of the two balls of ``case``'s FE
    module (two balls, whatever the case's ``n_balls``)."""
    return b2b.contacts(replace(case, n_balls=2))


def eq36_hertz(case: LinearGuideCase, ball: int, angles=None):
    """Hertz contacts (lowmodel.contact.hertz.HertzContact, arrays over BL, BR, TR, TL) of ball ``ball`` at the
    lin2017 eq 36 forces for the contact angles ``angles`` [rad] (default: the case's rigid angles), and the
    forces [N]."""
    angles = case.contact_angles if angles is None else np.asarray(angles)
    forces = rigid.normal_forces(case.side_force(ball), case.vertical_force, angles)
    return hertz.solve_load(hertz.groove_geometry(case.guide), forces), forces


def fine_ellipses(case: LinearGuideCase) -> list:
    """The fine slabs (l_1, l_2, l_3) [m] of the four contacts (BL, BR, TR, TL): the case's ``fine_ellipse``
    factors times the Hertz semi-axes (a, b, b) at the eq 36 forces of the rigid angles, the larger of the two
    balls."""
    refs = [eq36_hertz(case, ball)[0] for ball in (0, 1)]
    a = np.maximum(np.asarray(refs[0].a), np.asarray(refs[1].a))
    b = np.maximum(np.asarray(refs[0].b), np.asarray(refs[1].b))
    k1, k2, k3 = case.fe.fine_ellipse
    return [(k1 * float(a_i), k2 * float(b_i), k3 * float(b_i)) for a_i, b_i in zip(a, b)]


def _module_mesh(case: LinearGuideCase, level):
    """The cached gmsh mesh of the guide's module at the ModuleLevel ``level``."""
    from ballbench.meshes.assemblies.fourpoint_module import fourpoint_module

    guide = case.guide
    return fourpoint_module(guide.ball_radius, guide.conformity, guide.nominal_angle, case.deviations, 1,
                            h_contact=level.h_contact, growth=level.growth, fine_radius=level.fine_radius,
                            h_max=level.h_max, fine_ellipses=fine_ellipses(case) if case.fe.fine_ellipse else None,
                            min_cap_angle=case.fe.min_cap_angle,
                            land_height=None if case.fe.land_depth is None else -case.fe.land_depth * guide.ball_radius)


def level_dofs(case: LinearGuideCase, level) -> int:
    """The P2 DOFs of the guide's module at ``level`` from its mesh alone (meshed or cached; no assembly): what the
    level's memory is predicted from."""
    return mesh_dofs(_module_mesh(case, level))


def solve_fe_level(case: LinearGuideCase, level):
    """Mesh, condense and solve the module for both balls' loads at the :class:`ModuleLevel` ``level``;
    returns (model, results, timings [s])."""
    from ballbench.fem import fourpoint as fp

    guide = case.guide
    timings = {}
    start = time.perf_counter()
    path = _module_mesh(case, level)
    timings["mesh_s"] = time.perf_counter() - start
    geometry = fp.ModuleGeometry(guide.ball_radius, guide.conformity, tuple(case.contact_angles))
    model = fp.build_module_model(path, geometry, materials=guide.material.pair, gap_limit=case.fe.gap_limit)
    timings.update(model.timings)
    start = time.perf_counter()
    # ball 1 (behind) carries N_x = rho N_y, ball 2 -rho N_y (lin2019 Fig 7; b2b.module_contacts)
    results = [fp.solve(model, case.side_force(ball), case.vertical_force) for ball in (0, 1)]
    timings["contact_solve_s"] = time.perf_counter() - start
    return model, results, timings


def traction_patches(model, results, normal: str = "mid"):
    """The FE contact tractions of each solved ball (fem.fourpoint.traction_patches) with the friction plane's
    ``normal`` (``"mid"``, ``"sphere"`` or ``"contact"``)."""
    from ballbench.fem import fourpoint as fp

    return [fp.traction_patches(model, r, normal=normal) for r in results]


def fe_informed(case: LinearGuideCase, model, results, *, normal: str = "mid", gaps=None):
    """FE-informed two-ball state (b2b_traction) from the module's solved contacts (``gaps`` [m]: the balls'
    initial gaps, None: touching)."""
    return b2b_traction.solve(traction_patches(model, results, normal), case.guide,
                              **({} if gaps is None else {"gaps": gaps}))


def full_stress(model, result, material):
    """Von Mises stress [Pa] per element of a solved module (fem.fourpoint.von_mises of the full displacement)."""
    from ballbench.fem import fourpoint as fp

    return fp.von_mises(model, fp.full_displacement(model, result), material.pair)


def hertz_axes(case: LinearGuideCase, model) -> list:
    """Per ball, the (4, 2) Hertz semi-axes (a, b) [m] at the eq 36 forces of the module's rigid contact angles."""
    refs = [eq36_hertz(case, ball, model.geometry.contact_angles)[0] for ball in (0, 1)]
    return [np.column_stack([ref.a, ref.b]) for ref in refs]


def sensitivity(case: LinearGuideCase, model, results, low, contacts) -> list[tuple[str, float]]:
    """How F_B2B [N] moves with the contact normal of the FE tractions, with the contact angle taken rigid
    (no geometric update) or under load, and with Hertz or FE ellipses: ``[(variant, F_B2B), ...]``; ``low``:
    the low-order touching state of ``contacts``."""
    from ballbench.fem import fourpoint as fp

    rows = [("low-order: Hertz ellipses on planes, rigid angles, eq 36 (lin2019)", float(low.b2b_force[0]))]
    hertz_planar = [b2b_traction.hertz_patches(contacts, j) for j in range(2)]
    hertz_curved = [b2b_traction.hertz_patches(contacts, j, planar=False) for j in range(2)]
    for label, patches in (("Hertz samples on planes (b2b_traction; quadrature check)", hertz_planar),
                           ("Hertz samples on the sphere (curved contact)", hertz_curved)):
        state = b2b_traction.solve(patches, case.guide)
        rows.append((label, float(state.b2b_force[0])))
    loaded = np.array([[c.contact_angle for c in r.contacts] for r in results])
    loaded_contacts = replace(contacts, contact_angles=loaded)
    rows.append(("low-order with the FE loaded contact angles (Hertz ellipses)",
                 float(b2b.solve(loaded_contacts, [0.0]).b2b_force[0])))
    for normal in ("mid", "sphere", "contact"):
        rows.append((f"FE tractions, loaded angles, normal '{normal}'",
                     float(fe_informed(case, model, results, normal=normal).b2b_force[0])))
    rigid_results = [fp.solve(model, case.side_force(ball), case.vertical_force, geometric_update=False)
                     for ball in (0, 1)]
    rows.append(("FE tractions, rigid contact angles (no geometric update)",
                 float(fe_informed(case, model, rigid_results).b2b_force[0])))
    return rows


def show_module(case: LinearGuideCase, scene_dir, fidelity: str, solve: bool = False) -> list:
    """The ``show`` hook of an FE-informed linear-guide scene, at the case's checked level for ``fidelity``
    (quick or default): the 3D screenshots of the saved module fields; none saved: FileNotFoundError, or with
    ``solve`` the module solved again and ``pressure.png`` (the four contact patches of both balls with
    the Hertz ellipses of the low-order model and the FE moment ellipses) and ``stress.png`` (von Mises stress of
    ball 1's module on the cross-section z = 0, which holds all four contacts: BL-TR and BR-TL are the two pairs
    of opposite contacts)."""
    if fidelity not in ("quick", "default"):
        raise ValueError(f"fidelity must be 'quick' or 'default', got {fidelity!r}")
    if render3d.has_fields(scene_dir):  # the fields saved by validate: the 3D screenshots, no solve
        return render3d.render(scene_dir)
    if not solve:
        raise FileNotFoundError(f"no saved module fields in {scene_dir} (fields.json)")
    level = case.fe.levels.checked(fidelity)
    model, results, _ = solve_fe_level(case, level)
    target = Path(scene_dir)
    target.mkdir(parents=True, exist_ok=True)
    name = target.name
    pressure = save(patch_figure(results, hertz_axes(case, model), ylabel="z [mm]",
                                 heading=f"{name}, h = {level.h_contact * 1e6:.0f} um",
                                 hertz_label="Hertz ellipse (eq 36 force)"), target / "pressure.png")
    result = results[0]
    stress = full_stress(model, result, case.guide.material) / 1e6
    cut = cut_figure(model.pair.points, model.pair.tets, stress, normal=(0, 0, 1), origin=(0, 0, 0),
                     title=f"{name}, ball 1 (N_x = {case.side_force(0):.0f} N, N_y = {case.vertical_force:.0f} N), "
                           f"cut z = 0 through the four contacts\n{contact_summary(result)}")
    from ballbench.fem.fields import write_module_fields

    write_module_fields(target, model, results, materials=case.guide.material.pair, scene=name, fidelity=fidelity,
                        level={"h_contact_m": level.h_contact, "growth": level.growth})
    return [pressure, save(cut, target / "stress.png")] + render3d.render(target)
