"""Reading, overriding and writing cases (TOML via :mod:`tomllib` / ``tomli_w``)."""

from __future__ import annotations

import copy
import math
import os
import re
import tomllib
import typing
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import ParameterError, closest, did_you_mean, not_text
from .case import Case

#: the package that holds the built-in cases and their reference numbers
PRESETS_PACKAGE = "flexbeam.parameters.presets"


def builtin_cases() -> dict[str, str]:
    """Names of the built-in cases with their one-line descriptions."""
    out: dict[str, str] = {}
    for entry in sorted(resources.files(PRESETS_PACKAGE).iterdir(), key=lambda p: p.name):
        if entry.name.endswith(".toml") and not entry.name.endswith(".reference.toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            out[entry.name[: -len(".toml")]] = str(data.get("description", "")).split("\n")[0]
    return out


def _read_source(source: str | Path) -> dict[str, Any]:
    path = Path(source)
    if path.suffix == ".toml" or path.exists():
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise ParameterError(f"case: cannot read '{path}': {exc.strerror}") from None
        except UnicodeDecodeError as exc:  # TOML is UTF-8 (a binary file, a result.nc given as a case)
            raise ParameterError(not_text("case", path, "TOML", exc)) from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise ParameterError(f"case: '{path}' is not valid TOML: {exc}") from None
        base = data.get("base")
        if isinstance(base, dict) and isinstance(base.get("table"), str):  # a CSV path relative to the case file
            base["table"] = str(path.parent / base["table"])
        return data
    names = builtin_cases()
    if str(source) not in names:
        raise ParameterError(
            f"case: unknown case '{source}'; give a TOML path or one of: "
            f"{', '.join(names)}{closest(str(source), names)}"
        )
    entry = resources.files(PRESETS_PACKAGE) / f"{source}.toml"
    return tomllib.loads(entry.read_text(encoding="utf-8"))


def _format_validation_error(exc: ValidationError) -> str:
    errors = exc.errors()
    # A misspelt key leaves the field it meant missing: name the unknown key first.
    unknown = [e for e in errors if e["type"] == "extra_forbidden"]
    err = unknown[0] if unknown else errors[0]
    msg = str(err["msg"])
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, ") :]
    loc = dotted_key(err["loc"])
    where = err["loc"][:2]
    if len(where) == 2 and where[0] == "obstacles" and isinstance(where[1], int) and msg.startswith("obstacle."):
        # a check of [obstacle]'s model run on an [[obstacles]] entry: name the entry's field
        return f"obstacles[{where[1]}]." + msg[len("obstacle.") :]
    if err["type"] == "extra_forbidden":
        return unknown_field_message(key_parts(err["loc"]), isinstance(err.get("input"), dict))
    if err["type"] == "missing":
        return f"{loc}: required field is missing"
    if loc and not msg.startswith(loc.split(".")[0] + "."):
        got = err.get("input")
        got_txt = f" (got {got!r})" if got is not None and not isinstance(got, dict) else ""
        return f"{loc}: {msg}{got_txt}{_shape_hint(err['type'], loc)}{_range_hint(err['type'], loc)}"
    return msg


#: pydantic's errors of a value of the wrong shape (a number for a pair, a list too short), whose own text does not
#: say what the field holds
_SHAPE_ERRORS = ("tuple_type", "list_type", "too_short", "too_long")


def _shape_hint(kind: str, loc: str) -> str:
    """For an error of :data:`_SHAPE_ERRORS`, "; expected " with the field's shape (a tuple's number of items) and
    description (``base.acceleration = 1.0`` said "Input should be a valid tuple" only); else ""."""
    if kind not in _SHAPE_ERRORS:
        return ""
    try:
        info = schema_field(loc)
    except ParameterError:
        return ""
    args = [a for a in typing.get_args(info.annotation) if typing.get_origin(a) is tuple] or [info.annotation]
    items = typing.get_args(args[0]) if typing.get_origin(args[0]) is tuple else ()
    shape = f"a list of {len(items)} numbers, " if items and Ellipsis not in items else ""
    return f"; expected {shape}{info.description}" if info.description else ""


#: pydantic's errors of a number out of its field's bounds, whose text names the bound that failed alone
_RANGE_ERRORS = ("greater_than", "greater_than_equal", "less_than", "less_than_equal")


def _range_hint(kind: str, loc: str) -> str:
    """For an error of :data:`_RANGE_ERRORS` on a field bounded on both sides, "; allowed range [lo, hi]" (round
    brackets for strict bounds): ``contact.restitution = -1`` said "greater than or equal to 0" only, not that 1 is
    the most; else ""."""
    if kind not in _RANGE_ERRORS:
        return ""
    try:
        info = schema_field(loc)
    except ParameterError:
        return ""
    lo = hi = ""
    for bound in info.metadata:
        if hasattr(bound, "ge") or hasattr(bound, "gt"):
            lo = f"[{bound.ge:g}" if hasattr(bound, "ge") else f"({bound.gt:g}"
        if hasattr(bound, "le") or hasattr(bound, "lt"):
            hi = f"{bound.le:g}]" if hasattr(bound, "le") else f"{bound.lt:g})"
    return f"; allowed range {lo}, {hi}" if lo and hi else ""


_INDEXED = re.compile(r"^(\w+)\[(\d+)\]$")
_BRACKETED = re.compile(r"^(\w+)\[([^\]]*)\]$")  # (an index that is not a count: obstacles[-1], obstacles[a])


def key_parts(loc: tuple) -> list[str]:
    """A validation error's location as the parts of the dotted key ``--set`` takes: ``("obstacles", 0, "centre")``
    -> ``["obstacles[0]", "centre"]``."""
    parts: list[str] = []
    for part in loc:
        if isinstance(part, int) and parts:
            parts[-1] += f"[{part}]"
        else:
            parts.append(str(part))
    return parts


def dotted_key(loc: tuple) -> str:
    """A validation error's location as the dotted key ``--set`` takes: ``"obstacles[0].centre"``."""
    return ".".join(key_parts(loc))


def _split(part: str) -> tuple[str, int | None]:
    """``"obstacles[1]"`` -> ("obstacles", 1); ``"beam"`` -> ("beam", None)."""
    m = _INDEXED.match(part)
    return (m.group(1), int(m.group(2))) if m else (part, None)


def _section_model(path: list[str]) -> type[BaseModel] | None:
    """The pydantic model of the case section at ``path`` ([] = Case; ``obstacles[i]`` an entry of a list of
    sections), or None if it is no section."""
    model: type[BaseModel] | None = Case
    for part in path:
        name, index = _split(part)
        if model is None or name not in model.model_fields:
            return None
        model = _item_model(model, name) if index is not None else _field_model(model, name)
    return model


def schema_field(key: str):
    """The pydantic FieldInfo of the dotted case field ``key`` (``obstacles[0].contact.stiffness`` names a field of
    an entry of a list of sections); a one-line ParameterError for an unknown or incomplete path."""
    parts = key.split(".")
    model: type[BaseModel] | None = Case
    for depth, part in enumerate(parts):
        name, index = _split(part)
        bad = _BRACKETED.match(part) if index is None and model is not None else None
        if bad and bad.group(1) in model.model_fields and _item_model(model, bad.group(1)) is not None:
            raise ParameterError(  # ("unknown section 'obstacles[-1]'" before)
                f"{key}: '{bad.group(2)}' is no index of {bad.group(1)}: they count 0, 1, 2, ..."
            )
        if model is None:
            raise ParameterError(f"{key}: '{'.'.join(parts[:depth])}' is not a section")
        if name not in model.model_fields:
            raise ParameterError(unknown_field_message(parts[: depth + 1], depth < len(parts) - 1, key))
        if index is not None:
            model = _item_model(model, name)
            if model is None:
                raise ParameterError(f"{key}: '{name}' is not a list of sections (no [{index}])")
            if depth == len(parts) - 1:
                raise ParameterError(f"{key}: name a field of {part}, e.g. {part}.{next(iter(model.model_fields))}")
        elif depth == len(parts) - 1:
            return model.model_fields[name]
        else:
            model = _field_model(model, name)
    raise AssertionError("unreachable")


def field_units(key: str) -> str:
    """The units of the dotted case field ``key`` as its description gives them, in brackets (``[rad]`` -> ``rad``,
    ``[-]`` -> ``-``), "" where it gives none; a one-line ParameterError for an unknown field (:func:`schema_field`)."""
    found = re.search(r"\[([^\]]+)\]", schema_field(key).description or "")
    return found.group(1) if found else ""


def unknown_field_message(path: list[str], section: bool, key: str | None = None) -> str:
    """One-line message for an unknown case field or section, naming it first.

    Parameters
    ----------
    path
        Dotted path of the unknown name, e.g. ``["beam", "lenght"]``.
    section
        Whether it was given as a section (a TOML table, or a prefix of a longer key).
    key
        The full key as the user wrote it, if longer than ``path`` (``--set bem.length=1``).

    Returns
    -------
    str
        ``"beam.lenght: unknown field, did you mean length?"``; without a close match the
        known names of the enclosing section are listed instead.
    """
    name, parent = path[-1], path[:-1]
    model = _section_model(parent)
    choices = list(model.model_fields) if model is not None else []
    where = ".".join(parent) or "case"
    what = "unknown section" if section else "unknown field"
    head = ".".join(path)
    if key is not None and key != head:
        head, what = key, f"{what} '{head}'"
    hint = did_you_mean(name, choices) or (f"; {where} has: {', '.join(choices)}" if choices else "")
    return f"{head}: {what}{hint}"


def validate_case(data: dict[str, Any]) -> Case:
    """Build a :class:`Case` from a plain dict, raising a one-line ParameterError."""
    try:
        return Case.model_validate(data)
    except ValidationError as exc:
        raise ParameterError(_format_validation_error(exc)) from None


def load_case(source: str | Path | Case | Mapping[str, Any], overrides: dict[str, Any] | None = None) -> Case:
    """Load a built-in case by name, or a TOML file, and apply dotted overrides.

    Parameters
    ----------
    source
        Built-in case name (see :func:`builtin_cases`), path to a TOML file, a Case, or
        the nested dict a TOML file holds (``{"beam": {"length": 0.7, ...}, ...}``; not modified).
    overrides
        ``{"beam.youngs_modulus": 70e9, ...}``; keys are dotted paths of case fields.

    Returns
    -------
    Case
        The validated case.

    Raises
    ------
    ParameterError
        Unknown case, key or section (named first, with its closest match, even when
        the field it was meant for is then missing), or a value outside its allowed range.
    """
    if overrides is not None and not isinstance(overrides, Mapping):
        raise ParameterError(
            f"overrides: a mapping of dotted keys to values, e.g. {{'model.modes': 3}} (got {type(overrides).__name__}"
            "; KEY=VALUE strings: parse_overrides)"
        )
    if isinstance(source, Case):
        data = source.model_dump(exclude_none=True)
    elif isinstance(source, Mapping):
        data = copy.deepcopy(dict(source))
    elif isinstance(source, (str, os.PathLike)):
        data = _read_source(source)
    else:
        raise ParameterError(f"case: a built-in case name, a TOML path, a Case or a dict (got {type(source).__name__})")
    for key, value in (overrides or {}).items():
        if not isinstance(key, str):  # (1 -> AttributeError: 'int' object has no attribute 'split')
            raise ParameterError(f"overrides: each key is a dotted field name such as 'model.modes' (got {key!r})")
        set_dotted(data, key, value)
    return validate_case(data)


def _field_model(model: type[BaseModel], key: str) -> type[BaseModel] | None:
    field = model.model_fields[key]
    ann = field.annotation
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return ann
    return None


def _item_model(model: type[BaseModel], key: str) -> type[BaseModel] | None:
    """The section type of the entries of a list-of-sections field (``obstacles``), else None."""
    ann = model.model_fields[key].annotation
    if typing.get_origin(ann) is list:
        (item,) = typing.get_args(ann)
        if isinstance(item, type) and issubclass(item, BaseModel):
            return item
    return None


def set_dotted(data: dict[str, Any], key: str, value: Any) -> None:
    """Set ``data[a][b] = value`` for ``key = "a.b"``, checking the path exists in Case; ``a[i].b`` sets field b of
    entry i of the list of sections a (``obstacles[0].contact.stiffness``), which must exist in ``data``."""
    schema_field(key)  # the path against the schema: unknown names, plain fields used as sections
    parts = key.split(".")
    node = data
    for depth, part in enumerate(parts):
        name, index = _split(part)
        where = ".".join(parts[: depth + 1])
        if depth == len(parts) - 1:
            node[name] = value
        elif index is not None:
            items = node.get(name) or []
            if not isinstance(items, list) or index >= len(items):
                raise ParameterError(f"{key}: {where} does not exist (the case has {len(items)} {name})")
            node = items[index]
        else:
            node = node.setdefault(name, {})
            if not isinstance(node, dict):
                raise ParameterError(f"{key}: '{where}' is not a section")


def get_dotted(case: Case, key: str) -> Any:
    """The value of the dotted field ``key`` of ``case`` (``obstacles[0].contact.stiffness`` as :func:`set_dotted`
    takes it); a one-line ParameterError for an unknown path or a missing entry."""
    schema_field(key)
    node: Any = case
    for part in key.split("."):
        name, index = _split(part)
        node = getattr(node, name)
        if index is not None:
            if index >= len(node):
                raise ParameterError(f"{key}: {name}[{index}] does not exist (the case has {len(node)} {name})")
            node = node[index]
    return node


def parse_value(text: str) -> Any:
    """Parse a command-line ``VALUE`` as a TOML value (number, bool, array, string)."""
    try:
        value = tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        lowered = text.strip().lower()
        if lowered in ("nan", "+nan", "-nan"):
            return math.nan
        return text
    return value


def parse_overrides(items: list[str]) -> dict[str, Any]:
    """Turn ``["a.b=1", ...]`` into ``{"a.b": 1}``."""
    out: dict[str, Any] = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key.strip():
            raise ParameterError(f"--set: expected KEY=VALUE (got '{item}')")
        out[key.strip()] = parse_value(text.strip())
    return out


def dump_case(case: Case) -> str:
    """TOML text of a case that :func:`load_case` reads back to an equal case.  Empty lists are left out (their
    fields' default): TOML's ``obstacles = []`` would forbid the ``[[obstacles]]`` tables a user appends to the
    dumped case (docs/usage.md's way to add a stop)."""
    import tomli_w

    data = _without_empty_lists(case.model_dump(mode="json", exclude_none=True))
    head = {k: data.pop(k) for k in ("name", "description")}
    return tomli_w.dumps({**head, **data}, multiline_strings=True)


def _without_empty_lists(data: dict) -> dict:
    """``data`` (a dumped case's tables) without its empty lists, in its tables at any depth."""
    return {k: _without_empty_lists(v) if isinstance(v, dict) else v for k, v in data.items() if v != []}
