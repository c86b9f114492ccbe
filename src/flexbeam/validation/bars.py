"""The steel bar on stops: one builder for the free-bar cases that tests and benchmarks share.

The bar is the interim steel bar of the free-beam cases (``tests/validation/data/free-bar-drop.toml``: steel
assumed, E = 200 GPa, nu = 0.29, rho = 7870 kg/m^3, 0.2 m long, 12.7 mm across -- placeholders, not the numbers of
Stoianovici & Hurmuzlu 1996, which could not be read), free (``joint.kind = "free"``), its centre of mass G at
(0, ``y_G``) and its axis at ``angle`` to the x axis.  Spheres of radius ``stop_radius`` touch its lower surface
beneath the points at signed distances ``offsets`` from G along its axis; each contact follows the
Lankarani-Nikravesh law with the Hertz stiffness of the bar's section on the sphere's (1.16e10 N/m^1.5, as in
free-bar-drop), is found anywhere on the bar and may carry Coulomb friction.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..model.system import BeamSystem
from ..parameters import Case, load_case
from ..simulation import initial_state

#: the steel bar (free-bar-drop.toml; steel assumed): 20 cm long, 12.7 mm across
STEEL_BAR = {"length": 0.2, "density": 7870.0, "youngs_modulus": 200e9, "poisson_ratio": 0.29, "section": "circle",
             "radius": 0.00635}  # fmt: skip
#: [N/m^1.5] the Hertz stiffness 4/3 E* sqrt(R) of the bar's end cap on a steel body (free-bar-drop.toml)
STIFFNESS = 1.16e10


def evenly_beneath(s: int) -> list[float]:
    """The offsets from G of ``s`` stops evenly spaced beneath x = 0.05 L .. 0.95 L (one stop: beneath G)."""
    L = STEEL_BAR["length"]
    xs = np.linspace(0.05, 0.95, s) * L if s > 1 else np.array([0.5 * L])
    return [float(x - 0.5 * L) for x in xs]


def bar_on_stops(
    offsets: Sequence[float],
    velocity: tuple[float, float],
    *,
    modes: int = 0,
    mu: float = 0.0,
    mu_s: float | None = None,
    restitution: float = 0.5,
    angle: float = 0.0,
    t_end: float = 0.05,
    y_G: float = 0.1,
    stop_radius: float = 0.01,
    name: str = "bar-on-stops",
) -> Case:
    """The steel bar touching one stop beneath each of ``offsets`` [m] (signed, along its axis from G), G moving at
    ``velocity`` [m/s] (world frame), no spin, gravity 9.81 m/s^2; friction mu_k = ``mu``, mu_s = ``mu_s`` (default
    mu), the stops' Lankarani-Nikravesh contacts with restitution ``restitution``.

    A stop's centre is the point beneath offset d at the distance c + r from the axis: (d cos a + (c + r) sin a,
    y_G + d sin a - (c + r) cos a) with c the bar's radius, r ``stop_radius`` and a ``angle``.
    """
    L, c = STEEL_BAR["length"], STEEL_BAR["radius"]
    ca, sa, r = math.cos(angle), math.sin(angle), c + stop_radius
    centres = [[d * ca + r * sa, y_G + d * sa - r * ca] for d in offsets]
    stops = [{"kind": "sphere", "centre": centre, "radius": stop_radius, "contact": {"position": 0.5 * L + d}}
             for centre, d in zip(centres[1:], offsets[1:], strict=True)]  # fmt: skip
    return load_case({
        "name": name, "beam": dict(STEEL_BAR), "joint": {"kind": "free"},
        "model": {"modes": modes, "gravity": 9.81},
        "obstacle": {"kind": "sphere", "centre": centres[0], "radius": stop_radius},
        "obstacles": stops,
        "contact": {"law": "lankarani_nikravesh", "position": 0.5 * L + offsets[0], "stiffness": STIFFNESS,
                    "side": "below", "restitution": restitution, "anywhere": True, "friction": mu,
                    **({} if mu_s is None else {"friction_static": mu_s})},
        "initial": {"kind": "state", "position": [0.0, y_G], "velocity": list(velocity), "angle": angle,
                    "rate": 0.0},
        "solver": {"t_end": t_end},
    })  # fmt: skip


def start_delassus(case: Case) -> tuple[np.ndarray, np.ndarray]:
    """(W, v-) of all ``case``'s pairs at its start: W = J M^-1 J^T over the coordinates solved for, J the pairs'
    normal rows then their tangential rows (as :mod:`flexbeam.methods.impulse` orders them), v- their velocities."""
    system = BeamSystem.from_case(case)
    y, _ = initial_state(system, case)
    rows = [system.tangent(0.0, y, k) for k in range(len(system.contact.pairs))]
    J = np.vstack([r[3] for r in rows] + [r[4] for r in rows])
    M, _ = system.mass_and_kinetic(0.0, y)
    free = slice(system.ngiven, None)
    W = J[:, free] @ np.linalg.solve(M[free, free], J[:, free].T)
    return W, np.array([r[1] for r in rows] + [r[2] for r in rows])
