"""CiA 306 semantics over the INI reader: EDS and DCF files to the model.

Keys are matched case-insensitively; keys odgen does not interpret are kept in
`extra` so the EDS writer gives every value back. Objects listed with
CompactSubObj are expanded into sub-entries marked `compact`.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from ..catalogue.rule import Rule
from ..catalogue.syntax import SYN010, SYN012, SYN013, SYN014, SYN015, SYN016, SYN017, SYN019
from ..diagnostics import Diagnostics, Loc
from ..model import VAR, Field, Obj, ObjectDictionary, ObjectList, Section, Sub
from ..model.datatypes import BASIC_TYPES, DataType
from ..model.od import SINGLE_VALUE_CODES
from ..model.values import Value, parse_int_literal, parse_value
from . import ini

OBJECT_LISTS = ("MandatoryObjects", "OptionalObjects", "ManufacturerObjects")
HEADER_SECTIONS = ("FileInfo", "DeviceInfo", "DeviceComissioning", "DummyUsage", "Comments",
                   "Tools", "DynamicChannels", "SupportedModules")
_CANONICAL_SECTIONS = {name.lower(): name for name in HEADER_SECTIONS + OBJECT_LISTS}
_MODULE_SECTION = re.compile(r"^m\d+(moduleinfo|fixedobjects|subextends|subext[0-9a-f]{4}|comments)$")
_OBJECT_SECTION = re.compile(r"^([0-9a-f]{4})(?:(sub)([0-9a-f]+)|(name)|(value))?$", re.IGNORECASE)
_SHORT_INDEX = re.compile(r"^([0-9a-f]{1,3})(sub[0-9a-f]+|name|value)?$", re.IGNORECASE)  # [A0], [A0sub1]

# Keywords of object and sub-object sections, in the spelling of CiA 306.
KEYWORDS = ("ParameterName", "ObjectType", "DataType", "AccessType", "DefaultValue", "LowLimit",
            "HighLimit", "PDOMapping", "ObjFlags", "SubNumber", "CompactSubObj", "ParameterValue",
            "Denotation", "UploadFile", "DownloadFile", "StorageLocation", "CountLabel")
_CANONICAL_KEYS = {k.lower(): k for k in KEYWORDS}
# CANopenNode's editor writes its extensions as comments: ;StorageLocation=RAM
_SPELLED_RIGHT = frozenset(KEYWORDS)
COMMENT_KEYS = frozenset({"storagelocation", "countlabel", "tpdodetectcos"})
OBJECT_KEYS = frozenset({"parametername", "objecttype", "subnumber", "compactsubobj", "objflags",
                         "storagelocation", "countlabel"})
VALUE_KEYS = frozenset({"datatype", "accesstype", "defaultvalue", "lowlimit", "highlimit", "pdomapping",
              "objflags", "parametervalue", "denotation", "uploadfile", "downloadfile",
              "storagelocation", "parametername", "objecttype", "countlabel"})
TEMPLATE_KEYS = frozenset({"datatype", "accesstype", "defaultvalue", "lowlimit", "highlimit", "pdomapping"})
_STRINGLIKE = ("vstring", "ustring", "domain")
HASH_COMMENT = re.compile(r"\s+#.*$")


def load_eds(data: bytes, source: str, diags: Diagnostics, fmt: str = "eds") -> ObjectDictionary:
    text = ini.decode(data, source, diags)
    names: dict[str, int] = {}  # every section name read so far (the INI reader fills it)
    od = _Reader(source, fmt, diags).read(ini.sections(text, source, diags, COMMENT_KEYS, names), names)
    if _SPACE_AT_LINE_END.search(text) or text.endswith(" "):  # one scan, ~2 ms a MB
        _keep_string_padding(od, text)
    return od


_SPACE_AT_LINE_END = re.compile(" [\r\n]")
_PADDED_KEYS = (("default", "defaultvalue"), ("parameter_value", "parametervalue"))


def _keep_string_padding(od: ObjectDictionary, text: str) -> None:
    """A string's DefaultValue/ParameterValue keeps the spaces that end its line, as the XDD reader
    keeps them: CANopenNode pads a string with spaces to reserve its capacity (`Trace1` and 24
    spaces: 30 bytes), which the INI reader, stripping every line, would cut to 6. Only files
    with a line ending in a space pay for this second look at the lines that hold string values."""
    wanted: dict[int, tuple[Sub, str, str]] = {}
    for obj in od.objects.values():
        for sub in obj.subs.values():
            if sub.dtype is not None and sub.dtype.kind in ("vstring", "ustring"):
                for attr, key in _PADDED_KEYS:
                    value = getattr(sub, attr)
                    if value is not None and value.line:
                        wanted[value.line] = (sub, attr, key)
    pending = sorted(wanted, reverse=True)  # line numbers, the next one last
    for first, lines in ini._parts(text):
        while pending and pending[-1] < first + len(lines):
            number = pending.pop()
            sub, attr, key = wanted[number]
            written, _, raw = lines[number - first].partition("=")
            padded, value = raw.lstrip(), getattr(sub, attr)
            if written.strip().lower() == key and padded != value.text and padded.rstrip() == value.text:
                setattr(sub, attr, parse_value(padded, sub.dtype, number))


class _Reader:
    def __init__(self, source: str, fmt: str, diags: Diagnostics) -> None:
        self.od = ObjectDictionary(source=source, format=fmt)
        self.diags = diags
        self.spellings: set[str] = set()
        self.compact: list[tuple[int, ini.IniSection]] = []  # [XXXXName]/[XXXXValue], read last

    def loc(self, line: int) -> Loc:
        return Loc(self.od.source, line)

    def report(self, rule: Rule, line: int, message: str, index: int | None = None, blocks: bool = True) -> None:
        self.diags.add(rule, self.loc(line), message, index, blocks=blocks)

    def read(self, stream: Iterable[tuple[str, ini.IniSection]], names: dict[str, int]) -> ObjectDictionary:
        """Sections are converted as they are read and then dropped; what needs a section further on
        waits: a sub-object whose object comes later, [XXXXName]/[XXXXValue] (after every sub-object),
        and an index written without leading zeros (it depends on whether [00A0] exists)."""
        later: list[tuple[str, ini.IniSection]] = []
        for key, section in stream:
            match = _OBJECT_SECTION.match(key)
            if (match is None and _SHORT_INDEX.match(key)) or not self._section(key, match, section, waiting=True):
                later.append((key, section))
        for key, section in sorted(later, key=lambda item: "sub" in item[0]):  # objects before sub-objects
            key = self._padded(key, section, names)
            self._section(key, _OBJECT_SECTION.match(key), section, waiting=False)
        for index, section in self.compact:
            self._compact_section(index, section)
        self._node_id()
        return self.od

    def _section(self, key: str, match: re.Match[str] | None, section: ini.IniSection, waiting: bool) -> bool:
        """Convert one section (`match`: its name against _OBJECT_SECTION); False when it has to wait
        for the rest of the file."""
        if match is None:
            self._header_section(key, section)
            return True
        hex_index, sub, sub_text, name_list, value_list = match.groups()
        index = int(hex_index, 16)
        if sub:
            if waiting and index not in self.od.objects:
                return False
            self._sub_section(index, sub_text, section)
        elif name_list or value_list:  # [XXXXName], [XXXXValue]
            self.compact.append((index, section))
        else:
            self._object(index, section)
        return True

    def _padded(self, key: str, section: ini.IniSection, names: dict[str, int]) -> str:
        """An object section written without leading zeros ([A0]) is read as [00A0], unless that exists too."""
        short = _SHORT_INDEX.match(key)
        if short is None:
            return key
        padded = short.group(1).zfill(4) + (short.group(2) or "")
        if padded.lower() in names:
            return key
        self.diags.add(SYN019, self.loc(section.line),
                       f"section [{section.name}] writes the index without leading zeros; read as [{padded.upper()}]")
        return padded

    # -- header sections -------------------------------------------------

    def _header_section(self, key: str, section: ini.IniSection) -> None:
        canonical = _CANONICAL_SECTIONS.get(key)
        if key == "devicecommissioning" and "devicecomissioning" not in self.od.sections:
            canonical = "DeviceComissioning"
            self.diags.add(SYN010, self.loc(section.line),
                           f"section [{section.name}] is spelled [DeviceComissioning] in CiA 306; read as such")
            key = "devicecomissioning"
        elif canonical is None and not _MODULE_SECTION.match(key):
            self.diags.add(SYN010, self.loc(section.line), f"section [{section.name}] is not defined by CiA 306")
        self._spelling(section.name, canonical, section.line)
        if canonical in OBJECT_LISTS:
            self.od.object_lists[key] = self._object_list(canonical, section)
            return
        target = Section(canonical or section.name, section.line)
        target.fields = {lower: Field(entry.key, entry.value, entry.line) for lower, entry in section.entries()}
        self.od.sections[key] = target

    def _object_list(self, name: str, section: ini.IniSection) -> ObjectList:
        olist = ObjectList(name, section.line)
        for _, entry in section.entries():
            fld = Field(entry.key, entry.value, entry.line)
            if entry.key.lower() == "supportedobjects":
                olist.supported = fld
            else:
                olist.entries.append(fld)
        return olist

    def _node_id(self) -> None:
        section = self.od.section("DeviceComissioning")
        fld = section.get("NodeID") if section else None
        if fld is not None:
            self.od.node_id = self._number(fld.key, fld.text, fld.line)

    # -- objects -----------------------------------------------------------

    def _object(self, index: int, section: ini.IniSection) -> None:
        values = section.values
        code = self._int(section, "objecttype")
        sub_number = self._int(section, "subnumber")
        compact = self._int(section, "compactsubobj")
        # Obj's fields in order, as _sub builds Sub; no ObjectType means VAR (CiA 306)
        obj = Obj(index, values.get("parametername") or "", section.line, VAR if code is None else code,
                  "objecttype" in values, {}, sub_number, 0, compact, None, None, values.get("countlabel"), None,
                  {}, dict(section.lines))
        self._check_spellings(section)
        if obj.is_var:
            obj.subs[0] = self._sub(index, 0, section, obj.name)
            obj.storage = obj.subs[0].storage
        else:
            self._container(obj, section)
        self.od.objects[index] = obj

    def _container(self, obj: Obj, section: ini.IniSection) -> None:
        obj.obj_flags = self._int(section, "objflags")
        obj.storage = section.values.get("storagelocation")
        keep = OBJECT_KEYS | TEMPLATE_KEYS if obj.compact_sub_obj else OBJECT_KEYS
        if not keep.issuperset(section.values):
            obj.extra = self._extra(section, keep)
        if obj.compact_sub_obj:
            self._expand_compact(obj, section)

    def _sub(self, index: int, subindex: int, section: ini.IniSection, name: str | None = None) -> Sub:
        values = section.values  # lower-case keys: this runs once per sub-entry, keep it lean
        get = values.get
        data_type = self._int(section, "datatype")
        dtype = BASIC_TYPES.get(data_type) if data_type is not None else None
        object_type = None
        if name is None and "objecttype" in values:  # only real sub-object sections carry their own
            object_type = self._int(section, "objecttype")
        access = self._access(section)
        pdo_mapping = self._flag(section, "pdomapping")
        obj_flags = self._int(section, "objflags") if "objflags" in values else None
        default = self._value(section, "defaultvalue", dtype) if "defaultvalue" in values else None
        low = self._value(section, "lowlimit", dtype) if "lowlimit" in values else None
        high = self._value(section, "highlimit", dtype) if "highlimit" in values else None
        parameter_value = self._value(section, "parametervalue", dtype) if "parametervalue" in values else None
        extra = {} if VALUE_KEYS.issuperset(values) else self._extra(section, VALUE_KEYS)
        # Sub's fields in order: passed by keyword, they would cost a third of this function's time
        return Sub(subindex, name if name is not None else get("parametername") or "", section.line, object_type,
                   data_type, access, pdo_mapping, default, low, high, parameter_value, get("denotation"),
                   obj_flags, get("uploadfile"), get("downloadfile"), get("storagelocation"), False, extra,
                   dict(section.lines))

    @staticmethod
    def _extra(section: ini.IniSection, known: frozenset[str]) -> dict[str, Field]:
        return {key: Field(entry.key, entry.value, entry.line) for key, entry in section.entries() if key not in known}

    def _access(self, section: ini.IniSection) -> str | None:
        text = section.values.get("accesstype")
        if text is None:
            return None
        if "#" in text:
            text = self._strip_hash_comment(section.entry("accesstype"))
        return text.strip().lower()

    def _value(self, section: ini.IniSection, key: str, dtype: DataType | None) -> Value | None:
        text = section.values.get(key)
        if text is None:
            return None
        if "#" in text and dtype is not None and dtype.kind not in _STRINGLIKE:
            text = self._strip_hash_comment(section.entry(key))
        return parse_value(text, dtype, section.lines[key])

    def _strip_hash_comment(self, entry: ini.IniEntry) -> str:
        match = HASH_COMMENT.search(entry.value) if "#" in entry.value else None
        if match is None:
            return entry.value
        self.diags.add(SYN014, self.loc(entry.line),
                       f"inline comment '{match.group(0).strip()}' after the value of '{entry.key}' is dropped")
        return entry.value[: match.start()]

    # -- sub-objects ---------------------------------------------------------

    def _sub_section(self, index: int, sub_text: str, section: ini.IniSection) -> None:
        subindex = int(sub_text, 16)
        parent = self.od.objects.get(index)
        if subindex > 0xFE:
            self.report(SYN017, section.line, f"[{section.name}]: sub-index 0x{subindex:X} is above 0xFE")
            return
        if parent is None or parent.object_code in SINGLE_VALUE_CODES:
            why = f"has no [{index:04X}] section" if parent is None else "is not an ARRAY or RECORD"
            self.report(SYN013, section.line, f"[{section.name}]: object 0x{index:04X} {why}")
            return
        self._check_spellings(section)
        if section.name[4:7] != "sub":
            self._spelling(section.name[4:7], "sub", section.line)
        parent.subs[subindex] = self._sub(index, subindex, section)

    # -- CompactSubObj -------------------------------------------------------

    def _expand_compact(self, obj: Obj, section: ini.IniSection) -> None:
        count = obj.compact_sub_obj or 0
        if count > 0xFE:
            # sub-index 255 is reserved by CiA 301 (the object's structure): no master reads it as an element
            self.report(SYN016, obj.line_of("compactsubobj"), f"CompactSubObj={count} is above 254", obj.index,
                        blocks=False)
            count = 0xFE
        sub0 = Sub(0, "NrOfObjects", line=obj.line, data_type=0x0005, access="ro", compact=True)
        sub0.default = parse_value(str(count), BASIC_TYPES[0x0005], obj.line_of("compactsubobj"))
        obj.subs[0] = sub0
        for subindex in range(1, count + 1):
            sub = self._sub(obj.index, subindex, section, name=f"{obj.name}{subindex}")
            sub.compact, sub.extra, sub.storage = True, {}, None
            obj.subs[subindex] = sub

    def _compact_section(self, index: int, section: ini.IniSection) -> None:
        obj = self.od.objects.get(index)
        kind = "names" if section.name.lower().endswith("name") else "values"
        if obj is None or not obj.compact_sub_obj:
            self.report(SYN016, section.line,
                        f"[{section.name}] lists {kind} but object 0x{index:04X} has no CompactSubObj", index)
            return
        entries = self._compact_entries(obj, section)
        for subindex, entry in entries.items():
            sub = obj.subs.get(subindex)
            if sub is None:  # CompactSubObj on an object that is not an ARRAY/RECORD (OBJ007)
                continue
            if kind == "names":
                sub.name = entry.value
            else:
                sub.parameter_value = parse_value(entry.value, sub.dtype, entry.line)

    def _compact_entries(self, obj: Obj, section: ini.IniSection) -> dict[int, ini.IniEntry]:
        result: dict[int, ini.IniEntry] = {}
        nr = section.get("NrOfEntries")
        for key, entry in section.entries():
            if key == "nrofentries":
                continue
            subindex, _ = parse_int_literal(key)
            if subindex is None or not 1 <= subindex <= (obj.compact_sub_obj or 0):
                bad = f"[{section.name}] entry '{entry.key}' is not a sub-index 1..{obj.compact_sub_obj}"
                self.report(SYN016, entry.line, bad, obj.index)
                continue
            result[subindex] = entry
        declared = self._int_entry(nr) if nr is not None else None
        if declared != len(result):
            line = nr.line if nr is not None else section.line
            written = nr.value if nr is not None else "(missing)"
            mismatch = f"[{section.name}] NrOfEntries={written} but {len(result)} entries follow"
            self.report(SYN016, line, mismatch, obj.index, blocks=False)  # the entries present are all read
        return result

    # -- small readers ---------------------------------------------------------

    def _int(self, section: ini.IniSection, key: str) -> int | None:
        """The integer under a lower-case key: a plain number is read here, anything else by _int_entry."""
        text = section.values.get(key)
        if text is None:
            return None
        if "#" not in text:
            number, notes = parse_int_literal(text)
            if number is not None and not notes:
                return number
        return self._int_entry(section.entry(key))

    def _int_entry(self, entry: ini.IniEntry | None) -> int | None:
        if entry is None:
            return None
        return self._number(entry.key, self._strip_hash_comment(entry), entry.line)

    def _number(self, key: str, text: str, line: int) -> int | None:
        number, notes = parse_int_literal(text)
        for rule, message in notes:
            self.diags.add(rule, self.loc(line), f"{key}: {message}")
        if number is None:
            # an empty value is read as absent, as every reader does: nothing the C holds depends on it
            self.diags.add(SYN015, self.loc(line), f"{key}='{text}' is not a number", blocks=bool(text.strip()))
        return number

    def _flag(self, section: ini.IniSection, key: str) -> bool:
        text = section.values.get(key)
        if text is None or text == "0":
            return False
        if text == "1":
            return True
        return self._flag_entry(section.entry(key))

    def _flag_entry(self, entry: ini.IniEntry | None) -> bool:
        if entry is None:
            return False
        text = self._strip_hash_comment(entry).strip().lower()
        number, _ = parse_int_literal(text)
        if number in (0, 1):
            return number == 1
        if text in ("true", "false"):
            return text == "true"
        self.diags.add(SYN015, self.loc(entry.line), f"{entry.key}='{entry.value}' is not 0 or 1",
                       blocks=bool(text))
        return False

    def _check_spellings(self, section: ini.IniSection) -> None:
        if _SPELLED_RIGHT.issuperset(section.keys.values()):
            return
        for key, entry in section.entries():
            if entry.key not in _SPELLED_RIGHT:
                self._spelling(entry.key, _CANONICAL_KEYS.get(key), entry.line)

    def _spelling(self, written: str, canonical: str | None, line: int) -> None:
        """Report each unusual spelling of a known keyword once per file."""
        if canonical is None or written == canonical or written.lower() != canonical.lower():
            return
        if written in self.spellings:
            return
        self.spellings.add(written)
        self.diags.add(SYN012, self.loc(line), f"'{written}' is spelled '{canonical}' in CiA 306")

