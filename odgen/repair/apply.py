"""Line edits of an EDS/DCF: what `odgen fix` writes, changing only the lines a repair names.

The file is edited as bytes read as Latin-1 (one character per byte), so lines no repair names
are written back byte for byte whatever their encoding, and the file's line ends are kept.
"""

from __future__ import annotations

from dataclasses import dataclass

SET, DELETE, ADD_KEY, INSERT_BEFORE = "set", "delete", "add_key", "insert_before"


@dataclass(frozen=True)
class Edit:
    """One change of the text. `line` is 1-based.

    set: the `Key=value` line at `line` gets `text` as its value (the key as written is kept);
    delete: the line goes; add_key: `Key=text` follows the last line of the section whose header
    is at `line`; insert_before: the `lines` come before `line` (a new section)."""

    kind: str
    line: int
    key: str = ""
    text: str = ""
    lines: tuple[str, ...] = ()


def _section_end(lines: list[str], header: int) -> int:
    """The 0-based index of the last key line of the section whose header is at 0-based `header`."""
    last = header
    for i in range(header + 1, len(lines)):
        text = lines[i].strip()
        if text.startswith("["):
            break
        if text and not text.startswith(";"):
            last = i
    return last


def apply_edits(data: bytes, edits: list[Edit]) -> bytes:
    """The file with the edits made, in their order (a later `set` of a line wins); a `set` of a line that
    is no `Key=value` is skipped.

    Lines are split at LF only (a CR stays with its line), so no other byte is taken for a line end."""
    lines = data.decode("latin-1").split("\n")
    cr = "\r" if lines and lines[0].endswith("\r") else ""
    replaced: dict[int, str | None] = {}
    before: dict[int, list[str]] = {}
    after: dict[int, list[str]] = {}
    for edit in edits:
        i = edit.line - 1
        if not 0 <= i < len(lines):
            continue
        if edit.kind == SET and "=" in lines[i]:
            key = lines[i].partition("=")[0]
            replaced[i] = f"{key}={edit.text}" + ("\r" if lines[i].endswith("\r") else "")
        elif edit.kind == DELETE:
            replaced[i] = None
        elif edit.kind == ADD_KEY:
            after.setdefault(_section_end(lines, i), []).append(f"{edit.key}={edit.text}{cr}")
        elif edit.kind == INSERT_BEFORE:
            before.setdefault(i, []).extend(f"{line}{cr}" for line in edit.lines)
    out: list[str] = []
    for i, line in enumerate(lines):
        out += before.get(i, [])
        new = replaced.get(i, line)
        if new is not None:
            out.append(new)
        out += after.get(i, [])
    return "\n".join(out).encode("latin-1", errors="replace")
