"""Report sections on the beam's frequencies: cantilever eigenvalues and the rotating cantilever."""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ...views.plotting import pyplot, save_figure
from ..references import PUBLISHED_ROOTS, ROTATING_DATA, published_rotating_values, reference_flapwise
from ..report import Row, Section

if TYPE_CHECKING:
    from collections.abc import Callable

    from ...model.beam import ModalBeam

    #: ``beam(delta, coupling="first-order")``: the unit beam of :func:`_unit_beam`, cached
    _BeamOf = Callable[..., ModalBeam]

#: cantilever modes of flexbeam's rotating beam
_ROTATING_MODES = 12

_ROTATING_SOURCE = (
    "exact continuous beam: flapwise (EI w'')'' - (N w')' = rho A omega^2 w with the centrifugal "
    "tension N, chordwise omega^2 = omega_flap^2 - Omega^2 (inextensible), solved by a Frobenius "
    "power series (the method of A. D. Wright et al., 1982; `flexbeam.validation.reference_flapwise`), "
    "itself checked against the published values of `tests/validation/data/rotating_cantilever.toml` "
    "(Hamza-Cherif & Houmat, ICAS 2004, Table 2; Ozdemir Ozgumus & Kaya via IJMME 2015). "
    "flexbeam: first-order model, 12 cantilever modes, `spin_frequencies`. "
    "Dimensionless: gamma = Omega T, omega_bar = omega T, T = sqrt(rho A L^4/EI), delta = r_h/L."
)


def section_roots(reduced: bool, figdir: Path | None) -> Section:
    from ...model.modes import cantilever_roots

    s = Section(
        "roots",
        "Cantilever eigenvalues beta_k L",
        "roots of cos(bL) cosh(bL) = -1 as tabulated to nine significant figures (e.g. R. D. "
        "Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979, Table 8-1), and the "
        "asymptote (2k - 1) pi / 2 for high k (its error is ~2 exp(-(2k-1) pi/2)).",
    )
    ks = (12, 16, 32, 64)
    roots = cantilever_roots(max(ks))
    for k, ref in enumerate(PUBLISHED_ROOTS, start=1):
        s.rows.append(Row(f"beta_{k} L", ref, roots[k - 1], 1e-8))
    for k in ks:
        s.rows.append(Row(f"beta_{k} L (asymptote)", (2 * k - 1) * math.pi / 2, roots[k - 1], 1e-9, "abs"))
    return s


def section_rotating(reduced: bool, figdir: Path | None) -> Section:
    """Rotating cantilever: flexbeam's flapwise and chordwise frequencies against the exact continuous beam (a
    Frobenius series, :func:`~flexbeam.validation.reference_flapwise`) and published values."""
    s = Section(
        "rotating", "Rotating cantilever bending frequencies", _ROTATING_SOURCE, columns=["delta", "gamma", "mode"]
    )
    beam = functools.cache(_unit_beam)
    published = published_rotating_values()
    s.rows += _published_rows(beam, published)
    if not published:
        s.notes.append(f"Published values not found ({ROTATING_DATA}); only the series is compared.")
    s.rows += _series_rows(beam, (0.0, 5.0, 10.0) if reduced else (0.0, 2.0, 4.0, 6.0, 8.0, 10.0))
    s.notes.append(_rotating_note(s.rows))
    if figdir is not None:
        _plot_rotating(beam, published, 21 if reduced else 41, figdir / "rotating_frequencies.png")
        s.figures.append(
            (
                "rotating_frequencies.png",
                "Bending frequencies of the rotating cantilever, modes 1-3: "
                "series (lines), flexbeam (markers), published values (x).",
            )
        )
    return s


def _unit_beam(delta: float, coupling: str = "first-order") -> ModalBeam:
    """The modal beam (first-order unless ``coupling`` says otherwise, :data:`_ROTATING_MODES` cantilever modes) of
    a unit beam, rho S = EI = L = 1, on a hub of radius ``delta``: its frequencies are the dimensionless ones."""
    from ...model.beam import build_modal_beam
    from ...parameters.case import Case

    case = Case.model_validate(
        {
            "beam": {
                "length": 1.0,
                # rho S = 1, EI = 1 (exact: powers of two) on a slender section, sqrt(I/S)/L = 2^-8
                "density": 2.0**8,
                "youngs_modulus": 2.0**24,
                "section": "general",
                "area": 2.0**-8,
                "second_moment": 2.0**-24,
                "half_depth": 0.0,
            },
            "hub": {"radius": delta},
            "model": {"modes": _ROTATING_MODES, "coupling": coupling, "gravity": 0.0, "frame": "hub"},
            "contact": {"position": 1.0},
        }
    )
    return build_modal_beam(case)


def _where(delta: float, gamma: float, mode: int) -> dict[str, str]:
    """The extra columns of a row: hub radius ratio, dimensionless spin rate, mode number."""
    return {"delta": f"{delta:g}", "gamma": f"{gamma:g}", "mode": str(mode)}


def _published_rows(beam: _BeamOf, published: list[dict]) -> list[Row]:
    """The published flapwise values against the series (checking the reference), then against flexbeam."""
    from ...model.frequencies import spin_frequencies

    rows = []
    for e in published:
        ref = reference_flapwise(float(e["gamma"]), float(e["delta"]))[e["mode"] - 1]
        rows.append(
            Row(
                "series (the reference, not flexbeam) vs published",
                e["value"],
                ref,
                1.5e-4,
                "abs",
                _where(e["delta"], e["gamma"], e["mode"]),
            )
        )
    for e in published:
        got = spin_frequencies(beam(float(e["delta"])), float(e["gamma"]), "flapwise")[e["mode"] - 1]
        rows.append(Row("published flapwise", e["value"], got, 1e-4, "rel", _where(e["delta"], e["gamma"], e["mode"])))
    return rows


def _series_rows(beam: _BeamOf, gammas: tuple[float, ...]) -> list[Row]:
    """flexbeam's first three flapwise and chordwise frequencies against the series (chordwise: omega_flap^2 -
    Omega^2) at hub radius ratios 0 and 1 and the spin rates ``gammas``."""
    from ...model.frequencies import spin_frequencies

    rows = []
    for plane in ("flapwise", "chordwise"):
        for delta in (0.0, 1.0):
            for gamma in gammas:
                ref = np.array(reference_flapwise(gamma, delta))
                if plane == "chordwise":
                    ref = np.sqrt(ref**2 - gamma**2)
                got = spin_frequencies(beam(delta), gamma, plane)[:3]
                for m in range(3):
                    rows.append(Row(f"{plane} omega_bar", ref[m], got[m], 1e-4, "rel", _where(delta, gamma, m + 1)))
    return rows


def _rotating_note(rows: list[Row]) -> str:
    """The tolerances, and the Ritz bound seen in the rows: assumed-mode frequencies lie above the exact ones."""
    excess = [r.value / r.reference - 1 for r in rows if r.quantity.endswith("omega_bar")]
    return (
        "Tolerances: 1e-4 for flexbeam (the unit tests allow 0.5 %), one unit of the last published digit "
        "for the series. Ritz bounds: the assumed-mode frequencies lie above the exact ones (largest excess here "
        f"{max(excess):.2e}, "
        f"smallest {min(excess):.2e}). "
        "The zeroth-order model's chordwise stiffness K - Omega^2 M loses definiteness at gamma = 3.516 "
        "(the first non-rotating frequency): dotted line in the figure."
    )


def _plot_rotating(beam: _BeamOf, published: list[dict], points: int, path: Path) -> None:
    """Figure: frequencies against the spin rate at ``points`` rates in [0, 10], one panel per hub radius ratio."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.2), sharey=True)
    gfine = np.linspace(0.0, 10.0, points)
    for ax, delta in zip(axes, (0.0, 1.0)):
        _plot_rotating_panel(ax, beam, [e for e in published if float(e["delta"]) == delta], delta, gfine)
    axes[0].set_ylabel("Dimensionless frequency omega_bar [-]")
    axes[0].legend(fontsize=7)
    save_figure(fig, path)


def _plot_rotating_panel(ax: Any, beam: _BeamOf, published: list[dict], delta: float, gfine: np.ndarray) -> None:
    """One panel of :func:`_plot_rotating`: modes 1-3 of the series (lines) and of flexbeam (markers), the
    zeroth-order model's first chordwise frequency (while real) and the published values (x)."""
    from ...model.frequencies import spin_frequencies

    flap = np.array([reference_flapwise(float(g), delta) for g in gfine])
    chord = np.sqrt(np.maximum(flap**2 - gfine[:, None] ** 2, 0.0))
    fb_flap = np.array([spin_frequencies(beam(delta), float(g), "flapwise")[:3] for g in gfine])
    fb_chord = np.array([spin_frequencies(beam(delta), float(g), "chordwise")[:3] for g in gfine])
    zeroth = np.array([spin_frequencies(beam(delta, "zeroth-order"), float(g), "chordwise")[0] for g in gfine])
    for m in range(3):
        c = f"C{m}"
        ax.plot(gfine, flap[:, m], c=c, lw=1.2, label="series, flapwise" if m == 0 else None)
        ax.plot(gfine, chord[:, m], c=c, lw=1.2, ls="--", label="series, chordwise" if m == 0 else None)
        ax.plot(gfine[::2], fb_flap[::2, m], "o", c=c, ms=4, mfc="none", label="flexbeam, flapwise" if m == 0 else None)
        ax.plot(gfine[::2], fb_chord[::2, m], "s", c=c, ms=3, label="flexbeam, chordwise" if m == 0 else None)
    ax.plot(gfine, np.where(zeroth > 0, zeroth, np.nan), ":", c="k", lw=1.2, label="zeroth-order chordwise, mode 1")
    if published:
        ax.plot(
            [e["gamma"] for e in published], [e["value"] for e in published], "x", c="k", ms=7,
            label="published (flapwise)",
        )  # fmt: skip
    ax.set_yscale("log")
    ax.set_xlabel("Dimensionless spin rate gamma [-]")
    ax.set_title(f"hub radius ratio delta = {delta:g}")
    ax.grid(alpha=0.3, which="both")
