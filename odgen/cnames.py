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

# Names a dictionary (its files NAME.h/NAME.c, its symbols NAME and NAME_*) must not take: the C99
# headers (a generated stdint.h would shadow <stdint.h>, as -I puts the output folder first), and the
# library identifiers the generated C, the runtime or `odgen check`'s self-test declare or call.
C_HEADERS = frozenset(
    """
assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal stdarg stdbool stddef
stdint stdio stdlib string tgmath time wchar wctype
""".split()  # noqa: SIM905
)
C_LIBRARY = frozenset(
    """
main errno offsetof size_t ptrdiff_t wchar_t intptr_t uintptr_t intmax_t uintmax_t int8_t int16_t int32_t int64_t
uint8_t uint16_t uint32_t uint64_t memcpy memset memcmp memmove memchr strlen strcmp strncmp strcpy strncpy strcat
strchr strrchr strstr printf fprintf sprintf snprintf puts putchar fputs fflush fopen fclose fread fwrite
stdin stdout stderr malloc calloc realloc free exit abort atexit qsort bsearch abs labs atoi atol strtol strtoul
strtod fabs floor ceil sqrt pow isnan isinf signal raise va_list jmp_buf FILE EOF
""".split()  # noqa: SIM905
)

MAX_IDENT = 48
_IDENT_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_WORD_RE = re.compile(r"[a-z0-9]+")  # the words of an identifier, in lower case


@functools.lru_cache(maxsize=8192)  # generation asks for the same names many times over
def identifier(text: str, fallback: str = "entry") -> str:
    """A lower-case C identifier from free text: `Vendor-ID` -> `vendor_id`."""
    ascii_text = text if text.isascii() else text.encode("ascii", "ignore").decode()
    ident = "_".join(_WORD_RE.findall(ascii_text.lower()))[:MAX_IDENT].strip("_") or fallback
    if ident[0].isdigit():
        ident = "n" + ident
    if ident in C_KEYWORDS or ident.startswith("__"):
        ident += "_"
    return ident


def name_clash(name: str) -> str | None:
    """Why `name` cannot name a dictionary, or None when it can."""
    if name.lower() == "odg" or name.lower().startswith("odg_"):
        return "would clash with the runtime (odg.h, odg_* and ODG_* names)"
    if name in C_HEADERS:
        return f"would make {name}.h shadow the C library's <{name}.h>"
    if name in C_LIBRARY:
        return "is a name of the C library"
    if name.startswith("_") and name[1:2].isupper():
        return "is reserved to the C implementation (underscore and capital)"
    return None


def is_identifier(text: str) -> bool:
    return bool(_IDENT_RE.match(text)) and text not in C_KEYWORDS and not text.startswith("__")


COMMENT_WIDTH = 60


@functools.lru_cache(maxsize=8192)
def comment(text: str, width: int = COMMENT_WIDTH) -> str:
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
