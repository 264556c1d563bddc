"""The model as a CiA 306 EDS/DCF file: deterministic, every value kept.

Values are written as their source text (so `$NODEID+0x180` stays so); keys
odgen does not interpret follow the ones it does. Objects go to the object list
that named them, else to the list their index range implies.
"""

from __future__ import annotations

from collections.abc import Iterable

from ..model import Field, Obj, ObjectDictionary, Sub
from ..model.cia301 import MANDATORY
from ..model.od import VAR
from .eds import HASH_COMMENT, KEYWORDS, OBJECT_LISTS

_KEYWORDS = {k.lower(): k for k in KEYWORDS}
_LEADING_SECTIONS = ("FileInfo", "DeviceInfo", "DeviceComissioning", "DummyUsage", "Comments")


def list_of(obj: Obj) -> str:
    if obj.object_list in OBJECT_LISTS:
        return obj.object_list
    if obj.index in MANDATORY:
        return "MandatoryObjects"
    return "ManufacturerObjects" if 0x2000 <= obj.index <= 0x5FFF else "OptionalObjects"


def write_eds(od: ObjectDictionary) -> str:
    out: list[str] = []
    for name in _LEADING_SECTIONS:
        _header(out, od, name)
    groups: dict[str, list[Obj]] = {name: [] for name in OBJECT_LISTS}
    for obj in od.sorted_objects():
        groups[list_of(obj)].append(obj)
    foreign = od.format in ("xdd", "xdc")
    for name in OBJECT_LISTS:
        _object_list(out, name, groups[name], foreign)
    for key, section in od.sections.items():
        if section.name not in _LEADING_SECTIONS:
            _header(out, od, key)
    return "\n".join(map(_one_line, out)).rstrip("\n") + "\n"


def _extra(out: list[str], fields: Iterable[Field], foreign: bool) -> None:
    """Keys odgen does not interpret. One the section already has (an XDD's PDOmapping="TPDO" beside
    PDOMapping=1 when the access does not say the direction), or that spells a CiA 306 keyword in
    other letters (an XDD attribute obJectType), is left out: EDS has no place for it, and readers
    would take it for the keyword or ignore it as a repeat (SYN003). `foreign`: the keys come from
    an XDD/XDC (CANopenEditor's CO_flagsPDO, CO_disabled ...), where they are no EDS key; they are
    kept as `;Key=Value` comments, as CANopenEditor writes its own, so that the EDS is one odgen's
    lint passes (a key it does not know is OBJ025). An EDS's own unknown keys stay keys."""
    start = next(i for i in range(len(out) - 1, -1, -1) if out[i].startswith("["))
    have = {line.lstrip(";").partition("=")[0].lower() for line in out[start + 1:]}
    for f in fields:
        respelled = _KEYWORDS.get(f.key.lower(), f.key) != f.key
        if f.key.lower() not in have and not respelled and _ini_key(f.key):
            out.append(f"{';' if foreign and f.key not in KEYWORDS else ''}{f.key}={f.text}")
            have.add(f.key.lower())


def _one_line(line: str) -> str:
    """A line break inside a value (an XDD can hold one) would start a new key or section: a space instead."""
    return line.replace("\r\n", " ").replace("\r", " ").replace("\n", " ") if "\r" in line or "\n" in line else line


def _hex(number: int, width: int = 0) -> str:
    """0x form for the reader's numbers; a negative one (read from a hostile file) in decimal, as read."""
    return f"0x{number:0{width}X}" if number >= 0 else str(number)


def _header(out: list[str], od: ObjectDictionary, name: str) -> None:
    section = od.section(name)
    if section is None:
        return
    out.append(f"[{section.name}]")
    out.extend(f"{f.key}={f.text}" for f in section.fields.values() if _ini_key(f.key))
    out.append("")


def _object_list(out: list[str], name: str, objects: list[Obj], foreign: bool) -> None:
    out.append(f"[{name}]")
    out.append(f"SupportedObjects={len(objects)}")
    out.extend(f"{n}=0x{obj.index:04X}" for n, obj in enumerate(objects, start=1))
    out.append("")
    for obj in objects:
        _object(out, obj, foreign)


def _object(out: list[str], obj: Obj, foreign: bool) -> None:
    out.append(f"[{obj.index:04X}]")
    out.append(f"ParameterName={obj.name}")
    if obj.object_code_written or obj.object_code != VAR:
        out.append(f"ObjectType={_hex(obj.object_code)}")
    if obj.is_var and 0 in obj.subs:
        _value_keys(out, obj.subs[0], foreign)
        if obj.count_label is not None:
            out.append(f";CountLabel={obj.count_label}")
        out.append("")
        return
    _container_keys(out, obj, foreign)
    out.append("")
    for sub in obj.sorted_subs():
        if not sub.compact:
            _sub_section(out, obj, sub, foreign)
    if obj.compact_sub_obj:
        _compact_sections(out, obj)


def _container_keys(out: list[str], obj: Obj, foreign: bool) -> None:
    if obj.sub_number is not None:
        out.append(f"SubNumber={_hex(obj.sub_number)}")
    if obj.compact_sub_obj is not None:
        out.append(f"CompactSubObj={obj.compact_sub_obj}")
        template = obj.subs.get(1)
        if template is not None and template.compact:
            _typed_keys(out, template)
    if obj.obj_flags is not None:
        out.append(f"ObjFlags={_hex(obj.obj_flags)}")
    if obj.count_label is not None:
        out.append(f";CountLabel={obj.count_label}")
    if obj.storage is not None:
        out.append(f";StorageLocation={obj.storage}")
    _extra(out, obj.extra.values(), foreign)


def _sub_section(out: list[str], obj: Obj, sub: Sub, foreign: bool) -> None:
    out.append(f"[{obj.index:04X}sub{sub.subindex:X}]")
    out.append(f"ParameterName={sub.name}")
    if sub.object_type is not None:
        out.append(f"ObjectType={_hex(sub.object_type)}")
    _value_keys(out, sub, foreign)
    out.append("")


def _ini_key(key: str) -> bool:
    """A key an INI reader reads back as a key (an XDD attribute or dummy entry may be named
    anything; ;Key=Value comments are the writer's own)."""
    return bool(key.strip()) and key.lstrip()[0] not in ";#[" and "=" not in key


def _typed_keys(out: list[str], sub: Sub) -> None:
    if sub.data_type is not None:
        out.append(f"DataType={_hex(sub.data_type, 4)}")
    if sub.access is not None:  # the EDS reader drops a ' #...' tail of AccessType: so does the writer
        out.append(f"AccessType={HASH_COMMENT.sub('', sub.access)}")
    for key, value in (("DefaultValue", sub.default), ("LowLimit", sub.low), ("HighLimit", sub.high)):
        if value is not None:
            out.append(f"{key}={value.text}")
    out.append(f"PDOMapping={int(sub.pdo_mapping)}")


def _value_keys(out: list[str], sub: Sub, foreign: bool) -> None:
    _typed_keys(out, sub)
    if sub.obj_flags is not None:
        out.append(f"ObjFlags={_hex(sub.obj_flags)}")
    if sub.parameter_value is not None:
        out.append(f"ParameterValue={sub.parameter_value.text}")
    for key, text in (("Denotation", sub.denotation), ("UploadFile", sub.upload_file),
                      ("DownloadFile", sub.download_file)):
        if text is not None:
            out.append(f"{key}={text}")
    if sub.storage is not None:
        out.append(f";StorageLocation={sub.storage}")
    _extra(out, sub.extra.values(), foreign)


def _compact_sections(out: list[str], obj: Obj) -> None:
    compact = [s for s in obj.sorted_subs() if s.compact and s.subindex > 0]
    names = [s for s in compact if s.name != f"{obj.name}{s.subindex}"]
    values = [s for s in compact if s.parameter_value is not None]
    for suffix, subs, text in (("Name", names, lambda s: s.name),
                               ("Value", values, lambda s: s.parameter_value.text)):
        if subs:
            out.append(f"[{obj.index:04X}{suffix}]")
            out.append(f"NrOfEntries={len(subs)}")
            out.extend(f"{s.subindex}={text(s)}" for s in subs)
            out.append("")
