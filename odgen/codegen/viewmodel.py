"""Everything the templates print, decided here: names, C types, initializers, tables.

The templates only loop over these lists. Values live in one struct per storage
class (rom in FLASH; ram and each persistence group in RAM with a const defaults
copy), members ordered by alignment so the compiler adds no padding.

The large tables have a row per sub-entry (value members, sub-entries, name macros,
accessors) or per entry: five rows per sub-entry in all. A jinja2 loop pays for every
field and every piece of text of every row, which made up most of a large render, so
the templates print these tables with the `rows` filter (generate.py): each row is
one printf-style line, written in the template, filled from the row's fields. Rows
are NamedTuples whose fields the template names, or plain tuples in the order of
their line (macros, accessors), built once per sub-entry here.
"""

from __future__ import annotations

import functools
import math
import re
import struct
import zlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from operator import attrgetter
from typing import NamedTuple

from ..catalogue.gen import GEN004, GEN005, GEN006, GEN007, GEN009
from ..diagnostics import Diagnostics, Loc
from ..model import Obj, ObjectDictionary, Sub, Value
from ..model.expect import initial_value
from ..model.capacity import domain_capacity, domain_default, served_limits, string_capacity, string_default
from ..model.od import READABLE, WRITABLE
from ..model.pdo import default_mapped
from ..model.datatypes import BASIC_TYPES, DataType
from ..cnames import COMMENT_WIDTH, comment, identifier, string_literal
from .packing import packable, packs_values
from .sharing import SharedView, share
from .spread import Run, member_size, runs
from ..model.cia301 import RESTORE, STORE
from ..place.options import PersistOptions
from ..place.persistence import PersistView, persist_view
from ..place.placement import Placement, Placements, COMMAND_CLASS
from .lookup import PerfectHash, perfect_hash
from .runtimecfg import NodeLimit, Switch, node_limits, runtime_config

MAX_C_STRING = 4095

# type kind -> (C type by storage width)
_INT_CTYPES = {8: "int8_t", 16: "int16_t", 24: "int32_t", 32: "int32_t", 40: "int64_t", 48: "int64_t",
               56: "int64_t", 64: "int64_t"}
_UINT_CTYPES = {1: "uint8_t", 8: "uint8_t", 16: "uint16_t", 24: "uint32_t", 32: "uint32_t", 40: "uint64_t",
                48: "uint64_t", 56: "uint64_t", 64: "uint64_t"}
ALIGN = {"int8_t": 1, "uint8_t": 1, "char": 1, "int16_t": 2, "uint16_t": 2, "int32_t": 4, "uint32_t": 4,
          "float": 4, "int64_t": 8, "uint64_t": 8, "double": 8}
_GROUP_SUBS = {"comm": 2, "app": 3, "application": 3}
# Initializers of value zero as written here (int_literal, real_literal, empty strings and domains).
_ZERO_INIT = re.compile(r'0|0\.0f?|U?INT(32|64)_C\((0x)?0\)|\{0\}|\{0x0000\}|""')
# StorageStruct.copied: the share of non-zero values from which a RAM block's reset copies its
# defaults (chosen on the corpus's linked Cortex-M4 firmware: never larger than assigning).
DENSE = 0.25


class Member(NamedTuple):
    """One value in a storage struct."""

    name: str
    ctype: str
    array: str  # "" or "[n]"
    init: str
    note: str
    align: int
    key: tuple[int, int]
    # The default's elements up to its last non-zero one (a scalar: 1 or 0) and their initializer:
    # what the group's spread of non-zero defaults keeps of it (spread.py).
    used: int
    head: str


@dataclass
class StorageStruct:
    name: str  # C struct variable, e.g. io_node_ram
    type_name: str
    attr: str  # placement macro
    const: bool
    members: list[Member] = field(default_factory=list)
    defaults: str = ""  # name of the const defaults copy (RAM structs)

    @property
    def qualifier(self) -> str:
        return "const " if self.const else ""

    @property
    def group(self) -> bool:
        """Whether the struct is a persistence group's mirror: its defaults are a spread (spread.py)."""
        return self.attr.startswith("ODG_ATTR_PERSIST_")

    @property
    def spread(self) -> str:
        return f"{self.name}_spread" if self.group else ""

    @functools.cached_property  # asked once the members are complete and sorted
    def runs(self) -> list[Run]:
        return runs(self.members, ALIGN)

    @functools.cached_property  # the template asks twice; asked once the members are complete
    def copied(self) -> bool:
        """Whether the reset copies the defaults with odg_copy rather than assigning the struct.
        A persistence group's defaults are in FLASH for the persistence layer anyway; a RAM block
        of which at least DENSE of the values start non-zero costs less as a copied table than
        as one store per value. Assigning a sparse block lets compilers clear it and store the
        few other values with no table, but a dense one becomes a call of libc's memcpy."""
        if self.attr != "ODG_ATTR_RAM":
            return True
        nonzero = sum(1 for m in self.members if not _ZERO_INIT.fullmatch(m.init))
        return nonzero >= DENSE * len(self.members)


class SubView(NamedTuple):
    """A row of NAME_subs."""

    offset: str
    size: int
    sub: int
    type: int
    attr: str
    storage: str
    note: str
    stride: int = 0  # in a shared run's list: bytes from one member's value to the next's (sharing.py)

    @property
    def size_field(self) -> str:
        """`size` as the table holds it: with the stride in its high byte in a shared list."""
        return f"{self.size} | {self.stride}u << 8" if self.stride else str(self.size)


@dataclass
class EntryView:
    index: int
    first: int
    count: int
    code: str
    note: str


@dataclass
class PackedView:
    """An ARRAY whose elements share one descriptor (packing.py): the C asserts their layout."""
    index: int
    first: str  # offset expression of element 1
    last: str  # of element `count`
    count: int
    size: int


@dataclass
class GroupView:
    name: str
    mirror: str
    defaults: str
    type_name: str
    signature: int
    store_sub: int  # the group's place in NV: persistview.PersistView
    spread: str  # the table placing the runs of `defaults` (spread.py)
    defaults_ref: str  # &defaults, or NULL when every default is zero


@dataclass
class HookView:
    sub_pos: int
    kinds: str
    function: str
    note: str


@dataclass
class LimitView:
    low: str
    high: str
    sub_pos: int
    note: str


@dataclass
class DomainView:
    name: str
    buffer: str
    length: str
    capacity: int


@dataclass
class DictView:
    name: str
    upper: str
    version: str
    digest: str
    source: str
    lookup: str
    structs: list[StorageStruct] = field(default_factory=list)
    entries: list[EntryView] = field(default_factory=list)
    subs: list[SubView] = field(default_factory=list)
    limits: list[LimitView] = field(default_factory=list)
    hooks: list[HookView] = field(default_factory=list)
    functions: list[str] = field(default_factory=list)
    groups: list[GroupView] = field(default_factory=list)
    domains: list[DomainView] = field(default_factory=list)
    packed: list[PackedView] = field(default_factory=list)
    shared: list[SharedView] = field(default_factory=list)  # runs sharing descriptors (sharing.py)
    macros: list[tuple[str, str, str]] = field(default_factory=list)  # #define name value /* note */
    accessors: list[tuple[str, str]] = field(default_factory=list)  # #define name expression
    persist: PersistView | None = None  # NV regions, layouts, status object
    config: list[Switch] = field(default_factory=list)  # the runtime's ODG_CFG_* switches
    node: list[NodeLimit] = field(default_factory=list)  # the node layer's ODG_NODE_* limits
    hash: PerfectHash | None = None  # for --lookup hash

    def _table(self, suffix: str, present: bool) -> str:
        return f"{self.name}_{suffix}" if present else "NULL"

    @property
    def limits_ref(self) -> str:
        return self._table("limits", bool(self.limits))

    @property
    def hook_map_ref(self) -> str:
        return self._table("hook_map", bool(self.hooks))

    @property
    def hook_slots_ref(self) -> str:
        return self._table("hook_slots", bool(self.hooks))

    @property
    def groups_ref(self) -> str:
        return self._table("groups", bool(self.groups))

    @property
    def domains_ref(self) -> str:
        return self._table("domains", bool(self.domains))

    def _block(self, key: str) -> str:
        block = next((s for s in self.structs if s.name == f"{self.name}_{key}"), None)
        return f"&{block.name}" if block is not None else "NULL"

    @property
    def rom_ref(self) -> str:
        return self._block("rom")

    @property
    def ram_ref(self) -> str:
        return self._block("ram")

    @property
    def find_ref(self) -> str:
        return self._table("find", self.lookup == "switch")


# ---- values ----------------------------------------------------------------------------


def ctype_of(dtype: DataType) -> str:
    if dtype.kind == "int":
        return _INT_CTYPES[dtype.bits]
    if dtype.kind in ("uint", "bool"):
        return _UINT_CTYPES[dtype.bits]
    if dtype.kind == "real":
        return "float" if dtype.bits == 32 else "double"
    if dtype.kind == "time":
        return "uint64_t"
    if dtype.kind == "vstring":
        return "char"
    if dtype.kind == "ustring":
        return "uint16_t"
    return "uint8_t"  # octet string, domain


_CTYPES = {code: ctype_of(dtype) for code, dtype in BASIC_TYPES.items()}  # by data type code


_UNSIGNED_BITS = {"uint8_t": 8, "uint16_t": 16, "uint32_t": 32, "uint64_t": 64}


def int_literal(value: int, ctype: str) -> str:
    bits = _UNSIGNED_BITS.get(ctype)
    if bits is not None:  # modulo 2^bits, as C converts: `$NODEID-1` is stored as the offset -1
        value &= (1 << bits) - 1
    if ctype in ("int64_t", "int32_t"):
        macro = "INT64_C" if ctype == "int64_t" else "INT32_C"
        bits = 64 if ctype == "int64_t" else 32
        if value == -(1 << (bits - 1)):
            return f"(-{macro}({(1 << (bits - 1)) - 1}) - 1)"
        return f"{macro}({value})"
    if ctype == "uint64_t":
        return f"UINT64_C(0x{value:X})"
    if ctype == "uint32_t":
        return f"UINT32_C(0x{value:X})"
    return str(value)


def real_literal(value: float, bits: int) -> str:
    if math.isnan(value):
        return "NAN"
    if math.isinf(value):
        return "INFINITY" if value > 0 else "-INFINITY"
    if bits == 32:
        value = struct.unpack("<f", struct.pack("<f", value))[0]
        return f"{value:.9g}f" if "e" in f"{value:.9g}" or "." in f"{value:.9g}" else f"{value:.9g}.0f"
    text = f"{value:.17g}"
    return text if ("e" in text or "." in text) else text + ".0"


def limit_bits(value: int | float, dtype: DataType) -> int:
    """The 64-bit pattern odg_limit_t holds for a limit of `dtype`."""
    if dtype.kind == "real":
        return int.from_bytes(struct.pack("<d", float(value)), "little")
    return int(value) & 0xFFFFFFFFFFFFFFFF


# ---- the builder --------------------------------------------------------------------------


class _Builder:
    def __init__(self, od: ObjectDictionary, placements: Placements, name: str,
                 diags: Diagnostics) -> None:
        self.od, self.placements, self.diags = od, placements, diags
        self.name = name
        self.structs: dict[str, StorageStruct] = {}  # by storage class, "persist:app"
        self.member_names: dict[str, tuple[int, int]] = {}
        self.storage_codes: dict[str, str] = {}  # ODG_S_* by storage class
        self.mapped = default_mapped(od)  # PDOMapping=0 entries the description's own mappings map (PDO002)
        self.pack_commands = packs_values(od, placements)  # packing.py

    def struct_for(self, storage: str) -> StorageStruct:
        struct = self.structs.get(storage)
        if struct is None:
            key = storage.replace(":", "_")
            const = storage == "rom"
            group = storage.split(":", 1)[1] if ":" in storage else ""
            attr = "ODG_ATTR_ROM" if const else ("ODG_ATTR_PERSIST_" + group.upper() if group else "ODG_ATTR_RAM")
            var = f"{self.name}_{key}"
            struct = self.structs[storage] = StorageStruct(var, f"{var}_t", attr, const,
                                                           defaults="" if const else f"{var}_defaults")
        return struct

    def storage_code(self, placement: Placement) -> str:
        code = self.storage_codes.get(placement.storage)
        if code is None:
            code = self.storage_codes[placement.storage] = _storage_code(placement.storage, self.name.upper())
        return code

    def member_name(self, name: str, obj: Obj, sub: Sub) -> str:
        """`name` for the value member of `sub`, reported (GEN004) when another sub-entry has it."""
        key = (obj.index, sub.subindex)
        if self.member_names.setdefault(name, key) != key:
            self.diags.add(GEN004, Loc(self.od.source, sub.line), f"C name {name} is used twice", obj.index)
        return name


def build(od: ObjectDictionary, placements: Placements, persist: PersistOptions, name: str,
          *, version: str, digest: str, lookup: str, diags: Diagnostics, lss: bool = False,
          node_caps: Mapping[str, int] | None = None, sdo_block: bool = True) -> DictView:
    """The finished view of a placed dictionary: tables, values, persistence, runtime switches, lookup."""
    b = _Builder(od, placements, name, diags)
    view = DictView(name=name, upper=name.upper(), version=version, digest=digest,
                    source=comment(od.source.rsplit("/", 1)[-1]), lookup=lookup)
    for obj in od.sorted_objects():
        if obj.index < 0x1000:
            diags.add(GEN006, Loc(od.source, obj.line), "defines a data type; not generated", obj.index)
            continue
        _entry(b, view, obj)
    if not view.entries:  # C99 has no zero-size arrays: empty tables would not compile
        diags.add(GEN009, Loc(od.source), "the description has no object from 0x1000 on: nothing to generate")
    share(view)
    view.structs = [_sorted_struct(s) for _, s in sorted(b.structs.items(),
                                                         key=lambda kv: _struct_order(kv[0].replace(":", "_")))]
    view.groups = _groups(od, view)
    _check_group_names(b, view)
    _check_functions(b, view)
    for block in view.structs:
        _check_block_size(b, block)
    view.persist = persist_view(od, placements, persist, diags)
    if lookup == "hash":  # before the runtime's switches, one of which is its width
        view.hash = perfect_hash([e.index for e in view.entries])
    view.config = runtime_config(view)
    view.node = node_limits(view, od, lss, dict(node_caps or {}), diags, sdo_block)
    return view


BLOCK_LIMIT = 0xFFFF  # odg_sub_t.offset is 16-bit: one value block addresses at most 64 KiB


def _check_block_size(b: _Builder, struct: StorageStruct) -> None:
    """A value block the 16-bit sub-entry offsets cannot address is refused (GEN007) at the
    first value that lies beyond it, instead of C that fails its own size check."""
    end = 0
    for m in struct.members:
        end = -(-end // m.align) * m.align + member_bytes(m)
        if end > BLOCK_LIMIT:
            index, sub = m.key
            obj = b.od.objects.get(index)
            line = obj.subs[sub].line if obj is not None and sub in obj.subs else 0
            total = sum(map(member_bytes, struct.members))
            b.diags.add(GEN007, Loc(b.od.source, line),
                        f"{struct.name} needs {total}+ bytes; a storage class's block is at most {BLOCK_LIMIT} "
                        f"bytes (16-bit offsets), exceeded from 0x{index:04X}sub{sub} on", index)
            return


def member_bytes(m: Member) -> int:
    return member_size(m, ALIGN)


def _generated_symbols(view: DictView) -> set[str]:
    tables = ("entries", "subs", "limits", "hook_map", "hook_slots", "groups", "state", "find", "reset")
    names = {view.name, *(f"{view.name}_{t}" for t in tables), *(name for name, _ in view.accessors)}
    names |= {s.name for s in view.structs} | {s.defaults for s in view.structs} | {d.name for d in view.domains}
    names |= {s.spread for s in view.structs if s.group} | {f"{s.defaults}_t" for s in view.structs if s.group}
    return names


def _check_group_names(b: _Builder, view: DictView) -> None:
    """Persistence groups whose symbols meet (group `a` has type `NAME_persist_a_t`, which is group `a_t`)."""
    owner: dict[str, str] = {}
    for s in view.structs:
        for symbol in (s.name, s.type_name, s.defaults, s.spread, f"{s.defaults}_t" if s.group else ""):
            if not symbol:
                continue
            first = owner.setdefault(symbol, s.name)
            if first != s.name:
                where_from = b.od.source
                b.diags.add(GEN004, Loc(where_from), f"C name {symbol} is generated for both {first} and {s.name}; "
                            "rename one persistence group (;StorageLocation or the options file)")
                break  # one report for the two groups


def _check_functions(b: _Builder, view: DictView) -> None:
    """Hook functions named in the options must not clash with generated or runtime names."""
    named = [placement for placement in b.placements.values() if placement.function]
    if not named:
        return
    taken = _generated_symbols(view)
    for placement in named:
        fn = placement.function
        if fn and (fn in taken or fn.startswith("odg_")) and placement.function_loc is not None:
            clash = f"hook function {fn} clashes with a generated or runtime name"
            b.diags.add(GEN004, placement.function_loc, clash)
            taken.discard(fn)  # report each clash once


def _struct_order(key: str) -> tuple[int, str]:
    return ({"rom": 0, "ram": 1}.get(key, 2), key)


def _sorted_struct(s: StorageStruct) -> StorageStruct:
    """Members by alignment, widest first, then by (index, sub): two stable sorts, the first of which
    finds the members already in order (they are added object by object)."""
    s.members.sort(key=attrgetter("key"))
    s.members.sort(key=attrgetter("align"), reverse=True)
    return s


_OBJECT_CODES = {2: "ODG_OBJ_DOMAIN", 8: "ODG_OBJ_ARRAY", 9: "ODG_OBJ_RECORD"}


def _entry(b: _Builder, view: DictView, obj: Obj) -> None:
    subs = obj.sorted_subs()
    if not subs:  # nothing a client could read; odg_verify refuses an entry without sub-entries
        b.diags.add(GEN009, Loc(b.od.source, obj.line), "has no sub-entry, not even sub 0: nothing to generate",
                    obj.index)
        return
    dense = subs[-1].subindex == len(subs) - 1  # sub-indices 0..n-1 (distinct and sorted)
    code = _OBJECT_CODES.get(obj.structure, "ODG_OBJ_VAR")
    note = comment(obj.name)
    view.entries.append(EntryView(obj.index, len(view.subs), len(subs), code + (" | ODG_E_DENSE" if dense else ""),
                                  note))
    hex_index, ident = f"{obj.index:04X}", identifier(obj.name, "object")
    view.macros.append((f"{view.upper}_IDX_X{hex_index}_{ident.upper()}", f"0x{hex_index}u", note))
    names = _Names(hex_index, f"x{hex_index}_{ident}", obj.is_var)
    for sub in subs:
        _sub(b, view, obj, sub, names)
    if packable(b.od, obj, b.placements, b.pack_commands):
        _pack(view)


class _Names(NamedTuple):
    """What the C names of an object's sub-entries are made of, worked out once per object."""

    hex_index: str  # "2000"
    member: str  # the value member of a VAR; the prefix of an ARRAY's or RECORD's, "x2000_name"
    is_var: bool


def _pack(view: DictView) -> None:
    """One descriptor for the elements 1..N of the entry just described (packing.py)."""
    entry = view.entries[-1]
    elements = view.subs[entry.first + 1:]
    one = elements[0]
    if len(elements) != entry.count - 1 or any((s.type, s.size, s.attr, s.storage) != (one.type, one.size, one.attr,
                                                                                        one.storage) for s in elements):
        return
    last = elements[-1]
    if not one.storage.startswith("ODG_S_COMMAND"):  # commands have no value whose layout to assert
        view.packed.append(PackedView(entry.index, one.offset, last.offset, len(elements), one.size))
    view.subs[entry.first + 1] = one._replace(sub=last.sub, note=f"sub-indices 1..{last.sub} (1: {one.note})")
    del view.subs[entry.first + 2:]
    entry.count = 2
    entry.code += " | ODG_E_PACKED"  # sub 0 stays where ODG_E_DENSE says


def _sub(b: _Builder, view: DictView, obj: Obj, sub: Sub, names: _Names) -> None:
    """The sub-entry's descriptor, value member, accessor and name macro (this runs once per sub-entry:
    the value in force, the name's identifier and its comment are worked out once here)."""
    subindex = sub.subindex
    placement = b.placements[(obj.index, subindex)]
    dtype = BASIC_TYPES.get(sub.data_type or 0)
    if dtype is None:
        b.diags.add(GEN005, Loc(b.od.source, sub.line_of("datatype")),
                    f"has DataType 0x{sub.data_type or 0:04X}, not a basic type", obj.index,
                    None if names.is_var else subindex)
        return
    ident = "" if names.is_var else identifier(sub.name, "sub")
    member = b.member_name(names.member if names.is_var else f"{names.member}_s{subindex}_{ident}", obj, sub)
    note = comment(sub.name)
    value = b.od.value_in_force(sub)
    nodeid = value is not None and value.nodeid and isinstance(value.parsed, int)
    pdo = (_BOTH if sub.pdo_mapping else b.mapped.get((obj.index, subindex), _NONE)) if dtype.is_numeric else _NONE
    attr = _attr_flags(sub.access, pdo, nodeid, bool(placement.hooks))
    pos = len(view.subs)
    if placement.storage == COMMAND_CLASS:
        storage = "ODG_S_COMMAND" + (" | ODG_S_RESTORE_FLAG" if obj.index == RESTORE else "")
        view.subs.append(SubView("0", 4, subindex, dtype.code, attr, storage, note))
        return
    target = b.struct_for(placement.storage)
    member_note = _prefixed_comment(f"0x{names.hex_index}sub{subindex}", sub.name, note)
    offset, size = _value_member(b, view, target, (obj.index, subindex), sub, dtype, placement, member, value,
                                 member_note)
    if (sub.low is not None or sub.high is not None) and _limit(view, pos, sub, value, dtype):
        attr += " | ODG_A_LIMIT"
    view.subs.append(SubView(offset, size, subindex, dtype.code, attr, b.storage_code(placement), note))
    if placement.hooks:
        kinds = " | ".join(f"ODG_HOOK_{k.upper()}" for k in placement.hooks)
        label = comment(f"0x{obj.index:04X}sub{subindex}")
        view.hooks.append(HookView(pos, kinds, placement.function or "NULL", label))
        if placement.function and placement.function not in view.functions:
            view.functions.append(placement.function)
    if not names.is_var:
        view.macros.append((f"{view.upper}_SUB_X{names.hex_index}_S{subindex}_{ident.upper()}",
                            f"0x{subindex:02X}u", note))


def _prefixed_comment(prefix: str, text: str, flat: str) -> str:
    """comment(f"{prefix} {text}") for a `prefix` without spaces or comment characters, from `flat`
    = comment(text) when that is whole and the two fit the width (the common case, without a second
    pass over the text)."""
    if flat and len(prefix) + 1 + len(flat) <= COMMENT_WIDTH:
        return f"{prefix} {flat}"
    return comment(f"{prefix} {text}")


_BOTH: frozenset[str] = frozenset(("RPDO", "TPDO"))
_NONE: frozenset[str] = frozenset()


@functools.cache
def _attr_flags(access: str | None, pdo: frozenset[str], nodeid: bool, hooked: bool) -> str:
    """ODG_A_* of a sub-entry: its access, PDO mapping (`pdo`: the directions a numeric entry may be
    mapped in, as far as its access allows), a $NODEID default, hooks. Few combinations occur, so each is
    worked out once."""
    flags = []
    if access in READABLE:
        flags.append("ODG_A_READ")
    if access in WRITABLE:
        flags.append("ODG_A_WRITE")
    if "TPDO" in pdo and access in ("ro", "const", "rwr", "rw"):
        flags.append("ODG_A_TPDO")
    if "RPDO" in pdo and access in ("wo", "rww", "rw"):
        flags.append("ODG_A_RPDO")
    if nodeid:
        flags.append("ODG_A_NODEID")
    if hooked:
        flags.append("ODG_A_HOOK")
    return " | ".join(flags) or "0"


def _storage_code(storage: str, upper: str) -> str:
    if storage == "rom":
        return "ODG_S_ROM"
    if storage == "ram":
        return "ODG_S_RAM"
    group = storage.split(":", 1)[1] if storage.startswith("persist:") else "app"
    return f"ODG_S_PERSIST | ({upper}_GROUP_{group.upper()} << 2)"


def _value_member(b: _Builder, view: DictView, target: StorageStruct, key: tuple[int, int], sub: Sub,
                  dtype: DataType, placement: Placement, member: str, value: Value | None,
                  note: str) -> tuple[str, int]:
    """The member holding the value in the struct of its storage class; (offset, size) for the descriptor."""
    ctype = _CTYPES[dtype.code]
    kind = dtype.kind
    if kind in ("vstring", "ostring", "ustring"):
        data = string_default(dtype, value)
        array, init, size = _string_init(dtype, data, placement.capacity)
        used, head = _head(data, 4 if kind == "ustring" else 2)
        target.members.append(Member(member, ctype, array, init, note, ALIGN[ctype], key, used, head))
    elif kind == "domain":
        return _domain(b, view, target, member, value, placement, note, key)
    else:
        number = initial_value(value, sub, dtype)
        init = real_literal(float(number), dtype.bits) if kind == "real" else int_literal(int(number), ctype)
        target.members.append(Member(member, ctype, "", init, note, ALIGN[ctype], key,
                                     0 if _ZERO_INIT.fullmatch(init) else 1, init))
        size = max(dtype.bits // 8, 1)
    view.accessors.append((f"{view.name}_{member}", f"({target.name}.{member})"))
    return f"offsetof({target.type_name}, {member})", size


def _string_init(dtype: DataType, data: bytes | list[int], capacity: int | None) -> tuple[str, str, int]:
    """A string's C array suffix, initializer and capacity in bytes, from its default as stored."""
    cap = string_capacity(dtype, data, capacity)
    if dtype.kind == "vstring":
        assert isinstance(data, bytes)
        if len(data) > MAX_C_STRING:  # C99 compilers need only take string literals of 4095 characters
            return f"[{cap + 1}]", "{" + ", ".join(f"0x{x:02X}" for x in data) + ", 0}", cap
        return f"[{cap + 1}]", string_literal(data), cap
    if dtype.kind == "ostring":
        body = ", ".join(f"0x{x:02X}" for x in data) or "0"
        return f"[{max(cap, 1)}]", "{" + body + "}", cap
    body = ", ".join(f"0x{u:04X}" for u in [*data, 0])
    return f"[{cap // 2 + 1}]", "{" + body + "}", cap


def _head(units: bytes | list[int], digits: int) -> tuple[int, str]:
    """A string's or domain's elements up to its last non-zero one, and their initializer."""
    used = len(units)
    while used > 0 and units[used - 1] == 0:
        used -= 1
    return used, "{" + ", ".join(f"0x{u:0{digits}X}" for u in units[:used]) + "}"


def _domain(b: _Builder, view: DictView, target: StorageStruct, member: str, value: Value | None,
            placement: Placement, note: str, key: tuple[int, int]) -> tuple[str, int]:
    data = domain_default(value)
    rom = placement.storage == "rom"  # const: exactly its bytes, in FLASH
    cap = max(len(data), 1) if rom else domain_capacity(value, placement.capacity)
    body = ", ".join(f"0x{x:02X}" for x in data) or "0"
    target.members.append(Member(member + "_buf", "uint8_t", f"[{cap}]", "{" + body + "}", note, 1, key,
                                 *_head(data, 2)))
    target.members.append(Member(member + "_len", "uint32_t", "", f"UINT32_C({len(data)})", note, 4, key,
                                 1 if data else 0, f"UINT32_C({len(data)})"))
    # odg_domain_t points at writable memory; a DOMAIN in rom is const and never written through
    # them (odg_write refuses ODG_S_ROM and entries without ODG_A_WRITE), so the casts are safe.
    buffer, length = f"{target.name}.{member}_buf", f"&{target.name}.{member}_len"
    if rom:
        buffer, length = f"(uint8_t *){buffer}", f"(uint32_t *){length}"
    view.domains.append(DomainView(member, buffer, length, cap))
    return str(len(view.domains) - 1), cap


def _limit(view: DictView, pos: int, sub: Sub, value: Value | None, dtype: DataType) -> bool:
    if not dtype.is_numeric or (sub.low is None and sub.high is None):
        return False
    limits = served_limits(sub.low, sub.high, value, dtype, sub.writable)
    if limits is None:
        return False
    low, high = limits
    view.limits.append(LimitView(f"UINT64_C(0x{limit_bits(low, dtype):016X})",
                                 f"UINT64_C(0x{limit_bits(high, dtype):016X})", pos, comment(f"{low} .. {high}")))
    return True


def _groups(od: ObjectDictionary, view: DictView) -> list[GroupView]:
    store = od.objects.get(STORE)
    groups = []
    for s in view.structs:
        if not s.name.startswith(f"{view.name}_persist_"):
            continue
        group = s.name[len(f"{view.name}_persist_"):]
        sub = _GROUP_SUBS.get(group, 0)
        store_sub = sub if store is not None and sub in store.subs else 1
        groups.append(GroupView(group, s.name, s.defaults, s.type_name, _signature(s), store_sub, s.spread,
                                f"&{s.defaults}" if s.runs else "NULL"))
    return groups


def _signature(s: StorageStruct) -> int:
    """Layout signature: (index, sub, C type, array) in struct order."""
    text = ";".join(f"{m.key[0]:04X}.{m.key[1]}.{m.ctype}{m.array}" for m in s.members)
    return zlib.crc32(text.encode("ascii"))

