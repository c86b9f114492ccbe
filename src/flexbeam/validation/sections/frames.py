"""Report section: the two body frames against the finite-element reference on the seed case."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..report import Row, Section
from ..runs import seed, simulate


def section_frames(reduced: bool, figdir: Path | None) -> Section:
    from ...integrate.modal_basis import ModalBasis
    from ...model.system import BeamSystem

    s = Section(
        "frames",
        "The hub frame and the system frame against the finite-element reference",
        'flexbeam\'s finite-element model (`method="fem"`, independent of the modal model) on the seed '
        "experiment, first contact, against the modal model (CCFM) in both body frames (`model.frame`, "
        "docs/formulation.md): the seed paper's hub frame with clamped-free modes, and the system frame with the "
        "hub + beam eigenmodes (the default for a free joint). Both converge to the same peak and duration; the "
        "system frame's linear mass matrix is diag(J0, mu L I) (condition number independent of n), the hub "
        "frame's carries the light root-slope coordinate (its condition number and top frequency grow with n, "
        "and so does the step count). Tolerance: 0.1 % from n = 16 on in the system frame (the target), 0.2 % "
        "for the hub frame at n = 16, the truncation error of fewer modes above it.",
        columns=["modes", "frame", "cond M0", "top frequency [rad/s]", "steps in 0.1 s"],
    )
    elements = 64  # converged to 2.4e-5 (against 32 elements): well inside the 0.1 % target; 0.1 s to run
    fem = simulate(seed(solver__t_end=1e-3, fem__elements=elements), "fem").metrics()
    modes = (4, 12, 16) if reduced else (4, 8, 12, 16, 24, 32)
    # the truncation error at few modes; from n = 16 on 0.1 % (the target), the hub frame 0.2 % at n = 16 exactly
    tolerance = {4: 0.4, 8: 0.01, 12: 3e-3, ("hub", 16): 2e-3}
    for n in modes:
        for frame in ("system", "hub"):
            case = seed(model__modes=n, model__frame=frame, solver__t_end=1e-3)
            m = simulate(case).metrics()
            system = BeamSystem.from_case(case)
            M0 = system.mass_matrix(0.0, system.state(0.0, 0.0))
            top = float(ModalBasis.of(system).omega.max())
            steps = "-"
            if not (reduced or (frame == "hub" and n > 16)):  # the hub frame's 0.1 s at n = 32 takes ~10 s
                steps = str(simulate(seed(model__modes=n, model__frame=frame)).stats["steps"])
            ex = {
                "modes": str(n),
                "frame": frame,
                "cond M0": f"{np.linalg.cond(M0):.3g}",
                "top frequency [rad/s]": f"{top:.4g}",
                "steps in 0.1 s": steps,
            }
            tol = tolerance.get((frame, n), tolerance.get(n, 1e-3))
            s.rows.append(Row("peak force [N]", fem["peak_force"], m["peak_force"], tol, extra=ex))
            s.rows.append(Row("contact duration [s]", fem["contact_duration"], m["contact_duration"], tol, extra=ex))
    s.notes.append(
        f"FE: {elements} elements (the 32- and 64-element peaks differ by 2.4e-5). The two frames span the same "
        "functions only in the limit n -> inf, so at a given n their truncation errors differ; with 4 modes the "
        "hub frame's clamped basis misses the pinned root's mobility and over-predicts the peak by 35 % "
        "(the system frame by 18 %), and over 20 ms it makes three contacts where the FE model and the system "
        "frame make one."
    )
    return s
