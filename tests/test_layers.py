"""The package's imports point down its layers and form no cycle (docs/architecture.md).

Every ``import`` and ``from ... import`` in ``src/flexbeam`` is read with :mod:`ast` -- at module level, inside
functions (a lazy import is still an import) and in ``try`` blocks; only imports under ``if TYPE_CHECKING:`` are
left out, since they run for the type checker only.  Each module belongs to one layer of :data:`LAYERS`; a module
may import from its own layer or a lower one.  The package's own ``__init__`` (the public facade) may import
anything.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "flexbeam"

#: bottom to top; a module is in the first layer one of whose prefixes it starts with
LAYERS: list[tuple[str, tuple[str, ...]]] = [
    ("base", ("flexbeam.errors", "flexbeam.numerics", "flexbeam.kernels", "flexbeam.version", "flexbeam.progress",
              "flexbeam._namespace", "flexbeam.schemas", "flexbeam.threads", "flexbeam.interrupt")),
    ("laws", ("flexbeam.contact.laws", "flexbeam.contact.hertz")),
    ("parameters", ("flexbeam.parameters",)),
    ("contact", ("flexbeam.contact",)),
    ("model", ("flexbeam.model",)),
    ("integrate", ("flexbeam.integrate",)),
    ("results", ("flexbeam.results",)),
    ("methods", ("flexbeam.methods", "flexbeam.fem")),
    ("simulation", ("flexbeam.simulation", "flexbeam.registry", "flexbeam.memory")),
    ("views", ("flexbeam.views",)),
    ("applications", ("flexbeam.sweep", "flexbeam.calibrate", "flexbeam.validation", "flexbeam.bifurcation")),
    ("cli", ("flexbeam.cli",)),
]  # fmt: skip


def module_name(path: Path) -> str:
    rel = path.relative_to(SRC.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {module_name(p): p for p in SRC.rglob("*.py")}


def layer_of(module: str) -> int:
    best, rank = -1, -1
    for i, (_, prefixes) in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best:
                best, rank = len(prefix), i
    return rank


def _type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def imports(module: str) -> set[str]:
    """The flexbeam modules ``module`` imports at run time (submodules named by ``from pkg import sub`` included)."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and _type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("flexbeam"):
                    found.add(_known(alias.name))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("flexbeam"):
                subs = [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in MODULES]
                found.update(subs)
                if len(subs) < len(node.names):
                    found.add(_known(target))
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(path.read_text("utf-8")))
    found.discard(module)
    return found


def _known(name: str) -> str:
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name


def test_every_module_has_a_layer():
    assert [m for m in MODULES if layer_of(m) < 0 and m != "flexbeam"] == []


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m != "flexbeam"))
def test_imports_point_down(module):
    mine = layer_of(module)
    up = sorted(f"{t} ({LAYERS[layer_of(t)][0]})" for t in imports(module) if t != "flexbeam" and layer_of(t) > mine)
    assert not up, f"{module} ({LAYERS[mine][0]}) imports from a higher layer: {up}"
    assert "flexbeam" not in imports(module), f"{module} imports the package facade (import the module itself)"


def test_no_import_cycle():
    graph = {m: imports(m) for m in MODULES}
    state: dict[str, int] = {}
    stack: list[str] = []

    def dfs(v: str) -> list[str] | None:
        state[v] = 1
        stack.append(v)
        for w in sorted(graph[v]):
            if state.get(w) == 1:
                return stack[stack.index(w) :] + [w]
            if w not in state:
                cycle = dfs(w)
                if cycle:
                    return cycle
        stack.pop()
        state[v] = 2
        return None

    for v in sorted(graph):
        if v not in state:
            cycle = dfs(v)
            assert cycle is None, " -> ".join(cycle)
