"""Whether a stick holds is decided at the slip's stop (:mod:`flexbeam.methods.stick_start`), against closed forms.

**A bar sliding up an incline steeper than the friction angle.**  The rigid bar of ``test_friction_ccfm.py`` lies on two
stops along a line inclined at alpha, tan(alpha) = 0.5 > mu_s = 0.3 (mu_k = 0.2), and slides up it at v0.  Both
contacts slip uphill; with the friction -mu_k (F_1 + F_2) downhill, G's momentum balances along the incline (u, up)
and across it (n) read

    m (v_u(t) - v0) = -m g t sin(alpha) - mu_k int_0^t (F_1 + F_2) dt,   m (v_n(t) - v_n(0)) = int_0^t (F_1 + F_2) dt
                                                                                                - m g t cos(alpha),

so v_u(t) = v0 - g t (sin(alpha) + mu_k cos(alpha)) - mu_k (v_n(t) - v_n(0)) and the slip stops at

    T = (v0 - mu_k (v_n(T) - v_n(0))) / (g (sin(alpha) + mu_k cos(alpha)))

(v0 / (g (sin(alpha) + mu_k cos(alpha))) once the bar has settled on the stops).  There the stick would need
lambda_t = -m g sin(alpha) against the static limit mu_s m g cos(alpha): it cannot hold, and the bar slides back down
at once, the friction now uphill: v_u(t) = -g (t - T) (sin(alpha) - mu_k cos(alpha)) + mu_k (v_n(t) - v_n(T)).  The run
must not enter a stick there at all -- no stick phase of zero length at the stop (the kernel's unstick event would
end it before its first step) -- and both closed forms hold to within the normals' tilt, 2 theta_max (1/mu_k + mu_k)
relative (theta_max: the bar's turn off the incline; the bound of ``test_friction_ccfm.py``).

**... and below it.**  tan(alpha) = 0.1 < mu_s: the bar slides up, stops at the same closed-form T, and sticks there:
every phase after the stop sticks, and the contact points creep less than 1e-9 m (the kernel's stick holds the slip
velocity to ~3e-11 m/s: 1e-9 m leaves a margin of 10 over the 0.1 s checked).

**The multiplier the decision uses is the kernel's.**  At the start of each stick phase of these runs the kernel's
collocated multiplier, its nodal interpolant extrapolated to the phase's start, agrees with the one the decision
evaluates (:meth:`~flexbeam.model.system.BeamSystem.contact_forces`) to within 1e-3 of max(abs(lambda_t), mu_s F): the
interpolant's own error (measured 9e-6 here; up to 3.8e-4 on the ringing tip of ``tip-wall`` at a first step of
1e-6 s, 5e-5 on the free bar's drop: the benchmark cases of ``benchmarks/friction.py``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import flexbeam as fb
from flexbeam.model.system import BeamSystem

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_ccfm import G, bar_on_stops, creep, states  # noqa: E402

MU_K, MU_S, V0 = 0.2, 0.3, 0.1
#: the Gauss nodes of the collocation (4 points) on (0, 1)
NODES = np.array([0.5 - math.sqrt(525 + 70 * math.sqrt(30)) / 70, 0.5 - math.sqrt(525 - 70 * math.sqrt(30)) / 70])
NODES = np.concatenate((NODES, 1.0 - NODES[::-1]))


def stop_time(alpha: float) -> float:
    """v0 / (g (sin(alpha) + mu_k cos(alpha))): the settled bar's stop on the incline."""
    return V0 / (G * (math.sin(alpha) + MU_K * math.cos(alpha)))


def uphill(y: np.ndarray, alpha: float) -> tuple[np.ndarray, np.ndarray]:
    """(v_u, v_n): G's velocity along the incline (up) and across it, of states ``y`` (rows)."""
    ca, sa = math.cos(alpha), math.sin(alpha)
    return y[:, 3] * ca + y[:, 4] * sa, -y[:, 3] * sa + y[:, 4] * ca


def run(alpha: float, t_end: float):
    case = bar_on_stops(MU_K, V0, t_end, alpha=alpha, mu_s=MU_S)
    sol = fb.simulate(case, "ccfm")
    assert sol.status == "success", sol.message
    return case, sol


def slip_stop(sol) -> tuple[float, float]:
    """(the end of the slip uphill, its direction sign(v_t)): the end of the last phase in which a pair slips the
    way it started."""
    segs = sol.source.run.segments
    up = segs[0].phase.friction[0, 4]
    return [s for s in segs if (s.phase.friction[:, 4] == up).any()][-1].t1, up


def stop_bound(sol, alpha: float, T: float) -> tuple[float, float, float]:
    """(the closed-form stop (v0 - mu_k (v_n(T) - v_n(0))) / (g (sin + mu_k cos)), its tilt bound, theta_max) of the
    run up to T."""
    t = np.linspace(0.0, T, 2001)
    y = states(sol, t)
    _, vn = uphill(y, alpha)
    theta_max = float(np.max(np.abs(y[:, 2] - alpha)))
    closed = (V0 - MU_K * (vn[-1] - vn[0])) / (G * (math.sin(alpha) + MU_K * math.cos(alpha)))
    return closed, 2.0 * theta_max * (1.0 / MU_K + MU_K) * closed, theta_max


def test_a_bar_sliding_up_a_steep_incline_stops_and_slides_back_without_a_stick():
    alpha = math.atan(0.5)
    t_end = 2.0 * stop_time(alpha)
    _, sol = run(alpha, t_end)
    T, up = slip_stop(sol)
    closed, bound, theta_max = stop_bound(sol, alpha, T)
    assert abs(T - closed) <= bound, (T, closed, bound)
    segs = sol.source.run.segments
    assert not [s for s in segs if s.phase.friction is not None and (s.phase.friction[:, 1] > 0.0).any()
                and s.t0 >= T - 1e-12], "a stick was entered at the stop"  # fmt: skip
    after = [s for s in segs if s.t0 >= T]
    assert after and all((s.phase.friction[:, 4] == -up).all() for s in after)  # both slide downhill from T on
    t = np.linspace(T, sol.source.run.t_final, 2001)
    vu, vn = uphill(states(sol, t), alpha)
    down = -G * (t[-1] - T) * (math.sin(alpha) - MU_K * math.cos(alpha)) + MU_K * (vn[-1] - vn[0])
    tilt = 2.0 * float(max(theta_max, np.max(np.abs(states(sol, t)[:, 2] - alpha)))) * (1.0 / MU_K + MU_K)
    assert abs(vu[-1] - down) <= tilt * abs(down), (vu[-1], down, tilt)


def test_a_bar_sliding_up_a_gentle_incline_stops_and_sticks():
    alpha = math.atan(0.1)
    case, sol = run(alpha, stop_time(alpha) + 0.12)  # the creep is checked over the 0.1 s after the stop
    T, _ = slip_stop(sol)
    closed, bound, _ = stop_bound(sol, alpha, T)
    assert abs(T - closed) <= bound, (T, closed, bound)
    after = [s for s in sol.source.run.segments if s.t0 >= T]
    assert after and all((s.phase.friction[:, 1] > 0.0).all() for s in after)  # stuck (a holder and its follower)
    assert max(abs(c) for c in creep(sol, BeamSystem.from_case(case), T, T + 0.1)) < 1e-9


@pytest.mark.parametrize("alpha", [math.atan(0.1), math.atan(0.25)])
def test_the_stick_multiplier_at_a_phase_start_is_the_kernels(alpha):
    """The kernel's first-step multiplier of each stick phase, extrapolated to its start, against
    BeamSystem.contact_forces there (module docstring)."""
    case, sol = run(alpha, stop_time(alpha) + 0.02)
    system = BeamSystem.from_case(case)
    S, checked = system.pairs, 0
    lag = np.array([np.prod([(0.0 - NODES[m]) / (NODES[j] - NODES[m]) for m in range(4) if m != j]) for j in range(4)])
    for seg in sol.source.run.segments:
        fr = seg.phase.friction
        if fr is None or seg.dense is None or not (fr[:, 1] == 1.0).any():
            continue
        N, rec = seg.dense.stepper.basis.N, seg.dense.records[0]
        F, Ft = system.contact_forces(seg.t0, seg.y0, seg.phase.buffer)
        for k in np.flatnonzero(fr[:, 1] == 1.0):
            lam = float(lag @ rec[4 + 6 * N + 4 * S + 8 + 4 * k : 4 + 6 * N + 4 * S + 12 + 4 * k])
            Fs = F[k] + sum(F[j] for j in range(S) if fr[j, 1] == 2.0 + k)
            assert abs(lam - Ft[k]) <= 1e-3 * max(abs(Ft[k]), MU_S * Fs), (seg.t0, lam, Ft[k], Fs)
            checked += 1
    assert checked
