"""Sun, Wang, Gao, Zhao (2021), Appl. Sci. 11, 12081: the double-nut ball screw of Table 1 and the inputs of the
parameter studies (Secs 2.3, 3.2, 4.2-4.4), SI units.

Table 1 calls the helix angle alpha (papers/README.md); the parameter study varies it (Sec 4.2).
"Screw radius r = 16 mm" is the ball-centre (pitch) radius: with the pitch L0 = 10 mm it gives the printed helix
angle, ``atan(10 / (2 pi 16)) = 5.68 deg``.  The printed results are references
(:mod:`ballbench.validation.references.published.sun2021`).
"""
from __future__ import annotations

import math

from ballbench.lowmodel.bearing import BallScrew, Lubricant, Material
from ballbench.validation.cases.case import MeshLevels, PairLevel

STEEL = Material(youngs_modulus=200e9,  # E1 = E2 [Pa]   printed 200 GPa
                 poisson_ratio=0.3)     # nu1 = nu2      printed 0.3
OIL = Lubricant(viscosity=0.05,         # eta0 [Pa s]    printed 0.05
                density=970.0)          # rho0 [kg/m^3]  printed 970
BALL_RADIUS = 2.9765e-3                 # r_b [m]        printed 2.9765 mm
GROOVE_RADIUS = 3.215e-3                # r_S = r_N [m]  printed 3.215 mm (normal section)
PITCH_RADIUS = 16e-3                    # r [m]          printed "screw radius" 16 mm
SURFACE_SPEED = 83e-3                   # Omega' [m/s]   printed screw speed 83 mm/s (pitch-circle surface speed)
HELIX_ANGLE = math.radians(5.68)        # alpha [rad]    printed 5.68 deg (eq 1 and eq 20 take the printed value)
SCREW = BallScrew(ball_radius=BALL_RADIUS,
                  pitch_radius=PITCH_RADIUS,
                  lead=10e-3,                             # L0 [m]         printed pitch 10 mm
                  nominal_angle=math.radians(40.26),     # beta_0 [rad]   printed 40.26 deg
                  conformity=GROOVE_RADIUS / (2.0 * BALL_RADIUS),  # r_S / (2 r_b) = 0.5401
                  material=STEEL,
                  screw_speed=SURFACE_SPEED / PITCH_RADIUS,  # [rad/s]
                  ball_count=168,                        # n_bb           printed 168
                  preload=1500.0,                        # F_pre [N]      printed 1500 N
                  lubricant=OIL)

HELIX_ANGLES_DEG = (5.68, 13.97, 21.71)           # Sec 4.2, Figs 8, 9, 11-13 (labels as printed)
ENTRAINMENT_SPEED = 1.0053                        # u_s [m/s]  printed 1005.3 mm/s (Sec 4.3, Fig 10)
EHL_HALF_WIDTH = 277e-6                           # [m]  eq 18: x, y in [-277, 277] um
FRACTAL_DIMENSION = 2.47                          # D (Sec 2.3)
FRACTAL_SCALE = 0.41                              # G (Sec 2.3), unit not printed
DRY_FRICTION = 0.1                                # mu_a (Sec 3.2)
# Sec 2.3 leaves the WM sample length, cutoff, gamma, ridges and the unit of G unstated; the choices of the
# sun2021 friction scenes (docs/mixed_lubrication.md): G read in pm (the nm reading is reported beside it)
FRACTAL_SCALE_READINGS = {"pm": 1e-12, "nm": 1e-9}  # [m] per printed unit of G
FRACTAL_SAMPLE_LENGTH = 2 * EHL_HALF_WIDTH        # L [m]: the eq 18 domain, 554 um (choice)
FRACTAL_CUTOFF_LENGTH = 50e-6                     # L_s [m]: resolved by >= 2 cells at every fidelity (choice)
EYRING_STRESS = 5e6                               # tau0 [Pa] of eq 23: unstated (choice, a mineral-oil value)


def screw_speed_to_rpm(surface_speed: float) -> float:
    """sun2021's screw speed Omega' [m/s] (pitch-circle surface speed) in rev/min: 0.50265 m/s is 300 rpm."""
    return surface_speed / PITCH_RADIUS * 60.0 / (2.0 * math.pi)

# FE of the contact at points A (screw) and B (nut), 21.71 deg (studies.sun2021.fe_contact): levels (n = b / h_contact,
# growth away from the fine zone) as the Table 4 screw pair of cases.lin2019; the concave nut block's z window holds
# ball nodes beside the block, which fem.surface.locate_along_z leaves out of the candidate set.  B's quick level is
# coarser, for the quick time budget (docs/halfspace.md, "FE against BEM").
FE_LEVELS = {
    "A": MeshLevels(quick=(PairLevel(5.5, 1.6),), default=(PairLevel(6.0, 1.45),),
                    fine=(PairLevel(5.5, 1.6), PairLevel(6.0, 1.45), PairLevel(6.5, 1.4))),
    "B": MeshLevels(quick=(PairLevel(5.0, 1.8),), default=(PairLevel(6.0, 1.45),),
                    fine=(PairLevel(5.5, 1.6), PairLevel(6.0, 1.45), PairLevel(6.5, 1.4))),
}
FE_GAP_LIMIT = 1.05  # candidate zone: exact meshed gap <= 1.05 delta_Hertz (the largest gap in contact ~0.7 delta)
