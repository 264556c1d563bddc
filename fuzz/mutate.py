"""Structural mutation of device descriptions, and the property every mutant must keep.

A seed file is split once into units the mutators understand: EDS sections, XDD
CANopenObject and parameter elements. A mutant is a slice of a seed (a few of its
objects, so inputs stay small and many) with one or more mutations applied, then
encoded in one of the encodings and line-end styles device files come in.

The property: reading, linting and writing back as EDS yields diagnostics or a model,
never an exception; a file without a model carries an error; the EDS written reads
back to the same EDS; the CPU time is bounded (a hang) and, in the fuzz run, linear
in the size.
"""

from __future__ import annotations

import hashlib
import random
import re
import signal
import time
import traceback
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from odgen.diagnostics import Severity
from odgen.formats import FORMATS, load_bytes
from odgen.formats.eds import COMMENT_KEYS
from odgen.formats.eds_writer import write_eds
from odgen.lint.driver import lint_model
from odgen.lint.passes import LintOptions

ROOT = Path(__file__).resolve().parents[1]
REPO_SEEDS = (ROOT / "tests" / "fixtures", ROOT / "examples")
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
REGRESSIONS = ROOT / "tests" / "fuzz" / "regressions"
HANG_SECONDS = 10.0  # CPU seconds for one input: inputs are a few KB and take milliseconds

# Values at the limits of the CiA 301 types, and text that is almost a number.
LIMITS = ("0", "-0", "1", "-1", "0x7F", "0x80", "0xFF", "0x100", "-128", "0x7FFF", "0x8000", "0xFFFF",
          "-32768", "0x10000", "0x7FFFFFFF", "0x80000000", "0xFFFFFFFF", "-2147483648", "0x100000000",
          "0xFFFFFFFFFFFF", "0x7FFFFFFFFFFFFFFF", "0x8000000000000000", "0xFFFFFFFFFFFFFFFF",
          "-9223372036854775809", "0x10000000000000000", "1" + "0" * 40, "9" * 400, "9" * 5000, "0x" + "F" * 300,
          "0" * 5000 + "1", "0x", "0x-1", "--1",
          "+5", "1e309", "-1e309", "nan", "inf", "1.5", "0b101", "017", "08", "0o17", "1_000", "0X1A", "#1",
          "١٢", "0x1F\x00", " 12 ", "")
NODEID = ("$NODEID", "$NODEID+0x180", "0x180+$NODEID", "$NODEID+", "+$NODEID", "$nodeid+0x200",
          "$NODEID*2", "$NODEID+$NODEID", "$NODEID-1", "$NODEID+0xFFFFFFFFFFFFFFFF", "$NODEIDx",
          "$NODEID+-5", "$ NODEID", "$NODEID+0x80000000", "0x600+$NODEID+1", "$NODEID+1e3", "$")
JUNK = ("", " ", "=", ";", "[", "]", "[]", "\t", "\x00", "\x1a", "é", "\u202e", "\ud7ff", "<", "&", "&amp;",
        "&#0;", "&#x110000;", "&#10;[1000]&#10;", "&#13;", "\x0c", "\x85", "\u2028", "]]>", "<!--", "\\",
        "\"", "'", "*/", "\n#define X 1\n", "%s%n", "A" * 300)
SECTION_NAMES = ("[1000]", "[1000sub0]", "[1A00sub1FF]", "[1018sub]", "[2000sub-1]", "[FFFF]", "[0000]",
                 "[1000Name]", "[1003Value]", "[MandatoryObjects]", "[FileInfo]", "[DeviceComissioning]",
                 "[DummyUsage]", "[M1ModuleInfo]", "[", "[]", "[1000", "[1A00subFE]", "[1F00sub00000001]")
KEYS = ("ParameterName", "ObjectType", "DataType", "AccessType", "DefaultValue", "LowLimit", "HighLimit",
        "PDOMapping", "ObjFlags", "SubNumber", "CompactSubObj", "ParameterValue", "SupportedObjects",
        "NrOfEntries", "NodeID", "1", "0x1", "Dummy0007", "BaudRate_125", "Granularity", "NrOfRXPDO")
ACCESS = ("ro", "wo", "rw", "rwr", "rww", "const", "RW", "r", "", "rw ", "readWrite")
ENCODINGS = ("utf-8", "utf-8", "utf-8", "utf-8-sig", "utf-16", "utf-16-le", "utf-16-be", "latin-1",
             "cp1252", "utf-32")
NEWLINES = ("\n", "\n", "\r\n", "\r", "mixed")

_EDS_SECTION = re.compile(r"^[ \t]*\[", re.M)
_XML_UNITS = (re.compile(r"<(?:\w+:)?CANopenObject\b[^>]*?(?:/>|>.*?</(?:\w+:)?CANopenObject>)\s*", re.S),
              re.compile(r"<(?:\w+:)?parameter\b[^>]*?(?:/>|>.*?</(?:\w+:)?parameter>)\s*", re.S),
              re.compile(r"<(?:\w+:)?struct\b[^>]*?(?:/>|>.*?</(?:\w+:)?struct>)\s*", re.S))
_ID_DEF = re.compile(r"\buniqueID=\"([^\"]*)\"")
_ID_REF = re.compile(r"\buniqueIDRef=\"([^\"]*)\"")
_COMMENT = re.compile(r"\s;.*$")
_NUMBER = re.compile(r"0[xX][0-9A-Fa-f]+|-?\b\d+\b")
_ATTR = re.compile(r"\s(\w+)=\"([^\"]*)\"")
_KEY_LINE = re.compile(r"^([^\[;#\n=][^=\n]*)=([^\n]*)$", re.M)


class Hang(BaseException):
    """Raised by the CPU timer; a BaseException so the readers' `except Exception` cannot swallow it."""


@dataclass
class Seed:
    name: str
    fmt: str
    frame: list[str]  # text around the unit groups: frame[0] group[0] frame[1] group[1] ... frame[-1]
    groups: list[list[str]]

    @property
    def size(self) -> int:
        return sum(map(len, self.frame)) + sum(len(u) for g in self.groups for u in g)


def decode(data: bytes) -> str:
    for encoding in ("utf-8-sig", "cp1252"):
        try:
            return data.decode(encoding)
        except UnicodeDecodeError:
            continue
    return data.decode("latin-1")


def split(name: str, fmt: str, text: str) -> Seed:
    if fmt in ("eds", "dcf"):
        starts = [m.start() for m in _EDS_SECTION.finditer(text)]
        units = [text[a:b] for a, b in zip(starts, starts[1:] + [len(text)], strict=False)]
        return Seed(name, fmt, [text[: starts[0]] if starts else text, ""], [units])
    runs = sorted((found for found in (list(p.finditer(text)) for p in _XML_UNITS) if found),
                  key=lambda found: found[0].start())
    frame, groups, pos = [], [], 0
    for found in runs:  # parameters come before the objects in most files, but not in all
        found = [m for m in found if m.start() >= pos]
        if found:
            frame.append(text[pos: found[0].start()])
            groups.append([m.group(0) for m in found])
            pos = found[-1].end()
    frame.append(text[pos:])
    return Seed(name, fmt, frame, groups)


def seed_files(with_corpus: bool = True) -> list[Path]:
    dirs = [*REPO_SEEDS, *([CORPUS] if with_corpus and CORPUS.is_dir() else [])]
    files = {p for d in dirs for p in d.rglob("*") if p.is_file() and p.suffix.lower() in FORMATS}
    return sorted(files)


def load_seeds(with_corpus: bool = True) -> list[Seed]:
    return [split(p.name, FORMATS[p.suffix.lower()], decode(p.read_bytes())) for p in seed_files(with_corpus)]


# -- mutations ------------------------------------------------------------------------------------------
# Each takes the text (or for unit mutations the unit groups) and the random source.

Units = list[list[str]]


def slice_units(groups: Units, rng: random.Random) -> Units:
    """A few units of each group, in their order: small inputs, many of them. XDD parameters
    are kept when a kept object refers to them (plus a few others), so slices still read."""
    out = [_sample(units, rng) if not _defines_ids(units) else units for units in groups]
    kept = "".join(u for units, mine in zip(out, groups, strict=True) if not _defines_ids(mine) for u in units)
    referenced = set(_ID_REF.findall(kept))
    for _ in range(2):  # objects name parameters, parameters name data types
        for i, units in enumerate(groups):
            if _defines_ids(units) and len(units) > 12:
                out[i] = [u for u in units if _unique_id(u) in referenced or rng.random() < 0.02]
                referenced.update(r for u in out[i] for r in _ID_REF.findall(u))
    return out


def _sample(units: list[str], rng: random.Random) -> list[str]:
    if len(units) <= 12:
        return list(units)
    return [units[i] for i in sorted(rng.sample(range(len(units)), rng.randint(1, 12)))]


def _defines_ids(units: list[str]) -> bool:
    return bool(units) and _unique_id(units[0]) is not None


def _unique_id(unit: str) -> str | None:
    match = _ID_DEF.search(unit, 0, 300)
    return match.group(1) if match else None


def _pick(groups: Units, rng: random.Random) -> list[str] | None:
    filled = [g for g in groups if g]
    return rng.choice(filled) if filled else None


def unit_delete(groups: Units, rng: random.Random) -> None:
    units = _pick(groups, rng)
    if units:
        del units[rng.randrange(len(units))]


def unit_duplicate(groups: Units, rng: random.Random) -> None:
    units = _pick(groups, rng)
    if units:
        units.insert(rng.randrange(len(units) + 1), rng.choice(units))


def unit_reorder(groups: Units, rng: random.Random) -> None:
    units = _pick(groups, rng)
    if units:
        rng.shuffle(units)


def _lines_op(text: str, rng: random.Random, op: Callable[[list[str], random.Random], None]) -> str:
    lines = text.split("\n")
    op(lines, rng)
    return "\n".join(lines)


def key_delete(text: str, rng: random.Random) -> str:
    return _on_key_line(text, rng, lambda line: "")


def key_duplicate(text: str, rng: random.Random) -> str:
    return _on_key_line(text, rng, lambda line: f"{line}\n{line}")


def key_reorder(text: str, rng: random.Random) -> str:
    def swap(lines: list[str], rng: random.Random) -> None:
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    return _lines_op(text, rng, swap)


def key_case(text: str, rng: random.Random) -> str:
    return _on_key_line(text, rng, lambda line: line.upper() if rng.random() < 0.5 else line.lower())


def key_value(text: str, rng: random.Random) -> str:
    """An EDS value or XML attribute replaced: limits, $NODEID forms, access words, junk."""
    pool = rng.choice((LIMITS, NODEID, ACCESS, JUNK))
    value = rng.choice(pool)
    if "=\"" in text and rng.random() < 0.7:
        return _on_match(_ATTR, text, rng, lambda m: f' {m.group(1)}="{value}"')
    return _on_key_line(text, rng, lambda line: line.split("=", 1)[0] + "=" + value)


def key_insert(text: str, rng: random.Random) -> str:
    line = f"{rng.choice(KEYS)}={rng.choice(LIMITS + NODEID)}"
    return _lines_op(text, rng, lambda lines, r: lines.insert(r.randrange(len(lines) + 1), line))


def section_insert(text: str, rng: random.Random) -> str:
    head = rng.choice(SECTION_NAMES)
    return _lines_op(text, rng, lambda lines, r: lines.insert(r.randrange(len(lines) + 1), head))


def number_limit(text: str, rng: random.Random) -> str:
    return _on_match(_NUMBER, text, rng, lambda m: rng.choice(LIMITS))


def nodeid(text: str, rng: random.Random) -> str:
    return _on_match(_NUMBER, text, rng, lambda m: rng.choice(NODEID))


def attr_delete(text: str, rng: random.Random) -> str:
    return _on_match(_ATTR, text, rng, lambda m: "")


def attr_duplicate(text: str, rng: random.Random) -> str:
    return _on_match(_ATTR, text, rng, lambda m: m.group(0) * 2)


def xml_markup(text: str, rng: random.Random) -> str:
    """Markup that strains an XML reader: entities, CDATA, comments, deep nesting, a DOCTYPE."""
    depth = rng.choice((10, 300, 3000))
    pieces = ("&ent;", "<![CDATA[x]]>", "<!-- c -->", "<?pi x?>", "<a>" * depth + "</a>" * depth,
              '<!DOCTYPE x [<!ENTITY ent "&#x41;">]>', "<x:y/>", "\x00", "&#xD800;", "</ObjectList>")
    pos = rng.randrange(len(text) + 1)
    return text[:pos] + rng.choice(pieces) + text[pos:]


def truncate(text: str, rng: random.Random) -> str:
    return text[: rng.randrange(len(text) + 1)]


def span_delete(text: str, rng: random.Random) -> str:
    a = rng.randrange(len(text) + 1)
    return text[:a] + text[a + rng.randint(1, 64):]


def span_duplicate(text: str, rng: random.Random) -> str:
    a = rng.randrange(len(text) + 1)
    return text[:a] + text[a: a + rng.randint(1, 256)] + text[a:]


def junk_insert(text: str, rng: random.Random) -> str:
    a = rng.randrange(len(text) + 1)
    return text[:a] + rng.choice(JUNK) + text[a:]


def _on_key_line(text: str, rng: random.Random, edit: Callable[[str], str]) -> str:
    return _on_match(_KEY_LINE, text, rng, lambda m: edit(m.group(0)))


def _on_match(pattern: re.Pattern[str], text: str, rng: random.Random, edit: Callable[[re.Match[str]], str]) -> str:
    found = list(pattern.finditer(text))
    if not found:
        return text
    m = rng.choice(found)
    return text[: m.start()] + edit(m) + text[m.end():]


UNIT_OPS = {"unit-delete": unit_delete, "unit-duplicate": unit_duplicate, "unit-reorder": unit_reorder}
TEXT_OPS: dict[str, Callable[[str, random.Random], str]] = {
    "key-delete": key_delete, "key-duplicate": key_duplicate, "key-reorder": key_reorder, "key-case": key_case,
    "key-value": key_value, "key-insert": key_insert, "section-insert": section_insert,
    "number-limit": number_limit, "nodeid": nodeid, "truncate": truncate, "span-delete": span_delete,
    "span-duplicate": span_duplicate, "junk-insert": junk_insert}
XML_OPS: dict[str, Callable[[str, random.Random], str]] = {
    "attr-delete": attr_delete, "attr-duplicate": attr_duplicate, "xml-markup": xml_markup}
BYTE_OPS = ("byte-flip", "byte-insert")
OPS = (*UNIT_OPS, *TEXT_OPS, *XML_OPS, *BYTE_OPS)


@dataclass
class Mutant:
    seed: str
    fmt: str
    data: bytes
    ops: list[str]


def mutate(seed: Seed, rng: random.Random) -> Mutant:
    groups = slice_units(seed.groups, rng)
    ops: list[str] = []
    for _ in range(_count(rng)):
        if rng.random() < 0.25 and groups:
            name = rng.choice(list(UNIT_OPS))
            UNIT_OPS[name](groups, rng)
            ops.append(name)
    text = _join(seed.frame, groups)
    table = {**TEXT_OPS, **(XML_OPS if seed.fmt in ("xdd", "xdc") else {})}
    for _ in range(_count(rng)):
        name = rng.choice(list(table))
        text = table[name](text, rng)
        ops.append(name)
    data, encoding = encode(text, seed.fmt, rng)
    ops.extend(encoding.split())
    if rng.random() < 0.1:
        data, op = _byte_op(data, rng)
        ops.append(op)
    return Mutant(seed.name, seed.fmt, data, ops)


def _count(rng: random.Random) -> int:
    n = 1
    while n < 8 and rng.random() < 0.4:
        n += 1
    return n


def _join(frame: list[str], groups: Units) -> str:
    parts = [frame[0]]
    for units, after in zip(groups, frame[1:], strict=False):
        parts.extend(units)
        parts.append(after)
    return "".join(parts)


def encode(text: str, fmt: str, rng: random.Random) -> tuple[bytes, str]:
    newline = rng.choice(NEWLINES)
    if newline == "mixed":
        text = "".join(line + rng.choice(("\n", "\r\n", "\r")) for line in text.split("\n"))
    elif newline != "\n":
        text = text.replace("\n", newline)
    encoding = rng.choice(ENCODINGS)
    if fmt in ("xdd", "xdc") and rng.random() < 0.3:
        text = re.sub(r'encoding="[^"]*"', f'encoding="{rng.choice(ENCODINGS)}"', text, count=1)
    eol = {"\n": "LF", "\r\n": "CRLF", "\r": "CR"}.get(newline, newline)
    return text.encode(encoding, errors="replace"), f"enc:{encoding} eol:{eol}"


def _byte_op(data: bytes, rng: random.Random) -> tuple[bytes, str]:
    pos = rng.randrange(len(data) + 1)
    if rng.random() < 0.5 and pos < len(data):
        return data[:pos] + bytes([data[pos] ^ (1 << rng.randrange(8))]) + data[pos + 1:], "byte-flip"
    return data[:pos] + bytes(rng.randrange(256) for _ in range(rng.randint(1, 8))) + data[pos:], "byte-insert"


# -- the property -----------------------------------------------------------------------------------------


@dataclass
class Outcome:
    model: bool
    failure: str | None  # a signature when the property broke: exception type and where it was raised
    ns: int  # wall time: the CPU clock here ticks in milliseconds; re-measures take the best
    detail: str = ""


def check(data: bytes, fmt: str, hang_seconds: float = HANG_SECONDS) -> Outcome:
    """Read, lint and write back one input under a CPU-time limit."""
    previous = signal.signal(signal.SIGPROF, _on_timer)
    signal.setitimer(signal.ITIMER_PROF, hang_seconds)
    start = time.perf_counter_ns()
    try:
        model, failure, detail = _property(data, fmt)
    except Hang:
        model, failure, detail = False, "hang", f"over {hang_seconds:g} s of CPU"
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
    return Outcome(model, failure, time.perf_counter_ns() - start, detail)


def _on_timer(signum, frame) -> None:
    raise Hang()


def _property(data: bytes, fmt: str) -> tuple[bool, str | None, str]:
    try:
        od, diags = load_bytes(data, f"fuzz.{fmt}", fmt)
        written = None
        if od is not None:
            lint_model(od, diags, LintOptions())
            written = write_eds(od)
        texts = [d.text() for d in diags.sorted()]
        unstable = _unstable_key(written) if written is not None else None
        if unstable is not None:
            return True, f"convert-not-stable:{unstable}", (written or "")[-2000:]
    except Exception as err:  # the property under test: no exception escapes
        return False, signature(err), "".join(traceback.format_exception(err))[-3000:]
    if od is None and not any(d.severity >= Severity.ERROR for d in diags):
        return False, "no-model-without-error", "\n".join(texts)[-2000:]
    if any(d.loc.line < 0 for d in diags):
        return od is not None, "bad-location", "\n".join(texts)[-2000:]
    return od is not None, None, ""


def _unstable_key(written: str) -> str | None:
    """What `odgen convert` writes must read back to the same model: writing it again gives the same
    text. None when it does, else the key of the first line that differs.

    Two limits of INI, which has no quoting, are the exception: readers drop blanks at either end
    of a value (an XDD string padded with spaces loses the padding in EDS form) and take ` ;` and
    what follows for a comment (an XDD name `a ;b` is `a` in EDS form, reported as SYN014). And
    comments are no data: the `;Key=Value` lines convert writes for an XDD's own properties
    (CANopenEditor's CO_flagsPDO ...) are for the reader of the file, and an EDS reader skips them;
    only the comment keys the EDS reader reads (`;StorageLocation=` ...) are compared."""
    again, _ = load_bytes(written.encode("utf-8"), "converted.eds", "eds")
    if again is None:
        return "unreadable"
    first, second = _trimmed(written), _trimmed(write_eds(again))
    if first == second:
        return None
    diff = next((a or b for a, b in zip(first, second, strict=False) if a != b), "length")
    return re.sub(r"[^A-Za-z]+", "", diff.partition("=")[0])[:20] or "section"


def _trimmed(text: str) -> list[str]:
    return [key.strip() + eq + _COMMENT.sub("", value).strip()
            for key, eq, value in (line.partition("=") for line in text.split("\n"))
            if not key.startswith(";") or key[1:].strip().lower() in COMMENT_KEYS]


def signature(err: BaseException) -> str:
    frames = [f for f in traceback.extract_tb(err.__traceback__) if "/odgen/" in f.filename]
    where = f"{Path(frames[-1].filename).name}:{frames[-1].lineno}" if frames else "?"
    return f"{type(err).__name__}@{where}"


def save_regression(data: bytes, fmt: str, failure: str) -> Path:
    """Keep a finding as a regression input, named after its content."""
    digest = hashlib.sha1(data).hexdigest()[:12]
    kind = re.sub(r"[^A-Za-z0-9]+", "-", failure).strip("-").lower()[:40]
    path = REGRESSIONS / f"{kind}-{digest}.{fmt}"
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists():
        path.write_bytes(data)
    return path


def minimise(data: bytes, fmt: str, failure: str, budget: int = 300) -> bytes:
    """Drop line chunks while the same failure remains (ddmin over lines, bounded attempts)."""
    lines = data.splitlines(keepends=True)
    chunk = max(1, len(lines) // 2)
    tries = 0
    while chunk >= 1 and tries < budget:
        i, shrunk = 0, False
        while i < len(lines) and tries < budget:
            candidate = lines[:i] + lines[i + chunk:]
            tries += 1
            if candidate and check(b"".join(candidate), fmt, 2.0).failure == failure:
                lines, shrunk = candidate, True
            else:
                i += chunk
        if not shrunk:
            chunk //= 2
    return b"".join(lines)


def mutants(seeds: list[Seed], rng: random.Random, count: int) -> Iterable[Mutant]:
    for _ in range(count):
        yield mutate(rng.choice(seeds), rng)
