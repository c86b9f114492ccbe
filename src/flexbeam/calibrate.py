"""Calibration: least-squares fit of case parameters to measured impacts.

Two kinds of measurement, which may be combined:

* **histories** -- a CSV file with a time column and a contact-force and/or a
  normal-velocity column (SI units: s, N, m/s; velocity positive away from the
  obstacle, as ``normal_velocity``).  Data and model are aligned on the first contact:
  both time axes are shifted to the instant the force first reaches 10 % of the
  measured peak (linear interpolation between samples; without a force column the
  data's time is taken as time since the onset), and a remaining time shift is
  fitted with the parameters (a nuisance parameter within one contact duration,
  reported as ``time_shift``).
  The model's samples are interpolated linearly onto the data times.  Residuals are
  divided by the channel's largest measured magnitude.
* **features** -- summary numbers such as ``peak_force=584``; residuals are relative,
  ``(model - measured) / |measured|``.  A trial whose force has no second peak counts
  ``second_peak_force = 0`` (the limit of a vanishing shoulder).

The fit is :func:`scipy.optimize.least_squares` (trust-region reflective) in scaled
variables: ``z = ln(x / x0)`` for a field that is positive without an upper limit
(stiffness, moduli), ``z = (x - x0) / s`` otherwise, with ``s`` the allowed range when
the field has one (restitution: [0, 1]) and the field's range as bounds.  The
standard uncertainty of the fitted values is ``sqrt(diag(C))`` with
``C = sigma^2 (J^T J)^-1`` in the scaled variables mapped back to the fields
(``J``: finite-difference Jacobian at the solution, ``sigma^2 = |r|^2 / (m - p)``).
It assumes independent residuals of equal variance, so with histories it is only
as good as the noise is white; with as many features as parameters it is undefined.

The simulated time is cut to what the measurements need (the first contact and its
aftermath for first-contact features, the data's span for histories) unless
``solver.t_end`` is already shorter.
"""

from __future__ import annotations

import csv
import json
import math
import re
import types
import typing
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .errors import ModelError, ParameterError, SolverError, closest
from .parameters.case import Case
from .parameters.io import load_case, parse_value, set_dotted

if TYPE_CHECKING:
    import numpy as np

    from .solution import Solution

#: metrics of the first contact alone (the fit may stop the simulation after it)
FIRST_CONTACT_FEATURES = ("peak_force", "peak_time", "contact_duration", "second_peak_force", "impact_velocity",
                          "post_impact_velocity", "impulse", "energy_before", "energy_after",
                          "sensor_peak_force", "sensor_second_peak_force", "sensor_duration")
#: features that read 0 when a trial's force has a single peak
SECOND_PEAKS = ("second_peak_force", "sensor_second_peak_force")
#: metrics that can be fitted as features
FEATURES = FIRST_CONTACT_FEATURES + ("contacts", "tip_deflection_min", "tip_deflection_max")
#: CSV column roles and the column names tried when ``columns`` does not name them
ROLES = {"time": ("time", "t"), "force": ("force", "contact_force", "F"),
         "velocity": ("velocity", "normal_velocity", "v")}


# ------------------------------------------------------------------------ inputs
@dataclass
class Measured:
    """Measured histories: time [s], contact force [N] and/or normal velocity [m/s]."""

    time: np.ndarray
    force: np.ndarray | None = None
    velocity: np.ndarray | None = None
    source: str = ""

    @property
    def channels(self) -> list[str]:
        return [c for c in ("force", "velocity") if getattr(self, c) is not None]


def parse_columns(text: str | None) -> dict[str, str]:
    """``"time=t,force=F"`` -> ``{"time": "t", "force": "F"}`` (roles: time, force, velocity)."""
    out: dict[str, str] = {}
    for item in (text or "").split(","):
        if not item.strip():
            continue
        role, sep, name = item.partition("=")
        role = role.strip()
        if not sep or not name.strip():
            raise ParameterError(f"--columns: expected ROLE=COLUMN,... (got '{item}')")
        if role not in ROLES:
            raise ParameterError(f"--columns: unknown role '{role}'; allowed: {', '.join(ROLES)}{closest(role, ROLES)}")
        out[role] = name.strip()
    return out


def parse_features(text: str | None) -> dict[str, float]:
    """``"peak_force=584,contact_duration=0.6e-3"`` -> dict of measured values."""
    out: dict[str, float] = {}
    for item in (text or "").split(","):
        if not item.strip():
            continue
        name, sep, value = item.partition("=")
        name = name.strip()
        v = parse_value(value.strip()) if sep else None
        if not sep or isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ParameterError(f"--features: expected NAME=NUMBER,... (got '{item}')")
        out[name] = float(v)
    return out


def parse_fit(text: str | Sequence[str]) -> list[str]:
    """``"contact.stiffness,contact.restitution"`` -> list of dotted keys."""
    items = text.split(",") if isinstance(text, str) else list(text)
    keys = [k.strip() for k in items if k.strip()]
    if not keys:
        raise ParameterError("--fit: give at least one case field, e.g. contact.stiffness")
    if len(set(keys)) != len(keys):
        raise ParameterError(f"--fit: a field is given twice ({', '.join(keys)})")
    return keys


def read_measured(path: str | Path, columns: Mapping[str, str] | None = None) -> Measured:
    """Read a CSV file with a header row (``#`` lines are comments) into :class:`Measured`.

    ``columns`` maps roles (time, force, velocity) to column names; a role it does not
    name is looked up under the names in :data:`ROLES`, except that naming force or
    velocity selects just the channels named.
    """
    import numpy as np

    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as f:
            rows = [r for r in csv.reader(line for line in f if not line.lstrip().startswith("#")) if r]
    except OSError as exc:
        raise ParameterError(f"data: cannot read '{path}': {exc.strerror}") from None
    if len(rows) < 3:
        raise ParameterError(f"data: '{path}' needs a header row and at least two data rows")
    header = [h.strip() for h in rows[0]]
    columns = dict(columns or {})
    named_channels = {"force", "velocity"} & set(columns)
    chosen: dict[str, int] = {}
    for role, candidates in ROLES.items():
        if named_channels and role != "time" and role not in named_channels:
            continue  # --columns names the channels to fit: only those
        if role in columns:
            name = columns[role]
            if name not in header:
                raise ParameterError(f"--columns {role}: no column '{name}' in '{path}'; columns: "
                                     f"{', '.join(header)}{closest(name, header)}")
            chosen[role] = header.index(name)
        else:
            for name in candidates:
                if name in header:
                    chosen[role] = header.index(name)
                    break
    if "time" not in chosen:
        raise ParameterError(f"data: no time column in '{path}' (columns: {', '.join(header)}); "
                             "name it with --columns time=NAME")
    if "force" not in chosen and "velocity" not in chosen:
        raise ParameterError(f"data: no force or velocity column in '{path}' (columns: {', '.join(header)}); "
                             "name them with --columns force=NAME,velocity=NAME")
    values: dict[str, np.ndarray] = {}
    for role, j in chosen.items():
        col = []
        for i, row in enumerate(rows[1:], 2):
            try:
                col.append(float(row[j]))
            except (ValueError, IndexError):
                raise ParameterError(f"data: '{path}' row {i}, column '{header[j]}': not a number") from None
        values[role] = np.asarray(col)
    ok = np.all([np.isfinite(v) for v in values.values()], axis=0)
    t = values["time"][ok]
    if t.size < 2 or np.any(np.diff(t) <= 0):
        raise ParameterError(f"data: the time column of '{path}' must increase strictly")
    return Measured(t, values["force"][ok] if "force" in values else None,
                    values["velocity"][ok] if "velocity" in values else None, str(path))


# -------------------------------------------------------------------- parameters
def _field(key: str) -> tuple[float, float, bool, str]:
    """(lower, upper, is_real, units) of a dotted case field, from the schema."""
    from annotated_types import Ge, Gt, Le, Lt
    from pydantic import BaseModel
    from pydantic.fields import FieldInfo

    set_dotted({}, key, 0.0)  # unknown keys -> ParameterError with best matches
    model: Any = Case
    parts = key.split(".")
    for part in parts[:-1]:
        model = model.model_fields[part].annotation
    info = model.model_fields[parts[-1]]
    metas: list[Any] = list(info.metadata)
    bases: list[Any] = []

    def walk(ann: Any) -> None:
        origin = typing.get_origin(ann)
        if origin is typing.Annotated:
            args = typing.get_args(ann)
            metas.extend(args[1:])
            walk(args[0])
        elif origin in (typing.Union, types.UnionType):
            for a in typing.get_args(ann):
                walk(a)
        else:
            bases.append(ann)

    walk(info.annotation)
    for m in list(metas):
        if isinstance(m, FieldInfo):
            metas.extend(m.metadata)
    lo, hi = -math.inf, math.inf
    for m in metas:
        if isinstance(m, (Ge, Gt)):
            lo = max(lo, float(m.ge if isinstance(m, Ge) else m.gt))
        elif isinstance(m, (Le, Lt)):
            hi = min(hi, float(m.le if isinstance(m, Le) else m.lt))
    is_real = float in bases and not any(isinstance(b, type) and issubclass(b, BaseModel) for b in bases)
    found = re.search(r"\[([^\]]+)\]", info.description or "")
    return lo, hi, is_real, found.group(1) if found else ""


@dataclass
class Parameter:
    """A fitted field and its scaling: ``x = x0 exp(z)`` (log) or ``x = x0 + scale z``."""

    key: str
    x0: float
    lower: float
    upper: float
    log: bool
    scale: float
    units: str = ""

    @classmethod
    def of(cls, case: Case, key: str) -> Parameter:
        lo, hi, is_real, units = _field(key)
        if not is_real:
            raise ParameterError(f"--fit {key}: not a real-valued field (only numbers can be fitted)")
        x0 = _get(case, key)
        if x0 is None and key == "contact.stiffness":
            from .model.system import BeamSystem

            x0 = BeamSystem.from_case(case).law.stiffness
        if x0 is None:
            raise ParameterError(f"--fit {key}: the case gives no value; give a starting value with --set {key}=VALUE")
        x0 = float(x0)
        if lo >= 0.0 and math.isinf(hi) and x0 > 0.0:
            return cls(key, x0, lo, hi, True, 1.0, units)
        scale = hi - lo if math.isfinite(hi - lo) else (abs(x0) or 1.0)
        return cls(key, x0, lo, hi, False, scale, units)

    def value(self, z: float) -> float:
        return self.x0 * math.exp(z) if self.log else self.x0 + self.scale * z

    def derivative(self, z: float) -> float:
        """dx/dz."""
        return self.value(z) if self.log else self.scale

    def bounds(self) -> tuple[float, float]:
        if self.log:
            lo = math.log(self.lower / self.x0) if self.lower > 0 else -math.inf
            return lo, math.inf
        return (self.lower - self.x0) / self.scale, (self.upper - self.x0) / self.scale


def _get(case: Case, key: str) -> Any:
    obj: Any = case
    for part in key.split("."):
        obj = getattr(obj, part)
    return obj


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


# ------------------------------------------------------------------------ result
@dataclass
class Calibration:
    """Result of :func:`calibrate`.

    ``values``/``uncertainty`` hold the fitted fields (in ``parameters`` order);
    ``time_shift`` is the fitted alignment offset [s] when histories were fitted.
    """

    case: Case
    method: str
    parameters: list[Parameter]
    values: np.ndarray
    uncertainty: np.ndarray
    covariance: np.ndarray
    correlation: np.ndarray
    names: list[str]
    sigma: float
    dof: int
    cost: float
    nfev: int
    success: bool
    message: str
    active: list[str]
    residuals: np.ndarray
    solution: Solution
    initial_solution: Solution
    measured: Measured | None = None
    features: dict[str, float] = field(default_factory=dict)
    time_shift: float = math.nan
    time_shift_uncertainty: float = math.nan
    channel_rms: dict[str, float] = field(default_factory=dict)
    channel_rms_initial: dict[str, float] = field(default_factory=dict)
    aligned_time: np.ndarray | None = None  # data times used, relative to the data's alignment instant [s]
    data_mask: np.ndarray | None = None  # which data samples were used (inside the simulated time)
    model_reference: tuple[float, float] = (math.nan, math.nan)  # (initial, fitted) alignment instants [s]

    @property
    def fitted(self) -> dict[str, float]:
        return {p.key: float(v) for p, v in zip(self.parameters, self.values)}

    def _repr_html_(self) -> str:
        """Notebook display (:func:`flexbeam.display.calibration_html`)."""
        from .display import calibration_html

        return calibration_html(self)

    def to_dict(self) -> dict[str, Any]:
        """The JSON report (``flexbeam calibrate --json``)."""
        from .solution import _jsonable

        m_fit, m_init = self.solution.metrics(), self.initial_solution.metrics()
        out: dict[str, Any] = {
            "case": self.case.name,
            "method": self.method,
            "parameters": {
                p.key: {"initial": p.x0, "value": float(v), "uncertainty": float(u), "units": p.units,
                        "scaling": "log" if p.log else "linear", "at_bound": p.key in self.active}
                for p, v, u in zip(self.parameters, self.values, self.uncertainty)
            },
            "correlation": {"names": self.names, "matrix": self.correlation.tolist()},
            "residuals": {
                "sigma": self.sigma, "dof": self.dof, "cost": self.cost, "count": int(self.residuals.size),
                "rms": float(math.sqrt(float(self.residuals @ self.residuals) / max(self.residuals.size, 1))),
            },
            "nfev": self.nfev,
            "success": self.success,
            "message": self.message,
        }
        if self.measured is not None:
            out["data"] = {"file": self.measured.source, "samples": int(self.aligned_time.size)
                           if self.aligned_time is not None else 0,
                           "channels": self.measured.channels,
                           "rms": self.channel_rms, "rms_initial": self.channel_rms_initial,
                           "time_shift": self.time_shift, "time_shift_uncertainty": self.time_shift_uncertainty}
        if self.features:
            out["features"] = {k: {"measured": v, "initial": m_init.get(k), "fitted": m_fit.get(k),
                                   "residual": (m_fit.get(k, math.nan) - v)}
                               for k, v in self.features.items()}
        out["metrics"] = {k: v for k, v in m_fit.items() if k not in ("force_peaks", "force_peak_times")}
        return _jsonable(out)

    def write(self, out: str | Path) -> dict[str, Path]:
        """``calibration.json``, ``fitted.toml`` (runs with ``flexbeam run``), ``overlay.png``
        and, for histories, ``residuals.csv`` in the directory ``out``."""
        from .parameters.io import dump_case
        from .solution import write_text_atomic

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        files = {
            "report": write_text_atomic(out / "calibration.json", json.dumps(self.to_dict(), indent=2)),
            "case": write_text_atomic(out / "fitted.toml", dump_case(self.case)),
            "overlay": self.plot(out / "overlay.png"),
        }
        if self.measured is not None and self.aligned_time is not None:
            lines = ["time_after_onset," + ",".join(f"{c}_residual" for c in self.measured.channels)]
            n = self.aligned_time.size
            parts = [self.residuals[i * n:(i + 1) * n] * _channel_scale(self.measured, c)
                     for i, c in enumerate(self.measured.channels)]
            for i in range(n):
                lines.append(f"{self.aligned_time[i]:.9g}," + ",".join(f"{p[i]:.9g}" for p in parts))
            files["residuals"] = write_text_atomic(out / "residuals.csv", "\n".join(lines) + "\n")
        return files

    def plot(self, path: str | Path) -> Path:
        """Measured data (or feature values) overlaid on the initial and fitted model."""
        from .plotting import _pyplot, _save

        plt = _pyplot()
        label = ", ".join(f"{p.key} = {v:.4g}" for p, v in zip(self.parameters, self.values))
        if self.measured is not None and self.aligned_time is not None and self.data_mask is not None:
            chans = self.measured.channels
            fig, axes = plt.subplots(len(chans), 1, figsize=(6.4, 3.2 * len(chans)), squeeze=False)
            tau = self.aligned_time
            lo, hi = float(tau.min()), float(tau.max())
            for ax, chan in zip(axes[:, 0], chans):
                var = "contact_force" if chan == "force" else "normal_velocity"
                ax.plot(tau * 1e3, getattr(self.measured, chan)[self.data_mask], ".", ms=2, c="0.5", label="measured")
                for sol, ref, shift, style, name in (
                    (self.initial_solution, self.model_reference[0], 0.0, "--", "initial"),
                    (self.solution, self.model_reference[1], _nan0(self.time_shift), "-", f"fitted: {label}"),
                ):
                    t = sol.time - ref - shift
                    sel = (t >= lo) & (t <= hi)
                    ax.plot(t[sel] * 1e3, sol[var][sel], style, lw=1.2, label=name)
                ax.set_ylabel("Contact force [N]" if chan == "force" else "Normal velocity of P [m/s]")
                ax.grid(alpha=0.3)
                ax.legend(fontsize=7)
            axes[-1, 0].set_xlabel("Time after first contact [ms]")
            axes[0, 0].set_title(f"{self.case.name}: calibration ({self.method.upper()})")
        else:
            fig, ax = plt.subplots(figsize=(6.4, 4.0))
            for sol, style, name in ((self.initial_solution, "--", "initial"),
                                     (self.solution, "-", f"fitted: {label}")):
                t0 = sol.contacts[0].onset if sol.contacts else 0.0
                dur = sol.contacts[0].duration if sol.contacts and math.isfinite(sol.contacts[0].duration) else 1e-3
                sel = (sol.time >= t0 - 0.1 * dur) & (sol.time <= t0 + 1.5 * dur)
                ax.plot((sol.time[sel] - t0) * 1e3, sol["contact_force"][sel], style, lw=1.2, label=name)
            f = self.features
            for key, ls in (("peak_force", "--"), ("second_peak_force", ":")):
                if key in f:
                    ax.axhline(f[key], ls=ls, c="k", lw=0.8, label=f"measured {key} {f[key]:g} N")
            if "contact_duration" in f:
                ax.axvline(f["contact_duration"] * 1e3, ls="-.", c="0.4", lw=0.8,
                           label=f"measured contact_duration {f['contact_duration'] * 1e3:g} ms")
            ax.set_xlabel("Time after first contact [ms]")
            ax.set_ylabel("Contact force [N]")
            ax.set_title(f"{self.case.name}: calibration to features ({self.method.upper()})")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        return _save(fig, path)


def _nan0(x: float) -> float:
    return 0.0 if not math.isfinite(x) else x


def _channel_scale(measured: Measured, channel: str) -> float:
    import numpy as np

    v = getattr(measured, channel)
    return float(np.max(np.abs(v))) or 1.0


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


# ------------------------------------------------------------------------- model
class _Problem:
    """Residuals of one calibration as a function of the scaled variables."""

    def __init__(self, base: Case, params: list[Parameter], method: str, measured: Measured | None,
                 features: dict[str, float], align_fraction: float) -> None:
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
            self.scales = [_channel_scale(measured, c) for c in measured.channels]

    # -- simulation with a small cache (the finite-difference Jacobian's time-shift column reuses it)
    def case_at(self, x: Sequence[float]) -> Case:
        return load_case(self.case, {p.key: float(v) for p, v in zip(self.params, x)})

    def simulate(self, x: Sequence[float]) -> Solution:
        from .simulation import simulate

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
        if not whole and ended and need < t_try:
            self.case = load_case(self.base, {"solver.t_end": need})
            self.cache.clear()
            sol = self.simulate(x0)
        if not sol.contacts:
            raise ModelError("calibration: the initial case has no contact within solver.t_end")
        for k in self.features:
            if not math.isfinite(float(sol.metrics().get(k, math.nan))):
                raise ParameterError(f"--features {k}: the initial model gives no value for it "
                                     f"(e.g. a rigid or few-mode beam has no second force peak)")
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

    from .simulation import METHOD_NAMES

    if method not in METHOD_NAMES:
        raise ParameterError(f"method: unknown impact method '{method}'; allowed: "
                             f"{', '.join(METHOD_NAMES)}{closest(method, METHOD_NAMES)}")
    base = load_case(case, dict(overrides) if overrides else None)
    keys = parse_fit(fit)
    params = [Parameter.of(base, k) for k in keys]
    measured = data if isinstance(data, Measured) or data is None else read_measured(data, columns)
    feats = dict(features or {})
    for k in feats:
        if k not in FEATURES:
            raise ParameterError(f"--features {k}: unknown feature; allowed: {', '.join(FEATURES)}"
                                 f"{closest(k, FEATURES)}")
    if measured is None and not feats:
        raise ParameterError("calibrate: give measured histories (--data) and/or features (--features)")
    if measured is not None and measured.force is not None and method == "imm":
        raise ParameterError("method: 'imm' has no contact-force history to fit (use ccfm or ccm)")
    if not 0.0 < align_fraction < 1.0:
        raise ParameterError(f"align_fraction: must be in (0, 1) (got {align_fraction})")
    problem = _Problem(base, params, method, measured, feats, align_fraction)
    sol0 = problem.prepare()
    n_z = len(params) + (1 if problem.fit_shift else 0)
    z0 = np.zeros(n_z)
    # the time shift stays within one contact duration of the threshold alignment
    lo = np.array([p.bounds()[0] for p in params] + ([-1.0] if problem.fit_shift else []))
    hi = np.array([p.bounds()[1] for p in params] + ([1.0] if problem.fit_shift else []))
    r0 = problem.residuals(z0)
    if r0.size < n_z:
        raise ParameterError(f"calibrate: {r0.size} measured values cannot determine {n_z} parameters "
                             "(give more features or histories)")
    res = least_squares(problem.residuals, z0, bounds=(lo, hi), method="trf", diff_step=1e-3, x_scale=1.0,
                        max_nfev=max_nfev)
    cov_z, s2, dof = covariance(res.jac, res.fun)
    deriv = np.array([p.derivative(float(z)) for p, z in zip(params, res.x)]
                     + ([problem.time_scale] if problem.fit_shift else []))
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
        case=fitted_case, method=method, parameters=params, values=np.asarray(x_hat), uncertainty=sd[: len(params)],
        covariance=cov, correlation=corr, names=names, sigma=math.sqrt(s2) if math.isfinite(s2) else math.nan,
        dof=dof, cost=float(res.cost), nfev=int(res.nfev), success=bool(res.success), message=str(res.message),
        active=active, residuals=res.fun, solution=sol, initial_solution=sol0, measured=measured, features=feats,
    )
    if measured is not None:
        n = int(np.count_nonzero(problem.mask))
        result.time_shift = float(res.x[-1]) * problem.time_scale
        result.time_shift_uncertainty = float(sd[-1])
        result.aligned_time = problem.tau[problem.mask]
        result.data_mask = problem.mask
        result.model_reference = (problem.reference(sol0), problem.reference(sol))
        for i, (chan, scale) in enumerate(zip(measured.channels, problem.scales)):
            result.channel_rms[chan] = float(np.sqrt(np.mean(res.fun[i * n:(i + 1) * n] ** 2)) * scale)
            result.channel_rms_initial[chan] = float(np.sqrt(np.mean(r0[i * n:(i + 1) * n] ** 2)) * scale)
    if out is not None:
        result.write(out)
    return result
