"""Wang, Chen, Lu, Lv (2022), Machines 10, 203: the printed results of Tables 1 and 2 and Table A1's lead angle.

Inputs: :mod:`ballbench.validation.cases.wang2022`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType

HALF_UNIT = 0.0005          # Tables 1-2 print 3 decimals
LEAD_ANGLE = math.radians(8.74)  # Table A1: psi [rad], printed 8.74 deg (arctan(L / 2 pi r_m) = 8.742 deg)


@dataclass(frozen=True)
class BearingTable1:
    """wang2022 Table 1: deep-groove ball bearing 61830, inner ring at 3600 rpm, lead 0 (printed results in m/s)."""

    present: float = 15.994                       # U_A = U_B of the present model and Harris [m/s]
    wei_U_A: float = 7.971                        # [m/s]
    wei_U_B: float = 22.740                       # [m/s]
    wei_S_A: float = 2.000                        # [-]
    wei_S_B: float = 0.701                        # [-]


def _present_vectors():
    # (symbol, attribute of lowmodel.screw.kinematics' result): (t, n, b) [m/s]
    return {
        ("V_An^a", "nut_velocity"): (-0.101, 0.000, -0.659),
        ("V_Bs^a", "screw_velocity"): (3.820, 0.071, -0.587),
        ("V_Ab^a", "ball_velocity_nut"): (-0.056, -0.032, -0.691),
        ("V_Bb^a", "ball_velocity_screw"): (3.764, 0.032, -0.627),
        ("V_SA", "sliding_velocity_nut"): (0.045, -0.032, -0.032),
        ("V_SB", "sliding_velocity_screw"): (0.056, 0.040, 0.040),
    }


def _present_scalars():
    return {("U_A", "entrainment_nut", "m/s"): 2.140, ("U_B", "entrainment_screw", "m/s"): 2.146,
            ("S_A", "slide_roll_nut", "1"): 0.030, ("S_B", "slide_roll_screw", "1"): 0.037}


def _wei_vectors():
    return {"V_An^a": (-0.101, 0.000, -0.659), "V_Bs^a": (3.820, -0.071, -0.587),
            "V_Ab^a": (1.789, 0.000, -0.659), "V_Bb^a": (1.919, 0.000, -0.659),
            "V_SA": (1.890, 0.000, 0.000), "V_SB": (1.901, -0.072, 0.072)}


def _wei_scalars():
    return {"U_A": 1.071, "U_B": 2.937, "S_A": 1.766, "S_B": 0.648}


@dataclass(frozen=True)
class ScrewTable2:
    """wang2022 Table 2 at the Table A1 inputs: Frenet components (t, n, b) [m/s] and scalars, as printed.

    Wei's vectors are also the inputs of the Wei-measure checks (eqs 1-6 applied to them).
    """

    present_vectors: MappingProxyType = field(default_factory=lambda: MappingProxyType(_present_vectors()))
    present_scalars: MappingProxyType = field(default_factory=lambda: MappingProxyType(_present_scalars()))
    wei_vectors: MappingProxyType = field(default_factory=lambda: MappingProxyType(_wei_vectors()))
    wei_scalars: MappingProxyType = field(default_factory=lambda: MappingProxyType(_wei_scalars()))


TABLE1 = BearingTable1()
TABLE2 = ScrewTable2()
