"""
A parameter sweep on Dask
=========================

:func:`flexbeam.sweep` runs one case many times with some fields changed and returns
the metrics of every run as an :class:`xarray.Dataset` with one dimension per swept
field.  Here: a 2 x 2 grid of contact stiffness K and impact velocity v on the seed
case's rigid limit (no modes, no gravity, the first contact only).

For that rigid rod every law of the Hunt-Crossley family has one dimensionless
solution, d = d_max f(t/t_c) with d_max ~ (m v^2 / K)^(2/5), so the peak force scales
as ``K^(2/5) |v|^(6/5)`` and the contact duration as ``K^(-2/5) |v|^(-1/5)`` -- whatever the
law's damping.

The cases run on an in-process Dask cluster (threads); ``fb.sweep`` without ``scheduler``
starts a local cluster of worker processes instead (its workers do not run the calling
script again, so neither needs a ``__main__`` guard around the sweep).  ``out="sweep"``
would keep each case on disk and make the sweep resumable.
"""

# %%
# Run the grid
# ------------
from dask.distributed import Client

import flexbeam as fb

GRID = {"contact.stiffness": [2e9, 4e9], "initial.impact_velocity": [-0.2, -0.4]}
RIGID_FIRST_CONTACT = {"model.modes": 0, "model.gravity": 0.0, "solver.t_end": 2e-3}

# (no dashboard, and the scheduler's HTTP endpoints on a free port: 8787 may be taken by another cluster)
CLUSTER = {"processes": False, "n_workers": 1, "threads_per_worker": 1, "dashboard_address": None}
with Client(**CLUSTER, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"}) as client:
    ds = fb.sweep("seed-experiment", grid=GRID, overrides=RIGID_FIRST_CONTACT, scheduler=client)

# %%
# The result: one variable per metric over the two swept fields.
if __name__ == "__main__":
    print(ds["peak_force"].to_pandas())
    print(ds["contact_duration"].to_pandas())

# %%
# Plot
# ----
if __name__ == "__main__":
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
    ds["peak_force"].plot.line(x="initial.impact_velocity", marker="o", ax=ax)
    ax.set(xlabel="Impact velocity [m/s]", ylabel="Peak force [N]", title="Rigid limit, CCFM")
    plt.show()
