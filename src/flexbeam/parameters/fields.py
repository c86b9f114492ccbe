"""The building blocks of the case schema: finite, bounded and positive numbers, and the base of every section
(``extra="forbid"``: a misspelt key is an error)."""

from __future__ import annotations

import math
import tomllib
import types
import typing
from collections.abc import Mapping
from functools import cache
from typing import Annotated, Any, Self

import numpy as np
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
    """Text, true or false, NaN and +-inf named as such before a bounded field's range is checked."""
    _number_given(value)
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


def _number_given(value: object) -> None:
    """A ValueError unless ``value`` (or each item of a list or tuple) is a number: pydantic's lax mode read
    ``contact.friction = true`` as a friction coefficient of 1, ``model.modes = true`` as one mode and ``length =
    "0.7"`` as 0.7."""
    if _has(value, _BOOLS):
        raise ValueError("must be a number, not true or false")
    if _has(value, str):
        texts = value if isinstance(value, (list, tuple)) else [value]
        spelled = next((v for v in texts if isinstance(v, str) and _python_number(v)), None)
        if spelled is not None:  # ("-.4", "5.e9", "08": numbers to Python, text to TOML, which --set reads)
            raise ValueError(
                "must be a number as TOML writes one: a digit on each side of the point, no leading zero (e.g. -0.4, "
                "5.0e9, 8)"
            )
        raise ValueError("must be a number, not text")


def _python_number(text: str) -> bool:
    """Does Python's float() read ``text`` as a finite number that TOML does not (``.5``, ``5.e9``, ``08``)?  A
    number TOML reads, given as text (``length = "0.7"``), is text: quoted."""
    try:
        if not math.isfinite(float(text)):
            return False
    except ValueError:
        return False
    try:
        return not isinstance(tomllib.loads(f"v = {text}")["v"], (int, float))
    except tomllib.TOMLDecodeError:
        return True


def Bounded(lo: float, hi: float):  # noqa: N802 - a type
    """A finite float in [lo, hi]."""
    return Annotated[float, BeforeValidator(_finite_first), Field(ge=lo, le=hi)]


#: an angle [rad]: within +-1000 rad (160 turns), where double precision still resolves 1e-13 rad; at 1e6 rad the
#: integrators cannot resolve the motion of a step (measured: step-size underflow after 3.5e5 steps)
Angle = Bounded(-1e3, 1e3)
#: an angular rate [rad/s]: within +-1e4 rad/s (~1e5 rpm; a 1 m beam's tip would move at 10 km/s)
MAX_RATE = 1e4
Rate = Bounded(-MAX_RATE, MAX_RATE)
#: a speed [m/s]: within +-1e4 m/s, as fast as that rate moves a 1 m beam's tip (a free beam's centre of mass thrown
#: at 1e300 m/s ran with its kinetic energy overflowing to inf)
Speed = Bounded(-1e4, 1e4)
#: the smallest sphere obstacle [m]
MIN_SPHERE_RADIUS = 1e-6

CONTACT_LAWS = LAW_NAMES  # the registry of contact laws (flexbeam.contact.laws.LAWS)


def _kinds(annotation: Any) -> frozenset[str]:
    """What a field of this type takes: ``"number"``, ``"bool"``, ``"other"`` (text, paths, sections, ...), or
    ``"own"`` for a type whose own validator checks its input; Annotated and unions unwrapped, a list or tuple by its
    items, Any all three."""
    while typing.get_origin(annotation) is Annotated:
        if any(isinstance(m, BeforeValidator) for m in typing.get_args(annotation)[1:]):
            return frozenset({"own"})  # (its own validator checks what it is given: Bounded, the output interval)
        annotation = typing.get_args(annotation)[0]
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType, list, tuple):
        args = [a for a in typing.get_args(annotation) if a is not type(None) and a is not Ellipsis]
        return frozenset().union(*(_kinds(a) for a in args))
    if annotation is bool:
        return frozenset({"bool"})
    if annotation in (int, float):
        return frozenset({"number"})
    if annotation is Any:
        return frozenset({"number", "bool", "other"})
    return frozenset({"other"})


@cache
def _field_kinds(section: type[BaseModel], name: str) -> frozenset[str]:
    field = section.model_fields.get(name)
    return _kinds(field.annotation) if field is not None else frozenset({"number", "bool", "other"})


#: true or false: Python's, and numpy's (an override built from an array's entry)
_BOOLS = (bool, np.bool_)


def _has(value: object, kind: type | tuple[type, ...]) -> bool:
    """Is ``value``, or an item of it (a list or tuple), of ``kind``?"""
    return isinstance(value, kind) or (isinstance(value, (list, tuple)) and any(isinstance(v, kind) for v in value))


class Section(BaseModel):
    """The base of every section of a case: unknown keys are errors, and so is true or false or a string where a
    number belongs, and anything but true or false where a switch does (pydantic's lax mode read
    ``contact.friction = true`` as a friction coefficient of 1, ``model.modes = true`` as one mode, ``length =
    "0.7"`` as 0.7 and ``contact.anywhere = "yes"`` or ``1`` as true)."""

    model_config = ConfigDict(extra="forbid", validate_assignment=True)

    def model_copy(self, *, update: Mapping[str, Any] | None = None, deep: bool = False) -> Self:
        """pydantic's copy, validated again when ``update`` is given, as an assignment is (``validate_assignment``):
        pydantic's own takes the update as it is -- a case copied with ``solver.t_end = -1`` ran "success" with no
        sample.  A bad value raises pydantic's ``ValidationError`` naming the field."""
        copied = super().model_copy(deep=deep)
        if not update:
            return copied
        data = {name: getattr(copied, name) for name in type(self).model_fields}
        data.update(update)
        return type(self).model_validate(data)

    @field_validator("*", mode="before")
    @classmethod
    def _numbers_and_switches_only(cls, value: object, info: ValidationInfo) -> object:
        if info.field_name is None or value is None:  # (None: an optional field's "not given", pydantic's to judge)
            return value
        kinds = _field_kinds(cls, info.field_name)
        if kinds == {"number"}:
            _number_given(value)
        elif kinds == {"bool"}:
            if not isinstance(value, _BOOLS):
                raise ValueError("must be true or false")
            return bool(value)  # (numpy's bool as Python's)
        return value


__all__ = [
    "CONTACT_LAWS", "MAX_RATE", "MIN_SPHERE_RADIUS", "Angle", "Bounded", "Finite", "NonNegative", "Positive", "Rate",
    "Section", "Speed",
]  # fmt: skip
