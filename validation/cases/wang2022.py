"""Wang, Chen, Lu, Lv (2022), Machines 10, 203: the ball screw of Table A1 and the bearing of Table 1, SI units.

wang2022's nomenclature calls r_b and r_m "diameters"; its equations and Table 2 use them as radii
(papers/README.md): ``pitch_radius = d_m / 2``, ``ball_radius = d_b / 2``.  The printed results
are references (:mod:`ballbench.validation.references.published.wang2022`).
"""
from __future__ import annotations

import math

from ballbench.lowmodel.bearing import BallScrew

RPM = 2.0 * math.pi / 60.0  # rad/s per rpm

SCREW = BallScrew(ball_radius=6.35e-3 / 2,              # r_b [m]       printed d_b = 6.35 mm
                  pitch_radius=41.4e-3 / 2,             # r_m [m]       printed d_m = 41.4 mm
                  lead=20e-3,                           # L [m]         printed 20 mm
                  nominal_angle=math.radians(45.0),     # alpha [rad]   printed 45 deg
                  screw_speed=2000 * RPM,               # omega [rad/s] printed 2000 rpm
                  ball_mass=1.05e-3,                    # m [kg]        printed 1.05 g
                  ball_count=52)                        # N             printed 52

# Table 1: deep-groove ball bearing 61830, inner ring driven, lead 0
BEARING_INNER_RING_SPEED = 3600 * RPM                   # [rad/s]  printed 3600 rpm
BEARING_CONTACT_ANGLE = math.pi / 4                     # alpha_i = alpha_o [rad] (Sec 3.1)
