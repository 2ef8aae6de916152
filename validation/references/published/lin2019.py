"""Lin, Duan, Okwudire (2019), J. Tribol. 141: the printed results of Tables 1-3 and 5 and Secs 2.3-3.4 (SI).

Inputs: :mod:`ballbench.validation.cases.lin2019`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

PSI = 5.307e-4  # Table 1: Psi [(m^2/N)^(1/3)], printed 5.307e-4 (4 significant figures), derived from Hertz


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
class PrintedScrewCase:
    """lin2019 Table 5 and Sec 3.3: one two-ball case of the ball screw (cases.lin2019.TABLE5)."""

    f_b2b_numerical: float       # N (Table 5, low-order numerical)
    f_b2b_ansys: float           # N (Table 5, ANSYS FEA)
    friction_increase: float     # % (Sec 3.3, low-order numerical, "relative to that before B2B contact")


@dataclass(frozen=True)
class PrintedWholeScrew:
    """lin2019 Sec 3.4 (Figs 20-21): the whole-screw simulation's printed results."""

    occupation: float = 97.8                  # %   "97.8% occupation ratio of the active ball track"
    groups: int = 4                           # [-] "Four groups of ball-to-ball contact form"
    peak_increase: float = 49.6               # %   B2B extra friction torque, maximum
    peak_angle: float = math.radians(126.0)   # rad printed 126 deg nut rotation angle
    zero_angle: float = math.radians(306.0)   # rad printed 306 deg (no B2B contact)


PRINTED = PrintedTwoBallCase()
TABLE5_A = PrintedScrewCase(1.92, 1.80, 39.2)   # case (a), theta 2 deg: 1.92 / 1.80 N, 39.2 %
TABLE5_B = PrintedScrewCase(2.89, 2.71, 60.2)   # case (b), theta 3 deg: 2.89 / 2.71 N, 60.2 %
TABLE5 = {"a": TABLE5_A, "b": TABLE5_B}
WHOLE_SCREW = PrintedWholeScrew()
