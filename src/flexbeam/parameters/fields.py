"""The building blocks of the case schema: finite, bounded and positive numbers, and the base of every section
(``extra="forbid"``: a misspelt key is an error)."""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field

from ..contact.laws import LAW_NAMES


def _finite(value: float) -> float:
    if not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


Finite = Annotated[float, AfterValidator(_finite)]
Positive = Annotated[float, Field(gt=0), AfterValidator(_finite)]
NonNegative = Annotated[float, Field(ge=0), AfterValidator(_finite)]


def _finite_first(value: object) -> object:
    """NaN and +-inf named as such before a bounded field's range is checked."""
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


def Bounded(lo: float, hi: float):  # noqa: N802 - a type
    """A finite float in [lo, hi]."""
    return Annotated[float, BeforeValidator(_finite_first), Field(ge=lo, le=hi)]


#: an angle [rad]: within +-1000 rad (160 turns), where double precision still resolves 1e-13 rad; at 1e6 rad the
#: integrators cannot resolve the motion of a step (measured: step-size underflow after 3.5e5 steps)
Angle = Bounded(-1e3, 1e3)
#: an angular rate [rad/s]: within +-1e4 rad/s (~1e5 rpm; a 1 m beam's tip would move at 10 km/s)
MAX_RATE = 1e4
Rate = Bounded(-MAX_RATE, MAX_RATE)
#: the smallest sphere obstacle [m]
MIN_SPHERE_RADIUS = 1e-6

CONTACT_LAWS = LAW_NAMES  # the registry of contact laws (flexbeam.contact.laws.LAWS)


class Section(BaseModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True)


__all__ = [
    "CONTACT_LAWS", "MAX_RATE", "MIN_SPHERE_RADIUS", "Angle", "Bounded", "Finite", "NonNegative", "Positive", "Rate",
    "Section",
]  # fmt: skip
