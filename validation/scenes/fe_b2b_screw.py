"""FE validation of the ball-to-ball (B2B) force on lin2019's two-ball ball-screw module (issue 12, screw half).

lin2019 Sec 3.3, Table 4 geometry, Table 5: ball 1 theta = 0, ball 2 theta = 2 deg (case a) or 3 deg (case b),
50 N on the screw, the balls touching; ANSYS 1.80 / 2.71 N, the paper's low-order 1.92 / 2.89 N.  Readings of the
ball-screw issue (docs/ball_screw.md): Fig 17 = both screw flanks at 45 deg + theta ("tilted"); preload = ball
oversize 1.6848 um fitted on case (a)'s low-order force alone.

Models:

* ``lowmodel.screw.b2b`` (low-order, Hertz ellipses, eqs 34-61) against Table 5;
* the FE screw module at each mesh level (``fem.screw_module``: one ball between a clamped screw segment and a
  nut segment carrying the ball's axial share, P2 elasticity, frictionless mortar contact on the exact sphere and
  helical flanks, the oversize as an interference fit, loaded contact angles by the geometric update), one module
  per ball (ball 1 and ball 2 differ in theta): per-contact forces against a frictionless Hertz statics reference
  (:func:`hertz_statics`) and against the low-order model, ellipses against the low-order model's Hertz ellipses at
  the FE's force;
* FE-informed B2B (``lowmodel.screw.b2b_traction``) at each mesh level, when that model is present.

The ball's axial share: the low-order touching state's force of the screw contacts on that ball along the screw
axis (normal + friction; the two shares add up to the 50 N).
"""
from __future__ import annotations

import csv
import dataclasses
import math
import time

import numpy as np

from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.meshes.parts.groove_segment import BODY_DEPTH  # R_B from the pitch radius (the builder's default)
from ballbench.validation.figures import render3d
from ballbench.validation.papers import lin2019
from ballbench.validation.scene import KnownGap, scene
from ballbench.validation.scenes import lin2019_screw

T4 = lin2019.TABLE4
AXIAL_LOAD = lin2019.WHOLE_SCREW.axial_load_two_ball  # N on the screw (lin2019 Sec 3.3)
PRINTED = {"a": lin2019.TABLE5_A, "b": lin2019.TABLE5_B}
E_STEEL, NU_STEEL = T4.youngs_modulus, T4.poisson_ratio
GAP_LIMIT = 5e-6  # m, candidate zone (on the gap with the oversize subtracted): approaches 0.5-0.7 um + 1.7 um preload
# (h_contact [m], growth, fine_radius [m]) about the four contact points.  The semi-axes are a = 185-290 um and
# b = 40-70 um (b/a = 0.21-0.25): the fine zone resolves b, the ends of a lie in the growth zone (as fe_b2b.py).
# Measured (case a, FE-informed F_B2B, the builder's shallow segments): 50 um 1.970 N, 40 um 2.003 N, 30 um
# 2.001 N; the 50 um level also misses b by 19 % and p0 by 21 %, so the quick level is 40 um (within 0.1 % of the
# default's F_B2B).
# h_max [m]: the element size far from the contacts in the deep bodies (BODY_DEPTH), ANSYS's 1 mm (lin2019 Sec 3.3).
# Measured (case a, 40 um): F_B2B 1.975 / 1.956 / 1.955 N at h_max 1.4 / 1.0 / 0.93 mm (220k / 302k / 335k DOFs);
# case b 2.9945 / 2.9815 N at 1.4 / 1.0 mm (docs/fe_b2b.md).
LEVELS = {
    "quick": [(4.0e-5, 1.5, 1.5e-4, 1.0e-3)],
    "default": [(3.0e-5, 1.4, 1.5e-4, 1.0e-3)],
    "fine": [(4.0e-5, 1.5, 1.5e-4, 1.0e-3), (3.0e-5, 1.4, 1.5e-4, 1.0e-3), (2.2e-5, 1.35, 1.5e-4, 1.0e-3)],
}
# The bodies (issue 12, docs/fe_b2b.md "Depth of the FE bodies"): screw core and nut outside at R_P -+ BODY_DEPTH R_B,
# i.e. 5 R_B below the lands (the former default 2 R_B clamps the segments 1.75 R_B below them: too stiff, the FE
# forces 2-5.5 % above the Hertz statics).  Table 4 gives neither radius; lin2019 Sec 3.3 meshed the CAD screw shaft
# and nut (Fig 18).  R_P - 5.25 R_B = 1.92 mm: the screw segment reaches to near the shaft's axis (a solid shaft);
# R_P + 5.25 R_B = 31.1 mm: a nut body of 62 mm outer diameter.  Measured (case a, 40 um): depth 2 / 3.25 / 5.25 R_B
# -> worst force vs Hertz statics +5.5 / +2.6 / -1.1 %, F_B2B 2.003 / 1.985 / 1.955 N.
TIME_LIMIT_S = {"quick": 90.0, "default": 300.0}  # issue 12: per scene at its level
SCENE_BUDGET_S = {"quick": TIME_LIMIT_S["quick"], "default": TIME_LIMIT_S["default"],
                  "fine": 5.0 * TIME_LIMIT_S["default"]}
# rough wall time at the default level on 2 cores [s] (two modules of 232k DOFs, meshes cached, with the
# sensitivity study): measured 104-200 s per case on the shared machine, docs/fe_b2b.md
SCENE_COST_S = 180.0
MODEL_LOW = "lowmodel.screw.b2b"
FRICTIONLESS_GAP = KnownGap(
    reason="The FE module is frictionless (the issue's decoupling: normal tractions from the FE, friction in the "
           "B2B model), while the low-order model's contact forces come from the ball's equilibrium with friction "
           "(mu = 0.1, eq 54): friction moves load between the diagonals SL-NR and SR-NL by up to 4 N of 14-21 N.",
    evidence="this scene: the FE forces against the frictionless Hertz statics of the same geometry, preload and "
             "axial share (hertz_statics, checked at 2 %); contacts.csv (F_FE, F_hertz_statics, F_low_order).")

# (case, h_contact [m]) where the FE-informed F_B2B misses ANSYS's value by more than 10 % (measured)
ANSYS_GAP_LEVELS = {("b", 4.0e-5)}
ANSYS_GAP = KnownGap(
    reason="Case (b) at the 40 um level: F_B2B 2.9815 N, +10.02 % of ANSYS's 2.71 N (the target 10 % is 2.981 N).  "
           "The 40 um level's discretisation error: the same module at the default 30 um gives 2.957 N (+9.1 %), "
           "i.e. the 40 um level lies 0.8 % above it (case a: 1.956 / 1.962 N at 40 / 30 um, -0.3 %; with the "
           "shallow segments 2.003 / 2.001 / 1.986 N at 40 / 30 / 22 um).  The preload is fitted on the paper's "
           "low-order value of case (a), not on ANSYS, and is not refitted here.",
    evidence="levels.csv of `ballbench validate fe-b2b-screw-b --quick` and of the default level (F_B2B per mesh "
             "level); docs/fe_b2b.md (screw half, depth table and results).")

# the FE's rigid equations hold to the QP's tolerance (solve tol 1e-9); measured below 1e-14 (case a, 40 um)
STATICS_TOL = 1e-9

# (case, quantity, h_contact [m]) where a fitted quantity misses Hertz by more than 5 % (measured, worst of 8
# contacts, moment ellipse of fem.postprocess, bodies of BODY_DEPTH; docs/fe_b2b.md)
ELLIPSE_GAP_LEVELS = {("b", "b", 4.0e-5)}
ELLIPSE_GAP = KnownGap(
    reason="The ellipses are slender (b/a = 0.21-0.25, b = 40-69 um along the groove): at the quick level's h = 40 um "
           "the fine zone puts 1-1.7 elements across b: b of case (b) 5.58 % at 40 um (merged deep bodies and moment "
           "ellipse, 2026-11-23); case (a) passes at 40 um.",
    evidence="contacts.csv of `ballbench validate fe-b2b-screw-a --quick`, `fe-b2b-screw-b --quick` and of the "
             "default levels; docs/fe_b2b.md (screw half).")


def fe_model_name(h_contact: float) -> str:
    return f"FE screw module (h {h_contact * 1e6:.0f} um)"


def fe_informed_name(h_contact: float) -> str:
    return f"FE-informed screw.b2b_traction (h {h_contact * 1e6:.0f} um)"


def oversize() -> float:
    """The preload of docs/ball_screw.md: ball oversize [m] fitted on Table 5 case (a) (lin2019_screw)."""
    return lin2019_screw.fitted_oversize()


def low_order(case: str, preload: float | None = None):
    """(contacts, free state, touching state) of the low-order model for Table 5 case ``case`` at the oversize
    ``preload`` [m] (default :func:`oversize`)."""
    preload = oversize() if preload is None else preload
    contacts = screw_contacts.ball_contacts(lin2019_screw.table4_module(preload),
                                        np.array([0.0, PRINTED[case].theta]), reading=lin2019_screw.READING)
    free, state = lin2019_screw.two_ball(case, preload)
    return contacts, free, state


def ansys_fitted_oversize() -> float:
    """Oversize [m] at which the low-order model gives ANSYS's case (a) force 1.80 N (brentq; sensitivity only:
    the scene's preload is the reading of docs/ball_screw.md, fitted on the paper's low-order 1.92 N)."""
    from scipy.optimize import brentq

    target = PRINTED["a"].f_b2b_ansys
    return float(brentq(lambda o: lin2019_screw.two_ball("a", o)[1].b2b_force[0] - target, 1.0e-6, 3.0e-6,
                        xtol=1e-12))


def axial_shares(contacts, state) -> np.ndarray:
    """(n,) N: each ball's axial load, the force of its screw contacts (SL, SR: normal + friction) along z_hat."""
    alpha = contacts.module.lead_angle
    z_hat = np.array([0.0, math.sin(alpha), math.cos(alpha)])
    angles = state.contact_angle
    sign_u, sign_w = np.array([-1.0, -1.0]), np.array([-1.0, 1.0])
    e = np.stack([sign_u * np.cos(angles[:, :2]), np.zeros_like(angles[:, :2]), sign_w * np.sin(angles[:, :2])],
                 axis=-1)  # (n, 2, 3) CS3, ball centre -> contact (eq 37)
    normal = -state.normal_force[:, :2, None] * e
    return ((normal + state.friction_force[:, :2]) @ z_hat).sum(axis=1)


def hertz_statics(contacts, ball: int, axial_load: float) -> np.ndarray:
    """Frictionless reference forces (SL, SR, NR, NL) [N] of one ball: rigid grooves with Hertz contacts.

    Unknowns: ball centre ``(x3, z3)`` and nut shift ``u``; ``F_i = (delta_i / C_i)^(3/2)`` with
    ``delta_i = |p_B - C_i| + R_B + oversize - r_g`` (lin2019 eq 53, nut arc centres shifted by ``(0, u cos alpha)``,
    eq 48) and the ball's equilibrium without friction in x3 and z3 plus the screw's axial push ``axial_load`` [N].
    The same geometry and Hertz constants as the low-order model, none of its friction: the FE's reference."""
    from scipy.optimize import fsolve

    module = contacts.module
    centres = contacts.arc_centres[ball]
    constant = contacts.hertz_constant[ball]
    cos_a = math.cos(module.lead_angle)
    r_g, radius = module.groove_radius, module.ball_radius

    def forces(z):
        p, u = z[:2] * 1e-6, z[2] * 1e-6
        c = centres.copy()
        c[2:, 1] += u * cos_a
        d = p - c
        dist = np.linalg.norm(d, axis=1)
        delta = np.maximum(dist + radius + module.oversize - r_g, 0.0)
        return (delta / constant) ** 1.5, d / dist[:, None]

    def residual(z):
        f, e = forces(z)
        on_ball = -(f[:, None] * e)
        return [on_ball[:, 0].sum(), on_ball[:, 1].sum(), on_ball[:2, 1].sum() * cos_a - axial_load]

    z, info, _, message = fsolve(residual, np.zeros(3), full_output=True, xtol=1e-13)
    # judged by the residual, not by fsolve's flag: with xtol 1e-13 MINPACK may stop with "not making good
    # progress" at a residual of 4e-12 N (case b, ball 1), a converged point
    if max(abs(r) for r in residual(z)) > 1e-8 * axial_load:
        from ballbench.lowmodel.errors import ConvergenceError

        raise ConvergenceError(f"hertz_statics: {message}", residual=float(np.max(np.abs(residual(z)))),
                               iterations=int(info["nfev"]), tolerance=1e-8 * axial_load)
    return forces(z)[0]


def statics_residual(contacts, ball: int, forces, axial_load: float) -> np.ndarray:
    """(3,) N: residuals of one ball's frictionless statics with the contact forces ``forces`` (SL, SR, NR, NL) [N]
    acting along the rigid flank normals of the low-order model (lin2019 eq 37, ``contacts.contact_angles``):
    ball equilibrium along x3 and z3, and the screw's axial push on the ball (screw contacts, along the screw axis
    ``z_hat = (0, sin alpha, cos alpha)`` in CS3) minus the ball's axial share ``axial_load`` [N].

    The FE module's three rigid equations (``fem.screw_module``) in independent form: computed from the low-order
    model's angles and the scene's share, not from the FE geometry.  Zero to the solver tolerance for a right
    module; a load on the wrong sign or ball, a flank at the wrong angle or a swapped screw/nut contact is not."""
    forces = np.asarray(forces, dtype=float)
    angles = contacts.contact_angles[ball]
    sign_u, sign_w = np.array([-1.0, -1.0, 1.0, 1.0]), np.array([-1.0, 1.0, 1.0, -1.0])
    on_ball = -forces[:, None] * np.column_stack([sign_u * np.cos(angles), sign_w * np.sin(angles)])  # (x3, z3)
    cos_a = math.cos(contacts.module.lead_angle)
    return np.array([on_ball[:, 0].sum(), on_ball[:, 1].sum(), on_ball[:2, 1].sum() * cos_a - axial_load])


def half_turn_asymmetry(forces) -> float:
    """Relative asymmetry ``max(|F_SL - F_NR|, |F_SR - F_NL|) / max F`` of a ball's forces (SL, SR, NR, NL) [N].
    With all four flanks at one angle (theta = 0) and no friction the module is symmetric under the half turn
    about y3 that maps screw onto nut (SL <-> NR, SR <-> NL); its statics alone (x3 and z3 balance) force the
    equality, whatever the bodies' stiffness."""
    forces = np.asarray(forces, dtype=float)
    return float(max(abs(forces[0] - forces[2]), abs(forces[1] - forces[3])) / forces.max())


def hertz_ellipse(contacts, ball: int, forces) -> np.ndarray:
    """(4, 3) Hertz (a [m], b [m], p0 [Pa]) of the low-order model's contacts of ``ball`` at the forces (4,) [N]."""
    forces = np.asarray(forces, dtype=float)
    a = contacts.semi_major_unit[ball] * np.cbrt(forces)
    b = contacts.b_over_a[ball] * a
    return np.column_stack([a, b, 1.5 * forces / (math.pi * a * b)])


def solve_fe_level(case: str, h_contact: float, growth: float, fine_radius: float, h_max: float, shares):
    """Mesh, condense and solve one module per ball; returns (models, results, timings)."""
    from ballbench.fem import screw_module as sm
    from ballbench.meshes.assemblies.ball_screw_module import ball_screw_module

    timings = {"mesh_s": 0.0, "assembly_s": 0.0, "condense_s": 0.0, "contact_solve_s": 0.0}
    models, results = [], []
    for ball, theta in enumerate((0.0, PRINTED[case].theta)):
        start = time.perf_counter()
        path = ball_screw_module(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead, T4.nominal_angle,
                                 (theta, theta, 0.0, 0.0), 1, h_contact=h_contact, growth=growth,
                                 fine_radius=fine_radius, h_max=h_max,
                                 screw_back_radius=T4.pitch_radius - BODY_DEPTH * T4.ball_radius,
                                 nut_back_radius=T4.pitch_radius + BODY_DEPTH * T4.ball_radius)
        timings["mesh_s"] += time.perf_counter() - start
        geometry = sm.screw_module_geometry(T4.ball_radius, T4.conformity, T4.pitch_radius, T4.lead,
                                            sm.flank_angles_tilted(T4.nominal_angle, theta), oversize())
        model = sm.build_screw_model(path, geometry, materials=(E_STEEL, NU_STEEL), gap_limit=GAP_LIMIT)
        timings["assembly_s"] += model.timings["assembly_s"]
        timings["condense_s"] += model.timings["condense_s"]
        start = time.perf_counter()
        results.append(sm.solve(model, float(shares[ball])))
        timings["contact_solve_s"] += time.perf_counter() - start
        models.append(model)
    return models, results, timings


def fe_informed(models, results, *, normal: str = "mid", free_balls=None):
    """FE-informed two-ball result (``screw.b2b_traction.module_b2b``) of the solved modules."""
    from ballbench.fem import fourpoint as fp
    from ballbench.lowmodel.screw import b2b_traction as sbt

    patches = [fp.traction_patches(model, result, normal=normal) for model, result in zip(models, results)]
    return sbt.module_b2b(patches, lin2019_screw.table4_module(oversize()), **(
        {} if free_balls is None else {"free_balls": free_balls}))


def _run(run, case: str) -> None:
    printed = PRINTED[case]
    (contacts, free, state), time_low = run.time(low_order, case)
    _, solve_s = run.time(screw_b2b.solve, contacts, AXIAL_LOAD)
    force_low = float(state.b2b_force[0])
    increase_low = lin2019_screw.friction_increase(free, state)
    if case == "b":  # case (a)'s low-order force is the preload's fit (docs/ball_screw.md): no check there
        run.check(model=MODEL_LOW, quantity="F_B2B (low-order)", unit="N", value=force_low,
                  reference=printed.f_b2b_numerical, source="lin2019 Table 5 case (b), low-order numerical",
                  tolerance=0.05, time_s=solve_s, note="prediction: preload fitted on case (a)'s force alone")
    run.check(model=MODEL_LOW, quantity="F_B2B", unit="N", value=force_low, reference=printed.f_b2b_ansys,
              source=f"lin2019 Table 5 case ({case}), ANSYS FEA", tolerance=0.10, time_s=solve_s,
              note="issue 12: within 10 % of ANSYS (the paper's own low-order model is 6.4-6.7 % above)")
    run.check(model=MODEL_LOW, quantity="friction increase by B2B", unit="%", value=increase_low,
              reference=printed.friction_increase, source="lin2019 Sec 3.3 (low-order)",
              tolerance=3.0 / printed.friction_increase, time_s=time_low, note="tolerance 3 points")
    shares = axial_shares(contacts, state)
    reference = [hertz_statics(contacts, ball, shares[ball]) for ball in range(2)]
    rows, contact_rows = [], []
    last = None
    for h_contact, growth, fine_radius, h_max in run.progress(LEVELS[run.fidelity],
                                                              desc=f"fe-b2b-screw-{case} mesh levels"):
        start = time.perf_counter()
        models, results, timings = solve_fe_level(case, h_contact, growth, fine_radius, h_max, shares)
        row = dict(h_contact_um=h_contact * 1e6, growth=growth, fine_radius_um=fine_radius * 1e6, h_max_mm=h_max * 1e3,
                   ndofs=sum(m.ndofs for m in models), multipliers=sum(m.n_multipliers for m in models))
        t_b2b = time.perf_counter()
        informed = fe_informed(models, results)
        timings["b2b_s"] = time.perf_counter() - t_b2b
        row.update(F_B2B=float(informed.b2b_force[0]), friction_increase_pct=float(informed.friction_increase),
                   power_balance=float(informed.power_balance))
        wall = time.perf_counter() - start
        row.update(wall_s=wall, **{k: float(v) for k, v in timings.items()})
        rows.append(row)
        name = fe_informed_name(h_contact)
        run.check(model=name, quantity="F_B2B", unit="N", value=float(informed.b2b_force[0]),
                  reference=printed.f_b2b_ansys, source=f"lin2019 Table 5 case ({case}), ANSYS FEA",
                  tolerance=0.10, time_s=wall,
                  note=f"issue 12: within 10 %; {row['ndofs']} DOFs in two modules; mesh + assembly + "
                       "condensation + 2 contact solves + B2B solves; preload fitted on the paper's low-order 1.92 N, "
                       "not on ANSYS",
                  known_gap=ANSYS_GAP if any(case == c and abs(h_contact - h) < 1e-9 for c, h in ANSYS_GAP_LEVELS)
                  else None)
        run.check(model=name, quantity="friction increase by B2B", unit="%",
                  value=float(informed.friction_increase), reference=printed.friction_increase,
                  source="lin2019 Sec 3.3 (the paper's low-order value; no FE value is printed)",
                  tolerance=3.0 / printed.friction_increase, time_s=wall, note="tolerance 3 points")
        run.check(model=name, quantity="power balance (input - losses)/input", unit="1",
                  value=float(informed.power_balance), reference=0.0, scale=1.0, tolerance=1e-6, time_s=wall,
                  why="the value is itself a relative power error: zero judged on the scale 1",
                  source="energy conservation incl. B2B loss (screw at rest, nut drives); issue 12: 1e-6")
        for ball, result in enumerate(results):
            forces = np.array([c.normal_force for c in result.contacts])
            ellipse = hertz_ellipse(contacts, ball, forces)
            for i, contact in enumerate(result.contacts):
                fit = contact.ellipse
                contact_rows.append(dict(
                    h_contact_um=h_contact * 1e6, ball=ball + 1, contact=contact.name, F=contact.normal_force,
                    F_hertz_statics=float(reference[ball][i]), F_low_order=float(state.normal_force[ball, i]),
                    angle_deg=math.degrees(contact.contact_angle),
                    angle_rigid_deg=math.degrees(models[ball].geometry.contact_angles[i]),
                    angle_low_order_deg=math.degrees(state.contact_angle[ball, i]),
                    a_um=np.nan if fit is None else fit.a * 1e6, a_hertz_um=ellipse[i, 0] * 1e6,
                    b_um=np.nan if fit is None else fit.b * 1e6, b_hertz_um=ellipse[i, 1] * 1e6,
                    p0_MPa=np.nan if fit is None else fit.p0 / 1e6, p0_hertz_MPa=ellipse[i, 2] / 1e6,
                    approach_um=(contact.approach + oversize()) * 1e6,
                    delta_hertz_um=float(contacts.hertz_constant[ball, i] * contact.normal_force ** (2 / 3)) * 1e6,
                    approach_low_order_um=float(state.approach[ball, i]) * 1e6))
        last = (h_contact, models, results, wall)
    h_contact, models, results, wall = last
    name = fe_model_name(h_contact)
    level = [r for r in contact_rows if r["h_contact_um"] == h_contact * 1e6]

    def worst(key, ref):
        return max(abs(r[key] / r[ref] - 1.0) for r in level)

    run.check(model=name, quantity="contact forces, worst of 8: |F_FE/F_Hertz statics - 1|", unit="1",
              value=worst("F", "F_hertz_statics"), reference=0.0, scale=1.0, tolerance=0.02, time_s=wall,
              source="frictionless Hertz statics of the same geometry, preload and axial share (hertz_statics); "
                     "issue 12: 2 %",
              why="the value is itself a relative force error: zero judged on the scale 1",
              note="statically indeterminate (4 forces, 3 equations): the FE's compliance and the interference decide; "
                   "with the bodies of BODY_DEPTH (docs/fe_b2b.md, depth table)")
    fe_forces = [[c.normal_force for c in result.contacts] for result in results]
    balance = max(float(np.abs(statics_residual(contacts, ball, fe_forces[ball], shares[ball])).max() / shares[ball])
                  for ball in range(2))
    run.check(model=name, quantity="ball statics, worst of 2 balls: max |residual| / axial share", unit="1",
              value=balance, reference=0.0, scale=1.0, tolerance=STATICS_TOL, time_s=wall,
              source="x3 and z3 balance of each ball and the screw's axial push = the ball's share, with the FE "
                     "forces along the low-order model's rigid flank normals (statics_residual, lin2019 eq 37)",
              why="the value is itself a relative force residual: zero judged on the scale 1",
              note="rejects a module loaded with the wrong sign or share, flanks at the wrong angles, screw and nut "
                   "contacts swapped (docs/mutations.md)")
    run.check(model=name, quantity="half-turn symmetry of ball 1 (theta 0): max(|F_SL-F_NR|, |F_SR-F_NL|)/max F",
              unit="1", value=half_turn_asymmetry(fe_forces[0]), reference=0.0, scale=1.0, tolerance=STATICS_TOL,
              time_s=wall, source="frictionless statics of four flanks at one angle (half_turn_asymmetry)",
              why="the value is itself a relative force difference: zero judged on the scale 1",
              note="rejects a deviation on ball 1's module or its nut flanks NR and NL swapped (docs/mutations.md)")
    run.check(model=name, quantity="contact forces, worst of 8: |F_FE/F_low-order - 1|", unit="1",
              value=worst("F", "F_low_order"), reference=0.0, scale=1.0, tolerance=0.02, time_s=wall,
              source="lowmodel.screw.b2b touching state (with friction, eq 54); issue 12: 2 %",
              why="the value is itself a relative force error: zero judged on the scale 1",
              known_gap=FRICTIONLESS_GAP)
    for key, what in (("a", "a"), ("b", "b"), ("p0", "p0")):
        unit_key = "MPa" if key == "p0" else "um"
        run.check(model=name, quantity=f"fitted {what}, worst of 8: |FE/Hertz - 1|", unit="1",
                  value=worst(f"{key}_{unit_key}", f"{key}_hertz_{unit_key}"), reference=0.0, scale=1.0,
                  tolerance=0.05, time_s=wall,
                  source="low-order model's Hertz ellipse (ball_in_screw_groove) at the FE's force; issue 12: 5 %",
                  why="the value is itself a relative error: zero judged on the scale 1",
                  known_gap=ELLIPSE_GAP if any(case == c and key == k and abs(h_contact - h) < 1e-9
                                               for c, k, h in ELLIPSE_GAP_LEVELS) else None)
    if run.fidelity in TIME_LIMIT_S:
        run.budget(model=name, quantity="wall_time", unit="s", value=sum(r["wall_s"] for r in rows),
                   budget=TIME_LIMIT_S[run.fidelity], time_s=wall,
                   source=f"issue 12 time budget at the {run.fidelity} level (a cached mesh costs nothing)")
    for filename, table in (("levels.csv", rows), ("contacts.csv", contact_rows)):
        with open(run.path(filename), "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(table[0]))
            writer.writeheader()
            writer.writerows(table)
        run.add_artifact(run.path(filename))
    lines = []
    for r in rows:
        text = f"{r['h_contact_um']:.0f} um: {r['ndofs']} DOFs, {r['wall_s']:.0f} s"
        text += f", F_B2B {r['F_B2B']:.3f} N, increase {r['friction_increase_pct']:.1f} %"
        lines.append(text)
    run.note(f"Preload: oversize {oversize() * 1e6:.4f} um (interference fit); axial shares {shares[0]:.3f} / "
             f"{shares[1]:.3f} N.  Low-order: F_B2B {force_low:.3f} N, friction increase {increase_low:.2f} %.  "
             "FE per level: " + "; ".join(lines) + ".  Per contact (contacts.csv): FE force against the frictionless "
             "Hertz statics and the low-order model, loaded vs rigid angle, fitted a, b, p0 vs Hertz, approach.")
    run.save_figure(_figure(models, results, contacts), "pressure_patches.png")
    render3d.module_artifacts(run, models, results, materials=(E_STEEL, NU_STEEL), case=f"theta 0 / "
                              f"{math.degrees(printed.theta):g} deg, {AXIAL_LOAD:g} N",
                              level={"h_contact_m": h_contact, "growth": LEVELS[run.fidelity][-1][1]})
    if run.fidelity != "quick":
        _sensitivity(run, case, models, results, state, contacts)


def _figure(models, results, contacts, heading: str = "contact pressure"):
    from ballbench.validation.scenes.fe_b2b import patch_figure

    axes = [hertz_ellipse(contacts, ball, [c.normal_force for c in result.contacts])[:, :2]
            for ball, result in enumerate(results)]
    return patch_figure(results, axes, ylabel="e2 along the groove [mm]", xlim=0.4, ylim=0.12, heading=heading,
                        hertz_label="Hertz ellipse at the FE force")


def _sensitivity(run, case, models, results, state, contacts) -> None:
    """F_B2B with Hertz or FE patches, rigid or loaded contact angles, and the friction-plane normal."""
    from ballbench.fem import screw_module as sm
    from ballbench.lowmodel.screw import b2b_traction as sbt

    module = lin2019_screw.table4_module(oversize())
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
                     float(fe_informed(models, results, normal=normal).b2b_force[0])))
    # the unknown preload: the oversize at which the low-order model gives ANSYS's case (a) 1.80 N
    ansys_oversize = ansys_fitted_oversize()
    contacts_ansys, _, state_ansys = low_order(case, ansys_oversize)
    shares_ansys = axial_shares(contacts_ansys, state_ansys)
    lowered = [sm.solve(sm.with_oversize(model, ansys_oversize), float(shares_ansys[ball]))
               for ball, model in enumerate(models)]
    rows.append((f"low-order at the oversize fitted on ANSYS's case (a) 1.80 N ({ansys_oversize * 1e6:.4f} um)",
                 float(state_ansys.b2b_force[0])))
    rows.append((f"FE-informed at that oversize ({ansys_oversize * 1e6:.4f} um)",
                 float(fe_informed(models, lowered).b2b_force[0])))
    rigid = [sm.solve(model, float(shares[ball]), geometric_update=False)
             for ball, model in enumerate(models)]
    rows.append(("FE tractions, rigid contact angles (no geometric update)",
                 float(fe_informed(models, rigid).b2b_force[0])))
    ansys = PRINTED[case].f_b2b_ansys
    with open(run.path("sensitivity.csv"), "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["variant", "F_B2B_N", f"vs_ANSYS_{ansys}"])
        for label, value in rows:
            writer.writerow([label, f"{value:.4f}", f"{value / ansys - 1:+.4f}"])
    run.add_artifact(run.path("sensitivity.csv"))
    run.note("Sensitivity (sensitivity.csv): " + "; ".join(f"{label}: {value:.3f} N" for label, value in rows))


def show(scene_name: str, out_dir, fidelity: str = "default") -> list:
    """``ballbench show fe-b2b-screw-a|b``: ``pressure.png`` (the four contact patches of both balls with the
    low-order model's Hertz ellipses at the FE forces and the FE moment ellipses, ``fe_b2b.patch_figure``) and
    ``stress.png`` (von Mises stress of ball 2's module on the plane through the ball centre normal to the helix,
    x3-z3, which holds all four contacts: SL-NR and SR-NL are the two pairs of opposite contacts)."""
    from pathlib import Path

    from ballbench.fem.fields import write_module_fields
    from ballbench.validation.scenes.fe_b2b import contact_summary, save_figure, stress_cut

    cases = {"fe-b2b-screw-a": "a", "fe-b2b-screw-b": "b"}
    if scene_name not in cases:
        raise ValueError(f"show supports {tuple(cases)} here, got {scene_name!r}")
    if fidelity not in ("quick", "default"):
        raise ValueError(f"fidelity must be 'quick' or 'default', got {fidelity!r}")
    case = cases[scene_name]
    contacts, _, state = low_order(case)
    h_contact, growth, fine_radius, h_max = LEVELS[fidelity][-1]
    models, results, _ = solve_fe_level(case, h_contact, growth, fine_radius, h_max, axial_shares(contacts, state))
    target = Path(out_dir) / scene_name
    target.mkdir(parents=True, exist_ok=True)
    heading = f"{scene_name}, h = {h_contact * 1e6:.0f} um"
    pressure_path = save_figure(_figure(models, results, contacts, heading=heading), target / "pressure.png")
    model, result = models[1], results[1]
    geometry = model.geometry
    stress_path = stress_cut(model, result, target / "stress.png", normal=geometry.cs3[:, 1],
                             origin=geometry.ball_centre, view_up=geometry.cs3[:, 2], axis_names=("-x3", "z3"),
                             title=f"{scene_name}, ball 2 (theta {math.degrees(PRINTED[case].theta):g} deg), cut "
                                   f"x3-z3 through the ball centre and the four contacts\n{contact_summary(result)}")
    write_module_fields(target, models, results, materials=(E_STEEL, NU_STEEL), scene=scene_name, fidelity=fidelity,
                        level={"h_contact_m": h_contact, "growth": growth})
    return [pressure_path, stress_path] + render3d.render(target)


def _default_level() -> str:
    h_contact, growth, fine_radius, h_max = LEVELS["default"][-1]
    return (f"h {h_contact * 1e6:.0f} um, growth {growth:g}, fine zone {fine_radius * 1e6:.0f} um, h_max "
            f"{h_max * 1e3:g} mm, bodies to R_P -+ {BODY_DEPTH:g} R_B")


@scene("fe-b2b-screw-a", "FE-informed B2B force on lin2019's two-ball ball-screw module, Table 5 case (a) "
       "(theta 0 / 2 deg, 50 N): low-order, FE contacts and FE-informed per mesh level against ANSYS 1.80 N",
       kind="FE", cost_s=SCENE_COST_S, budget_s=SCENE_BUDGET_S, level=_default_level())
def fe_b2b_screw_a(run):
    _run(run, "a")


@scene("fe-b2b-screw-b", "FE-informed B2B force on lin2019's two-ball ball-screw module, Table 5 case (b) "
       "(theta 0 / 3 deg, 50 N): low-order, FE contacts and FE-informed per mesh level against ANSYS 2.71 N",
       kind="FE", cost_s=SCENE_COST_S, budget_s=SCENE_BUDGET_S, level=_default_level())
def fe_b2b_screw_b(run):
    _run(run, "b")
