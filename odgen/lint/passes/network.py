"""NET: a CANopen network of nodes (`odgen lint --network NET.toml`, driven by odgen.lint.network).

No per-file checks: `check_network` looks across the nodes' PDOs once every file is linted.
COB-IDs are read from the value in force (a DCF's ParameterValue, else the DefaultValue)
with `$NODEID` resolved with the node-id NET.toml gives; COB-IDs with bit 31 set are off.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ...catalogue.network import NET004, NET005, NET006, NET007
from ...diagnostics import Diagnostics, Loc
from ...model import ObjectDictionary
from ...model.cia301 import (
    EMCY_BASE, HEARTBEAT, RPDO_COMM, RPDO_MAPPING, SDO_REQUEST, SDO_RESPONSE, TPDO_COMM, TPDO_MAPPING)
from ...model.pdo import MPDO
from ...model.values import number
from .common import at, value_in_force, value_line
from .pdo import mapping_entries


FIXED = ((EMCY_BASE, "EMCY"), (SDO_RESPONSE, "SDO response"), (SDO_REQUEST, "SDO request"), (HEARTBEAT, "heartbeat"))
KINDS = (("RPDO", RPDO_COMM, RPDO_MAPPING), ("TPDO", TPDO_COMM, TPDO_MAPPING))


@dataclass(frozen=True)
class Node:
    od: ObjectDictionary
    node_id: int
    origin: Mapping[tuple[int, int], Loc] = field(default_factory=dict)  # values the network file configured

    def loc(self, index: int, sub: int, line: int) -> Loc:
        """Where a value comes from: the network file that configured it, else the description."""
        return self.origin.get((index, sub), Loc(self.od.source, line))


@dataclass
class Pdo:
    node: Node
    kind: str  # RPDO | TPDO
    number: int  # 1-based
    comm: int  # communication object index
    cob_id: int
    line: int  # of the COB-ID value
    lengths: list[tuple[int, int, int]] | None  # (bits, line, sub) per entry; None: not a fixed mapping
    map_line: int  # of the mapping's sub0 value

    @property
    def name(self) -> str:
        return f"node {self.node.node_id} {self.kind}{self.number}"

    @property
    def at(self) -> str:
        return str(self.node.loc(self.comm, 1, self.line))

    def layout(self) -> str:
        bits = [str(b) for b, _, _ in self.lengths or []]
        return f"{len(bits)} entr{'y' if len(bits) == 1 else 'ies'} ({', '.join(bits) or 'none'} bit)"


def pdos(node: Node) -> list[Pdo]:
    """The node's enabled PDOs with their COB-ID resolved and mapping decoded."""
    od, found = node.od, []
    for kind, comm_base, map_base in KINDS:
        for n in range(0x200):
            sub = od.find(comm_base + n, 1)
            value, keyword = value_in_force(od, sub) if sub is not None else (None, "")
            raw = at(value, node.node_id) if sub is not None and value is not None else None
            if sub is None or not isinstance(raw, int) or raw & 0x80000000:
                continue
            cob = raw & (0x1FFFFFFF if raw & 0x20000000 else 0x7FF)
            lengths, map_line = _layout(od, map_base + n)
            found.append(Pdo(node, kind, n + 1, comm_base + n, cob, value_line(sub, value, keyword), lengths,
                             map_line))
    return found


def _layout(od: ObjectDictionary, index: int) -> tuple[list[tuple[int, int, int]] | None, int]:
    obj = od.objects.get(index)
    sub0 = obj.subs.get(0) if obj is not None else None
    if obj is None or sub0 is None:
        return None, 0
    value, keyword = value_in_force(od, sub0)
    if number(value) in MPDO:
        return None, 0
    entries = mapping_entries(od, obj, Diagnostics())  # the file's own lint reports what is wrong with them
    return [(e.length, e.line, e.sub.subindex) for e in entries], value_line(sub0, value, keyword)


def check_network(nodes: list[Node], diags: Diagnostics) -> None:
    every = [p for node in nodes for p in pdos(node)]
    producers: dict[int, Pdo] = {}
    for p in every:
        if p.kind != "TPDO":
            continue
        first = producers.setdefault(p.cob_id, p)
        if first is not p:
            diags.add(NET004, p.node.loc(p.comm, 1, p.line), f"{p.name} transmits COB-ID 0x{p.cob_id:X}, "
                      f"as {first.name} does ({first.at})", p.comm, 1)
    for p in every:
        producer = producers.get(p.cob_id)
        if p.kind == "RPDO" and producer is None:
            diags.add(NET005, p.node.loc(p.comm, 1, p.line),
                      f"{p.name} receives COB-ID 0x{p.cob_id:X}, which no node transmits", p.comm, 1)
        elif p.kind == "RPDO" and producer is not None:
            _compare(p, producer, diags)
    fixed = {base + node.node_id: (node, what) for node in nodes for base, what in FIXED}
    for p in every:
        owner = fixed.get(p.cob_id)
        if owner is not None and owner[0].node_id != p.node.node_id:
            diags.add(NET007, p.node.loc(p.comm, 1, p.line), f"{p.name} uses COB-ID 0x{p.cob_id:X}, the "
                      f"{owner[1]} COB-ID of node {owner[0].node_id}", p.comm, 1)


def _compare(rpdo: Pdo, tpdo: Pdo, diags: Diagnostics) -> None:
    if rpdo.lengths is None or tpdo.lengths is None:
        return
    mine, theirs = [b for b, _, _ in rpdo.lengths], [b for b, _, _ in tpdo.lengths]
    if mine == theirs:
        return
    differ = next((i for i, (a, b) in enumerate(zip(mine, theirs, strict=False)) if a != b), None)
    line, sub = (rpdo.lengths[differ][1], rpdo.lengths[differ][2]) if differ is not None else (rpdo.map_line, 0)
    diags.add(NET006, rpdo.node.loc(rpdo.comm + 0x200, sub, line),
              f"{rpdo.name} maps {rpdo.layout()} but {tpdo.name} ({tpdo.at}) transmits {tpdo.layout()}",
              rpdo.comm + 0x200, sub)
