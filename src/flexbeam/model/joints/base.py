"""What a joint kind gives the rest of the model: the seam that the revolute joint, the free beam, and the kinds to
come (a moving base), implement (docs/architecture.md, *Adding a joint kind*).

The beam's full coordinates are ``[rigid, q]``: the floating frame's ``nrigid`` coordinates, then the n modal
coordinates.  The first ``ngiven`` of the rigid ones may be functions of time (a prescribed hub angle): they are not
in the state, whose layout is ``[z, z', (s, s'), E_d, W]`` with z the full coordinates without the given ones.
The compiled kernels have the same seam (``kernels/src/joint.h``); :meth:`Joint.code` and :meth:`Joint.parameters`
are what the model buffer carries to them.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import TYPE_CHECKING, ClassVar

import numpy as np

if TYPE_CHECKING:
    from ...parameters.case import Case
    from ..beam import ModalBeam
    from ..system import BeamSystem


class Joint(ABC):
    """A joint kind: its coordinates, its drive, its rigid-body mass, and the state layout it implies."""

    #: the name in ``[joint] kind``
    kind: ClassVar[str]
    #: the kernels' FB_JOINT_* code
    code: ClassVar[int]
    #: names of the frame's coordinates, leading the full coordinates
    coordinates: ClassVar[tuple[str, ...]]
    #: impact methods (flexbeam.registry) that do not model this kind yet: refused in one line naming joint.kind
    unsupported_methods: ClassVar[tuple[str, ...]] = ()

    def __init__(self, case: Case) -> None:
        self.case = case

    @property
    def nrigid(self) -> int:
        """The frame's coordinates."""
        return len(self.coordinates)

    @property
    @abstractmethod
    def ngiven(self) -> int:
        """How many of the frame's coordinates are functions of time (not in the state)."""

    @property
    def prescribed(self) -> bool:
        """Does the joint give a coordinate as a function of time?"""
        return self.ngiven > 0

    @abstractmethod
    def parameters(self) -> list[float]:
        """The joint's parameters in the kernels' model buffer (``jp``, read by ``joint_<kind>.c``)."""

    @abstractmethod
    def frame(self, t: float, y: np.ndarray, n: int) -> tuple[float, float, np.ndarray, np.ndarray]:
        """(theta, theta', q, q') of state ``y`` at time ``t``: the frame's angle and rate, the modal coordinates."""

    @abstractmethod
    def given(self, t: float) -> np.ndarray:
        """(positions, rates, accelerations) of the given coordinates at time t, rows of ``ngiven`` each."""

    @abstractmethod
    def state(self, n: int, rigid: np.ndarray, rates: np.ndarray, q: np.ndarray, qd: np.ndarray,
              tail: list[float]) -> np.ndarray:  # fmt: skip
        """The state vector from the frame's coordinates and rates (the given ones ignored), q, q' and the tail
        ([s, s',] E_d, W)."""

    def full_velocities(self, t: float, y: np.ndarray, n: int) -> np.ndarray:
        """z' over the full coordinates [rigid, q] (the given ones' rates from time)."""
        nz = self.nrigid - self.ngiven + n
        zd = np.empty(self.nrigid + n)
        zd[: self.ngiven] = self.given(t)[1]
        zd[self.ngiven :] = y[nz : 2 * nz]
        return zd

    def full_accelerations(self, t: float, yd: np.ndarray, n: int) -> np.ndarray:
        """z'' over the full coordinates from the state's derivative (the given ones' from time)."""
        nz = self.nrigid - self.ngiven + n
        zdd = np.empty(self.nrigid + n)
        zdd[: self.ngiven] = self.given(t)[2]
        zdd[self.ngiven :] = yd[nz : 2 * nz]
        return zdd

    def with_velocities(self, y: np.ndarray, zd: np.ndarray, n: int) -> np.ndarray:
        """Copy of ``y`` with the state's velocities from full velocities ``zd`` (the given ones dropped)."""
        nz = self.nrigid - self.ngiven + n
        y = y.copy()
        y[nz : 2 * nz] = zd[self.ngiven : self.nrigid + n]
        return y

    def origin(self, t: float, y: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray] | None:
        """The frame's origin and its velocity in the plane at state ``y``; None: the fixed point O (the origin)."""
        return None

    @abstractmethod
    def hub_angle(
        self, beam: ModalBeam, theta: float, rate: float, q: np.ndarray, qd: np.ndarray
    ) -> tuple[float, float]:
        """The hub angle and its rate (what the outputs report and a drive torque works on)."""

    @abstractmethod
    def linear_model(self, beam: ModalBeam) -> tuple[np.ndarray, np.ndarray, int | None]:
        """(M0, K0, varying): the mass and stiffness of the model linearised about the undeformed beam at rest over
        the state's coordinates, and the index of the one diagonal entry of M that varies with q (the frame's
        rotary inertia J_c + q^T M_c q; None when it is given), for the integrator's Sherman-Morrison update."""

    @abstractmethod
    def initial_state(self, system: BeamSystem, case: Case,
                      first_impact: Callable[[np.ndarray], float]) -> tuple[np.ndarray, dict[str, float]]:  # fmt: skip
        """The state of ``case.initial`` and the values derived for it; ``first_impact(y0)``: the contact point's
        normal velocity at the first impact of a free flight from y0, NaN if none (for a start whose impact speed is
        solved for; the simulation layer provides it)."""
