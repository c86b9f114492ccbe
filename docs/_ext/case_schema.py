"""Sphinx directive ``case-schema``: the case-file reference, built from the pydantic schema.

Each section of :class:`flexbeam.parameters.case.Case` becomes a heading (its TOML table,
e.g. ``[obstacle.support]``), the section's docstring, and a table of its fields with type,
default, allowed values and description (rows from ``case_fields.py``).  The text is
generated at every build, so the page follows the code.
"""

from __future__ import annotations

from case_fields import FieldRow, case_sections
from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective

HEADER = ("key", "type", "default", "allowed", "description")
WIDTHS = (24, 12, 12, 18, 34)


def _cell(text: str, literal: bool = False) -> nodes.entry:
    para = nodes.paragraph()
    if text:
        para += nodes.literal(text, text) if literal else nodes.Text(text)
    return nodes.entry("", para)


def _choices_cell(choices: tuple[str, ...]) -> nodes.entry:
    para = nodes.paragraph()
    for i, c in enumerate(choices):
        if i:
            para += nodes.Text(", ")
        para += nodes.literal(c, c)
    return nodes.entry("", para)


def _table(rows: list[FieldRow]) -> nodes.table:
    table = nodes.table(classes=["case-schema"])
    group = nodes.tgroup(cols=len(HEADER))
    table += group
    group.extend(nodes.colspec(colwidth=w) for w in WIDTHS)
    head = nodes.thead()
    head += nodes.row("", *(_cell(h) for h in HEADER))
    group += head
    body = nodes.tbody()
    for r in rows:
        value = r.default not in ("required", "omitted")
        allowed = _choices_cell(r.choices) if r.choices else _cell(r.allowed)
        body += nodes.row("", _cell(r.key, literal=True), _cell(r.type), _cell(r.default, literal=value), allowed,
                          _cell(r.description))
    group += body
    return table


class CaseSchema(SphinxDirective):
    """``.. case-schema::`` -- one section per case table, with its fields."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        import case_fields

        from flexbeam.parameters import case

        for module in (case, case_fields):  # rebuild the page when the schema changes
            self.env.note_dependency(module.__file__)
        out: list[nodes.Node] = []
        for sec in case_sections():
            title = f"[{sec.key}]" if sec.key else "Top level"
            section = nodes.section(ids=[nodes.make_id(f"case-{sec.key or 'top-level'}")])
            section += nodes.title(title, title)
            if sec.doc:
                doc = nodes.container()
                self.state.nested_parse(StringList(sec.doc.splitlines(), source=f"{sec.model.__qualname__}"),
                                        self.content_offset, doc)
                section += doc.children
            if sec.rows:
                section += _table(sec.rows)
            out.append(section)
        return out


def setup(app: Sphinx) -> dict[str, object]:
    app.add_directive("case-schema", CaseSchema)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
