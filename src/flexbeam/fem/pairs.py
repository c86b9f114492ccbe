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
    case's contact position (a start).  ``friction``, ``friction_static``: Coulomb friction at the point, by the
    regularised law of :func:`flexbeam.fem.contact_law.friction_law`."""

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
    friction: float = 0.0  #: Coulomb's kinetic coefficient mu_k (contact.friction)
    friction_static: float = 0.0  #: the static coefficient mu_s (contact.friction_static)
    #: the case's law: "coulomb" (the FE regularises it, fem.friction_velocity) or "threlfall" (its friction_velocity)
    friction_model: str = "coulomb"
    friction_velocity: float = 1e-3


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
                p.anywhere, p.friction, p.friction_static, p.friction_model, p.friction_velocity,
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


#: columns of a pair's kernel parameters: the law's [K, n, chi/d'_0, C], then friction's [mu_k, mu_s, v_s, model]
LAW_COLUMNS, PARAM_COLUMNS = 4, 8


def friction_params(pairs: tuple[FemPair, ...], velocity: float) -> np.ndarray:
    """Each pair's friction parameters [mu_k, mu_s, v_s, model] (S x 4; zeros without friction) for
    :func:`flexbeam.fem.contact_law.friction_law`: Coulomb's law regularised by Brown & McPhee's (model 0) with
    v_s = ``velocity`` (``fem.friction_velocity``), or Threlfall's law (model 1) with the case's v_0."""

    def row(p: FemPair) -> list[float]:
        if p.friction_static <= 0.0:
            return [0.0, 0.0, 1.0, 0.0]
        if p.friction_model == "threlfall":
            return [p.friction, p.friction_static, p.friction_velocity, 1.0]
        return [p.friction, p.friction_static, velocity, 0.0]

    return np.array([row(p) for p in pairs], float).reshape(len(pairs), PARAM_COLUMNS - LAW_COLUMNS)


class ContactState:
    """Which contact pairs are in their contact phase, their law parameters [K, n, chi/d'_0, C] and friction.

    ``laws[k]`` is pair k's parameter vector (None while it is free); ``active`` (int64, S) and ``params``
    (S x 8: the law's four, then the pair's friction [mu_k, mu_s, v_s, model] (``friction``, S x 4, default none);
    zeros for free pairs) are the arrays the kernels read.
    """

    __slots__ = ("active", "friction", "laws", "params")

    def __init__(self, laws: tuple[np.ndarray | None, ...], friction: np.ndarray | None = None) -> None:
        self.laws = tuple(laws)
        self.friction = np.zeros((len(self.laws), PARAM_COLUMNS - LAW_COLUMNS)) if friction is None else friction
        self.active = np.array([p is not None for p in self.laws], np.int64)
        self.params = np.zeros((len(self.laws), PARAM_COLUMNS))
        for k, p in enumerate(self.laws):
            if p is not None:
                self.params[k, :LAW_COLUMNS] = p
                self.params[k, LAW_COLUMNS:] = self.friction[k]

    @property
    def any(self) -> bool:
        """Is some pair in contact?"""
        return any(p is not None for p in self.laws)

    def with_pair(self, pair: int, params: np.ndarray | None) -> ContactState:
        """A copy with pair ``pair`` in contact under ``params`` (None: free)."""
        laws = list(self.laws)
        laws[pair] = params
        return ContactState(tuple(laws), self.friction)
