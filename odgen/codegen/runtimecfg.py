"""The runtime compiled to what a dictionary uses: the ODG_CFG_* switches of NAME_config.h, and the
node layer sized to it: the ODG_NODE_* limits (node_limits).

Each switch turns a feature of runtime/odg.c on when the dictionary has something that needs it;
the rest is left out of the build (64-bit arithmetic on a 32-bit core, string and domain
handling, hooks, limit checks, persistence groups, the 0x1010/0x1011 commands, the lookup modes
the dictionary does not use, and in runtime/odg_persist.c the migration of strings and domains
the "ODG1" path of groups without migration, and the boot migration when no group migrates).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..catalogue.gen import GEN001, GEN010
from ..diagnostics import Diagnostics, Loc
from ..model import ObjectDictionary
from ..place.options import table_key_line

if TYPE_CHECKING:  # the view-model calls runtime_config() to finish a view
    from .viewmodel import DictView

WIDE = {0x0C, 0x0D, 0x11, 0x12, 0x13, 0x14, 0x15, 0x18, 0x19, 0x1A, 0x1B}  # wider than 32 bits
STRINGS = {0x09, 0x0A}
UNICODE = 0x0B
DOMAIN = 0x0F
STREAMS = {*STRINGS, UNICODE, DOMAIN}
REALS = {0x08, 0x11}


def width(size: int) -> int:
    """Bytes of the C type of a number of wire size `size` (ODG_STRIDE in runtime/odg.h)."""
    return 4 if size == 3 else (8 if size > 4 else size)


@dataclass
class Switch:
    macro: str
    what: str
    on: bool
    why: str  # the first entry that needs it, or ""


def _first(view: DictView, positions: list[int]) -> str:
    """'0xIIIIsubS' of the first sub-entry position."""
    if not positions:
        return ""
    pos = min(positions)
    entry = next(e for e in view.entries if e.first <= pos < e.first + e.count)
    return f"0x{entry.index:04X}sub{view.subs[pos].sub}"


def runtime_config(view: DictView) -> list[Switch]:
    subs = list(enumerate(view.subs))
    limited = {lim.sub_pos for lim in view.limits}
    persisted = [p for p, s in subs if "ODG_S_PERSIST" in s.storage]
    migration = view.persist is not None and view.persist.migration
    needs = [
        ("ODG_CFG_INT64", "types wider than 32 bits", [p for p, s in subs if s.type in WIDE]),
        ("ODG_CFG_STRINGS", "VISIBLE_STRING / OCTET_STRING", [p for p, s in subs if s.type in STRINGS]),
        ("ODG_CFG_UNICODE", "UNICODE_STRING", [p for p, s in subs if s.type == UNICODE]),
        ("ODG_CFG_DOMAINS", "DOMAIN", [p for p, s in subs if s.type == DOMAIN]),
        ("ODG_CFG_HOOKS", "hooks", [h.sub_pos for h in view.hooks]),
        ("ODG_CFG_LIMITS", "limits on integers", [p for p in limited if view.subs[p].type not in REALS]),
        ("ODG_CFG_REAL_LIMITS", "limits on REAL32 / REAL64", [p for p in limited if view.subs[p].type in REALS]),
        ("ODG_CFG_GROUPS", "persistence groups", [p for p, s in subs if "ODG_S_PERSIST" in s.storage]),
        ("ODG_CFG_COMMAND", "0x1010 / 0x1011 commands", [p for p, s in subs if "ODG_S_COMMAND" in s.storage]),
        ("ODG_CFG_PACKED", "ARRAYs and RECORDs whose elements share one descriptor",
         [e.first + 1 for e in view.entries if "ODG_E_PACKED" in e.code]),
        ("ODG_CFG_SHARED", "runs of alike entries that share their descriptors",
         [e.first for e in view.entries if "ODG_E_SHARED" in e.code]),
        ("ODG_CFG_PERSIST_STREAMS", "strings or domains in a migrated persistence group",
         [p for p in persisted if view.subs[p].type in STREAMS] if migration else []),
        ("ODG_CFG_PERSIST_STATUS", "boot status object",
         [p for e in view.entries if view.persist is not None and e.index == view.persist.status_object
          for p in range(e.first, e.first + e.count)]),
        ("ODG_CFG_PERSIST_ODG1", "persistence groups without migration", persisted[:1] if not migration else []),
        ("ODG_CFG_PERSIST_MIGRATION", "persistence groups migrated at boot", persisted[:1] if migration else []),
        # with one group no other group's boot can write over its image before it moves home
        ("ODG_CFG_PERSIST_TWO_PASS", "a migrated group among two or more (the ordered boot)",
         persisted[:1] if migration and len(view.groups) > 1 else []),
    ]
    switches = [Switch(macro, what, bool(where), _first(view, where)) for macro, what, where in needs]
    for switch in switches:  # a packed descriptor's sub is the last element's: name them all
        if switch.macro == "ODG_CFG_PACKED" and switch.on:
            entry = next(e for e in view.entries if "ODG_E_PACKED" in e.code)
            switch.why = f"0x{entry.index:04X}sub1..{view.subs[entry.first + 1].sub}"
    hashed = view.lookup == "hash"
    wide = view.hash is not None and view.hash.bits > 8
    return switches + [Switch("ODG_CFG_HASH", "lookup by perfect hash", hashed, "--lookup hash" if hashed else ""),
                       Switch("ODG_CFG_HASH_WIDE", "a perfect hash of more than 256 slots (16-bit tables)", wide,
                              f"{len(view.entries)} entries" if wide else ""),
                       Switch("ODG_CFG_UNHASHED", "lookup by generated find or binary search", not hashed,
                              f"--lookup {view.lookup}" if not hashed else "")]


# ---- the node layer's limits (runtime/odg_node.h) ----------------------------------------------

@dataclass(frozen=True)
class NodeKey:
    """One [node] key of the options file: the ODG_NODE_* limit it sets and what it may be."""
    key: str
    macro: str
    what: str
    low: int
    high: int
    default: int | None = None  # a limit the dictionary does not decide: the value without the key


NODE_KEYS = (
    NodeKey("rpdo", "ODG_NODE_MAX_RPDO", "RPDOs served (0x1400 + n)", 0, 512),
    NodeKey("tpdo", "ODG_NODE_MAX_TPDO", "TPDOs served (0x1800 + n)", 0, 512),
    NodeKey("mapping", "ODG_NODE_MAX_MAP", "mapping entries per PDO", 0, 64),
    NodeKey("heartbeat_consumers", "ODG_NODE_MAX_HB", "heartbeats watched (0x1016 sub 1..)", 0, 127),
    NodeKey("comm_bytes", "ODG_NODE_COMM_BYTES", "bytes of communication values reset communication restores",
            0, 65535),
    NodeKey("errors", "ODG_NODE_MAX_ERRORS", "errors active at once", 1, 255, 8),
    NodeKey("emcy_queue", "ODG_NODE_EMCY_QUEUE", "EMCY frames held back by the inhibit time 0x1015", 1, 255, 4),
)
MAX_MAPPING = 64  # CiA 301: a PDO maps at most 64 objects (one bit each)
# The master's limit (runtime/odg_master.h), in a dictionary with 0x1F81 only
MASTER_SLAVES = NodeKey("slaves", "ODG_MASTER_MAX_SLAVES", "slaves the master boots (0x1F81 bit 0)", 1, 127, 8)
SLAVE_ASSIGNMENT = 0x1F81


@dataclass
class NodeLimit:
    macro: str
    value: int
    what: str
    why: str  # what in the dictionary (or the options) decided the value


def node_options(raw: dict[str, object], source: str, text: str, diags: Diagnostics) -> dict[str, int]:
    """The limit keys of an options file's [node] table (lss and sdo_block are read with the placement options);
    a key odgen does not know, or a value out of its range, is GEN001 at the key's line."""
    keys = {k.key: k for k in (*NODE_KEYS, MASTER_SLAVES)}
    limits: dict[str, int] = {}
    for name, value in raw.items():
        spec = keys.get(name)
        loc = Loc(source, table_key_line(text, "node", name))
        if spec is None:
            diags.add(GEN001, loc, f"[node] has no key '{name}'; use lss, sdo_block or {', '.join(keys)}")
        elif isinstance(value, bool) or not isinstance(value, int) or not spec.low <= value <= spec.high:
            diags.add(GEN001, loc, f"[node] {name} = {value!r}: give a whole number {spec.low}..{spec.high}")
        else:
            limits[name] = value
    return limits


def _highest_subs(view: DictView, lo: int, hi: int) -> dict[int, int]:
    """index -> highest sub-index, for the entries of lo..hi (a packed descriptor names its last element)."""
    return {e.index: max(view.subs[p].sub for p in range(e.first, e.first + e.count))
            for e in view.entries if lo <= e.index <= hi}


def comm_bytes(view: DictView) -> int:
    """The bytes odg_node_comm_bytes(&dict) counts: the numbers of 0x1000-0x1FFF but 0x1003 that an
    SDO client may write, in RAM or a persistence group, each in the bytes of its C type."""
    packed = {p.index: p.count for p in view.packed}
    total = 0
    for e in view.entries:
        if not 0x1000 <= e.index <= 0x1FFF or e.index == 0x1003:
            continue
        for p in range(e.first, e.first + e.count):
            s = view.subs[p]
            kept = ("ODG_A_WRITE" in s.attr and ("ODG_S_RAM" in s.storage or "ODG_S_PERSIST" in s.storage)
                    and s.size <= 8 and s.type not in STREAMS)
            if kept:
                elements = packed.get(e.index, 1) if p == e.first + 1 and e.index in packed else 1
                total += elements * width(s.size)
    return total


def node_limits(view: DictView, od: ObjectDictionary, lss: bool, caps: dict[str, int],
                diags: Diagnostics, sdo_block: bool = True) -> list[NodeLimit]:
    """The ODG_NODE_* limits the dictionary needs, lowered where the options' [node] keys say; a PDO,
    mapping entry or heartbeat entry beyond a lowered limit is GEN010 (the node could not serve it)."""
    rpdo = sorted(e.index - 0x1400 for e in view.entries if 0x1400 <= e.index <= 0x15FF)
    tpdo = sorted(e.index - 0x1800 for e in view.entries if 0x1800 <= e.index <= 0x19FF)
    mapping = {**_highest_subs(view, 0x1600, 0x17FF), **_highest_subs(view, 0x1A00, 0x1BFF)}
    consumers = _highest_subs(view, 0x1016, 0x1016)
    needs = {
        "rpdo": (rpdo[-1] + 1 if rpdo else 0, f"0x{0x1400 + rpdo[-1]:04X}" if rpdo else "no RPDO"),
        "tpdo": (tpdo[-1] + 1 if tpdo else 0, f"0x{0x1800 + tpdo[-1]:04X}" if tpdo else "no TPDO"),
        "mapping": (min(max(mapping.values(), default=0), MAX_MAPPING),
                    _widest(mapping) if mapping else "no PDO mapping"),
        "heartbeat_consumers": (consumers.get(0x1016, 0), "0x1016" if consumers else "no 0x1016"),
        "comm_bytes": (comm_bytes(view), "0x1000-0x1FFF"),
    }
    _refuse_beyond(od, caps, rpdo, tpdo, mapping, consumers, diags)
    limits = []
    for spec in NODE_KEYS:
        need, why = needs.get(spec.key, (spec.default or 0, "default"))
        value = need if spec.default is None else spec.default
        if spec.key in caps:
            value = min(value, caps[spec.key]) if spec.default is None else caps[spec.key]
            why = f"[node] {spec.key} = {caps[spec.key]}; {why}"
        if spec.key != "comm_bytes":  # arrays: C has no empty ones
            value = max(value, 1)
        limits.append(NodeLimit(spec.macro, value, spec.what, why))
    limits.append(NodeLimit("ODG_NODE_LSS", int(lss), "the LSS slave (odg_lss.c)",
                            "LSS_Supported=1 or [node] lss" if lss else "not supported"))
    limits.append(NodeLimit("ODG_NODE_SDO_BLOCK", int(sdo_block), "SDO block transfer (odg_sdo.c)",
                            "served unless [node] sdo_block = false" if sdo_block else "[node] sdo_block = false"))
    return limits + master_limits(od, caps, diags)


def master_limits(od: ObjectDictionary, caps: dict[str, int], diags: Diagnostics) -> list[NodeLimit]:
    """ODG_MASTER_MAX_SLAVES, for a dictionary with 0x1F81 (a master's): the slaves its 0x1F81
    assigns as generated (bit 0 of a sub-entry's value), as `odgen network` writes it. When none is
    (0x1F81 filled at run time), the runtime's default; [node] slaves sets it, and one below the
    slaves assigned is GEN010 (the master would ignore the last ones)."""
    obj = od.objects.get(SLAVE_ASSIGNMENT)
    if obj is None:
        return []
    assigned = []
    for sub in obj.subs.values():
        value = od.value_in_force(sub)
        number = value.resolve(0) if value is not None else None
        if 1 <= sub.subindex <= 127 and isinstance(number, int) and number & 1:
            assigned.append(sub.subindex)
    spec = MASTER_SLAVES
    if spec.key in caps:
        if caps[spec.key] < len(assigned):
            diags.add(GEN010, Loc(od.source, obj.line),
                      f"0x1F81 assigns {len(assigned)} slaves, but the options' [node] slaves = {caps[spec.key]} "
                      "leaves some out: raise slaves", SLAVE_ASSIGNMENT, None)
        return [NodeLimit(spec.macro, caps[spec.key], spec.what, f"[node] slaves = {caps[spec.key]}")]
    if not assigned:
        return [NodeLimit(spec.macro, spec.default or 1, spec.what, "0x1F81 assigns none when generated: default")]
    return [NodeLimit(spec.macro, len(assigned), spec.what,
                      f"0x1F81 assigns {len(assigned)} (node {', '.join(map(str, sorted(assigned)))})")]


def _widest(mapping: dict[int, int]) -> str:
    index = max(mapping, key=lambda i: (mapping[i], -i))
    return f"0x{index:04X}sub{mapping[index]}"


def _refuse_beyond(od: ObjectDictionary, caps: dict[str, int], rpdo: list[int], tpdo: list[int],
                   mapping: dict[int, int], consumers: dict[int, int], diags: Diagnostics) -> None:
    """GEN010 for every object whose PDO, mapping entries or heartbeat entries a lowered limit leaves out."""
    def refuse(index: int, sub: int | None, key: str, what: str) -> None:
        obj = od.objects.get(index)
        found = obj.subs.get(sub) if obj is not None and sub is not None else None
        line = found.line if found is not None and found.line else (obj.line if obj is not None else 0)
        diags.add(GEN010, Loc(od.source, line),
                  f"{what}, but the options' [node] {key} = {caps[key]} leaves it out: raise {key} "
                  "or remove it from the description", index, sub)

    for key, base, ks in (("rpdo", 0x1400, rpdo), ("tpdo", 0x1800, tpdo)):
        for k in ks if key in caps else []:
            if k >= caps[key]:
                refuse(base + k, None, key, f"{key.upper()} {k + 1} is described")
    for index, highest in sorted(mapping.items()) if "mapping" in caps else []:
        if highest > caps["mapping"]:
            refuse(index, caps["mapping"] + 1, "mapping", f"the mapping has {min(highest, MAX_MAPPING)} entries")
    if "heartbeat_consumers" in caps and consumers.get(0x1016, 0) > caps["heartbeat_consumers"]:
        refuse(0x1016, caps["heartbeat_consumers"] + 1, "heartbeat_consumers",
               f"{consumers[0x1016]} heartbeat consumer entries are described")
