"""Independent finite-element reference solver (``--method fem``).

A planar, geometrically exact (co-rotational) Euler-Bernoulli beam clamped to the
rotating hub, meshed with ``case.fem.elements`` two-node elements with a node at
the contact point, integrated in time with the generalized-alpha scheme and Newton
iterations, with the same obstacle, CCFM contact laws, drives and initial states as
the modal model -- but without modal truncation and without the second-order
coupling-deformation approximation.

* :mod:`flexbeam.fem.kernels` -- element internal force/tangent (Crisfield 1991),
  exact inertia of the interpolated field, assembly (Numba);
* :mod:`flexbeam.fem.model` -- mesh, properties, statics, frequencies;
* :mod:`flexbeam.fem.integrator` -- generalized-alpha (Chung & Hulbert 1993) with
  contact-event location;
* :mod:`flexbeam.fem.simulate` -- :func:`simulate_fem`, returning a
  :class:`~flexbeam.solution.Solution`.
"""

from __future__ import annotations

from .model import FemBeam, build_mesh
from .simulate import simulate_fem

__all__ = ["FemBeam", "build_mesh", "simulate_fem"]
