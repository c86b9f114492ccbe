"""Calibration: the least-squares fit of case fields to measured histories and/or features."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from ..errors import ParameterError, closest
from ..parameters.case import Case
from ..parameters.io import load_case
from ..results.metrics import FEATURES
from .fields import Parameter, parse_fit
from .measured import Measured, read_measured
from .problem import ResidualProblem, covariance
from .result import Calibration


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
        Directory for ``calibration.json``, ``fitted.toml``, ``overlay.png``, ``residuals.csv``.

    Returns
    -------
    Calibration
    """
    import numpy as np
    from scipy.optimize import least_squares

    from ..registry import METHOD_NAMES

    if method not in METHOD_NAMES:
        raise ParameterError(
            f"method: unknown impact method '{method}'; allowed: "
            f"{', '.join(METHOD_NAMES)}{closest(method, METHOD_NAMES)}"
        )
    base = load_case(case, dict(overrides) if overrides else None)
    keys = parse_fit(fit)
    params = [Parameter.of(base, k) for k in keys]
    measured = data if isinstance(data, Measured) or data is None else read_measured(data, columns)
    feats = dict(features or {})
    for k in feats:
        if k not in FEATURES:
            raise ParameterError(
                f"--features {k}: unknown feature; allowed: {', '.join(FEATURES)}{closest(k, FEATURES)}"
            )
    if measured is None and not feats:
        raise ParameterError("calibrate: give measured histories (--data) and/or features (--features)")
    if measured is not None and measured.force is not None and method == "imm":
        raise ParameterError("method: 'imm' has no contact-force history to fit (use ccfm or ccm)")
    if not 0.0 < align_fraction < 1.0:
        raise ParameterError(f"align_fraction: must be in (0, 1) (got {align_fraction})")
    problem = ResidualProblem(base, params, method, measured, feats, align_fraction)
    sol0 = problem.prepare()
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
    cov_z, s2, dof = covariance(res.jac, res.fun)
    deriv = np.array(
        [p.derivative(float(z)) for p, z in zip(params, res.x)] + ([problem.time_scale] if problem.fit_shift else [])
    )
    cov = cov_z * np.outer(deriv, deriv)
    with np.errstate(invalid="ignore", divide="ignore"):
        sd = np.sqrt(np.diag(cov))
        sd_z = np.sqrt(np.diag(cov_z))
        corr = cov_z / np.outer(sd_z, sd_z)
    x_hat = problem.x_of(res.x)
    sol = problem.simulate(x_hat)
    names = keys + (["time_shift"] if problem.fit_shift else [])
    active = [names[i] for i in np.nonzero(res.active_mask)[0]]
    fitted_case = load_case(base, {p.key: v for p, v in zip(params, x_hat)})
    result = Calibration(
        case=fitted_case,
        method=method,
        parameters=params,
        values=np.asarray(x_hat),
        uncertainty=sd[: len(params)],
        covariance=cov,
        correlation=corr,
        names=names,
        sigma=math.sqrt(s2) if math.isfinite(s2) else math.nan,
        dof=dof,
        cost=float(res.cost),
        nfev=int(res.nfev),
        success=bool(res.success),
        message=str(res.message),
        active=active,
        residuals=res.fun,
        solution=sol,
        initial_solution=sol0,
        measured=measured,
        features=feats,
    )
    if measured is not None:
        n = int(np.count_nonzero(problem.mask))
        result.time_shift = float(res.x[-1]) * problem.time_scale
        result.time_shift_uncertainty = float(sd[-1])
        result.aligned_time = problem.tau[problem.mask]
        result.data_mask = problem.mask
        result.model_reference = (problem.reference(sol0), problem.reference(sol))
        for i, (chan, scale) in enumerate(zip(measured.channels, problem.scales)):
            result.channel_rms[chan] = float(np.sqrt(np.mean(res.fun[i * n : (i + 1) * n] ** 2)) * scale)
            result.channel_rms_initial[chan] = float(np.sqrt(np.mean(r0[i * n : (i + 1) * n] ** 2)) * scale)
    if out is not None:
        result.write(out)
    return result
