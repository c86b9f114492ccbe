"""
Calibration against a measured force history
=============================================

:func:`flexbeam.calibrate` fits case fields to measurements by least squares.  To see
that it recovers what it should, the "measurement" here is synthetic: the force history
of the seed case (a 2-mode beam, for speed) with a *known* contact stiffness
K = 2e9 N/m^1.5 and restitution e = 0.6, sampled at 1 MHz on a clock that starts at an
arbitrary time, with Gaussian noise of 1 % of the peak force.

The fit starts from the case's own values (the Hertz stiffness of the hemisphere,
4.43e9, and e = 0.8), aligns data and model on the first contact and fits K and e
together with the remaining time shift.  Its standard uncertainties come from the
Jacobian at the solution.
"""

# %%
# A synthetic measurement
# -----------------------
import numpy as np

import flexbeam as fb
from flexbeam.calibrate import Measured

TRUE = {"contact.stiffness": 2.0e9, "contact.restitution": 0.6}
NOISE = 0.01  # standard deviation of the noise, as a fraction of the peak force

case = fb.load_case("seed-experiment", {"model.modes": 2, "solver.t_end": 2e-3})
truth = fb.simulate(fb.load_case(case, TRUE))
t = np.arange(-1e-4, 1.2e-3, 1e-6)  # 1 MHz from 0.1 ms before the contact
force = np.interp(t, truth.time, truth["contact_force"], left=0.0)
rng = np.random.default_rng(1)
measured = Measured(time=t + 3.7e-4, force=force + rng.normal(0.0, NOISE * force.max(), t.size), source="synthetic")

# %%
# Fit
# ---
fit = fb.calibrate(case, fit=["contact.stiffness", "contact.restitution"], data=measured)
fitted = fit.fitted

# %%
# The fitted values with their standard uncertainties, against the truth.  In a
# notebook ``fit`` itself shows the tables and an overlay plot.
if __name__ == "__main__":
    for (key, value), u in zip(fitted.items(), fit.uncertainty):
        print(f"{key:22} {value:12.6g} +- {u:.2g}   (true {TRUE[key]:g})")
    print(f"residual sigma {fit.sigma:.4f} of the peak (noise put in: {NOISE})")

# %%
# Plot: data, the starting model and the fitted model
# ---------------------------------------------------
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    # the data on the fitted model's clock: its alignment instant plus the fitted time shift
    t_data = fit.aligned_time + fit.model_reference[1] + fit.time_shift - fit.solution.contacts[0].onset
    ax.plot(t_data * 1e3, measured.force[fit.data_mask], ".", ms=1.5, c="0.6", label="synthetic measurement")
    for sol, style, label in (
        (fit.initial_solution, "--", "start (K = 4.43e9, e = 0.8)"),
        (fit.solution, "-", "fitted"),
    ):
        t0 = sol.contacts[0].onset
        sel = (sol.time >= t0) & (sol.time <= t0 + 1e-3)
        ax.plot((sol.time[sel] - t0) * 1e3, sol["contact_force"][sel], style, label=label)
    ax.set(xlabel="Time after first contact [ms]", ylabel="Contact force [N]")
    ax.legend(fontsize=8)
    plt.show()
