"""Report sections on the impact methods: IMM impulse identities, CCM constraint, compliant support."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..references import two_mass_chain
from ..report import Row, Section
from ..runs import rod_mass_and_inertia, seed, simulate


def section_imm(reduced: bool, figdir: Path | None) -> Section:
    from ...methods.impulse import impulse_jump
    from ...model.system import BeamSystem
    from ...simulation import initial_state

    s = Section(
        "imm",
        "Impulse-momentum identities (IMM)",
        "Y. A. Khulief, A. A. Shabana, *Mech. Mach. Theory* 22 (1987) 213: with W = J M^-1 J^T, "
        "the impulse P = -(1 + e) v^-/W gives v^+ = -e v^- and removes (1 - e^2)(v^-)^2/(2W) of "
        "kinetic energy. flexbeam: `impulse_jump` on the seed beam (6 modes) deformed and "
        "vibrating at the impact, and the IMM run of a rigid rod (m_eff = J_O/x_P^2); bouncing rod "
        "under gravity: flights 2 w_k/alpha with w_k = e^k w_0, alpha = 3g/(2L), accumulating at "
        "t = 2 w_0/(alpha (1 - e)) (small-angle).",
    )

    def jump(e):
        case = seed(model__modes=6, contact__restitution=e)
        system = BeamSystem.from_case(case)
        y, _ = initial_state(system, case)
        rng = np.random.default_rng(5)
        k2 = np.arange(1, 7) ** 2
        y[1:7] = rng.normal(size=6) * 1e-5 / k2
        y[8:14] = rng.normal(size=6) * 1e-2 / k2
        return system, y, impulse_jump(system, 0.0, y, e)

    _, _, j1 = jump(1.0)
    s.rows.append(Row("e = 1: kinetic energy after / before", 1.0, j1.kinetic_after / j1.kinetic_before, 1e-12))
    s.rows.append(Row("e = 1: v+ / v-", -1.0, j1.velocity_after / j1.velocity_before, 1e-12))
    _, _, j0 = jump(0.0)
    s.rows.append(Row("e = 0: v+ / v-", 0.0, j0.velocity_after / j0.velocity_before, 1e-12, "abs"))
    for e in (0.5, 0.9):
        system, y, j = jump(e)
        M = system.mass_matrix(0.0, y)
        J = system.gap(0.0, y)[3]
        W = float(J @ np.linalg.solve(M, J))
        v = j.velocity_before
        s.rows.append(Row(f"e = {e:g}: v+ / v-", -e, j.velocity_after / v, 1e-12))
        s.rows.append(
            Row(
                f"e = {e:g}: kinetic energy loss [J]",
                (1 - e**2) * v**2 / (2 * W),
                j.kinetic_before - j.kinetic_after,
                1e-10,
            )
        )
    e = 0.35
    case = seed(
        model__modes=0, model__gravity=0.0, contact__restitution=e, contact__law="hunt_crossley", solver__t_end=1e-3
    )
    sol = simulate(case, "imm")
    i = np.nonzero(sol.time == sol.contacts[0].onset)[0]
    before, after = float(sol["theta_rate"][i[0]]), float(sol["theta_rate"][i[-1]])
    s.rows.append(Row("rigid rod, e = 0.35: theta'+ / theta'-", -e, after / before, 1e-12))
    _, J_O = rod_mass_and_inertia(case)
    m_eff = J_O / case.contact.position**2
    s.rows.append(Row("rigid rod, e = 0.35: impulse [N s]", (1 + e) * m_eff * 0.4, sol.contacts[0].impulse, 1e-10))
    e = 0.5
    case = seed(model__modes=0, contact__restitution=e, contact__law="hunt_crossley", solver__t_end=0.2)
    sol = simulate(case, "imm")
    onsets = np.array([c.onset for c in sol.contacts])
    w0 = 0.4 / case.contact.position * e
    alpha = 3 * case.model.gravity / (2 * case.beam.length)
    for k in range(3):
        s.rows.append(Row(f"bouncing rod: flight {k + 1} [s]", 2 * w0 * e**k / alpha, onsets[k + 1] - onsets[k], 1e-4))
    s.rows.append(Row("bouncing rod: accumulation time [s]", 2 * w0 / alpha / (1 - e), onsets[-1], 1e-3))
    s.notes.append(
        f"The bouncing rod ends resting on the obstacle after {len(onsets)} impacts (final phase '{sol.phase[-1]}')."
    )
    return s


def section_ccm(reduced: bool, figdir: Path | None) -> Section:
    s = Section(
        "ccm",
        "Contact constraint (CCM)",
        "statics: a rigid rod pinned at O resting on the obstacle at x_P carries lambda x_P = m g L/2 "
        "(moment balance about O). flexbeam: CCM, 0 modes, started at rest on the obstacle, mean and "
        "extreme contact force over the constrained phase; and the gap held closed during the seed "
        "impact (4 modes).",
        columns=["x_P [m]"],
    )
    for xp in (0.585,) if reduced else (0.585, 0.35):
        case = seed(
            model__modes=0,
            initial__kind="state",
            initial__angle=0.0,
            initial__rate=0.0,
            contact__position=xp,
            solver__t_end=0.01,
        )
        sol = simulate(case, "ccm")
        F = sol["contact_force"][sol.phase == "constrained"]
        m, _ = rod_mass_and_inertia(case)
        ref = m * case.model.gravity * case.beam.length / (2 * xp)
        ex = {"x_P [m]": f"{xp:g}"}
        s.rows.append(Row("resting rod: mean contact force [N]", ref, float(np.mean(F)), 1e-9, extra=ex))
        s.rows.append(
            Row("resting rod: extreme contact force [N]", ref, float(F[np.argmax(np.abs(F - ref))]), 1e-9, extra=ex)
        )
    sol = simulate(seed(model__modes=4, solver__t_end=2e-3), "ccm")
    inside = sol.phase == "constrained"
    s.rows.append(
        Row(
            "seed impact: max |gap| while constrained [m]",
            0.0,
            float(np.max(np.abs(sol["gap"][inside]))),
            1e-10,
            "abs",
            extra={"x_P [m]": "0.585"},
        )
    )
    s.rows.append(
        Row(
            "seed impact: min force / peak force while constrained",
            0.0,
            min(0.0, float(np.min(sol["contact_force"][inside]) / np.max(sol["contact_force"]))),
            1e-6,
            "abs",
            extra={"x_P [m]": "0.585"},
        )
    )
    return s


def section_support(reduced: bool, figdir: Path | None) -> Section:
    s = Section(
        "support",
        "Obstacle on a compliant support (force sensor)",
        "closed-form two-body mechanics: a rigid rod (effective mass m1 = J_O / x_P^2 at P, no gravity) "
        "hits an obstacle of mass m2 = 0.05 kg on a spring k_s = 2e6 N/m. CCFM with a linear contact "
        "spring k_c = 5e6 N/m: the chain's normal-mode solution (`flexbeam.validation.two_mass_chain`), "
        "contact force and the sensor's -k_s x2; CCM: perfectly plastic impact, then both bodies on k_s "
        "for half a period, peak force m1 v_c w with v_c = m1 v0/(m1 + m2), w^2 = k_s/(m1 + m2).",
        columns=["method"],
    )
    m2, ks, kc, v0 = 0.05, 2.0e6, 5.0e6, -0.4
    base = dict(
        model__modes=0,
        model__gravity=0.0,
        obstacle__support__mass=m2,
        obstacle__support__stiffness=ks,
        initial__impact_velocity=v0,
        solver__t_end=3e-3,
    )
    case = seed(**base, contact__law="hertz", contact__stiffness=kc, contact__exponent=1.0, solver__sample_step=2e-8)
    m1 = rod_mass_and_inertia(case)[1] / case.contact.position**2
    F, t_c, F_s, t_s = two_mass_chain(m1, m2, kc, ks, v0)
    m = simulate(case).metrics()
    ex = {"method": "CCFM"}
    s.rows += [
        Row("peak contact force [N]", F, m["peak_force"], 2e-4, extra=ex),
        Row("contact duration [s]", t_c, m["contact_duration"], 2e-4, extra=ex),
        Row("peak sensor force [N]", F_s, m["sensor_peak_force"], 1e-3, extra=ex),
        Row("sensor pulse duration [s]", t_s, m["sensor_duration"], 1e-3, extra=ex),
    ]
    sol = simulate(seed(**base), "ccm")
    held = [ev for ev in sol.contacts[1:] if ev.onset < 1e-6] or sol.contacts[:1]
    v_c = m1 * abs(v0) / (m1 + m2)
    w = math.sqrt(ks / (m1 + m2))
    ex = {"method": "CCM"}
    s.rows += [
        Row("contact force peak [N]", m1 * v_c * w, held[0].peak_force, 1e-4, extra=ex),
        Row("contact duration [s]", math.pi / w, held[0].end - sol.contacts[0].onset, 1e-4, extra=ex),
    ]
    s.notes.append(
        "CCM: right after the e = 0 jump the spring force is zero and the sphere's curvature makes "
        "the multiplier a hair tensile; P leaves and is caught again within a microsecond at a "
        "vanishing approach speed, and the contact then lasts (the duration is counted from the first "
        "onset)."
    )
    return s
