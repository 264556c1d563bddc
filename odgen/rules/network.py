"""NET: a CANopen network of nodes (`odgen lint --network NET.toml`, driven by odgen.network).

No per-file checks: `check_network` looks across the nodes' PDOs once every file is linted.
COB-IDs are read from the value in force (a DCF's ParameterValue, else the DefaultValue)
with `$NODEID` resolved with the node-id NET.toml gives; COB-IDs with bit 31 set are off.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import Diagnostics, Loc, Severity, define_rule
from ..model import ObjectDictionary
from .common import at, number, value_in_force, value_line
from .pdo import MPDO, mapping_entries

E, W = Severity.ERROR, Severity.WARNING

define_rule(
    "NET001", E, "network file is not a list of nodes",
    why="NET.toml lists the nodes as `[[node]]` tables, each with `file` (relative to NET.toml) "
    "and `node_id`; anything else cannot be checked.",
    example='[[node]]\nfile = "slave.eds"\n(no node_id)',
    fix="Give every [[node]] a `file` string and a `node_id` integer, and nothing else.")
define_rule(
    "NET002", E, "node-id outside 1..127 or used twice",
    why="Every node of a CANopen network has its own node-id 1..127; the fixed COB-IDs (SDO, EMCY, "
    "heartbeat) and every `$NODEID` value derive from it, so two nodes with one id collide on all of them.",
    example='[[node]]\nfile = "a.eds"\nnode_id = 2\n[[node]]\nfile = "b.eds"\nnode_id = 2',
    fix="Give each node a distinct node-id in 1..127.")
define_rule(
    "NET003", E, "node's file is missing or unreadable",
    why="A node whose description cannot be read cannot be checked against the others.",
    example='[[node]]\nfile = "missing.eds"\nnode_id = 2',
    fix="Correct the path (relative to NET.toml) or add the file.")
define_rule(
    "NET004", E, "two TPDOs transmit the same COB-ID",
    why="A COB-ID has exactly one producer; two nodes transmitting the same identifier with different "
    "data cause bus errors (same identifier, different bits) or frames that consumers misread.",
    example="node 2: [1800sub1] DefaultValue=0x182\nnode 4: [1800sub1] DefaultValue=0x182",
    fix="Give one of the TPDOs another COB-ID, or disable it (bit 31).")
define_rule(
    "NET005", W, "RPDO COB-ID that no node transmits",
    why="An enabled RPDO waits for a frame no node of the network sends: its entries never change. "
    "Often a node-id or COB-ID typo.",
    example="node 1: [1401sub1] DefaultValue=0x183\n(no node 3 in NET.toml)",
    fix="Set the COB-ID of the producing TPDO, add the producer to NET.toml, or disable the RPDO (bit 31).")
define_rule(
    "NET006", E, "RPDO mapping does not match the producing TPDO",
    why="A consumer decodes a frame by its own mapping: unless it has the same number of entries with "
    "the same lengths in the same order as the producer's, every field after the first difference "
    "is read at the wrong bit offset.",
    example="TPDO [1A00] maps 8 bit, 8 bit\nRPDO [1600] maps 16 bit",
    fix="Make the RPDO mapping's lengths follow the TPDO's (pad with dummy entries where needed).")
define_rule(
    "NET007", E, "PDO COB-ID collides with another node's fixed COB-ID",
    why="SDO (0x580+id, 0x600+id), EMCY (0x80+id) and heartbeat (0x700+id) of each node are fixed by "
    "its node-id; a PDO on one of them is taken for that service, or disturbs it.",
    example="node 2: [1800sub1] DefaultValue=0x83\nnode 3 in the network (EMCY 0x83)",
    fix="Move the PDO to a COB-ID that no node's fixed services use.")

FIXED = ((0x80, "EMCY"), (0x580, "SDO response"), (0x600, "SDO request"), (0x700, "heartbeat"))
KINDS = (("RPDO", 0x1400, 0x1600), ("TPDO", 0x1800, 0x1A00))


@dataclass(frozen=True)
class Node:
    od: ObjectDictionary
    node_id: int


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
        return str(Loc(self.node.od.source, self.line))

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
            diags.add("NET004", Loc(p.node.od.source, p.line), f"{p.name} transmits COB-ID 0x{p.cob_id:X}, "
                      f"as {first.name} does ({first.at})", p.comm, 1)
    for p in every:
        producer = producers.get(p.cob_id)
        if p.kind == "RPDO" and producer is None:
            diags.add("NET005", Loc(p.node.od.source, p.line),
                      f"{p.name} receives COB-ID 0x{p.cob_id:X}, which no node transmits", p.comm, 1)
        elif p.kind == "RPDO" and producer is not None:
            _compare(p, producer, diags)
    fixed = {base + node.node_id: (node, what) for node in nodes for base, what in FIXED}
    for p in every:
        owner = fixed.get(p.cob_id)
        if owner is not None and owner[0].node_id != p.node.node_id:
            diags.add("NET007", Loc(p.node.od.source, p.line), f"{p.name} uses COB-ID 0x{p.cob_id:X}, the "
                      f"{owner[1]} COB-ID of node {owner[0].node_id}", p.comm, 1)


def _compare(rpdo: Pdo, tpdo: Pdo, diags: Diagnostics) -> None:
    if rpdo.lengths is None or tpdo.lengths is None:
        return
    mine, theirs = [b for b, _, _ in rpdo.lengths], [b for b, _, _ in tpdo.lengths]
    if mine == theirs:
        return
    differ = next((i for i, (a, b) in enumerate(zip(mine, theirs, strict=False)) if a != b), None)
    line, sub = (rpdo.lengths[differ][1], rpdo.lengths[differ][2]) if differ is not None else (rpdo.map_line, 0)
    diags.add("NET006", Loc(rpdo.node.od.source, line),
              f"{rpdo.name} maps {rpdo.layout()} but {tpdo.name} ({tpdo.at}) transmits {tpdo.layout()}",
              rpdo.comm + 0x200, sub)
