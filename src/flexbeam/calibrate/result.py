"""The result of a calibration: fitted values, uncertainties, the JSON report, files and overlay plot."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..parameters.case import Case
from .fields import Parameter
from .measured import Measured

if TYPE_CHECKING:
    import numpy as np

    from ..results.solution import Solution


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
        """Notebook display (:func:`flexbeam.views.display.calibration_html`)."""
        from ..views.display import calibration_html

        return calibration_html(self)

    def to_dict(self) -> dict[str, Any]:
        """The JSON report (``flexbeam calibrate --json``)."""
        from ..results.files import jsonable

        m_fit, m_init = self.solution.metrics(), self.initial_solution.metrics()
        out: dict[str, Any] = {
            "case": self.case.name,
            "method": self.method,
            "parameters": {
                p.key: {
                    "initial": p.x0,
                    "value": float(v),
                    "uncertainty": float(u),
                    "units": p.units,
                    "scaling": "log" if p.log else "linear",
                    "at_bound": p.key in self.active,
                }
                for p, v, u in zip(self.parameters, self.values, self.uncertainty)
            },
            "correlation": {"names": self.names, "matrix": self.correlation.tolist()},
            "residuals": {
                "sigma": self.sigma,
                "dof": self.dof,
                "cost": self.cost,
                "count": int(self.residuals.size),
                "rms": float(math.sqrt(float(self.residuals @ self.residuals) / max(self.residuals.size, 1))),
            },
            "nfev": self.nfev,
            "success": self.success,
            "message": self.message,
        }
        if self.measured is not None:
            out["data"] = {
                "file": self.measured.source,
                "samples": int(self.aligned_time.size) if self.aligned_time is not None else 0,
                "channels": self.measured.channels,
                "rms": self.channel_rms,
                "rms_initial": self.channel_rms_initial,
                "time_shift": self.time_shift,
                "time_shift_uncertainty": self.time_shift_uncertainty,
            }
        if self.features:
            out["features"] = {
                k: {
                    "measured": v,
                    "initial": m_init.get(k),
                    "fitted": m_fit.get(k),
                    "residual": (m_fit.get(k, math.nan) - v),
                }
                for k, v in self.features.items()
            }
        out["metrics"] = {k: v for k, v in m_fit.items() if k not in ("force_peaks", "force_peak_times")}
        return jsonable(out)

    def write(self, out: str | Path) -> dict[str, Path]:
        """``calibration.json``, ``fitted.toml`` (runs with ``flexbeam run``), ``overlay.png``
        and, for histories, ``residuals.csv`` in the directory ``out``."""
        from ..parameters.io import dump_case
        from ..results.files import write_text_atomic

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
            parts = [
                self.residuals[i * n : (i + 1) * n] * self.measured.scale(c)
                for i, c in enumerate(self.measured.channels)
            ]
            for i in range(n):
                lines.append(f"{self.aligned_time[i]:.9g}," + ",".join(f"{p[i]:.9g}" for p in parts))
            files["residuals"] = write_text_atomic(out / "residuals.csv", "\n".join(lines) + "\n")
        return files

    def plot(self, path: str | Path) -> Path:
        """Measured data (or feature values) overlaid on the initial and fitted model."""
        from ..views.plotting import pyplot, save_figure

        plt = pyplot()
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
            for sol, style, name in (
                (self.initial_solution, "--", "initial"),
                (self.solution, "-", f"fitted: {label}"),
            ):
                t0 = sol.contacts[0].onset if sol.contacts else 0.0
                dur = sol.contacts[0].duration if sol.contacts and math.isfinite(sol.contacts[0].duration) else 1e-3
                sel = (sol.time >= t0 - 0.1 * dur) & (sol.time <= t0 + 1.5 * dur)
                ax.plot((sol.time[sel] - t0) * 1e3, sol["contact_force"][sel], style, lw=1.2, label=name)
            f = self.features
            for key, ls in (("peak_force", "--"), ("second_peak_force", ":")):
                if key in f:
                    ax.axhline(f[key], ls=ls, c="k", lw=0.8, label=f"measured {key} {f[key]:g} N")
            if "contact_duration" in f:
                ax.axvline(
                    f["contact_duration"] * 1e3,
                    ls="-.",
                    c="0.4",
                    lw=0.8,
                    label=f"measured contact_duration {f['contact_duration'] * 1e3:g} ms",
                )
            ax.set_xlabel("Time after first contact [ms]")
            ax.set_ylabel("Contact force [N]")
            ax.set_title(f"{self.case.name}: calibration to features ({self.method.upper()})")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        return save_figure(fig, path)


def _nan0(x: float) -> float:
    return 0.0 if not math.isfinite(x) else x
