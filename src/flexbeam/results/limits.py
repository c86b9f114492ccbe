"""What the output samples of a run may hold: the memory limit (``solver.memory_limit``, else a share of the
machine's physical memory) and the bytes a number of samples takes.  :mod:`flexbeam.memory` estimates a whole run
before it starts; :func:`check_samples` refuses the samples of a finished run before they are evaluated.
"""

from __future__ import annotations

import os

from ..errors import ParameterError
from ..kernels import OUTPUT_COLUMNS, PAIR_COLUMNS
from ..parameters.case import Case

#: share of the physical memory a run may hold when ``solver.memory_limit`` is omitted
DEFAULT_FRACTION = 0.5
#: the limit when the physical memory cannot be read (no ``os.sysconf``) [B]
FALLBACK_LIMIT = 8 * 2**30

#: output samples: bytes per float at peak (the arrays, plus the parts they are joined from; 816 B measured for the
#: seed's 43 floats)
SAMPLE_BYTES_PER_FLOAT = 20.0


def physical_memory() -> float | None:
    """The machine's physical memory [B] (``os.sysconf``), None where it cannot be read."""
    try:
        pages, size = os.sysconf("SC_PHYS_PAGES"), os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None
    return float(pages * size) if pages > 0 and size > 0 else None


def memory_limit(case: Case) -> tuple[float, str]:
    """(limit [B], how it was set): ``solver.memory_limit``, else :data:`DEFAULT_FRACTION` of the physical memory."""
    if case.solver.memory_limit is not None:
        return float(case.solver.memory_limit), "solver.memory_limit"
    phys = physical_memory()
    if phys is None:
        return float(FALLBACK_LIMIT), "the default limit (physical memory unknown)"
    return DEFAULT_FRACTION * phys, f"{100 * DEFAULT_FRACTION:g} % of the physical memory, the default"


def size_text(nbytes: float) -> str:
    """``nbytes`` in B, kB, MB, GB or TB, three digits."""
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if nbytes >= scale:
            return f"{nbytes / scale:.3g} {unit}"
    return f"{nbytes:.3g} B"


def sample_bytes(case: Case, pairs: int, count: float) -> float:
    """Bytes held at peak by ``count`` output samples of ``case`` (``pairs`` contact pairs)."""
    n = case.model.modes
    columns = len(OUTPUT_COLUMNS) - (0 if case.obstacle.support.compliant else 2)
    per_pair = len(PAIR_COLUMNS) * pairs if pairs > 1 or anywhere(case) else 0
    centre = 4 if case.joint.kind == "free" else 0  # G's position and velocity
    floats = columns + 2 * n + len(case.output.measuring_points) + per_pair + centre + 3  # + total energy, time, phase
    return count * floats * SAMPLE_BYTES_PER_FLOAT


def anywhere(case: Case) -> bool:
    return case.contact.anywhere or any(ob.contact.anywhere for ob in case.obstacles)


def check_samples(case: Case, pairs: int, free: int, contact: int) -> None:
    """Refuse to evaluate the output samples of a finished run -- ``free`` on the ``solver.sample_step`` grid,
    ``contact`` on the ``solver.contact_sample_step`` one (both on ``output.interval`` when given) -- when they
    would exceed the memory limit: one line naming the sample step that gives most of them."""
    need = sample_bytes(case, pairs, free + contact)
    limit, source = memory_limit(case)
    if need > limit:
        field = case.sample_step_field(contact > free)
        raise ParameterError(
            f"{field}: the {free + contact} output samples of this run ({contact} in contact) would hold about "
            f"{size_text(need)}, more than the limit of {size_text(limit)} ({source}); allowed here: a {field} "
            f"about {need / limit:.3g} times coarser, or raise solver.memory_limit [B]"
        )


__all__ = ["anywhere", "check_samples", "memory_limit", "physical_memory", "sample_bytes", "size_text"]
