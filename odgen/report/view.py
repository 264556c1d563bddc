"""What the report shows, decided here from the model, the lint findings, the placement and the
memory figures; the templates and the SVG drawing only lay it out.

Findings go to the row of their entry (index and sub-index); a finding that names an object but
no sub-index, or a sub-index the object does not define, goes to the object's first row; the rest
(header sections, the file as a whole) are listed before the table.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ..pipeline import Request, run
from ..codegen.memory import MemoryRow, memory_rows
from ..place.placement import Placements
from ..diagnostics import RULES, Diagnostic, Severity, where
from ..model import ObjectDictionary, Obj, Sub
from ..model.cia301 import RPDO_MAPPING, TPDO_MAPPING
from ..model.datatypes import BASIC_TYPES
from ..model.od import OBJECT_CODES
from ..model.pdo import FD_FRAME_BITS, FRAME_BITS, MAPPINGS, decode_mapping, mapping_objects

if TYPE_CHECKING:
    from .network import NetworkView

RULES_DOC = "docs/rules.md"  # where a finding's rule id links to (its anchor there)
IDENTITY = ((0x1000, 0, "Device type"), (0x1018, 1, "Vendor-ID"), (0x1018, 2, "Product code"),
            (0x1018, 3, "Revision number"), (0x1018, 4, "Serial number"))
HEADER_SECTIONS = ("FileInfo", "DeviceInfo", "DeviceComissioning")


@dataclass
class Finding:
    rule: str
    severity: str
    message: str
    line: int
    title: str
    link: str
    index: int | None = None
    sub: int | None = None
    row: str = ""  # Row.key of the entry it is shown at ("" when at none)

    @property
    def address(self) -> str:
        return where(self.index, self.sub)


@dataclass
class Row:
    key: str  # HTML id: e-1A00-01
    index: int
    sub: int
    object_name: str
    name: str
    type: str
    access: str
    value: str
    low: str
    high: str
    pdo: bool
    storage: str
    storage_from: str
    hooks: str
    hooks_from: str
    var: bool  # a single-value object: its one row is the object
    header: str  # on an ARRAY/RECORD's first row: its object code, for the row naming the object
    findings: list[Finding] = field(default_factory=list)

    @property
    def address(self) -> str:
        return where(self.index, None if self.var else self.sub)


@dataclass
class Box:
    """One mapped entry of a PDO: `bits` bits from bit `bit` of the frame."""

    bit: int
    bits: int
    address: str  # 0x6000sub1, or the data type index of a dummy
    name: str
    dummy: bool
    target: str  # Row.key of the mapped entry ("" when it is not in the dictionary)


@dataclass
class Lane:
    label: str  # e.g. "TPDO1" or "node 3 RPDO2"
    boxes: list[Box]


@dataclass
class Pdo:
    kind: str  # TPDO | RPDO
    number: int
    comm: int
    mapping: int
    frame_bits: int
    params: list[tuple[str, str]]
    lanes: list[Lane]
    findings: list[Finding] = field(default_factory=list)
    node: int | None = None  # the producing node in a network picture

    @property
    def key(self) -> str:
        return ("" if self.node is None else f"n{self.node}-") + f"{self.kind.lower()}{self.number}"

    @property
    def used_bits(self) -> int:
        return max((b.bit + b.bits for lane in self.lanes for b in lane.boxes), default=0)


@dataclass
class Report:
    title: str
    source: str
    format: str
    identity: list[tuple[str, str]]
    sections: list[tuple[str, list[tuple[str, str]]]]
    rows: list[Row]
    general: list[Finding]  # findings not at an entry
    pdos: list[Pdo]
    memory: list[MemoryRow] | None  # None when the dictionary cannot be generated
    memory_note: str
    storage_note: str  # why the storage column is empty, if it is
    can_fd: bool
    counts: dict[str, int]
    network: NetworkView | None = None  # with --network


def rule_anchor(rule_id: str) -> str:
    """The anchor docs/rules.md's heading `### ID — title` gets (GitHub's slug rule)."""
    rule = RULES[rule_id]
    text = f"{rule.id} — {rule.title}".lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def finding(d: Diagnostic) -> Finding:
    rule = RULES[d.rule]
    return Finding(d.rule, d.severity.label, d.message, d.loc.line, rule.title,
                   f"{RULES_DOC}#{rule_anchor(d.rule)}", d.index, d.sub)


def type_name(sub: Sub) -> str:
    if sub.data_type is None:
        return ""
    dtype = BASIC_TYPES.get(sub.data_type)
    return dtype.name if dtype is not None else f"0x{sub.data_type:04X}"


def value_text(od: ObjectDictionary, sub: Sub) -> str:
    value = od.value_in_force(sub)
    return value.text.strip() if value is not None else ""


def row_key(index: int, sub: int) -> str:
    return f"e-{index:04X}-{sub:02X}"


def _rows(od: ObjectDictionary, placements: Placements | None) -> list[Row]:
    rows = []
    for obj in od.sorted_objects():
        for n, sub in enumerate(obj.sorted_subs()):
            p = placements.get((obj.index, sub.subindex)) if placements is not None else None
            hooks = ", ".join(p.hooks) + (f" → {p.function}()" if p.function else "") if p else ""
            rows.append(Row(row_key(obj.index, sub.subindex), obj.index, sub.subindex, obj.name,
                            sub.name or obj.name, type_name(sub), sub.access or "", value_text(od, sub),
                            sub.low.text.strip() if sub.low else "", sub.high.text.strip() if sub.high else "",
                            sub.pdo_mapping, p.storage if p else "", p.storage_from if p else "",
                            hooks, p.hooks_from if p and p.hooks else "", obj.is_var,
                            "" if n or obj.is_var else OBJECT_CODES.get(obj.object_code, "")))
    return rows


def _place_findings(od: ObjectDictionary, rows: list[Row], diags: list[Diagnostic]) -> list[Finding]:
    """Put each finding on its entry's row; return the ones that belong to no entry."""
    by_key = {r.key: r for r in rows}
    general = []
    for d in diags:
        obj = od.objects.get(d.index) if d.index is not None else None
        row = None
        if obj is not None and obj.subs:
            sub = d.sub if d.sub is not None and d.sub in obj.subs else obj.sorted_subs()[0].subindex
            row = by_key.get(row_key(obj.index, sub))
        if row is not None and d.loc.file == od.source:
            row.findings.append(finding(d))
            row.findings[-1].row = row.key
        else:
            general.append(finding(d))
    return general


def _identity(od: ObjectDictionary) -> list[tuple[str, str]]:
    facts = []
    for index, subindex, label in IDENTITY:
        sub = od.find(index, subindex)
        if sub is not None:
            facts.append((label, value_text(od, sub)))
    device = od.find(0x1000, 0)
    value = od.value_in_force(device) if device is not None else None
    if value is not None and isinstance(value.parsed, int) and not value.nodeid:
        facts.append(("Device profile", f"CiA {value.parsed & 0xFFFF}"))
    relative = sum(1 for obj in od.objects.values() for s in obj.subs.values()
                   if any(v is not None and v.nodeid for v in (s.default, s.parameter_value)))
    node = f"node-id {od.node_id} (configured)" if od.is_config and od.node_id is not None else "set at run time"
    facts.append(("Node-id", f"{node}; {relative} value(s) relative to $NODEID"))
    return facts


def _sections(od: ObjectDictionary) -> list[tuple[str, list[tuple[str, str]]]]:
    found = []
    for name in HEADER_SECTIONS:
        section = od.section(name)
        if section is not None and section.fields:
            found.append((section.name, [(f.key, f.text.strip()) for f in section.fields.values()]))
    return found


def _comm_params(od: ObjectDictionary, comm: int) -> list[tuple[str, str]]:
    params = []
    cob = od.find(comm, 1)
    if cob is not None:
        text = value_text(od, cob)
        value = od.value_in_force(cob)
        off = value is not None and isinstance(value.parsed, int) and bool(value.parsed & 0x80000000)
        params.append(("COB-ID", text + (" (disabled)" if off else "")))
    else:
        params.append(("COB-ID", f"no 0x{comm:04X}"))
    for subindex, label, unit in ((2, "Transmission type", ""), (3, "Inhibit time", " × 100 µs"),
                                  (5, "Event timer", " ms")):
        sub = od.find(comm, subindex)
        if sub is not None:
            text = value_text(od, sub)
            params.append((label, text + (unit if text else "")))
    return params


def pdo_boxes(od: ObjectDictionary, obj: Obj) -> list[Box]:
    """The active mapping entries as boxes, each at the bit offset the entries before it leave."""
    boxes, bit = [], 0
    for entry in decode_mapping(od, obj).entries:  # the lint pass reports what is wrong with them
        dummy = entry.index < 0x20
        target = od.find(entry.index, entry.subindex)
        owner = od.objects.get(entry.index)
        if dummy:
            dtype = BASIC_TYPES.get(entry.index)
            name, address = f"dummy {dtype.name if dtype else ''}".strip(), f"0x{entry.index:04X}"
        else:
            name = (target.name if target is not None else "") or (owner.name if owner is not None else "?")
            address = where(entry.index, None if owner is not None and owner.is_var else entry.subindex)
        key = row_key(entry.index, entry.subindex) if target is not None and not dummy else ""
        boxes.append(Box(bit, entry.length, address, name, dummy, key))
        bit += entry.length
    return boxes


def _pdos(od: ObjectDictionary, can_fd: bool) -> list[Pdo]:
    found = []
    frame = FD_FRAME_BITS if can_fd else FRAME_BITS
    for obj, kind in sorted(mapping_objects(od), key=lambda pair: (pair[1] != "TPDO", pair[0].index)):
        base = TPDO_MAPPING if kind == "TPDO" else RPDO_MAPPING
        comm = MAPPINGS[base][1] + obj.index - base
        found.append(Pdo(kind, obj.index - base + 1, comm, obj.index, frame, _comm_params(od, comm),
                         [Lane(f"{kind}{obj.index - base + 1}", pdo_boxes(od, obj))]))
    return found


def build_report(path: Path, options: Path | None = None, node_id: int | None = None,
                 can_fd: bool = False) -> tuple[Report | None, list[Diagnostic]]:
    """The report of one description, and every finding (None when the file cannot be read)."""
    result = run(Request(path, options=options, node_id=node_id, can_fd=can_fd), until="view")  # no C printed
    diags = result.diags.sorted()
    od = result.od
    if od is None:
        return None, diags
    rows = _rows(od, result.placements)
    general = _place_findings(od, rows, diags)
    pdos = _pdos(od, can_fd)
    for pdo in pdos:
        pdo.findings = [f for r in rows if r.index in (pdo.comm, pdo.mapping) for f in r.findings]
    memory = memory_rows(result.view) if result.view is not None else None
    note = "" if memory is not None else "Not generated: the description has errors (see the findings)."
    undecided = "" if result.placements is not None else \
        "Storage and hooks are not decided: the description has errors (see the findings)."
    counts = {s.label: sum(1 for d in diags if d.severity == s) for s in reversed(Severity)}
    device = od.section("DeviceInfo")
    product = device.text("ProductName").strip() if device is not None else ""
    return Report(product or path.name, str(path), od.format.upper(), _identity(od), _sections(od), rows,
                  general, pdos, memory, note, undecided, can_fd, counts), diags
