"""The generator's options file (TOML): placement, hooks and capacities per entry.

    [[entry]]
    match = ["0x2000-0x2FFF", "0x6200sub1-8"]   # index, index range, sub, sub range, "*"
    storage = "persist:app"                      # rom | ram | persist | persist:<group>
    hooks = ["pre_write", "post_write"]          # pre_read | pre_write | post_write
    function = "app_outputs"                     # optional: generated prototype, registered at init
    capacity = 64                                # bytes, for strings and domains

    [persist]                                    # stored parameters (docs/persistence.md)
    migration = true                             # self-describing images, migrated at boot
    headroom = 50                                # % of a region's need kept free for growth
    status_object = 0x2FF0                       # the boot status object (RECORD), absent if unset
    align = 2048                                 # slot alignment: a flash NV's erase page (ODG_PERSIST_ALIGN)

    [[group]]
    name = "app"
    region = 1024                                # pin the group's NV region (bytes)

    [node]
    lss = true      # build the node with the LSS slave even when the description has no LSS_Supported=1
    sdo_block = false  # build the SDO server without block transfer (a block initiate is refused)
    tpdo = 4        # and lower limits of the node layer (docs/generate.md)

Entries apply in file order; for each key, the last entry that sets it wins.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..catalogue.gen import GEN001
from ..diagnostics import Diagnostics, Loc
from ..cnames import is_identifier

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

HOOK_KINDS = ("pre_read", "pre_write", "post_write")
KEYS = ("match", "storage", "hooks", "function", "capacity")
_STORAGE_RE = re.compile(r"^(rom|ram|persist(:[a-z][a-z0-9_]{0,15})?)$")
_PATTERN_RE = re.compile(
    r"^0x([0-9a-f]{1,4})(?:-0x([0-9a-f]{1,4}))?(?:sub(?:0x)?([0-9a-f]{1,2})(?:-(?:0x)?([0-9a-f]{1,2}))?)?$")


@dataclass(frozen=True)
class Pattern:
    text: str
    index_lo: int
    index_hi: int
    sub_lo: int = 0
    sub_hi: int = 255

    def matches(self, index: int, sub: int) -> bool:
        return self.index_lo <= index <= self.index_hi and self.sub_lo <= sub <= self.sub_hi


@dataclass
class OptionEntry:
    source: str
    line: int
    patterns: list[Pattern]
    storage: str | None = None
    hooks: tuple[str, ...] | None = None
    function: str | None = None
    capacity: int | None = None
    used: bool = False


@dataclass
class PersistOptions:
    migration: bool = True
    headroom: int = 50
    status_object: int | None = None
    regions: dict[str, int] = field(default_factory=dict)  # pinned, by group name
    align: int | None = None  # slot alignment (ODG_PERSIST_ALIGN): the NV's erase page; None: the runtime's 8


SWITCHES = ("lss", "sdo_block")  # the [node] keys that are true or false; the rest are limits


@dataclass
class Options:
    source: str = ""
    text: str = ""
    entries: list[OptionEntry] = field(default_factory=list)
    persist: PersistOptions = field(default_factory=PersistOptions)
    node_lss: bool = False  # [node] lss
    node_sdo_block: bool = True  # [node] sdo_block
    node: dict[str, object] = field(default_factory=dict)  # the other [node] keys: codegen.runtimecfg reads them


def parse_pattern(text: str) -> Pattern | None:
    """`0x6000`, `0x6000-0x60FF`, `0x6200sub1`, `0x6200sub1-8` (hex sub-indices), or `*`."""
    compact = text.strip().lower().replace(" ", "")
    if compact == "*":
        return Pattern(text, 0, 0xFFFF)
    m = _PATTERN_RE.match(compact)
    if m is None:
        return None
    lo = int(m.group(1), 16)
    hi = int(m.group(2), 16) if m.group(2) else lo
    if m.group(3) is None:
        return Pattern(text, lo, hi) if lo <= hi else None
    s_lo = int(m.group(3), 16)
    s_hi = int(m.group(4), 16) if m.group(4) else s_lo
    return Pattern(text, lo, hi, s_lo, s_hi) if lo <= hi and s_lo <= s_hi else None


def load_options(path: Path | None, diags: Diagnostics) -> Options:
    if path is None:
        return Options()
    return read_options(path, diags)[1]


def read_options(path: Path, diags: Diagnostics) -> tuple[bytes, Options]:
    """The options file's bytes (what the generated headers' digest covers) and the options they give."""
    try:
        data = path.read_bytes()
        text = data.decode("utf-8")
    except (OSError, UnicodeDecodeError) as err:
        diags.add(GEN001, Loc(str(path)), f"cannot read the options file: {err}")
        return b"", Options(str(path))
    return data, parse_options(text.replace("\r\n", "\n").replace("\r", "\n"), str(path), diags)


def parse_options(text: str, source: str, diags: Diagnostics) -> Options:
    options = Options(source, text)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        diags.add(GEN001, Loc(source, _error_line(err)), f"not valid TOML: {err}")
        return options
    unknown = sorted(set(doc) - {"entry", "persist", "group", "node"})
    if unknown:
        diags.add(GEN001, Loc(source, 1),
                  f"unknown top-level key(s) {', '.join(unknown)}; only [[entry]], [persist], [[group]] and [node]")
    _persist(doc, text, source, options.persist, diags)
    node = doc.get("node", {})
    if not isinstance(node, dict) or not all(isinstance(node.get(key, False), bool) for key in SWITCHES):
        diags.add(GEN001, Loc(source, 1), "[node] takes lss and sdo_block = true or false, and the node's limits")
    else:
        options.node_lss = node.get("lss", False)
        options.node_sdo_block = node.get("sdo_block", True)
        options.node = {key: value for key, value in node.items() if key not in SWITCHES}
    lines = [n for n, line in enumerate(text.splitlines(), start=1) if line.strip().startswith("[[entry]]")]
    raw_entries = doc.get("entry", [])
    if not isinstance(raw_entries, list):
        diags.add(GEN001, Loc(source, 1), "'entry' must be an array of tables ([[entry]])")
        return options
    for n, raw in enumerate(raw_entries):
        line = lines[n] if n < len(lines) else 0
        entry = _entry(raw, Loc(source, line), diags)
        if entry is not None:
            options.entries.append(entry)
    return options


def _error_line(err: Exception) -> int:
    m = re.search(r"line (\d+)", str(err))
    return int(m.group(1)) if m else 0


def _entry(raw: object, loc: Loc, diags: Diagnostics) -> OptionEntry | None:
    if not isinstance(raw, dict):
        diags.add(GEN001, loc, "[[entry]] must be a table")
        return None
    bad = sorted(set(raw) - set(KEYS))
    if bad:
        diags.add(GEN001, loc, f"unknown key(s) {', '.join(bad)}; use {', '.join(KEYS)}")
        return None
    patterns = _patterns(raw.get("match"), loc, diags)
    if patterns is None:
        return None
    entry = OptionEntry(loc.file, loc.line, patterns)
    checks = (_storage, _hooks, _function, _capacity)
    return entry if all(check(entry, raw, loc, diags) for check in checks) else None


def _patterns(value: object, loc: Loc, diags: Diagnostics) -> list[Pattern] | None:
    texts = [value] if isinstance(value, str) else value
    if not isinstance(texts, list) or not texts or not all(isinstance(t, str) for t in texts):
        diags.add(GEN001, loc, "'match' must be a pattern or a list of patterns")
        return None
    patterns = [parse_pattern(t) for t in texts]
    for text, pattern in zip(texts, patterns, strict=True):
        if pattern is None:
            diags.add(GEN001, loc, f"'{text}' is not a pattern: use 0x6000, 0x6000-0x60FF, 0x6200sub1-8 or *")
    return [p for p in patterns if p is not None] if all(patterns) else None


def _storage(entry: OptionEntry, raw: dict, loc: Loc, diags: Diagnostics) -> bool:
    value = raw.get("storage")
    if value is None:
        return True
    if not isinstance(value, str) or not _STORAGE_RE.match(value):
        diags.add(GEN001, loc, f"storage '{value}' is not rom, ram, persist or persist:<group>")
        return False
    entry.storage = value
    return True


def _hooks(entry: OptionEntry, raw: dict, loc: Loc, diags: Diagnostics) -> bool:
    value = raw.get("hooks")
    if value is None:
        return True
    if not isinstance(value, list) or any(v not in HOOK_KINDS for v in value):
        diags.add(GEN001, loc, f"hooks {value!r} must be a list of {', '.join(HOOK_KINDS)}")
        return False
    entry.hooks = tuple(k for k in HOOK_KINDS if k in value)
    return True


def _function(entry: OptionEntry, raw: dict, loc: Loc, diags: Diagnostics) -> bool:
    value = raw.get("function")
    if value is None:
        return True
    if not isinstance(value, str) or not is_identifier(value):
        diags.add(GEN001, loc, f"function '{value}' is not a C identifier")
        return False
    entry.function = value
    return True


def _capacity(entry: OptionEntry, raw: dict, loc: Loc, diags: Diagnostics) -> bool:
    value = raw.get("capacity")
    if value is None:
        return True
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value <= 65535:
        diags.add(GEN001, loc, f"capacity {value!r} must be a number of bytes 0..65535")
        return False
    entry.capacity = value
    return True


PERSIST_KEYS = ("migration", "headroom", "status_object", "align")
MAX_ALIGN = 0x8000  # two slots of it fill ODG_PERSIST_MAX_REGION
_GROUP_RE = re.compile(r"^[a-z][a-z0-9_]{0,15}$")


def _line_of(text: str, header: str, n: int = 0) -> int:
    lines = [k for k, line in enumerate(text.splitlines(), start=1) if line.strip().startswith(header)]
    return lines[n] if n < len(lines) else 1


def table_key_line(text: str, table: str, key: str) -> int:
    """The line of `key = ...` in an options file's `[table]` (0 when it is not there)."""
    section = ""
    for n, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("["):
            section = stripped
        elif section == f"[{table}]" and re.match(rf"{re.escape(key)}\s*=", stripped):
            return n
    return 0


def _key_line(text: str, key: str) -> int:
    """The line of `key = ...` in the [persist] table, else that of [persist]."""
    return table_key_line(text, "persist", key) or _line_of(text, "[persist]")


def _persist(doc: dict, text: str, source: str, persist: PersistOptions, diags: Diagnostics) -> None:
    """[persist] and [[group]]: migration on/off, headroom, status object, slot alignment, pinned regions."""
    raw = doc.get("persist", {})
    loc = Loc(source, _line_of(text, "[persist]"))
    if not isinstance(raw, dict):
        diags.add(GEN001, loc, "'persist' must be a table ([persist])")
        raw = {}
    for key in sorted(set(raw) - set(PERSIST_KEYS)):
        diags.add(GEN001, loc, f"unknown key {key} in [persist]; use {', '.join(PERSIST_KEYS)}")
    migration = raw.get("migration", True)
    if isinstance(migration, bool):
        persist.migration = migration
    else:
        diags.add(GEN001, loc, f"migration {migration!r} must be true or false")
    headroom = raw.get("headroom", 50)
    if isinstance(headroom, int) and not isinstance(headroom, bool) and 0 <= headroom <= 1000:
        persist.headroom = headroom
    else:
        diags.add(GEN001, loc, f"headroom {headroom!r} must be a percentage 0..1000")
    status = raw.get("status_object")
    if isinstance(status, int) and not isinstance(status, bool) and 0x2000 <= status <= 0x5FFF:
        persist.status_object = status
    elif status is not None:
        diags.add(GEN001, loc, f"status_object {status!r} must be an index in 0x2000..0x5FFF (manufacturer area)")
    align = raw.get("align")
    if (isinstance(align, int) and not isinstance(align, bool) and 8 <= align <= MAX_ALIGN
            and align & (align - 1) == 0):
        persist.align = align
    elif align is not None:
        diags.add(GEN001, Loc(source, _key_line(text, "align")),
                  f"align {align!r} must be a power of two 8..{MAX_ALIGN} (the NV's erase page, in bytes)")
    groups = doc.get("group", [])
    if not isinstance(groups, list):
        diags.add(GEN001, Loc(source, 1), "'group' must be an array of tables ([[group]])")
        return
    for n, group in enumerate(groups):
        _group(group, Loc(source, _line_of(text, "[[group]]", n)), persist, diags)


def _group(raw: object, loc: Loc, persist: PersistOptions, diags: Diagnostics) -> None:
    if not isinstance(raw, dict) or set(raw) != {"name", "region"}:
        diags.add(GEN001, loc, "[[group]] needs name and region, and nothing else")
        return
    name, region = raw["name"], raw["region"]
    if not isinstance(name, str) or not _GROUP_RE.match(name):
        diags.add(GEN001, loc, f"group name {name!r} is not a persistence group name (persist:<group>)")
    elif not isinstance(region, int) or isinstance(region, bool) or not 64 <= region <= 0x1000000 or region % 16:
        diags.add(GEN001, loc, f"region {region!r} must be a number of bytes 64..16 MiB, a multiple of 16")
    else:
        persist.regions[name] = region
