"""The object-dictionary model every reader produces and every later stage reads.

Plain data. A VAR object keeps its attributes on `subs[0]`, so every value in the
dictionary is addressed as (index, sub) whatever the object code. Values keep
their source text next to the parsed form; `line` fields locate them in `source`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .datatypes import BASIC_TYPES, DataType
from .values import Value

# Object codes (CiA 301 table 42, CiA 306 ObjectType).
NULL, DOMAIN, DEFTYPE, DEFSTRUCT, VAR, ARRAY, RECORD = 0x0, 0x2, 0x5, 0x6, 0x7, 0x8, 0x9
OBJECT_CODES = {NULL: "NULL", DOMAIN: "DOMAIN", DEFTYPE: "DEFTYPE", DEFSTRUCT: "DEFSTRUCT",
                VAR: "VAR", ARRAY: "ARRAY", RECORD: "RECORD"}
SINGLE_VALUE_CODES = (DOMAIN, DEFTYPE, VAR)

ACCESS_TYPES = ("ro", "wo", "rw", "rwr", "rww", "const")
READABLE = ("ro", "rw", "rwr", "rww", "const")
WRITABLE = ("wo", "rw", "rwr", "rww")


@dataclass(slots=True)
class Field:
    """A key/value pair kept verbatim: header keys and keys odgen does not interpret."""

    key: str
    text: str
    line: int = field(default=0, compare=False)


@dataclass(slots=True)
class Sub:
    subindex: int
    name: str = ""
    line: int = field(default=0, compare=False)
    object_type: int | None = None  # as written on a sub-object, if at all
    data_type: int | None = None
    access: str | None = None  # lower case as written, validity checked by rules
    pdo_mapping: bool = False
    default: Value | None = None
    low: Value | None = None
    high: Value | None = None
    parameter_value: Value | None = None
    denotation: str | None = None
    obj_flags: int | None = None
    upload_file: str | None = None
    download_file: str | None = None
    storage: str | None = None  # ;StorageLocation= / CO_storageGroup
    compact: bool = False  # expanded from CompactSubObj, not written as a section
    extra: dict[str, Field] = field(default_factory=dict)  # unknown keys, lower-case key
    lines: dict[str, int] = field(default_factory=dict, compare=False)  # keyword -> line

    def line_of(self, keyword: str) -> int:
        """Line of a keyword (lower case) if written, else of the entry itself."""
        return self.lines.get(keyword, self.line)

    @property
    def readable(self) -> bool:
        return self.access in READABLE

    @property
    def writable(self) -> bool:
        return self.access in WRITABLE

    @property
    def dtype(self) -> DataType | None:
        return BASIC_TYPES.get(self.data_type) if self.data_type is not None else None


@dataclass(slots=True)
class Obj:
    index: int
    name: str = ""
    line: int = field(default=0, compare=False)
    object_code: int = VAR
    object_code_written: bool = True  # False when ObjectType was absent (implied VAR)
    subs: dict[int, Sub] = field(default_factory=dict)
    sub_number: int | None = None  # SubNumber as declared
    sub_number_line: int = field(default=0, compare=False)
    compact_sub_obj: int | None = None  # CompactSubObj as declared
    obj_flags: int | None = None
    storage: str | None = None
    count_label: str | None = None
    object_list: str | None = None  # which [...Objects] list named it, if any
    extra: dict[str, Field] = field(default_factory=dict)
    lines: dict[str, int] = field(default_factory=dict, compare=False)  # keyword -> line

    def line_of(self, keyword: str) -> int:
        return self.lines.get(keyword, self.line)

    @property
    def is_var(self) -> bool:
        return self.object_code in SINGLE_VALUE_CODES

    @property
    def var(self) -> Sub | None:
        """The single value of a VAR/DOMAIN/DEFTYPE object."""
        return self.subs.get(0) if self.is_var else None

    def sorted_subs(self) -> list[Sub]:
        return [self.subs[k] for k in sorted(self.subs)]

    @property
    def structure(self) -> int:
        """The object code the object is generated as: an ARRAY whose elements differ in data type
        (CanFestival's 0x1400/0x1800, rule OBJ026) is the RECORD CiA 301 defines."""
        if self.object_code == 0x8 and len({s.data_type for k, s in self.subs.items() if k and s.data_type}) > 1:
            return 0x9
        return self.object_code


@dataclass(slots=True)
class Section:
    """A header section ([FileInfo], [DeviceInfo], ...) as ordered key/value fields."""

    name: str
    line: int = field(default=0, compare=False)
    fields: dict[str, Field] = field(default_factory=dict)  # lower-case key

    def get(self, key: str) -> Field | None:
        return self.fields.get(key.lower())

    def text(self, key: str, default: str = "") -> str:
        f = self.get(key)
        return f.text if f is not None else default

    def set(self, key: str, text: str, line: int = 0) -> None:
        self.fields[key.lower()] = Field(key, text, line)


@dataclass(slots=True)
class ObjectList:
    """[MandatoryObjects] / [OptionalObjects] / [ManufacturerObjects] as written."""

    name: str
    line: int = field(default=0, compare=False)
    supported: Field | None = None
    entries: list[Field] = field(default_factory=list)  # key "1".."N", text the index


@dataclass(slots=True)
class ObjectDictionary:
    source: str  # the file name used in diagnostics
    format: str  # eds | dcf | xdd | xdc
    objects: dict[int, Obj] = field(default_factory=dict)
    sections: dict[str, Section] = field(default_factory=dict)  # lower-case name
    object_lists: dict[str, ObjectList] = field(default_factory=dict)  # lower-case name
    node_id: int | None = None  # DCF [DeviceComissioning] NodeID / XDC

    def section(self, name: str) -> Section | None:
        return self.sections.get(name.lower())

    def ensure_section(self, name: str) -> Section:
        key = name.lower()
        if key not in self.sections:
            self.sections[key] = Section(name)
        return self.sections[key]

    def sorted_objects(self) -> list[Obj]:
        return [self.objects[k] for k in sorted(self.objects)]

    def find(self, index: int, sub: int = 0) -> Sub | None:
        obj = self.objects.get(index)
        return obj.subs.get(sub) if obj is not None else None

    @property
    def is_config(self) -> bool:
        """DCF/XDC: a configured device, where ParameterValue/Denotation belong."""
        return self.format in ("dcf", "xdc")

    def value_in_force(self, sub: Sub) -> Value | None:
        """The value the device starts with: a DCF's (XDC's) ParameterValue where given, else the
        DefaultValue; an EDS's ParameterValue is ignored (OBJ024). `Value.resolve(node_id)` resolves
        `$NODEID`; a Denotation names the value, it is not one. The rules, `generate`, `check`,
        `roundtrip` and `explain` all take values from here."""
        given = sub.parameter_value
        if self.is_config and given is not None and not given.empty:
            return given
        return sub.default
