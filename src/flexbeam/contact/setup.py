"""Contact set-up of a case: the contact point on the beam, the obstacle's geometry and support, the law.

One place for what the modal model and the finite-element reference share as *input*: where P is on the beam,
where the obstacle is (placed, when the case gives no centre, so that it touches P with the beam straight at
``initial.impact_angle``), how it is held, and which contact law with which stiffness acts (the Hertz stiffness
of a sphere on the beam's cylinder unless ``contact.stiffness`` is given).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..parameters.case import Case
from .hertz import effective_modulus, sphere_on_cylinder_stiffness
from .laws import ContactLaw, make_law

OBSTACLE_SPHERE, OBSTACLE_PLANE = 0, 1


@dataclass(frozen=True)
class ObstacleGeometry:
    """An obstacle in the plane of motion.

    ``kind`` 0: sphere (or point, radius 0) at ``centre``; 1: half-plane through ``centre`` with outward unit
    ``normal``.  ``support`` = [m_s, k_s, c_s, u_x, u_y] of a mass-spring-damper holding it (zeros: rigid).
    """

    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray
    support: np.ndarray = field(default_factory=lambda: np.zeros(5))

    @property
    def compliant(self) -> bool:
        return bool(self.support[0] > 0.0)


@dataclass(frozen=True)
class ContactSetup:
    """The contact point P (material coordinate ``position``, ``offset`` c below the centre line), the obstacle
    and the contact law of a case."""

    position: float
    offset: float
    obstacle: ObstacleGeometry
    law: ContactLaw

    @classmethod
    def from_case(cls, case: Case) -> ContactSetup:
        """Contact point, obstacle placement and law of ``case``."""
        c = case.beam.surface_offset
        obstacle = place_obstacle(case, case.contact.position, c)
        return cls(float(case.contact.position), float(c), obstacle, contact_law(case))


def contact_law(case: Case) -> ContactLaw:
    """The case's contact law; its stiffness from Hertz theory (sphere on the beam's cylinder, exponent 3/2)
    unless ``contact.stiffness`` is given."""
    K = case.contact.stiffness
    exponent = case.contact.exponent
    if K is None:
        E_star = effective_modulus(
            case.beam.youngs_modulus, case.beam.poisson_ratio, case.obstacle.youngs_modulus,
            case.obstacle.poisson_ratio,
        )  # fmt: skip
        radius = case.beam.radius if case.beam.section == "circle" else 0.0
        K = sphere_on_cylinder_stiffness(case.obstacle.radius, radius or 0.0, E_star)
        exponent = 1.5
    return make_law(case.contact.law, K, exponent, case.contact.restitution)


def place_obstacle(case: Case, position: float, offset: float) -> ObstacleGeometry:
    """The obstacle's arrays; without a centre it touches P (beam straight, hub at ``initial.impact_angle``)."""
    ob = case.obstacle
    th = case.initial.impact_angle
    e1 = np.array([math.cos(th), math.sin(th)])
    e2 = np.array([-math.sin(th), math.cos(th)])
    r_P = (case.hub.radius + position) * e1 - offset * e2
    if ob.kind == "sphere":
        centre = np.array(ob.centre, float) if ob.centre is not None else r_P - ob.radius * e2
        outward = r_P - centre
        norm = math.hypot(*outward)
        outward = outward / norm if norm > 0.0 else e2
        kind, radius, normal = OBSTACLE_SPHERE, float(ob.radius), np.zeros(2)
    else:
        centre = np.array(ob.centre, float) if ob.centre is not None else r_P
        normal = np.array(ob.normal, float) if ob.normal is not None else e2
        kind, radius, outward = OBSTACLE_PLANE, 0.0, normal
    support = np.zeros(5)
    sup = ob.support
    if sup.compliant:
        u = np.array(sup.direction, float) if sup.direction is not None else outward
        support = np.array([sup.mass, sup.stiffness, sup.damping, u[0], u[1]], float)
    return ObstacleGeometry(kind, centre, radius, normal, support)
