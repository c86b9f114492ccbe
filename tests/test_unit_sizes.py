"""Small units (docs/architecture.md): no function over 100 lines anywhere in ``src/`` -- Python or the C
kernels -- and no module over 400 lines, so that each piece has a name that says what it does."""

from __future__ import annotations

import ast
import re
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "flexbeam"
MAX_FUNCTION = 100
MAX_FILE = 400


def python_functions() -> list[tuple[int, str]]:
    """(lines, 'module:function') of every Python function and method."""
    out = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                out.append((node.end_lineno - node.lineno + 1, f"{path.relative_to(SRC)}:{node.name}"))
    return out


_C_HEAD = re.compile(r"^[A-Za-z_][\w \*]*\b(\w+)\s*\(")


def c_functions() -> list[tuple[int, str]]:
    """(lines, 'file:function') of every C function definition: from its first line (a declaration at column 0
    whose signature opens a brace) to the closing brace at column 0."""
    out = []
    for path in sorted((SRC / "kernels" / "src").glob("*.[ch]")):
        lines = path.read_text(encoding="utf-8").split("\n")
        i = 0
        while i < len(lines):
            m = _C_HEAD.match(lines[i])
            if not m or lines[i].startswith(("typedef", "#")):
                i += 1
                continue
            j = i
            while j < len(lines) and "{" not in lines[j] and ";" not in lines[j]:
                j += 1
            if j >= len(lines) or ";" in lines[j].split("{")[0] or "=" in "".join(lines[i : j + 1]).split("{")[0]:
                i = j + 1
                continue
            end = j
            if lines[j].count("{") != lines[j].count("}"):
                while end < len(lines) and not lines[end].startswith("}"):
                    end += 1
            out.append((end - i + 1, f"{path.name}:{m.group(1)}"))
            i = end + 1
    return out


def test_the_c_scanner_sees_the_kernels_functions():
    """The C scanner must find the functions it is meant to bound (else the size test could not fail)."""
    names = {name.split(":")[1] for _, name in c_functions()}
    assert {"fb_advance", "fb_rhs", "fb_outputs", "fb_collocate", "fb_column_max"} <= names
    assert len(names) > 150


def test_no_function_over_100_lines():
    long = sorted((n, name) for n, name in python_functions() + c_functions() if n > MAX_FUNCTION)
    assert not long, f"functions over {MAX_FUNCTION} lines: {long}"


def test_no_module_over_400_lines():
    files = [*SRC.rglob("*.py"), *(SRC / "kernels" / "src").glob("*.c")]
    long = sorted(
        (len(p.read_text(encoding="utf-8").splitlines()), str(p.relative_to(SRC)))
        for p in files
        if len(p.read_text(encoding="utf-8").splitlines()) > MAX_FILE
    )
    assert not long, f"modules over {MAX_FILE} lines: {long}"
