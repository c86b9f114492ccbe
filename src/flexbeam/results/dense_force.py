"""A contact force on a compiled phase's dense output, computed in the kernels from the positions and rates alone.

The outputs (:meth:`BeamSystem.outputs <flexbeam.model.system.BeamSystem.outputs>`) of a state hold every column --
energies, measuring points, every pair's gap -- and the dense states their energy bookkeeping; a contact's force
profile (its peaks, its impulse off the steps' nodes) needs one pair's force.  ``fb_pair_force_many``
(``kernels/src/extremes.c``) gives the same numbers, bit for bit: a force given by its law from the positions and
rates alone, with the outputs' arithmetic (unless a coordinate is given by time or a pair is held, where the outputs
take the forces from the equations: then through the outputs), the phase's exact end states at its ends.
"""

from __future__ import annotations

import numpy as np

from ..integrate.dense import ModalDense
from ..integrate.loop import Segment
from ..kernels import core


def compiled_pair_force(seg: Segment, times: np.ndarray, pair: int) -> np.ndarray | None:
    """The contact force of ``pair`` at ``times`` of segment ``seg``, or None when its phase has no compiled dense
    output (the reference integrator's)."""
    dense = seg.dense
    if not isinstance(dense, ModalDense):
        return None
    times = np.ascontiguousarray(times, float)
    out = np.empty(times.size)
    if times.size:
        st, rec = dense.stepper, dense.records
        core.pair_force(
            st.kernel, st.basis_buffer, rec, rec.shape[0], seg.phase.buffer, float(seg.t0), float(seg.t1),
            np.ascontiguousarray(seg.y0, float), np.ascontiguousarray(seg.y1, float), int(pair), times, out,
        )  # fmt: skip
    return out
