"""flexbeam's compiled kernels (C99, built by pip at install; sources in ``kernels/src``).

* ``model.c`` -- the equations of ``docs/formulation.md`` in physical coordinates: mass matrix, generalised
  forces, energies, point kinematics, gap and contact Jacobian, the contact laws;
* ``rhs.c`` -- the right-hand side of the reference integrator and the output columns;
* ``propagation.c`` -- exact modal propagation for polynomial forcing (variation of constants);
* ``collocation.c`` -- one Gauss collocation step (fixed point, the pairs' contact forces by Newton);
* ``stepcontrol.c`` -- the energy-norm error and the step-size controller;
* ``events.c`` -- the guaranteed search for impact/separation on the dense output, the release of a constraint;
* ``phase.c`` -- the phase driver (steps, control, the pairs' events, dense-output records); ``switching.c`` -- the
  switches it takes inside a phase (``friction_switch.c``: CCFM's Coulomb switches; ``held_switch.c``: CCM's
  contact on one pair, its jump from ``impulse_map.c``);
* ``bookkeeping.c`` -- dissipated energy, joint work and energy balance of a step, the dense evaluation;
* ``module.c`` -- the Python module (method table, init); ``glue_model.c``, ``glue_integrator.c``,
  ``glue_math.c`` -- its functions, ``glue.c`` / ``glue.h`` -- the buffer helpers.

Why C and not Numba: measured on this project's machine, a fresh process that imports numba and loads one
cached trivial kernel takes 0.82-0.98 s (numba's import 0.41 s, its target set-up on the first load), above the
whole 1 s budget of ``flexbeam run seed-experiment --json``; a cold first run compiled the old Numba kernels
for 70-121 s.  Compiled ahead of time by pip, the kernels load in milliseconds and give the same
floating-point results on every x86-64 machine (no host-CPU code generation, no FMA contraction), so the
tests' tolerances do not depend on the CPU.  The finite-element reference (``flexbeam.fem``) stays on Numba.

The arrays are packed once per system into flat float64 buffers by :mod:`flexbeam.kernels.layout`.
"""

from __future__ import annotations

from .._namespace import public_dir
from . import _core
from .layout import (
    OUTPUT_COLUMNS,
    PAIR_COLUMNS,
    SWITCH_FRICTION,
    SWITCH_HELD,
    SWITCH_REBOUND,
    pack_basis,
    pack_contacts,
    pack_controls,
    pack_model,
)

__all__ = [
    "OUTPUT_COLUMNS",
    "PAIR_COLUMNS",
    "SWITCH_FRICTION",
    "SWITCH_HELD",
    "SWITCH_REBOUND",
    "core",
    "pack_basis",
    "pack_contacts",
    "pack_controls",
    "pack_model",
]

core = _core

__dir__ = public_dir(globals())
