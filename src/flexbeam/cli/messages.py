"""Messages on stderr: one line each, whatever the text they quote."""

from __future__ import annotations


def one_line(message: object) -> str:
    """``message`` (an exception or text) on one line: a newline, e.g. in a quoted TOML key, is escaped."""
    return str(message).replace("\r", "\\r").replace("\n", "\\n")
