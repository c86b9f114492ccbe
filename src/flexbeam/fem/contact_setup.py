"""The FE reference's contact from the case: the contact law and where the obstacle stands.

Read from the case directly, without building the modal model.  The law's parameters are
the case's inputs and are shared with the modal model on purpose: the law and chi(e) from
:func:`flexbeam.contact.laws.make_law`, and, when ``contact.stiffness`` is omitted, the
Hertz stiffness K = 4/3 E* sqrt(R_e) of the sphere on the beam's section
(:mod:`flexbeam.contact.hertz`, exponent 3/2).  The force and the gap are evaluated by the
FE's own kernels (:mod:`flexbeam.fem.contact_law`, :mod:`flexbeam.fem.gap`).

Obstacle placement (the case's convention): without ``obstacle.centre`` the obstacle
touches P in the impact configuration, the straight beam at ``initial.impact_angle``
theta_i, where P is at r_P = (r_h + x_P) e1 - c e2 (e1 = (cos theta_i, sin theta_i),
e2 = (-sin theta_i, cos theta_i), c the surface offset): a sphere's centre is then
r_P - R e2, a half-plane passes through r_P with the normal e2 unless
``obstacle.normal`` is given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact.hertz import effective_modulus, sphere_on_cylinder_stiffness
from ..contact.laws import ContactLaw, make_law
from ..parameters.case import Case
from .gap import HALF_PLANE, SPHERE


@dataclass(frozen=True)
class ContactSetup:
    """Contact law and obstacle of a case, as the FE kernels take them.

    ``kind`` is :data:`~flexbeam.fem.gap.SPHERE` or :data:`~flexbeam.fem.gap.HALF_PLANE`;
    ``radius`` is 0 and ``normal`` unused for a half-plane, ``normal`` is zero for a sphere.
    """

    law: ContactLaw
    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray

    @classmethod
    def from_case(cls, case: Case) -> ContactSetup:
        """The contact law and the placed obstacle of ``case``."""
        return cls(law_of(case), *obstacle_of(case))


def law_of(case: Case) -> ContactLaw:
    """The case's contact law; the stiffness defaults to Hertz's sphere on the beam section."""
    K = case.contact.stiffness
    exponent = case.contact.exponent
    if K is None:
        E_star = effective_modulus(case.beam.youngs_modulus, case.beam.poisson_ratio,
                                   case.obstacle.youngs_modulus, case.obstacle.poisson_ratio)
        section_radius = case.beam.radius if case.beam.section == "circle" else 0.0
        K = sphere_on_cylinder_stiffness(case.obstacle.radius, section_radius or 0.0, E_star)
        exponent = 1.5
    return make_law(case.contact.law, K, exponent, case.contact.restitution)


def obstacle_of(case: Case) -> tuple[int, np.ndarray, float, np.ndarray]:
    """(kind, centre, radius, normal) of the obstacle, placed as the module docstring says."""
    ob = case.obstacle
    theta = case.initial.impact_angle
    e1 = np.array([math.cos(theta), math.sin(theta)])
    e2 = np.array([-math.sin(theta), math.cos(theta)])
    r_P = (case.hub.radius + case.contact.position) * e1 - case.beam.surface_offset * e2
    if ob.kind == "sphere":
        centre = np.array(ob.centre, float) if ob.centre is not None else r_P - ob.radius * e2
        return SPHERE, centre, float(ob.radius), np.zeros(2)
    centre = np.array(ob.centre, float) if ob.centre is not None else r_P
    normal = np.array(ob.normal, float) if ob.normal is not None else e2
    return HALF_PLANE, centre, 0.0, normal
