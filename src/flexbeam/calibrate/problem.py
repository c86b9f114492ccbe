"""The least-squares problem: residuals of measurements against simulations, and their covariance."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..errors import ModelError, ParameterError, SolverError
from ..parameters.case import Case
from ..parameters.io import load_case
from ..results.metrics import FIRST_CONTACT_FEATURES, SECOND_PEAKS
from .fields import Parameter
from .measured import Measured

if TYPE_CHECKING:
    import numpy as np

    from ..results.solution import Solution


def covariance(jac: np.ndarray, residuals: np.ndarray) -> tuple[np.ndarray, float, int]:
    """``sigma^2 (J^T J)^-1``, ``sigma^2 = |r|^2 / (m - p)`` and ``m - p``.

    Singular ``J^T J`` (a parameter the residuals do not depend on) gives infinite
    variances; ``m == p`` gives NaN (no residual degrees of freedom).
    """
    import numpy as np

    m, p = jac.shape
    dof = m - p
    s2 = float(residuals @ residuals) / dof if dof > 0 else math.nan
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    if s.size == 0 or s[-1] <= np.finfo(float).eps * max(m, p) * s[0]:
        return np.full((p, p), math.inf), s2, dof
    return s2 * (vt.T / s**2) @ vt, s2, dof


def _crossing(t: np.ndarray, f: np.ndarray, level: float) -> float:
    """First time ``f`` reaches ``level`` (linear interpolation between samples); NaN if never."""
    import numpy as np

    idx = np.nonzero(f >= level)[0]
    if idx.size == 0:
        return math.nan
    i = int(idx[0])
    if i == 0 or f[i] == f[i - 1]:
        return float(t[i])
    return float(t[i - 1] + (level - f[i - 1]) * (t[i] - t[i - 1]) / (f[i] - f[i - 1]))


class ResidualProblem:
    """Residuals of one calibration as a function of the scaled variables."""

    def __init__(
        self,
        base: Case,
        params: list[Parameter],
        method: str,
        measured: Measured | None,
        features: dict[str, float],
        align_fraction: float,
    ) -> None:
        import numpy as np

        self.base, self.params, self.method = base, params, method
        self.measured, self.features = measured, features
        self.cache: dict[tuple[float, ...], Solution] = {}
        self.case = base
        self.level = math.nan
        self.tau = np.empty(0)
        self.mask = np.empty(0, dtype=bool)
        self.scales: list[float] = []
        self.time_scale = 1.0
        if measured is not None:
            if measured.force is not None:
                peak = float(np.max(measured.force))
                if not peak > 0:
                    raise ParameterError(f"data: the force column of '{measured.source}' has no positive value")
                self.level = align_fraction * peak
                self.tau = measured.time - _crossing(measured.time, measured.force, self.level)
            else:
                self.tau = measured.time.copy()
            self.scales = [measured.scale(c) for c in measured.channels]

    # -- simulation with a small cache (the finite-difference Jacobian's time-shift column reuses it)
    def case_at(self, x: Sequence[float]) -> Case:
        return load_case(self.case, {p.key: float(v) for p, v in zip(self.params, x)})

    def simulate(self, x: Sequence[float]) -> Solution:
        from ..simulation import simulate

        key = tuple(float(v) for v in x)
        if key not in self.cache:
            case = self.case_at(x)
            try:
                sol = simulate(case, self.method)
            except SolverError as exc:
                raise SolverError(f"calibration: at {self._where(x)}: {exc}") from None
            if sol.status == "failed":
                raise SolverError(f"calibration: the simulation failed at {self._where(x)}: {sol.message}")
            if len(self.cache) >= 8:
                self.cache.pop(next(iter(self.cache)))
            self.cache[key] = sol
        return self.cache[key]

    def _where(self, x: Sequence[float]) -> str:
        return ", ".join(f"{p.key} = {v:.6g}" for p, v in zip(self.params, x))

    def reference(self, sol: Solution) -> float:
        """Model instant aligned with the data's reference (force crossing or onset)."""
        onset = sol.contacts[0].onset if sol.contacts else 0.0
        if math.isfinite(self.level):
            t = _crossing(sol.time, sol["contact_force"], self.level)
            if math.isfinite(t):
                return t
        return onset

    # -- set-up: the initial run, the simulated window and the samples used
    def prepare(self) -> Solution:
        """Run the initial case, cut ``solver.t_end`` to what is needed, choose the data samples."""
        import numpy as np

        x0 = [p.x0 for p in self.params]
        t_case = self.base.solver.t_end
        whole = any(k not in FIRST_CONTACT_FEATURES for k in self.features)
        span = float(self.tau.max()) if self.measured is not None else 0.0
        t_try = t_case if whole else min(t_case, max(2e-3, 1.2 * span))
        while True:
            self.case = load_case(self.base, {"solver.t_end": t_try})
            sol = self.simulate(x0)
            ended = bool(sol.contacts) and math.isfinite(sol.contacts[0].end)
            need = 0.0
            if ended:
                ev = sol.contacts[0]
                need = ev.end + 2.0 * ev.duration if self.features else 0.0
                if self.measured is not None:
                    need = max(need, self.reference(sol) + span + 0.05 * (span - float(self.tau.min())))
            if t_try >= t_case or (ended and need <= t_try):
                break
            t_try = min(t_case, max(4.0 * t_try, need))
        if not whole and ended and sol.contacts[0].end < need < t_try:  # (IMM's impact has no duration: no cut)
            self.case = load_case(self.base, {"solver.t_end": need})
            self.cache.clear()
            sol = self.simulate(x0)
        if not sol.contacts:
            raise ModelError("calibration: the initial case has no contact within solver.t_end")
        first = [k for k in self.features if k in FIRST_CONTACT_FEATURES]
        if first and not math.isfinite(sol.contacts[0].end):  # (its peak was the force at t_end: a fit to nothing)
            raise ParameterError(
                f"solver.t_end: {self.case.solver.t_end:g} s ends inside the first contact (from "
                f"{sol.contacts[0].onset:.6g} s), whose end --features {', '.join(first)} read: raise solver.t_end"
            )
        for k in self.features:
            if not math.isfinite(float(sol.metrics().get(k, math.nan))):
                raise ParameterError(
                    f"--features {k}: the initial model gives no value for it "
                    f"(e.g. a rigid or few-mode beam has no second force peak)"
                )
        if self.measured is not None:
            ref = self.reference(sol)
            self.mask = self.tau <= self.case.solver.t_end - ref
            if np.count_nonzero(self.mask) < len(self.params) + 2:
                raise ParameterError("data: too few samples inside the simulated time (raise solver.t_end)")
            ev = sol.contacts[0]
            self.time_scale = ev.duration if math.isfinite(ev.duration) and ev.duration > 0 else max(span, 1e-6)
        return sol

    @property
    def fit_shift(self) -> bool:
        return self.measured is not None

    def x_of(self, z: Sequence[float]) -> list[float]:
        return [p.value(float(zi)) for p, zi in zip(self.params, z)]

    def residuals(self, z: np.ndarray) -> np.ndarray:
        import numpy as np

        x = self.x_of(z)
        sol = self.simulate(x)
        parts: list[np.ndarray] = []
        if self.measured is not None:
            shift = float(z[-1]) * self.time_scale
            t = self.tau[self.mask] + self.reference(sol) + shift
            for chan, scale in zip(self.measured.channels, self.scales):
                var = "contact_force" if chan == "force" else "normal_velocity"
                model = np.interp(t, sol.time, sol[var])
                parts.append((model - getattr(self.measured, chan)[self.mask]) / scale)
        if self.features:
            metrics = sol.metrics()
            for k, v in self.features.items():
                m = float(metrics.get(k, math.nan))
                if k in SECOND_PEAKS and not math.isfinite(m):
                    # a trial force with a single peak: its second peak has shrunk to nothing
                    # (the limit of a vanishing shoulder), so the residual stays defined
                    m = 0.0
                if not math.isfinite(m):
                    raise ModelError(f"calibration: feature {k} is undefined at {self._where(x)}")
                parts.append(np.array([(m - v) / (abs(v) or 1.0)]))
        return np.concatenate(parts)
