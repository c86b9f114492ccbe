"""
Apparent restitution of a dropped bar against its inclination
=============================================================

A free steel bar (``joint.kind = "free"``, the case file ``tests/validation/data/free-bar-drop.toml``: 20 cm long,
12.7 mm across, hemispherical end caps, an *elastic* Hertz contact) falls at 1.4 m/s onto a rigid floor, its axis at
the angle theta to the floor.  A rigid bar with an elastic contact rebounds with restitution 1 at every angle, and
its spin after the impact is the closed form (Stronge, Impact Mechanics, 2000, sec. 4.2)

    P = 2 m v0 / (1 + 3 cos^2 theta),   omega+ = -6 P cos theta / (m L).

The flexible bar (eight free-free modes) rings: its bending vibration takes part of the rigid-body energy, and brings
the struck end back to the floor for more contacts within one collision episode, as Stoianovici & Hurmuzlu
(J. Appl. Mech. 63 (1996) 307) observed.  Its apparent coefficient of restitution -- of the rigid-body motion,
Newton's, Poisson's and Stronge's (docs/free-beam.md, *Collision episodes*) -- then changes with the angle.

The angles run as one :func:`flexbeam.sweep` over ``initial.impact_angle`` on an in-process Dask cluster, the
flexible bar and its rigid model (``model.modes = 0``) each; a few seconds in all.
"""

# %%
# Run the sweeps
# --------------
from pathlib import Path

import numpy as np
from dask.distributed import Client

import flexbeam as fb

# the case file of the test suite (sphinx-gallery runs the examples in examples/ and sets no __file__)
HERE = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
CASE = HERE.parent / "tests" / "validation" / "data" / "free-bar-drop.toml"
ANGLES = np.radians(np.arange(5.0, 86.0, 2.5))
#: the first episode ends within 0.6 ms at every angle; 4 ms of flight after it keep the runs short
SHORT = {"solver.t_end": 0.004}

CLUSTER = {"processes": False, "n_workers": 1, "threads_per_worker": 1, "dashboard_address": None}
with Client(**CLUSTER, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"}) as client:
    grid = {"initial.impact_angle": [float(a) for a in ANGLES]}
    flexible = fb.sweep(str(CASE), grid=grid, overrides=SHORT, scheduler=client)
    rigid = fb.sweep(str(CASE), grid=grid, overrides={**SHORT, "model.modes": 0}, scheduler=client)

# %%
# The rigid bar's closed form: an elastic contact restitutes e = 1 at every angle, and the impulse and spin are
# those above (checked here on the rigid model's runs, which CCFM integrates through the Hertz contact).
case = fb.load_case(CASE)
m, L, v0 = case.beam.mass, case.beam.length, abs(case.initial.impact_velocity)
P = 2.0 * m * v0 / (1.0 + 3.0 * np.cos(ANGLES) ** 2)
degrees = np.degrees(ANGLES)
rigid_error = float(np.max(np.abs(rigid["restitution_newton"].values - 1.0)))
impulse_error = float(np.max(np.abs(rigid["impulse"].values / P - 1.0)))

if __name__ == "__main__":
    print(f"rigid model: |e_N - 1| <= {rigid_error:.1e}, impulse against the closed form <= {impulse_error:.1e}")
    for name in ("restitution_newton", "restitution_poisson", "restitution_energetic", "episode_contacts"):
        print(name, np.round(flexible[name].values, 4))

# %%
# Plot
# ----
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True, height_ratios=(2, 1), layout="constrained")
    top.axhline(1.0, color="k", lw=1, label="rigid bar, closed form (e = 1)")
    top.plot(degrees, rigid["restitution_newton"], "s", mfc="none", color="0.5", label="rigid model, Newton")
    styles = (("restitution_newton", "o-", "Newton"), ("restitution_poisson", "x", "Poisson"),
              ("restitution_energetic", "+", "Stronge"))  # fmt: skip
    for name, style, label in styles:
        top.plot(degrees, flexible[name], style, ms=5, label=f"8 modes, {label}")
    top.set(ylabel="apparent restitution", title="Steel bar dropped at 1.4 m/s on its end cap (elastic Hertz, CCFM)")
    top.legend(fontsize="small", loc="lower left")
    bottom.plot(degrees, flexible["episode_contacts"], "o-", color="C0", label="8 modes")
    bottom.plot(degrees, rigid["episode_contacts"], "s", mfc="none", color="0.5", label="rigid model")
    bottom.set(xlabel="inclination [deg]", ylabel="contacts in\nthe first episode")
    bottom.legend(fontsize="small")
    plt.show()
