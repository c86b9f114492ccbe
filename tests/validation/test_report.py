"""The validation report (``python -m flexbeam.validation``) cannot drift from the code.

The reduced report is regenerated into a temporary directory: every section must be present,
every compared quantity within its stated tolerance, every figure written, and the Markdown must
print exactly the structured result.  The full page kept in the tree, ``docs/validation.md``, must
have the same sections and only passing rows.  (How long the report takes is measured in
``benchmarks/``, not asserted here.)
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from flexbeam.validation import SECTIONS, main, run_validation

DOCS = Path(__file__).resolve().parents[2] / "docs"


@pytest.fixture(scope="module")
def reduced(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    return out, run_validation(reduced=True, out=out)


def _split(line: str) -> list[str]:
    """Cells of a Markdown table row (escaped pipes stay inside their cell)."""
    return [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]


def _tables(text: str) -> dict[str, list[dict[str, str]]]:
    """Section heading -> rows (header name -> cell) of the table under it."""
    out: dict[str, list[dict[str, str]]] = {}
    heading, header = None, None
    for line in text.splitlines():
        if line.startswith("## "):
            heading, header = line[3:].strip(), None
            out[heading] = []
        elif heading and line.startswith("|"):
            cells = _split(line)
            if header is None:
                header = cells
            elif not set(line) <= set("|-"):
                out[heading].append(dict(zip(header, cells)))
    return out


def test_every_section_is_present_and_passes(reduced):
    out, sections = reduced
    assert [s.key for s in sections] == list(SECTIONS)
    for s in sections:
        assert s.rows, f"{s.key}: no compared quantities"
        bad = [(r.quantity, r.extra, r.reference, r.value, r.error, r.tolerance) for r in s.rows if not r.passed]
        assert not bad, f"{s.key}: {bad}"
        for name, _ in s.figures:
            assert (out / "figures" / name).stat().st_size > 1000


def _printed(cell: str, value: float, digits: int) -> bool:
    """A printed cell is ``value`` to ``digits`` significant figures (half a unit of the last one)."""
    x = float(cell)
    if not math.isfinite(value) or value == 0.0:
        return x == value
    return abs(x - value) <= 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - digits + 1) * (1 + 1e-9)


def test_written_page_prints_the_results(reduced):
    """Row for row, the Markdown holds the structured result: quantity, reference and value (9 significant
    figures, 7 in exponent form), error and tolerance (4 and 3), the check and the verdict."""
    out, sections = reduced
    text = (out / "validation.md").read_text("utf-8")
    tables = _tables(text)
    assert list(tables) == [s.title for s in sections]
    for s in sections:
        rows = tables[s.title]
        assert len(rows) == len(s.rows)
        for row, r in zip(rows, s.rows, strict=True):
            assert row["quantity"] == r.quantity.replace("|", "\\|"), (s.key, row)
            for name, x in (("reference", r.reference), ("flexbeam", r.value)):
                assert _printed(row[name], x, 7 if "e" in row[name] else 9), (s.key, name, row, x)
            assert _printed(row["error"], r.error, 4) and _printed(row["tolerance"], r.tolerance, 3), (s.key, row)
            assert (
                row["check"]
                == {"rel": "relative", "abs": "absolute", "upper": "value <= reference", "lower": "value >= reference"}[
                    r.kind
                ]
            ), (s.key, row)
            assert row["status"] == ("pass" if r.passed else "FAIL"), (s.key, row)
        for name, _ in s.figures:
            assert f"](figures/{name})" in text


def test_committed_page_is_a_full_run_with_the_same_sections(reduced):
    _, sections = reduced
    page = DOCS / "validation.md"
    assert page.is_file(), "docs/validation.md missing: run `python -m flexbeam.validation`"
    text = page.read_text("utf-8")
    assert "(full run" in text
    tables = _tables(text)
    assert list(tables) == [s.title for s in sections]
    for title, rows in tables.items():
        assert rows, title
        assert all(r["status"] == "pass" and float(r["error"]) <= float(r["tolerance"]) for r in rows), title
    for link in re.findall(r"\]\((figures/[^)]+)\)", text):
        assert (DOCS / link).is_file(), link


def test_command_line_runs_a_subset(tmp_path):
    assert main(["--reduced", "--only", "roots", "pendulum", "--out", str(tmp_path)]) == 0
    text = (tmp_path / "validation.md").read_text("utf-8")
    assert list(_tables(text)) == [SECTIONS["roots"](True, None).title, SECTIONS["pendulum"](True, None).title]


@pytest.mark.slow
def test_committed_page_matches_a_fresh_full_run(tmp_path):
    """docs/validation.md cannot go stale: a full run now gives, row for row, the committed quantities, and each
    committed value is the fresh one to within the row's own tolerance (relative or absolute) plus half a unit of
    its last printed digit.  Bound rows (energy drifts and the like, which only have to stay below their bound)
    must agree to a factor 2."""
    sections = run_validation(reduced=False, out=tmp_path)
    tables = _tables((DOCS / "validation.md").read_text("utf-8"))
    assert list(tables) == [s.title for s in sections]
    for s in sections:
        rows = tables[s.title]
        assert len(rows) == len(s.rows), s.title
        for row, r in zip(rows, s.rows, strict=True):
            assert row["quantity"] == r.quantity.replace("|", "\\|"), (s.title, row)
            for key, val in r.extra.items():  # labels exactly; numbers (step counts, ...) to 10 %
                _same_extra(row[key], str(val), (s.title, row, key))
            old, new = float(row["flexbeam"]), float(r.value)
            where = (s.title, r.quantity, r.extra, old, new)
            digits = 7 if "e" in row["flexbeam"] else 9
            printed = 0.5 * 10.0 ** (math.floor(math.log10(abs(new))) - digits + 1) if new else 0.0
            if r.kind == "rel":
                assert abs(old - new) <= r.tolerance * abs(r.reference) + printed, where
            elif r.kind == "abs":
                assert abs(old - new) <= r.tolerance + printed, where
            else:
                assert 0.5 * abs(new) <= abs(old) <= 2.0 * abs(new), where


def _same_extra(old: str, new: str, where) -> None:
    """A row's extra column: a number to 10 % (a printed percentage also to half a unit of its last digit, so that
    "-0.00%" and "+0.00%" -- a deviation of 1e-6 whose sign the round-off picks -- agree), a label exactly."""
    if old.endswith("%") and new.endswith("%"):
        a, b = float(old[:-1]), float(new[:-1])
        decimals = len(old[:-1].partition(".")[2])
        assert abs(a - b) <= 0.1 * abs(b) + 0.5 * 10.0**-decimals, where
        return
    try:
        assert float(old) == pytest.approx(float(new), rel=0.1), where
    except ValueError:
        assert old == new.replace("|", "\\|"), where
