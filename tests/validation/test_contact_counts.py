"""What one contact is, on runs: an IMM Zeno sequence of a rigid rod, whose counts follow from the restitution
coefficient in closed form, and the identities the seed case's counts satisfy on any machine."""

from __future__ import annotations

import math

import pytest

import flexbeam as fb
from flexbeam.results.counts import MICRO_IMPACT_FRACTION
from tests.conftest import seed

V0 = 0.4  # the seed case's approach speed of P [m/s]


@pytest.mark.parametrize(("e", "rest"), [(0.8, 1e-6), (0.8, 1e-4), (0.5, 1e-6)])
def test_rigid_rod_zeno_sequence_counts_follow_from_the_restitution(e, rest):
    """A rigid rod (``model.modes = 0``) lands on its stop at v0 under gravity (IMM).  Its free flight conserves
    energy with one degree of freedom, so P comes back at the speed it left: the k-th impact approaches at
    e^k v0 (Newton's restitution), with the impulse m_eff (1 + e) e^k v0.  Records: impacts k = 0, 1, ... until
    the first whose rebound e^(k+1) v0 falls below ``solver.rest_velocity``, which comes to rest instead (IMM):
    floor(ln(rest / v0) / ln e) + 1 records, the last a resting contact that lasts to t_end.  Contacts: the
    impacts with e^k >= 1 % (floor(ln 0.01 / ln e) + 1 of them, whatever the rest velocity) and the resting
    contact, whose impulse (the reaction m g x_G / x_P = 7.5 N over > 0.1 s) exceeds the first impact's; the
    impacts between are one chatter episode.  The nearest power e^k to the 1 % threshold is 7.8 % from it (e = 0.8,
    k = 21), the nearest e^(k+1) to rest / v0 3.9 % (e = 0.8, rest 1e-4, k + 1 = 37): far beyond the error of the
    speeds (measured: successive speeds in the ratio e to 5e-8, so at most 3e-6 after 58 impacts)."""
    case = seed(model__modes=0, contact__restitution=e, solver__rest_velocity=rest, solver__t_end=0.5)
    sol = fb.simulate(case, method="imm")
    assert sol.status == "success"
    m = sol.metrics()
    records = math.floor(math.log(rest / V0) / math.log(e)) + 1
    impacts = math.floor(math.log(MICRO_IMPACT_FRACTION) / math.log(e)) + 1
    assert m["contact_records"] == records
    assert m["contacts"] == impacts + 1
    assert m["micro_impacts"] == records - impacts - 1
    assert m["chatter_episodes"] == 1
    kinds = [ev["kind"] for ev in m["events"]]
    assert kinds == ["contact"] * impacts + ["micro-impact"] * (records - impacts - 1) + ["contact"]
    resting = sol.contacts[-1]
    assert math.isnan(resting.end) and resting.impulse > sol.contacts[0].impulse
    # counted by its speed alone: an impact weaker than 1 % of the resting contact's impulse (impulse only would
    # have made it a micro-impact)
    assert any(
        ev["kind"] == "contact" and ev["impulse"] < MICRO_IMPACT_FRACTION * resting.impulse for ev in m["events"]
    )


def test_seed_imm_counts_add_up():
    """The seed case under IMM ends its first 0.1 s in a Zeno sequence and a resting contact on this machine
    (78 records; another BLAS kernel gives a different trajectory at the integrator-tolerance level, so no count
    is pinned): whatever the records, every one is a contact or a micro-impact, and the JSON agrees with itself."""
    m = fb.simulate("seed-experiment", method="imm").metrics()
    assert m["contacts"] + m["micro_impacts"] == m["contact_records"] == len(m["events"])
    assert m["contacts"] == sum(ev["kind"] == "contact" for ev in m["events"])
    assert m["chatter_episodes"] == len({ev["chatter_episode"] for ev in m["events"]} - {None})
    (pair,) = m["pairs"]
    for key in ("contacts", "contact_records", "micro_impacts", "chatter_episodes"):
        assert pair[key] == m[key]


@pytest.mark.parametrize(("method", "friction"), [("imm", 0.0), ("ccm", 0.3)])
def test_a_beam_settling_on_a_stop_chatters_under_imm_and_ccm_and_the_stop_says_what_carries_it_on(method, friction):
    """tip-wall to 0.3 s with the guard at 200 contacts: as the beam settles on the wall, IMM's impulses (the struck
    point thrown back by the modes they excite) and CCM's held contact with friction (released by the undamped modes'
    ringing) pile up contacts -- the 200th comes at 0.19 s and 0.17 s (measured), over a tenth of a second before
    t_end -- and the run stops with a message naming CCFM and solver.max_contacts.  CCFM, whose law damps the
    contact, carries the same case to t_end with 65-69 contacts (a third of the guard)."""
    rough = {"contact.friction": friction} if friction else {}
    case = fb.load_case("tip-wall", {"solver.t_end": 0.3, "solver.max_contacts": 200, **rough})
    sol = fb.simulate(case, method)
    assert sol.status == "max-contacts"
    assert "CCFM carries a lasting contact" in sol.message and "raise solver.max_contacts" in sol.message
    assert fb.simulate(case, "ccfm").status == "success"


def test_a_rods_impact_under_imm_chatters_within_the_waves_transit_and_the_stop_names_the_rod():
    """rod-end (a steel rod falling on its end, axial modes): IMM's impulse at the struck end throws it back at once
    through the axial modes, so the impacts accumulate within the first wave's transit (the axial wave crosses the
    rod's length and back in 2 L / c; any pile-up of 50 records must come before it: CCFM's contact lasts about that
    long), and the run stops with a message that names this case -- a rod's impact, not a beam settling on a stop --
    and the ways on (CCFM, solver.max_contacts)."""
    case = fb.load_case("rod-end", {"solver.max_contacts": 50})
    sol = fb.simulate(case, "imm")
    assert sol.status == "max-contacts"
    assert "a rod's impact borne by its waves" in sol.message
    assert "CCFM carries a lasting contact" in sol.message and "raise solver.max_contacts" in sol.message
    c = math.sqrt(case.beam.youngs_modulus / case.beam.density)
    assert sol.time[-1] < 2 * case.beam.length / c
