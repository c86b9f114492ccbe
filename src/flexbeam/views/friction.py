"""The friction figure of a run with Coulomb friction (any method: :mod:`flexbeam.methods.coulomb`): each frictional
pair's tangential force against the friction cone mu_s F (upper panel) and its slip velocity (lower panel), the
stick intervals shaded."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..results.solution import Solution
from .plotting import pyplot, save_figure


def plot_friction(sol: Solution, path: str | Path, title: str = "") -> Path:
    """Tangential force F_t [N] with the bounds -+ mu_s F of each pair that had friction, and its slip velocity
    [m/s], against time [ms]; a ValueError naming ``contact.friction`` for a run without friction arrays."""
    if "pair_tangential_force" not in sol.arrays:
        raise ValueError("plot: the friction figure needs a run with contact.friction > 0 (any method)")
    plt = pyplot()
    fig, (top, low) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 5.6))
    t = sol.time * 1e3
    state = sol["pair_friction_state"]
    ft, vt = sol["pair_tangential_force"], sol["pair_slip_velocity"]
    force = sol["pair_contact_force"] if "pair_contact_force" in sol.arrays else sol["contact_force"][:, None]
    system = getattr(sol.source, "system", None)
    pairs = system.contact.pairs if system is not None else None
    for k in range(ft.shape[1]):
        if not np.any(state[:, k] > 0):
            continue
        mu_s = pairs[k].friction_static if pairs is not None else np.nan
        (line,) = top.plot(t, ft[:, k], label=f"pair {k}: F_t")
        top.plot(t, mu_s * force[:, k], c=line.get_color(), ls=":", lw=0.8, label=f"pair {k}: -+ mu_s F")
        top.plot(t, -mu_s * force[:, k], c=line.get_color(), ls=":", lw=0.8)
        low.plot(t, vt[:, k], c=line.get_color(), label=f"pair {k}")
        stick = state[:, k] == 2
        if stick.any():
            shade = {"color": line.get_color(), "alpha": 0.1, "transform": low.get_xaxis_transform()}
            low.fill_between(t, 0, 1, where=stick, **shade)
    top.set_ylabel("Tangential force [N]")
    low.set_ylabel("Slip velocity [m/s]")
    low.set_xlabel("Time [ms]")
    top.set_title(title or "Coulomb friction (stick shaded)")
    for ax in (top, low):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    return save_figure(fig, path)
