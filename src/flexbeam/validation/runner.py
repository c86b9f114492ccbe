"""Running the report: the sections, the page written atomically, and the command line.

``python -m flexbeam.validation [--reduced] [--out docs] [--only SECTION ...]`` calls :func:`main`.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path

from .report import Section, render
from .sections import SECTIONS

#: what the command does (the first line of the package's docstring)
DESCRIPTION = "Validation report: flexbeam against independent references, written to ``docs/validation.md``."


def run_validation(
    reduced: bool = False,
    out: str | Path | None = "docs",
    only: list[str] | None = None,
    log: Callable[[str], None] | None = None,
) -> list[Section]:
    """Run the sections (all, or ``only``) and, if ``out`` is given, write ``out/validation.md``.

    Figures go to ``out/figures``; every file is written atomically (temporary file, rename).
    """
    from ..results.files import write_text_atomic

    figdir = None if out is None else Path(out) / "figures"
    if figdir is not None:
        figdir.mkdir(parents=True, exist_ok=True)
    sections = []
    t_all = time.perf_counter()
    for key, fun in SECTIONS.items():
        if only and key not in only:
            continue
        t0 = time.perf_counter()
        sec = fun(reduced, figdir)
        sec.seconds = time.perf_counter() - t0
        sections.append(sec)
        if log:
            bad = [r for r in sec.rows if not r.passed]
            log(
                f"{key:12s} {len(sec.rows):4d} rows  {'pass' if sec.passed else 'FAIL'}  {sec.seconds:6.1f} s"
                + "".join(
                    f"\n    FAIL {r.quantity} {r.extra}: ref {r.reference!r} got {r.value!r} "
                    f"err {r.error:.3e} > {r.tolerance:g}"
                    for r in bad
                )
            )
    if out is not None:
        text = render(sections, reduced, time.perf_counter() - t_all)
        write_text_atomic(Path(out) / "validation.md", text)
    return sections


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m flexbeam.validation", description=DESCRIPTION)
    parser.add_argument("--reduced", action="store_true", help="fast version (< 60 s): fewer modes, shorter runs")
    parser.add_argument("--out", default="docs", help="output directory (validation.md, figures/); default docs")
    parser.add_argument("--only", nargs="*", choices=list(SECTIONS), help="run only these sections")
    args = parser.parse_args(argv)
    sections = run_validation(args.reduced, args.out, args.only, log=lambda m: print(m, flush=True))
    print(f"wrote {Path(args.out) / 'validation.md'}")
    return 0 if all(s.passed for s in sections) else 1
