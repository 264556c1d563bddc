"""The one sanitizer for every string that reaches C: identifiers, comments, literals."""

from __future__ import annotations

import functools
import re

C_KEYWORDS = frozenset(
    """
auto break case char const continue default do double else enum extern float for goto if inline int
long register restrict return short signed sizeof static struct switch typedef union unsigned void
volatile while _Bool _Complex _Imaginary bool true false NULL
""".split()  # noqa: SIM905
)

MAX_IDENT = 48
_IDENT_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@functools.lru_cache(maxsize=8192)  # generation asks for the same names many times over
def identifier(text: str, fallback: str = "entry") -> str:
    """A lower-case C identifier from free text: `Vendor-ID` -> `vendor_id`."""
    words = re.findall(r"[A-Za-z0-9]+", text.encode("ascii", "ignore").decode())
    ident = "_".join(w.lower() for w in words)[:MAX_IDENT].strip("_") or fallback
    if ident[0].isdigit():
        ident = "n" + ident
    if ident in C_KEYWORDS or ident.startswith("__"):
        ident += "_"
    return ident


def is_identifier(text: str) -> bool:
    return bool(_IDENT_RE.match(text)) and text not in C_KEYWORDS and not text.startswith("__")


@functools.lru_cache(maxsize=8192)
def comment(text: str, width: int = 60) -> str:
    """Text safe inside /* */: no comment terminators, no line breaks, printable ASCII."""
    flat = " ".join(text.split())
    if not (flat.isascii() and flat.isprintable()):  # the common case needs no per-character pass
        flat = "".join(c if 32 <= ord(c) < 127 else "?" for c in flat)
    safe = flat
    if "*" in safe or "/" in safe or "\\" in safe:
        safe = safe.replace("*/", "* /").replace("/*", "/ *").replace("\\", "/")
    return safe if len(safe) <= width else safe[: width - 3] + "..."


def string_literal(data: bytes) -> str:
    """A C string literal for raw bytes: printable ASCII kept, the rest octal-escaped."""
    out = []
    for byte in data:
        char = chr(byte)
        if char in '"\\':
            out.append("\\" + char)
        elif char == "?":
            out.append("\\?")  # no trigraphs
        elif 32 <= byte < 127:
            out.append(char)
        else:
            out.append(f"\\{byte:03o}")
    return '"' + "".join(out) + '"'
