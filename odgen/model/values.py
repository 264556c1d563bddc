"""Literal values as written in descriptions, parsed against a data type.

CiA 306 numbers follow C `strtoul(..., 0)`: decimal, `0x` hex, leading-`0` octal,
with a sign for signed types. Integer entries may be `$NODEID`-relative; the
canonical form is `$NODEID+<number>`, but real files also write
`<number>+$NODEID`, lowercase, and spaces, which are read and noted.
"""

from __future__ import annotations

import math
import re
import struct
from dataclasses import dataclass, field
from functools import lru_cache

from ..catalogue.rule import Rule
from ..catalogue.syntax import SYN006, SYN007, SYN008, SYN009, SYN020
from .datatypes import BASIC_TYPES, DataType

# (rule, message) pairs a reader turns into located diagnostics.
Note = tuple[Rule, str]

MAX_DIGITS = 64  # significant digits of an integer literal; 64-bit values need 20 decimal or 16 hex
_HEX_DIGITS = "0123456789abcdefABCDEF"
_INT_RE = re.compile(r"^([+-]?)(0[xX][0-9a-fA-F]+|[0-9]+)$")
_C_SUFFIX = re.compile(r"(?<=[0-9a-fA-F])(?:[uU](?:ll|LL|l|L)?|(?:ll|LL|l|L)[uU]?)$")  # 0x1234LL, 10u
_NODEID_RE = re.compile(r"\$nodeid", re.IGNORECASE)
_PREFIX_FORM = re.compile(r"^\$NODEID(\+.+)?$")
_TIME_PAIR_RE = re.compile(r"^(\d+)\s+(\d+)$")
_FLOAT_RE = re.compile(r"^[+-]?(\d+\.?\d*([eE][+-]?\d+)?|\.\d+([eE][+-]?\d+)?|inf|nan)$", re.I)


@dataclass(slots=True)
class Value:
    """A value as written (`text`) and as understood (`parsed`).

    For a `$NODEID`-relative value `parsed` is the offset added to the node-id.
    `error` says why the text could not be read as the entry's data type.
    """

    text: str
    line: int = field(default=0, compare=False)
    parsed: int | float | str | bytes | None = None
    nodeid: bool = False
    error: str | None = None
    notes: tuple[Note, ...] = field(default=(), compare=False, repr=False)  # a tuple: most values have none

    def resolve(self, node_id: int) -> int | float | str | bytes | None:
        if self.nodeid and isinstance(self.parsed, int):
            return self.parsed + node_id
        return self.parsed

    @property
    def empty(self) -> bool:
        return self.text.strip() == ""


def bounded_int(digits: str, base: int = 10) -> int | None:
    """int(digits, base), or None past MAX_DIGITS significant digits: no CiA 301 type holds such a
    number, and Python refuses to convert decimals of more than 4300 digits either way."""
    significant = digits.lstrip("0")
    return int(significant or "0", base) if len(significant) <= MAX_DIGITS else None


@lru_cache(maxsize=1 << 16)
def parse_int_literal(text: str) -> tuple[int | None, tuple[Note, ...]]:
    """Read one integer literal; None when it is not one.

    Cached: a description repeats a few literals (0x7, 0x0007, 0, 1, rw) thousands of times, and the
    rules read each object list entry (its number and its index) more than once: room for all of them."""
    stripped = text.strip()
    # the two common forms without the regex: plain decimal and unsigned hex
    if stripped.isdigit() and stripped.isascii() and (stripped[0] != "0" or len(stripped) == 1):
        return (int(stripped) if len(stripped) <= MAX_DIGITS else None), ()
    if stripped[:2] in ("0x", "0X") and len(stripped) > 2 and not stripped[2:].lstrip(_HEX_DIGITS):
        return bounded_int(stripped[2:], 16), ()
    m = _INT_RE.match(stripped)
    if not m:
        return None, ()
    sign, digits = m.groups()
    notes: tuple[Note, ...] = ()
    if digits[:2] in ("0x", "0X"):
        value = bounded_int(digits[2:], 16)
    elif len(digits) > 1 and digits[0] == "0":
        value, notes = _leading_zero(digits)
    else:
        value = bounded_int(digits)
    if value is None:
        return None, ()
    return (-value if sign == "-" else value), notes


def _leading_zero(digits: str) -> tuple[int | None, tuple[Note, ...]]:
    """`001` is octal in CiA 306 (strtoul base 0); say so when it matters."""
    decimal = bounded_int(digits)
    if decimal is None:
        return None, ()
    if any(c in "89" for c in digits):
        return decimal, ((SYN006, f"'{digits}' has a leading zero but is not octal; read as {decimal}"),)
    octal = int(digits.lstrip("0") or "0", 8)  # as long as the decimal, which is bounded
    if octal != decimal:
        return octal, ((SYN006, f"'{digits}' is octal ({octal}) under CiA 306, not {decimal}"),)
    return octal, ()


def split_nodeid(text: str) -> tuple[bool, str, list[Note]]:
    """Remove a `$NODEID` term; returns (relative, remaining number text, notes)."""
    if not _NODEID_RE.search(text):
        return False, text, []
    compact = re.sub(r"\s+", "", text)
    notes: list[Note] = []
    if not _PREFIX_FORM.match(compact) or compact != text.strip():
        notes.append((SYN007, f"'{text.strip()}' is not the CiA 306 form $NODEID+<number>"))
    rest = _NODEID_RE.sub("", compact, count=1)
    rest = rest.strip("+") if rest.count("+") <= 1 else rest
    return True, rest or "0", notes


def _without_c_suffix(value: Value, text: str) -> str:
    """CANopenNode's files write INTEGER64 defaults with C's `LL`: read the number, note the suffix."""
    suffix = _C_SUFFIX.search(text)
    if suffix is None or _INT_RE.match(text[: suffix.start()].strip()) is None:
        return text
    value.notes += ((SYN020, f"'{text}': C suffix '{suffix.group()}' dropped; CiA 306 numbers have none"),)
    return text[: suffix.start()]


def parse_value(text: str, dtype: DataType | None, line: int = 0) -> Value:
    """Parse `text` as a value of `dtype`; never raises.

    What a text means for a basic type is remembered: a description repeats a few values (0, 0x00000000,
    $NODEID+0x180) thousands of times."""
    if dtype is None or BASIC_TYPES.get(dtype.code) is not dtype:
        return _parse_value(text, dtype, line)
    known = _PARSED.get((dtype.code, text))
    if known is None:
        value = _parse_value(text, dtype, line)
        if len(text) <= _PARSED_TEXT and len(_PARSED) < _PARSED_KEPT:
            _PARSED[dtype.code, text] = (value.parsed, value.nodeid, value.error, value.notes)
        return value
    parsed, nodeid, error, notes = known
    return Value(text, line, parsed, nodeid, error, notes)


# (data type, text) -> what parse_value found: parsed, nodeid, error, notes (immutable, so shared)
_PARSED: dict[tuple[int, str], tuple[int | float | str | bytes | None, bool, str | None, tuple[Note, ...]]] = {}
_PARSED_KEPT, _PARSED_TEXT = 1 << 16, 64  # entries and text length remembered: memory stays bounded


def _parse_value(text: str, dtype: DataType | None, line: int) -> Value:
    value = Value(text=text, line=line)
    stripped = text.strip()
    if dtype is None or (stripped == "" and not dtype.is_string):
        return value  # an empty number is "no value"; an empty string is ""
    reader = _READERS.get(dtype.kind, _read_text)
    reader(value, stripped, dtype)
    return value


def _read_integer(value: Value, text: str, dtype: DataType) -> None:
    relative, rest, notes = split_nodeid(text)
    value.nodeid = relative
    value.notes += tuple(notes)
    rest = _without_c_suffix(value, rest)
    number, int_notes = parse_int_literal(rest)
    value.notes += int_notes
    if number is None:
        number = _bool_word(rest) if dtype.kind == "bool" else None
    if number is None:
        value.error = f"'{text}' is not an integer"
        return
    value.parsed = _twos_complement(value, number, rest, dtype)


def _read_time(value: Value, text: str, dtype: DataType) -> None:
    """TIME_OF_DAY/TIME_DIFFERENCE: one number, or Lely's `<days> <ms>` pair."""
    pair = _TIME_PAIR_RE.match(text)
    if pair is None:
        _read_integer(value, text, dtype)
        return
    days, ms = bounded_int(pair.group(1)), bounded_int(pair.group(2))
    if days is None or ms is None or ms >= 1 << 28 or days >= 1 << 16:
        value.error = f"'{text}' is not <days 0..65535> <ms 0..268435455>"
        return
    value.parsed = (days << 32) | ms  # ms in the low 28 bits, days in bytes 4-5


def _bool_word(text: str) -> int | None:
    return {"true": 1, "false": 0}.get(text.lower())


def _twos_complement(value: Value, number: int, text: str, dtype: DataType) -> int:
    """A signed entry written as unsigned hex (0xFFFF for -1) means its bit pattern."""
    if dtype.kind != "int" or not text.lower().startswith("0x"):
        return number
    top = 1 << dtype.bits
    if (dtype.max or 0) < number < top:
        value.notes += ((SYN008, f"'{text}' read as the {dtype.bits}-bit two's complement {number - top}"),)
        return number - top
    return number


def _read_real(value: Value, text: str, dtype: DataType) -> None:
    if _FLOAT_RE.match(text):
        value.parsed = float(text)
        return
    number, notes = parse_int_literal(text)
    if number is None:
        value.error = f"'{text}' is not a number"
        return
    if text.lower().lstrip("+-").startswith("0x"):
        value.parsed = _bits_to_real(number, dtype.bits)
        value.notes += ((SYN009, f"'{text}' read as an IEEE 754 bit pattern = {value.parsed!r}"),)
    else:
        value.parsed = float(number)
    value.notes += notes


def _bits_to_real(number: int, bits: int) -> float:
    fmt, ifmt = ("!f", "!I") if bits == 32 else ("!d", "!Q")
    try:
        result = struct.unpack(fmt, struct.pack(ifmt, number))[0]
    except struct.error:
        return math.nan
    return float(result)


def _read_octets(value: Value, text: str, dtype: DataType) -> None:
    digits = re.sub(r"\s+", "", text)
    if digits[:2].lower() == "0x":
        digits = digits[2:]
    if len(digits) % 2 or not re.fullmatch(r"[0-9a-fA-F]*", digits):
        value.error = f"'{text}' is not a sequence of hex bytes"
        return
    value.parsed = bytes.fromhex(digits)


def _read_text(value: Value, text: str, dtype: DataType) -> None:
    value.parsed = value.text


_READERS = {
    "bool": _read_integer,
    "int": _read_integer,
    "uint": _read_integer,
    "time": _read_time,
    "real": _read_real,
    "ostring": _read_octets,
    "vstring": _read_text,
    "ustring": _read_text,
    "domain": _read_text,
}


def number(value: Value | None) -> int | float | None:
    """A value's parsed number (the offset for `$NODEID` values), None if not a number."""
    if value is None or value.error or isinstance(value.parsed, bool):
        return None
    return value.parsed if isinstance(value.parsed, (int, float)) else None


def plain_int(value: Value | None) -> int | None:
    """A value's integer when it is one and not relative to the node-id, else None."""
    n = number(value)
    return n if isinstance(n, int) and value is not None and not value.nodeid else None
