"""
Bending frequencies of a rotating beam
======================================

The chordwise (in-plane) bending frequencies of Kane's 10 m cantilever, linearised
about steady spin Omega, for the two coupling models
(:func:`flexbeam.model.frequencies.case_frequencies`):

* the **first-order** model keeps the coupling deformation u_x = -1/2 q^T H q; its
  centrifugal geometric stiffness D stiffens the beam as it spins,
  omega^2 = eig(K + Omega^2 (D - M), M);
* the **zeroth-order** model drops it and softens, omega^2 = eig(K - Omega^2 M, M):
  omega_1^2 = omega_1(0)^2 - Omega^2, which vanishes -- the beam buckles -- when the
  spin reaches the first bending frequency omega_1(0) = 1.8751^2 sqrt(EI / (mu L^4)).

A negative entry is the negative square root of ``|omega^2|``: an unstable mode.
"""

# %%
# Frequencies over spin
# ---------------------
import numpy as np
from scipy.optimize import brentq

import flexbeam as fb
from flexbeam.model.frequencies import case_frequencies

case = fb.load_case("kane-spinup", {"model.modes": 6})
spins = np.linspace(0.0, 10.0, 51)  # rad/s
curves = [case_frequencies(case, spin) for spin in spins]
first_order = np.array([c["first-order"][:3] for c in curves])  # rad/s, modes 1-3
zeroth_order = np.array([c["zeroth-order"][:3] for c in curves])

#: the spin at which the zeroth-order model's first frequency vanishes [rad/s]
buckling_spin = brentq(lambda s: case_frequencies(case, s)["zeroth-order"][0], 1.0, 8.0, xtol=1e-12)

# %%
# The non-rotating frequencies are the cantilever's, and the zeroth-order beam buckles
# exactly at the first of them.
if __name__ == "__main__":
    print("non-rotating frequencies [rad/s]:", np.round(first_order[0], 4))
    print(f"zeroth-order first frequency vanishes at Omega = {buckling_spin:.6f} rad/s")

# %%
# Plot
# ----
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5), layout="constrained")
    for k in range(3):
        ax.plot(spins, first_order[:, k], c=f"C{k}", label=f"mode {k + 1}, first-order")
        ax.plot(spins, zeroth_order[:, k], c=f"C{k}", ls="--", label=f"mode {k + 1}, zeroth-order")
    ax.axvline(buckling_spin, c="0.5", lw=0.8, ls=":")
    ax.axhline(0.0, c="0.5", lw=0.5)
    ax.set(
        xlabel="Spin rate Omega [rad/s]",
        ylabel="Chordwise frequency [rad/s]",
        title="Kane beam (L = 10 m), 6 modes; negative = unstable",
    )
    ax.legend(fontsize=7, ncol=2)
    plt.show()
