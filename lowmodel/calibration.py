"""Calibrated constants of the low-order models: fits with uncertainty and the calibration file.

Fits (scipy ``least_squares``; covariance ``s^2 (J^T J)^-1`` from the Jacobian
at the optimum with ``s^2 = SSR / (n - p)``; intervals ``value +- t_(n-p) SE``,
Student t at the stated confidence):

* :func:`fit_contact_law` -- the contact stiffness law of one contact type
  from load-approach data (FE or a rig): ``U = C F^(2/3) + C_b F``
  (lin2019 eq 53 plus the finite-body compliance ``C_b`` that Hertz leaves out,
  the law of ``fem.postprocess.approach_fit``) and, from the contact size,
  ``a = Psi R_B^(1/3) F^(1/3)`` (lin2019 eq 15);
* :func:`fit_friction_coefficient` -- ``mu`` from measured friction and normal
  forces, ``f = mu F`` (through the origin), or ``f = (mu_0 + mu_v v) F`` when
  speeds are given;
* :func:`fit_line_through_origin` -- ``k_f`` as the least-squares slope of a
  friction map (lin2019 eq 14).

The file (:func:`save` / :func:`load`) is JSON: ``{"format": "ballbench-calibration",
"version": 1, "constants": {group: {name: {value, std_error, ci_low, ci_high,
confidence, unit, source, ...}}}}``; groups are contact types (``ball-groove-0.56``,
``ball-ball``, ...), ``friction`` and ``k_f``.  SI units.
"""
from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np
from scipy import optimize

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["Constant", "Calibration", "FitResult", "fit_least_squares", "fit_contact_law", "ContactLaw", "law_force",
           "fit_friction_coefficient", "fit_line_through_origin", "save", "load", "FORMAT", "VERSION"]

FORMAT = "ballbench-calibration"
VERSION = 1


@dataclass(frozen=True)
class Constant:
    """A calibrated constant: ``value`` with its standard error and ``confidence`` interval [ci_low, ci_high]
    (all in ``unit``), the ``source`` of the data, number of data points and rms fit residual."""

    value: float
    std_error: float
    ci_low: float
    ci_high: float
    unit: str
    source: str
    confidence: float = 0.95
    n_points: int = 0
    rms_residual: float = 0.0
    reference: float | None = None  # the uncalibrated (e.g. Hertz) value, if there is one

    def covers(self, truth: float) -> bool:
        return self.ci_low <= truth <= self.ci_high


@dataclass(frozen=True)
class Calibration:
    """Constants by group and name: ``calibration.value("ball-groove-0.56", "psi")``."""

    constants: dict = field(default_factory=dict)  # group -> name -> Constant
    notes: tuple = ()

    def get(self, group: str, name: str) -> Constant:
        if group not in self.constants:
            raise KeyError(f"calibration has no group {group!r}; groups: {sorted(self.constants)}")
        if name not in self.constants[group]:
            raise KeyError(f"calibration group {group!r} has no constant {name!r}; "
                           f"constants: {sorted(self.constants[group])}")
        return self.constants[group][name]

    def value(self, group: str, name: str) -> float:
        return self.get(group, name).value

    def merged(self, group: str, constants: dict) -> "Calibration":
        """A copy with ``constants`` (name -> Constant) added to ``group``."""
        new = {g: dict(c) for g, c in self.constants.items()}
        new.setdefault(group, {}).update(constants)
        return Calibration(new, self.notes)


@dataclass(frozen=True)
class FitResult:
    """Least-squares fit: ``params`` (p,), ``covariance`` (p, p), ``std_error`` (p,), ``ci`` (p, 2) at
    ``confidence``, ``rms`` residual, ``dof`` = n - p."""

    params: np.ndarray
    covariance: np.ndarray
    std_error: np.ndarray
    ci: np.ndarray
    rms: float
    dof: int
    confidence: float


STATIONARITY = 1e-3  # largest Gauss-Newton step at an accepted fit, relative to max(|p|, x_scale) (scipy stops
# ~1e-9 short of the optimum; a start many decades off stops ~1e100 short)


def fit_least_squares(residual: Callable[[np.ndarray], np.ndarray], p0, *, n_points: int,
                      confidence: float = 0.95, x_scale=None) -> FitResult:
    """Minimise ``sum residual(p)^2`` (scipy ``least_squares``, trust-region reflective).

    ``residual(p)`` returns (n,) residuals of equal variance (divide by the
    measurement sigma first when it varies).  Covariance ``s^2 (J^T J)^-1``
    with ``s^2 = SSR/(n - p)``; intervals from Student's t with ``n - p``
    degrees of freedom.  Needs ``n_points > p``.
    """
    from scipy import stats

    confidence = checks.bounded("confidence", confidence, 0.0, 1.0, note="a probability such as 0.95")
    p0 = np.reshape(checks.finite("p0", p0), -1)
    n_points = checks.count("n_points", n_points, 1)
    if n_points <= p0.size:
        raise ValueError(f"n_points must exceed the number of parameters in p0 ({p0.size}) for an uncertainty, "
                         f"got {n_points}")
    scale = (np.where(np.abs(p0) > 0, np.abs(p0), 1.0) if x_scale is None
             else np.broadcast_to(checks.positive("x_scale", x_scale), p0.shape))
    with np.errstate(all="ignore"):
        start = np.asarray(residual(p0), dtype=float)
    _check_residual(start, "at p0", ValueError)
    non_finite = []  # the points where residual returned NaN or inf during the fit (the trust region avoids them)

    def watched(p):
        values = np.asarray(residual(p), dtype=float)
        if not non_finite and not np.all(np.isfinite(values)):
            non_finite.append(np.array(p))
        return values

    with np.errstate(all="ignore"):  # the trust region from a poor start (p0 ~ 1e-127) may under/overflow: judged below
        result = optimize.least_squares(watched, p0, x_scale=scale, method="trf", xtol=1e-15, ftol=1e-15,
                                        gtol=1e-15)
    seen = f"; residual returned NaN or inf at p = {non_finite[0]!r} on the way" if non_finite else ""
    if not (result.success and np.all(np.isfinite(result.x))):
        # (scipy's own message is not passed on: it may read as a success or name scipy's internals)
        reason = "iteration limit" if result.status == 0 else "no minimum found"
        raise ConvergenceError(f"least squares: {reason} (scipy.optimize.least_squares status {result.status} after "
                               f"{result.nfev} evaluations of residual){seen}", residual=_norm(result.fun),
                               iterations=int(result.nfev), tolerance=1e-15, reason=reason)
    _check_residual(result.fun, f"at the fitted p = {result.x!r}", ConvergenceError, int(result.nfev))
    norm = _norm(result.fun)
    jac = result.jac
    if not np.all(np.isfinite(jac)):
        raise ConvergenceError("least squares: the Jacobian of residual at the fitted p is not finite",
                               residual=norm, iterations=int(result.nfev), tolerance=1e-15,
                               reason="non-finite Jacobian")
    # stationarity: at a minimum one more Gauss-Newton step moves p by a rounding error; scipy's tolerances are
    # relative to x_scale, so a start p0 many decades off the solution (1e-127 for 1.7 with the default scale |p0|)
    # can stop where it began
    gauss_newton = np.linalg.lstsq(jac, -result.fun, rcond=None)[0]
    moved = float(np.max(np.abs(gauss_newton) / np.maximum(np.abs(result.x), scale)))
    if not moved <= STATIONARITY:
        raise ConvergenceError(f"least squares: stopped away from a minimum (a Gauss-Newton step still moves p by "
                               f"{moved:.3e} of its size > {STATIONARITY:g}): rescale p0 or x_scale{seen}",
                               residual=norm, iterations=int(result.nfev), tolerance=STATIONARITY,
                               reason="not stationary" + (" (non-finite residual nearby)" if non_finite else ""))
    dof = n_points - p0.size
    ssr = float(result.fun @ result.fun)
    _, singular, vt = np.linalg.svd(jac, full_matrices=False)
    if singular[-1] <= singular[0] * 1e-12 or not singular[-1] ** 2 > 0.0:  # (or the covariance overflows)
        raise ValueError("residual: the data do not determine every parameter of p0 (singular Jacobian): widen the "
                         "load range")
    covariance = (vt.T / singular**2) @ vt * (ssr / dof)
    std_error = np.sqrt(np.diag(covariance))
    half = float(stats.t.ppf(0.5 + 0.5 * confidence, dof)) * std_error
    params = result.x
    return FitResult(params, covariance, std_error, np.column_stack([params - half, params + half]),
                     math.sqrt(ssr / n_points), dof, confidence)


def _norm(values) -> float:
    """Euclidean norm without overflow (inf only when the norm itself is beyond the float range or not finite)."""
    values = np.asarray(values, dtype=float)
    if values.size == 0 or not np.all(np.isfinite(values)):
        return math.inf if values.size else 0.0
    peak = float(np.max(np.abs(values)))
    if peak == 0.0:
        return 0.0
    with np.errstate(over="ignore"):
        return float(peak * np.linalg.norm(values / peak))


def _check_residual(values: np.ndarray, where: str, error, iterations: int = 0) -> None:
    """``residual``'s values ``where``: a 1-D array, finite, with a sum of squares inside the float range."""
    if values.ndim != 1 or values.size == 0:
        raise ValueError(f"residual must return a 1-D array of residuals, got shape {values.shape} {where}")
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size or not _norm(values) < 1e150:  # (its square, the sum of squares, within the float range)
        what = (f"{float(values[bad[0]])!r} at index {int(bad[0])} of {values.size}" if bad.size
                else f"values up to {float(np.max(np.abs(values))):.3e}, whose sum of squares overflows")
        message = f"residual returns {what} {where}: a fit needs finite residuals of a representable size"
        if error is ValueError:
            raise ValueError(message)
        raise ConvergenceError(f"least squares: {message}", residual=math.inf, iterations=iterations,
                               tolerance=1e-15, reason="non-finite residual")


def _range_scale(values) -> float:
    """1 for data inside [1e-100, 1e100] in size (fits run as given there), else a power of two near their largest
    size: dividing by it is exact, and the fit's sums of squares stay inside the float range."""
    peak = float(np.max(np.abs(values)))
    return 1.0 if 1e-100 <= peak <= 1e100 or peak == 0.0 else checks.power_of_two_scale(values)


def _fit(data: str, residual, p0, **options) -> FitResult:
    """:func:`fit_least_squares`; its ValueErrors name the caller's ``data`` (e.g. ``"forces, approaches"``)."""
    try:
        return fit_least_squares(residual, p0, **options)
    except ValueError as error:
        raise ValueError(f"{data}: {error}") from None


def _constant(fit: FitResult, k: int, unit: str, source: str, n: int, rms: float, reference=None) -> Constant:
    return Constant(float(fit.params[k]), float(fit.std_error[k]), float(fit.ci[k, 0]), float(fit.ci[k, 1]), unit,
                    source, fit.confidence, n, rms, None if reference is None else float(reference))


def _data(name: str, values, unit: str, *, positive: bool = True) -> np.ndarray:
    """Data column ``values`` as a flat float array, checked by the shared ``lowmodel.checks``."""
    check = checks.positive if positive else checks.finite
    return np.reshape(check(name, values, unit), -1)


@dataclass(frozen=True)
class ContactLaw:
    """Fitted contact stiffness law of one contact type: ``hertz_constant`` C [m N^-2/3],
    ``bulk_compliance`` C_b [m/N] and (when contact sizes were given) ``psi`` [(m^2/N)^(1/3)]."""

    hertz_constant: Constant
    bulk_compliance: Constant
    psi: Constant | None = None

    def approach(self, force) -> np.ndarray:
        """``U = C F^(2/3) + C_b F`` [m] at ``force`` [N]."""
        force = np.asarray(force, dtype=float)
        return self.hertz_constant.value * force ** (2.0 / 3.0) + self.bulk_compliance.value * force

    def stiffness(self, force) -> np.ndarray:
        """``dF/dU`` [N/m] of the calibrated law at ``force`` [N] (> 0)."""
        force = np.asarray(force, dtype=float)
        return 1.0 / (2.0 / 3.0 * self.hertz_constant.value * force ** (-1.0 / 3.0) + self.bulk_compliance.value)

    def constants(self) -> dict:
        out = {"hertz_constant": self.hertz_constant, "bulk_compliance": self.bulk_compliance}
        if self.psi is not None:
            out["psi"] = self.psi
        return out


def law_force(approach, hertz_constant, bulk_compliance, *, tolerance: float = 1e-14,
              max_iterations: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Normal force ``F`` [N] and ``dF/dU`` [N/m] of the law ``U = C F^(2/3) + C_b F`` at approach ``U`` [m].

    The inverse of :meth:`ContactLaw.approach` (lin2019 eq 53 with the finite-body compliance ``C_b``;
    ``C_b = 0`` is Hertz, ``F = (U/C)^(3/2)``), elementwise over broadcast arrays: Newton on
    ``s = F^(1/3)``, ``C s^2 + C_b s^3 = U``, from the Hertz root.  ``U <= 0`` gives 0 (no contact).
    ``dF/dU = 3 s / (2 C + 3 C_b s)``.  With ``C_b < 0`` the law has a largest approach
    ``C s*^2 / 3`` at ``s* = 2 C / (3 |C_b|)`` (where it stops being monotone): ValueError beyond it.
    """
    approach = np.asarray(checks.finite("approach", approach, "m"))
    tolerance = checks.positive("tolerance", tolerance)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    c = np.broadcast_to(np.asarray(hertz_constant, dtype=float), approach.shape)
    c_b = np.broadcast_to(np.asarray(bulk_compliance, dtype=float), approach.shape)
    if np.any(c <= 0.0) or not np.all(np.isfinite(c)):
        raise ValueError("hertz_constant must be > 0 m N^-2/3 and finite")
    if not np.all(np.isfinite(c_b)):
        raise ValueError("bulk_compliance must be finite [m/N]")
    loaded = approach > 0.0
    u = np.where(loaded, approach, 0.0)
    with np.errstate(divide="ignore", over="ignore"):  # a tiny |C_b|: s* = inf, no limit in float range
        s_max = np.where(c_b < 0.0, 2.0 * c / (3.0 * np.abs(c_b)), np.inf)
        too_far = loaded & (c_b < 0.0) & (u >= c * s_max**2 / 3.0)
    if np.any(too_far):
        raise ValueError(f"approach must be below C s*^2 / 3 (s* = 2 C / (3 |C_b|)) where the law with C_b < 0 "
                         f"is monotone, got {float(u[too_far][0])!r} m")
    with np.errstate(over="ignore", invalid="ignore"):  # a force beyond the floating-point range: ValueError below
        s = np.sqrt(u / c)                                     # Hertz root (C_b = 0)
        for _ in range(max_iterations):
            residual = c * s * s + c_b * s**3 - u
            step = residual / np.where(loaded, 2.0 * c * s + 3.0 * c_b * s * s, 1.0)
            s = np.where(loaded, s - step, 0.0)
            if np.all(np.abs(step) <= tolerance * np.maximum(s, 1e-300)):
                break
        force = s**3
        slope = np.where(loaded, 3.0 * s / (2.0 * c + 3.0 * c_b * s), 0.0)
    if not (np.all(np.isfinite(force)) and np.all(np.isfinite(slope))):
        raise ValueError(f"approach up to {float(np.max(u))!r} m gives a force beyond the floating-point range "
                         "(hertz_constant, bulk_compliance)")
    if not np.all(np.abs(step) <= tolerance * np.maximum(s, 1e-300)):
        raise ConvergenceError("law_force: Newton on C s^2 + C_b s^3 = U did not converge",
                               residual=float(np.max(np.abs(residual))), iterations=max_iterations,
                               tolerance=tolerance, reason="iteration limit")
    return force, slope


def fit_contact_law(forces, approaches, *, semi_axes=None, ball_radius: float | None = None,
                    confidence: float = 0.95, source: str = "", hertz_constant: float | None = None,
                    psi: float | None = None) -> ContactLaw:
    """Fit ``U = C F^(2/3) + C_b F`` (lin2019 eq 53 + bulk compliance) and ``a = Psi R_B^(1/3) F^(1/3)`` (eq 15).

    Parameters
    ----------
    forces : (n,) N, normal loads (> 0, n >= 3 distinct)
    approaches : (n,) m, approach of the reference faces of the two bodies
    semi_axes : (n,) m, major semi-axis ``a`` at each load (optional; needs ``ball_radius`` [m])
    hertz_constant, psi : the uncalibrated (Hertz) values, stored as ``reference`` beside the fit
    """
    forces = _data("forces", forces, "N")
    approaches = _data("approaches", approaches, "m")
    if forces.size != approaches.size:
        raise ValueError(f"forces and approaches must have the same length, got {forces.size} and {approaches.size}")
    if np.unique(forces).size < 3:
        raise ValueError(f"forces: need >= 3 distinct loads for C and C_b with an uncertainty, "
                         f"got {np.unique(forces).size}")
    f_scale = float(np.max(forces))
    u_scale = float(np.max(approaches))
    basis = np.column_stack([(forces / f_scale) ** (2.0 / 3.0), forces / f_scale])
    guess, *_ = np.linalg.lstsq(basis, approaches / u_scale, rcond=None)

    def residual(p):
        return basis @ p - approaches / u_scale  # lin2019 eq 53 + C_b F, scaled

    fit = _fit("forces, approaches", residual, guess, n_points=forces.size, confidence=confidence,
               x_scale=np.maximum(np.abs(guess), 1e-3))
    to_c = np.array([u_scale / f_scale ** (2.0 / 3.0), u_scale / f_scale])  # back to SI
    fit_si = FitResult(fit.params * to_c, fit.covariance * np.outer(to_c, to_c), fit.std_error * to_c,
                       fit.ci * to_c[:, None], fit.rms * u_scale, fit.dof, fit.confidence)
    c = _constant(fit_si, 0, "m N^-2/3", source, forces.size, fit_si.rms, hertz_constant)
    c_b = _constant(fit_si, 1, "m/N", source, forces.size, fit_si.rms, 0.0)
    psi_constant = None
    if semi_axes is not None:
        if ball_radius is None:
            raise ValueError("semi_axes need ball_radius [m] for Psi (lin2019 eq 15)")
        radius = float(_data("ball_radius", ball_radius, "m")[0])
        axes = _data("semi_axes", semi_axes, "m")
        if axes.size != forces.size:
            raise ValueError(f"semi_axes must have one value per force, got {axes.size} and {forces.size}")
        regressor = radius ** (1.0 / 3.0) * forces ** (1.0 / 3.0)  # lin2019 eq 15: a = Psi R^(1/3) F^(1/3)
        a_scale = float(np.max(axes))
        start = float(regressor @ axes / (regressor @ regressor))
        fit_psi = _fit("forces, semi_axes", lambda p: (p[0] * regressor - axes) / a_scale, [start],
                       n_points=forces.size, confidence=confidence)
        psi_constant = _constant(fit_psi, 0, "(m^2/N)^(1/3)", source, forces.size, fit_psi.rms * a_scale, psi)
    return ContactLaw(c, c_b, psi_constant)


def fit_friction_coefficient(normal_force, friction_force, speed=None, *, confidence: float = 0.95,
                             source: str = "") -> dict:
    """``mu`` from ``f = mu F`` (least squares through the origin); with ``speed`` [m/s] given,
    ``f = (mu_0 + mu_v v) F`` (``mu`` then is ``mu_0``, ``mu_speed_slope`` is ``mu_v`` [s/m]).

    normal_force, friction_force : (n,) N (> 0); returns ``{name: Constant}``.
    """
    normal = _data("normal_force", normal_force, "N")
    friction = _data("friction_force", friction_force, "N", positive=False)
    if normal.size != friction.size:
        raise ValueError(f"normal_force and friction_force must have the same length, got {normal.size} and "
                         f"{friction.size}")
    needed = 2 if speed is None else 3  # more rows than fitted parameters
    if normal.size < needed:
        raise ValueError(f"normal_force and friction_force need >= {needed} values for an uncertainty, "
                         f"got {normal.size}")
    ratio = friction / normal
    # forces of any size: both divided by one power of two (exact; mu is a ratio), the rms scaled back
    force_scale = _range_scale(np.concatenate([normal, friction]))
    normal, friction = normal / force_scale, friction / force_scale
    if speed is None:
        fit = _fit("normal_force, friction_force", lambda p: p[0] * normal - friction, [float(np.mean(ratio))],
                   n_points=normal.size, confidence=confidence)
        return {"mu": _constant(fit, 0, "1", source, normal.size, fit.rms * force_scale)}
    speed = _data("speed", speed, "m/s", positive=False)
    if speed.size != normal.size:
        raise ValueError(f"speed must have one value per row, got {speed.size} and {normal.size}")
    if np.unique(speed).size < 2:
        raise ValueError("a speed dependence needs at least two distinct speeds")
    guess, *_ = np.linalg.lstsq(np.column_stack([normal, normal * speed]), friction, rcond=None)
    v_scale = float(np.max(np.abs(speed)))
    fit = _fit("normal_force, friction_force, speed", lambda p: (p[0] + p[1] * speed / v_scale) * normal - friction,
               [guess[0], guess[1] * v_scale], n_points=normal.size, confidence=confidence,
               x_scale=np.array([max(abs(guess[0]), 1e-3), max(abs(guess[1] * v_scale), 1e-3)]))
    to_si = np.array([1.0, 1.0 / v_scale])
    with np.errstate(over="ignore"):
        fit = FitResult(fit.params * to_si, fit.covariance * np.outer(to_si, to_si), fit.std_error * to_si,
                        fit.ci * to_si[:, None], fit.rms * force_scale, fit.dof, fit.confidence)
    if not all(np.all(np.isfinite(a)) for a in (fit.params, fit.covariance, fit.ci)):
        raise ValueError(f"speed: the speeds (largest {v_scale!r} m/s) are too small for mu_speed_slope [s/m]: its "
                         "value or covariance exceeds the floating-point range")
    return {"mu": _constant(fit, 0, "1", source, normal.size, fit.rms),
            "mu_speed_slope": _constant(fit, 1, "s/m", source, normal.size, fit.rms)}


def fit_line_through_origin(x, y, *, confidence: float = 0.95, source: str = "", unit: str = "1") -> Constant:
    """Least-squares slope ``k`` of ``y = -k x`` (lin2019 eq 14 ``f = -k_f mu F c/a``) with its interval.

    The interval of a fit to a deterministic curve measures the misfit of the line, not noise.
    """
    x = _data("x", x, "", positive=False)
    y = _data("y", y, "", positive=False)
    if x.size != y.size:
        raise ValueError(f"x and y must have the same length, got {x.size} and {y.size}")
    # x and y of any size: each divided by a power of two (exact), the slope and rms scaled back
    x_scale, y_scale = _range_scale(x), _range_scale(y)
    x, y = x / x_scale, y / y_scale
    if x.size < 2 or not float(x @ x) > 0.0:
        raise ValueError(f"x must hold >= 2 values, not all zero (or so small that x . x underflows), got {x!r}")
    start = float(-(x @ y) / (x @ x))
    fit = _fit("x, y", lambda p: -p[0] * x - y, [start], n_points=x.size, confidence=confidence)
    with np.errstate(over="ignore", under="ignore"):
        to_si = np.float64(y_scale) / np.float64(x_scale)  # numpy: beyond the float range is inf, checked below
        scaled, fit = fit, FitResult(fit.params * to_si, fit.covariance * to_si**2, fit.std_error * to_si,
                                     fit.ci * to_si, fit.rms * y_scale, fit.dof, fit.confidence)
    underflow = scaled.std_error[0] != 0.0 and not fit.std_error[0] >= np.finfo(float).tiny
    if underflow or not all(np.all(np.isfinite(a)) for a in (fit.params, fit.covariance, fit.ci)) \
            or not math.isfinite(fit.rms):
        raise ValueError(f"x, y: the slope y / x (|x| up to {float(np.max(np.abs(x))) * x_scale:.3e}, |y| up to "
                         f"{float(np.max(np.abs(y))) * y_scale:.3e}) or its variance is beyond the float range")
    return _constant(fit, 0, unit, source, x.size, fit.rms)


# --------------------------------------------------------------------------
# the file
# --------------------------------------------------------------------------
def save(calibration: Calibration, path: str | Path) -> Path:
    """Write ``calibration`` as JSON (see the module docstring); returns the path."""
    path = Path(path)
    document = {"format": FORMAT, "version": VERSION, "notes": list(calibration.notes),
                "constants": {group: {name: asdict(c) for name, c in constants.items()}
                              for group, constants in calibration.constants.items()}}
    path.write_text(json.dumps(document, indent=2) + "\n")
    return path


def load(path: str | Path) -> Calibration:
    """Read a calibration file written by :func:`save` (``ballbench calibrate``); errors name the file."""
    path = Path(path)
    try:
        document = json.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(f"calibration file {path} does not exist") from None
    except json.JSONDecodeError as error:
        raise ValueError(f"{path}: not a calibration file (invalid JSON: {error})") from None
    if not isinstance(document, dict) or document.get("format") != FORMAT:
        raise ValueError(f"{path}: not a calibration file (format must be {FORMAT!r})")
    if document.get("version") != VERSION or isinstance(document.get("version"), bool):
        raise ValueError(f"{path}: calibration version {document.get('version')!r} is not supported "
                         f"(this ballbench reads version {VERSION})")
    notes = document.get("notes", [])
    groups = document.get("constants", {})
    if not isinstance(notes, list) or not all(isinstance(note, str) for note in notes):
        raise ValueError(f"{path}: notes must be a list of strings")
    if not isinstance(groups, dict) or not all(isinstance(items, dict) for items in groups.values()):
        raise ValueError(f"{path}: constants must map each group to a mapping of constants")
    constants = {group: {name: _constant_record(path, f"{group}/{name}", record) for name, record in items.items()}
                 for group, items in groups.items()}
    return Calibration(constants, tuple(notes))


def _constant_record(path: Path, label: str, record) -> Constant:
    """One constant of a calibration file, every field of its type (errors name the file and the constant)."""
    fields = set(Constant.__dataclass_fields__)
    required = {"value", "std_error", "ci_low", "ci_high", "unit", "source"}
    if not isinstance(record, dict) or required - set(record) or set(record) - fields:
        keys = set(record) if isinstance(record, dict) else set()
        raise ValueError(f"{path}: constant {label} must have the fields {sorted(fields)}, "
                         f"missing {sorted(required - keys)}, unknown {sorted(keys - fields)}")

    def number(value):
        return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)

    bad = [name for name in ("value", "std_error", "ci_low", "ci_high", "rms_residual") if name in record
           and not number(record[name])]
    bad += [name for name in ("unit", "source") if not isinstance(record[name], str)]
    if "confidence" in record and not (number(record["confidence"]) and 0.0 < record["confidence"] < 1.0):
        bad.append("confidence")
    if "n_points" in record and not (isinstance(record["n_points"], int) and not isinstance(record["n_points"], bool)
                                     and record["n_points"] >= 0):
        bad.append("n_points")
    if record.get("reference") is not None and not number(record["reference"]):
        bad.append("reference")
    if bad:
        raise ValueError(f"{path}: constant {label} has invalid {', '.join(bad)} (finite numbers, strings for unit "
                         "and source, confidence in (0, 1), n_points an integer >= 0)")
    return Constant(**record)
