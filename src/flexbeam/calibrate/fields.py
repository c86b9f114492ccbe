"""Fitted case fields: their limits from the case schema and the scaled variables of the fit."""

from __future__ import annotations

import math
import re
import types
import typing
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import ParameterError
from ..parameters.case import Case
from ..parameters.io import field_units, get_dotted, schema_field


def parse_fit(text: str | Sequence[str]) -> list[str]:
    """``"contact.stiffness,contact.restitution"`` -> list of dotted keys."""
    items = text.split(",") if isinstance(text, str) else list(text)
    keys = [k.strip() for k in items if k.strip()]
    if not keys:
        raise ParameterError("--fit: give at least one case field, e.g. contact.stiffness")
    if len(set(keys)) != len(keys):
        raise ParameterError(f"--fit: a field is given twice ({', '.join(keys)})")
    return keys


def _field(key: str) -> tuple[float, float, bool, str]:
    """(lower, upper, is_real, units) of a dotted case field, from the schema."""
    from annotated_types import Ge, Gt, Le, Lt
    from pydantic import BaseModel
    from pydantic.fields import FieldInfo

    info = schema_field(key)  # unknown keys -> ParameterError with best matches
    metas: list[Any] = list(info.metadata)
    bases: list[Any] = []

    def walk(ann: Any) -> None:
        origin = typing.get_origin(ann)
        if origin is typing.Annotated:
            args = typing.get_args(ann)
            metas.extend(args[1:])
            walk(args[0])
        elif origin in (typing.Union, types.UnionType):
            for a in typing.get_args(ann):
                walk(a)
        else:
            bases.append(ann)

    walk(info.annotation)
    for m in list(metas):
        if isinstance(m, FieldInfo):
            metas.extend(m.metadata)
    lo, hi = -math.inf, math.inf
    for m in metas:
        if isinstance(m, (Ge, Gt)):
            lo = max(lo, float(m.ge if isinstance(m, Ge) else m.gt))
        elif isinstance(m, (Le, Lt)):
            hi = min(hi, float(m.le if isinstance(m, Le) else m.lt))
    is_real = float in bases and not any(isinstance(b, type) and issubclass(b, BaseModel) for b in bases)
    return lo, hi, is_real, field_units(key)


@dataclass
class Parameter:
    """A fitted field and its scaling: ``x = x0 exp(z)`` (log) or ``x = x0 + scale z``."""

    key: str
    x0: float
    lower: float
    upper: float
    log: bool
    scale: float
    units: str = ""

    @classmethod
    def of(cls, case: Case, key: str) -> Parameter:
        lo, hi, is_real, units = _field(key)
        if not is_real:
            raise ParameterError(f"--fit {key}: not a real-valued field (only numbers can be fitted)")
        x0 = get_dotted(case, key)
        pair = re.fullmatch(r"(?:obstacles\[(\d+)\]\.)?contact\.stiffness", key)
        if x0 is None and pair:  # Hertz theory's stiffness of that pair, the law it runs with
            from ..contact.setup import contact_law

            ob = None if pair.group(1) is None else case.obstacles[int(pair.group(1))]
            x0 = contact_law(case, ob, None if ob is None else ob.contact).stiffness
        if x0 is None:
            raise ParameterError(f"--fit {key}: the case gives no value; give a starting value with --set {key}=VALUE")
        x0 = float(x0)
        if lo >= 0.0 and math.isinf(hi) and x0 > 0.0:
            return cls(key, x0, lo, hi, True, 1.0, units)
        scale = hi - lo if math.isfinite(hi - lo) else (abs(x0) or 1.0)
        return cls(key, x0, lo, hi, False, scale, units)

    def value(self, z: float) -> float:
        return self.x0 * math.exp(z) if self.log else self.x0 + self.scale * z

    def derivative(self, z: float) -> float:
        """dx/dz."""
        return self.value(z) if self.log else self.scale

    def bounds(self) -> tuple[float, float]:
        if self.log:
            lo = math.log(self.lower / self.x0) if self.lower > 0 else -math.inf
            return lo, math.inf
        return (self.lower - self.x0) / self.scale, (self.upper - self.x0) / self.scale
