"""References for rolling and shifted contact with stick and slip, computed without the rolling solver.

Nothing here calls ``ballbench.lowmodel``.  Closed forms and published numbers:

* Carter (1926) steady rolling of two elastic cylinders (plane strain), Johnson (1985) Sec 8.2 eqs 8.26-8.30:
  with ``kappa = xi G / (2 (1 - nu) mu p0)`` (``G``, ``nu`` combined, ``p0`` the Hertz peak) the stick zone
  ``[a - 2a', a]`` at the leading edge has ``a'/a = 1 - kappa``; ``Q/(mu P) = 1 - (a'/a)^2``; the traction
  ``q = -sign(xi) mu p0 (sqrt(1 - x^2/a^2) - (a'/a) sqrt(1 - (x - a + a')^2/a'^2))`` (second term in the stick
  zone only); full slip for ``kappa >= 1``.  The form ``xi R/(mu a) = 1 - sqrt(1 - Q/(mu P))`` is the
  same with ``p0 = a G/(2 (1 - nu) R)`` (2D Hertz, quasi-identical bodies).
* Cattaneo (1938) and Mindlin (1949), Johnson (1985) Sec 7.1 eqs 7.38-7.42: a Hertz circle shifted
  tangentially from the unloaded state; stick radius ``c = a (1 - Q/(mu P))^(1/3)``; shift of the bodies
  ``delta = 3 mu P (2 - nu)/(8 G a) (1 - (1 - Q/(mu P))^(2/3))`` (two bodies, combined ``G``, ``nu``).  Exact for
  ``nu = 0``; for ``nu != 0`` Mindlin's traction leaves a small lateral slip (Johnson Sec 7.1).
* Kalker's creepage coefficients of the linear theory, Kalker (1990) Table E.3 (also in CONTACT,
  src/m_hertz.f90), nine entries.
* CONTACT's creep-force curve example ``tractcurv`` (examples/tractcurv.inp and its stored output
  examples/tractcurv.ref_out, first series: 'original Kalker theory', Coulomb friction), github eve70a/CONTACT.
"""
from __future__ import annotations

import math

import numpy as np

# Kalker (1990), Table E.3, Poisson's ratio 0.25, a along the rolling direction: {a/b: (C11, C22, C23)}
KALKER_TABLE_E3_NU_025 = {1.0: (4.12, 3.67, 1.47), 0.5: (3.62, 3.01, 0.929), 0.2: (3.37, 2.63, 0.603)}
KALKER_SOURCE = "Kalker (1990) Three-dimensional elastic bodies in rolling contact, Table E.3"


# CONTACT examples/tractcurv.inp (first series) and examples/tractcurv.ref_out (FX/FSTAT/FN)
TRACTCURV_INPUT = {
    "normal_force": 106.7e3,          # FN 106700 N
    "friction_coefficient": 0.33,     # FSTAT = FKIN = 0.33
    "poisson_ratio": 0.28,            # POISS 1, 2
    "shear_modulus": 82e9,            # GG 1, 2 = 82000 N/mm^2
    "curvature_rolling": 0.8,         # A1 = 0.0008 1/mm (gap A x^2 + B y^2), printed 'CURVATURES A1, B1'
    "curvature_lateral": 0.2814,      # B1 = 0.2814e-3 1/mm [1/m]
    "semi_axis_rolling": 6.304e-3,    # 'BASIC SEMIAXES AA, BB' 6.304, 12.61 mm
    "semi_axis_lateral": 12.61e-3,
    "grid": (48, 44),                 # MX, MY
    "cell": (0.2889e-3, 0.6304e-3),   # DX, DY [m]
    "potential_half_widths": (6.934e-3, 13.87e-3),  # 'POTENTIAL CONTACT' 1.1 x the semi-axes [m]
}
TRACTCURV_CREEPAGES = (0.4e-3, 0.8e-3, 1.2e-3, 1.6e-3, 2.0e-3, 2.4e-3)
TRACTCURV_FX_OVER_MU_FN = (0.2588, 0.4742, 0.6482, 0.7831, 0.8816, 0.9467)
TRACTCURV_SOURCE = "CONTACT (Vollebregt), examples/tractcurv.ref_out, first series (Kalker's theory, Coulomb)"


def carter_force(creepage: float, central_pressure: float, shear_modulus: float, poisson_ratio: float,
                 friction_coefficient: float) -> float:
    """``Q/(mu P)`` on body 1 (signed, opposite to the creepage) of Carter's rolling cylinders."""
    kappa = abs(creepage) * shear_modulus / (2.0 * (1.0 - poisson_ratio) * friction_coefficient * central_pressure)
    ratio = max(1.0 - kappa, 0.0)
    return -math.copysign(1.0 - ratio * ratio, creepage)


def carter_traction(x, semi_width: float, creepage: float, central_pressure: float, shear_modulus: float,
                    poisson_ratio: float, friction_coefficient: float) -> np.ndarray:
    """Carter's traction [Pa] on body 1 at ``x`` [m] (leading edge ``+a``); see the module docstring."""
    x = np.asarray(x, dtype=float)
    a = semi_width
    kappa = abs(creepage) * shear_modulus / (2.0 * (1.0 - poisson_ratio) * friction_coefficient * central_pressure)
    stick = max(1.0 - kappa, 0.0) * a
    outer = np.sqrt(np.maximum(1.0 - (x / a) ** 2, 0.0))
    inner = np.zeros_like(x)
    if stick > 0.0:
        inner = (stick / a) * np.sqrt(np.maximum(1.0 - ((x - a + stick) / stick) ** 2, 0.0))
    return -math.copysign(1.0, creepage) * friction_coefficient * central_pressure * (outer - inner)


def carter_stick_width(creepage: float, semi_width: float, central_pressure: float, shear_modulus: float,
                       poisson_ratio: float, friction_coefficient: float) -> float:
    """Width ``2 a'`` [m] of Carter's stick zone."""
    kappa = abs(creepage) * shear_modulus / (2.0 * (1.0 - poisson_ratio) * friction_coefficient * central_pressure)
    return 2.0 * max(1.0 - kappa, 0.0) * semi_width


def mindlin_stick_radius(force_ratio: float, radius: float) -> float:
    """Cattaneo-Mindlin stick radius ``c = a (1 - Q/(mu P))^(1/3)`` [m] (``force_ratio`` = Q/(mu P) in [0, 1])."""
    return radius * max(1.0 - force_ratio, 0.0) ** (1.0 / 3.0)


def mindlin_shift(force_ratio: float, normal_force: float, radius: float, shear_modulus: float,
                  poisson_ratio: float, friction_coefficient: float) -> float:
    """Cattaneo-Mindlin tangential shift ``delta`` [m] of two identical spheres at ``Q/(mu P)``."""
    return (3.0 * friction_coefficient * normal_force * (2.0 - poisson_ratio) / (8.0 * shear_modulus * radius)
            * (1.0 - max(1.0 - force_ratio, 0.0) ** (2.0 / 3.0)))


def mindlin_force_ratio(shift: float, normal_force: float, radius: float, shear_modulus: float,
                        poisson_ratio: float, friction_coefficient: float) -> float:
    """The inverse of :func:`mindlin_shift`: ``Q/(mu P)`` at the shift ``delta`` [m] (1 beyond full slip)."""
    scale = 3.0 * friction_coefficient * normal_force * (2.0 - poisson_ratio) / (8.0 * shear_modulus * radius)
    fraction = min(abs(shift) / scale, 1.0)
    return 1.0 - (1.0 - fraction) ** 1.5
