"""Lin, Duan, Okwudire, Wou (2017), IMECE2017-72486: the two case studies of Sec 3 (SI units).

The paper fixes only the contact angles; its maps are normalised by N_y, v and mu (``P_f / (mu_k v N_y)``), so
the loads and speeds below (lin2019 Table 1's guide, :mod:`.lin2019`) drop out of every checked number except
the scale of the unnormalised loss and of omega (through R_B).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.validation.cases.lin2019 import GUIDE, VERTICAL_FORCE


@dataclass(frozen=True)
class CaseStudies:
    """Inputs shared by case studies 1 (Sec 3.2) and 2 (Sec 3.3)."""

    nominal_angle: float = math.pi / 4                       # all nominal contact angles [rad], printed 45 deg
    vertical_force: float = VERTICAL_FORCE                   # N_y [N] ("a fixed N_y")
    ball_radius: float = GUIDE.ball_radius                   # R_B [m]
    friction_coefficient: float = GUIDE.friction_coefficient  # mu_k [-]
    groove_velocity: float = GUIDE.groove_velocity           # v [m/s]
    angle_range: float = math.radians(5.0)                   # |theta|, |alpha| of the checks and maps [rad]


CASES = CaseStudies()


def case1_angles(theta, nominal: float = CASES.nominal_angle):
    """Sec 3.2: beta_BL = beta_BR = 45 deg, beta_TR = 45 deg + theta, beta_TL = 45 deg - theta; (..., 4) [rad]."""
    theta = np.asarray(theta, dtype=float)
    zero = np.zeros_like(theta)
    return nominal + np.stack([zero, zero, theta, -theta], axis=-1)


def case2_angles(alpha, nominal: float = CASES.nominal_angle):
    """Sec 3.3: beta_BL = beta_BR = beta_TL = 45 deg, beta_TR = 45 deg + alpha; (..., 4) [rad]."""
    alpha = np.asarray(alpha, dtype=float)
    zero = np.zeros_like(alpha)
    return nominal + np.stack([zero, zero, alpha, zero], axis=-1)
