"""Coulomb friction in IMM's resting contact (issue 28): a pair at rest on its obstacle slips, stops, sticks, unsticks.

**A bar dropped flat on rough stops.**  The rigid steel bar of ``test_friction_ccfm.py`` is lifted by h above its two
hemispherical stops and dropped level, moving along its axis at v0.  It lands on both stops at once at v_n =
sqrt(2 g h).  The frictional impact LCP (docs/methods.md, "Friction at simultaneous impacts") gives both ends the
normal velocity -e v_n after and, while they slip throughout (v_x > mu (1 + e) v_n), v_x^+ = v_x - mu (1 + e) v_n;
the bar stays level (both ends leave at the same normal velocity) and flies back with the speed it landed with, so
the j-th impact is at e^j v_n.  IMM ends the sequence at the first impact whose rebound e e^j v_n falls below
``solver.rest_velocity`` (always the first for e = 0): that impact takes e = 0, m e^j v_n, and the bar rests.  Hence
the sliding velocity at the start of the resting phase

    v_s = v0 - mu v_n ((1 + e) (1 + e + ... + e^(k-1)) + e^k)         (k impacts before the resting one),

after which the held normals (vertical while the bar stays level) carry m g and kinetic friction decelerates G at
mu g: the slip stops (a located event) T = v_s / (mu g) after the resting phase started, having slid
d = v_s^2 / (2 mu g).  Over the whole run the impulse-momentum balance gives a closed form that does not depend on
h, e or the impacts: the normal impulses add up to m g t_stop (v_y is 0 at the start and at the stop), the
tangential ones to mu times that and to m v0, so the slip stops at t_stop = v0 / (mu g) after the drop.
The tolerance is the integrator's relative tolerance ``solver.fast_rtol`` (it bounds the relative error of the
flights' speeds and of the slide's v_x, so of v_s, T, d and t_stop) plus the normals' tilt bound
2 theta_max (1/mu + mu) of ``test_friction_ccfm.py`` (theta_max < 1e-13 here: nothing turns); measured errors are
below 3e-11 relative.

**Incline.**  The bar set down on stops along a line at alpha rests at once (its approach speed 0 is below
``solver.rest_velocity``): for tan(alpha) < mu_s it sticks (its contact points creep less than 1e-9 m over 1 s); for
tan(alpha) > mu_s it slides down at g (sin(alpha) - mu_k cos(alpha)) (within ``fast_rtol``).

**CCM and IMM agree.**  Once resting, IMM's held contact is CCM's: the same impulse map with e = 0 at the onset
(:meth:`~flexbeam.methods.base.ImpactMethod.held_impact`), the same DAE, rows, events and switches
(:class:`~flexbeam.methods.held_friction.HeldFriction`, one piece of code); the phases differ only by their name and
output spacing, which the integration does not see.  So their phases end at the same times in the same states, to
round-off: asserted within 1e-12 (of m, m/s, s; measured: identical).

**Friction power** F_t v_t <= 0 at every step's Gauss nodes (:func:`test_friction_ccfm.friction_power`, with its
allowance for a stick's residual slip velocity).
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.errors import FlexbeamWarning
from flexbeam.model.system import BeamSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_ccfm import G, bar_on_stops, creep, friction_power, states  # noqa: E402
from test_friction_ccm import MASS, RTOL, kinetic_jump, painleve_rod, run  # noqa: E402
from test_friction_impact import rough_bar  # noqa: E402

#: the drop height [m] and the axial velocity [m/s]: the bar slides ~2.5 mm, well on its stops
DROP, V0 = 5e-4, 0.15
#: CCM's and IMM's phase ends agree to round-off (module docstring)
SAME = 1e-12


def dropped(mu: float, e: float, rest: float, t_end: float) -> fb.Case:
    """``bar_on_stops`` lifted by DROP, sliding at V0, restitution ``e``, ``solver.rest_velocity`` = ``rest``."""
    data = bar_on_stops(mu, V0, t_end).model_dump()
    x, y = data["initial"]["position"]
    data["initial"]["position"] = [x, y + DROP]
    data["contact"]["restitution"] = e
    data["solver"]["rest_velocity"] = rest
    return fb.load_case(data)


def resting_slide(mu: float, e: float, rest: float) -> float:
    """The module docstring's v_s: the axial velocity when the bar comes to rest [m/s]."""
    vn = math.sqrt(2.0 * G * DROP)
    speeds = [vn]
    while e > 0.0 and e * speeds[-1] >= rest:
        speeds.append(e * speeds[-1])
    return V0 - mu * ((1.0 + e) * sum(speeds[:-1]) + speeds[-1])


def slips_end(sol) -> float:
    """The end of the last phase in which pair 0 slips [s]."""
    return [s.t1 for s in sol.source.run.segments if s.phase.friction is not None and s.phase.friction[0, 0] != 0.0][-1]


@pytest.mark.parametrize(("e", "rest"), [(0.0, 0.0), (0.5, 0.02)])
def test_a_bar_dropped_on_rough_stops_rests_then_slides_to_the_closed_form(e, rest):
    """v_s at the resting phase's start, the stop T after it and the slide d against the module docstring; the stop at
    v0 / (mu g) after the drop; the records' tangential impulses add up to m v0; while resting it slips (state 1,
    F_t = mu_k F_n), then sticks (state 2) to the end; friction power <= 0."""
    mu = 0.3
    t_stop = V0 / (mu * G)
    sol = run(dropped(mu, e, rest, 1.5 * t_stop), "imm")
    segs = sol.source.run.segments
    first = next(s for s in segs if s.phase.name == "resting")
    assert all(s.phase.name == "resting" for s in segs if s.t0 >= first.t0)  # it rests to the end
    end = slips_end(sol)
    y = states(sol, np.linspace(first.t0, end, 401))
    rel = 2.0 * float(np.max(np.abs(y[:, 2]))) * (1.0 / mu + mu) + RTOL
    v_s = resting_slide(mu, e, rest)
    assert first.y0[3] == pytest.approx(v_s, rel=RTOL)
    T, d = v_s / (mu * G), v_s**2 / (2.0 * mu * G)
    assert abs((end - first.t0) - T) <= rel * T, (end - first.t0, T)
    assert abs((y[-1, 0] - y[0, 0]) - d) <= rel * d, (y[-1, 0] - y[0, 0], d)
    assert abs(end - t_stop) <= rel * t_stop, (end, t_stop)
    assert sum(c.tangential_impulse for c in sol.contacts) == pytest.approx(MASS * V0, rel=RTOL)
    t, state = sol.time, sol["pair_friction_state"]
    slipping = (t > first.t0) & (t < end)
    assert np.all(state[slipping] == 1.0) and np.all(state[t > end] == 2.0)
    Fn, Ft = sol["pair_contact_force"][slipping], sol["pair_tangential_force"][slipping]
    np.testing.assert_array_equal(Ft, mu * Fn)  # kinetic friction against v_t < 0 (t = (-1, 0), v_x > 0)
    assert max(p - a for p, a, _ in friction_power(sol, sol.source.system)) <= 0.0


def test_a_bar_resting_on_an_incline_below_the_friction_angle_stays_put():
    """tan(alpha) = 0.1 < mu_s = 0.3: resting from the start, sticking throughout, its contact points creep less than
    1e-9 m over 1 s (Simpson's rule on the slip velocity sampled on the dense output); friction power <= 0."""
    case = bar_on_stops(0.2, 0.0, 1.0, alpha=math.atan(0.1), mu_s=0.3)
    sol = run(case, "imm")
    assert {s.phase.name for s in sol.source.run.segments if s.t1 > 0.0} == {"resting"}
    system = BeamSystem.from_case(case)
    assert max(abs(c) for c in creep(sol, system, 0.0, 1.0)) < 1e-9
    assert np.all(sol["pair_friction_state"] == 2.0)
    assert max(p - a for p, a, _ in friction_power(sol, system)) <= 0.0


def test_a_bar_resting_on_an_incline_above_the_friction_angle_accelerates_at_the_closed_form():
    """tan(alpha) = 0.5 > mu_s = 0.3 > mu_k = 0.2: its stick ends at once and it slides down at
    g (sin(alpha) - mu_k cos(alpha)): velocity and distance after 0.05 s within fast_rtol; friction power <= 0."""
    alpha, mu = math.atan(0.5), 0.2
    sol = run(bar_on_stops(mu, 0.0, 0.05, alpha=alpha, mu_s=0.3), "imm")
    acc = G * (math.sin(alpha) - mu * math.cos(alpha))
    y0, y1 = sol.source.run.segments[0].y0, sol.source.run.segments[-1].y1
    ca, sa = math.cos(alpha), math.sin(alpha)
    assert -(y1[3] * ca + y1[4] * sa) == pytest.approx(acc * 0.05, rel=RTOL)
    assert -((y1[0] - y0[0]) * ca + (y1[1] - y0[1]) * sa) == pytest.approx(0.5 * acc * 0.05**2, rel=RTOL)
    assert sol.source.run.segments[-1].phase.name == "resting"
    assert max(p - a for p, a, _ in friction_power(sol, sol.source.system)) <= 0.0


def phase_ends(sol) -> tuple[np.ndarray, np.ndarray]:
    """The run's phase end times and states."""
    segs = sol.source.run.segments
    return np.array([s.t1 for s in segs]), np.array([s.y1 for s in segs])


@pytest.mark.parametrize(
    "case",
    [dropped(0.3, 0.0, 0.0, 0.08), bar_on_stops(0.2, 0.0, 0.05, alpha=math.atan(0.5), mu_s=0.3)],
    ids=["dropped", "incline"],
)
def test_ccm_and_imms_resting_phase_agree(case):
    """The same case under CCM and IMM: the phases end at the same times in the same states, within SAME (module
    docstring), with the same friction rows; their tangential impulses agree too."""
    ccm, imm = run(case, "ccm"), run(case, "imm")
    (ta, ya), (tb, yb) = phase_ends(ccm), phase_ends(imm)
    assert ta.shape == tb.shape
    np.testing.assert_allclose(tb, ta, rtol=0.0, atol=SAME)
    np.testing.assert_allclose(yb, ya, rtol=0.0, atol=SAME)
    rows = [[None if s.phase.friction is None else s.phase.friction.tolist() for s in r.source.run.segments]
            for r in (ccm, imm)]  # fmt: skip
    assert rows[0] == rows[1]
    np.testing.assert_allclose([c.tangential_impulse for c in imm.contacts],
                               [c.tangential_impulse for c in ccm.contacts], rtol=0.0, atol=SAME)  # fmt: skip


def test_painleve_in_imms_resting_contact_is_resolved_by_a_tangential_impact():
    """``test_friction_ccm.py``'s rod set down at 60 degrees (a < 0 for mu = 1.5), its end sliding away at 1 m/s: it
    rests at once (e = 0), its slip has a < 0: a warning naming Painlevé at t = 0, a tangential impact that does not
    add kinetic energy, a finished run without NaN; and the rod reaching a = 0 while sliding (48 degrees, 20 m/s,
    5 rad/s) gets its warning where CCM's does (the same time within SAME)."""
    hits = {}
    for method in ("imm", "ccm"):
        for angle, u, w in ((60.0, 1.0, 0.0), (48.0, 20.0, 5.0)):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                sol = run(painleve_rod(angle, 1.5, u, w), method)
            found = [str(c.message) for c in caught if issubclass(c.category, FlexbeamWarning) and "Painlevé" in
                     str(c.message)]  # fmt: skip
            assert len(found) == 1, found
            hits[method, angle] = float(found[0].split("t = ")[1].split(" s")[0])
            if angle == 60.0 and method == "imm":
                T0, T1 = kinetic_jump(sol, 0.0)
                assert T1 <= T0 * (1.0 + 1e-14)
    assert hits["imm", 60.0] == 0.0
    assert hits["imm", 48.0] == pytest.approx(hits["ccm", 48.0], abs=SAME)


def test_imms_resting_friction_on_the_reference_integrator_stops_the_run_in_one_line():
    """The reference integrator does not locate friction's events: the run stops where a frictional pair comes to rest,
    its message one line starting with the field (IMM's frictional impacts alone still run there)."""
    case = fb.load_case(bar_on_stops(0.3, 0.1, 0.01).model_dump(), {"solver.integrator": "reference"})
    sol = fb.simulate(case, "imm")
    assert sol.status == "failed"
    assert sol.message.startswith("contact.friction: pair 0 comes to rest at t = 0 s") and "\n" not in sol.message
    impact = fb.load_case(rough_bar(30.0, 0.3, 0.5).model_dump(), {"solver.integrator": "reference"})
    sol = fb.simulate(impact, "imm")  # the bar bounces off: no rest, no stop
    assert sol.status == "success" and abs(sol.contacts[0].tangential_impulse) > 0.0
