"""The joint that carries the beam's floating frame: one module per kind (docs/architecture.md, *Adding a joint
kind*).

* :mod:`~flexbeam.model.joints.base` -- what every kind gives the model (:class:`~.base.Joint`);
* :mod:`~flexbeam.model.joints.revolute` -- a revolute joint at a fixed point O, free, torque-driven or with its
  angle prescribed (:mod:`~flexbeam.model.joints.drive`);
* :mod:`~flexbeam.model.joints.free` -- no joint: a free-flying beam, its frame at the centre of mass.

The compiled side of the seam is ``kernels/src/joint.h``, one ``joint_<kind>.c`` per kind.
"""

from __future__ import annotations

from ..._namespace import public_dir
from ...parameters.case import Case
from .base import Joint
from .free import FreeJoint
from .revolute import RevoluteJoint

#: ``[joint] kind`` -> its class
JOINTS: dict[str, type[Joint]] = {RevoluteJoint.kind: RevoluteJoint, FreeJoint.kind: FreeJoint}


def joint_of(case: Case) -> Joint:
    """The joint of ``case`` (``[joint] kind``)."""
    return JOINTS[case.joint.kind](case)


__all__ = ["JOINTS", "FreeJoint", "Joint", "RevoluteJoint", "joint_of"]

__dir__ = public_dir(globals())
