"""Friction at many simultaneous impacts (issue 28): the search of ``flexbeam.methods.frictional_search``, which stops
at the first consistent mode pattern when the solution is certified unique (lambda_min(W) > norm(diag(mu) W_t)_2,
mu_s = mu_k), against the enumeration of all 4^s patterns and against an independent LCP solution.

* **Random positive-definite W** (Hypothesis, s = 4..6 pairs, mu drawn inside the certificate): the search's impulses
  equal the enumeration's (to the bound derived in the test), satisfy the law and gain no energy.
* **The uniqueness certificate** is not vacuous: for W = I (no coupling) every mu < 1 is certified, mu >= 1 not; a
  singular W or mu_s > mu_k is never certified.
* **A flexible bar landing flat on 8 stops** (16 modes, W positive definite, mu = 0.1, certified): solved, the law
  holds with no energy gain, and the impulses equal those of Stewart & Trinkle's LCP solved independently
  (test_friction_simultaneous.stewart_trinkle: scipy's MILP), sliding and nearly sticking.  No timing is asserted;
  benchmarks/frictional_impacts.py measures the cost (docs/performance.md).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from flexbeam.methods import frictional_lcp
from flexbeam.methods.frictional_lcp import solve_frictional_impact
from flexbeam.methods.frictional_search import certified_unique
from flexbeam.validation.bars import bar_on_stops, evenly_beneath, start_delassus

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_simultaneous import assert_the_law_and_no_gain, stewart_trinkle  # noqa: E402


def _gap(W: np.ndarray, mu: np.ndarray) -> float:
    """lambda_min(W) - norm(diag(mu) W_t)_2: the certificate's margin."""
    s = mu.size
    return float(np.linalg.eigvalsh(W)[0] - np.linalg.norm(mu[:, None] * W[s:, :], 2))


@st.composite
def certified_problems(draw):
    """(M, J, zd, e, mu): s = 4..6 pairs, n = 2 s + 1..3 coordinates with masses in [0.1, 10], J's rows random in
    [-1, 1] or the identity's plus up to half of that, mu_i = f_i c lambda_min(W) / norm(W_t)_2 with f_i in [0, 1]
    and c in [0, 0.95] (certified unique)."""
    s = draw(st.integers(4, 6))
    n = 2 * s + draw(st.integers(1, 3))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    M = np.diag(rng.uniform(0.1, 10.0, n))
    J = rng.uniform(-1.0, 1.0, (2 * s, n))
    if draw(st.booleans()):  # nearly uncoupled rows: a larger lambda_min, mu up to ~1, sticks and slips both met
        J = np.eye(2 * s, n) + draw(st.floats(0.0, 0.5)) * J
    W = J @ np.diag(1.0 / np.diag(M)) @ J.T
    scale = np.linalg.eigvalsh(W)[0] / np.linalg.norm(W[s:, :], 2)
    f = rng.uniform(0.0, 1.0, s) if draw(st.booleans()) else np.ones(s)
    mu = f * draw(st.floats(0.0, 0.95)) * scale
    e = draw(st.sampled_from([0.0, 0.5, 1.0])) if draw(st.booleans()) else draw(st.floats(0.0, 1.0))
    return M, J, rng.uniform(-1.0, 1.0, n), e, mu


@settings(max_examples=40, deadline=None)
@given(certified_problems())
def test_search_equals_the_enumeration(problem):
    """The search (s > 3, certified) and the enumeration (``ENUMERATED_PAIRS`` raised to s) return the same impulses:
    both accept patterns whose xi residual is at most tol_v = 1e-10 max|q| per row; two such solutions d apart obey
    gap norm(d)^2 <= (the module's derivation with residuals) 2 tol_v (1 + max mu) sqrt(2 s) norm(d), so
    norm(d) <= 2 (1 + max mu) sqrt(2 s) tol_v / gap; asserted with a 10x margin (measured: 0, the same pattern).
    Both satisfy the law and gain no energy (test_friction_simultaneous's bounds)."""
    M, J, zd, e, mu = problem
    s = mu.size
    W, v_minus = J @ np.diag(1.0 / np.diag(M)) @ J.T, J @ zd
    assert certified_unique(W, mu, mu)
    P = solve_frictional_impact(W, v_minus, np.full(s, e), mu, mu)
    assert_the_law_and_no_gain(M, J, zd, e, mu, P)
    saved, frictional_lcp.ENUMERATED_PAIRS = frictional_lcp.ENUMERATED_PAIRS, s
    try:
        P_all = solve_frictional_impact(W, v_minus, np.full(s, e), mu, mu)
    finally:
        frictional_lcp.ENUMERATED_PAIRS = saved
    tol_v = 1e-10 * np.max(np.abs((1.0 + e) * v_minus))
    bound = 10.0 * 2.0 * (1.0 + np.max(mu)) * np.sqrt(2 * s) * tol_v / _gap(W, mu)
    assert np.linalg.norm(P - P_all) <= bound


def test_the_certificate():
    """W = I (4 uncoupled pairs): norm(diag(mu) W_t)_2 = max mu, so mu = 0.99 is certified and 1.01 is not; a singular
    W (rank 7 of 8) and mu_s > mu_k are never certified."""
    W = np.eye(8)
    assert certified_unique(W, np.full(4, 0.99), np.full(4, 0.99))
    assert not certified_unique(W, np.full(4, 1.01), np.full(4, 1.01))
    assert not certified_unique(W, np.full(4, 0.3), np.full(4, 0.2))
    J = np.random.default_rng(0).uniform(-1.0, 1.0, (8, 7))
    assert not certified_unique(J @ J.T, np.full(4, 0.01), np.full(4, 0.01))


@pytest.mark.parametrize("vx", [0.5, 0.01])
def test_bar_flat_on_eight_stops(vx):
    """The steel bar (16 modes) landing flat on 8 stops at (vx, -1 m/s), mu = 0.1, e = 0.5 (benchmarks/
    frictional_impacts.py's case): certified, solved by the search, the law holds with no energy gain (in coordinates
    where M = I: z~ = L^T z', J~ = J L^-T with M = L L^T), and the impulses equal Stewart & Trinkle's LCP solution to
    1e-8 of the largest (the MILP's active set is exact; the rest is round-off and the 1e-10 acceptance)."""
    case = bar_on_stops(evenly_beneath(8), (vx, -1.0), modes=16, mu=0.1)
    W, v_minus = start_delassus(case)
    mu, e = np.full(8, 0.1), 0.5
    assert certified_unique(W, mu, mu)
    P = solve_frictional_impact(W, v_minus, np.full(8, e), mu, mu)
    assert P is not None and np.all(P[:8] > 0.0)
    expected = stewart_trinkle(W, (1.0 + e) * v_minus, mu)
    assert np.max(np.abs(P - expected)) <= 1e-8 * np.max(np.abs(expected))
    # the law and the energy, in coordinates where M = I: W = J~ J~^T (a Cholesky factor of W stands for J~)
    Jt = np.linalg.cholesky(W)
    zd = np.linalg.solve(Jt, v_minus)
    assert_the_law_and_no_gain(np.eye(16), Jt, zd, e, mu, P)
