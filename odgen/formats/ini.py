"""An INI reader that knows nothing of CANopen but keeps what configparser drops.

It keeps line numbers, the spelling of names, duplicates (reported, first wins),
and `;Key=Value` comment lines (CANopenNode writes `;StorageLocation=RAM`).
Decoding: UTF-8 with or without BOM; UTF-16/32 when a BOM or the NUL bytes of an
ASCII start say so (reported); else Windows-1252 (reported).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import NamedTuple

from ..catalogue.syntax import SYN001, SYN002, SYN003, SYN004, SYN005, SYN014, SYN021
from ..diagnostics import Diagnostics, Loc

_SECTION_RE = re.compile(r"^\[([^\]]*)\]\s*(?:[;#].*)?$")
_COMMENT_KEY_RE = re.compile(r"^;\s*([A-Za-z_][A-Za-z0-9_]*)\s*=(.*)$")
_INLINE_COMMENT_RE = re.compile(r"\s+;.*$")
_NAMES_KEPT = 4096
# Keys one section may hold: an object list names at most 65535 indices (plus SupportedObjects); no
# CiA 306 section needs more, and a file of millions of short keys would otherwise fill memory.
MAX_KEYS = 65600
# Keys one file may hold: more than a 16 MiB description of real objects has (its lines are longer
# than 16 bytes); the bound keeps the memory of any accepted file under 20 times its size.
MAX_FILE_KEYS = 1_000_000


class IniEntry(NamedTuple):
    """One key of a section, as IniSection.get() and IniSection.entries() give it."""

    key: str  # as written
    value: str
    line: int


@dataclass(slots=True)
class IniSection:
    """A section's keys (first wins) in three dicts by lower-case key, in file order: a section is
    mostly read key by key, and its values and lines are what the model keeps."""

    name: str
    line: int
    values: dict[str, str] = field(default_factory=dict)
    lines: dict[str, int] = field(default_factory=dict)
    keys: dict[str, str] = field(default_factory=dict)  # the key as written
    commented: set[str] = field(default_factory=set)  # keys written as ";Key=Value"

    def get(self, key: str) -> IniEntry | None:
        lower = key.lower()
        return self.entry(lower) if lower in self.values else None

    def value(self, key: str) -> str | None:
        return self.values.get(key.lower())

    def entry(self, lower: str) -> IniEntry:
        """The entry of a lower-case key the section has."""
        return IniEntry(self.keys[lower], self.values[lower], self.lines[lower])

    def entries(self) -> Iterator[tuple[str, IniEntry]]:
        """(lower-case key, entry) of every key in file order."""
        keys, lines = self.keys, self.lines
        for lower, value in self.values.items():
            yield lower, IniEntry(keys[lower], value, lines[lower])

    def put(self, lower: str, key: str, value: str, line: int) -> None:
        self.values[lower], self.lines[lower], self.keys[lower] = value, line, key


_BOMS = ((b"\xff\xfe\x00\x00", "utf-32-le"), (b"\x00\x00\xfe\xff", "utf-32-be"),
         (b"\xff\xfe", "utf-16-le"), (b"\xfe\xff", "utf-16-be"))


def decode(data: bytes, source: str, diags: Diagnostics) -> str:
    wide = _wide(data)
    if wide is not None:
        encoding, skip = wide
        try:
            text = data[skip:].decode(encoding)
        except UnicodeDecodeError:
            pass  # not what it looked like: read it as bytes below
        else:
            diags.add(SYN004, Loc(source, 1), f"file is {encoding.upper()}, not UTF-8; read as such")
            return text
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        diags.add(SYN004, Loc(source, line), "file is not UTF-8; read as Windows-1252")
    # cp1252 leaves five bytes undefined; read those as Latin-1 so decoding never fails
    return "".join(_cp1252_char(b) for b in data)


def _wide(data: bytes) -> tuple[str, int] | None:
    """UTF-16/32 by its BOM, or UTF-16 without one when an ASCII first character has a NUL beside it."""
    for bom, encoding in _BOMS:
        if data.startswith(bom):
            return encoding, len(bom)
    if len(data) >= 4 and data[0] and not data[1] and data[2] and not data[3]:
        return "utf-16-le", 0
    if len(data) >= 4 and not data[0] and data[1] and not data[2] and data[3]:
        return "utf-16-be", 0
    return None


def _cp1252_char(byte: int) -> str:
    try:
        return bytes([byte]).decode("cp1252")
    except UnicodeDecodeError:
        return chr(byte)


def sections(text: str, source: str, diags: Diagnostics, comment_keys: frozenset[str] = frozenset(),
             seen: dict[str, int] | None = None) -> Iterator[tuple[str, IniSection]]:
    """The sections of INI text in file order as (lower-case name, section), each once it is complete,
    so a reader can convert and drop it: a large file is never held as entries and model at once.
    A repeated section is reported and left out; at most MAX_KEYS keys of a section are kept.
    `seen` collects the lower-case name and line of every section read so far."""
    seen = {} if seen is None else seen
    reader = _SectionReader(source, diags, comment_keys)
    for number, lines in _parts(text):
        yield from reader.read(lines, number, seen)
    done = reader.close()
    if done is not None:
        yield done
    reader.finish()


class _SectionReader:
    """The section being read: its keys, and the keys past MAX_KEYS that are counted, not kept."""

    def __init__(self, source: str, diags: Diagnostics, comment_keys: frozenset[str]) -> None:
        self.source, self.diags, self.comment_keys = source, diags, comment_keys
        self.section: IniSection | None = None
        self.key = ""  # the open section's name in lower case
        self.kept = False  # False for a repeated section, read but left out
        # the open section's dicts (before the first section: dicts nothing reads)
        self.values: dict[str, str] = {}
        self.lines: dict[str, int] = {}
        self.keys: dict[str, str] = {}
        self.names: dict[str, tuple[str, str]] = {}  # a key as written -> (that key, lower case)
        self.dropped, self.first_dropped = 0, 0
        self.total = 0  # keys kept in the whole file
        self.room = 0  # keys the open section may still keep under both caps (0 before any section)
        self.file_dropped, self.file_first_dropped = 0, 0

    def open(self, name: str, line: int, seen: dict[str, int]) -> None:
        key = self.key = name.lower()
        self.values, self.lines, self.keys = {}, {}, {}
        self.section = IniSection(name, line, self.values, self.lines, self.keys, set())
        self.room = min(MAX_KEYS, MAX_FILE_KEYS - self.total)  # what recount() finds for an empty section
        self.kept = key not in seen
        if self.kept:
            seen[key] = line
        else:
            self.diags.add(SYN002, Loc(self.source, line),
                           f"section [{name}] repeats line {seen[key]}; this copy is ignored")

    def read(self, lines: list[str], first_number: int, seen: dict[str, int]) -> Iterator[tuple[str, IniSection]]:
        """Read `lines`, the first being line `first_number`; yield each section as it is complete.

        The common line, a new key without an inline comment, is read here, with the open section's
        dicts and `room` in local variables: this runs once per line of the file, and every operation
        more per line shows in the reading time. Any other line goes to line()."""
        names = self.names
        values, line_of, keys, room = self.values, self.lines, self.keys, self.room
        for number, raw in enumerate(lines, first_number):
            line = raw.strip()
            if not line:
                continue
            first = line[0]
            if room and first not in "[;#":
                written, equals, value = line.partition("=")
                if equals and ";" not in value:
                    key, lower = names.get(written) or _names(written, names)
                    if lower not in values:
                        values[lower], line_of[lower], keys[lower] = value.lstrip(), number, key
                        room -= 1
                        continue
            self.total += self.room - room  # the keys kept above since the last line()
            self.room = room
            done = self.line(line, first, number, seen)
            if done is not None:
                yield done
            values, line_of, keys, room = self.values, self.lines, self.keys, self.room
        self.total += self.room - room
        self.room = room

    def line(self, line: str, first: str, number: int, seen: dict[str, int]) -> tuple[str, IniSection] | None:
        """Any line but the common one (stripped, not blank, `first` its first character); the section
        it completes, if it opens one."""
        done = None
        name = _section_name(line) if first == "[" else None
        if name is not None:
            done = self.close()
            self.open(name, number, seen)
        elif first in ";#":
            _comment_line(self.section, line, number, self.comment_keys)
            self.recount()
        elif "=" in line:
            self.key_line(line, number)
        else:
            self.diags.add(SYN001, Loc(self.source, number), f"'{_clip(line)}' is neither [section] nor key=value")
        return done

    def recount(self) -> None:
        """`room` again, after a line that may have changed it."""
        room = min(MAX_KEYS - len(self.values), MAX_FILE_KEYS - self.total)  # comment keys may pass MAX_KEYS
        self.room = max(room, 0) if self.section is not None else 0

    def key_line(self, line: str, number: int) -> None:
        """A key line read() did not keep itself: before any section, a repeated key, past a cap, or
        with an inline comment."""
        written, _, value = line.partition("=")
        key, lower = self.names.get(written) or _names(written, self.names)
        values = self.values
        if self.section is None or lower in values:  # SYN005, or a repeated key (SYN003)
            _key_line(self.section, line, number, self.source, self.diags)
        elif len(values) >= MAX_KEYS:
            self.dropped += 1
            self.first_dropped = self.first_dropped or number
        elif self.total >= MAX_FILE_KEYS:
            self.file_dropped += 1
            self.file_first_dropped = self.file_first_dropped or number
        elif ";" in value:  # an inline comment to cut off and report
            _key_line(self.section, line, number, self.source, self.diags)
            self.total += 1
            self.recount()
        else:
            self.section.put(lower, key, value.lstrip(), number)
            self.total += 1
            self.recount()

    def close(self) -> tuple[str, IniSection] | None:
        section, self.section = self.section, None
        if section is None:
            return None
        if self.dropped:
            self.diags.add(SYN021, Loc(self.source, self.first_dropped),
                           f"[{section.name}] has more than {MAX_KEYS} keys; the {self.dropped} from here on "
                           "are not read")
            self.dropped, self.first_dropped = 0, 0
        return (self.key, section) if self.kept else None

    def finish(self) -> None:
        if self.file_dropped:
            self.diags.add(SYN021, Loc(self.source, self.file_first_dropped),
                           f"the file has more than {MAX_FILE_KEYS} keys; the {self.file_dropped} from here on "
                           "are not read")


def _parts(text: str, size: int = 1 << 20) -> Iterator[tuple[int, list[str]]]:
    """(number of the first line, lines) of `text`, about `size` characters at a time: a list of every
    line of a large file costs more memory than the file itself. Lines end at CR LF, LF or CR only:
    str.splitlines() would also split at form feeds, U+0085, U+2028 and others that other EDS readers
    keep inside a value."""
    if "\r" in text:
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    start, number = 0, 1
    while start <= len(text):
        end = text.find("\n", start + size)
        end = len(text) if end < 0 else end
        lines = text[start:end].split("\n")
        yield number, lines
        number += len(lines)
        start = end + 1


def _section_name(line: str) -> str | None:
    """The name of a `[section]` line (stripped), None if the line is no section header."""
    if line[-1] == "]" and line.find("]") == len(line) - 1:  # the common header, without the regex
        return line[1:-1].strip()
    match = _SECTION_RE.match(line)
    return match.group(1).strip() if match else None


def _names(written: str, names: dict[str, tuple[str, str]]) -> tuple[str, str]:
    key = written.rstrip()
    lower = key.lower()
    spelled = key, key if lower == key else lower  # one string where the key is written in lower case
    if len(names) < _NAMES_KEPT:  # a description uses a few dozen key spellings; a hostile file, millions
        names[written] = spelled
    return spelled


def _comment_line(section: IniSection | None, line: str, number: int, keys: frozenset[str]) -> None:
    match = _COMMENT_KEY_RE.match(line)
    if match and section is not None and match.group(1).lower() in keys:
        key, value = match.group(1), match.group(2).strip()
        lower = key.lower()
        if lower not in section.values:
            section.put(lower, key, value, number)
            section.commented.add(lower)


def _key_line(section: IniSection | None, line: str, number: int, source: str, diags: Diagnostics) -> None:
    key, _, value = line.partition("=")
    key, value = key.rstrip(), value.lstrip()
    if section is None:
        diags.add(SYN005, Loc(source, number), f"'{key}' stands before any [section]")
        return
    comment = ""
    match = _INLINE_COMMENT_RE.search(value) if ";" in value else None
    if match:
        value, comment = value[: match.start()], match.group(0).strip()
        diags.add(SYN014, Loc(source, number),
                  f"inline comment '{_clip(comment)}' after the value of '{key}' is dropped")
    lower = key.lower()
    if lower in section.values and lower not in section.commented:
        diags.add(SYN003, Loc(source, number),
                  f"key '{key}' repeats line {section.lines[lower]} in [{section.name}]; this one is ignored",
                  blocks=_changes_dictionary(section.name) and value.strip() != section.values[lower].strip())
        return
    section.commented.discard(lower)
    section.put(lower, key, value, number)


_LISTS = frozenset(("mandatoryobjects", "optionalobjects", "manufacturerobjects", "fileinfo", "comments"))


def _changes_dictionary(section: str) -> bool:
    """Whether a repeated key here could change the generated C: the object lists and the file's
    own notes do not (the C is built from the object sections); an identical copy never does."""
    return section.lower() not in _LISTS


def _clip(text: str, width: int = 40) -> str:
    return text if len(text) <= width else text[: width - 3] + "..."
