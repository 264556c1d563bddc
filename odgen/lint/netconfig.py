"""What the network file configures in each node: entries found by name, values read as the
entry's type and checked against its description, PDO wiring turned into PDO parameters.

`configure` returns per node the values the master writes at boot ((index, sub) -> `Configured`,
each with the place in the network file, or the DCF, that set it); the mistakes are NET findings
at those places. `odgen lint --network` and `odgen network` both call it.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field

from ..catalogue.network import NET001, NET008, NET009, NET010, NET011, NET012, NET013, NET015
from ..diagnostics import Diagnostics, Loc, where
from ..model import ObjectDictionary, Sub, Value
from ..model.cia301 import RPDO_COMM, RPDO_MAPPING, TPDO_COMM, TPDO_MAPPING
from ..model.values import number, parse_value
from ..model.wire import wire_bytes
from .netfile import NetworkSpec, NodeSpec, PdoSpec

_ADDRESS_RE = re.compile(r"^0x([0-9A-Fa-f]{1,4})(?:sub(?:0x([0-9A-Fa-f]+)|(\d+)))?$")
PDO_BITS = 64
SYNC_GENERATE = 0x40000000  # 0x1005 bit 30: the node produces SYNC
PDO_OFF = 0x80000000  # COB-ID bit 31: the PDO does not exist


@dataclass(frozen=True)
class Configured:
    value: Value  # parsed as the entry's type; `resolve(node_id)` gives the number
    loc: Loc  # where it was configured


@dataclass
class NodeModel:
    """A node of the network: its entry in the network file, its description, what is configured."""

    spec: NodeSpec
    od: ObjectDictionary
    values: dict[tuple[int, int], Configured] = field(default_factory=dict)
    wired: dict[tuple[int, int], int] = field(default_factory=dict)  # PDO parameters the wiring set

    @property
    def node_id(self) -> int:
        return self.spec.node_id or 0

    def data(self, index: int, sub: int) -> bytes:
        """The bytes the master writes for a configured entry."""
        entry = self.od.find(index, sub)
        assert entry is not None and entry.dtype is not None
        resolved = self.values[(index, sub)].value.resolve(self.node_id)
        assert resolved is not None
        return wire_bytes(resolved, entry.dtype)

    def in_force(self, index: int, sub: int) -> int | None:
        """The number a node starts with once configured: the configured value, else its description's."""
        configured = self.values.get((index, sub))
        entry = self.od.find(index, sub)
        value = configured.value if configured else self.od.value_in_force(entry) if entry else None
        resolved = value.resolve(self.node_id) if value is not None else None
        return resolved if isinstance(resolved, int) else None

    def configured_od(self) -> ObjectDictionary:
        """A copy of the description, as a DCF, with every configured value as its ParameterValue."""
        od = copy.copy(self.od)
        od.format = "dcf" if od.format in ("eds", "dcf") else "xdc"
        od.node_id = self.node_id
        od.objects = dict(od.objects)
        for (index, sub), configured in self.values.items():
            obj = copy.copy(od.objects[index])
            obj.subs = dict(obj.subs)
            obj.subs[sub] = copy.copy(obj.subs[sub])
            obj.subs[sub].parameter_value = configured.value
            od.objects[index] = obj
        return od


def _norm(text: str) -> str:
    return re.sub(r"[\s_]+", "", text).lower()


def find_entry(od: ObjectDictionary, text: str) -> list[tuple[int, int]]:
    """The entries `text` names: `0x6000sub1`, `0x1017`, an object's name (a VAR), `object/sub`, or a
    sub-entry's name; names compared without regard to case, spaces and underscores."""
    address = _ADDRESS_RE.match(text.strip())
    if address:
        index = int(address.group(1), 16)
        subindex = int(address.group(2), 16) if address.group(2) else int(address.group(3) or 0)
        return [(index, subindex)] if od.find(index, subindex) is not None else []
    wanted = _norm(text)
    obj_name, _, sub_name = (_norm(part) for part in text.rpartition("/"))
    return [(obj.index, sub.subindex) for obj in od.sorted_objects() for sub in obj.sorted_subs()
            if (obj.is_var and _norm(obj.name) == wanted)
            or (not obj.is_var and sub.subindex and (_norm(sub.name) == wanted
                                                     or (obj_name and _norm(obj.name) == obj_name
                                                         and _norm(sub.name) == sub_name)))]


def resolve(node: NodeModel, text: str, loc: Loc, diags: Diagnostics) -> tuple[int, int] | None:
    """The one entry `text` names in the node's description; NET008 when none or several."""
    found = find_entry(node.od, text)
    if len(found) == 1:
        return found[0]
    if not found and _ADDRESS_RE.match(text.strip()):
        diags.add(NET008, loc, f"{node.spec.name}: {node.od.source} has no entry {text.strip()}")
    elif not found:
        diags.add(NET008, loc, f"{node.spec.name}: no entry of {node.od.source} is named {text!r}")
    else:
        shown = ", ".join(where(i, s) for i, s in found[:5]) + (" ..." if len(found) > 5 else "")
        diags.add(NET008, loc, f"{node.spec.name}: {text!r} names {len(found)} entries of {node.od.source} "
                  f"({shown}); write the index and sub-index")
    return None


def _text(value: int | float | str | bool) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"
    return repr(value) if isinstance(value, float) else str(value)


def set_value(node: NodeModel, index: int, subindex: int, raw: int | float | str | bool, loc: Loc,
              diags: Diagnostics) -> bool:
    """Configure one entry; NET009 if the description does not let it be written, NET010 if the
    value is not one of its type or outside its limits."""
    obj, sub = node.od.objects.get(index), node.od.find(index, subindex)
    if obj is None or sub is None:
        diags.add(NET009, loc, f"{node.spec.name}: {node.od.source} has no such entry", index, subindex)
        return False
    at = None if obj.is_var else subindex  # findings name 0x1017, not 0x1017sub0
    if not sub.writable:
        diags.add(NET009, loc, f"{node.spec.name}: {sub.name!r} is {sub.access or 'without access type'} in "
                  f"{node.od.source}:{sub.line}; the master cannot write it", index, at)
        return False
    value = parse_value(_text(raw), sub.dtype, loc.line)
    problem = _outside(node, sub, value)
    if problem:
        diags.add(NET010, loc, f"{node.spec.name}: {sub.name!r} = {raw!r}: {problem}", index, at)
        return False
    node.values[(index, subindex)] = Configured(value, loc)
    return True


def _outside(node: NodeModel, sub: Sub, value: Value) -> str | None:
    dtype = sub.dtype
    if dtype is None or sub.data_type == 0x000F:
        return f"odgen configures entries of a basic type, not {sub.data_type!r}"
    if value.error:
        return f"not a {dtype.name}: {value.error}"
    resolved = value.resolve(node.node_id)
    if dtype.is_numeric and isinstance(resolved, (int, float)):
        if (dtype.min is not None and resolved < dtype.min) or (dtype.max is not None and resolved > dtype.max):
            return f"outside {dtype.name}"
        for bound, beyond, word in ((sub.low, resolved < _bound(sub.low, node), "below LowLimit"),
                                    (sub.high, resolved > _bound(sub.high, node), "above HighLimit")):
            if bound is not None and beyond:
                return f"{word} {bound.text} ({node.od.source}:{bound.line or sub.line})"
    return None


def _bound(limit: Value | None, node: NodeModel) -> float:
    if limit is None:
        return 0.0
    n = number(limit)
    if n is None:
        return float("nan")  # compares false: a limit that is not a number limits nothing
    return float(n + node.node_id if limit.nodeid else n)


def configure(network: NetworkSpec, nodes: list[NodeModel], dcfs: dict[str, ObjectDictionary | None],
              diags: Diagnostics) -> None:
    """Fill each node's `values`: its DCF's ParameterValues, then `[node.values]`, then the wiring."""
    for node in nodes:
        dcf = dcfs.get(node.spec.name)
        if dcf is not None:
            _from_dcf(node, dcf, diags)
        for setting in node.spec.settings:
            loc = Loc(network.source, setting.line)
            entry = resolve(node, setting.key, loc, diags)
            if entry is not None:
                set_value(node, *entry, setting.value, loc, diags)
    by_name = {node.spec.name: node for node in nodes}
    for pdo in network.pdos:
        _wire(pdo, by_name, network.source, diags)
    for node in nodes:
        _pdo_without_cob_id(node, diags)


def _pdo_without_cob_id(node: NodeModel, diags: Diagnostics) -> None:
    """A configured mapping is written between invalidating and validating its PDO's COB-ID
    (CiA 301), so the PDO's communication object must have one."""
    for (index, sub), configured in list(node.values.items()):
        if (RPDO_MAPPING <= index < RPDO_MAPPING + 0x200 or TPDO_MAPPING <= index < TPDO_MAPPING + 0x200) \
                and node.in_force(index - 0x200, 1) is None:
            diags.add(NET009, configured.loc, f"{node.spec.name}: {node.od.source} has no COB-ID "
                      f"{where(index - 0x200, 1)} for this mapping's PDO; it cannot be changed as CiA 301 "
                      "requires", index, sub)
            del node.values[(index, sub)]


def _from_dcf(node: NodeModel, dcf: ObjectDictionary, diags: Diagnostics) -> None:
    """A DCF's ParameterValues that differ from the description's values in force."""
    for obj in dcf.sorted_objects():
        for sub in obj.sorted_subs():
            given = sub.parameter_value
            if given is None or given.empty:
                continue
            mine = node.od.find(obj.index, sub.subindex)
            start = node.od.value_in_force(mine) if mine is not None else None
            if start is not None and start.resolve(node.node_id) == given.resolve(node.node_id):
                continue
            set_value(node, obj.index, sub.subindex, given.text, Loc(dcf.source, given.line or sub.line), diags)


def _wire(pdo: PdoSpec, by_name: dict[str, NodeModel], source: str, diags: Diagnostics) -> None:
    loc = Loc(source, pdo.loc.line)
    producer, consumer = by_name.get(pdo.producer), by_name.get(pdo.consumer)
    for name, node, key in ((pdo.producer, producer, "from"), (pdo.consumer, consumer, "to")):
        if node is None:
            diags.add(NET001, Loc(source, pdo.line(key)), f"[[pdo]] `{key}` = {name!r} is no node of the network")
    if producer is None or consumer is None:
        return
    cob = pdo.cob_id
    if cob is None and pdo.tpdo <= 4:
        cob = 0x180 + 0x100 * (pdo.tpdo - 1) + producer.node_id
    if cob is None:
        diags.add(NET001, loc, f"[[pdo]] TPDO{pdo.tpdo} has no predefined COB-ID: give `cob_id`")
        return
    mapped = _entries(pdo, producer, consumer, loc, diags)
    if mapped is None:
        return
    sides = (("TPDO", producer, TPDO_COMM, TPDO_MAPPING, pdo.tpdo, [(a, bits) for a, _, bits in mapped]),
             ("RPDO", consumer, RPDO_COMM, RPDO_MAPPING, pdo.rpdo, [(b, bits) for _, b, bits in mapped]))
    for kind, node, comm, mapping, pdo_number, entries in sides:
        c, m = comm + pdo_number - 1, mapping + pdo_number - 1
        if node.od.find(c, 1) is None or node.od.find(m, 0) is None \
                or any(node.od.find(m, n) is None for n in range(1, len(entries) + 1)):
            diags.add(NET012, loc, f"{node.spec.name} has no {kind}{pdo_number} with {len(entries)} mapping "
                      f"entries ({where(c)}, {where(m)}) in {node.od.source}")
            continue
        words = [(index << 16) | (sub << 8) | bits for (index, sub), bits in entries]
        wanted = {(c, 1): cob, (c, 2): pdo.transmission, (m, 0): len(entries)}
        wanted.update({(m, n): w for n, w in enumerate(words, start=1)})
        for (index, sub), value in wanted.items():
            at = Loc(source, pdo.line("transmission")) if (index, sub) == (c, 2) else loc
            _wire_value(node, index, sub, value, at, diags)


def _wire_value(node: NodeModel, index: int, sub: int, value: int, loc: Loc, diags: Diagnostics) -> None:
    before = node.wired.get((index, sub))
    if before is not None and before != value:
        line = node.values[(index, sub)].loc.line
        diags.add(NET012, loc, f"{node.spec.name}: this wiring sets 0x{value:X}, the wiring at line {line} "
                  f"0x{before:X}", index, sub)
        return
    if set_value(node, index, sub, value, loc, diags):
        node.wired[(index, sub)] = value


def _entries(pdo: PdoSpec, producer: NodeModel, consumer: NodeModel, loc: Loc,
             diags: Diagnostics) -> list[tuple[tuple[int, int], tuple[int, int], int]] | None:
    """Per wired pair: the producer's entry, the consumer's entry, their length in bits."""
    mapped: list[tuple[tuple[int, int], tuple[int, int], int]] = []
    bits, ok = 0, True
    for sent, taken in pdo.entries:
        a, b = resolve(producer, sent, loc, diags), resolve(consumer, taken, loc, diags)
        if a is None or b is None:
            ok = False
            continue
        sa, sb = producer.od.find(*a), consumer.od.find(*b)
        assert sa is not None and sb is not None
        problem = _unmappable(sa, "a TPDO", sa.readable) or _unmappable(sb, "an RPDO", sb.writable)
        if problem is None and (sa.dtype is None or sb.dtype is None or sa.dtype != sb.dtype):
            problem = (f"{sent!r} is {sa.dtype.name if sa.dtype else '?'} but {taken!r} is "
                       f"{sb.dtype.name if sb.dtype else '?'}; a consumer must take the type the producer sends")
        if problem is not None:
            diags.add(NET012, loc, f"{producer.spec.name} -> {consumer.spec.name}: {problem}")
            ok = False
            continue
        assert sa.dtype is not None
        mapped.append((a, b, sa.dtype.bits))
        bits += sa.dtype.bits
    if ok and bits > PDO_BITS:
        diags.add(NET012, loc, f"{producer.spec.name} -> {consumer.spec.name}: {bits} bit mapped, a CAN PDO "
                  f"carries {PDO_BITS}")
        ok = False
    return mapped if ok else None


def _unmappable(sub: Sub, pdo: str, direction: bool) -> str | None:
    if not sub.pdo_mapping:
        return f"{sub.name!r} cannot be mapped (PDOMapping=0)"
    if not direction or sub.dtype is None or sub.dtype.bits == 0:
        return f"{sub.name!r} ({sub.access}) cannot be mapped into {pdo}"
    return None


IDENTITY = (("vendor_id", 1), ("product_code", 2), ("revision", 3), ("serial", 4))


def expected_identity(node: NodeModel) -> dict[int, int]:
    """0x1018 sub -> the value the master expects (0x1F85-0x1F88); a sub not checked is left out."""
    expected = {}
    for key, sub in IDENTITY:
        given = node.spec.options.get(key)
        if isinstance(given, int) and not isinstance(given, bool):
            expected[sub] = given
        elif sub < 4 and node.spec.options.get("check_identity", True):
            described = node.in_force(0x1018, sub)
            if described:
                expected[sub] = described
    return expected


def check_boot(network: NetworkSpec, nodes: list[NodeModel], diags: Diagnostics) -> None:
    """NET011 identities that cannot match, NET013 heartbeat times the slave cannot meet."""
    for node in nodes:
        if node.spec.master:
            continue
        for key, sub in IDENTITY:
            given = node.spec.options.get(key)
            if not isinstance(given, int) or isinstance(given, bool):
                continue
            entry, described = node.od.find(0x1018, sub), node.in_force(0x1018, sub)
            loc = Loc(network.source, node.spec.line(key))
            if entry is None:
                diags.add(NET011, loc, f"{node.spec.name}: {key} 0x{given:X} is checked against 0x1018sub{sub}, "
                          f"which {node.od.source} does not have", 0x1018, sub)
            elif described and described != given:  # 0: a description of any unit, not of this one
                diags.add(NET011, loc, f"{node.spec.name}: {key} 0x{given:X} but {node.od.source}:{entry.line} "
                          f"gives 0x{described:X}", 0x1018, sub)
        booted = network.master is not None  # without a master nobody checks identities
        if booted and node.spec.options.get("check_identity", True) and node.od.find(0x1018, 1) is None:
            diags.add(NET011, Loc(network.source, node.spec.line("check_identity")),
                      f"{node.spec.name}: the identity is checked but {node.od.source} has no 0x1018sub1 "
                      "(vendor-ID); set check_identity = false", 0x1018, 1)
        _heartbeat(network, node, diags)


def _heartbeat(network: NetworkSpec, node: NodeModel, diags: Diagnostics) -> None:
    consumer = node.spec.options.get("heartbeat", 0)
    if not isinstance(consumer, int) or not consumer:
        return
    producer = node.in_force(0x1017, 0)
    loc = Loc(network.source, node.spec.line("heartbeat"))
    if producer is None or producer == 0:
        diags.add(NET013, loc, f"{node.spec.name}: the master expects a heartbeat every {consumer} ms but the "
                  f"slave sends none (0x1017 = {producer if producer is not None else 'absent'}); configure 0x1017",
                  0x1017)
    elif consumer <= producer:
        diags.add(NET013, loc, f"{node.spec.name}: heartbeat {consumer} ms is not longer than the slave's "
                  f"producer heartbeat time 0x1017 = {producer} ms", 0x1017)


def produces_sync(node: NodeModel) -> bool:
    """Whether the node, once configured, sends SYNC: 0x1005 bit 30 set and 0x1006 (µs) not 0."""
    return bool((node.in_force(0x1005, 0) or 0) & SYNC_GENERATE) and (node.in_force(0x1006, 0) or 0) > 0


def _synchronous(kind: str, transmission: int) -> bool:
    """CiA 301 transmission types acted on at SYNC: 0..240, and 252 for a TPDO (sampled at SYNC, sent on RTR)."""
    return transmission <= 240 or (kind == "TPDO" and transmission == 252)


def _configured_pdos(node: NodeModel) -> dict[int, list[Loc]]:
    """The communication object of each PDO the network file (or a DCF) configures, with the places."""
    found: dict[int, list[Loc]] = {}
    for (index, _sub), configured in node.values.items():
        for comm in (RPDO_COMM, TPDO_COMM):
            if comm <= index < comm + 0x400:  # its communication object, or its mapping 0x200 above
                found.setdefault(comm + (index - comm) % 0x200, []).append(configured.loc)
    return found


def check_sync(nodes: list[NodeModel], diags: Diagnostics) -> None:
    """NET015: a PDO the network wires or configures that waits for SYNC, where no node sends SYNC."""
    if any(produces_sync(node) for node in nodes):
        return
    for node in nodes:
        for comm, locs in sorted(_configured_pdos(node).items()):
            kind, number = ("RPDO", comm - RPDO_COMM + 1) if comm < TPDO_COMM else ("TPDO", comm - TPDO_COMM + 1)
            cob, transmission = node.in_force(comm, 1), node.in_force(comm, 2)
            if cob is None or cob & PDO_OFF or transmission is None or not _synchronous(kind, transmission):
                continue
            given = node.values.get((comm, 2))
            loc = given.loc if given else min(locs, key=lambda at: (at.file, at.line))
            acts = "transmits" if kind == "TPDO" else "applies what it receives"
            diags.add(NET015, loc, f"{node.spec.name}: {kind}{number} (transmission type {transmission}) {acts} "
                      "only at SYNC, and no node of the network produces SYNC (0x1005 bit 30 and 0x1006 > 0)",
                      comm, 2)
