"""Files written for a run: result.nc, summary.json and the two figures (all atomically)."""

from __future__ import annotations

import json
from pathlib import Path

from ..errors import ParameterError
from ..parameters.case import Case
from ..parameters.references import reference_for
from ..results.files import jsonable, write_text_atomic
from ..results.solution import Solution

#: the files ``run --out`` writes (:func:`write_run_outputs`)
RUN_FILES = ("result.nc", "summary.json", "contact_force.png", "normal_velocity.png")


def write_run_outputs(sol: Solution, case: Case, out: str | Path) -> dict[str, Path]:
    """Write ``result.nc`` (a streamed run wrote it already), ``summary.json``, ``contact_force.png`` and
    ``normal_velocity.png``."""
    from .plotting import plot_contact_force, plot_normal_velocity

    out = Path(out)
    if sol.file is None:  # the output samples first: too many for the memory limit, they are refused before any file
        _ = sol.time
    out.mkdir(parents=True, exist_ok=True)
    reference = reference_for(case)
    summary = {
        "metrics": sol.metrics(),
        "provenance": sol.provenance,
        "reference": reference,
        "contacts": [vars(ev) for ev in sol.contacts],
    }
    files = {
        "result": sol.to_netcdf(out / "result.nc"),
        "summary": write_text_atomic(out / "summary.json", json.dumps(jsonable(summary), indent=2)),
        "contact_force": plot_contact_force(
            [sol], out / "contact_force.png", reference, f"{case.name}: contact force ({sol.method.upper()})"
        ),
        "normal_velocity": plot_normal_velocity(
            [sol], out / "normal_velocity.png", reference, f"{case.name}: normal velocity of P ({sol.method.upper()})"
        ),
    }
    return files


COMPARE_METHODS = ("ccfm", "ccm", "fem")


def compare_table(solutions: list[Solution], reference: dict) -> list[dict]:
    """One row per method: peaks, duration, contacts and micro-impacts (docs/methods.md, *What one contact is*),
    wall time and errors against the experiment -- None for a quantity the method does not resolve: IMM's impact is
    instantaneous (no peak force; its duration of 0 is no measure of the experiment's) -- and the run's status (a
    run that stopped early compares what it computed).  Every row has every key."""
    exp = reference.get("experiment", {})
    rows = []
    for sol in solutions:
        m = sol.metrics()
        row = {
            "method": sol.method,
            "status": sol.status,
            "peak_force": m["peak_force"],
            "second_peak_force": m["second_peak_force"],
            "contact_duration": m["contact_duration"],
            "force_peaks": len(m["force_peaks"]),
            "contacts": m["contacts"],
            "micro_impacts": m["micro_impacts"],
            "wall_time": m["wall_time"],
        }
        for key in ("peak_force", "second_peak_force", "contact_duration"):
            resolved = m[key] == m[key] and not (key == "contact_duration" and m[key] == 0.0)
            row[f"{key}_error"] = (m[key] - exp[key]) / exp[key] if key in exp and resolved else None
        row["paper_peak_force"] = reference.get(sol.method, {}).get("peak_force")
        rows.append(row)
    return rows


def markdown_table(rows: list[dict], reference: dict) -> str:
    def fmt(v, scale=1.0, digits=4):
        return "-" if v is None or v != v else f"{v * scale:.{digits}g}"

    def pct(v):  # a relative error in per cent; "-" without one (no reference, no value)
        return "-" if v is None or v != v else f"{fmt(v, 100, 3)} %"

    exp = reference.get("experiment", {})
    lines = [
        "| method | peak [N] | error | 2nd peak [N] | error | duration [ms] | error | peaks | contacts | "
        "micro-impacts | wall time [s] | paper's peak [N] |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['method']} | {fmt(r['peak_force'])} | {pct(r.get('peak_force_error'))} | "
            f"{fmt(r['second_peak_force'])} | {pct(r.get('second_peak_force_error'))} | "
            f"{fmt(r['contact_duration'], 1e3)} | {pct(r.get('contact_duration_error'))} | "
            f"{r['force_peaks']} | {r['contacts']} | {r['micro_impacts']} | {fmt(r['wall_time'])} | "
            f"{fmt(r.get('paper_peak_force'))} |"
        )
    if exp:
        lines.append("")
        lines.append(
            f"Experiment (Duan et al. 2013): peak {exp.get('peak_force')} N, second peak "
            f"{exp.get('second_peak_force')} N, duration ~{exp.get('contact_duration', 0) * 1e3:g} ms."
        )
    return "\n".join(lines) + "\n"


def compare(
    case: Case, out: str | Path | None = None, methods: tuple[str, ...] = COMPARE_METHODS, progress_factory=None
) -> tuple[list[Solution], list[dict]]:
    """Run ``case`` with several methods; write overlaid figures and the comparison table.  A case the FE reference
    does not model is refused before any method runs (it was after the others' runs), with the methods that can."""
    from ..simulation import simulate

    if "fem" in methods:
        from ..fem.simulate import check_supported

        others = ",".join(m for m in methods if m != "fem")
        try:
            check_supported(case)
        except ParameterError as exc:
            raise ParameterError(f"{exc}{f'; compare the others: --methods {others}' if others else ''}") from None
    solutions = []
    for method in methods:
        progress = progress_factory(method) if progress_factory else None
        try:
            solutions.append(simulate(case, method, progress=progress, outputs=out is not None))
        finally:
            if progress is not None:
                progress.close()
    reference = reference_for(case)
    rows = compare_table(solutions, reference)
    if out is not None:
        from .plotting import plot_contact_force, plot_normal_velocity

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        plot_contact_force(solutions, out / "contact_force.png", reference, f"{case.name}: contact force")
        plot_normal_velocity(solutions, out / "normal_velocity.png", reference, f"{case.name}: normal velocity of P")
        write_text_atomic(out / "comparison.md", markdown_table(rows, reference))
        write_text_atomic(
            out / "comparison.json", json.dumps(jsonable({"rows": rows, "reference": reference}), indent=2)
        )
    return solutions, rows
