"""The building blocks of the case schema: finite, bounded and positive numbers, and the base of every section
(``extra="forbid"``: a misspelt key is an error)."""

from __future__ import annotations

import math
import types
import typing
from functools import cache
from typing import Annotated, Any

from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field, ValidationInfo, field_validator

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


def _takes(annotation: Any) -> tuple[bool, bool]:
    """(whether a field of this type takes a number, whether it takes true/false), Annotated and unions unwrapped;
    a list or tuple by its items."""
    while typing.get_origin(annotation) is Annotated:
        annotation = typing.get_args(annotation)[0]
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType, list, tuple):
        kinds = [_takes(a) for a in typing.get_args(annotation) if a is not type(None) and a is not Ellipsis]
        return any(n for n, _ in kinds), any(b for _, b in kinds)
    if annotation is bool:
        return False, True
    return annotation in (int, float), annotation is Any


@cache
def _numbers_only(section: type[BaseModel], name: str) -> bool:
    """Whether field ``name`` of ``section`` takes numbers (or lists of them) and no true/false."""
    field = section.model_fields.get(name)
    if field is None:
        return False
    number, boolean = _takes(field.annotation)
    return number and not boolean


def _has_bool(value: object) -> bool:
    return isinstance(value, bool) or (isinstance(value, (list, tuple)) and any(isinstance(v, bool) for v in value))


class Section(BaseModel):
    """The base of every section of a case: unknown keys are errors, and so is true or false where a number
    belongs (pydantic's lax mode read ``contact.friction = true`` as a friction coefficient of 1 and
    ``model.modes = true`` as one mode)."""

    model_config = ConfigDict(extra="forbid", validate_assignment=True)

    @field_validator("*", mode="before")
    @classmethod
    def _no_true_or_false_for_a_number(cls, value: object, info: ValidationInfo) -> object:
        if _has_bool(value) and info.field_name is not None and _numbers_only(cls, info.field_name):
            raise ValueError("must be a number, not true or false")
        return value


__all__ = [
    "CONTACT_LAWS", "MAX_RATE", "MIN_SPHERE_RADIUS", "Angle", "Bounded", "Finite", "NonNegative", "Positive", "Rate",
    "Section",
]  # fmt: skip
