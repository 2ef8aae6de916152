"""The synthetic round trip of the calibration fits.

:func:`synthetic_truth`, :func:`synthetic_fit`, :func:`coverage`: data drawn from known constants plus noise (the
``calibration-roundtrip`` scene and tests/validation/studies/test_calibration_roundtrip.py): the fits of
lowmodel.calibration recover them within their intervals, as often as the intervals claim.  The contact laws
calibrated on FE are :func:`.fe_laws.contact_law` (a case) and :func:`.fe_laws.fe_contact_law` (a scene's case).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ballbench.lowmodel import calibration as cal
from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases import lin2019
from ballbench.validation.studies.calibration.spec import read_friction_csv

__all__ = ["synthetic_truth", "synthetic_fit", "coverage", "LOADS", "NOISE_U", "NOISE_A", "NOISE_F",
           "BULK", "MU_0", "MU_V", "K_F"]

# the synthetic truth: Hertz C and Psi of lin2019 Table 1's 0.56 groove, a bulk compliance of the order FE
# finds, a friction coefficient with a speed dependence and lin2019's k_f (Sec 2.3.2)
BULK = 2e-11  # m/N
MU_0, MU_V = 0.1, 0.5  # 1, s/m
K_F = 1.38  # lin2019 Sec 2.3.2 (references.published.lin2019.PRINTED.k_f; a test checks they agree)
LOADS = np.linspace(25.0, 150.0, 9)  # N
NOISE_U = 2e-9  # m (0.07 % of U at 150 N)
NOISE_A = 0.003  # relative, contact size
NOISE_F = 0.02  # N, friction force


def synthetic_truth() -> dict:
    """The constants the synthetic data are drawn from (SI units)."""
    guide = lin2019.GUIDE
    geometry = hertz.groove_geometry(guide)
    return {"hertz_constant": hertz.hertz_constant(geometry), "bulk_compliance": BULK,
            "psi": hertz.psi_constant(geometry, guide.ball_radius), "mu": MU_0, "mu_speed_slope": MU_V, "k_f": K_F}


def synthetic_fit(seed: int, truth: dict, work: Path | None = None, confidence: float = 0.95) -> dict:
    """Fit every constant to synthetic data of ``seed``; returns ``{name: Constant}``.

    With ``work`` the friction data go through a CSV file (units N and mm/s, read back by
    :func:`.spec.read_friction_csv`).
    """
    radius = lin2019.GUIDE.ball_radius
    rng = np.random.default_rng(seed)
    approach = truth["hertz_constant"] * LOADS ** (2 / 3) + truth["bulk_compliance"] * LOADS  # lin2019 eq 53 + C_b F
    approach = approach + rng.normal(0.0, NOISE_U, LOADS.size)
    semi_axis = truth["psi"] * radius ** (1 / 3) * LOADS ** (1 / 3) * (1 + rng.normal(0.0, NOISE_A, LOADS.size))
    law = cal.fit_contact_law(LOADS, approach, semi_axes=semi_axis, ball_radius=radius, confidence=confidence,
                              source=f"synthetic, seed {seed}")
    normal = np.repeat([20.0, 60.0, 120.0, 200.0], 3)  # N
    speed = np.tile([0.01, 0.05, 0.1], 4)  # m/s
    friction = (truth["mu"] + truth["mu_speed_slope"] * speed) * normal + rng.normal(0.0, NOISE_F, normal.size)
    if work is not None:
        path = work / f"friction-{seed}.csv"
        lines = ["# synthetic friction data (calibration-roundtrip)",
                 "normal_force [N],friction_force [N],speed [mm/s]"]
        lines += [f"{float(n)!r},{float(f)!r},{float(v) * 1e3!r}" for n, f, v in zip(normal, friction, speed)]
        path.write_text("\n".join(lines) + "\n")
        data = read_friction_csv(path)
        normal, friction, speed = data["normal_force"], data["friction_force"], data["speed"]
    mu = cal.fit_friction_coefficient(normal, friction, speed, confidence=confidence)
    kappa = np.linspace(-0.5, 0.5, 21)
    k_f = cal.fit_line_through_origin(kappa, -truth["k_f"] * kappa + rng.normal(0.0, 0.01, kappa.size),
                                      confidence=confidence)
    return {**law.constants(), **mu, "k_f": k_f}


def coverage(seeds, truth: dict, confidence: float = 0.95) -> dict:
    """Share of ``seeds`` whose interval covers the truth, per constant."""
    hits = {name: 0 for name in truth}
    for seed in seeds:
        for name, constant in synthetic_fit(int(seed), truth, confidence=confidence).items():
            hits[name] += constant.covers(truth[name])
    return {name: count / len(seeds) for name, count in hits.items()}
