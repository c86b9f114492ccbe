"""Report section on several obstacles and contact anywhere: rigid-rod closed forms on the new presets, and the
flexible presets against the finite-element reference.

:func:`section_obstacles` assembles the rows of the checks below, each a function of its own: the rigid rod (modes
off, no gravity) against exact geometry and rigid Hertz theory, then the flexible presets against the FE model.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from ...contact.hertz import rigid_hertz_impact
from ...parameters.case import Case
from ..report import Row, Section
from ..runs import preset, rod_mass_and_inertia, simulate

if TYPE_CHECKING:
    from ...results.records import ContactEvent
    from ...results.solution import Solution

_SOURCE = (
    "The presets `two-stops`, `spinning-stop` and `tip-wall` with the modes off (a rigid rod of inertia "
    "J_O = mu L^3/3 about the joint, no gravity): between contacts the rate is constant, so the contact "
    "times follow from exact geometry. Two stops: IMM intervals theta_u/(e^k omega_0) (each impact flips "
    "the rate by -e), elastic CCFM intervals t_c + theta_u/omega_0 with t_c the rigid Hertz time of the "
    "mass J_O/l^2 at speed omega_0 l, l the stop's lever arm (Johnson 1985 Sec. 11.4). A simultaneous "
    "impact on two stops at x_1, x_2: least-norm impulses P_i = x_i J_O (1 + e) omega_0 / (x_1^2 + x_2^2). "
    "Contact anywhere: a straight rod touches a sphere at distance d from the joint at "
    "x = sqrt(d^2 - (c + r_s)^2), after theta(t) = tau t^2/(2 J_O) reaches phi - asin((c + r_s)/d)."
)

_NOTES = (
    "Spinning stop (contact anywhere, FE and modal model): started 2 ms before the rigid touch with the beam "
    "straight and rotating rigidly (theta = tau t^2 / (2 J_O)), 32 elements against 32 modes; measured onset "
    "2.3e-8 s, contact point 1.0e-7 m, peak 5.4e-4, duration 3.9e-4; tolerances about 20x those.",
    "FE rows: reference the finite-element model (32 elements, its automatic step), value the modal model "
    "(32 modes, CCFM), pure Hertz, no gravity for two-stops; tolerance 3e-3, at least 10x the measured "
    "differences (1.9e-4, 2.0e-4, 2.7e-4, 1.0e-4: the two discretisations' own errors). The upper stop's "
    "peak is not compared: the FE's automatic step "
    "resolves contacts after the first only to about 1 % (measured 6e-3 here; `fem.time_step` refines it, "
    "tests/fem/test_pairs.py).",
    "What the closed forms neglect: the contact normal turning during a contact (theta changes by about "
    "delta_max / x_P ~ 2e-4 rad), a 1e-6 to 1e-5 relative effect on the contact times; the tolerances are "
    "10x the measured differences or more. The flexible presets are compared with the finite-element "
    "reference where it supports the obstacles (see the FE section).",
)

#: restitution of the rigid-rod impacts on the stops
_RESTITUTION = 0.8


def section_obstacles(reduced: bool, figdir: Path | None) -> Section:
    """Several obstacles and contact anywhere: rigid-rod closed forms, then the flexible presets against the FE
    reference (``reduced`` and ``figdir`` unused: the section is fast and has no figure)."""
    s = Section("obstacles", "Several obstacles and contact anywhere (closed forms, FE reference)", _SOURCE)
    e = _RESTITUTION
    base = preset("two-stops", model__modes=0, model__gravity=0.0, solver__t_end=0.04, contact__restitution=e)
    x_p = base.contact.position
    _, J_O = rod_mass_and_inertia(base)
    omega0 = -base.initial.impact_velocity / x_p
    theta_u, lever_u = _upper_stop_contact(base)
    s.rows += _two_stops_imm_rows(base, e, omega0, theta_u)
    s.rows += _two_stops_elastic_rows(x_p, J_O, omega0, theta_u, lever_u)
    s.rows += _simultaneous_impact_rows(base, e, J_O, omega0)
    s.rows += _spinning_stop_rigid_rows(J_O)
    s.rows += _tip_wall_rigid_rows(J_O)
    s.rows += _two_stops_fe_rows()
    s.rows += _tip_wall_fe_rows()
    s.rows += _spinning_stop_fe_rows()
    s.notes += _NOTES
    return s


def _with_obstacles(case: Case, obstacles: list[dict]) -> Case:
    data = case.model_dump()
    data["obstacles"] = obstacles
    return Case.model_validate(data)


def _upper_stop_contact(case: Case) -> tuple[float, float]:
    """``two-stops``' upper stop on a rigid rod: the angle at which the upper surface point at x_P reaches it and
    the lever arm |r x n| of its normal there (exact geometry)."""
    ob = case.obstacles[0]
    x_p, c, radius = case.contact.position, case.beam.surface_offset, ob.radius
    centre = np.asarray(ob.centre)

    def point(th: float) -> np.ndarray:
        return np.array([x_p * math.cos(th) - c * math.sin(th), x_p * math.sin(th) + c * math.cos(th)])

    clearance = float(np.linalg.norm(point(0.0) - centre)) - radius
    theta = brentq(lambda th: np.linalg.norm(point(th) - centre) - radius, 0.0, 2.5 * clearance / x_p, xtol=1e-15)
    p = point(theta)
    n = (p - centre) / np.linalg.norm(p - centre)
    return theta, abs(p[0] * n[1] - p[1] * n[0])


def _contact_point_at_onset(sol: Solution, event: ContactEvent) -> float:
    """Position x along the beam of ``event``'s contact point at its onset (first sample at or after it)."""
    return sol["pair_contact_position"][int(np.searchsorted(sol.time, event.onset)), 0]


def _two_stops_imm_rows(base: Case, e: float, omega0: float, theta_u: float) -> list[Row]:
    """IMM between two stops: the rate flips by -e at each impact, so interval k is theta_u / (e^k omega_0)."""
    onsets = [ev.onset for ev in simulate(base, "imm").contacts]
    return [
        Row(f"two stops, IMM e = {e:g}: interval {k} [s]", theta_u / (e**k * omega0), onsets[k] - onsets[k - 1], 1e-9)
        for k in range(1, min(len(onsets), 4))
    ]


def _two_stops_elastic_rows(x_p: float, J_O: float, omega0: float, theta_u: float, lever_u: float) -> list[Row]:
    """Elastic CCFM between two stops: interval = rigid Hertz contact time at the stop just left (Johnson 1985
    Sec. 11.4, mass J_O/l^2 at speed omega_0 l) + the flight theta_u / omega_0."""
    K = 1e9
    elastic = preset(
        "two-stops", model__modes=0, model__gravity=0.0, solver__t_end=0.03, contact__law="hertz",
        contact__stiffness=K,
    )  # fmt: skip
    sol = simulate(elastic, "ccfm")
    t_c = [rigid_hertz_impact(J_O / lev**2, omega0 * lev, K, 1.5)[2] for lev in (x_p, lever_u)]
    onsets = [ev.onset for ev in sol.contacts]
    return [
        Row(
            f"two stops, elastic CCFM: interval {k} [s]",
            t_c[(k - 1) % 2] + theta_u / omega0,
            onsets[k] - onsets[k - 1],
            2e-5,
        )
        for k in range(1, min(len(onsets), 3))
    ]


def _simultaneous_impact_rows(base: Case, e: float, J_O: float, omega0: float) -> list[Row]:
    """A rigid rod on two lower stops at once (IMM): least-norm impulses P_i = x_i J_O (1 + e) omega_0 /
    (x_1^2 + x_2^2)."""
    x_p = base.contact.position
    c, x2 = base.beam.surface_offset, 0.3
    stop = {"kind": "sphere", "radius": 0.01, "centre": [x2, -c - 0.01], "contact": {"position": x2}}
    both = _with_obstacles(preset("seed-experiment", model__modes=0, model__gravity=0.0, solver__t_end=1e-3,
                                  contact__restitution=e), [stop])  # fmt: skip
    sol = simulate(both, "imm")
    scale = J_O * (1.0 + e) * omega0 / (x_p**2 + x2**2)
    jumps = {ev.pair: ev.jump_impulse for ev in sol.contacts if ev.onset == 0.0}
    return [
        Row("simultaneous impact: impulse at x_P [N s]", scale * x_p, jumps.get(0, math.nan), 1e-9),
        Row("simultaneous impact: impulse at 0.3 m [N s]", scale * x2, jumps.get(1, math.nan), 1e-9),
    ]


def _spinning_stop_rigid_rows(J_O: float) -> list[Row]:
    """Contact anywhere on the torque-driven rigid rod: theta = tau t^2 / (2 J_O) reaches phi - asin((c + r_s)/d)
    and the rod touches the sphere at x = sqrt(d^2 - (c + r_s)^2)."""
    spin = preset("spinning-stop", model__modes=0)
    centre = np.asarray(spin.obstacle.centre)
    d, phi = float(np.hypot(*centre)), math.atan2(centre[1], centre[0])
    reach = spin.beam.surface_offset + spin.obstacle.radius
    sol = simulate(spin, "imm")
    first = sol.contacts[0]
    t_hit = math.sqrt(2.0 * J_O * (phi - math.asin(reach / d)) / spin.drive.torque)
    return [
        Row("spinning stop: contact time [s]", t_hit, first.onset, 1e-9),
        Row(
            "spinning stop: contact point x [m]", math.sqrt(d**2 - reach**2), _contact_point_at_onset(sol, first), 1e-9
        ),
    ]


def _tip_wall_rigid_rows(J_O: float) -> list[Row]:
    """The tip on a wall: a rigid Hertz impact on the half-plane, mass J_O/L^2 at 0.4 m/s (Johnson 1985)."""
    wall = preset("tip-wall", model__modes=0, model__gravity=0.0, contact__law="hertz", solver__t_end=5e-3)
    sol = simulate(wall, "ccfm")
    L = wall.beam.length
    _, f_max, t_wall = rigid_hertz_impact(J_O / L**2, 0.4, wall.contact.stiffness, wall.contact.exponent)
    return [
        Row("tip on a wall: contact duration [s]", t_wall, sol.contacts[0].duration, 1e-4),
        Row("tip on a wall: peak force [N]", f_max, sol.contacts[0].peak_force, 1e-4),
    ]


def _two_stops_fe_rows() -> list[Row]:
    """Flexible ``two-stops`` (pure Hertz, no gravity): FE reference (32 elements) against 32 modes (CCFM)."""
    flexible = {"model__gravity": 0.0, "contact__law": "hertz", "solver__t_end": 0.02}
    fem = simulate(preset("two-stops", fem__elements=32, **flexible), "fem")
    modal = simulate(preset("two-stops", model__modes=32, **flexible), "ccfm")
    upper = [next(ev.onset for ev in sol.contacts if ev.pair == 1) for sol in (fem, modal)]
    return [
        Row(
            "two stops (flexible, FE reference): first peak [N]",
            fem.contacts[0].peak_force,
            modal.contacts[0].peak_force,
            3e-3,
        ),
        Row("two stops (flexible, FE reference): upper stop's onset [s]", upper[0], upper[1], 3e-3),
    ]


def _tip_wall_fe_rows() -> list[Row]:
    """Flexible ``tip-wall``: FE reference (32 elements) against 32 modes (CCFM), first contact."""
    fem = simulate(preset("tip-wall", solver__t_end=1.5e-3, fem__elements=32), "fem")
    modal = simulate(preset("tip-wall", solver__t_end=1.5e-3, model__modes=32), "ccfm")
    rows = []
    for label, key in (("peak [N]", "peak_force"), ("duration [s]", "duration")):
        ref, val = (getattr(sol.contacts[0], key) for sol in (fem, modal))
        rows.append(Row(f"tip on a wall (flexible, FE reference): {label}", ref, val, 3e-3))
    return rows


def _rigid_spin_start(spin: Case, lead: float) -> dict[str, float]:
    """Overrides that start ``spin`` ``lead`` seconds before the rigid rod would touch its obstacle, the beam
    straight and rotating rigidly: theta = tau t^2 / (2 J_O), theta' = tau t / J_O."""
    J_spin = rod_mass_and_inertia(spin)[1]
    centre = np.asarray(spin.obstacle.centre)
    reach = spin.beam.surface_offset + spin.obstacle.radius
    torque = spin.drive.torque
    touch = math.atan2(centre[1], centre[0]) - math.asin(reach / np.hypot(*centre))
    t0 = math.sqrt(2.0 * J_spin * touch / torque) - lead
    return {"initial__angle": torque * t0**2 / (2.0 * J_spin), "initial__rate": torque * t0 / J_spin}


def _spinning_stop_fe_rows() -> list[Row]:
    """Contact anywhere, flexible ``spinning-stop`` from 2 ms before the rigid touch: FE reference (32 elements)
    against 32 modes (CCFM), first contact."""
    start = {**_rigid_spin_start(preset("spinning-stop"), 2e-3), "solver__t_end": 2.45e-3}
    fem = simulate(preset("spinning-stop", fem__elements=32, **start), "fem")
    modal = simulate(preset("spinning-stop", model__modes=32, **start), "ccfm")
    first = [sol.contacts[0] for sol in (fem, modal)]
    at = [_contact_point_at_onset(sol, ev) for sol, ev in zip((fem, modal), first)]
    label = "spinning stop (flexible, FE reference)"
    return [
        Row(f"{label}: onset [s]", first[0].onset, first[1].onset, 5e-7, "abs"),
        Row(f"{label}: contact point x [m]", at[0], at[1], 2e-6, "abs"),
        Row(f"{label}: peak [N]", first[0].peak_force, first[1].peak_force, 1e-2),
        Row(f"{label}: duration [s]", first[0].duration, first[1].duration, 1e-2),
    ]
