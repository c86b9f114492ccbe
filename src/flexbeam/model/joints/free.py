"""A free-flying beam: no joint.  The floating frame sits at the centre of mass G (docs/formulation.md, *A
free-flying beam*).

Coordinates ``[x_G, y_G, theta, q]`` with the free-free modes (:class:`~flexbeam.model.modes.FreeFreeShapes`),
orthogonal to the rigid translation and rotation, so that the linearised mass matrix is diag(m, m, J_G, mu L I)
and only its theta-theta entry varies with q (J_G + q^T M_c q).  No hub and no drive; gravity acts on y_G alone.
The compiled side is ``kernels/src/joint_free.c``.

Initial states (``[initial]``): ``state`` (G at ``position`` moving at ``velocity``, the frame at ``angle``
turning at ``rate``, the modal coordinates of ``modal_displacement`` and ``modal_velocity``) and ``impact`` (the
frame at ``impact_angle``, beam straight, translating without spin along the first pair's contact normal at
``impact_velocity``, G placed so that that pair's gap is zero).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from ...errors import ParameterError
from ...parameters.case import Case
from .base import Joint
from .revolute import flexible_blocks, initial_modal

if TYPE_CHECKING:
    from ..beam import ModalBeam
    from ..system import BeamSystem


class FreeJoint(Joint):
    """No joint: the beam's centre of mass and angle are free coordinates."""

    kind = "free"
    code = 1
    coordinates = ("x_G", "y_G", "theta")
    #: every method runs a free beam: CCM (tests/validation/test_free_beam_ccm.py), the FE reference
    #: (flexbeam.fem.free)
    unsupported_methods: tuple[str, ...] = ()

    @property
    def ngiven(self) -> int:
        return 0

    @property
    def mass(self) -> float:
        """The beam's mass m = mu L [kg]."""
        return self.case.beam.mass

    def parameters(self) -> list[float]:
        """[m] (``joint_free.c``)."""
        return [float(self.mass)]

    def frame(self, t: float, y: np.ndarray, n: int) -> tuple[float, float, np.ndarray, np.ndarray]:
        nz = n + 3
        return float(y[2]), float(y[nz + 2]), y[3:nz], y[nz + 3 : 2 * nz]

    def origin(self, t: float, y: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
        """(R_G, R_G'): the centre of mass and its velocity."""
        nz = n + 3
        return np.array(y[0:2], float), np.array(y[nz : nz + 2], float)

    def given(self, t: float) -> np.ndarray:
        return np.zeros((3, 0))

    def state(self, n: int, rigid, rates, q, qd, tail) -> np.ndarray:
        """``rigid``: [x_G, y_G, theta], or [theta] alone (G at the origin, at rest); ``rates`` alike."""
        rigid, rates = np.asarray(rigid, float), np.asarray(rates, float)
        if rigid.size == 1:
            rigid = np.array([0.0, 0.0, rigid[0]])
        if rates.size == 1:
            rates = np.array([0.0, 0.0, rates[0]])
        return np.concatenate((rigid, q, rates, qd, tail))

    def hub_angle(self, beam: ModalBeam, theta: float, rate: float, q: np.ndarray, qd: np.ndarray):
        return theta, rate

    def linear_model(self, beam: ModalBeam) -> tuple[np.ndarray, np.ndarray, int | None]:
        n = beam.nq
        M0 = np.zeros((n + 3, n + 3))
        M0[0, 0] = M0[1, 1] = self.mass
        M0[2, 2] = beam.Jc
        M0[3:, 3:], K0 = flexible_blocks(beam)
        K0 = np.pad(K0, ((3, 0), (3, 0)))
        return M0, K0, 2

    def initial_state(self, system: BeamSystem, case: Case, first_impact: Callable[[np.ndarray], float]):
        init = case.initial
        n = system.n
        tail = [0.0, 0.0, 0.0, 0.0] if system.compliant else [0.0, 0.0]
        if init.kind == "state":
            q, qd = initial_modal(case, n)
            y = self.state(n, [*init.position, init.angle], [*init.velocity, init.rate], q, qd, tail)
            return y, {}
        if init.kind != "impact":
            raise ParameterError(
                f"initial.kind: '{init.kind}' needs a joint; a free beam starts with 'state' or 'impact'"
            )
        zeros = np.zeros(n)
        y = self.state(n, [0.0, 0.0, init.impact_angle], [0.0, 0.0, 0.0], zeros, zeros, tail)
        for _ in range(3):  # translate G along the normal until pair 0 touches (one step is exact but for round-off)
            delta, _, _, J = system.gap(0.0, y)
            normal = J[:2]
            y[:2] -= delta * normal
            if abs(delta) <= 1e-15 * max(1.0, case.beam.length):
                break
        normal = system.gap(0.0, y)[3][:2]
        y[n + 3 : n + 5] = init.impact_velocity * normal
        return y, {"impact_x_G": float(y[0]), "impact_y_G": float(y[1])}
