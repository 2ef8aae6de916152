"""Lin, Duan, Okwudire (2019), J. Tribol. 141: Tables 1-5 and the Sec 2.4 case study (SI units).

Printed values and units are in the comments; papers/README.md lists the
known defects of the extracted text (Table 2 columns merged, Table 4's
"210 N/mm^2").
"""
from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class LinearBearing:
    """lin2019 Table 1: parameters of the linear ball bearing case studies."""

    ball_radius: float = 5e-3            # R_B [m]          printed 5 mm
    conformity: float = 0.56             # conf. [-]        printed 0.56
    psi: float = 5.307e-4                # Psi [(m^2/N)^(1/3)], printed 5.307e-4 (4 significant figures)
    vertical_force: float = 100.0        # N_y [N]          printed 100 N
    groove_velocity: float = 10e-3       # v [m/s]          printed 10 mm/s
    friction_coefficient: float = 0.1    # mu [-]           printed 0.1
    youngs_modulus: float = 2.1e11       # E [Pa]           printed 2.1e11 N/m^2
    poisson_ratio: float = 0.28          # nu [-]           printed 0.28

    @property
    def material(self) -> dict[str, float]:
        """``youngs_modulus`` and ``poisson_ratio`` as keyword arguments (the Hertz constructors take them)."""
        return {"youngs_modulus": self.youngs_modulus, "poisson_ratio": self.poisson_ratio}


@dataclass(frozen=True)
class CaseStudy:
    """lin2019 Sec 2.4 (Fig 7) and the Tables 2-3 case: beta_BL = beta_0 - theta, beta_BR = beta_0 + theta."""

    nominal_angle: float = math.pi / 4          # beta_0 [rad]  printed 45 deg
    theta: float = math.radians(2.0)            # contact angle deviation [rad], printed 2 deg
    side_force_ratio: float = -0.6              # rho = N_x / N_y [-], printed -0.6


@dataclass(frozen=True)
class PrintedTwoBallCase:
    """lin2019 Tables 2 and 3, case (a) (theta = 2 deg, rho = -0.6), and Sec 2.4.1's worst case."""

    epsilon_1_numerical: float = 0.87    # % (Table 2, low-order numerical; 2 decimals)
    epsilon_analytical: float = 0.75     # % (Table 2, analytical eq 33: epsilon_1 = -epsilon_2; 2 decimals)
    f_b2b_numerical: float = 4.01        # N (Table 3, low-order numerical)
    f_b2b_ansys: float = 3.96            # N (Table 3, ANSYS FEA)
    f_b2b_analytical: float = 3.74       # N (Table 3, analytical formula eq 30)
    worst_friction_increase: float = 185.2  # % ("more than 185.2 %", Sec 2.4.1 / Fig 9(c))
    k_f: float = 1.38                    # [-] (Sec 2.3.2, read off Fig 5)


@dataclass(frozen=True)
class BallScrew:
    """lin2019 Table 4: parameters of the ball-screw B2B simulation."""

    ball_radius: float = 2.778e-3                 # R_B [m]       printed 2.778 mm
    conformity: float = 0.56                      # conf. [-]     printed 0.56
    pitch_radius: float = 16.5e-3                 # R_P [m]       printed 16.5 mm
    lead: float = 20e-3                           # p [m]         printed 20 mm
    nominal_angle: float = math.radians(45.0)     # beta_0 [rad]  printed 45 deg
    nut_angular_velocity: float = 2 * math.pi     # omega_N [rad/s], printed 2 pi rad/s
    friction_coefficient: float = 0.1             # mu [-]
    youngs_modulus: float = 2.1e11                # E [Pa]: printed "210 N/mm^2", a typo for 210 GPa (papers/README)
    poisson_ratio: float = 0.28                   # nu [-]

    @property
    def material(self) -> dict[str, float]:
        return {"youngs_modulus": self.youngs_modulus, "poisson_ratio": self.poisson_ratio}


TABLE1 = LinearBearing()
CASE = CaseStudy()
PRINTED = PrintedTwoBallCase()
TABLE4 = BallScrew()


@dataclass(frozen=True)
class PrintedScrewCase:
    """lin2019 Table 5 and Sec 3.3: one two-ball case of the ball screw (ball 1 theta = 0, ball 2 theta)."""

    theta: float                 # contact angle deviation of ball 2 on the screw side [rad]
    f_b2b_numerical: float       # N (Table 5, low-order numerical)
    f_b2b_ansys: float           # N (Table 5, ANSYS FEA)
    friction_increase: float     # % (Sec 3.3, low-order numerical, "relative to that before B2B contact")


@dataclass(frozen=True)
class PrintedWholeScrew:
    """lin2019 Sec 3.4 (Figs 19-21): the whole-screw simulation, inputs and printed results."""

    screw_length: float = 0.8                 # m          printed 800 mm
    n_balls: int = 37                         # [-]        "37 balls in two loaded turns"
    loaded_turns: int = 2                     # [-]
    occupation: float = 97.8                  # %          "97.8% occupation ratio of the active ball track"
    axial_load: float = 1500.0                # N          printed 1500 N
    duration: float = 2.0                     # s          "2 s in 200 steps"
    steps: int = 200                          # [-]
    theta_cycles: int = 4                     # [-]        four cycles over the two turns (Fig 19 missing)
    groups: int = 4                           # [-]        "Four groups of ball-to-ball contact form"
    peak_increase: float = 49.6               # %          B2B extra friction torque, maximum
    peak_angle: float = math.radians(126.0)   # rad        printed 126 deg nut rotation angle
    zero_angle: float = math.radians(306.0)   # rad        printed 306 deg (no B2B contact)
    axial_load_two_ball: float = 50.0         # N          Sec 3.3 two-ball module, on the screw


TABLE5_A = PrintedScrewCase(math.radians(2.0), 1.92, 1.80, 39.2)   # case (a): printed 2 deg, 1.92 / 1.80 N, 39.2 %
TABLE5_B = PrintedScrewCase(math.radians(3.0), 2.89, 2.71, 60.2)   # case (b): printed 3 deg, 2.89 / 2.71 N, 60.2 %
WHOLE_SCREW = PrintedWholeScrew()
