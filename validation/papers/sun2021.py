"""Sun, Wang, Gao, Zhao (2021), Appl. Sci. 11, 12081: Table 1 (inputs) and the numbers the text states, SI units.

Table 1 calls the helix angle alpha (papers/README.md); the parameter study
varies it (Sec 4.2).  "Screw radius r = 16 mm" is the ball-centre (pitch)
radius: with the pitch L0 = 10 mm it gives the printed helix angle,
``atan(10 / (2 pi 16)) = 5.68 deg``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class BallScrew:
    """sun2021 Table 1: the double-nut ball screw."""

    pitch_radius: float = 16e-3                   # r [m]          printed "screw radius" 16 mm
    ball_radius: float = 2.9765e-3                # r_b [m]        printed 2.9765 mm
    groove_radius: float = 3.215e-3               # r_S = r_N [m]  printed 3.215 mm (normal section)
    lead: float = 10e-3                           # L0 [m]         printed pitch 10 mm
    helix_angle: float = math.radians(5.68)       # alpha [rad]    printed 5.68 deg
    contact_angle: float = math.radians(40.26)    # beta_0 [rad]   printed 40.26 deg
    preload: float = 1500.0                       # F_pre [N]      printed 1500 N
    screw_speed: float = 83e-3                    # Omega' [m/s]   printed 83 mm/s
    ball_count: int = 168                         # n_bb           printed 168
    youngs_modulus: float = 200e9                 # E1 = E2 [Pa]   printed 200 GPa
    poisson_ratio: float = 0.3                    # nu1 = nu2      printed 0.3
    lubricant_density: float = 970.0              # rho0 [kg/m^3]  printed 970
    viscosity: float = 0.05                       # eta0 [Pa s]    printed 0.05

    @property
    def conformity(self) -> float:
        """``r_S / (2 r_b)`` = 0.5401."""
        return self.groove_radius / (2.0 * self.ball_radius)


TABLE_1 = BallScrew()
HELIX_ANGLES_DEG = (5.68, 13.97, 21.71)           # Sec 4.2, Figs 8, 9, 11-13 (labels as printed)
ENTRAINMENT_SPEED = 1.0053                        # u_s [m/s]  printed 1005.3 mm/s (Sec 4.3, Fig 10)
EHL_HALF_WIDTH = 277e-6                           # [m]  eq 18: x, y in [-277, 277] um
FRACTAL_DIMENSION = 2.47                          # D (Sec 2.3)
FRACTAL_SCALE = 0.41                              # G (Sec 2.3), unit not printed
DRY_FRICTION = 0.1                                # mu_a (Sec 3.2)
MIXED_TO_HYDRODYNAMIC_SPEED = 0.50265             # [m/s]  printed 502.65 mm/s (Sec 3.2, Fig 6)
ASPERITY_STRESS_GAIN_21_71 = {"A": 0.0293, "B": 0.0301}  # Sec 4.4: "2.93 % and 3.01 % more accurate"
# Sec 2.3 leaves the WM sample length, cutoff, gamma, ridges and the unit of G unstated; the choices of the
# sun2021 friction scenes (docs/mixed_lubrication.md): G read in pm (the nm reading is reported beside it)
FRACTAL_SCALE_READINGS = {"pm": 1e-12, "nm": 1e-9}  # [m] per printed unit of G
FRACTAL_SAMPLE_LENGTH = 2 * EHL_HALF_WIDTH        # L [m]: the eq 18 domain, 554 um (choice)
FRACTAL_CUTOFF_LENGTH = 50e-6                     # L_s [m]: resolved by >= 2 cells at every fidelity (choice)
EYRING_STRESS = 5e6                               # tau0 [Pa] of eq 23: unstated (choice, a mineral-oil value)


def screw_speed_to_rpm(surface_speed: float) -> float:
    """sun2021's screw speed Omega' [m/s] (pitch-circle surface speed) in rev/min: 0.50265 m/s is 300 rpm."""
    return surface_speed / TABLE_1.pitch_radius * 60.0 / (2.0 * math.pi)
