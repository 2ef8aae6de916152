"""Sun, Wang, Gao, Zhao (2021), Appl. Sci. 11, 12081: the numbers the text states (SI).

Inputs: :mod:`ballbench.validation.cases.sun2021`.
"""
from __future__ import annotations

MIXED_TO_HYDRODYNAMIC_SPEED = 0.50265             # [m/s]  printed 502.65 mm/s (Sec 3.2, Fig 6)
ASPERITY_STRESS_GAIN_21_71 = {"A": 0.0293, "B": 0.0301}  # Sec 4.4: "2.93 % and 3.01 % more accurate"
