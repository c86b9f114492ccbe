"""The tables the commands print (Rich, imported when a table is printed): a run's metrics and a calibration's
report.  Every text is escaped from Rich's markup: a message's "[[obstacles]]" or a unit's "[s]" is printed as
written, not taken for a style tag and dropped."""

from __future__ import annotations

import math
from typing import Any


def print_metrics(metrics: dict[str, Any], title: str) -> None:
    """Print a run's metrics (:meth:`~flexbeam.results.solution.Solution.metrics`) as a table of ``title``.

    One row per metric, a row per contact pair when there are several; the per-contact ``events`` are left out
    (they are in ``--json``).
    """
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    table = Table(title=escape(title))
    table.add_column("metric")
    table.add_column("value", justify="right")
    for key, value in metrics.items():
        if key == "pairs":  # one row per contact pair with several: its contacts and first peak
            for p in value if len(value) > 1 else []:
                peak = p["peak_force"]
                text = contacts_text(p) + ", first peak " + ("-" if math.isnan(peak) else f"{peak:.6g} N")
                table.add_row(escape(f"pair {p['pair']} ({p['obstacle']})"), escape(text))
            continue
        if key in ("events", "episodes"):  # one per contact record / collision episode: in --json only
            continue
        if isinstance(value, float):
            text = "-" if math.isnan(value) else f"{value:.6g}"
        elif isinstance(value, list):
            text = ", ".join(f"{v:.4g}" for v in value)
        else:
            text = str(value)
        table.add_row(escape(key), escape(text))
    Console().print(table)


def contacts_text(counts: dict[str, Any]) -> str:
    """``"3 contacts"``, with ``" (+37 micro-impacts in 1 chatter episode)"`` when there are micro-impacts."""
    text = f"{counts['contacts']} contacts"
    micro, episodes = counts["micro_impacts"], counts["chatter_episodes"]
    if micro:
        text += f" (+{micro} micro-impacts in {episodes} chatter episode{'s' if episodes != 1 else ''})"
    return text


def _number(v: Any) -> str:
    """A number of a calibration report to 6 significant digits; "-" for None or a non-finite value."""
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.6g}"


def print_calibration(report: dict[str, Any], title: str) -> None:
    """Print a calibration's report (:meth:`~flexbeam.calibrate.result.Calibration.to_dict`): the fitted
    parameters, the measured and modelled features, the data's residuals and time shift, the fit's summary."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    num = _number
    table = Table(title=escape(f"{title}: calibration"))
    for col in ("parameter", "initial", "fitted", "std. uncertainty", "units"):
        table.add_column(col, justify="left" if col in ("parameter", "units") else "right")
    for key, p in report["parameters"].items():
        table.add_row(
            escape(key + (" (at bound)" if p["at_bound"] else "")),
            num(p["initial"]),
            num(p["value"]),
            num(p["uncertainty"]),
            escape(p["units"]),
        )
    console = Console()
    console.print(table)
    if "features" in report:
        ft = Table(title="features")
        for col in ("feature", "measured", "initial model", "fitted model"):
            ft.add_column(col, justify="left" if col == "feature" else "right")
        for key, f in report["features"].items():
            ft.add_row(escape(key), num(f["measured"]), num(f["initial"]), num(f["fitted"]))
        console.print(ft)
    if "data" in report:
        d = report["data"]
        for chan, rms in d["rms"].items():
            console.print(escape(f"{chan} residual rms: {num(rms)} (initial {num(d['rms_initial'][chan])})"))
        console.print(
            escape(
                f"time shift: {num(d['time_shift'])} s +- {num(d['time_shift_uncertainty'])} s, "
                f"{d['samples']} samples of {d['file']}"
            )
        )
    r = report["residuals"]
    console.print(
        escape(f"residual sigma {num(r['sigma'])} (dof {r['dof']}), {report['nfev']} evaluations: {report['message']}")
    )
