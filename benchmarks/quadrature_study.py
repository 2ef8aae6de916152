"""The offset friction's angular quadrature: cost against accuracy (docs/speed.md, 'The offset friction's quadrature').

A measurement study, run by hand (not collected by pytest; nothing in the models changes):

1. ``capture``: one whole-screw run of ``benchmarks/test_bench_screw.py::test_whole_screw_simulation`` (37 balls,
   200 steps) on the numpy path, every call of ``contact.ellipse_friction_offset.friction_offset`` recorded
   (spin_velocity, slip_minor, slip_major, b/a and the tanh-sinh level the screw chose).
2. ``errors``: a sample of the captured contacts (random draw plus the extremes of R_c, b/a and the rim
   distance), the reference integrals at tanh-sinh level 8 (checked against level 9), and the error of each
   candidate angular rule on the same panels: tanh-sinh levels 2-4, Gauss-Legendre with 8-24 nodes per panel,
   and Gauss-Legendre after a sigmoidal change of variable that clusters nodes at the panel ends.  A rule on
   (0, 1) is a table of nodes and weights; ``friction_offset`` reads its table through
   ``ellipse_friction_offset.tanh_sinh``, which this study replaces for the call (the kernels read it through
   ``screw.ball.kernel_tables``), so every candidate runs the same panels and radial closed forms.
3. ``timing``: CPU time per contact of the compiled ``screw.ball_kernels.friction_offset`` with each rule's table.
4. ``screw``: the whole screw (benchmark run, CPU time, torque histories, worst power balance) with the kernels fed
   a candidate table (``kernel_tables`` replaced in this process only) against the current one; ``screw-time``
   alternates the two over several rounds.
5. ``validate``: ``ballbench validate`` of the screw scenes with a candidate table (the scenes' outputs, among them
   lin2019-fig21's).

Run: ``python benchmarks/quadrature_study.py capture|errors|grid|timing|screw|screw-time|validate|all [--rule NAME]
[--data DIR]``.
"""
from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from ballbench.lowmodel.contact import ellipse_friction_offset as efo
from ballbench.lowmodel.quadrature import tanh_sinh

OVERSIZE = 1.6848e-6  # m, benchmarks/test_bench_screw.py (lin2019 Table 5 case a fit)
OUTPUTS = ("force_major", "force_minor", "moment", "loss")
REFERENCE_LEVEL, CHECK_LEVEL = 8, 9


def load_average() -> str:
    return f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}"


# --------------------------------------------------------------------------
# rules on (0, 1)
# --------------------------------------------------------------------------
def gauss(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def sigmoidal(n: int, order: int):
    """Gauss-Legendre in u after x = u^p / (u^p + (1 - u)^p): nodes cluster at both ends (order p)."""
    u, wu = gauss(n)
    a, b = u**order, (1.0 - u) ** order
    x = a / (a + b)
    dx = order * (u * (1.0 - u)) ** (order - 1) / (a + b) ** 2
    return x, wu * dx


def gauss_jacobi(n: int, alpha: float = 0.5):
    """Gauss-Jacobi for the weight ((1 - x) x)^alpha on (0, 1), the weight divided out (a rule for f itself)."""
    from scipy.special import roots_jacobi

    x, w = roots_jacobi(n, alpha, alpha)
    return 0.5 * (x + 1.0), 0.5 * w / (1.0 - x * x) ** alpha


def composite(breaks, counts):
    """Gauss-Legendre on the sub-intervals of (0, 1) between ``breaks``, ``counts`` nodes each."""
    parts = [(a + (b - a) * x, (b - a) * w) for (a, b), n in zip(zip(breaks[:-1], breaks[1:]), counts)
             for x, w in [gauss(n)]]
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


def rules() -> dict:
    """name -> (nodes, weights) on (0, 1)."""
    table = {f"tanh-sinh {level}": tanh_sinh(level) for level in (2, 3, 4)}
    for n in (8, 12, 16, 18, 20, 24):
        table[f"Gauss {n}"] = gauss(n)
    for n in (16, 24):
        table[f"Gauss-Jacobi 1/2 {n}"] = gauss_jacobi(n)
    for n in (16, 24):
        table[f"Gauss {n}, sigmoid 2"] = sigmoidal(n, 2)
    table["Gauss 6+8+6, ends 0.2"] = composite([0.0, 0.2, 0.8, 1.0], [6, 8, 6])
    for nodes, weights in table.values():   # read-only as the tanh-sinh tables: the kernels' argument types, so
        nodes.setflags(write=False)         # a candidate table runs the cached machine code (no recompilation)
        weights.setflags(write=False)
    return table


def with_rule(rule, spin, slip_minor, slip_major, beta):
    """friction_offset with ``rule`` in place of the tanh-sinh table on every panel."""
    saved = efo.tanh_sinh
    efo.tanh_sinh = lambda level: rule
    chunk = max(1, 2_000_000 // rule[0].size)   # bounded memory for the reference levels
    try:
        parts = [efo.friction_offset(spin[i:i + chunk], slip_minor[i:i + chunk], slip_major[i:i + chunk],
                                     beta[i:i + chunk]) for i in range(0, spin.size, chunk)]
    finally:
        efo.tanh_sinh = saved
    return efo.OffsetFriction(*(np.concatenate([getattr(p, f) for p in parts]) for f in (*OUTPUTS, "jacobian")))


def as_array(fr) -> tuple[np.ndarray, np.ndarray]:
    return np.stack([getattr(fr, name) for name in OUTPUTS], axis=-1), fr.jacobian


# --------------------------------------------------------------------------
# 1. capture
# --------------------------------------------------------------------------
def capture(data: Path) -> None:
    from ballbench.lowmodel import kernels
    from ballbench.lowmodel.screw import contacts as screw_contacts
    from ballbench.lowmodel.screw import load_distribution, whole_screw

    records, original = [], efo.friction_offset

    def spy(spin, slip_minor, slip_major, beta, *, level=4):
        records.append(np.stack(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                                      (spin, slip_minor, slip_major, beta, level))), axis=-1))
        return original(spin, slip_minor, slip_major, beta, level=level)

    module = screw_contacts.screw_module(oversize=OVERSIZE)
    stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37)
    kernels.use_kernels(False)
    efo.friction_offset = spy
    start = time.process_time()
    try:
        history = whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness)
    finally:
        efo.friction_offset = original
        kernels.use_kernels(None)
    seconds = time.process_time() - start
    calls = np.array([r.shape[0] for r in records])
    inputs = np.concatenate(records)
    data.mkdir(parents=True, exist_ok=True)
    np.savez(data / "capture.npz", inputs=inputs, calls=calls)
    print(f"capture: {len(records)} calls of friction_offset, {inputs.shape[0]} contacts (median {np.median(calls):.0f}"
          f" per call), {int(history.iterations.sum())} Newton iterations; numpy path {seconds:.1f} s CPU; "
          f"{load_average()}")
    summarise(inputs, calls)


def branches(inputs: np.ndarray):
    spin, un, um, beta = inputs[:, 0], inputs[:, 1], inputs[:, 2], inputs[:, 3]
    scaled = np.hypot(un, um / beta)
    far = scaled >= efo.FAR_CENTRE * np.abs(spin)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa, lam = un / spin, -um / (spin * beta)
    rc = np.hypot(kappa, lam)
    return kappa, lam, beta, rc, far


def summarise(inputs: np.ndarray, calls: np.ndarray) -> None:
    kappa, lam, beta, rc, far = branches(inputs)
    near = ~far
    inside = near & (rc < 1.0)
    outside = near & (rc >= 1.0)
    levels = inputs[:, 4]
    n = inputs.shape[0]
    print(f"contacts {n}: centred R_c < 1 {inside.sum()} ({100 * inside.mean():.1f} %), centred 1 <= R_c < 100 "
          f"{outside.sum()} ({100 * outside.mean():.1f} %), disc (R_c >= 100 or spin 0) {far.sum()} "
          f"({100 * far.mean():.2f} %)")
    for name, v in (("kappa", kappa[near]), ("lam", lam[near]), ("R_c", rc[near]), ("b/a", beta)):
        q = np.percentile(v, [0, 1, 50, 99, 100])
        print(f"  {name:6s} min {q[0]: .4g}  p1 {q[1]: .4g}  median {q[2]: .4g}  p99 {q[3]: .4g}  max {q[4]: .4g}")
    dist = np.abs(1.0 - rc[near])
    print(f"  |1 - R_c| min {dist.min():.3g}, p1 {np.percentile(dist, 1):.3g}; fraction within 1e-2 of the rim "
          f"{np.mean(dist < 1e-2):.4f}, within 1e-3 {np.mean(dist < 1e-3):.4f}")
    nodes = {lv: tanh_sinh(int(lv))[0].size for lv in np.unique(levels)}
    per_contact = np.where(inside, 4, np.where(outside, 2, 0)) * np.vectorize(nodes.get)(levels) \
        + np.where(far, efo.disc_rule()[0].size, 0)
    print(f"  levels used {dict(zip(*np.unique(levels, return_counts=True)))}; nodes per panel {nodes}; nodes per "
          f"contact: inside {4 * nodes.get(3.0, 0)}, outside {2 * nodes.get(3.0, 0)}, disc {efo.disc_rule()[0].size};"
          f" mean {per_contact.mean():.1f}")


# --------------------------------------------------------------------------
# 2. errors
# --------------------------------------------------------------------------
def sample(inputs: np.ndarray, size: int = 2000, seed: int = 2026) -> np.ndarray:
    kappa, lam, beta, rc, far = branches(inputs)
    near = np.flatnonzero(~far)
    rng = np.random.default_rng(seed)
    drawn = rng.choice(near, size=min(size, near.size), replace=False)
    dist = np.abs(1.0 - rc[near])
    extremes = np.concatenate([near[np.argsort(dist)[:50]], near[np.argsort(beta[near])[:20]],
                               near[np.argsort(rc[near])[:20]], near[np.argsort(-rc[near])[:20]]])
    return inputs[np.unique(np.concatenate([drawn, extremes]))]


def relative(values: np.ndarray, jac: np.ndarray, ref: np.ndarray, ref_jac: np.ndarray):
    """Errors per contact: each output against the largest of |force_major|, |force_minor|, |moment| of the
    reference (the scale on which the ball's equilibrium sees them; loss against itself); the Jacobian's rows
    against the largest entry of the reference row (of the whole Jacobian where the row is zero)."""
    scale = np.max(np.abs(ref[:, :3]), axis=1)
    err = np.abs(values - ref)
    out = np.empty_like(err)
    out[:, :3] = err[:, :3] / scale[:, None]
    out[:, 3] = err[:, 3] / np.abs(ref[:, 3])
    row_scale = np.max(np.abs(ref_jac), axis=2)
    row_scale = np.where(row_scale > 0.0, row_scale, np.max(row_scale, axis=1, keepdims=True))  # a zero row
    jerr = np.max(np.abs(jac - ref_jac), axis=2) / row_scale
    return out, np.max(jerr, axis=1)


def errors(data: Path) -> None:
    saved = np.load(data / "capture.npz")
    inputs = sample(saved["inputs"])
    spin, un, um, beta = (inputs[:, j] for j in range(4))
    kappa, lam, _, rc, _ = branches(inputs)
    inside = rc < 1.0
    print(f"sample: {inputs.shape[0]} contacts ({inside.sum()} with R_c < 1), b/a {beta.min():.3f}-{beta.max():.3f}")
    ref, ref_jac = as_array(with_rule(tanh_sinh(REFERENCE_LEVEL), spin, un, um, beta))
    chk, chk_jac = as_array(with_rule(tanh_sinh(CHECK_LEVEL), spin, un, um, beta))
    e, ej = relative(chk, chk_jac, ref, ref_jac)
    print(f"reference level {REFERENCE_LEVEL} against level {CHECK_LEVEL}: outputs {e.max():.2e}, Jacobian "
          f"{ej.max():.2e}")
    rows = []
    for name, rule in rules().items():
        values, jac = as_array(with_rule(rule, spin, un, um, beta))
        e, ej = relative(values, jac, ref, ref_jac)
        nodes = rule[0].size
        worst = np.max(e, axis=1)
        rows.append((name, 4 * nodes, 2 * nodes, *np.max(e, axis=0), *np.percentile(e, 99, axis=0),
                     ej.max(), np.percentile(ej, 99), worst[inside].max(), worst[~inside].max()))
    header = ("rule", "nodes in", "nodes out", *(f"max {o}" for o in OUTPUTS), *(f"p99 {o}" for o in OUTPUTS),
              "max jac", "p99 jac", "max R_c<1", "max R_c>=1")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print(f"| {row[0]} | {row[1]} | {row[2]} | " + " | ".join(f"{v:.1e}" for v in row[3:]) + " |")
    np.savez(data / "errors.npz", sample=inputs)


def grid(data: Path, names=("tanh-sinh 3", "tanh-sinh 4", "Gauss 16", "Gauss 18", "Gauss 20", "Gauss 24")) -> None:
    """Beyond the screw's inputs: velocity centres at R_c from 0 to 50 in 72 directions for b/a 0.05-1."""
    radii = np.array([0.0, 0.5, 0.9, 0.99, 0.999, 1.0, 1.001, 1.01, 1.02, 1.05, 1.1, 1.2, 1.5, 2.0, 5.0, 10.0, 50.0])
    angles = np.linspace(0.0, 2.0 * math.pi, 72, endpoint=False) + 0.05
    betas = np.array([0.05, 0.1, 0.2, 0.25, 0.5, 1.0])
    rc, ang, beta = (v.ravel() for v in np.meshgrid(radii, angles, betas, indexing="ij"))
    kappa, lam = rc * np.cos(ang), rc * np.sin(ang)
    spin, un, um = np.ones_like(rc), kappa, -beta * lam
    ref, ref_jac = as_array(with_rule(tanh_sinh(REFERENCE_LEVEL), spin, un, um, beta))
    table = rules()
    worst = {}
    for name in names:
        values, jac = as_array(with_rule(table[name], spin, un, um, beta))
        e, ej = relative(values, jac, ref, ref_jac)
        worst[name] = (e.max(axis=1), ej)
    print(f"grid: {rc.size} velocity centres (R_c {radii.tolist()}, 72 directions, b/a {betas.tolist()}); errors "
          "against tanh-sinh level 8")
    print("b/a 0.2 and 0.25 (the screw's coarse level), worst over the directions: outputs / Jacobian")
    header = ["rule", *(f"R_c {r:g}" for r in radii)]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    coarse = (beta == 0.2) | (beta == 0.25)
    for name, (e, ej) in worst.items():
        cells = [f"{e[coarse & (rc == r)].max():.0e} / {ej[coarse & (rc == r)].max():.0e}" for r in radii]
        print(f"| {name} | " + " | ".join(cells) + " |")
    print("every R_c and direction, worst per b/a: outputs / Jacobian")
    header = ["rule", *(f"b/a {b:g}" for b in betas)]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for name, (e, ej) in worst.items():
        print(f"| {name} | " + " | ".join(f"{e[beta == b].max():.0e} / {ej[beta == b].max():.0e}" for b in betas)
              + " |")


# --------------------------------------------------------------------------
# 3. timing of the compiled contact
# --------------------------------------------------------------------------
def timing(data: Path, names=None, repeats: int = 7) -> None:
    import numba

    from ballbench.lowmodel import kernels
    from ballbench.lowmodel.screw import ball as screw_ball

    kernels.load(screw_ball.KERNELS)
    from ballbench.lowmodel.screw import ball_kernels as bk

    @numba.njit(cache=False)
    def run(inputs, nodes, weights, disc_t, disc_s, disc_w, far_centre):
        out = np.empty(4)
        jac = np.empty((4, 3))
        sums = np.empty(6)
        total = 0.0
        for i in range(inputs.shape[0]):
            bk.friction_offset(inputs[i, 0], inputs[i, 1], inputs[i, 2], inputs[i, 3], nodes, weights, disc_t,
                               disc_s, disc_w, far_centre, out, jac, sums)
            total += out[0] + jac[2, 1]
        return total

    inputs = np.load(data / "capture.npz")["inputs"]
    _, _, _, _, far = branches(inputs)
    near = np.ascontiguousarray(inputs[~far, :4])
    disc = efo.disc_rule()
    table = rules()
    names = names or ["tanh-sinh 2", "tanh-sinh 3", "tanh-sinh 4", "Gauss 16", "Gauss 18", "Gauss 20", "Gauss 24"]
    print(f"timing: {near.shape[0]} captured contacts (centred branches), best of {repeats} interleaved rounds; "
          f"{load_average()}")
    tables = {name: tuple(np.ascontiguousarray(v) for v in (gauss(1) if name == "Gauss 1" else table[name]))
              for name in ["Gauss 1", *names]}
    best = dict.fromkeys(tables, math.inf)
    for nodes, weights in tables.values():
        run(near[:10], nodes, weights, *disc, efo.FAR_CENTRE)
    for _ in range(repeats):
        for name, (nodes, weights) in tables.items():
            start = time.process_time()
            run(near, nodes, weights, *disc, efo.FAR_CENTRE)
            best[name] = min(best[name], time.process_time() - start)
    for name, (nodes, _) in tables.items():
        per = best[name] / near.shape[0]
        print(f"  {name:24s} {nodes.size:3d} nodes per panel: {per * 1e6:7.2f} us per contact, "
              f"{per * 148 * 1e3:.3f} ms per ring evaluation (148 contacts)")
    print(f"  ({load_average()})")


# --------------------------------------------------------------------------
# 4. the whole screw with a candidate table
# --------------------------------------------------------------------------
def _screw_setting(name: str):
    """The benchmark's module and stiffness table, the kernels' current node tables and ``name``'s in their place."""
    from ballbench.lowmodel.screw import ball as screw_ball
    from ballbench.lowmodel.screw import contacts as screw_contacts
    from ballbench.lowmodel.screw import load_distribution

    current = screw_ball.kernel_tables()
    rule = rules()[name]
    module = screw_contacts.screw_module(oversize=OVERSIZE)
    stiffness = load_distribution.axial_stiffness(module, 3.0 * 1500.0 / 37)
    return module, stiffness, current, (current[0], *rule, *rule, *current[5:])


def screw(data: Path, name: str) -> None:
    """The benchmark's whole screw with the current table and ``name``'s: CPU time, iterations, the torque histories
    and the worst power balance (the scenes' outputs: the ``validate`` stage)."""
    import json

    from ballbench.lowmodel.screw import ball as screw_ball
    from ballbench.lowmodel.screw import whole_screw

    current_function = screw_ball.kernel_tables
    module, stiffness, current, candidate = _screw_setting(name)
    results = {}
    whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness, steps=3)   # load the kernels
    for label, tables in (("current", current), (name, candidate), ("current again", current)):
        screw_ball.kernel_tables = lambda tables=tables: tables
        start = time.process_time()
        history = whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness)
        bench = time.process_time() - start
        results[label] = dict(bench_s=bench, iterations=int(history.iterations.sum()),
                              power=float(history.power_error.max()), b2b_torque=history.b2b_torque.tolist(),
                              groove_torque=history.groove_torque.tolist())
        print(f"{label:16s} benchmark run {bench:.2f} s CPU ({results[label]['iterations']} iterations), worst power "
              f"balance {results[label]['power']:.6e}; {load_average()}")
    screw_ball.kernel_tables = current_function
    a, b = results["current"], results[name]
    print(f"  power: {a['power']:.15g} -> {b['power']:.15g} (relative {abs(b['power'] - a['power']) / a['power']:.2e})")
    for key in ("b2b_torque", "groove_torque"):
        x, y = np.array(a[key]), np.array(b[key])
        print(f"  {key} history: largest difference {np.max(np.abs(x - y)):.3e} against largest value "
              f"{np.max(np.abs(x)):.3e}")
    (data / f"screw {name}.json").write_text(json.dumps(results))


def screw_time(data: Path, name: str, rounds: int = 6) -> None:
    """The benchmark's whole-screw run, CPU time, the current table and ``name``'s alternating in one process."""
    from ballbench.lowmodel.screw import ball as screw_ball
    from ballbench.lowmodel.screw import whole_screw

    current_function = screw_ball.kernel_tables
    module, stiffness, current, candidate = _screw_setting(name)
    seconds = {"current": [], name: []}
    print(f"whole screw (37 balls, 200 steps), CPU s, {rounds} alternating rounds; {load_average()}")
    for tables in (current, candidate):   # load the kernels for both argument sets outside the timing
        screw_ball.kernel_tables = lambda tables=tables: tables
        whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness, steps=3)
    for _ in range(rounds):
        for label, tables in (("current", current), (name, candidate)):
            screw_ball.kernel_tables = lambda tables=tables: tables
            start = time.process_time()
            whole_screw.simulate(module, amplitude=math.radians(3.0), stiffness=stiffness)
            seconds[label].append(time.process_time() - start)
    screw_ball.kernel_tables = current_function
    for label, values in seconds.items():
        print(f"  {label:12s} " + ", ".join(f"{v:.2f}" for v in values) + f" (median {np.median(values):.2f})")
    print(f"  ({load_average()})")


SCREW_SCENES = ("lin2019-table5-a", "lin2019-table5-b", "lin2019-fig21", "lin2019-screw-stability", "wang2022-*",
                "calibration-effect-screw")


def validate(data: Path, name: str) -> None:
    """``ballbench validate`` of the screw scenes (default level) in this process, the kernels fed ``name``'s table
    (or the current one for ``current``); report in ``data / 'validate <name>'``."""
    from ballbench.lowmodel.screw import ball as screw_ball
    from ballbench.validation import cli

    if name != "current":
        current = screw_ball.kernel_tables()
        rule = rules()[name]
        candidate = (current[0], *rule, *rule, *current[5:])
        screw_ball.kernel_tables = lambda: candidate
    start = time.process_time()
    code = cli.main(["validate", "--no-progress", "--out", str(data / f"validate {name}"), *SCREW_SCENES])
    print(f"validate with {name}: exit {code}, {time.process_time() - start:.1f} s CPU; {load_average()}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("stage",
                        choices=("capture", "errors", "grid", "timing", "screw", "screw-time", "validate", "all"))
    parser.add_argument("--data", type=Path, default=Path("/tmp/quadrature_study"))
    parser.add_argument("--rule", default="Gauss 24",
                        help="candidate of the screw and validate stages (validate: 'current': the tables as they are)")
    args = parser.parse_args()
    if args.stage in ("capture", "all"):
        capture(args.data)
    if args.stage in ("errors", "all"):
        errors(args.data)
    if args.stage in ("grid", "all"):
        grid(args.data)
    if args.stage in ("timing", "all"):
        timing(args.data)
    if args.stage in ("screw", "all"):
        screw(args.data, args.rule)
    if args.stage in ("screw-time", "all"):
        screw_time(args.data, args.rule)
    if args.stage == "validate":
        validate(args.data, args.rule)


if __name__ == "__main__":
    main()
