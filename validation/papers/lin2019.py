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
