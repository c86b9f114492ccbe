"""Natural frequencies of small in-plane vibration about steady rotation.

Linearising the flexible equations (``docs/formulation.md``) about theta' = Omega = const, theta'' = 0,
q = 0, g = 0, with the hub held at constant speed -- the beam root clamped to a hub turning at a prescribed
rate, the hub frame with its clamped-free modes:

    M_ff q'' + [K_ff + Omega^2 (D - M_ff)] q = 0   ->   omega^2 = eig(K_ff + Omega^2 (D - M_ff), M_ff).

The first-order model's D is the centrifugal geometric stiffness; the zeroth-order
model lacks it, so its stiffness K_ff - Omega^2 M_ff softens with spin and loses
definiteness (buckles) once Omega exceeds the first cantilever frequency.
For the out-of-plane (flapwise) problem the -Omega^2 M_ff term is absent, so
omega_chordwise^2 = omega_flapwise^2 - Omega^2 for the same D.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import eigh

from ..errors import ParameterError
from ..parameters.case import Case
from .beam import ModalBeam, build_modal_beam


def spin_frequencies(beam: ModalBeam, spin: float, plane: str = "chordwise") -> np.ndarray:
    """Frequencies [rad/s] of the modal beam spinning at ``spin`` [rad/s].

    Parameters
    ----------
    beam
        Modal matrices (first- or zeroth-order, as built).
    spin
        Hub rate Omega [rad/s].
    plane
        ``"chordwise"`` (in the plane of rotation, the model of this package) or
        ``"flapwise"`` (out of plane: no -Omega^2 M_ff softening).

    Returns
    -------
    ndarray
        Ascending frequencies; an unstable (divergent) mode is returned as the
        negative square root of ``|omega^2|``, so a negative entry flags instability.
    """
    if beam.frame != "hub":
        raise ValueError(
            "beam: spin frequencies about a hub held at constant speed need the hub frame "
            "(build it with hub_frame_beam)"
        )
    if beam.n == 0:
        return np.empty(0)
    K = beam.Kff + spin**2 * beam.D
    if plane == "chordwise":
        K = K - spin**2 * beam.Mff
    elif plane != "flapwise":
        raise ValueError("plane: must be 'chordwise' or 'flapwise'")
    w2 = eigh(K, beam.Mff, eigvals_only=True)
    return np.sign(w2) * np.sqrt(np.abs(w2))


def hub_frame_beam(case: Case, coupling: str | None = None) -> ModalBeam:
    """The modal beam of ``case`` in the hub frame (clamped-free modes), optionally with another coupling model."""
    model = case.model.model_copy(update={"frame": "hub", **({"coupling": coupling} if coupling else {})})
    return build_modal_beam(case.model_copy(update={"model": model}))


def case_frequencies(case: Case, spin: float, plane: str = "chordwise") -> dict[str, np.ndarray]:
    """Frequencies of both coupling models for ``case`` at hub rate ``spin`` (hub held at constant speed).  A free
    beam (``joint.kind = "free"``) has no hub to spin about: a one-line :class:`~flexbeam.errors.ParameterError`
    (it ended in a ValueError's traceback)."""
    if case.joint.kind != "revolute":
        raise ParameterError(
            f"joint.kind: natural frequencies about steady spin need the beam clamped to a hub (joint.kind = "
            f"'revolute'); this case's beam is '{case.joint.kind}'"
        )
    return {c: spin_frequencies(hub_frame_beam(case, c), spin, plane) for c in ("first-order", "zeroth-order")}
