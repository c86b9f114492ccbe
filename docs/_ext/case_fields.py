"""Every field of the case schema (:class:`flexbeam.parameters.case.Case`) as rows of text.

Read from the pydantic models themselves -- annotation, default, ``Field`` constraints,
``Literal`` choices and description -- so that the case-file reference page, which the
``case-schema`` directive (``case_schema.py``) builds from these rows at every
documentation build, cannot drift from the code.  No Sphinx import here: the tests
check the rows without building the documentation.
"""

from __future__ import annotations

import inspect
import math
import types
import typing
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, Literal

from annotated_types import Ge, Gt, Le, Lt
from pydantic import AfterValidator, BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined


@dataclass(frozen=True)
class FieldRow:
    """One case field: dotted key, type, default, allowed range or choices, and description.

    ``default`` is a TOML value, or "required" / "omitted" (optional, no value) / "" (a table);
    ``choices`` lists the allowed strings of a field with fixed choices (``allowed`` is then "").
    """

    key: str
    type: str
    default: str
    allowed: str
    description: str
    choices: tuple[str, ...] = ()


@dataclass(frozen=True)
class SectionRows:
    """A section of the case file (a TOML table) with its docstring and fields."""

    key: str
    model: type[BaseModel]
    doc: str
    rows: list[FieldRow]


def _unwrap(ann: Any, metas: list[Any]) -> Any:
    """Strip ``Annotated`` layers, collecting their metadata into ``metas``."""
    while typing.get_origin(ann) is typing.Annotated:
        base, *extra = typing.get_args(ann)
        for m in extra:
            metas.extend(m.metadata if isinstance(m, FieldInfo) else [m])
        ann = base
    return ann


def _type_name(ann: Any, metas: list[Any]) -> str:
    ann = _unwrap(ann, metas)
    origin = typing.get_origin(ann)
    if origin in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(ann) if a is not type(None)]
        names = [_type_name(a, metas) for a in args]
        optional = len(args) < len(typing.get_args(ann))
        return " or ".join(names) + (" (optional)" if optional else "")
    if origin is Literal:
        return "string" if all(isinstance(a, str) for a in typing.get_args(ann)) else "literal"
    if origin is tuple:
        inner = [_type_name(a, metas) for a in typing.get_args(ann)]
        return f"[{', '.join(inner)}]"
    if origin is list:
        (item,) = typing.get_args(ann)
        item_metas: list[Any] = []
        name = f"list of {_type_name(item, item_metas)}"
        metas.extend(item_metas)
        return name
    return {float: "float", int: "integer", str: "string", bool: "boolean"}.get(ann, getattr(ann, "__name__", str(ann)))


def _choices(ann: Any) -> list[Any]:
    ann = _unwrap(ann, [])
    if typing.get_origin(ann) is Literal:
        return list(typing.get_args(ann))
    if typing.get_origin(ann) in (typing.Union, types.UnionType):
        return [c for a in typing.get_args(ann) for c in _choices(a)]
    return []


def _number(x: float) -> str:
    return f"{x:g}"


def _allowed(metas: list[Any]) -> str:
    lo, hi, lo_open, hi_open = -math.inf, math.inf, False, False
    for m in metas:
        if isinstance(m, Ge) and m.ge >= lo:
            lo, lo_open = m.ge, False
        elif isinstance(m, Gt) and m.gt >= lo:
            lo, lo_open = m.gt, True
        elif isinstance(m, Le) and m.le <= hi:
            hi, hi_open = m.le, False
        elif isinstance(m, Lt) and m.lt <= hi:
            hi, hi_open = m.lt, True
    if math.isinf(lo) and math.isinf(hi):
        finite = any(isinstance(m, AfterValidator) and m.func.__name__ == "_finite" for m in metas)
        return "finite" if finite else ""
    if math.isinf(hi):
        return f"{'>' if lo_open else '>='} {_number(lo)}"
    if math.isinf(lo):
        return f"{'<' if hi_open else '<='} {_number(hi)}"
    return f"{'(' if lo_open else '['}{_number(lo)}, {_number(hi)}{')' if hi_open else ']'}"


def _default(info: FieldInfo) -> str:
    if info.default_factory is not None:
        value = info.default_factory()
        return "" if isinstance(value, BaseModel) else repr(value)
    if info.default is PydanticUndefined:
        return "required"
    if info.default is None:
        return "omitted"
    if isinstance(info.default, str):
        return f'"{info.default}"'
    if isinstance(info.default, float):
        return _number(info.default)
    return repr(info.default)


def _section_model(info: FieldInfo) -> type[BaseModel] | None:
    ann = _unwrap(info.annotation, [])
    return ann if inspect.isclass(ann) and issubclass(ann, BaseModel) else None


def field_rows(model: type[BaseModel], prefix: str = "") -> list[FieldRow]:
    """The plain (non-section) fields of ``model``, keys prefixed with ``prefix``."""
    rows = []
    for name, info in model.model_fields.items():
        if _section_model(info) is not None:
            continue
        metas: list[Any] = list(info.metadata)
        type_name = _type_name(info.annotation, metas)
        choices = tuple(f'"{c}"' if isinstance(c, str) else str(c) for c in _choices(info.annotation))
        rows.append(FieldRow(key=prefix + name, type=type_name, default=_default(info),
                             allowed="" if choices else _allowed(metas), description=info.description or "",
                             choices=choices))
    return rows


def case_sections(model: type[BaseModel] | None = None, prefix: str = "") -> Iterator[SectionRows]:
    """The case's top-level fields, then every section (nested ones after their parent), in schema order."""
    if model is None:
        from flexbeam.parameters.case import Case

        model = Case
    yield SectionRows(prefix.rstrip("."), model, inspect.cleandoc(model.__doc__ or ""), field_rows(model, prefix))
    for name, info in model.model_fields.items():
        sub = _section_model(info)
        if sub is not None:
            yield from case_sections(sub, f"{prefix}{name}.")
