"""The output columns at every phase's two ends, evaluated once for the whole run.

A contact record's energies before and after (at its onset and end), the energy balance's first checkpoint of each
phase and the tip's values at each phase's ends are outputs at a segment's exact start state (t0, y0) or end state
(t1, y1).  Asked one at a time they cost a kernel call and its Python around it each; here every segment's two
ends go through :meth:`BeamSystem.outputs <flexbeam.model.system.BeamSystem.outputs>` in one call per distinct
contacts buffer (the outputs of a sample depend only on its time, its state and the buffer: the same numbers, bit
for bit, as one call per sample).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..integrate.loop import Segment
from ..kernels import OUTPUT_COLUMNS
from ..model.system import BeamSystem


class SegmentEnds:
    """Output columns (:data:`~flexbeam.kernels.OUTPUT_COLUMNS`) at each segment's start and end."""

    def __init__(self, segments: Sequence[Segment], system: BeamSystem) -> None:
        self.segments = segments
        n, ncol = len(segments), len(OUTPUT_COLUMNS)
        self.start, self.end = np.empty((n, ncol)), np.empty((n, ncol))
        groups: dict[bytes, list[int]] = {}
        for i, seg in enumerate(segments):
            groups.setdefault(np.asarray(seg.phase.buffer).tobytes(), []).append(i)
        for idx in groups.values():
            times = np.array([segments[i].t0 for i in idx] + [segments[i].t1 for i in idx], float)
            states = np.vstack([segments[i].y0 for i in idx] + [segments[i].y1 for i in idx])
            cols, _, _ = system.outputs(times, states, segments[idx[0]].phase.buffer)
            table = np.empty((times.size, ncol))
            for j, name in enumerate(OUTPUT_COLUMNS):
                table[:, j] = cols[name]
            self.start[idx], self.end[idx] = table[: len(idx)], table[len(idx) :]

    def start_columns(self, i: int) -> dict[str, np.ndarray]:
        """The columns at segment ``i``'s start, as one-sample arrays (as :meth:`BeamSystem.outputs` gives them)."""
        return {name: self.start[i, j : j + 1] for j, name in enumerate(OUTPUT_COLUMNS)}

    def column(self, i: int, name: str, t: float) -> float | None:
        """Output ``name`` of segment ``i`` at a time ``t`` in [t0, t1] when ``t`` is one of its ends (as
        :meth:`Segment.states` reads them: the start state at t0, else the end state at t1), else None."""
        seg, j = self.segments[i], OUTPUT_COLUMNS.index(name)
        if t <= seg.t0:
            return float(self.start[i, j])
        if t >= seg.t1:
            return float(self.end[i, j])
        return None
