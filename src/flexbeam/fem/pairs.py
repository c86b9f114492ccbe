"""The FE model's contact pairs: each pair's point and obstacle, the kernels' arrays of them, and which pairs are in
their contact phase.

A pair is a point of the beam (at a mesh node, or, with ``contact.anywhere``, the point of the deformed beam's
capsule surface nearest its obstacle) against one rigid obstacle (sphere or half-plane) under its own CCFM law
(:mod:`flexbeam.contact.setup` reads them from the case, as for the modal model).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contact.laws import ContactLaw
from ..contact.setup import ContactSetup


@dataclass(frozen=True)
class FemPair:
    """One contact pair of the FE model: the contact point at mesh node ``node`` (material coordinate
    ``position``, signed ``offset`` c below the centre line: r_P = X - c n(psi)) against one rigid obstacle
    (``kind`` 0 sphere / 1 half-plane, ``centre``, ``radius``, outward ``normal``) under the CCFM ``law``.

    With ``anywhere`` the contact point is instead the point of the beam's capsule surface (radius ``offset`` = c
    about the deformed centre line, hemispherical caps at x = 0 and L) nearest the obstacle, found at every
    evaluation (:func:`flexbeam.fem.gap.anywhere_gap`); ``node`` and ``position`` are then only the mesh node at the
    case's contact position (a start)."""

    node: int
    position: float
    offset: float
    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray
    law: ContactLaw
    label: str
    anywhere: bool = False


def pairs_from_setup(contact: ContactSetup, x_nodes: np.ndarray, surface_offset: float) -> tuple[FemPair, ...]:
    """The case's contact pairs on the mesh ``x_nodes``: each at the node nearest its position, against its
    obstacle; a pair anywhere has the capsule's radius c = |``surface_offset``| as its offset."""
    pairs = []
    for p in contact.pairs:
        ob = contact.obstacles[p.obstacle]
        offset = abs(surface_offset) if p.anywhere else p.offset  # anywhere: the capsule's radius c
        pairs.append(
            FemPair(
                int(np.argmin(np.abs(x_nodes - p.position))), p.position, offset, int(ob.kind),
                np.asarray(ob.centre, float), float(ob.radius), np.asarray(ob.normal, float), p.law, p.label,
                p.anywhere,
            )
        )  # fmt: skip
    return tuple(pairs)


def pair_arrays(pairs: tuple[FemPair, ...]) -> tuple[np.ndarray, ...]:
    """The pairs as the kernels read them (:func:`flexbeam.fem.assembly.assemble`), arrays over the pairs: nodes,
    offsets, obstacle kinds, centres (S x 2), radii, normals (S x 2), anywhere flags."""
    return (
        np.array([p.node for p in pairs], np.int64),
        np.array([p.offset for p in pairs], float),
        np.array([p.kind for p in pairs], np.int64),
        np.array([p.centre for p in pairs], float).reshape(len(pairs), 2),
        np.array([p.radius for p in pairs], float),
        np.array([p.normal for p in pairs], float).reshape(len(pairs), 2),
        np.array([int(p.anywhere) for p in pairs], np.int64),
    )


class ContactState:
    """Which contact pairs are in their contact phase, and their law parameters [K, n, chi/d'_0, C].

    ``laws[k]`` is pair k's parameter vector (None while it is free); ``active`` (int64, S) and ``params``
    (S x 4, zeros for free pairs) are the arrays the kernels read.
    """

    __slots__ = ("active", "laws", "params")

    def __init__(self, laws: tuple[np.ndarray | None, ...]) -> None:
        self.laws = tuple(laws)
        self.active = np.array([p is not None for p in self.laws], np.int64)
        self.params = np.zeros((len(self.laws), 4))
        for k, p in enumerate(self.laws):
            if p is not None:
                self.params[k] = p

    @property
    def any(self) -> bool:
        """Is some pair in contact?"""
        return any(p is not None for p in self.laws)

    def with_pair(self, pair: int, params: np.ndarray | None) -> ContactState:
        """A copy with pair ``pair`` in contact under ``params`` (None: free)."""
        laws = list(self.laws)
        laws[pair] = params
        return ContactState(tuple(laws))
