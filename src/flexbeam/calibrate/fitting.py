"""Calibration: the least-squares fit of case fields to measured histories and/or features.

:func:`calibrate` checks the request, lets :class:`~flexbeam.calibrate.problem.ResidualProblem` prepare the
residuals, fits them with :func:`scipy.optimize.least_squares` (:func:`_least_squares`), maps the covariance of the
scaled variables to the fields (:func:`_uncertainty`) and gathers the :class:`Calibration`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import ParameterError, closest
from ..parameters.case import Case
from ..parameters.io import load_case
from ..results.metrics import FEATURES, METRICS, POSITIVE_FEATURES
from .fields import Parameter, parse_fit
from .measured import Measured, read_measured
from .problem import ResidualProblem, covariance
from .result import Calibration

if TYPE_CHECKING:
    import numpy as np
    from scipy.optimize import OptimizeResult

    from ..results.solution import Solution


def calibrate(
    case: Case | str | Path,
    fit: str | Sequence[str],
    data: str | Path | Measured | None = None,
    features: Mapping[str, float] | None = None,
    method: str = "ccfm",
    columns: Mapping[str, str] | None = None,
    overrides: Mapping[str, Any] | None = None,
    align_fraction: float = 0.1,
    max_nfev: int = 60,
    out: str | Path | None = None,
) -> Calibration:
    """Fit case fields to measured histories and/or features by least squares.

    Parameters
    ----------
    case
        Starting case (its values of the fitted fields are the starting point).
    fit
        Dotted case fields to fit, e.g. ``["contact.stiffness", "contact.restitution"]``.
    data
        CSV path (or :class:`Measured`) with time and force and/or velocity columns.
    features
        Measured summary metrics, e.g. ``{"peak_force": 584.0, "contact_duration": 6e-4}``
        (names from :data:`FEATURES`).
    columns
        CSV column names by role: ``{"time": "t", "force": "F", "velocity": "v"}``.
    overrides
        Dotted overrides applied to the case first.
    align_fraction
        Force level, as a fraction of the measured peak, at which data and model are aligned.
    out
        Directory for ``calibration.json``, ``fitted.toml``, ``overlay.png`` and, with ``data``, ``residuals.csv``.

    Returns
    -------
    Calibration
    """
    from ..registry import check_method

    check_method(method)
    _check_budget(max_nfev)
    base = load_case(case, dict(overrides) if overrides else None)
    params = [Parameter.of(base, k) for k in parse_fit(fit)]
    if columns and (data is None or isinstance(data, Measured)):  # (ignored before)
        raise ParameterError("--columns: it names the columns of a --data file, and none is given")
    measured = data if isinstance(data, Measured) or data is None else read_measured(data, columns)
    feats = dict(features or {})
    _check_measurements(measured, feats, method, align_fraction)
    problem = ResidualProblem(base, params, method, measured, feats, align_fraction)
    sol0 = problem.prepare()
    res, r0 = _least_squares(problem, max_nfev)
    u = _uncertainty(problem, res)
    result = _calibration(problem, res, u, sol0)
    if measured is not None:
        _add_history_fit(result, problem, res, r0, float(u.sd[-1]))
    if out is not None:
        result.write(out)
    return result


def _check_measurements(
    measured: Measured | None, features: dict[str, float], method: str, align_fraction: float
) -> None:
    """One-line :class:`ParameterError` for measurements a calibration cannot use: an unknown feature name, no
    measurement at all, a force history for IMM (which has no contact force), an alignment level outside (0, 1)."""
    for k, v in features.items():
        if k not in FEATURES:
            raise ParameterError(
                f"--features {k}: unknown feature; allowed: {', '.join(FEATURES)}{closest(k, FEATURES)}"
            )
        if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v):  # (as parse_features)
            raise ParameterError(f"--features {k}: must be a finite number (got {v!r})")
        if k in POSITIVE_FEATURES and not v > 0.0:  # a force, a duration or an impulse measured
            raise ParameterError(f"--features {k}: must be > 0 {METRICS[k].units} (got {v:g})")
    if measured is None and not features:
        raise ParameterError("calibrate: give measured histories (--data) and/or features (--features)")
    if measured is not None and measured.force is not None and method == "imm":
        raise ParameterError("method: 'imm' has no contact-force history to fit (use ccfm or ccm)")
    if not 0.0 < align_fraction < 1.0:
        raise ParameterError(f"align_fraction: must be in (0, 1) (got {align_fraction})")


def _check_budget(max_nfev: object) -> None:
    """max_nfev a whole number >= 1 (scipy's ValueError reached the caller raw)."""
    if isinstance(max_nfev, bool) or not isinstance(max_nfev, numbers.Integral) or max_nfev < 1:
        raise ParameterError(f"max_nfev: must be a whole number >= 1 (got {max_nfev!r})")


def _least_squares(problem: ResidualProblem, max_nfev: int) -> tuple[OptimizeResult, np.ndarray]:
    """Trust-region reflective least squares (:func:`scipy.optimize.least_squares`) of ``problem``'s residuals in
    the scaled variables, from the case's values (z = 0) within the fields' ranges: (scipy's result, the residuals
    at the start)."""
    import numpy as np
    from scipy.optimize import least_squares

    params = problem.params
    n_z = len(params) + (1 if problem.fit_shift else 0)
    z0 = np.zeros(n_z)
    # the time shift stays within one contact duration of the threshold alignment
    lo = np.array([p.bounds()[0] for p in params] + ([-1.0] if problem.fit_shift else []))
    hi = np.array([p.bounds()[1] for p in params] + ([1.0] if problem.fit_shift else []))
    r0 = problem.residuals(z0)
    if r0.size < n_z:
        raise ParameterError(
            f"calibrate: {r0.size} measured values cannot determine {n_z} parameters (give more features or histories)"
        )
    res = least_squares(
        problem.residuals, z0, bounds=(lo, hi), method="trf", diff_step=1e-3, x_scale=1.0, max_nfev=max_nfev
    )
    dead = [p.key for p, column in zip(params, res.jac.T) if not np.any(column)]
    if dead:  # (under CCM no contact law acts: its stiffness moved nothing, and the "fit" read as a success)
        raise ParameterError(
            f"--fit {', '.join(dead)}: changes none of the fitted quantities under {problem.method}, so it cannot be "
            "fitted (not identifiable)"
        )
    return res, r0


@dataclass
class _Uncertainty:
    """The covariance of the fitted values (fields, then the time shift [s]), their standard uncertainties, the
    correlation matrix, the residual variance sigma^2 and its degrees of freedom."""

    covariance: np.ndarray
    sd: np.ndarray
    correlation: np.ndarray
    s2: float
    dof: int


def _uncertainty(problem: ResidualProblem, res: OptimizeResult) -> _Uncertainty:
    """``C = sigma^2 (J^T J)^-1`` in the scaled variables (:func:`covariance`) mapped to the fields by the first-order
    change of variables ``C_x = C_z (dx/dz)(dx/dz)^T``; the correlation is that of the scaled variables."""
    import numpy as np

    cov_z, s2, dof = covariance(res.jac, res.fun)
    deriv = np.array(
        [p.derivative(float(z)) for p, z in zip(problem.params, res.x)]
        + ([problem.time_scale] if problem.fit_shift else [])
    )
    cov = cov_z * np.outer(deriv, deriv)
    with np.errstate(invalid="ignore", divide="ignore"):
        sd = np.sqrt(np.diag(cov))
        sd_z = np.sqrt(np.diag(cov_z))
        corr = cov_z / np.outer(sd_z, sd_z)
    return _Uncertainty(cov, sd, corr, s2, dof)


def _calibration(problem: ResidualProblem, res: OptimizeResult, u: _Uncertainty, sol0: Solution) -> Calibration:
    """The :class:`Calibration` of a finished fit: the fitted case and its run, the values, their uncertainties
    and the fit's diagnostics (the history-specific fields are :func:`_add_history_fit`'s)."""
    import numpy as np

    params = problem.params
    x_hat = problem.x_of(res.x)
    sol = problem.simulate(x_hat)
    names = [p.key for p in params] + (["time_shift"] if problem.fit_shift else [])
    return Calibration(
        case=load_case(problem.base, {p.key: v for p, v in zip(params, x_hat)}),
        method=problem.method,
        parameters=params,
        values=np.asarray(x_hat),
        uncertainty=u.sd[: len(params)],
        covariance=u.covariance,
        correlation=u.correlation,
        names=names,
        sigma=math.sqrt(u.s2) if math.isfinite(u.s2) else math.nan,
        dof=u.dof,
        cost=float(res.cost),
        nfev=int(res.nfev),
        success=bool(res.success),
        message=str(res.message),
        active=[names[i] for i in np.nonzero(res.active_mask)[0]],
        residuals=res.fun,
        solution=sol,
        initial_solution=sol0,
        measured=problem.measured,
        features=problem.features,
    )


def _add_history_fit(
    result: Calibration, problem: ResidualProblem, res: OptimizeResult, r0: np.ndarray, shift_sd: float
) -> None:
    """Fill ``result``'s history fields: the fitted time shift [s] and its standard uncertainty ``shift_sd``, the
    data samples used and their aligned times, the model's alignment instants (initial and fitted run), and each
    channel's rms residual (in the channel's units) at the start (``r0``) and after the fit."""
    import numpy as np

    n = int(np.count_nonzero(problem.mask))
    result.time_shift = float(res.x[-1]) * problem.time_scale
    result.time_shift_uncertainty = shift_sd
    result.aligned_time = problem.tau[problem.mask]
    result.data_mask = problem.mask
    result.model_reference = (problem.reference(result.initial_solution), problem.reference(result.solution))
    for i, (chan, scale) in enumerate(zip(result.measured.channels, problem.scales)):
        result.channel_rms[chan] = float(np.sqrt(np.mean(res.fun[i * n : (i + 1) * n] ** 2)) * scale)
        result.channel_rms_initial[chan] = float(np.sqrt(np.mean(r0[i * n : (i + 1) * n] ** 2)) * scale)
