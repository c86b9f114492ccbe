"""Report sections comparing models: modal vs FE, first- vs zeroth-order (Kane spin-up), energy."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..references import kane_hub_rates, quasi_static_tip
from ..report import Row, Section
from ..runs import modes_label, preset, seed, simulate

if TYPE_CHECKING:
    from ...parameters.case import Case
    from ...results.solution import Solution


def section_fem(reduced: bool, figdir: Path | None) -> Section:
    s = Section(
        "fem",
        "Modal model against the finite-element reference",
        'flexbeam\'s independent geometrically nonlinear finite-element model (`method="fem"`: '
        "co-rotational Euler-Bernoulli elements, generalized-alpha; it shares no equations with the "
        "modal model) on the seed experiment, first contact. Reference: FEM; value: modal model (CCFM).",
        columns=["modes", "elements"],
    )
    elements = 32 if reduced else 64
    fem = simulate(seed(solver__t_end=1e-3, fem__elements=elements), "fem")
    fm = fem.metrics()
    runs = ((12, 5e-3),) if reduced else ((12, 5e-3), (24, 2e-3), (32, 2e-3))
    modal = {}
    for n, tol in runs:
        sol = simulate(seed(model__modes=n, solver__t_end=1e-3))
        modal[n] = sol
        m = sol.metrics()
        ex = {"modes": str(n), "elements": str(elements)}
        s.rows.append(Row("peak force [N]", fm["peak_force"], m["peak_force"], tol, extra=ex))
        s.rows.append(Row("contact duration [s]", fm["contact_duration"], m["contact_duration"], tol, extra=ex))
        s.rows.append(Row("peak time [s]", fm["peak_time"], m["peak_time"], 10 * tol, extra=ex))
    s.notes.append(
        "The paper (Duan, Zhang & Hong 2013) reports 584 N measured, 689 N (its CCFM) and 625 N (its "
        "CCM); flexbeam's defaults assume a Hertz stiffness for an undocumented hemisphere and are not "
        "tuned to those numbers (see README)."
    )
    if figdir is not None:
        from ...views.plotting import plot_contact_force

        plot_contact_force(
            [modal[12], fem],
            figdir / "fem_vs_modal_force.png",
            title=f"Seed impact: 12 modes (CCFM) vs FEM ({elements} elements)",
        )
        s.figures.append(("fem_vs_modal_force.png", "Seed impact, first contact: modal model against the FE model."))
    return s


_KANE_SOURCE = (
    "T. R. Kane, R. R. Ryan, A. K. Banerjee, *J. Guidance Control Dyn.* 10 (1987) 139: a 10 m "
    "cantilever spun up to W in 15 s (`kane-spinup` preset). Reference for the first-order model: "
    "the quasi-static deflection of the spinning cantilever under the hub acceleration, "
    "EI w'''' - (N w')' - mu theta'^2 w = -mu theta'' (r_h + x), solved with solve_bvp "
    "(`flexbeam.validation.quasi_static_tip`); after the spin-up it is zero. Zeroth-order model: "
    "stiffness K - theta'^2 M is indefinite above omega_1 = 3.80 rad/s, so it must diverge "
    "(bound: the beam length), and stay bounded below."
)

_KANE_NOTE = (
    "The Solution metrics `tip_deflection_min`/`tip_deflection_max` are the extremes of the tip "
    "deflection in the rotating frame over the run. flexbeam's extreme exceeds the quasi-static one by "
    "0.5-1.5 %, the size of the dynamic amplification of a load varying at 2 pi/T_s = 0.42 rad/s on a "
    "beam whose first frequency is 3.8-5 rad/s ((0.42/3.8)^2 = 1.2 %); it does not shrink with more "
    "modes (2 modes: -0.5735 m, 5 modes: -0.5744 m at W = 6 rad/s)."
)


def section_kane(reduced: bool, figdir: Path | None) -> Section:
    """Kane spin-up (Kane, Ryan & Banerjee 1987): the first-order model against the quasi-static deflection, the
    zeroth-order model divergent above its first frequency and bounded below."""
    s = Section(
        "kane",
        "Kane spin-up: first-order bounded, zeroth-order divergent",
        _KANE_SOURCE,
        columns=["model", "W [rad/s]", "modes"],
    )
    first = ((6.0, 2),) if reduced else ((4.0, 5), (6.0, 5), (10.0, 5))
    zeroth = ((4.0, 1),) if reduced else ((3.0, 5), (4.0, 5), (6.0, 5))
    plotted, ref_curve = [], None
    for W, n in first:
        rows, sol, quasi_static = _kane_first_order(W, n)
        s.rows += rows
        if W == 6.0:
            plotted.append((sol, f"first-order, {modes_label(n)}, W = {W:g} rad/s"))
            ref_curve = quasi_static
        elif not reduced:
            plotted.append((sol, f"first-order, {modes_label(n)}, W = {W:g} rad/s"))
    first_max: dict[float, float] = {}
    for W, n in zeroth:
        rows, sol, diverges = _kane_zeroth_order(W, n, first_max)
        s.rows += rows
        if diverges and sol is not None and (W == 6.0 or reduced):
            plotted.append((sol, f"zeroth-order, {modes_label(n)}, W = {W:g} rad/s"))
    s.notes.append(_KANE_NOTE)
    if figdir is not None:
        _plot_kane(plotted, ref_curve, figdir / "kane_tip_deflection.png")
        s.figures.append(
            (
                "kane_tip_deflection.png",
                "Tip deflection during and after the spin-up; the zeroth-order model leaves the plot (divergence).",
            )
        )
    return s


def _kane_first_order(W: float, n: int) -> tuple[list[Row], Solution, tuple[np.ndarray, np.ndarray]]:
    """The first-order model spun up to ``W`` with ``n`` modes against the quasi-static tip deflection
    (:func:`~flexbeam.validation.quasi_static_tip`): (rows, the run, the quasi-static curve (t, w) to plot)."""
    case = preset("kane-spinup", drive__spin_rate=W, model__modes=n)
    b, Ts = case.beam, case.drive.spin_up_time
    mu, EI, L, rh = b.line_density, b.bending_stiffness, b.length, case.hub.radius
    sol = simulate(case)
    t, tip = sol.time, sol["tip_deflection"]
    idx = np.unique(np.searchsorted(t, np.linspace(0.0, Ts, 31)).clip(0, t.size - 1))
    qs = np.array([quasi_static_tip(mu, EI, L, *kane_hub_rates(float(t[i]), W, Ts), rh) for i in idx])
    peak = float(np.max(np.abs(qs)))
    tq = np.linspace(0.0, Ts, 61)
    qdense = np.array([quasi_static_tip(mu, EI, L, *kane_hub_rates(float(x), W, Ts), rh) for x in tq])
    m = sol.metrics()
    ex = {"model": "first-order", "W [rad/s]": f"{W:g}", "modes": str(n)}
    after = t >= Ts
    mid = Ts + 0.5 * (t[-1] - Ts)
    late = float(np.max(np.abs(tip[t >= mid])))
    early = float(np.max(np.abs(tip[after & (t < mid)])))
    rows = [
        Row(
            "max |tip - quasi-static| / max |quasi-static| during spin-up",
            0.0,
            float(np.max(np.abs(tip[idx] - qs))) / peak,
            0.025,
            "abs",
            extra=ex,
        ),
        Row("tip_deflection_min [m]", float(qdense.min()), m["tip_deflection_min"], 0.025, extra=ex),
        Row(
            "max |tip| after spin-up / quasi-static peak",
            0.02,
            float(np.max(np.abs(tip[after]))) / peak,
            kind="upper",
            extra=ex,
        ),
        Row("late / early residual vibration amplitude", 1.5, late / early, kind="upper", extra=ex),
    ]
    return rows, sol, (tq, qdense)


def _kane_zeroth_order(W: float, n: int, first_max: dict[float, float]) -> tuple[list[Row], Solution | None, bool]:
    """The zeroth-order model spun up to ``W`` with ``n`` modes: its linearised omega_1^2 = omega_1(0)^2 - W^2, and
    its tip diverging (W above omega_1: beyond the beam length) or bounded and softer than the first-order model's
    (whose largest tip deflection ``first_max`` caches by W).  Returns (rows, the run or None if it raised, whether
    W is above omega_1)."""
    from ...model.frequencies import case_frequencies

    case = preset("kane-spinup", drive__spin_rate=W, model__modes=n, model__coupling="zeroth-order")
    L = case.beam.length
    w1 = case_frequencies(case, 0.0)["zeroth-order"][0]
    wW = case_frequencies(case, W)["zeroth-order"][0]
    ex = {"model": "zeroth-order", "W [rad/s]": f"{W:g}", "modes": str(n)}
    rows = [Row("linearised omega_1^2 at W [1/s^2]", w1**2 - W**2, math.copysign(wW**2, wW), 1e-8, extra=ex)]
    sol, amp = _largest_tip(case)
    if W > w1:
        rows.append(Row("max |tip| [m] (diverges: above L)", L, amp, kind="lower", extra=ex))
        return rows, sol, True
    rows.append(Row("max |tip| [m] (bounded: below L/10)", 0.1 * L, amp, kind="upper", extra=ex))
    if W not in first_max:
        ref = simulate(preset("kane-spinup", drive__spin_rate=W, model__modes=n))
        first_max[W] = float(np.max(np.abs(ref["tip_deflection"])))
    rows.append(Row("max |tip| [m] (softer than first-order)", first_max[W], amp, kind="lower", extra=ex))
    return rows, sol, False


def _largest_tip(case: Case) -> tuple[Solution | None, float]:
    """(the run, its largest |tip deflection|): infinite when the run fails, raises an arithmetic error or leaves
    non-finite values (a divergent model), and the run None when it raised."""
    try:
        sol = simulate(case)
        tip = sol["tip_deflection"]
        amp = float(np.max(np.abs(tip))) if np.all(np.isfinite(tip)) and sol.status == "success" else math.inf
    except (ArithmeticError, np.linalg.LinAlgError):
        sol, amp = None, math.inf
    return sol, amp


def _plot_kane(
    plotted: list[tuple[Solution, str]], reference: tuple[np.ndarray, np.ndarray] | None, path: Path
) -> None:
    """Figure: the tip deflection of the ``plotted`` (run, label) pairs and the quasi-static ``reference`` curve,
    the axis limited to twice the first-order runs' extreme (a divergent run leaves it)."""
    from ...views.plotting import plot_tip_deflection

    fo = [sol for sol, lab in plotted if lab.startswith("first")]
    lim = 2.0 * max(float(np.max(np.abs(sol["tip_deflection"]))) for sol in fo)
    plot_tip_deflection(
        [p[0] for p in plotted],
        path,
        labels=[p[1] for p in plotted],
        reference=reference,
        reference_label="quasi-static (solve_bvp), W = 6 rad/s",
        title="Kane spin-up: tip deflection",
        ylim=(-lim, lim),
    )


def section_energy(reduced: bool, figdir: Path | None) -> Section:
    s = Section(
        "energy",
        "Energy conservation",
        "the total energy T + V_e + V_g + U_c + E_dissipated - W_drive is a first integral of the "
        "equations (exact bookkeeping of the contact dissipation and the drive work); reference 0, "
        "value: the largest relative change over the run (`Solution.energy_drift`). The generalized-alpha "
        "FE reference dissipates slightly by design (rho_inf = 0.9).",
        columns=["run"],
    )
    modes, t_end = (4, 0.01) if reduced else (12, 0.03)
    runs: list[tuple[str, Callable[[], Any], float]] = [
        (
            f"CCFM Hertz, {modes} modes, {t_end:g} s",
            lambda: simulate(seed(model__modes=modes, contact__law="hertz", solver__t_end=t_end)),
            1e-6,
        ),
        (
            "CCFM Hunt-Crossley e = 0.5, 2 modes, 3 ms",
            lambda: simulate(
                seed(model__modes=2, contact__law="hunt_crossley", contact__restitution=0.5, solver__t_end=0.003)
            ),
            1e-6,
        ),
        (
            "torque drive -2 N m, 2 modes, 0.2 s",
            lambda: simulate(
                seed(
                    model__modes=2,
                    drive__kind="torque",
                    drive__torque=-2.0,
                    initial__kind="state",
                    initial__angle=0.3,
                    initial__rate=0.0,
                    contact__law="hertz",
                    solver__t_end=0.2,
                )
            ),
            1e-6,
        ),
        ("IMM e = 0.8, 4 modes, 10 ms", lambda: simulate(seed(model__modes=4, solver__t_end=0.01), "imm"), 1e-6),
        ("CCM, 4 modes, 10 ms", lambda: simulate(seed(model__modes=4, solver__t_end=0.01), "ccm"), 1e-6),
        ("FEM 32 elements, 10 ms", lambda: simulate(seed(solver__t_end=0.01, fem__elements=32), "fem"), 1e-4),
    ]
    for label, run, tol in runs:
        sol = run()
        s.rows.append(
            Row(
                "max relative energy change",
                0.0,
                sol.energy_drift()[1],
                tol,
                "abs",
                extra={"run": f"{label} ({sol.contact_counts().of_pair(None)['contacts']} contacts)"},
            )
        )
    return s
