"""The impact methods by name: one registry that the simulation, the CLI, sweeps and reports read.

Adding an impact method: write its class (a subclass of :class:`flexbeam.methods.base.ImpactMethod` saying what
an impact starts), and add it to :data:`IMPACT_METHODS`.  ``"fem"`` is the independent finite-element reference
(``flexbeam.fem``), which runs its own contact model and integrator.
"""

from __future__ import annotations

from .errors import ParameterError, closest
from .methods.base import ImpactMethod
from .methods.ccfm import CCFM
from .methods.ccm import CCM
from .methods.imm import IMM

#: method name -> (class, one-line description); "fem" is dispatched separately
IMPACT_METHODS: dict[str, tuple[type[ImpactMethod], str]] = {
    "ccfm": (CCFM, "continuous contact force (a law's force while the gap is closed)"),
    "ccm": (CCM, "contact constraint (e = 0 jump, then the unilateral constraint)"),
    "imm": (IMM, "impulse-momentum with a coefficient of restitution"),
}

#: every name ``simulate`` accepts
METHOD_NAMES = (*IMPACT_METHODS, "fem")


def _unknown(name: object) -> ParameterError:
    """The one-line error for a method name ``simulate`` does not accept (a closest match for a misspelt one)."""
    hint = closest(name, METHOD_NAMES) if isinstance(name, str) else ""
    shown = f"'{name}'" if isinstance(name, str) else f"{name!r} (not a name)"
    return ParameterError(f"method: unknown impact method {shown}; allowed: {', '.join(METHOD_NAMES)}{hint}")


def impact_method(name: str) -> type[ImpactMethod]:
    """The impact method class of ``name`` (a one-line ParameterError for an unknown name)."""
    if not isinstance(name, str) or name not in IMPACT_METHODS:
        raise _unknown(name)
    return IMPACT_METHODS[name][0]


def check_method(name: str) -> str:
    """``name`` if it is a method ``simulate`` accepts, else a one-line ParameterError."""
    if not isinstance(name, str) or name not in METHOD_NAMES:
        raise _unknown(name)
    return name
