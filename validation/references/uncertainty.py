"""The numerical uncertainty of a mesh study by the least-squares procedure of Eca and Hoekstra.

L. Eca, M. Hoekstra, "A procedure for the estimation of the numerical uncertainty of CFD calculations based on grid
refinement studies", J. Comput. Phys. 262 (2014) 104-130 (section 3 for the fits, Appendix A for the steps).  A
quantity ``phi_i`` solved on ``n_g >= 3`` meshes of element sizes ``h_i`` (any ratios, scattered data allowed):

1. Error estimate by least squares, each fit unweighted and weighted with ``w_i = (1 / h_i) / sum_j (1 / h_j)``, the
   one of smaller standard deviation kept (section 3):

       delta_RE = phi_i - phi_0 = alpha h_i^p                  (one term, observed order p)
       delta_1  = alpha h_i,   delta_2 = alpha h_i^2,   delta_12 = alpha_1 h_i + alpha_2 h_i^2   (fixed orders)

       sigma = sqrt(n_g sum_i w_i (phi_i - phi_fit,i)^2 / (n_g - n_p))     (n_p: the fit's number of parameters)

   The error of the finest mesh is ``eps = |phi_fit(h_n) - phi_0|`` of ``delta_RE`` when the data converge
   monotonically with ``0.5 <= p < p_formal``; otherwise (p below 0.5 or at and above the formal order, divergent or
   oscillating data) of the fixed-order fit of smallest ``sigma`` (three levels: see below): the observed order is
   then not trusted, and an erratic one (p = 17 from three levels that agree to 0.1 %) cannot make the estimate
   blow up or vanish.
2. The data range (eq 19): ``Delta_phi = (max phi_i - min phi_i) / (n_g - 1)``.
3. The safety factor: ``F_s = 1.25`` when the data converge monotonically with ``0.5 <= p < 1.05 p_formal`` (2.1 for
   the formal order 2) and ``sigma < Delta_phi``; else ``F_s = 3``.
4. The uncertainty of the finest mesh's ``phi_n``:

       U = F_s eps + sigma + |phi_n - phi_fit(h_n)|                              for sigma <  Delta_phi   (eq 20)
       U = 3 sigma / Delta_phi (eps + sigma + |phi_n - phi_fit(h_n)|)            for sigma >= Delta_phi   (eq 21)

   so that ``phi_n - U <= phi_exact <= phi_n + U`` (the paper's 95 % coverage).  ``U`` is about the finest value,
   which is therefore the reference; ``phi_0`` of the chosen fit is reported beside it.

Conventions where the paper is silent or needs more meshes (it recommends at least four): a fit with as many
parameters as meshes (``delta_RE`` or ``delta_12`` on three) has no degree of freedom; its ``sigma`` is taken with
the denominator 1 (zero for an exact fit), and ``delta_12`` (a polynomial through every point) is left out of the
choice below four meshes.  Three levels: when their observed order is not trusted, the one fixed-order fit is the
formal order's, ``delta_formal = alpha h^p_formal`` (unweighted or weighted, smaller ``sigma``), with ``F_s = 3``:
the GCI's rule for an observed order that cannot be relied on (Roache 1998; ASME V&V 20-2009, section 2-4: the
formal order with the factor of safety 3).  Each fixed fit on three levels keeps one degree of freedom, so choosing
between ``delta_1`` and ``delta_2`` by ``sigma`` would choose by a single residual, the scatter of the levels; with
``delta_1`` a study whose three levels agree within 0.2 % (docs/verification.md, "Three levels") would extrapolate
that scatter 2.3 times beyond the finest level (``h_n / (h_1 - h_n)`` for the ratio 1.2) and then triple it.  With
four or more levels the paper's choice among ``delta_1, delta_2, delta_12`` stands.

The exponent of ``delta_RE`` is searched in [0.05, 30] (a scan, then golden-section refinement of
``sum w_i (phi_i - phi_fit,i)^2``; for a fixed p the fit is linear in phi_0, alpha).  Identical values on every mesh
give ``U = 0``.  With three meshes converging monotonically inside ``[0.5, p_formal)`` the procedure is Roache's
GCI with F_s 1.25 (tests/validation/references/test_uncertainty.py reproduces Celik et al. 2008, J. Fluids Eng.
130, 078001, Table 1).  Pure arithmetic on the levels: it never calls a model.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.validation.references.richardson import study_levels

__all__ = ["Uncertainty", "eca_hoekstra", "SAFETY_TRUSTED", "SAFETY_UNTRUSTED"]

SAFETY_TRUSTED = 1.25   # eq 20 with a trusted observed order (Appendix A, step 3)
SAFETY_UNTRUSTED = 3.0  # otherwise, and the factor of eq 21
P_RANGE = (0.05, 30.0)  # where the exponent of delta_RE is searched
FITS = {"RE": "phi_0 + alpha h^p", "1": "phi_0 + alpha h", "2": "phi_0 + alpha h^2",
        "12": "phi_0 + alpha_1 h + alpha_2 h^2"}


@dataclass(frozen=True)
class Uncertainty:
    """The result of :func:`eca_hoekstra`.  ``value``: phi on the finest mesh (the reference); ``uncertainty``: U
    about it (same unit); ``extrapolated``: phi_0 of the chosen fit; ``order``: the observed order p of delta_RE
    (nan for oscillating data); ``fit``: the chosen fit (:data:`FITS`); ``weighted``: its weights; ``error``: eps;
    ``sigma``, ``data_range``, ``safety``: sigma, Delta_phi, F_s; ``note``: how, in words."""

    value: float
    uncertainty: float
    extrapolated: float
    order: float
    fit: str
    weighted: bool
    error: float
    sigma: float
    data_range: float
    safety: float
    note: str

    @property
    def relative_uncertainty(self) -> float:
        """``U / |phi_n|`` (inf for a zero value with U > 0, 0 for U = 0)."""
        if self.uncertainty == 0.0:
            return 0.0
        return self.uncertainty / abs(self.value) if self.value != 0.0 else math.inf

    @property
    def finest(self) -> float:
        """phi on the finest mesh (as :class:`references.richardson.Extrapolation` names it)."""
        return self.value


@dataclass(frozen=True)
class _Fit:
    key: str
    weighted: bool
    phi0: float
    fitted: np.ndarray  # phi_fit at every mesh
    sigma: float
    order: float


def _weights(h: np.ndarray, weighted: bool) -> np.ndarray:
    w = 1.0 / h if weighted else np.ones_like(h)
    return w / w.sum()


def _linear_fit(h, phi, w, powers) -> tuple[np.ndarray, np.ndarray]:
    """Weighted linear least squares ``phi ~ c_0 + sum_k c_k h^powers[k]``: (coefficients, fitted values)."""
    a = np.column_stack([np.ones_like(h)] + [h ** p for p in powers])
    root = np.sqrt(w)
    coefficients = np.linalg.lstsq(a * root[:, None], phi * root, rcond=None)[0]
    return coefficients, a @ coefficients


def _sigma(phi, fitted, w, parameters: int) -> float:
    n = len(phi)
    return float(math.sqrt(n * float(np.sum(w * (phi - fitted) ** 2)) / max(n - parameters, 1)))


def _fixed(h, phi, key: str, weighted: bool, formal_order: float = 2.0) -> _Fit:
    powers = {"1": (1.0,), "2": (2.0,), "12": (1.0, 2.0), "formal": (formal_order,)}[key]
    w = _weights(h, weighted)
    coefficients, fitted = _linear_fit(h, phi, w, powers)
    return _Fit(key, weighted, float(coefficients[0]), fitted, _sigma(phi, fitted, w, 1 + len(powers)), powers[0])


def _fit_words(fit: _Fit) -> str:
    return f"phi_0 + alpha h^{fit.order:g}" if fit.key == "formal" else FITS[fit.key]


def _power(h, phi, weighted: bool) -> _Fit:
    """delta_RE: the exponent minimising the weighted squares (scan, then golden-section refinement)."""
    w = _weights(h, weighted)

    def squares(p: float) -> float:
        return float(np.sum(w * (phi - _linear_fit(h, phi, w, (p,))[1]) ** 2))

    grid = np.geomspace(*P_RANGE, 400)
    values = [squares(p) for p in grid]
    k = int(np.argmin(values))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    golden = (math.sqrt(5.0) - 1.0) / 2.0
    c, d = hi - golden * (hi - lo), lo + golden * (hi - lo)
    fc, fd = squares(c), squares(d)
    for _ in range(80):
        if fc < fd:
            hi, d, fd = d, c, fc
            c = hi - golden * (hi - lo)
            fc = squares(c)
        else:
            lo, c, fc = c, d, fd
            d = lo + golden * (hi - lo)
            fd = squares(d)
    p = min((grid[k], values[k]), (c, fc), (d, fd), key=lambda t: t[1])[0]
    coefficients, fitted = _linear_fit(h, phi, w, (p,))
    return _Fit("RE", weighted, float(coefficients[0]), fitted, _sigma(phi, fitted, w, 3), float(p))


def _best(fits) -> _Fit:
    return min(fits, key=lambda f: f.sigma)


def eca_hoekstra(sizes, values, formal_order: float = 2.0) -> Uncertainty:
    """The uncertainty of ``values`` on the finest of meshes of element ``sizes`` (coarse to fine, >= 3) by Eca and
    Hoekstra's procedure (module docstring); ``formal_order``: the discretisation's formal order of the quantity.
    ValueError for fewer than three meshes, sizes that do not decrease or values that are not finite."""
    sizes, values = study_levels(sizes, values, 3, "eca_hoekstra",
                                 " (two meshes: references.richardson.extrapolate)")
    if not (math.isfinite(formal_order) and formal_order > 0.5):
        raise ValueError(f"formal_order must be a finite order > 0.5, got {formal_order!r}")
    n = len(values)
    finest = values[-1]
    data_range = (max(values) - min(values)) / (n - 1)  # eq 19
    if data_range == 0.0:
        return Uncertainty(finest, 0.0, finest, math.nan, FITS["1"], False, 0.0, 0.0, 0.0, SAFETY_TRUSTED,
                           f"{n} meshes, identical values: U = 0")
    # scaled for the arithmetic: h by the coarsest size, phi about the finest value in units of the data range
    h = np.asarray(sizes) / sizes[0]
    phi = (np.asarray(values) - finest) / data_range
    steps = np.diff(phi)
    monotone = bool(np.all(steps > 0) or np.all(steps < 0))
    power = _best([_power(h, phi, False), _power(h, phi, True)])
    p = power.order
    trusted = monotone and 0.5 <= p < formal_order
    if trusted:
        chosen = power
        how = f"observed order p = {p:.3g} (least squares)"
    else:
        # four or more levels: Eca and Hoekstra's choice among the fixed-order fits; three: the formal order's
        # (module docstring, "Three levels")
        keys = ("1", "2", "12") if n >= 4 else ("formal",)
        chosen = _best([_fixed(h, phi, key, weighted, formal_order) for key in keys for weighted in (False, True)])
        why = "oscillating levels" if not monotone else (
            f"observed order p = {p:.3g} below 0.5" if p < 0.5 else
            f"observed order p = {p:.3g} not below the formal order {formal_order:g}")
        how = (f"{why}: the fixed-order fit {_fit_words(chosen)} of smallest standard deviation" if n >= 4 else
               f"{why}: the formal-order fit {_fit_words(chosen)} (three levels)")
    scaled_sigma = chosen.sigma
    error = abs(float(chosen.fitted[-1]) - chosen.phi0)
    residual = abs(float(phi[-1] - chosen.fitted[-1]))
    if scaled_sigma < 1.0:  # sigma < Delta_phi (phi is in units of Delta_phi)
        safety = SAFETY_TRUSTED if (monotone and 0.5 <= p < 1.05 * formal_order) else SAFETY_UNTRUSTED
        scaled_u = safety * error + scaled_sigma + residual  # eq 20
        rule = f"F_s {safety:g} (eq 20)"
    else:
        safety = SAFETY_UNTRUSTED
        scaled_u = SAFETY_UNTRUSTED * scaled_sigma * (error + scaled_sigma + residual)  # eq 21
        rule = "sigma >= Delta_phi: 3 sigma / Delta_phi (eq 21)"
    sigma = scaled_sigma * data_range
    return Uncertainty(finest, scaled_u * data_range, finest + chosen.phi0 * data_range, p if monotone else math.nan,
                       _fit_words(chosen), chosen.weighted, error * data_range, sigma, data_range, safety,
                       f"Eca-Hoekstra on {n} meshes: {how}" + (", weighted" if chosen.weighted else "")
                       + f", {rule}")
