"""The repairs, one function per rule: each takes a finding and the model being repaired (a copy of
the loaded one) and returns what it did, or None when this finding is not one it can repair.

Every repair changes the model and names the lines of the file it changes (`Edit`); on an entry
that is not written as its own lines (a CompactSubObj element, an XDD attribute) it changes the
model only, which `generate --fix` uses and `odgen fix` reports it cannot write.
"""

from __future__ import annotations

import copy
import re
from collections.abc import Callable
from dataclasses import dataclass, field

from ..catalogue import RULES, Rule
from ..catalogue.comm import COM016, COM017
from ..catalogue.objects import OBJ006, OBJ010, OBJ011, OBJ012, OBJ014, OBJ015, OBJ017, OBJ030
from ..catalogue.pdo import PDO001, PDO002, PDO003, PDO004
from ..catalogue.syntax import SYN007, SYN015, SYN016
from ..diagnostics import Diagnostic, where
from ..model import VAR, ObjectDictionary, Obj, Sub, Value, parse_value
from ..model.cia301 import PDO_COUNT, RPDO_COMM, SDO_SERVER, TPDO_COMM
from ..model.datatypes import BASIC_TYPES
from ..model.pdo import mapping_kind
from ..model.values import number, parse_int_literal, plain_int, split_nodeid
from .apply import ADD_KEY, DELETE, INSERT_BEFORE, SET, Edit

UNSIGNED8, DOMAIN_TYPE = 0x0005, 0x000F
COB_INVALID = 0x80000000


@dataclass(frozen=True)
class Repair:
    """One repair: the finding it answers, whether it is safe, what it did and the lines it changes."""

    finding: Diagnostic
    safe: bool
    what: str
    edits: tuple[Edit, ...] = ()
    writable: bool = True  # False: the entry has no lines of its own, so `odgen fix` cannot write the repair
    order: int = 0  # when it was made: a later repair of the same line builds on an earlier one

    @property
    def rule(self) -> str:
        return self.finding.rule

    def text(self) -> str:
        subject = where(self.finding.index, self.finding.sub)
        body = f"{subject} {self.what}" if subject else self.what
        return f"{self.finding.loc}: {'fixed' if self.safe else 'fixed (unsafe)'}[{self.rule}]: {body}"


@dataclass
class _Work:
    od: ObjectDictionary  # the copy being repaired
    unsafe: bool
    done: list[Repair] = field(default_factory=list)
    mappings: dict[int, set[int]] = field(default_factory=dict)  # mapping index -> entries to drop
    mapping_findings: dict[int, list[Diagnostic]] = field(default_factory=dict)


Fix = Callable[[_Work, Diagnostic], "Repair | None"]


# -- helpers ---------------------------------------------------------------------------

def _sub(od: ObjectDictionary, d: Diagnostic) -> Sub | None:
    return od.find(d.index, d.sub or 0) if d.index is not None else None


def _in_force(od: ObjectDictionary, sub: Sub) -> tuple[Value | None, str]:
    value = od.value_in_force(sub)
    return value, ("parametervalue" if value is not None and value is sub.parameter_value else "defaultvalue")


def _line(sub: Sub, value: Value | None, keyword: str) -> int:
    return value.line if value is not None and value.line else sub.lines.get(keyword, 0)


def _set_value(sub: Sub, keyword: str, text: str) -> Edit | None:
    """The model's value under `keyword` becomes `text`; the edit of its line, if it has one."""
    old = getattr(sub, _ATTR[keyword])
    line = _line(sub, old, keyword)
    setattr(sub, _ATTR[keyword], parse_value(text, sub.dtype, line))
    return Edit(SET, line, text=text) if line and not sub.compact else None


_ATTR = {"defaultvalue": "default", "parametervalue": "parameter_value", "lowlimit": "low", "highlimit": "high"}


def _like(old: str, n: int) -> str:
    """`n` written as `old` was: hex with as many digits when it was hex."""
    text = old.strip()
    if not text.lower().startswith("0x"):
        return str(n)
    return f"{text[:2]}{n:0{len(text) - 2}X}"


def _edits(*edits: Edit | None) -> tuple[Edit, ...]:
    return tuple(e for e in edits if e is not None)


def _repair(work: _Work, d: Diagnostic, safe: bool, what: str, *edits: Edit | None,
            written: bool = True) -> Repair:
    kept = _edits(*edits)
    # an edit that came out None is a line the entry does not have (a CompactSubObj element, XML)
    repair = Repair(d, safe, what, kept, writable=written and len(kept) == len(edits), order=len(work.done))
    work.done.append(repair)
    return repair


# -- objects ---------------------------------------------------------------------------

def _sub0_highest(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ011 (safe): sub0 := the highest sub-index, where every sub-object is written as a section."""
    obj = work.od.objects.get(d.index) if d.index is not None else None
    sub0 = obj.subs.get(0) if obj is not None else None
    if obj is None or sub0 is None or any(s.compact for s in obj.subs.values()):
        return None
    value, keyword = _in_force(work.od, sub0)
    if value is None or plain_int(value) is None:
        return None
    highest = max(obj.subs)
    text = _like(value.text, highest)
    edit = _set_value(sub0, keyword, text)
    label = "ParameterValue" if keyword == "parametervalue" else "DefaultValue"
    # limits that pinned the old count would exclude the new one: they go with it
    stale = [k for k, below in (("lowlimit", True), ("highlimit", False))
             if (n := number(getattr(sub0, _ATTR[k]))) is not None and (highest < n if below else highest > n)]
    dropped = [_drop_limit(sub0, k) for k in stale]
    also = f" ({' and '.join('LowLimit' if k == 'lowlimit' else 'HighLimit' for k in stale)} removed)" if stale else ""
    return _repair(work, d, True, f"{label} {value.text.strip()} -> {text}, the highest sub-index{also}", edit,
                   *dropped)


def _sub0_missing(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ010: a missing sub0 added (safe); sub0 of another type made UNSIGNED8 when its value fits (unsafe)."""
    obj = work.od.objects.get(d.index) if d.index is not None else None
    if obj is None or not obj.subs:
        return None
    sub0 = obj.subs.get(0)
    if sub0 is None:
        return _add_sub0(work, d, obj)
    if not work.unsafe or sub0.data_type == UNSIGNED8:
        return None
    counts = [_count(v) for v in (sub0.default, sub0.parameter_value) if v is not None]
    if None in counts:
        return None  # a value that is no count 0..255: what sub0 says is unknown
    line = sub0.lines.get("datatype", 0)
    sub0.data_type = UNSIGNED8
    edits = [Edit(SET, line, text="0x0005") if line else None]
    for key in ("defaultvalue", "parametervalue"):
        old = getattr(sub0, _ATTR[key])
        if old is not None:
            n = _count(old)
            text = old.text.strip() if plain_int(old) == n else str(n)
            edits.append(_set_value(sub0, key, text))
    return _repair(work, d, False, "DataType -> 0x0005 (UNSIGNED8)", *edits, written=bool(line))


def _count(value: Value) -> int | None:
    """A sub0 value as a count 0..255 (a REAL32 2.0 is 2), None when it is none."""
    n = number(value)
    if value.nodeid or n is None or n != int(n) or not 0 <= n <= 0xFF:
        return None
    return int(n)


def _add_sub0(work: _Work, d: Diagnostic, obj: Obj) -> Repair:
    highest = max(obj.subs)
    first = obj.subs[min(obj.subs)]
    sub0 = Sub(0, "Highest sub-index supported", data_type=UNSIGNED8, access="ro",
               default=parse_value(str(highest), BASIC_TYPES[UNSIGNED8]))
    obj.subs = {0: sub0, **obj.subs}
    edits: list[Edit | None] = []
    written = bool(first.line) and not first.compact
    if written:
        edits.append(Edit(INSERT_BEFORE, first.line, lines=(
            f"[{obj.index:04X}sub0]", "ParameterName=Highest sub-index supported", "ObjectType=0x7",
            "DataType=0x0005", "AccessType=ro", f"DefaultValue={highest}", "PDOMapping=0", "")))
    if obj.sub_number is not None and obj.sub_number == len(obj.subs) - 1:
        obj.sub_number += 1  # SubNumber counts the sub-object sections, the new one too
        line = obj.sub_number_line or obj.lines.get("subnumber", 0)
        if line:
            edits.append(Edit(SET, line, text=str(obj.sub_number)))
    return _repair(work, d, True, f"sub0 added (UNSIGNED8, ro, DefaultValue={highest})", *edits, written=written)


def _sub_number(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ006 (safe), neither SubNumber nor CompactSubObj: SubNumber := the sub-object sections present.
    Without sub-objects, a header that carries a value's keywords (DataType, AccessType) is read as the
    VAR it describes (unsafe)."""
    obj = work.od.objects.get(d.index) if d.index is not None else None
    if obj is None or obj.sub_number is not None or obj.compact_sub_obj or "both" in d.message:
        return None
    written = [s for s in obj.subs.values() if not s.compact]
    if not written:
        return _as_var(work, d, obj)
    obj.sub_number = len(written)
    edit = Edit(ADD_KEY, obj.line, key="SubNumber", text=str(len(written))) if obj.line else None
    return _repair(work, d, True, f"SubNumber={len(written)} added", edit)


_VALUE_KEYS = {"datatype": "data_type", "accesstype": "access", "defaultvalue": "default", "lowlimit": "low",
               "highlimit": "high", "pdomapping": "pdo_mapping"}


def _as_var(work: _Work, d: Diagnostic, obj: Obj) -> Repair | None:
    """An ARRAY/RECORD header without sub-objects that has DataType and AccessType: the VAR it describes."""
    extra = obj.extra
    data_type = plain_int(parse_value(extra["datatype"].text, BASIC_TYPES[0x0006])) if "datatype" in extra else None
    if not work.unsafe or data_type is None or data_type not in BASIC_TYPES or "accesstype" not in extra:
        return None
    dtype = BASIC_TYPES[data_type]
    var = Sub(0, obj.name, line=obj.line, data_type=data_type, access=extra["accesstype"].text.strip().lower())
    for key in ("defaultvalue", "lowlimit", "highlimit"):
        if key in extra:
            setattr(var, _VALUE_KEYS[key], parse_value(extra[key].text, dtype, extra[key].line))
    var.pdo_mapping = "pdomapping" in extra and extra["pdomapping"].text.strip() not in ("", "0")
    var.lines = {key: extra[key].line for key in _VALUE_KEYS if key in extra}
    obj.extra = {k: f for k, f in extra.items() if k not in _VALUE_KEYS}
    old_code = obj.object_code
    obj.object_code, obj.subs = VAR, {0: var}
    line = obj.lines.get("objecttype", 0)
    edit = Edit(SET, line, text="0x7") if line else None
    return _repair(work, d, False, f"ObjectType 0x{old_code:X} -> 0x7 (VAR), as its DataType and AccessType "
                   "describe one value", edit)


def _limit_keyword(d: Diagnostic) -> str | None:
    for key, label in (("lowlimit", "LowLimit="), ("highlimit", "HighLimit=")):
        if d.message.startswith(label):
            return key
    return None


def _drop_limit(sub: Sub, keyword: str) -> Edit | None:
    old = getattr(sub, _ATTR[keyword])
    setattr(sub, _ATTR[keyword], None)
    line = _line(sub, old, keyword)
    return Edit(DELETE, line) if line and not sub.compact else None


def _limit_range(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ014: a limit outside the type's range removed; safe where it restricts nothing (the finding
    does not block then), unsafe beyond the other end."""
    sub, keyword = _sub(work.od, d), _limit_keyword(d)
    safe = not d.blocking
    if sub is None or keyword is None or getattr(sub, _ATTR[keyword]) is None or not (safe or work.unsafe):
        return None
    name = "LowLimit" if keyword == "lowlimit" else "HighLimit"
    return _repair(work, d, safe, f"{name} removed (the data type bounds the value)", _drop_limit(sub, keyword))


def _reversed_limits(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ015 (unsafe): limits written as bit patterns of a signed type (0x00..0xFF on INTEGER8) removed;
    other reversed limits swapped."""
    sub = _sub(work.od, d)
    if not work.unsafe or sub is None or sub.low is None or sub.high is None:
        return None
    low, high = sub.low, sub.high
    dtype = sub.dtype
    signed = dtype is not None and dtype.min is not None and dtype.min < 0
    patterns = signed and any(v.text.strip().lower().startswith("0x") and (number(v) or 0) < 0 for v in (low, high))
    if patterns:
        return _repair(work, d, False, f"LowLimit={low.text.strip()} and HighLimit={high.text.strip()} removed "
                       "(bit patterns of the whole type)", _drop_limit(sub, "lowlimit"), _drop_limit(sub, "highlimit"))
    low_text, high_text = low.text.strip(), high.text.strip()
    return _repair(work, d, False, f"LowLimit and HighLimit swapped ({high_text} .. {low_text})",
                   _set_value(sub, "lowlimit", high_text), _set_value(sub, "highlimit", low_text))


def _value_in_limits(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ017 (unsafe): a value outside its limits clamped; a $NODEID value has the limit it crosses removed."""
    sub = _sub(work.od, d)
    if not work.unsafe or sub is None:
        return None
    keyword = "parametervalue" if d.message.startswith("ParameterValue=") else "defaultvalue"
    crossed = "lowlimit" if " below LowLimit=" in d.message else "highlimit"
    value, limit = getattr(sub, _ATTR[keyword]), getattr(sub, _ATTR[crossed])
    if value is None:
        return None
    if limit is None:  # removed by another repair of this entry: nothing left to cross
        return _repair(work, d, False, "no limit left to cross")
    name = "LowLimit" if crossed == "lowlimit" else "HighLimit"
    if value.nodeid or limit.nodeid:
        return _repair(work, d, False, f"{name} removed ({value.text.strip()} is relative to the node-id)",
                       _drop_limit(sub, crossed))
    label = "ParameterValue" if keyword == "parametervalue" else "DefaultValue"
    text = limit.text.strip()
    return _repair(work, d, False, f"{label} {value.text.strip()} -> {text}, clamped to {name}",
                   _set_value(sub, keyword, text))


def _undefined_type(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ012 (unsafe): an undefined data type read as DOMAIN, as python canopen reads it."""
    sub = _sub(work.od, d)
    if not work.unsafe or sub is None or sub.data_type is None or sub.data_type in BASIC_TYPES:
        return None
    old = sub.data_type
    line = sub.lines.get("datatype", 0)
    sub.data_type = DOMAIN_TYPE
    for key in ("default", "parameter_value", "low", "high"):
        value = getattr(sub, key)
        if value is not None:
            setattr(sub, key, None if key in ("low", "high") else parse_value(value.text, sub.dtype, value.line))
    edits = [Edit(SET, line, text="0x000F") if line and not sub.compact else None]
    edits += [Edit(DELETE, sub.lines[k]) for k in ("lowlimit", "highlimit") if k in sub.lines and not sub.compact]
    return _repair(work, d, False, f"DataType 0x{old:04X} -> 0x000F (DOMAIN)", *edits)


def _const_to_ro(work: _Work, d: Diagnostic) -> Repair | None:
    """OBJ030 (safe): a const entry with a $NODEID-relative value made ro."""
    sub = _sub(work.od, d)
    if sub is None or sub.access != "const":
        return None
    sub.access = "ro"
    line = sub.lines.get("accesstype", 0)
    return _repair(work, d, True, "AccessType const -> ro", Edit(SET, line, text="ro") if line else None)


# -- PDOs ------------------------------------------------------------------------------

def _drop_mapping_entry(work: _Work, d: Diagnostic) -> Repair | None:
    """PDO001/PDO004 (unsafe): the mapping entry removed; done per mapping object in `_drop_entries`."""
    obj = work.od.objects.get(d.index) if d.index is not None else None
    if not work.unsafe or obj is None or d.sub is None or mapping_kind(obj.index) is None:
        return None
    work.mappings.setdefault(obj.index, set()).add(d.sub)
    work.mapping_findings.setdefault(obj.index, []).append(d)
    return None  # listed by _drop_entries


def _drop_entries(work: _Work) -> None:
    for index, drop in sorted(work.mappings.items()):
        obj = work.od.objects[index]
        sub0 = obj.subs.get(0)
        count_value, count_key = _in_force(work.od, sub0) if sub0 is not None else (None, "")
        count = plain_int(count_value)
        findings = work.mapping_findings[index]
        if sub0 is None or count_value is None or count is None:
            continue
        if 0 in drop:  # sub0 counts entries that are not defined: count the defined ones
            count = next((i - 1 for i in range(1, count + 1) if i not in obj.subs), count)
        kept = [i for i in range(1, count + 1) if i not in drop and i in obj.subs]
        texts = [_in_force(work.od, obj.subs[i])[0] for i in kept]
        edits: list[Edit | None] = []
        for position, subindex in enumerate(range(1, count + 1), start=1):
            sub = obj.subs.get(subindex)
            if sub is None:
                continue
            old, key = _in_force(work.od, sub)
            kept_value = texts[position - 1] if position <= len(texts) else None
            new = kept_value.text.strip() if kept_value is not None else "0x00000000"
            if old is None or old.text.strip() != new:
                edits.append(_set_value(sub, key, new))
        edits.append(_set_value(sub0, count_key, str(len(kept))))
        what = f"mapping entries {', '.join(f'sub{i}' for i in sorted(drop))} removed, sub0 -> {len(kept)}"
        first, rest = findings[0], findings[1:]
        _repair(work, first, False, what, *edits)
        for other in rest:
            _repair(work, other, False, f"removed with {where(first.index, first.sub)}'s repair")


def _mapping_length(work: _Work, d: Diagnostic) -> Repair | None:
    """PDO003 (unsafe), a mapping longer than its entry: the length set to the entry's size (later
    fields of the frame move)."""
    entry = _sub(work.od, d)
    if not work.unsafe or entry is None or not d.blocking:
        return None
    value, keyword = _in_force(work.od, entry)
    raw = plain_int(value)
    if value is None or raw is None:
        return None
    target = work.od.find(raw >> 16, (raw >> 8) & 0xFF)
    dtype = target.dtype if target is not None else BASIC_TYPES.get(raw >> 16)
    if dtype is None or not dtype.bits or (raw & 0xFF) <= dtype.bits:
        return None  # a shorter mapping: which length is right is unknown
    text = f"0x{(raw & ~0xFF) | dtype.bits:08X}"
    return _repair(work, d, False, f"mapping {value.text.strip()} -> {text}, the length of {dtype.name}",
                   _set_value(entry, keyword, text))


def _mappable(work: _Work, d: Diagnostic) -> Repair | None:
    """PDO002 (unsafe): the mapped entry made PDO-mappable, as the file's own mapping uses it."""
    entry = _sub(work.od, d)
    if not work.unsafe or entry is None:
        return None
    raw = plain_int(work.od.value_in_force(entry))
    if raw is None:
        return None
    target = work.od.find(raw >> 16, (raw >> 8) & 0xFF)
    if target is None or target.dtype is None or not target.dtype.is_numeric:
        return None  # no PDO carries a string or a DOMAIN, mappable or not
    if target.pdo_mapping:
        return _repair(work, d, False, "mapped entry already made PDO-mappable")
    target.pdo_mapping = True
    line = target.lines.get("pdomapping", 0)
    if target.compact:
        edit = None
    elif line:
        edit = Edit(SET, line, text="1")
    else:
        edit = Edit(ADD_KEY, target.line, key="PDOMapping", text="1") if target.line else None
    return _repair(work, d, False, f"{where(raw >> 16, (raw >> 8) & 0xFF)} PDOMapping -> 1", edit)


# -- communication ---------------------------------------------------------------------

def _can_disable(index: int, subindex: int | None) -> bool:
    """A channel whose COB-ID bit 31 switches it off: a PDO (sub1), an SDO channel other than the
    default server (sub1, sub2)."""
    pdo = any(base <= index < base + PDO_COUNT for base in (RPDO_COMM, TPDO_COMM)) and subindex == 1
    sdo = SDO_SERVER < index < SDO_SERVER + 0x100 and subindex in (1, 2)
    return pdo or sdo


def _disable_clash(work: _Work, d: Diagnostic) -> Repair | None:
    """COM016 (unsafe): the later PDO or SDO channel on a shared CAN-ID disabled (COB-ID bit 31)."""
    sub = _sub(work.od, d)
    if not work.unsafe or sub is None or d.index is None or not _can_disable(d.index, d.sub):
        return None
    value, keyword = _in_force(work.od, sub)
    n = number(value)
    if value is None or not isinstance(n, int):
        return None
    cob = (n | COB_INVALID) & 0xFFFFFFFF
    text = f"$NODEID+0x{cob:X}" if value.nodeid else f"0x{cob:08X}"
    return _repair(work, d, False, f"COB-ID {value.text.strip()} -> {text} (channel disabled)",
                   _set_value(sub, keyword, text))


def _sdo_server(work: _Work, d: Diagnostic) -> Repair | None:
    """COM017 (safe), the value finding: the COB-ID written as CiA 301 fixes it."""
    sub = _sub(work.od, d)
    if sub is None or d.index != SDO_SERVER or d.sub not in (1, 2) or not d.blocking:
        return None
    value, keyword = _in_force(work.od, sub)
    if value is None:
        return None
    text = "$NODEID+0x600" if d.sub == 1 else "$NODEID+0x580"
    return _repair(work, d, True, f"COB-ID {value.text.strip()} -> {text}", _set_value(sub, keyword, text))


# -- syntax ----------------------------------------------------------------------------

def _empty_keyword(work: _Work, d: Diagnostic) -> Repair | None:
    """SYN015 (safe): an empty keyword, read as absent, removed."""
    if d.blocking or not d.loc.line:
        return None
    return _repair(work, d, True, f"empty {d.message.split('=', 1)[0]}= removed", Edit(DELETE, d.loc.line))


def _nodeid_form(work: _Work, d: Diagnostic) -> Repair | None:
    """SYN007 (safe): a `$NODEID` value written as CiA 306 writes it, `$NODEID+<number>`."""
    sub = _sub(work.od, d)
    if sub is None or not d.loc.line:
        return None
    keys = [k for k in _ATTR if (v := getattr(sub, _ATTR[k])) is not None and v.line == d.loc.line and v.nodeid]
    if not keys:
        return None
    old = getattr(sub, _ATTR[keys[0]])
    _, rest, _ = split_nodeid(old.text)
    if parse_int_literal(rest)[0] is None:
        return None  # the number beside $NODEID is not one: no canonical form to write
    text = "$NODEID" if rest == "0" else f"$NODEID{rest}" if rest.startswith("-") else f"$NODEID+{rest}"
    edit = _set_value(sub, keys[0], text)
    return _repair(work, d, True, f"{old.text.strip()} -> {text}", edit)


def _compact_counts(work: _Work, d: Diagnostic) -> Repair | None:
    """SYN016 (safe), the findings that do not block: NrOfEntries set to the entries that follow; a
    CompactSubObj above 254 set to 254, which is what every reader serves (sub-index 255 is reserved)."""
    if d.blocking or not d.loc.line:
        return None
    match = re.search(r"NrOfEntries=(.*) but (\d+) entries follow", d.message)
    if match:
        count = match.group(2)
        edit = Edit(ADD_KEY, d.loc.line, key="NrOfEntries", text=count) if match.group(1) == "(missing)" \
            else Edit(SET, d.loc.line, text=count)
        return _repair(work, d, True, f"NrOfEntries -> {count}, the entries that follow", edit)
    obj = work.od.objects.get(d.index) if d.index is not None else None
    if obj is None or not d.message.startswith("CompactSubObj="):
        return None
    obj.compact_sub_obj = 0xFE
    return _repair(work, d, True, "CompactSubObj -> 254, the sub-objects every reader serves",
                   Edit(SET, d.loc.line, text="254"))


# Rule id -> its repair, in the order they are made (sub0 before the limits, limits before values).
_FIXES: tuple[tuple[Rule, Fix], ...] = (
    (SYN007, _nodeid_form),
    (SYN015, _empty_keyword),
    (SYN016, _compact_counts),
    (OBJ006, _sub_number),
    (OBJ010, _sub0_missing),
    (OBJ011, _sub0_highest),
    (OBJ012, _undefined_type),
    (OBJ014, _limit_range),
    (OBJ030, _const_to_ro),
    (OBJ015, _reversed_limits),
    (OBJ017, _value_in_limits),
    (PDO001, _drop_mapping_entry),
    (PDO004, _drop_mapping_entry),
    (PDO002, _mappable),
    (PDO003, _mapping_length),
    (COM016, _disable_clash),
    (COM017, _sdo_server),
)
REPAIRABLE = frozenset(rule.id for rule, _ in _FIXES)
ORDER = {rule.id: n for n, (rule, _) in enumerate(_FIXES)}
assert all(RULES[r].repair for r in REPAIRABLE)


def repair_model(od: ObjectDictionary, findings: list[Diagnostic],
                 unsafe: bool = False) -> tuple[ObjectDictionary, list[Repair]]:
    """A repaired copy of `od` and the repairs made for `findings` (safe ones; unsafe ones as well
    with `unsafe`). `od` itself is not changed."""
    work = _Work(copy.deepcopy(od), unsafe)
    fixes = {rule.id: fix for rule, fix in _FIXES}
    for d in sorted((d for d in findings if d.rule in fixes),
                    key=lambda d: (ORDER[d.rule], d.loc.line, d.index or 0, d.sub or 0)):
        fixes[d.rule](work, d)
    _drop_entries(work)
    return work.od, sorted(work.done, key=lambda r: (r.finding.loc.line, r.rule, r.finding.index or 0,
                                                     r.finding.sub or 0))


def would_repair(od: ObjectDictionary, findings: list[Diagnostic]) -> tuple[set[Diagnostic], set[Diagnostic]]:
    """The findings `--fix` would repair, and those `--unsafe-fixes` would (a superset)."""
    _, safe = repair_model(od, findings)
    _, unsafe = repair_model(od, findings, unsafe=True)
    return {r.finding for r in safe}, {r.finding for r in unsafe}




def blocking_marks(od: ObjectDictionary | None, findings: list[Diagnostic]) -> dict[Diagnostic, str]:
    """For each finding that blocks generation, the mark reporters write after its message: whether
    `--fix` (or only `--unsafe-fixes`) repairs it. Nothing is computed for a file without such findings."""
    blocking = [d for d in findings if d.blocks]
    if not blocking:
        return {}
    safe, unsafe = would_repair(od, findings) if od is not None else (set(), set())
    marks = {}
    for d in blocking:
        how = "--fix repairs it" if d in safe else "--unsafe-fixes repairs it" if d in unsafe else "no repair"
        marks[d] = f" [blocks generate; {how}]"
    return marks


__all__ = ["REPAIRABLE", "Repair", "blocking_marks", "repair_model", "would_repair"]
