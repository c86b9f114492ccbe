"""Coulomb friction with mu_k = 0 < mu_s (issue 28): a pair that slips without friction still sticks where it stops.

**Slide up an incline.**  The rigid bar of ``test_friction_ccfm.py`` lies on two stops along a line inclined at alpha
(tan(alpha) = 0.1) and is given v0 = 0.05 m/s up the incline.  With mu_k = 0 nothing but gravity acts along the
incline while it slips: it decelerates at g sin(alpha), stops at T = v0 / (g sin(alpha)) after
d = v0^2 / (2 g sin(alpha)), and there -- tan(alpha) < mu_s = 0.3 -- static friction holds it: its contact points creep
less than 1e-9 m over the following second (the slip velocity integrated on the dense output, as in
``test_friction_ccfm.py``).  On the former build the slip of a pair with mu_k = 0 was never watched for its stop
(its row's sigma = -mu_k sign(v_t) = 0 carried no direction): the bar slid back down for ever.

Under **CCM** the held normals stay perpendicular to the incline, so T and d are exact up to the integrator's relative
tolerance ``solver.fast_rtol`` (asserted; measured 1.4e-12 relative).  Under **CCFM** the bar rings on its compliant
stops and turns off the incline by at most theta_max; the normals stay perpendicular to the bar's axis (the nearest
point of a straight bar, ``contact.anywhere``), so each has a component of at most theta_max along the incline and
the normal impulse m (g cos(alpha) t + v_n(t) - v_n(0)) (the momentum balance across the incline) adds at most
E(t) = theta_max (g cos(alpha) t + max |v_n - v_n(0)|) to the velocity along it: T is within E(T) / (g sin(alpha)) and
d within E(T) T of the closed forms (asserted with a factor 2; measured 2.9e-8 s against the bound's 1.1e-6 s).
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
from test_friction_ccfm import G, bar_on_stops, creep, friction_power, states  # noqa: E402

#: the exponential integrator's relative tolerance (solver.fast_rtol, default)
RTOL = 1e-6
ALPHA, V0, MU_S = math.atan(0.1), 0.05, 0.3


def test_zero_kinetic_friction_below_the_static_coefficient_is_valid_input():
    """mu_s >= mu_k >= 0 (issue 28) admits mu_k = 0 < mu_s."""
    case = bar_on_stops(0.0, V0, 0.1, alpha=ALPHA, mu_s=MU_S)
    assert case.contact.friction == 0.0 and case.contact.friction_static == MU_S


@pytest.mark.parametrize("method", ["ccm", "ccfm"])
def test_a_frictionless_slip_up_an_incline_stops_at_the_closed_form_and_sticks(method):
    """The module docstring's slide: the located stop at T, G's slide d along the incline (CCM within fast_rtol,
    CCFM within twice the tilt bound), every phase after it sticking, creep < 1e-9 m over the following second,
    friction power <= 0."""
    ca, sa = math.cos(ALPHA), math.sin(ALPHA)
    T0, d0 = V0 / (G * sa), V0**2 / (2.0 * G * sa)
    case = bar_on_stops(0.0, V0, T0 + 1.0, alpha=ALPHA, mu_s=MU_S)
    sol = fb.simulate(case, method)
    assert sol.status == "success", sol.message
    segs = sol.source.run.segments
    stuck = [s for s in segs if s.phase.friction is not None and (s.phase.friction[:, 1] > 0.0).all()]
    assert stuck, "it never sticks"
    stop = stuck[0].t0
    assert all(s in stuck for s in segs if s.t0 >= stop), "it does not stay stuck after its stop"
    t = np.linspace(0.0, stop, 4001)
    y = states(sol, t)
    d = (y[-1, 0] - y[0, 0]) * ca + (y[-1, 1] - y[0, 1]) * sa
    if method == "ccm":
        assert stop == pytest.approx(T0, rel=RTOL)
        assert d == pytest.approx(d0, rel=RTOL)
    else:
        v_n = -y[:, 3] * sa + y[:, 4] * ca
        E = float(np.max(np.abs(y[:, 2] - ALPHA))) * (G * ca * stop + float(np.max(np.abs(v_n - v_n[0]))))
        assert abs(stop - T0) <= 2.0 * E / (G * sa), (stop, T0, E)
        assert abs(d - d0) <= 2.0 * E * stop, (d, d0, E)
    system = BeamSystem.from_case(case)
    assert max(abs(c) for c in creep(sol, system, stop, T0 + 1.0)) < 1e-9
    assert np.all(sol["pair_friction_state"][sol.time > stop] == 2.0)
    assert max(p - a for p, a, _ in friction_power(sol, system)) <= 0.0
