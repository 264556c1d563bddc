"""The network file (docs/network.md): `[master]`, `[[node]]` with `[node.values]`, `[[pdo]]`.

tomllib gives no line numbers, so `_Lines` finds them in the text: the line of each table's
header and of each key written under it. Every mistake is a NET001 finding at its line; what
can be read is kept, so one run reports every mistake.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..catalogue.network import NET001, NET002
from ..diagnostics import Diagnostics, Loc

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

NODE_KEYS = ("name", "file", "node_id", "dcf", "mandatory", "check_identity", "vendor_id", "product_code",
             "revision", "serial", "keep_alive", "heartbeat", "values")
MASTER_KEYS = ("name", "file", "node_id", "boot_time", "start_all", "start_self", "start_slaves", "reset_all",
               "stop_all", "values")
PDO_KEYS = ("from", "tpdo", "to", "rpdo", "cob_id", "transmission", "entries")
_HEADER_RE = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.\-]+)\s*\]\]?")
_KEY_RE = re.compile(r"""^\s*("(?:[^"\\]|\\.)*"|'[^']*'|[A-Za-z0-9_\-]+)\s*=""")
_NAME_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_\-]*$")


@dataclass(frozen=True)
class Setting:
    """A configured value: the key as written (index/sub or a name), the TOML value, its line."""

    key: str
    value: int | float | str | bool
    line: int


@dataclass(frozen=True)
class NodeSpec:
    file: Path
    node_id: int | None  # None when NET002 rejected it
    loc: Loc  # the [[node]] or [master] line
    name: str = ""
    master: bool = False
    dcf: Path | None = None
    settings: tuple[Setting, ...] = ()
    options: dict[str, int | bool] = field(default_factory=dict)  # boot options as read
    lines: dict[str, int] = field(default_factory=dict)  # key -> line

    def line(self, key: str) -> int:
        return self.lines.get(key, self.loc.line)


@dataclass(frozen=True)
class PdoSpec:
    producer: str
    tpdo: int
    consumer: str
    rpdo: int
    cob_id: int | None
    transmission: int
    entries: tuple[tuple[str, str], ...]  # producer entry, consumer entry
    loc: Loc
    lines: dict[str, int] = field(default_factory=dict)

    def line(self, key: str) -> int:
        return self.lines.get(key, self.loc.line)


@dataclass
class NetworkSpec:
    source: str
    nodes: list[NodeSpec] = field(default_factory=list)  # the master first, when there is one
    pdos: list[PdoSpec] = field(default_factory=list)

    @property
    def master(self) -> NodeSpec | None:
        return self.nodes[0] if self.nodes and self.nodes[0].master else None

    def named(self, name: str) -> NodeSpec | None:
        return next((n for n in self.nodes if n.name == name), None)


class _Lines:
    """Line numbers of tables and keys: `header(name, n)` is the line of the n-th `[name]` or
    `[[name]]`; `keys(name, n)` maps each key written under it to its line."""

    def __init__(self, text: str) -> None:
        self.tables: dict[str, list[tuple[int, dict[str, int]]]] = {}
        keys: dict[str, int] = {}
        for number, line in enumerate(text.splitlines(), start=1):
            header = _HEADER_RE.match(line)
            if header:
                keys = {}
                self.tables.setdefault(header.group(2), []).append((number, keys))
                continue
            key = _KEY_RE.match(line)
            if key:
                keys.setdefault(_unquote(key.group(1)), number)

    def header(self, name: str, n: int = 0) -> int:
        found = self.tables.get(name, [])
        return found[n][0] if n < len(found) else 0

    def keys(self, name: str, n: int = 0) -> dict[str, int]:
        found = self.tables.get(name, [])
        return found[n][1] if n < len(found) else {}

    def values_of(self, node_line: int) -> dict[str, int]:
        """Keys of the `[node.values]` table that follows the `[[node]]` at `node_line`."""
        for table in ("node.values", "master.values"):
            for number, keys in self.tables.get(table, []):
                if number > node_line and not any(node_line < n < number for n, _ in self._all_headers()):
                    return keys
        return {}

    def _all_headers(self) -> list[tuple[int, str]]:
        return [(n, name) for name, found in self.tables.items() for n, _ in found
                if name not in ("node.values", "master.values")]


def _unquote(key: str) -> str:
    return key[1:-1] if key[:1] in "\"'" and len(key) > 1 else key


def parse_network(text: str, path: Path, diags: Diagnostics) -> NetworkSpec:
    """The network file's nodes and PDO wiring; every mistake is a NET001/NET002 finding."""
    source, spec = str(path), NetworkSpec(str(path))
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        m = re.search(r"line (\d+)", str(err))
        diags.add(NET001, Loc(source, int(m.group(1)) if m else 0), f"not valid TOML: {err}")
        return spec
    lines = _Lines(text)
    for key in sorted(set(doc) - {"master", "node", "pdo"}):
        diags.add(NET001, Loc(source, 1), f"unknown table or key `{key}`; a network file has [master], "
                  "[[node]] and [[pdo]]")
    raw_nodes = doc.get("node", [])
    if not isinstance(raw_nodes, list) or not raw_nodes:
        diags.add(NET001, Loc(source, 1), "expected at least one [[node]] table")
        raw_nodes = []
    if "master" in doc:
        master = _node(doc["master"], Loc(source, lines.header("master")), path, lines, diags, master=True)
        if master is not None:
            spec.nodes.append(master)
    for n, raw in enumerate(raw_nodes):
        node = _node(raw, Loc(source, lines.header("node", n)), path, lines, diags, master=False, n=n)
        if node is not None:
            spec.nodes.append(node)
    _distinct(spec, diags)
    raw_pdos = doc.get("pdo", [])
    if not isinstance(raw_pdos, list):
        diags.add(NET001, Loc(source, 1), "`pdo` must be [[pdo]] tables")
        raw_pdos = []
    for n, raw in enumerate(raw_pdos):
        pdo = _pdo(raw, Loc(source, lines.header("pdo", n)), lines.keys("pdo", n), diags)
        if pdo is not None:
            spec.pdos.append(pdo)
    return spec


def _is_int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _node(raw: object, loc: Loc, path: Path, lines: _Lines, diags: Diagnostics, master: bool,
          n: int = 0) -> NodeSpec | None:
    table = "[master]" if master else "[[node]]"
    keys = lines.keys("master" if master else "node", n)
    if not isinstance(raw, dict) or not isinstance(raw.get("file"), str) or not _is_int(raw.get("node_id")):
        diags.add(NET001, loc, f"{table} needs `file` (a string) and `node_id` (an integer)")
        return None
    allowed = MASTER_KEYS if master else NODE_KEYS
    for key in sorted(set(raw) - set(allowed)):
        diags.add(NET001, Loc(loc.file, keys.get(key, loc.line)),
                  f"unknown key `{key}` in {table}; use {', '.join(allowed)}")
    options: dict[str, int | bool] = {}
    for key in sorted(set(raw) & set(allowed) - {"name", "file", "node_id", "dcf", "values"}):
        value, line = raw[key], keys.get(key, loc.line)
        wanted_int = key in _LIMITS
        if (wanted_int and (not _is_int(value) or not 0 <= value <= _LIMITS[key])) \
                or (not wanted_int and not isinstance(value, bool)):
            what = f"an integer 0..{_LIMITS[key]}" if wanted_int else "true or false"
            diags.add(NET001, Loc(loc.file, line), f"`{key}` = {value!r} must be {what}")
            continue
        options[key] = value
    name = raw.get("name", "master" if master else "")
    if not isinstance(name, str) or (name and not _NAME_RE.match(name)):
        diags.add(NET001, Loc(loc.file, keys.get("name", loc.line)),
                  f"name {name!r} must be a word (letters, digits, _ and -)")
        name = ""
    dcf = raw.get("dcf")
    if dcf is not None and not isinstance(dcf, str):
        diags.add(NET001, Loc(loc.file, keys.get("dcf", loc.line)), "`dcf` must be a file name (a string)")
        dcf = None
    node_id = raw["node_id"]
    if not 1 <= node_id <= 127:
        diags.add(NET002, loc, f"node_id {node_id} is outside 1..127")
        node_id = None
    return NodeSpec(path.parent / raw["file"], node_id, loc, name or f"node{raw['node_id']}", master,
                    path.parent / dcf if dcf else None, _settings(raw.get("values", {}), loc, lines, diags),
                    options, dict(keys))


_LIMITS = {"vendor_id": 0xFFFFFFFF, "product_code": 0xFFFFFFFF, "revision": 0xFFFFFFFF, "serial": 0xFFFFFFFF,
           "heartbeat": 0xFFFF, "boot_time": 0xFFFFFFFF}


def _settings(raw: object, loc: Loc, lines: _Lines, diags: Diagnostics) -> tuple[Setting, ...]:
    keys = lines.values_of(loc.line)
    if not isinstance(raw, dict):
        diags.add(NET001, loc, "`values` must be a table of entry = value")
        return ()
    found = []
    for key, value in raw.items():
        line = keys.get(key, loc.line)
        if not isinstance(value, (int, float, str)):
            diags.add(NET001, Loc(loc.file, line), f"value of `{key}` must be a number, a string or true/false")
            continue
        found.append(Setting(key, value, line))
    return tuple(found)


def _distinct(spec: NetworkSpec, diags: Diagnostics) -> None:
    ids: dict[int, int] = {}
    names: dict[str, int] = {}
    for node in spec.nodes:
        if node.node_id is not None and node.node_id in ids:
            diags.add(NET002, node.loc, f"node_id {node.node_id} is also the node at line {ids[node.node_id]}")
        elif node.node_id is not None:
            ids[node.node_id] = node.loc.line
        if node.name in names:
            diags.add(NET001, Loc(node.loc.file, node.line("name")),
                      f"name {node.name!r} is also the node at line {names[node.name]}")
        names.setdefault(node.name, node.loc.line)
    for n, node in enumerate(spec.nodes):
        if node.node_id is not None and ids.get(node.node_id) != node.loc.line:
            spec.nodes[n] = NodeSpec(node.file, None, node.loc, node.name, node.master, node.dcf, node.settings,
                                     node.options, node.lines)


def _pdo(raw: object, loc: Loc, keys: dict[str, int], diags: Diagnostics) -> PdoSpec | None:
    if not isinstance(raw, dict):
        diags.add(NET001, loc, "[[pdo]] must be a table")
        return None
    ok = True
    for key in sorted(set(raw) - set(PDO_KEYS)):
        diags.add(NET001, Loc(loc.file, keys.get(key, loc.line)), f"unknown key `{key}` in [[pdo]]; use "
                  f"{', '.join(PDO_KEYS)}")
        ok = False
    for key, lo, hi in (("tpdo", 1, 512), ("rpdo", 1, 512), ("cob_id", 1, 0x7FF), ("transmission", 0, 255)):
        value = raw.get(key)
        if (value is None and key in ("tpdo", "rpdo")) or (value is not None and (not _is_int(value)
                                                                                  or not lo <= value <= hi)):
            diags.add(NET001, Loc(loc.file, keys.get(key, loc.line)), f"[[pdo]] `{key}` must be an integer "
                      f"{lo}..{hi:#x}" if key == "cob_id" else f"[[pdo]] `{key}` must be an integer {lo}..{hi}")
            ok = False
    for key in ("from", "to"):
        if not isinstance(raw.get(key), str):
            diags.add(NET001, Loc(loc.file, keys.get(key, loc.line)), f"[[pdo]] needs `{key}`, a node's name")
            ok = False
    entries = raw.get("entries")
    if not isinstance(entries, list) or not entries or not all(
            isinstance(e, list) and len(e) == 2 and all(isinstance(s, str) for s in e) for e in entries):
        diags.add(NET001, Loc(loc.file, keys.get("entries", loc.line)),
                  '[[pdo]] `entries` must be a list of ["producer entry", "consumer entry"] pairs')
        ok = False
    if not ok or not isinstance(entries, list):
        return None
    return PdoSpec(raw["from"], raw["tpdo"], raw["to"], raw["rpdo"], raw.get("cob_id"),
                   raw.get("transmission", 255), tuple((a, b) for a, b in entries), loc, dict(keys))
