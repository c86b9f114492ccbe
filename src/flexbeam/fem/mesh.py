"""The FE beam's mesh: node coordinates with a node at each contact point, and material points on it.

The mesh has ``case.fem.elements`` two-node elements (:mod:`flexbeam.fem.element`), split so that a node lies at
the contact point x_P: n_1 = round(N x_P / L) uniform elements on [0, x_P] and N - n_1 on [x_P, L] (at least one on
each part of non-zero length).  With several contact pairs at different material points x_1 < ... < x_m the beam
is split at each of them alike (node k_i = round(N x_i / L), kept increasing).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import ParameterError


def build_mesh(length: float, elements: int, x_contact: float | Sequence[float]) -> np.ndarray:
    """Node coordinates x_0 = 0 < ... < x_N = L with a node at ``x_contact``.

    Parameters
    ----------
    length
        Beam length L [m].
    elements
        Requested number of elements N; raised to 2 when x_P lies strictly inside
        (to m + 1 for m distinct contact points inside).
    x_contact
        Material coordinate of the contact point x_P [m], or those of several contact
        points (then node k_i = round(N x_i / L) lies at x_i, kept strictly increasing,
        with uniform elements between).
    """
    if elements < 1:
        raise ParameterError(f"fem.elements: must be >= 1 (got {elements})")
    tol = 1e-12 * length
    if not np.isscalar(x_contact):
        inside = sorted({float(x) for x in x_contact if tol < x < length - tol})
        if len(inside) > 1:
            return _split_mesh(length, elements, inside)
        x_contact = inside[0] if inside else 0.0
    if x_contact <= tol or x_contact >= length - tol:
        return np.linspace(0.0, length, elements + 1)
    n1 = int(round(elements * x_contact / length))
    n1 = min(max(n1, 1), max(elements - 1, 1))
    n2 = max(elements - n1, 1)
    left = np.linspace(0.0, x_contact, n1 + 1)
    right = np.linspace(x_contact, length, n2 + 1)
    return np.concatenate((left, right[1:]))


def _split_mesh(length: float, elements: int, points: list[float]) -> np.ndarray:
    """Uniform elements between 0, the sorted interior ``points`` and L, node k_i = round(N x_i / L)."""
    m = len(points)
    total = max(elements, m + 1)
    ks, prev = [], 0
    for i, x in enumerate(points):
        k = min(max(int(round(total * x / length)), prev + 1), total - (m - i))
        ks.append(k)
        prev = k
    bounds = [0.0, *points, length]
    counts = np.diff([0, *ks, total])
    parts = [np.linspace(bounds[i], bounds[i + 1], int(n) + 1)[:-1] for i, n in enumerate(counts)]
    return np.concatenate((*parts, [length]))


def locate(x_nodes: np.ndarray, x: float) -> tuple[int, float]:
    """Element index and local coordinate xi in [0, 1] of material point x."""
    e = int(np.searchsorted(x_nodes, x, side="right") - 1)
    e = min(max(e, 0), x_nodes.size - 2)
    xi = (x - x_nodes[e]) / (x_nodes[e + 1] - x_nodes[e])
    return e, float(min(max(xi, 0.0), 1.0))
