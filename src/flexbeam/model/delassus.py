"""The inverse mass matrix seen by contact pairs' rows, [J_t; J] M^-1 [J_t; J]^T (the Delassus matrix): which pairs'
friction rows depend on others' (:func:`flexbeam.methods.coulomb.grouped`), the stick's ratio at an onset
(Stronge, *Impact Mechanics*, CUP 2000, ch. 5) and how a group's friction force is shared
(:mod:`flexbeam.results.friction`)."""

from __future__ import annotations

import numpy as np

from .. import numerics as nm
from .system import BeamSystem


def inverse_mass(system: BeamSystem, t: float, y: np.ndarray, pairs: list[int]) -> np.ndarray:
    """[J_t; J] M^-1 [J_t; J]^T of ``pairs`` (their tangential rows first, then their normal rows) over the coordinates
    solved for (bordered by the support's mass m_s with a compliant support)."""
    rows = [system.tangent(t, y, k) for k in pairs]
    J = np.array([r[4] for r in rows] + [r[3] for r in rows])
    M = system.mass_matrix(t, y)
    g = system.ngiven
    J, M = J[:, g:], M[g:, g:]
    return nm.matmul(J, nm.solve(M, np.ascontiguousarray(J.T)))
