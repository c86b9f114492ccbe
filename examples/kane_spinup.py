"""
Kane's spin-up: dynamic stiffening
==================================

Kane, Ryan & Banerjee (1987): a 10 m cantilever on a hub whose angle is prescribed,
spun up in T_s = 15 s to W = 6 rad/s,

    theta = (W/T_s) [t^2/2 + (T_s/2 pi)^2 (cos(2 pi t/T_s) - 1)]   (t < T_s), then rate W

(preset ``kane-spinup``).  W is above the beam's first bending frequency
omega_1 = 3.80 rad/s, which separates the two coupling models:

* the **first-order** model stiffens with spin and its tip follows the quasi-static
  deflection under the hub's angular acceleration, returning to a small vibration
  once the spin is constant;
* the **zeroth-order** model softens as K - theta'^2 M, loses stability once theta'
  passes omega_1, and its tip deflection grows without bound.
"""

# %%
# Simulate both models
# --------------------
# Three modes are enough for the tip; the 20 s run takes a few milliseconds.
import numpy as np

import flexbeam as fb
from flexbeam.validation import quasi_static_tip

case = fb.load_case("kane-spinup", {"model.modes": 3})
first = fb.simulate(case)
zeroth = fb.simulate(fb.load_case(case, {"model.coupling": "zeroth-order"}))

W, Ts = case.drive.spin_rate, case.drive.spin_up_time


def hub_rates(t: float) -> tuple[float, float]:
    """theta'(t) and theta''(t) of the spin-up profile [rad/s, rad/s^2]."""
    if t >= Ts:
        return W, 0.0
    a = 2 * np.pi / Ts
    return (W / Ts) * (t - np.sin(a * t) / a), (W / Ts) * (1 - np.cos(a * t))


#: the quasi-static tip deflection during the spin-up (scipy's solve_bvp on the spinning beam)
t_quasi = np.linspace(0.0, Ts, 31)
tip_quasi = np.array(
    [
        quasi_static_tip(case.beam.line_density, case.beam.bending_stiffness, case.beam.length, *hub_rates(t))
        for t in t_quasi
    ]
)
tip_first = np.interp(t_quasi, first.time, first["tip_deflection"])

# %%
# The first-order tip stays within centimetres of the quasi-static curve; the
# zeroth-order one runs away.
if __name__ == "__main__":
    print(f"first-order:  min tip {first.metrics()['tip_deflection_min']:.4f} m (quasi-static {tip_quasi.min():.4f} m)")
    print(f"zeroth-order: largest |tip| {np.nanmax(np.abs(zeroth['tip_deflection'])):.3g} m")

# %%
# Plot
# ----
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    ax.plot(first.time, first["tip_deflection"], label="first-order")
    ax.plot(zeroth.time, zeroth["tip_deflection"], label="zeroth-order (diverges)")
    ax.plot(t_quasi, tip_quasi, "k--", lw=0.9, label="quasi-static (solve_bvp)")
    ax.set_ylim(-1.0, 0.5)
    ax.set(xlabel="Time [s]", ylabel="Tip deflection [m]", title="Kane spin-up to W = 6 rad/s, 3 modes")
    ax.legend(fontsize=8)
    plt.show()
