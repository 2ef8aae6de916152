"""Scenes for the rough-raceway friction of sun2021 (Sec 2.3 eq 15 ROU, Sec 3 eqs 20-23, Figs 6, 12, 13).

Models: lowmodel.contact.roughness (WM raceway), lowmodel.contact.mixed (load-shared mixed EHL, eqs 21-23),
lowmodel.screw.friction_torque (eq 20 with wang2022 kinematics).  Inputs: validation/papers/sun2021.py.
Conventions and what the paper leaves unstated: docs/mixed_lubrication.md.
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel.contact import ehl, halfspace, hertz, mixed, roughness
from ballbench.lowmodel.contact.screw_contact import preload_contact_load
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import groove, helix
from ballbench.lowmodel.screw import friction_torque
from ballbench.validation.papers import sun2021 as paper
from ballbench.validation.scene import KnownGap, scene
from ballbench.validation.scenes.sun2021 import POINTS, SIGN_TEST

T1 = paper.TABLE_1
E_STAR = T1.youngs_modulus / (2.0 * (1.0 - T1.poisson_ratio**2))
LOAD = preload_contact_load(T1.preload, T1.ball_count, T1.helix_angle, T1.contact_angle)  # sun2021 eq 1
EHL_ITERATIONS = 30  # converged points take 6-12 Newton steps; where the solver stalls (slow speeds) fail fast
# nested iteration from the 64 x 16 grid stalls below ~250 mm/s screw speed (its across-groove cells are 44 um);
# the 128 x 32 grid started from the dry pressure converges down to 83 mm/s in 8-9 Newton steps
COARSEST = 32
READING = "pm"  # the unit the printed G = 0.41 is read in (docs/mixed_lubrication.md)


def ehl_domain(helix_angle_deg: float, point: str, n: int, helix_free: bool = False):
    """Grid (x along the track = entrainment, y across the groove) and smooth gap of the EHL domain (eq 18)."""
    body, flank = POINTS[point]
    lead = 0.0 if helix_free else float(helix.lead_from_angle(math.radians(helix_angle_deg), T1.pitch_radius))
    args = (T1.ball_radius, T1.conformity, T1.pitch_radius, lead, T1.contact_angle, body)
    frame = groove.contact_frame(groove.helical_groove(*args, flank))
    ball = (1.0 / T1.ball_radius, 1.0 / T1.ball_radius)
    contact = hertz.solve_load(hertz.from_curvatures(ball, (frame.curvature_major, frame.curvature_minor),
                                                     youngs_modulus=T1.youngs_modulus,
                                                     poisson_ratio=T1.poisson_ratio), LOAD)
    # x in [-277, 277] um (eq 18); across the groove widened to 1.3 a (a = 275 um at A), as sun2021-ehl
    grid = halfspace.surface_grid(paper.EHL_HALF_WIDTH, max(paper.EHL_HALF_WIDTH, 1.3 * float(contact.a)), 2 * n,
                                  n // 2)
    X, Y = grid.coordinates()
    gap = groove.pair_initial_gap(*args, flank=flank)(Y, X)
    return grid, gap - gap.min()


def raceway_heights(grid, reading: str = READING, seed: int = 0) -> roughness.RacewayRoughness:
    """The seeded WM raceway of sun2021 Sec 2.3 on ``grid`` with G read in ``reading`` ("pm" or "nm")."""
    return roughness.raceway_roughness(grid, paper.FRACTAL_DIMENSION,
                                       paper.FRACTAL_SCALE * paper.FRACTAL_SCALE_READINGS[reading],
                                       sample_length=paper.FRACTAL_SAMPLE_LENGTH,
                                       cutoff_length=paper.FRACTAL_CUTOFF_LENGTH, seed=seed)


def _speeds(surface_speed: float):
    return friction_torque.contact_speeds(surface_speed, T1.pitch_radius, T1.ball_radius, T1.lead,
                                          T1.contact_angle)


def mixed_point(grid, gap, heights, surface_speed: float, point: str = "B", coupled: bool = True):
    """Mixed contact, friction (eqs 21-23), eq 20 torque [N m] and entrainment [m/s] at screw speed [m/s]."""
    speeds = _speeds(surface_speed)
    u = float(speeds.entrainment_B if point == "B" else speeds.entrainment_A)
    sliding = speeds.sliding_B if point == "B" else speeds.sliding_A
    contact = mixed.solve(gap, heights, grid, E_STAR, LOAD, u, T1.viscosity, T1.lubricant_density,
                                initial_film=8e-8, ehl_iterations=EHL_ITERATIONS, coarsest=COARSEST,
                                coupled=coupled)
    friction = mixed.mixed_friction(contact, float(np.linalg.norm(sliding)), T1.viscosity, paper.EYRING_STRESS,
                                    paper.DRY_FRICTION)
    torque = friction_torque.friction_torque(friction.friction_coefficient, LOAD, speeds.sliding_B,
                                             ball_count=T1.ball_count, lead_angle=T1.helix_angle,
                                             pitch_radius=T1.pitch_radius, ball_radius=T1.ball_radius,
                                             contact_angle_B=T1.contact_angle)
    return contact, friction, torque, u


@scene("sun2021-roughness",
       "sun2021 Sec 2.3: WM fractal raceway (D = 2.47, G = 0.41 read in pm, seeded): sampled rms and line "
       "spectrum against the WM closed forms, fitted fractal dimension",
       kind="analytical", cost_s=1.0)
def sun2021_roughness(run):
    L, Ls = paper.FRACTAL_SAMPLE_LENGTH, paper.FRACTAL_CUTOFF_LENGTH
    G = paper.FRACTAL_SCALE * paper.FRACTAL_SCALE_READINGS[READING]
    D = paper.FRACTAL_DIMENSION
    # profile along x (the ridge m = M): lines at gamma^n / L of amplitude C gamma^((D-3) n)
    x = np.arange(0.0, 100 * L, Ls / 8)
    z, time_s = run.time(ehl.weierstrass_mandelbrot_surface, x, np.zeros_like(x), D, G, L, cutoff_length=Ls,
                         budget_s=0.0, max_repeat=1)
    frequency, amplitude = roughness.wm_line_spectrum(D, G, L, Ls)
    window = np.hanning(x.size)
    measured = np.array([2.0 * abs(np.sum(window * (z - z.mean()) * np.exp(-2j * math.pi * f * x))) / window.sum()
                         for f in frequency])
    for n, (f, a, m) in enumerate(zip(frequency, amplitude, measured)):
        run.check(model="lowmodel.contact.roughness", quantity=f"line amplitude n = {n} (f = {f * 1e-3:.2f} 1/mm)",
                  unit="m", value=float(m), reference=float(a), tolerance=0.03, time_s=time_s,
                  source="WM closed form C gamma^((D-3) n) (Yan & Komvopoulos 1998 eq 4)",
                  note="Hann-windowed DFT of a 100 L profile")
    fitted = 3.0 + np.polyfit(np.arange(measured.size) * math.log(1.5), np.log(measured), 1)[0]
    run.check(model="lowmodel.contact.roughness", quantity="fractal dimension D from the line spectrum", unit="1",
              value=float(fitted), reference=D, tolerance=0.004, time_s=time_s, source="sun2021 Sec 2.3: D = 2.47",
              note="slope of log amplitude against log frequency is D - 3; 0.004 relative is 0.01 in D")
    grid = halfspace.surface_grid(L / 2, L / 2, 64, 64)
    samples = [raceway_heights(grid, seed=seed) for seed in range(12)]
    ensemble = math.sqrt(float(np.mean([np.mean(s.heights**2) for s in samples])))
    run.check(model="lowmodel.contact.roughness", quantity="rms height over 12 seeds (554 um square)", unit="m",
              value=ensemble, reference=roughness.wm_rms(D, G, L, Ls), tolerance=0.12, time_s=time_s,
              source="WM closed form sigma = L (G/L)^(D-2) [ln(gamma)/2 sum gamma^(2(D-3)n)]^(1/2)",
              note="one domain holds few of the longest waves: the 12-seed estimate scatters by ~10 %")
    for reading, unit in paper.FRACTAL_SCALE_READINGS.items():
        run.note(f"G = 0.41 {reading}: rms {roughness.wm_rms(D, paper.FRACTAL_SCALE * unit, L, Ls) * 1e9:.1f} nm "
                 f"(L = {L * 1e6:.0f} um, L_s = {Ls * 1e6:.0f} um, gamma 1.5, M = 10)")
    import matplotlib.pyplot as plt

    figure, axis = plt.subplots(figsize=(5, 4.2))
    image = axis.imshow(samples[0].heights * 1e9, origin="lower",
                        extent=[grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6])
    figure.colorbar(image, ax=axis, label="height [nm]")
    axis.set_title("WM raceway, D = 2.47, G = 0.41 pm, seed 0")
    run.save_figure(figure, "wm_surface.png")


def _clearance(grid, gap, heights, surface_speed: float, coupled: bool = True) -> float:
    """Smallest rough film [m] at the nut contact; -inf where the coupled film closes (its solve fails).

    ``coupled``: the Reynolds equation with the roughness in the film (sun2021 eq 15); otherwise the rigid
    roughness against the smooth film, ``min(h_s - z)``.  ConvergenceError when the smooth solve fails too.
    """
    u = float(_speeds(surface_speed).entrainment_B)
    options = dict(initial_film=8e-8, coarsest=COARSEST, max_iterations=EHL_ITERATIONS)
    if coupled:
        try:
            return ehl.solve_reynolds(gap - heights, grid, E_STAR, LOAD, u, T1.viscosity, T1.lubricant_density,
                                      **options).minimum_film
        except ConvergenceError:
            pass
    film = ehl.solve_reynolds(gap, grid, E_STAR, LOAD, u, T1.viscosity, T1.lubricant_density, **options)
    return -math.inf if coupled else float(np.min(film.film - heights))


def _transition(grid, gap, heights, clearances: dict, steps: int, factor: float = 0.9, coupled: bool = True):
    """Screw speed [m/s] where the rough film first touches (clearance 0), from the sweep's ``clearances``.

    Below the slowest full-film speed: bracket downward (x ``factor``) until the film touches or the EHL solve stops
    converging (then the slowest full-film speed is an upper bound), then bisect in log speed.
    """
    full = sorted(speed for speed, c in clearances.items() if c > 0.0)
    if not full:
        return None, "the rough film touches at every speed of the sweep"
    hi = full[0]
    touching = [speed for speed, c in clearances.items() if c <= 0.0 and speed < hi]
    lo = max(touching) if touching else None
    c_hi = clearances[hi]
    speed = hi
    while lo is None and speed > 0.4 * full[0]:
        speed *= factor
        try:
            c = _clearance(grid, gap, heights, speed, coupled)
        except ConvergenceError as error:
            return hi, (f"upper bound: full film (film >= {c_hi * 1e9:+.1f} nm) at {hi * 1e3:.0f} mm/s, the "
                        f"slowest speed the EHL solve reaches (no convergence at {speed * 1e3:.0f} mm/s: {error})")
        if c <= 0.0:
            lo = speed
        else:
            hi, c_hi = speed, c
    if lo is None:
        return hi, f"upper bound: still full film at {hi * 1e3:.0f} mm/s"
    for _ in range(steps):
        mid = math.sqrt(lo * hi)
        if _clearance(grid, gap, heights, mid, coupled) > 0.0:
            hi = mid
        else:
            lo = mid
    return math.sqrt(lo * hi), f"bracket [{lo * 1e3:.1f}, {hi * 1e3:.1f}] mm/s"


def _scale_at_first_touch(grid, gap, heights, surface_speed: float) -> float:
    """Factor s on the heights at which the rough film first touches at ``surface_speed`` (s z = h_s somewhere).

    WM heights scale as G^(D-2) with the phases fixed, so G* = G s^(1/(D-2)) puts the first touch there.
    """
    u = float(_speeds(surface_speed).entrainment_B)
    film = ehl.solve_reynolds(gap, grid, E_STAR, LOAD, u, T1.viscosity, T1.lubricant_density, initial_film=8e-8,
                              coarsest=COARSEST, max_iterations=EHL_ITERATIONS).film
    up = heights > 0.0
    return float(np.min(film[up] / heights[up]))


TRANSITION_GAP = KnownGap(
    reason="sun2021 leaves the unit of G, the WM sample length and cutoff unstated; with G read in pm (rms 21 nm) "
           "the rough film of the nut contact, roughness inside the Reynolds equation as sun2021 eq 15 writes it, "
           "stays open down to about 80 mm/s (the film pressure flattens the long roughness waves); even the "
           "rigid roughness against the smooth film touches only at ~224 mm/s; with G in nm (rms 0.53 um) the film "
           "closes up to 2000 mm/s; no printed reading gives 502.65 mm/s",
    evidence="sun2021-fig6 notes (coupled and decoupled film against screw speed, both readings, the G that puts "
             "the rigid first touch at 502.65 mm/s); docs/mixed_lubrication.md")


@scene("sun2021-fig6",
       "sun2021 Sec 3.2, Fig 6: friction coefficient (eqs 21-23) and friction torque (eq 20) of the nut contact B "
       "against screw speed, wang2022 entrainment and sliding, WM raceway (G in pm): mixed-to-hydrodynamic "
       "transition against the published 502.65 mm/s",
       kind="low-order", cost_s=25.0)  # cost: 24 s wall default at load average 3 (51 s at 7-9), quick 15 s
def sun2021_fig6(run):
    n = {"quick": 64, "default": 64, "fine": 128}[run.fidelity]  # grid 2n x n/2 (n >= 64 resolves L_s = 50 um)
    grid, gap = ehl_domain(paper.HELIX_ANGLES_DEG[0], "B", n)
    rough = raceway_heights(grid)
    surface_speeds = {"quick": (0.083, 0.5), "default": (0.083, 0.15, 0.3, 0.5, 1.0, 2.0),
                      "fine": (0.083, 0.15, 0.3, 0.5, 1.0, 2.0)}[run.fidelity]
    rows, times = [], []
    for speed in run.progress(surface_speeds, desc="screw speeds"):
        try:
            (contact, friction, torque, u), time_s = run.time(mixed_point, grid, gap, rough.heights, speed,
                                                              budget_s=0.0, max_repeat=1)
        except ConvergenceError as error:
            run.note(f"{speed * 1e3:.0f} mm/s: no solution ({error})")
            continue
        times.append(time_s)
        rows.append((speed, u, contact, friction, torque))
        # Newtonian limit of eqs 22-23 (tau0 -> inf): sum eta(p) du / h dA over the wet film, from the fields
        sliding = float(np.linalg.norm(_speeds(speed).sliding_B))
        wet = (contact.film.pressure > 0.0) & (contact.rough_film > 0.0)
        newtonian = float(np.sum(ehl.roelands_viscosity(contact.film.pressure[wet], T1.viscosity) * sliding
                                 / contact.rough_film[wet])) * grid.cell_area
        limit = mixed.mixed_friction(contact, sliding, T1.viscosity, 1e30, paper.DRY_FRICTION)
        run.check(model="lowmodel.contact.mixed", quantity=f"film friction, Newtonian limit, {speed * 1e3:.0f} mm/s",
                  unit="N", value=limit.film_friction, reference=newtonian, tolerance=1e-6, time_s=time_s,
                  source="sun2021 eqs 22-23 at tau0 -> inf: Newton's eta du / h over the wet film",
                  note="catches a wrong film (smooth instead of rough), viscosity or area in eq 22")
    speeds = [r[0] for r in rows]
    mu = [r[3].friction_coefficient for r in rows]
    for speed, u, contact, friction, torque in rows:
        run.note(f"{speed * 1e3:.0f} mm/s ({paper.screw_speed_to_rpm(speed):.0f} rpm): u_s(B) {u * 1e3:.1f} mm/s, "
                 f"h_c {contact.smooth.central_film * 1e9:.1f} nm, "
                 f"{'coupled rough film: min' if contact.coupled else 'decoupled: clearance'} "
                 f"{contact.clearance * 1e9:+.1f} nm, "
                 f"R_s {contact.asperity_share:.3f}, mu {friction.friction_coefficient:.4f} (film "
                 f"{friction.film_friction:.3f} N, asperities {friction.asperity_friction:.3f} N), eq 20 torque "
                 f"{torque:.3f} N m")
    steps = {"quick": 2, "default": 4, "fine": 6}[run.fidelity]
    factor_down = 0.8 if run.fidelity == "quick" else 0.9
    clearances = {r[0]: r[2].clearance if r[2].coupled else -math.inf for r in rows}
    transition, how = _transition(grid, gap, rough.heights, clearances, steps, factor_down)
    run.note(f"transition (G in pm, coupled rough film): {how}")
    rigid = sorted((r[0], float(np.min(r[2].smooth.film - rough.heights))) for r in rows)
    run.note("rigid roughness against the smooth film (decoupled model, no flattening), min(h_s - z): "
             + ", ".join(f"{speed * 1e3:.0f} mm/s {c * 1e9:+.1f} nm" for speed, c in rigid))
    for (s1, c1), (s2, c2) in zip(rigid, rigid[1:]):
        if c1 <= 0.0 < c2:
            touch = s1 * (s2 / s1) ** (-c1 / (c2 - c1))
            run.note(f"its first touch, interpolated in log speed: {touch * 1e3:.0f} mm/s")
    full = [(speed, c) for speed, c in rigid if c > 0.0]
    if len(full) >= 2:
        # clearance = a Omega'^0.68 - c through the two slowest full-film points (Hamrock-Dowson h_min ~ u^0.68)
        (s1, c1), (s2, c2) = full[:2]
        a = (c2 - c1) / (s2**0.68 - s1**0.68)
        offset = a * s1**0.68 - c1
        if a > 0.0 and offset > 0.0 and rigid[0][1] > 0.0:
            run.note(f"extrapolated rigid first touch (clearance ~ Omega'^0.68 through {s1 * 1e3:.0f} and "
                     f"{s2 * 1e3:.0f} mm/s): {(offset / a) ** (1 / 0.68) * 1e3:.0f} mm/s (an estimate, not checked)")
    # the film-parameter rule (lambda = h_min / sigma >= 3 for full film, Hamrock & Dowson): where it crosses 3
    lam = [(r[0], r[2].smooth.minimum_film / rough.rms) for r in rows]
    run.note("lambda_min = h_min / sigma (sigma " + f"{rough.rms * 1e9:.1f} nm): "
             + ", ".join(f"{speed * 1e3:.0f} mm/s {value:.2f}" for speed, value in lam))
    for (s1, l1), (s2, l2) in zip(lam, lam[1:]):
        if l1 < 3.0 <= l2:
            crossing = s1 * (s2 / s1) ** (math.log(3.0 / l1) / math.log(l2 / l1))
            run.note(f"lambda_min = 3 (log-log between {s1 * 1e3:.0f} and {s2 * 1e3:.0f} mm/s) at {crossing * 1e3:.0f} "
                     f"mm/s, {100 * (crossing / paper.MIXED_TO_HYDRODYNAMIC_SPEED - 1):+.0f} % from 502.65 mm/s "
                     "(a rule of thumb, reported, not checked: the first touch is the model's own transition)")
    factor = _scale_at_first_touch(grid, gap, rough.heights, paper.MIXED_TO_HYDRODYNAMIC_SPEED)
    g_star = paper.FRACTAL_SCALE * paper.FRACTAL_SCALE_READINGS[READING] * factor ** (
        1.0 / (paper.FRACTAL_DIMENSION - 2.0))
    run.note(f"G that puts the rigid first touch at 502.65 mm/s on this seed and grid: {g_star * 1e12:.2f} pm (x "
             f"{factor:.2f}, rms {rough.rms * factor * 1e9:.1f} nm)")
    if transition is not None:
        run.check(model="lowmodel.contact.mixed",
                  quantity="Fig 6: mixed-to-hydrodynamic transition, screw speed where the rough film (eq 15 "
                           "with ROU) closes (nut contact B, 5.68 deg)",
                  unit="m/s", value=transition, reference=paper.MIXED_TO_HYDRODYNAMIC_SPEED, tolerance=0.1,
                  time_s=float(sum(times)), source="sun2021 Sec 3.2: 502.65 mm/s", known_gap=TRANSITION_GAP,
                  relation="ge" if how.startswith("upper bound") else "eq",
                  note=f"G in pm, coupled rough film; {how}")
    # the nm reading: is the contact still mixed at the top speed?
    rough_nm = raceway_heights(grid, "nm")
    nm_rows = []
    for speed in () if run.fidelity == "quick" else (1.0, 2.0):  # quick: the pm reading only
        try:
            contact, friction, _, _ = mixed_point(grid, gap, rough_nm.heights, speed)
        except (ConvergenceError, ValueError) as error:
            run.note(f"G in nm: no mixed solution at {speed * 1e3:.0f} mm/s ({error})")
            continue
        nm_rows.append((speed, contact, friction))
        run.note(f"G in nm (rms {rough_nm.rms * 1e9:.0f} nm): {speed * 1e3:.0f} mm/s "
                 f"{'coupled film open, min' if contact.coupled else 'coupled film closes; decoupled clearance'} "
                 f"{contact.clearance * 1e9:+.0f} nm, R_s {contact.asperity_share:.3f}, mu "
                 f"{friction.friction_coefficient:.4f}")
    if len(nm_rows) == 2:
        run.check(model="lowmodel.contact.mixed",
                  quantity="Fig 6b mixed branch (G in nm): mu falls with screw speed, mu(2000) - mu(1000 mm/s)",
                  unit="1", value=nm_rows[1][2].friction_coefficient - nm_rows[0][2].friction_coefficient,
                  reference=0.0, relation="le", scale=1.0, tolerance=0.0, why=SIGN_TEST, time_s=float(sum(times)),
                  source="sun2021 Sec 3.2, Fig 6b (Stribeck-like: mixed friction falls as the film grows)",
                  note=f"R_s {nm_rows[0][1].asperity_share:.3f} -> {nm_rows[1][1].asperity_share:.3f}")
    if rows and not any(r[2].asperity_share > 0.0 for r in rows):
        lowest = min(rows, key=lambda r: r[3].friction_coefficient)
        run.note("G in pm: no asperity contact at any speed of the sweep (the coupled rough film stays open), so "
                 "Fig 6b's mixed branch is not there; the film friction alone has its lowest mu "
                 f"({lowest[3].friction_coefficient:.4f}) at {lowest[0] * 1e3:.0f} mm/s (thin films raise the shear "
                 "rate at low speed, du / h ~ u^0.33 drives it up at high speed)")
    run.note("Screw speed Omega' = omega r (pitch-circle surface speed): 502.65 mm/s is 300 rpm, Table 1's 83 mm/s "
             "50 rpm; entrainment u_s(B) = 0.49 Omega' (wang2022).  Eyring tau0 = 5 MPa (unstated in sun2021), "
             "mu_a = 0.1 (Sec 3.2).  Grid " + f"{2 * n} x {n // 2}.")
    if len(rows) >= 2:
        import matplotlib.pyplot as plt

        figure, axes = plt.subplots(1, 3, figsize=(14, 4.2))
        axes[0].semilogx(np.array(speeds) * 1e3, mu, "o-", label="G in pm")
        if nm_rows:
            axes[0].semilogx([r[0] * 1e3 for r in nm_rows], [r[2].friction_coefficient for r in nm_rows], "s-",
                             label="G in nm")
        axes[0].axvline(paper.MIXED_TO_HYDRODYNAMIC_SPEED * 1e3, color="k", ls="--", label="sun2021 502.65 mm/s")
        if transition is not None:
            axes[0].axvline(transition * 1e3, color="r", ls=":", label="rough film closes (here)")
        axes[0].set_xlabel("screw speed [mm/s]")
        axes[0].set_ylabel("friction coefficient (eq 21)")
        axes[0].legend()
        last = rows[0][2]
        extent = [grid.y[0] * 1e6, grid.y[-1] * 1e6, grid.x[0] * 1e6, grid.x[-1] * 1e6]
        image = axes[1].imshow((last.film.pressure + last.asperity_pressure) / 1e6, origin="lower", extent=extent,
                               aspect="auto")
        axes[1].set_title(f"pressure [MPa], {rows[0][0] * 1e3:.0f} mm/s")
        figure.colorbar(image, ax=axes[1])
        image = axes[2].imshow(last.rough_film * 1e9, origin="lower", extent=extent, aspect="auto",
                               vmax=4.0 * last.smooth.central_film * 1e9)
        axes[2].set_title("rough film [nm]")
        figure.colorbar(image, ax=axes[2])
        for axis in axes[1:]:
            axis.set_xlabel("y, across the groove [um]")
            axis.set_ylabel("x, entrainment [um]")
        figure.tight_layout()
        run.save_figure(figure, "fig6_friction.png")


def _dry_rough(helix_angle_deg: float, point: str, n: int, helix_free: bool):
    grid, gap = ehl_domain(helix_angle_deg, point, n, helix_free)
    heights = raceway_heights(grid).heights  # boundary limit: the rough raceway carries the whole load
    smooth = halfspace.solve(gap, grid, E_STAR, force=LOAD)
    rough = halfspace.solve(gap - heights, grid, E_STAR, force=LOAD)
    return smooth, rough


ASPERITY_GAP = KnownGap(
    reason="the helix changes the contact through the curvature tensor only (sun2021-dry-contact: BEM = "
           "full-tensor Hertz); against the helix-free contact the central pressure moves by about 1 % at 21.71 "
           "deg, and the asperity stress of the boundary limit on the same raceway inherits that, not 3 %; in the "
           "mixed regime the asperity share differs by a few per cent, but with the sign and size set by where the "
           "asperities sit (seed)",
    evidence="sun2021-dry-contact (-0.91 % at A, +0.83 % at B against helix-free Hertz); sun2021-fig13 notes; "
             "docs/mixed_lubrication.md (decoupled model, 83 mm/s, seeds 0-4: R_s differs by -2.1 to -8.3 % at A, "
             "+0.3 to +4.0 % at B)")


@scene("sun2021-fig13",
       "sun2021 Sec 4.4, Fig 13 at 21.71 deg: asperity contact stress at A and B with the exact helical gap "
       "('non-Hertzian') against the helix-free gap ('Hertzian'), boundary limit on the same WM raceway: "
       "against the published 2.93 % and 3.01 %",
       kind="low-order", cost_s=4.0)  # cost: 3.9 s wall default at load average 3 (14 s at 10), quick 0.5 s
def sun2021_fig13(run):
    n = {"quick": 64, "default": 96, "fine": 192}[run.fidelity]  # n >= 64 resolves L_s = 50 um
    angle = paper.HELIX_ANGLES_DEG[-1]
    for point in POINTS:
        (exact, exact_rough), time_s = run.time(_dry_rough, angle, point, n, False, budget_s=0.0, max_repeat=1)
        free, free_rough = _dry_rough(angle, point, n, True)
        window = slice(n - 2, n + 2), slice(n // 4 - 2, n // 4 + 2)  # 4 x 4 cells round the centre

        def centre(contact):
            return float(contact.pressure[window].mean())

        difference = abs(centre(exact_rough) / centre(free_rough) - 1.0)
        run.check(model="lowmodel.contact.mixed",
                  quantity=f"Fig 13: central asperity stress, exact against helix-free gap, {point}, {angle} deg",
                  unit="1", value=difference, reference=paper.ASPERITY_STRESS_GAIN_21_71[point], tolerance=0.2,
                  time_s=time_s, source="sun2021 Sec 4.4: 2.93 % (A) and 3.01 % (B) at 21.71 deg",
                  known_gap=ASPERITY_GAP,
                  note=f"mean of the 4 x 4 central cells, G in pm (boundary limit); smooth: "
                       f"{100 * (centre(exact) / centre(free) - 1.0):+.2f} %")
        run.note(f"{point}: central pressure smooth exact {centre(exact) / 1e6:.1f} MPa, helix-free "
                 f"{centre(free) / 1e6:.1f} MPa; rough exact {centre(exact_rough) / 1e6:.1f} MPa, helix-free "
                 f"{centre(free_rough) / 1e6:.1f} MPa ({2 * n} x {n // 2} cells)")
    if run.fidelity != "quick":
        # the same comparison in the decoupled mixed model at 83 mm/s (Table 1's screw speed; the coupled rough
        # film is still open there): sparse asperity contacts
        for point in POINTS:
            shares = []
            for helix_free in (False, True):
                grid, gap = ehl_domain(angle, point, 64, helix_free)
                contact = mixed_point(grid, gap, raceway_heights(grid).heights, T1.screw_speed, point,
                                      coupled=False)[0]
                touching = contact.asperity_pressure > 0.0
                shares.append((contact.asperity_share, float(contact.asperity_pressure[touching].mean())
                               if touching.any() else 0.0, contact.central_asperity_pressure,
                               float(touching.mean())))
            (r0, m0, c0, f0), (r1, m1, c1, f1) = shares
            run.note(f"{point}, decoupled model (rigid roughness against the smooth film) at 83 mm/s (128 x 32, G in "
                     f"pm), exact against helix-free: R_s {r0:.5f} "
                     f"against {r1:.5f} ({100 * (r0 / r1 - 1):+.1f} %); mean asperity pressure {m0 / 1e6:.2f} "
                     f"against {m1 / 1e6:.2f} MPa ({100 * (m0 / m1 - 1):+.1f} %); central cell {c0 / 1e6:.1f} "
                     f"against {c1 / 1e6:.1f} MPa; {100 * f0:.1f} % of the cells touch")
    run.note("'Hertzian' here is the helix-free groove (lead 0: the geometry a helix-blind Hertz model uses); "
             "'non-Hertzian' the exact helical gap; both on the same seeded raceway and grid.  The boundary limit "
             "(the raceway carries the whole load) is the check: with G in pm the coupled rough film is open at "
             "83 mm/s, "
             "and in the decoupled model the asperity contacts are sparse (about 1 % of the load) and the central "
             "cell's asperity stress depends on where one asperity sits; those numbers are reported, not checked.")


def _central_ehl_pressure(helix_angle_deg: float, point: str, n: int, surface_speed: float,
                          helix_free: bool = False) -> float:
    grid, gap = ehl_domain(helix_angle_deg, point, n, helix_free)
    speeds = _speeds(surface_speed)
    u = float(speeds.entrainment_B if point == "B" else speeds.entrainment_A)
    return ehl.solve_reynolds(gap, grid, E_STAR, LOAD, u, T1.viscosity, T1.lubricant_density, initial_film=8e-8,
                              coarsest=COARSEST, max_iterations=EHL_ITERATIONS).central_pressure


@scene("sun2021-fig12",
       "sun2021 Sec 4.4, Fig 12: central EHL pressure at A (screw) and B (nut) against screw speed (wang2022 "
       "entrainment) and helix angle, exact helical gap ('non-Hertzian') against the helix-free gap ('Hertzian')",
       kind="low-order", cost_s=5.0)  # cost: 4.5 s wall default at load average 3 (17 s at 10), quick 1.6 s
def sun2021_fig12(run):
    n = {"quick": 32, "default": 64, "fine": 128}[run.fidelity]  # grid 2n x n/2, smooth surfaces
    last, first = paper.HELIX_ANGLES_DEG[-1], paper.HELIX_ANGLES_DEG[0]
    surface_speeds = (0.5, 1.0053, 2.0)  # 300, 600 (Sec 4.3's 1005.3 mm/s), 1194 rpm
    for point in run.progress(POINTS, desc="points"):
        central, time_s = run.time(lambda: [_central_ehl_pressure(last, point, n, s) for s in surface_speeds],
                                   budget_s=0.0, max_repeat=1)
        listing = ", ".join(f"{s * 1e3:.0f} mm/s -> {p / 1e6:.1f} MPa" for s, p in zip(surface_speeds, central))
        run.check(model="lowmodel.contact.ehl",
                  quantity=f"Fig 12: central EHL pressure at {point}, {last} deg, falls with screw speed "
                           "(largest step)",
                  unit="Pa", value=float(max(np.diff(central))), reference=0.0, relation="le", scale=1e6,
                  tolerance=0.0, why=SIGN_TEST, time_s=time_s / 3, source="sun2021 Sec 4.4, Fig 12 (trend)",
                  note="entrainment from wang2022 at each screw speed: " + listing)
        free = _central_ehl_pressure(last, point, n, surface_speeds[1], helix_free=True)
        published = "smaller" if point == "A" else "greater"
        run.check(model="lowmodel.contact.ehl",
                  quantity=f"Fig 12{'a' if point == 'A' else 'b'}: non-Hertzian (exact gap) {published} than "
                           f"Hertzian (helix-free) at {point}, {last} deg, 1005 mm/s: p_exact - p_free",
                  unit="Pa", value=central[1] - free, reference=0.0, relation="le" if point == "A" else "ge",
                  scale=1e6, tolerance=0.0, why=SIGN_TEST, time_s=time_s / 3,
                  source="sun2021 Sec 4.4, Fig 12a,b", note=f"{central[1] / 1e6:.1f} against {free / 1e6:.1f} MPa "
                                                            f"({100 * (central[1] / free - 1):+.2f} %)")
        low = _central_ehl_pressure(first, point, n, surface_speeds[1])
        trend = "decreases" if point == "A" else "increases"
        run.check(model="lowmodel.contact.ehl",
                  quantity=f"Fig 12: central EHL pressure at {point} {trend} with the helix angle, "
                           f"p({last}) - p({first}) at 1005 mm/s",
                  unit="Pa", value=central[1] - low, reference=0.0, relation="le" if point == "A" else "ge",
                  scale=1e6, tolerance=0.0, why=SIGN_TEST, time_s=time_s / 3, source="sun2021 Sec 4.4, Fig 12a,b",
                  note=f"{low / 1e6:.1f} -> {central[1] / 1e6:.1f} MPa")
    run.note(f"Smooth surfaces, eq 1 load, grid {2 * n} x {n // 2}; screw speed Omega' = omega r, entrainment of "
             "wang2022 (u_s = 0.49 Omega'); 'Hertzian' is the helix-free groove (lead 0).")
