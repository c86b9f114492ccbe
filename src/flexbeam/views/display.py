"""Rich display in notebooks: HTML for a :class:`~flexbeam.results.solution.Solution` and a calibration.

Jupyter calls an object's ``_repr_html_``; those of ``Solution`` and ``Calibration`` are
thin calls into this module.  Each gives a self-contained, well-formed HTML fragment
(it parses as XML): a status line, a table of the numbers and a small inline PNG plot.
The plot is drawn on a bare :class:`matplotlib.figure.Figure` (no pyplot), so it neither
changes the notebook's backend nor appears a second time as an open figure.

A sweep returns an :class:`xarray.Dataset`, whose own HTML repr already lists the swept
coordinates and every metric with its units, so sweeps get nothing here.
"""

from __future__ import annotations

import base64
import io
import math
from collections.abc import Iterable, Mapping, Sequence
from html import escape
from typing import TYPE_CHECKING, Any

import numpy as np

from ..results.envelope import envelope
from ..results.metrics import METRICS
from ..results.readback import read_envelope, read_names, read_span

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..results.solution import Solution

#: metrics shown in a solution's table, in this order (when present and not NaN)
SOLUTION_METRICS = (
    "peak_force",
    "second_peak_force",
    "peak_time",
    "contact_duration",
    "contacts",
    "micro_impacts",
    "chatter_episodes",
    "impact_velocity",
    "post_impact_velocity",
    "impulse",
    "sensor_peak_force",
    "sensor_second_peak_force",
    "sensor_duration",
    "tip_deflection_min",
    "tip_deflection_max",
    "energy_drift",
    "energy_drift_max",
    "wall_time",
    "steps",
)
#: status -> colour of the status badge
_COLOURS = {"success": "#1a7f37", "failed": "#cf222e"}
_FLEX = '<div style="display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start">'
_STYLE = "font-family: sans-serif; font-size: 13px; border-collapse: collapse; margin: 4px 0 8px 0; text-align: right"


def _number(value: Any) -> str:
    """A compact, readable number (4 significant digits; integers and strings as they are)."""
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        return "—" if math.isnan(v) else f"{v:.4g}"
    return escape(str(value))


def _table(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    head = "".join(f'<th style="padding: 2px 8px; text-align: left">{escape(h)}</th>' for h in header)
    body = []
    for row in rows:
        cells = [f'<td style="padding: 2px 8px; text-align: left">{escape(str(row[0]))}</td>']
        cells += [f'<td style="padding: 2px 8px">{_number(v)}</td>' for v in row[1:]]
        body.append(f"<tr>{''.join(cells)}</tr>")
    return f'<table style="{_STYLE}"><thead><tr>{head}</tr></thead><tbody>{"".join(body)}</tbody></table>'


def _status(title: str, status: str, message: str) -> str:
    colour = _COLOURS.get(status, "#9a6700")
    return (
        f'<div style="font-family: sans-serif; font-size: 13px"><b>{escape(title)}</b> '
        f'<span style="color: white; background: {colour}; border-radius: 3px; padding: 0 5px">'
        f'{escape(status)}</span> <span style="color: #57606a">{escape(message)}</span></div>'
    )


def _png(draw, size: tuple[float, float] = (4.2, 1.9), dpi: int = 90) -> str:
    """``<img>`` of a small figure drawn by ``draw(ax)``, embedded as base64 PNG."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, dpi=dpi, layout="constrained")
    ax = fig.add_subplot()
    alt = draw(ax)
    ax.grid(alpha=0.3)
    ax.tick_params(labelsize=7)
    ax.xaxis.label.set_fontsize(8)
    ax.yaxis.label.set_fontsize(8)
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f'<img alt="{escape(alt)}" src="data:image/png;base64,{data}" />'


def _first_contact_window(sol: Solution) -> np.ndarray:
    ev = sol.contacts[0]
    span = ev.duration if math.isfinite(ev.duration) and ev.duration > 0 else 1e-3
    return (sol.time >= ev.onset - 0.1 * span) & (sol.time <= ev.onset + 1.6 * span)


def _whole(sol: Solution, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The line of variable ``name`` over the whole run, reduced to its envelope (:mod:`flexbeam.results.envelope`;
    a streamed run's read from its file a slice at a time)."""
    if sol.samples_in_file:
        return read_envelope(sol.stored_file(), name)
    return envelope(sol.time, sol[name])


def _sampled(sol: Solution, name: str) -> bool:
    """Does ``sol`` hold samples of variable ``name`` (a streamed run's file asked, not its samples read)?"""
    return name in (read_names(sol.stored_file()) if sol.samples_in_file else sol.arrays)


def _draw_solution(sol: Solution):
    """What to plot: the first contact's force if there is one about it (with several contact pairs, each touching
    pair's force up to its first contact, labelled by its obstacle), else P's normal velocity over the run (IMM:
    jumps, no force), else the tip deflection (no contact).  The force is drawn from the samples about the first
    contact -- of a streamed run read alone from its file, as its figures are
    (:func:`~flexbeam.views.plotting._drawn`) --, a whole run's line from its envelope."""
    from .plotting import _drawn, _window, pair_forces

    def draw(ax: Axes) -> str:
        if sol.contacts:
            ev = sol.contacts[0]
            span = ev.duration if math.isfinite(ev.duration) and ev.duration > 0 else 1e-3
            win = _drawn(sol, 0.1 * span, 1.6 * span)
            pairs = pair_forces(win)
            sensor = win["sensor_force"] if "sensor_force" in win.arrays else None
            if pairs:
                t0, sel = _window(win, 0.1 * span, 1.6 * span, pairs)
                if any(np.nanmax(f[sel], initial=0.0) > 0.0 for _, _, f in pairs):
                    for k, label, f in pairs:
                        ax.plot((win.time[sel] - t0) * 1e3, f[sel], lw=1.0, c=f"C{k}", label=label)
                    if sensor is not None:
                        ax.plot((win.time[sel] - t0) * 1e3, sensor[sel], lw=0.8, ls=":", c="C0")
                    ax.legend(fontsize=6)
                    ax.set_xlabel("Time after first contact [ms]")
                    ax.set_ylabel("Contact force [N]")
                    return "contact force of each contact pair"
            force = win.arrays.get("contact_force")
            sel = _first_contact_window(win)
            if force is not None and np.nanmax(force[sel], initial=0.0) > 0.0:
                ax.plot((win.time[sel] - ev.onset) * 1e3, force[sel], lw=1.0, c="C0")
                if sensor is not None:
                    ax.plot((win.time[sel] - ev.onset) * 1e3, sensor[sel], lw=0.8, ls=":", c="C0")
                ax.set_xlabel("Time after first contact [ms]")
                ax.set_ylabel("Contact force [N]")
                return "contact force of the first contact"
            ax.plot(*_whole(sol, "normal_velocity"), lw=0.8, c="C2")
            ax.set_xlabel("Time [s]")
            ax.set_ylabel("Normal velocity of P [m/s]")
            return "normal velocity of the contact point"
        name = "tip_deflection" if _sampled(sol, "tip_deflection") else "theta"
        ax.plot(*_whole(sol, name), lw=0.8, c="C1")
        ax.set_xlabel("Time [s]")
        ax.set_ylabel("Tip deflection [m]" if name == "tip_deflection" else "Hub angle [rad]")
        return name.replace("_", " ")

    return draw


def _metric_rows(metrics: Mapping[str, Any], names: Iterable[str]) -> list[tuple[str, Any, str]]:
    rows = []
    for name in names:
        value = metrics.get(name)
        if value is None or (isinstance(value, float) and math.isnan(value)):
            continue
        units = METRICS[name].units if name in METRICS else ""
        rows.append((name, value, "" if units == "1" else units))
    return rows


def solution_html(sol: Solution) -> str:
    """HTML of a :class:`~flexbeam.results.solution.Solution`: status, metrics table, inline plot."""
    m = sol.metrics()
    case = str(sol.provenance.get("case_name", ""))
    title = f"flexbeam Solution: {case}, {sol.method.upper()}" if case else f"flexbeam Solution ({sol.method.upper()})"
    if sol.samples_in_file:  # (a streamed run: its time index alone, not its samples and phase labels)
        first, last, samples = read_span(sol.stored_file())
    else:
        samples = sol.time.size
        first, last = (sol.time[0], sol.time[-1]) if samples else (math.nan, math.nan)
    span = f"{first:.4g} to {last:.4g} s, {samples} samples" if samples else "no samples"
    parts = [
        _status(title, sol.status, sol.message),
        f'<div style="font-family: sans-serif; font-size: 12px; color: #57606a">{escape(span)}</div>',
        _FLEX,
        _table(("metric", "value", "units"), _metric_rows(m, SOLUTION_METRICS)),
    ]
    if samples > 1:
        parts.append(_png(_draw_solution(sol)))
    parts.append("</div>")
    return f"<div>{''.join(parts)}</div>"


def calibration_html(cal: Any) -> str:
    """HTML of a :class:`~flexbeam.calibrate.Calibration`: fitted values, features, overlay plot.

    The tables come from ``cal.to_dict()`` (the ``flexbeam calibrate --json`` report).
    """
    report = cal.to_dict()
    status = "success" if report["success"] else "failed"
    parts = [
        _status(f"flexbeam Calibration: {report['case']}, {report['method'].upper()}", status, str(report["message"])),
        _FLEX,
    ]
    params = report["parameters"]
    parts.append(
        _table(
            ("parameter", "initial", "fitted", "uncertainty", "units", "at bound"),
            ((k, p["initial"], p["value"], p["uncertainty"], p["units"], p["at_bound"]) for k, p in params.items()),
        )
    )
    if "features" in report:
        parts.append(
            _table(
                ("feature", "measured", "initial", "fitted"),
                ((k, f["measured"], f["initial"], f["fitted"]) for k, f in report["features"].items()),
            )
        )
    res = report["residuals"]
    rows = [("residual sigma", res["sigma"]), ("residual rms", res["rms"]), ("simulations", report["nfev"])]
    if "data" in report and report["data"]["time_shift"] is not None:
        rows.append(("time shift [s]", report["data"]["time_shift"]))
    parts.append(_table(("fit", "value"), rows))
    metrics = report["metrics"]
    peak = _metric_rows(metrics, ("peak_force", "second_peak_force", "contact_duration", "sensor_peak_force"))
    if peak:
        parts.append(_table(("fitted model", "value", "units"), peak))
    parts += [_png(_draw_calibration(cal)), "</div>"]
    return f"<div>{''.join(parts)}</div>"


def _draw_calibration(cal: Any):
    """Measured force (if a history was fitted) and the initial and fitted models' first contacts."""

    def draw(ax: Axes) -> str:
        measured = getattr(cal, "measured", None)
        for sol, style, label in ((cal.initial_solution, "--", "initial"), (cal.solution, "-", "fitted")):
            if not sol.contacts:
                continue
            sel = _first_contact_window(sol)
            t0 = sol.contacts[0].onset
            ax.plot((sol.time[sel] - t0) * 1e3, sol["contact_force"][sel], style, lw=1.0, label=label)
        if measured is not None and measured.force is not None and cal.aligned_time is not None:
            # the data's own alignment: time after its onset, shifted by the fitted offset
            shift = cal.time_shift if math.isfinite(cal.time_shift) else 0.0
            onset = cal.solution.contacts[0].onset if cal.solution.contacts else 0.0
            tau = cal.aligned_time + cal.model_reference[1] + shift - onset
            ax.plot(tau * 1e3, measured.force[cal.data_mask], ".", ms=1.5, c="0.5", label="measured")
        for name, ls in (("peak_force", "--"), ("second_peak_force", ":")):
            if name in cal.features:
                ax.axhline(cal.features[name], ls=ls, c="k", lw=0.7)
        ax.set_xlabel("Time after first contact [ms]")
        ax.set_ylabel("Contact force [N]")
        ax.legend(fontsize=6)
        return "measured and fitted contact force"

    return draw
