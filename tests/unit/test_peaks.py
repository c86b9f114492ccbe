"""Local maxima of a sampled force history (the peak finder behind the metrics)."""

from __future__ import annotations

import numpy as np

from flexbeam.results.peaks import interior_maxima


def test_two_hertz_like_peaks_are_found_at_fine_sampling():
    """Two smooth pulses sampled every 2e-7 s (the contact output step): both maxima found."""

    def force(t):
        return 900.0 * np.sin(np.pi * t / 6e-4) ** 1.5 + 300.0 * np.exp(-(((t - 4.5e-4) / 3e-5) ** 2))

    t = np.arange(0.0, 6e-4, 2e-7)
    idx = interior_maxima(force(t))
    assert len(idx) == 2
    fine = np.linspace(4e-4, 5e-4, 1_000_001)  # the second maximum on a 1e-10 s grid
    assert abs(t[idx[0]] - 3e-4) <= 2e-7
    assert abs(t[idx[1]] - fine[np.argmax(force(fine))]) <= 2e-7


def test_round_off_ripple_of_a_resting_force_is_no_peak():
    """A static reaction with relative ripple 1e-13 (what an integrator leaves) has no maxima."""
    rng = np.random.default_rng(1)
    f = 7.5088644 * (1.0 + 1e-13 * rng.standard_normal(50_000))
    assert interior_maxima(f) == []
