"""Figures in the style of the paper's Figs. 6-9: contact force and P's normal velocity.

Matplotlib is imported lazily with the non-interactive Agg backend.  Labels follow
"Quantity [unit]".  A run with several contact pairs shows one force line per pair that touches, labelled by
the pair's obstacle ("obstacle", "obstacles[0]", ...; :func:`pair_forces`).  Reference numbers (e.g. the
experiment's reported peaks and contact duration) are drawn as dashed lines with their source in the legend.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..results.files import atomic_path
from ..results.readback import read_window
from ..results.solution import Solution

_STYLE = {"ccfm": "C0", "ccm": "C3", "imm": "C2", "fem": "C1"}
#: colours of the further pairs of one run (its first pair keeps the method's colour)
_PAIR_COLOURS = ("C1", "C4", "C5", "C6", "C8", "C9", "C2", "C3")
#: line styles of the pairs when several runs are overlaid (each run in its method's colour)
_PAIR_STYLES = ("-", "--", "-.", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)))


def pyplot():
    """matplotlib.pyplot with the non-interactive Agg backend (imported on first use)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def pair_forces(sol: Solution) -> list[tuple[int, str, np.ndarray]] | None:
    """Each contact pair's force of a run with several pairs, for the pairs that touch.

    Parameters
    ----------
    sol
        A run.

    Returns
    -------
    list of (pair, label, force) or None
        For each pair with a contact (a contact event or a positive force): its number, its label
        (``"obstacle"``, ``"obstacles[0]"``, ... from the provenance's ``contact_pairs``; ``"pair k"`` when it
        records none) and its force [N] at the samples.  None when the run has a single pair (or no per-pair
        arrays): its force is ``contact_force``, drawn as before.
    """
    force = sol.arrays.get("pair_contact_force")
    if force is None or force.ndim != 2 or force.shape[1] < 2:
        return None
    labels = list(sol.provenance.get("contact_pairs") or [])
    touched = {ev.pair for ev in sol.contacts}
    return [
        (k, str(labels[k]) if k < len(labels) else f"pair {k}", force[:, k])
        for k in range(force.shape[1])
        if k in touched or bool(np.nanmax(force[:, k], initial=0.0) > 0.0)
    ]


def _window(
    sol: Solution, before: float, after: float, pairs: list[tuple[int, str, np.ndarray]] | None = None
) -> tuple[float, np.ndarray]:
    """Onset t0 of the first contact and the samples from ``before`` [s] ahead of it to ``after`` [s] past it --
    past the first contact of each of ``pairs`` (:func:`pair_forces`) if later."""
    t0 = sol.contacts[0].onset if sol.contacts else 0.0
    last = t0
    for k, _, force in pairs or ():
        onsets = [ev.onset for ev in sol.contacts if ev.pair == k]
        if not onsets and np.any(force > 0.0):
            onsets = [float(sol.time[np.argmax(force > 0.0)])]
        last = max([last, *onsets[:1]])
    sel = (sol.time >= t0 - before) & (sol.time <= last + after)
    return t0, sel


def _drawn(sol: Solution, before: float, after: float) -> Solution:
    """``sol``, or for a run whose samples are still in its result file alone (a streamed run nobody has read the
    arrays of) a Solution of the samples that :func:`_window` draws from it -- from ``before`` [s] ahead of the first
    contact to ``after`` [s] past the first contact of each pair, which its records (kept whole) give -- read from
    the file alone (:func:`~flexbeam.results.readback.read_window`): the figures of a run of any length read a window,
    not every sample (1000 s at 1 ms: 90 MB more before)."""
    if not sol.samples_in_file:
        return sol
    t0 = sol.contacts[0].onset if sol.contacts else 0.0
    firsts: dict[int, float] = {}
    for ev in sol.contacts:
        firsts.setdefault(ev.pair, ev.onset)
    last = max([t0, *firsts.values()])
    time, phase, arrays = read_window(sol.stored_file(), t0 - before, last + after)
    return Solution(time, phase, arrays, contacts=sol.contacts, status=sol.status, message=sol.message,
                    stats=sol.stats, provenance=sol.provenance, summaries=sol.summaries)  # fmt: skip


def _mark_references(ax, reference: dict[str, Any], method: str, quantity: str) -> None:
    exp = reference.get("experiment", {})
    if quantity == "force":
        if "peak_force" in exp:
            ax.axhline(exp["peak_force"], ls="--", c="k", lw=0.8, label=f"experiment peak {exp['peak_force']:g} N")
        if "second_peak_force" in exp:
            ax.axhline(
                exp["second_peak_force"],
                ls=":",
                c="k",
                lw=0.8,
                label=f"experiment 2nd peak {exp['second_peak_force']:g} N",
            )
        if "contact_duration" in exp:
            ax.axvline(
                exp["contact_duration"] * 1e3,
                ls="-.",
                c="0.5",
                lw=0.8,
                label=f"experiment duration ~{exp['contact_duration'] * 1e3:g} ms",
            )
        paper = reference.get(method, {})
        if "peak_force" in paper:
            ax.axhline(
                paper["peak_force"],
                ls="--",
                c=_STYLE.get(method, "C4"),
                lw=0.8,
                alpha=0.6,
                label=f"paper {method.upper()} peak {paper['peak_force']:g} N",
            )
    elif quantity == "velocity" and "impact_velocity" in exp:
        ax.axhline(
            exp["impact_velocity"], ls="--", c="k", lw=0.8, label=f"experiment v0 = {exp['impact_velocity']:g} m/s"
        )


def plot_contact_force(
    solutions: list[Solution], path: str | Path, reference: dict[str, Any] | None = None, title: str = ""
) -> Path:
    """Contact force [N] against time after the first contact [ms], methods overlaid.

    A run with several contact pairs (:func:`pair_forces`) shows one line per pair that touches, labelled
    "flexbeam METHOD, <pair's obstacle>" -- for a single run each pair in its own colour, for several runs in the
    method's colour with one line style per pair -- over a window reaching past each such pair's first contact.
    A single-pair run shows its ``contact_force``.

    Parameters
    ----------
    solutions
        The runs to overlay.
    path
        The PNG to write.
    reference
        Reference numbers (the case's ``reference``) drawn as dashed lines, or None.
    title
        The figure's title (default: "Contact force").

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    span = max(
        (s.contacts[0].duration for s in solutions if s.contacts and math.isfinite(s.contacts[0].duration)),
        default=1e-3,
    )
    for sol in solutions:
        sol = _drawn(sol, 0.1 * span, 1.6 * span)
        pairs = pair_forces(sol)
        t0, sel = _window(sol, 0.1 * span, 1.6 * span, pairs)
        if pairs is None:
            ax.plot(
                (sol.time[sel] - t0) * 1e3,
                sol["contact_force"][sel],
                c=_STYLE.get(sol.method, None),
                label=f"flexbeam {sol.method.upper()}",
            )
        for n, (k, label, force) in enumerate(pairs or ()):
            if len(solutions) == 1:  # one colour per pair, the first the method's
                own = _STYLE.get(sol.method, "C0")
                others = [c for c in _PAIR_COLOURS if c != own]
                colour, style = (own if k == 0 else others[(k - 1) % len(others)]), "-"
            else:  # the method's colour, one line style per pair
                colour, style = _STYLE.get(sol.method, None), _PAIR_STYLES[n % len(_PAIR_STYLES)]
            ax.plot(
                (sol.time[sel] - t0) * 1e3,
                force[sel],
                c=colour,
                ls=style,
                label=f"flexbeam {sol.method.upper()}, {label}",
            )
        if "sensor_force" in sol.arrays:  # compliant support: what the sensor under it reads
            ax.plot(
                (sol.time[sel] - t0) * 1e3,
                sol["sensor_force"][sel],
                c=_STYLE.get(sol.method, None),
                ls=":",
                label=f"flexbeam {sol.method.upper()}, sensor force",
            )
    if reference:
        _mark_references(ax, reference, solutions[0].method if len(solutions) == 1 else "", "force")
    contact = any(s.contacts for s in solutions)
    note = _no_force_note(solutions)
    if note:  # (an empty plot said nothing of why: an IMM run, a run without contact)
        ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", va="center", fontsize=9, color="0.3")
    ax.set_xlabel("Time after first contact [ms]" if contact else "Time [ms]")
    ax.set_ylabel("Contact force [N]")
    ax.set_title(title or "Contact force")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return save_figure(fig, path)


def _no_force_note(solutions: list[Solution]) -> str:
    """Why the contact-force figure of ``solutions`` has no force to draw ("" when one has): no contact in any run,
    or every run IMM's with instantaneous impacts alone (a resting contact has a force)."""
    if not any(s.contacts for s in solutions):
        return "no contact in this run"
    if all(s.method == "imm" and not any(ev.duration > 0.0 for ev in s.contacts) for s in solutions):
        return (
            "IMM: instantaneous impacts, no contact-force history\n"
            "(their impulses: the contact records; P's velocity: normal_velocity.png)"
        )
    return ""


def plot_normal_velocity(
    solutions: list[Solution], path: str | Path, reference: dict[str, Any] | None = None, title: str = ""
) -> Path:
    """Normal velocity of the contact point (measuring point 1) [m/s] against time [ms]; with several contact
    pairs (:func:`pair_forces`), that of each pair's point that touches, one line style per pair."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for sol in solutions:
        sol = _drawn(sol, 0.5e-3, 4e-3)
        pairs = pair_forces(sol)
        t0, sel = _window(sol, 0.5e-3, 4e-3, pairs)
        if pairs is None:
            ax.plot(
                (sol.time[sel] - t0) * 1e3,
                sol["normal_velocity"][sel],
                c=_STYLE.get(sol.method, None),
                label=f"flexbeam {sol.method.upper()}",
            )
        for n, (k, label, _) in enumerate(pairs or ()):
            ax.plot(
                (sol.time[sel] - t0) * 1e3,
                sol["pair_normal_velocity"][sel, k],
                c=_STYLE.get(sol.method, None),
                ls=_PAIR_STYLES[n % len(_PAIR_STYLES)],
                label=f"flexbeam {sol.method.upper()}, {label}",
            )
    if reference:
        _mark_references(ax, reference, "", "velocity")
    ax.axhline(0.0, c="0.7", lw=0.5)
    ax.set_xlabel("Time after first contact [ms]")
    ax.set_ylabel("Normal velocity of P [m/s]")
    ax.set_title(title or "Normal velocity of the impact point")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return save_figure(fig, path)


def save_figure(fig, path: str | Path) -> Path:
    """Write ``fig`` as a PNG at ``path`` atomically and close it."""
    path = Path(path)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=120, format="png", bbox_inches="tight")
    pyplot().close(fig)
    return path


def _run_label(sol: Solution) -> str:
    """'first-order, 5 modes, W = 6 rad/s' from a solution's provenance (fallback: the method)."""
    import tomllib

    try:
        case = tomllib.loads(str(sol.provenance.get("case_toml", "")))
        model, drive = case["model"], case.get("drive", {})
        label = f"{model['coupling']}, {model['modes']} mode{'' if model['modes'] == 1 else 's'}"
        if drive.get("kind") == "prescribed":
            label += f", W = {drive.get('spin_rate', 0.0):g} rad/s"
        return label
    except (tomllib.TOMLDecodeError, KeyError, TypeError):
        return f"flexbeam {sol.method.upper()}"


def plot_tip_deflection(
    solutions: list[Solution],
    path: str | Path,
    labels: list[str] | None = None,
    reference: tuple[np.ndarray, np.ndarray] | None = None,
    reference_label: str = "reference",
    title: str = "",
    ylim: tuple[float, float] | None = None,
) -> Path:
    """Tip deflection in the rotating frame [m] against time [s] (e.g. the Kane spin-up).

    ``labels`` default to the coupling model, number of modes and spin rate of each run;
    ``reference`` = (t [s], deflection [m]) is drawn dashed; ``ylim`` clips divergent runs.
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for k, sol in enumerate(solutions):
        label = labels[k] if labels is not None else _run_label(sol)
        tip = np.asarray(sol["tip_deflection"], float)
        ax.plot(sol.time, np.where(np.isfinite(tip), tip, np.nan), c=f"C{k}", lw=1.0, label=label)
    if reference is not None:
        ax.plot(reference[0], reference[1], "--", c="k", lw=0.9, label=reference_label)
    if ylim is not None:
        ax.set_ylim(*ylim)
    ax.axhline(0.0, c="0.7", lw=0.5)
    ax.set_xlabel("Time [s]")
    ax.set_ylabel("Tip deflection [m]")
    ax.set_title(title or "Tip deflection in the rotating frame")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return save_figure(fig, path)
