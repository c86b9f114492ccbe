"""Independent finite-element reference solver (``--method fem``).

A planar, geometrically exact (co-rotational) Euler-Bernoulli beam clamped to the
rotating hub, meshed with ``case.fem.elements`` two-node elements with a node at
each contact point, integrated in time with the generalized-alpha scheme and Newton
iterations, with the same obstacles and contact pairs (``[obstacle]`` and each
``[[obstacles]]`` entry, at fixed material points or, with ``contact.anywhere``, at the
point of the deformed beam's capsule surface nearest the obstacle), CCFM contact laws,
drives and initial states as the modal model -- but without modal truncation and without
the second-order coupling-deformation approximation.  What it does not model (a
compliant ``obstacle.support``) raises a ParameterError; a joint kind other than ``revolute`` and ``free`` a
ModelError.  A free beam (``joint.kind = "free"``, :mod:`flexbeam.fem.free`) has no hub: every node is free.

* :mod:`flexbeam.fem.element` -- element internal force/tangent (Crisfield 1991) and
  exact inertia of the interpolated field (Numba);
* :mod:`flexbeam.fem.assembly`, :mod:`flexbeam.fem.banded` -- assembly of the residual
  and the banded iteration matrix, Newton iterations, band solver (Numba);
* :mod:`flexbeam.fem.contact_law`, :mod:`flexbeam.fem.gap` -- the FE's own evaluation
  of the contact-law force and of the gap to the obstacle, at a node or, for contact
  anywhere, at the nearest point of the deformed centre line (Numba), and
  :mod:`flexbeam.contact.setup` -- the law and the obstacle read from the case (shared input);
* :mod:`flexbeam.fem.mesh` -- the nodes, with one at each contact point;
* :mod:`flexbeam.fem.beam` -- :class:`FemBeam`, the case's beam, hub, drive and pairs, and its equations of
  motion, with its contact geometry (:mod:`flexbeam.fem.contact_geometry`), outputs
  (:mod:`flexbeam.fem.outputs`: energies, point velocities), statics and frequencies
  (:mod:`flexbeam.fem.statics`); :mod:`flexbeam.fem.pairs` -- the contact pairs and which are in contact;
* :mod:`flexbeam.fem.integrator` -- generalized-alpha (Chung & Hulbert 1993) step;
* :mod:`flexbeam.fem.eventdriven` -- the run: contact phases, with the events located by
  :mod:`flexbeam.fem.event_location`, the step sizes of :mod:`flexbeam.fem.step_size` and the contact log of
  :mod:`flexbeam.fem.run_record`;
* :mod:`flexbeam.fem.initial` -- the initial state (a release angle solved by shooting on the FE free flight);
* :mod:`flexbeam.fem.free` -- the free beam: its rigid-body motion (G, the angular momentum about G, the mean-axis
  angle) and its start; :mod:`flexbeam.fem.rigid_motion` -- that motion on a run's samples, for the collision
  episodes and the apparent restitution of :mod:`flexbeam.results.episodes`;
* :mod:`flexbeam.fem.simulate` -- :func:`simulate_fem`, returning a
  :class:`~flexbeam.results.solution.Solution` (the force between samples from :mod:`flexbeam.fem.dense_force`);
* :mod:`flexbeam.fem.jit` -- the kernels' Numba compilation, cached on disk under a key of all
  the FE sources (an edit to any of them recompiles every kernel).

It shares no equations with the modal model: the contact force and the gap are
evaluated by its own kernels; only the case's inputs are interpreted alike (the law and
its chi(e), the Hertz stiffness, the obstacle placement, the joint of
:func:`flexbeam.model.joints.joint_of`: its kind -- a revolute joint or none (free), another kind raises a
ModelError -- and its drive :class:`flexbeam.model.joints.drive.JointDrive`) and the results go into the same
:class:`~flexbeam.results.solution.Solution`.
"""

from __future__ import annotations

from .._namespace import public_dir
from .beam import FemBeam
from .mesh import build_mesh
from .simulate import simulate_fem

__all__ = ["FemBeam", "build_mesh", "simulate_fem"]

__dir__ = public_dir(globals())
