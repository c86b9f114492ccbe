"""Contact set-up of a case: the contact point on the beam, the obstacle's geometry and support, the law.

One place for what the modal model and the finite-element reference share as *input*: the contact pairs -- which
material point of the beam can touch which obstacle, under which law -- and the obstacles: where they are
(``[obstacle]`` placed, when the case gives no centre, so that it touches P with the beam straight at
``initial.impact_angle``), how they are held, and which stiffness acts (the Hertz stiffness of a sphere on the
beam's cylinder unless a stiffness is given).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .. import numerics as nm
from ..errors import ParameterError
from ..parameters.case import SIDES, Case, Obstacle, PairContact
from ..parameters.contact import check_friction
from .hertz import effective_modulus, sphere_on_cylinder_stiffness
from .laws import ContactLaw, make_law

OBSTACLE_SPHERE, OBSTACLE_PLANE = 0, 1


@dataclass(frozen=True)
class ObstacleGeometry:
    """An obstacle in the plane of motion.

    ``kind`` 0: sphere (or point, radius 0) at ``centre``; 1: half-plane through ``centre`` with outward unit
    ``normal``.  ``support`` = [m_s, k_s, c_s, u_x, u_y] of a mass-spring-damper holding it (zeros: rigid).
    ``ground``: fixed to the ground on a moving base, ``centre`` in the inertial axes (the beam sees it at
    ``centre`` - r_O(t)); else in the base frame (only a moving base sets it).
    """

    kind: int
    centre: np.ndarray
    radius: float
    normal: np.ndarray
    support: np.ndarray = field(default_factory=lambda: np.zeros(5))
    ground: bool = False

    def seen_from(self, r_O) -> ObstacleGeometry:
        """The obstacle in the base frame when the joint O is at ``r_O``: a ground obstacle at ``centre`` - r_O."""
        if not self.ground:
            return self
        return replace(self, centre=self.centre - np.asarray(r_O, float), ground=False)

    @property
    def compliant(self) -> bool:
        return bool(self.support[0] > 0.0)


@dataclass(frozen=True)
class ContactPair:
    """A material point of the beam (``position`` x, ``offset`` c below the centre line) that can touch obstacle
    number ``obstacle`` (an index into :attr:`ContactSetup.obstacles`) under the contact ``law``."""

    position: float
    offset: float
    obstacle: int
    law: ContactLaw
    restitution: float
    label: str
    anywhere: bool = False  #: the contact point is found on the deformed beam (position, offset: a start)
    friction_static: float = 0.0  #: Coulomb's static coefficient mu_s (IMM's frictional impacts)
    friction: float = 0.0  #: the kinetic coefficient mu_k
    friction_model: str = "coulomb"  #: CCFM's law: "coulomb" (stick and slip) or "threlfall" (regularised)
    friction_velocity: float = 1e-3  #: the regularised law's v_0 [m/s]

    @property
    def frictional(self) -> bool:
        return self.friction_static > 0.0 or self.friction > 0.0


@dataclass(frozen=True)
class ContactSetup:
    """The contact pairs of a case and the obstacles they touch.

    Pair 0 is the case's ``[contact]`` point P against ``[obstacle]`` (obstacle 0, the only one that may stand on a
    compliant support); each ``[[obstacles]]`` entry adds an obstacle and its pair.  ``position``, ``offset``,
    ``obstacle`` and ``law`` are pair 0's.
    """

    pairs: tuple[ContactPair, ...]
    obstacles: tuple[ObstacleGeometry, ...]

    @property
    def position(self) -> float:
        return self.pairs[0].position

    @property
    def offset(self) -> float:
        return self.pairs[0].offset

    @property
    def obstacle(self) -> ObstacleGeometry:
        return self.obstacles[0]

    @property
    def law(self) -> ContactLaw:
        return self.pairs[0].law

    @classmethod
    def from_case(cls, case: Case) -> ContactSetup:
        """Contact points, obstacle placement and laws of ``case``."""
        c = case.beam.surface_offset
        offset = SIDES[case.contact.side] * c
        obstacles = [place_obstacle(case, case.contact.position, offset)]
        mu_k = case.contact.friction
        mu_s = mu_k if case.contact.friction_static is None else case.contact.friction_static
        pairs = [
            ContactPair(
                float(case.contact.position), float(offset), 0, contact_law(case), case.contact.restitution,
                "obstacle", case.contact.anywhere, float(mu_s), float(mu_k), case.contact.friction_model,
                float(case.contact.friction_velocity),
            )
        ]  # fmt: skip
        for i, ob in enumerate(case.obstacles):
            pc = ob.contact
            x = case.contact.position if pc.position is None else pc.position
            side = case.contact.side if pc.side is None else pc.side
            obstacles.append(obstacle_geometry(ob, np.array(ob.centre, float), _outward(case, side), case))
            law = contact_law(case, ob, pc)
            e = case.contact.restitution if pc.restitution is None else pc.restitution
            anywhere = case.contact.anywhere if pc.anywhere is None else pc.anywhere
            kinetic = mu_k if pc.friction is None else pc.friction
            static = pc.friction_static
            if static is None:
                static = mu_s if pc.friction is None else kinetic
            try:
                check_friction(f"obstacles[{i}].contact", kinetic, static)
            except ValueError as exc:
                raise ParameterError(str(exc)) from None
            model = case.contact.friction_model if pc.friction_model is None else pc.friction_model
            v0 = case.contact.friction_velocity if pc.friction_velocity is None else pc.friction_velocity
            pairs.append(ContactPair(float(x), float(SIDES[side] * c), i + 1, law, e, f"obstacles[{i}]", anywhere,
                                     float(static), float(kinetic), model, float(v0)))  # fmt: skip
        check_overlaps(obstacles, case.base.motion(0.0)[0], pairs)
        return cls(tuple(pairs), tuple(obstacles))

    def seen_from(self, r_O) -> tuple[ObstacleGeometry, ...]:
        """The obstacles in the base frame when the joint O is at ``r_O`` (:meth:`ObstacleGeometry.seen_from`)."""
        return tuple(o.seen_from(r_O) for o in self.obstacles)


def _name(i: int) -> str:
    return "obstacle" if i == 0 else f"obstacles[{i - 1}]"


def _contact_field(k: int) -> str:
    """The section of pair k's contact: ``contact`` (pair 0) or ``obstacles[k - 1].contact``."""
    return "contact" if k == 0 else f"obstacles[{k - 1}].contact"


def same_surface(a: ObstacleGeometry, b: ObstacleGeometry) -> bool:
    """Are ``a`` and ``b`` one rigid surface: the same kind, centre, radius and normal, in the same frame (the ground or
    the base), neither on a compliant support?  Several pairs touch one obstacle by repeating it (each its own
    ``[[obstacles]]`` entry and contact point)."""
    return (
        a.kind == b.kind
        and a.ground == b.ground
        and not (a.compliant or b.compliant)
        and a.radius == b.radius
        and np.array_equal(a.centre, b.centre)
        and np.array_equal(a.normal, b.normal)
    )


def check_overlaps(obstacles, r_O, pairs=()) -> None:
    """Obstacles may not overlap: two spheres closer than their radii, a sphere reaching through a plane, or two
    planes that are not parallel (their half-spaces intersect); raises a one-line ParameterError naming the later
    one.  ``obstacles`` as set up (:class:`ObstacleGeometry`), seen from the joint at ``r_O`` for the check.  An
    obstacle repeated exactly (:func:`same_surface`) is one surface that several pairs touch: each of them at a
    fixed material point (contact anywhere finds one point per surface, which another pair's may be)."""
    for j, b in enumerate(obstacles):
        for i, a in enumerate(obstacles[:j]):
            if same_surface(a, b):
                for k in (i, j):
                    if pairs and pairs[k].anywhere:
                        raise ParameterError(
                            f"{_contact_field(k)}.anywhere: {_name(j)} repeats {_name(i)} (one surface that several "
                            "pairs touch), so each of its pairs must be at a fixed point (contact anywhere finds one "
                            "point per surface, which another pair's may be)"
                        )
                if pairs and (pairs[i].position, pairs[i].offset) == (pairs[j].position, pairs[j].offset):
                    raise ParameterError(
                        f"{_contact_field(j)}.position: {_name(j)} repeats {_name(i)} and its pair's point (x = "
                        f"{pairs[j].position:g} m, the same side): one contact counted twice; move it or drop it"
                    )
                continue
            _check_overlap(a.seen_from(r_O), b.seen_from(r_O), i, j)


def _check_overlap(a: ObstacleGeometry, b: ObstacleGeometry, i: int, j: int) -> None:
    """One pair of distinct obstacles (:func:`check_overlaps`), seen from the joint."""
    if a.kind == OBSTACLE_SPHERE and b.kind == OBSTACLE_SPHERE:
        dist = nm.hypot(*(a.centre - b.centre))
        bad = dist < a.radius + b.radius
        what = f"its sphere is {dist:g} m from {_name(i)}'s, closer than the radii {a.radius + b.radius:g} m"
    elif a.kind == OBSTACLE_PLANE and b.kind == OBSTACLE_PLANE:
        cross = a.normal[0] * b.normal[1] - a.normal[1] * b.normal[0]
        bad = abs(cross) > 1e-12 or a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1] > 0.0
        what = f"its half-plane intersects {_name(i)}'s (not parallel and facing each other)"
    else:
        sph, pl = (a, b) if a.kind == OBSTACLE_SPHERE else (b, a)
        depth = nm.dot(pl.normal, sph.centre - pl.centre)
        bad = depth < sph.radius
        what = f"the sphere reaches {sph.radius - depth:g} m into the half-plane ({_name(i)} and it)"
    if bad:
        hint = "" if a.kind != b.kind else "; to touch one obstacle at several points, repeat it exactly"
        raise ParameterError(f"{_name(j)}.centre: overlaps {_name(i)} -- {what}{hint}")


def contact_law(case: Case, obstacle: Obstacle | None = None, pair: PairContact | None = None) -> ContactLaw:
    """The contact law of a pair (default: the case's ``[contact]`` against ``[obstacle]``); its stiffness from
    Hertz theory (the obstacle's sphere on the beam's cylinder, exponent 3/2) unless a stiffness is given (the
    pair's, else ``contact.stiffness``)."""
    obstacle = obstacle or case.obstacle
    con = case.contact
    pick = lambda name: getattr(con, name) if pair is None or getattr(pair, name) is None else getattr(pair, name)  # noqa: E731
    K, exponent = pick("stiffness"), pick("exponent")
    if K is None:
        E_star = effective_modulus(
            case.beam.youngs_modulus, case.beam.poisson_ratio, obstacle.youngs_modulus, obstacle.poisson_ratio
        )
        radius = case.beam.radius if case.beam.section == "circle" else 0.0
        K = sphere_on_cylinder_stiffness(obstacle.radius, radius or 0.0, E_star)
        k = next((k for k, o in enumerate(case.obstacles) if o is obstacle), None)
        if exponent != 1.5:  # (it was replaced by 1.5 without a word: --set contact.exponent=1.0 changed nothing)
            field = "contact" if pair is None or pair.exponent is None or k is None else _contact_field(k + 1)
            raise ParameterError(
                f"{field}.exponent: {exponent:g} needs a stiffness K [N/m^n] (contact.stiffness): with it omitted, "
                "Hertz theory gives K d^1.5, exponent 1.5"
            )
        if not 1e-300 < K < 1e300:  # (an obstacle's E of 5e-324 Pa made K = 0: a division by zero in the estimates)
            name = "obstacle" if k is None else _name(k + 1)
            raise ParameterError(
                f"{name}.youngs_modulus: gives a Hertz contact stiffness of {K:.3g} N/m^1.5, outside the positive "
                "doubles (1e-300, 1e300) (or give contact.stiffness)"
            )
    return make_law(pick("law"), K, exponent, pick("restitution"))


def _outward(case: Case, side: str) -> np.ndarray:
    """The direction from a contact point on ``side`` of the straight beam toward its obstacle, at
    ``initial.impact_angle``: -e2 below (and at the centre line), +e2 above."""
    th = case.initial.impact_angle
    e2 = np.array([-nm.sin(th), nm.cos(th)])
    return e2 if side == "above" else -e2


def place_obstacle(case: Case, position: float, offset: float) -> ObstacleGeometry:
    """Obstacle 0's arrays; without a centre it touches P (beam straight, hub at ``initial.impact_angle``; a free
    beam's centre of mass at the origin) at t = 0 (an obstacle fixed to the ground then at that place + r_O(0))."""
    ob = case.obstacle
    th = case.initial.impact_angle
    s, c = nm.sin(th), nm.cos(th)
    e1 = np.array([c, s])
    e2 = np.array([-s, c])
    root = -0.5 * case.beam.length if case.joint.kind == "free" else case.hub.radius  # x = 0 from the frame origin
    r_P = (root + position) * e1 - offset * e2
    towards = _outward(case, case.contact.side)
    if ob.centre is not None:
        centre = np.array(ob.centre, float)
    else:
        centre = r_P + ob.radius * towards if ob.kind == "sphere" else r_P
    if ob.kind == "sphere":  # the contact normal at P, from the sphere's centre
        norm = nm.hypot(*(r_P - centre))
        towards = (centre - r_P) / norm if norm > 0.0 else towards
    if ob.centre is None and _ground(ob, case):
        centre = centre + np.asarray(case.base.motion(0.0)[0], float)
    return obstacle_geometry(ob, centre, towards, case)


def _ground(ob: Obstacle, case: Case) -> bool:
    """Is ``ob`` fixed to the ground on a base that moves (else it is in the base frame, carried or still)?"""
    return ob.fixed_to == "ground" and case.base.moving


def obstacle_geometry(ob: Obstacle, centre: np.ndarray, towards: np.ndarray, case: Case) -> ObstacleGeometry:
    """The arrays of obstacle ``ob`` of ``case`` at ``centre``; ``towards``: from the beam toward the obstacle (a
    plane's default outward normal is its opposite; a support moves along the outward contact normal by default)."""
    if ob.kind == "sphere":
        kind, radius, normal = OBSTACLE_SPHERE, float(ob.radius), np.zeros(2)
        outward = -towards
    else:
        normal = np.array(ob.normal, float) if ob.normal is not None else -towards
        kind, radius, outward = OBSTACLE_PLANE, 0.0, normal
    support = np.zeros(5)
    sup = ob.support
    if sup.compliant:
        u = np.array(sup.direction, float) if sup.direction is not None else outward
        support = np.array([sup.mass, sup.stiffness, sup.damping, u[0], u[1]], float)
    return ObstacleGeometry(kind, centre, radius, normal, support, _ground(ob, case))
