"""CiA 311 XDD/XDC files (XML) to the model, the same model the EDS reader builds.

Reading, in order: parse with lxml without entity expansion, DTD or network;
refuse a DOCTYPE (XML003) and any root but the CANopen `ISO15745ProfileContainer`
(XML002); put every element of the CANopen 1.0/1.1 namespaces or of no namespace
into the 1.1 namespace on a copy (real files differ in qualification, see
schemas/cia311-odgen.xsd); read the model; validate the copy against the schema.

Mapping decisions (tests/test_xdd.py pins each of them):

- Format: "xdc" when NetworkManagement has a `deviceCommissioning` (what makes an
  XDC a configured device), else by the `.xdc` suffix of `source`, else "xdd".
- An entry's attributes come from the CANopenObject/CANopenSubObject and from the
  device-profile `parameter` its `uniqueIDRef` names (CANopenEditor writes them
  only there). The CANopenObject attribute wins when both give one (it is the
  exact CiA 301 form: hex data type code, access word); a difference is XML009.
- Access: accessType const/ro/wo/rw is the EDS word; a parameter's `access` maps
  const/read/write/readWrite to const/ro/wo/rw, readWriteInput (process input,
  read by TPDO) to rwr and readWriteOutput (process output, written by RPDO) to
  rww, as CANopenEditor does; a parameter without `access` is "read" (schema
  default). CiA 311 has no rwr/rww words and writes them as rw with
  PDOmapping="TPDO"/"RPDO" (libedssharp #128), so rw+TPDO reads as rwr and
  rw+RPDO as rww.
- PDOmapping default/optional/TPDO/RPDO is mappable. A TPDO/RPDO direction the
  access does not already say (ro/const/rwr imply TPDO, wo/rww imply RPDO) is kept
  verbatim in `sub.extra["pdomapping"]`, so nothing is lost.
- Parameter data types are IEC 61131 names; BITSTRING is OCTET_STRING when the
  entry has a default value and DOMAIN otherwise (CANopenEditor's convention).
- A VAR/DOMAIN/DEFTYPE object keeps its attributes on `subs[0]`, named as the
  object, as the EDS reader does.
- CANopenEditor properties: CO_storageGroup -> storage (of the object and, for a
  VAR, of subs[0]), CO_countLabel -> count_label; other properties (CO_disabled,
  CO_flagsPDO, CO_accessSRDO, ...) -> `extra` where the EDS reader keeps unknown
  keys: obj.extra of an ARRAY/RECORD, subs[0].extra of a VAR, sub.extra of a
  sub-object.
- Unknown attributes of CANopenObject/CANopenSubObject -> the same `extra`.
- Problems the model rules report for every format (no name, invalid access word
  or object code, undefined data type, values out of range) are left to them; the
  schema's messages about those attributes are dropped.
- Header: DeviceIdentity, ProfileBody file attributes, CANopenGeneralFeatures,
  baud rates, dummy usage and deviceCommissioning become the EDS sections
  DeviceInfo, FileInfo, DummyUsage and DeviceComissioning with EDS keys and EDS
  value forms (0/1 flags, MM-DD-YYYY dates, hh:mmAM times).
"""

from __future__ import annotations

import copy
import datetime
import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import Any, cast

from lxml import etree

from ..assets import schema_path
from ..catalogue.rule import Rule
from ..catalogue.xml import (
    XML001, XML002, XML003, XML004, XML005, XML006, XML007, XML008, XML009, XML010, XML011, XML012, XML013)
from ..diagnostics import Diagnostics, Loc
from ..model import ARRAY, DEFSTRUCT, RECORD, VAR, Field, Obj, ObjectDictionary, Sub, Value, lookup, parse_value
from ..model.datatypes import BASIC_TYPES, DataType
from ..model.od import OBJECT_CODES
from ..model.values import bounded_int

NS = "http://www.canopen.org/xml/1.1"
CANOPEN_NAMESPACES = (NS, "http://www.canopen.org/xml/1.0")
XSI = "http://www.w3.org/2001/XMLSchema-instance"
ROOT = "ISO15745ProfileContainer"

# IEC 61131 type names of device-profile parameters -> CiA 301 data type codes.
IEC_TYPES = {"BOOL": 0x01, "SINT": 0x02, "CHAR": 0x02, "INT": 0x03, "DINT": 0x04, "LINT": 0x15,
             "USINT": 0x05, "BYTE": 0x05, "UINT": 0x06, "WORD": 0x06, "UDINT": 0x07,
             "DWORD": 0x07, "ULINT": 0x1B, "LWORD": 0x1B, "REAL": 0x08, "LREAL": 0x11,
             "STRING": 0x09, "WSTRING": 0x0B, "BITSTRING": 0x0A}
OCTET_STRING, DOMAIN_TYPE = 0x0A, 0x0F
# Codes a BITSTRING parameter may stand for (CANopenEditor writes odd-sized integers so).
BITSTRING_CODES = {0x0A, 0x0C, 0x0D, 0x0F, 0x10, 0x12, 0x13, 0x14, 0x16, 0x18, 0x19, 0x1A}

ACCESS_WORDS = ("const", "ro", "wo", "rw")
PARAMETER_ACCESS = {"const": "const", "read": "ro", "write": "wo", "readWrite": "rw",
                    "readWriteInput": "rwr", "readWriteOutput": "rww", "noAccess": None}
PDO_WORDS = ("no", "default", "optional", "TPDO", "RPDO")
OBJECT_CODE_NAMES = {"NULL": 0, "DOMAIN": 2, "DEFTYPE": 5, "DEFSTRUCT": 6, "VAR": 7, "ARRAY": 8,
                     "RECORD": 9}

ENTRY_ATTRIBUTES = {"index", "subIndex", "name", "objectType", "dataType", "lowLimit", "highLimit",
                    "accessType", "defaultValue", "actualValue", "denotation", "PDOmapping",
                    "objFlags", "uniqueIDRef", "subNumber"}
CONTAINER_IGNORED = ("dataType", "accessType", "PDOmapping", "defaultValue", "actualValue",
                     "lowLimit", "highLimit", "denotation")

# Attributes the reader reads and reports itself; the schema's complaints about
# their values are dropped so each problem is reported once.
READER_OWNED = {("CANopenObject", a) for a in ("index", "subNumber")} | {
    (e, a) for e in ("CANopenObject", "CANopenSubObject")
    for a in ("subIndex", "objectType", "dataType", "accessType", "PDOmapping", "objFlags")
} | {("parameter", "access"), ("parameter", "uniqueID"), ("deviceCommissioning", "NodeID"),
                                                                            ("deviceCommissioning", "nodeID")} | {
    ("CANopenGeneralFeatures", a) for a in ("granularity", "nrOfRxPDO", "nrOfTxPDO")  # header rules check them
}

def _node_id_attr(el: etree._Element) -> str:
    """The node-id attribute's spelling: CiA 311's `nodeID`, or `NodeID` as some tools write it."""
    return "NodeID" if el.get("nodeID") is None and el.get("NodeID") is not None else "nodeID"


# The hexBinary forms of CiA 311 (as in the schema), with an example.
HEX_FORMS = {"index": ("[0-9A-Fa-f]{4}", "1A00"), "subIndex": ("[0-9A-Fa-f]{2}", "0A"),
             "dataType": ("[0-9A-Fa-f]{2}([0-9A-Fa-f]{2})?", "0007"),
             "objFlags": ("([0-9A-Fa-f]{2}){1,4}", "0003")}
BAUD_KEYS = {f"{rate} Kbps": f"BaudRate_{rate}" for rate in (10, 20, 50, 125, 250, 500, 800, 1000)}


# Converters of XML values to the EDS form return None for text the schema rejects
# (reported there), so the header rules do not report the same value again.

def _eds_date(text: str) -> str | None:
    """An xs:date as the EDS MM-DD-YYYY."""
    try:
        return datetime.date.fromisoformat(text.strip()[:10]).strftime("%m-%d-%Y")
    except ValueError:
        return None


def _eds_time(text: str) -> str | None:
    """An xs:time as the EDS hh:mm(AM|PM)."""
    match = re.match(r"^\s*(\d{2}):(\d{2})", text)
    if match is None or int(match.group(1)) > 23:
        return None
    hour, minute = int(match.group(1)), match.group(2)
    return f"{(hour % 12) or 12:02d}:{minute}{'AM' if hour < 12 else 'PM'}"


def _flag(text: str) -> str | None:
    """An xs:boolean as the EDS 0/1 flag."""
    return {"true": "1", "1": "1", "false": "0", "0": "0"}.get(text.strip())


# ProfileBody file attributes -> [FileInfo] keys, with the conversion to the EDS form.
FILE_INFO: dict[str, tuple[str, Callable[[str], str | None]]] = {
    "fileName": ("FileName", str), "fileVersion": ("FileVersion", str), "fileCreator": ("CreatedBy", str),
    "fileCreationDate": ("CreationDate", _eds_date), "fileCreationTime": ("CreationTime", _eds_time),
    "fileModifiedBy": ("ModifiedBy", str), "fileModificationDate": ("ModificationDate", _eds_date),
    "fileModificationTime": ("ModificationTime", _eds_time)}


def q(name: str) -> str:
    return f"{{{NS}}}{name}"


def load_xdd(data: bytes, source: str, diags: Diagnostics) -> ObjectDictionary | None:
    """Read an XDD/XDC; None when the file is not a readable CiA 311 document."""
    root = _parse(data, source, diags)
    if root is None or not _is_cia311(root, source, diags):
        return None
    doc = _normalized(root)
    reader = _Reader(source, doc, diags)
    od = reader.read()
    _validate(doc, source, diags, reader)
    return od


# -- parsing -------------------------------------------------------------------


def _parse(data: bytes, source: str, diags: Diagnostics) -> etree._Element | None:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=False, remove_blank_text=False)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as err:
        line = err.lineno if isinstance(err.lineno, int) and err.lineno > 0 else 1
        message = re.sub(r",\s*line \d+, column \d+$", "", err.msg or "") or "the file is not XML"
        diags.add(XML001, Loc(source, line), message)
        return None
    doctype = str(getattr(root.getroottree().docinfo, "doctype", "") or "")
    if doctype:
        start = data.find(b"<!DOCTYPE")
        line = data.count(b"\n", 0, start) + 1 if start >= 0 else 1
        diags.add(XML003, Loc(source, line),
                  f"DOCTYPE declaration '{_clip(doctype)}' refused: odgen reads no DTD and expands no entities")
        return None
    return root


def _is_cia311(root: etree._Element, source: str, diags: Diagnostics) -> bool:
    name = etree.QName(root)
    if name.localname == ROOT and name.namespace in CANOPEN_NAMESPACES:
        return True
    if name.localname == ROOT and name.namespace is None:
        diags.add(XML004, Loc(source, _line(root) or 1),
                  f"{ROOT} has no namespace; CiA 311 puts it in {NS}")
        return True
    found = f"{{{name.namespace}}}{name.localname}" if name.namespace else name.localname
    diags.add(XML002, Loc(source, _line(root) or 1),
              f"the root element is {found}, not {ROOT} in the CANopen namespace {NS}")
    return False


def _normalized(root: etree._Element) -> etree._Element:
    """A copy with the CANopen elements in one namespace and no xsi attributes."""
    doc = copy.deepcopy(root)
    for el in doc.iter():
        if not isinstance(el.tag, str):
            continue
        name = etree.QName(el)
        if name.namespace is None or name.namespace in CANOPEN_NAMESPACES:
            el.tag = q(name.localname)
        for attr in [a for a in el.attrib if str(a).startswith(f"{{{XSI}}}")]:
            del el.attrib[attr]
    return doc


def _clip(text: str, width: int = 60) -> str:
    text = " ".join(text.split())
    return text if len(text) <= width else text[: width - 3] + "..."


# -- small helpers over elements -------------------------------------------------


def _children(el: etree._Element | None, name: str) -> list[etree._Element]:
    return [] if el is None else list(el.iterchildren(q(name)))


def _child(el: etree._Element | None, name: str) -> etree._Element | None:
    return None if el is None else el.find(q(name))


def _text(el: etree._Element) -> str:
    return (el.text or "").strip()


def _label(el: etree._Element | None) -> str | None:
    """The first label or description of a g_labels element."""
    for child in [] if el is None else el.iterchildren(q("label"), q("description")):
        return _text(child)
    return None


def _line(el: etree._Element | None) -> int:
    line = None if el is None else el.sourceline
    return line if isinstance(line, int) else 0


@dataclass
class _Found:
    """A value as found in the file: its text and the line of the element holding it."""

    text: str
    line: int


# -- the model ---------------------------------------------------------------------


class _Reader:
    def __init__(self, source: str, root: etree._Element, diags: Diagnostics) -> None:
        self.od = ObjectDictionary(source=source, format="xdd")
        self.root = root
        self.diags = diags
        self.params: dict[str, etree._Element] = {}
        self.reported: set[tuple[int, str]] = set()  # (line, attribute) this reader reported
        self.subjects: dict[int, tuple[int, int | None]] = {}  # element line -> (index, sub)

    def loc(self, line: int) -> Loc:
        return Loc(self.od.source, line)

    def report(self, rule: Rule, el: etree._Element, attr: str, message: str,
               index: int | None = None, sub: int | None = None) -> None:
        if attr:  # so the schema's message about the same attribute is not repeated
            self.reported.add((_line(el), attr))
        self.diags.add(rule, self.loc(_line(el)), message, index, sub)

    def find(self, path: str) -> Iterator[etree._Element]:
        """Elements by a path of local names below the root, e.g. 'ProfileBody/DeviceIdentity'."""
        return self.root.iterfind(".//" + "/".join(q(part) for part in path.split("/")))

    def first(self, path: str) -> etree._Element | None:
        return next(self.find(path), None)

    def read(self) -> ObjectDictionary:
        self._index_parameters()
        self._file_info()
        self._device_info()
        self._general_features()
        self._baud_rates()
        self._dummy_usage()
        self._commissioning()
        self._objects()
        self.od.format = self._format()
        return self.od

    def _format(self) -> str:
        if self.first("NetworkManagement/deviceCommissioning") is not None:
            return "xdc"
        return "xdc" if self.od.source.lower().endswith(".xdc") else "xdd"

    def _index_parameters(self) -> None:
        for param in self.find("ApplicationProcess/parameterList/parameter"):
            uid = param.get("uniqueID")
            if not uid:
                continue  # required: the schema reports it
            first = self.params.setdefault(uid, param)
            if first is not param:
                self.report(XML004, param, "uniqueID",
                            f"parameter uniqueID '{uid}' is used again; the parameter of line {_line(first)} counts")

    # -- header sections -----------------------------------------------------

    def _device_body(self) -> etree._Element | None:
        bodies = list(self.root.iterchildren(q("ISO15745Profile")))
        bodies = [b for b in (_child(p, "ProfileBody") for p in bodies) if b is not None]
        for body in bodies:
            if _child(body, "DeviceIdentity") is not None or _child(body, "ApplicationProcess") is not None:
                return body
        return bodies[0] if bodies else None

    def _file_info(self) -> None:
        body = self._device_body()
        if body is None:
            return
        section = self.od.ensure_section("FileInfo")
        section.line = _line(body)
        for attr, (key, how) in FILE_INFO.items():
            text = body.get(attr)
            value = how(text) if text is not None else None
            if value is not None:
                section.set(key, value, _line(body))
        product_text = self.first("DeviceIdentity/productText")
        description = _label(product_text)
        if description is not None:
            section.set("Description", description, _line(product_text))

    def _device_info(self) -> None:
        identity = self.first("ProfileBody/DeviceIdentity")
        layer = self.first("ApplicationLayers/identity")
        keys = (("vendorName", "VendorName"), ("vendorID", "VendorNumber"),
                ("productName", "ProductName"), ("productID", "ProductNumber"),
                ("orderNumber", "OrderCode"))
        for name, key in keys:
            el = _child(identity, name)
            el = el if el is not None else _child(layer, name)
            if el is not None:
                self._info(key, _text(el), _line(el))

    def _info(self, key: str, text: str | None, line: int) -> None:
        if text is None:
            return  # not convertible: the schema reports it
        section = self.od.ensure_section("DeviceInfo")
        section.line = section.line or line
        section.set(key, text, line)

    def _general_features(self) -> None:
        general = self.first("NetworkManagement/CANopenGeneralFeatures")
        if general is not None:
            line = _line(general)
            if general.get("granularity") is not None:
                self._info("Granularity", general.get("granularity", ""), line)
            for attr, key in (("nrOfRxPDO", "NrOfRXPDO"), ("nrOfTxPDO", "NrOfTXPDO")):
                self._info(key, general.get(attr, "0"), line)
            for attr, key in (("layerSettingServiceSlave", "LSS_Supported"),
                              ("bootUpSlave", "SimpleBootUpSlave"), ("groupMessaging", "GroupMessaging")):
                self._info(key, _flag(general.get(attr, "false")), line)
            channels = _integer(general.get("dynamicChannels", "0"))
            self._info("DynamicChannelsSupported", None if channels is None else str(int(channels > 0)), line)
        master = self.first("NetworkManagement/CANopenMasterFeatures")
        if master is not None:
            self._info("SimpleBootUpMaster", _flag(master.get("bootUpMaster", "false")), _line(master))

    def _baud_rates(self) -> None:
        baud = self.first("TransportLayers/PhysicalLayer/baudRate")
        if baud is None:
            return
        supported = {el.get("value", "").strip(): _line(el) for el in _children(baud, "supportedBaudRate")}
        for value, key in BAUD_KEYS.items():
            self._info(key, "1" if value in supported else "0", supported.get(value, _line(baud)))

    def _dummy_usage(self) -> None:
        for el in self.find("ApplicationLayers/dummyUsage/dummy"):
            key, sep, flag = el.get("entry", "").partition("=")
            if sep:  # a malformed entry is a schema error
                section = self.od.ensure_section("DummyUsage")
                section.line = section.line or _line(el)
                section.set(key.strip(), flag.strip(), _line(el))

    def _commissioning(self) -> None:
        el = self.first("NetworkManagement/deviceCommissioning")
        if el is None:
            return
        section = self.od.ensure_section("DeviceComissioning")
        section.line = _line(el)
        keys = ((_node_id_attr(el), "NodeID"), ("nodeName", "NodeName"), ("actualBaudRate", "Baudrate"),
                ("networkNumber", "NetNumber"), ("networkName", "NetworkName"))
        for attr, key in keys:
            if el.get(attr) is not None:
                text = el.get(attr, "")
                section.set(key, re.sub(r"\s*Kbps$", "", text) if attr == "actualBaudRate" else text, _line(el))
        manager = _flag(el.get("CANopenManager", ""))
        if manager is not None:
            section.set("CANopenManager", manager, _line(el))
        self.od.node_id = self._node_id(el)

    def _node_id(self, el: etree._Element) -> int | None:
        attr = _node_id_attr(el)
        text = el.get(attr)
        if text is None:
            self.report(XML005, el, attr, "deviceCommissioning without nodeID")
            return None
        number = _integer(text)
        if number is None:
            self.report(XML005, el, attr, f"deviceCommissioning {attr} '{text}' is not a number")
        return number

    # -- objects -------------------------------------------------------------------

    def _objects(self) -> None:
        lists = list(self.find("ApplicationLayers/CANopenObjectList"))
        if not lists:
            where = self.first("ApplicationLayers")
            el = where if where is not None else self.root
            self.report(XML010, el, "", "the file has no ApplicationLayers/CANopenObjectList")
        for olist in lists:
            for el in _children(olist, "CANopenObject"):
                self._object(el)

    def _object(self, el: etree._Element) -> None:
        index = self._address(el, "index", None)
        if index is None:
            return
        first = self.od.objects.get(index)
        if first is not None:
            self.report(XML006, el, "index", f"is described again; the object of line {first.line} is kept", index)
            return
        self.subjects[_line(el)] = (index, None)
        param = self._parameter(el, index, None)
        subs = _children(el, "CANopenSubObject")
        obj = Obj(index=index, line=_line(el), name=self._name(el, param))
        code = self._object_type(el, index, None)
        obj.object_code_written = code is not None
        obj.object_code = code if code is not None else (RECORD if subs else VAR)
        obj.lines.update(parametername=_line(el), objecttype=_line(el))
        if el.get("subNumber") is not None:  # on a VAR too, for the objects rules to report
            obj.sub_number = self._decimal(el, "subNumber", index, None)
            obj.sub_number_line = obj.lines["subnumber"] = _line(el)
        if obj.is_var:
            self._single_value(obj, el, param, subs)
        else:
            self._container(obj, el, param, subs)
        self.od.objects[index] = obj

    def _single_value(self, obj: Obj, el: etree._Element, param: etree._Element | None,
                      subs: list[etree._Element]) -> None:
        if subs:
            count = f"its {len(subs)} sub-objects are" if len(subs) > 1 else "its sub-object is"
            self.report(XML011, subs[0], "", f"is a single-value object (objectType {obj.object_code}); "
                        f"{count} ignored", obj.index)
        sub = Sub(subindex=0, name=obj.name, line=obj.line)
        sub.lines.update(obj.lines)
        self._entry(sub, el, param, obj.index, None)
        self._extra(el, sub.extra)  # unknown keys of a VAR live on its value, as in the EDS reader
        self._properties(obj, sub, param)
        obj.storage = sub.storage
        obj.subs[0] = sub

    def _container(self, obj: Obj, el: etree._Element, param: etree._Element | None,
                   subs: list[etree._Element]) -> None:
        if obj.object_code in (ARRAY, RECORD, DEFSTRUCT):
            self._ignored_values(el, param, obj)
        obj.obj_flags = self._obj_flags(el, obj.index, None)
        self._extra(el, obj.extra)
        self._properties(obj, None, param)
        for sub_el in subs:
            self._sub(obj, sub_el)

    def _sub(self, obj: Obj, el: etree._Element) -> None:
        subindex = self._address(el, "subIndex", obj.index)
        if subindex is None:
            return
        first = obj.subs.get(subindex)
        if first is not None:
            self.report(XML007, el, "subIndex",
                        f"is described again; the sub-object of line {first.line} is kept", obj.index, subindex)
            return
        self.subjects[_line(el)] = (obj.index, subindex)
        param = self._parameter(el, obj.index, subindex)
        sub = Sub(subindex=subindex, name=self._name(el, param), line=_line(el))
        sub.object_type = self._object_type(el, obj.index, subindex)
        sub.lines.update(parametername=_line(el), objecttype=_line(el))
        self._entry(sub, el, param, obj.index, subindex)
        self._extra(el, sub.extra)
        self._properties(None, sub, param)
        obj.subs[subindex] = sub

    def _name(self, el: etree._Element, param: etree._Element | None) -> str:
        """The name attribute (required); a missing one is taken from the parameter's label."""
        name = el.get("name")
        return name if name is not None else _label(param) or ""

    def _parameter(self, el: etree._Element, index: int, sub: int | None) -> etree._Element | None:
        ref = el.get("uniqueIDRef")
        if ref is None:
            return None
        param = self.params.get(ref.strip())
        if param is None:
            self.report(XML008, el, "uniqueIDRef", f"has uniqueIDRef '{ref}', which names no parameter", index, sub)
        return param

    def _ignored_values(self, el: etree._Element, param: etree._Element | None, obj: Obj) -> None:
        written = [a for a in CONTAINER_IGNORED if el.get(a) is not None]
        written += [f"parameter {c}" for c in ("defaultValue", "actualValue", "denotation")
                    if _child(param, c) is not None]
        if written:
            verb = "are" if len(written) > 1 else "is"
            code = OBJECT_CODES[obj.object_code]
            self.report(XML013, el, "", f"is {'an' if code[0] == 'A' else 'a'} {code}: {', '.join(written)} on the "
                        f"object {verb} ignored; values belong on the sub-objects", obj.index)

    # -- one value entry (a VAR object or a sub-object) -------------------------------

    def _entry(self, sub: Sub, el: etree._Element, param: etree._Element | None,
               index: int, subindex: int | None) -> None:
        where = (index, subindex)
        sub.data_type = self._data_type(sub, el, param, where)
        pdo = self._pdo_word(el, where)
        sub.pdo_mapping = pdo in ("default", "optional", "TPDO", "RPDO")
        if pdo is not None:
            sub.lines["pdomapping"] = _line(el)
        sub.access = self._access(sub, el, param, where)
        if sub.access == "rw" and pdo in ("TPDO", "RPDO"):
            sub.access = "rwr" if pdo == "TPDO" else "rww"
        if pdo in ("TPDO", "RPDO") and sub.access not in _IMPLIES[pdo]:
            sub.extra["pdomapping"] = Field("PDOmapping", pdo, _line(el))  # a direction the access does not say
        dtype = lookup(sub.data_type)
        sub.default = self._value(sub, "defaultvalue", dtype, where, el.get("defaultValue"), el,
                                  self._param_value(param, "defaultValue"))
        low, high = self._param_range(param)
        sub.low = self._value(sub, "lowlimit", dtype, where, el.get("lowLimit"), el, low)
        sub.high = self._value(sub, "highlimit", dtype, where, el.get("highLimit"), el, high)
        sub.parameter_value = self._value(sub, "parametervalue", dtype, where, el.get("actualValue"), el,
                                          self._param_value(param, "actualValue"))
        sub.denotation = self._denotation(sub, el, param, where)
        sub.obj_flags = self._obj_flags(el, index, subindex)
        if sub.obj_flags is not None:
            sub.lines["objflags"] = _line(el)

    def _data_type(self, sub: Sub, el: etree._Element, param: etree._Element | None,
                   where: tuple[int, int | None]) -> int | None:
        written = self._hex(el, "dataType", where) if el.get("dataType") is not None else None
        iec = self._iec_type(param)
        if el.get("dataType") is not None:
            sub.lines["datatype"] = _line(el)  # also when unreadable: that is reported, not "missing"
        if written is not None:
            if iec is not None and not _compatible(written, iec[0]):
                self.report(XML009, el, "dataType", f"has dataType 0x{written:04X} but its parameter "
                            f"(line {_line(iec[1])}) declares {etree.QName(iec[1]).localname}; "
                            f"0x{written:04X} is used", *where)
            return written
        if iec is None:
            return None
        sub.lines["datatype"] = _line(iec[1])
        code = IEC_TYPES[etree.QName(iec[1]).localname]
        if code == OCTET_STRING and el.get("defaultValue") is None and _child(param, "defaultValue") is None:
            return DOMAIN_TYPE
        return code

    def _iec_type(self, param: etree._Element | None) -> tuple[str, etree._Element] | None:
        for child in [] if param is None else param.iterchildren(*(q(n) for n in IEC_TYPES)):
            return etree.QName(child).localname, child
        return None

    def _access(self, sub: Sub, el: etree._Element, param: etree._Element | None,
                where: tuple[int, int | None]) -> str | None:
        written = self._access_word(el, where) if el.get("accessType") is not None else None
        declared = self._parameter_access(param, where) if param is not None else None
        if written is None:
            if declared is not None:
                sub.lines["accesstype"] = declared.line
                return declared.text or None
            # a parameter without access is "read" (schema default); unreadable stays unset
            return "ro" if param is not None and el.get("accessType") is None else None
        sub.lines["accesstype"] = _line(el)
        if declared is None or not declared.text or declared.text == written:
            return written
        if written == "rw" and declared.text in ("rwr", "rww"):
            return declared.text  # the parameter says which PDO direction the rw entry takes
        self.report(XML009, el, "accessType", f"has accessType '{el.get('accessType')}' but its "
                    f"parameter (line {declared.line}) says access '{_ACCESS_NAME.get(declared.text, declared.text)}'; "
                    f"'{written}' is used", *where)
        return written

    def _parameter_access(self, param: etree._Element, where: tuple[int, int | None]) -> _Found | None:
        """The EDS word for a parameter's explicit access ('' for noAccess or unreadable)."""
        text = param.get("access")
        if text is None:
            return None
        word = _word(text, PARAMETER_ACCESS)
        if word is None:  # kept as written; the objects rules report an invalid AccessType
            return _Found(text.strip().lower(), _line(param))
        if word != text:
            self.report(XML012, param, "access", f"has parameter access '{text}'; CiA 311 writes '{word}'", *where)
        return _Found(PARAMETER_ACCESS[word] or "", _line(param))

    def _access_word(self, el: etree._Element, where: tuple[int, int | None]) -> str | None:
        text = el.get("accessType", "")
        word = text.strip().lower()
        if word in ACCESS_WORDS:
            if word != text:
                self.report(XML012, el, "accessType", f"has accessType '{text}'; CiA 311 writes '{word}'", *where)
            return word
        if word in ("rwr", "rww"):
            pdo = "TPDO" if word == "rwr" else "RPDO"
            self.report(XML012, el, "accessType", f"has accessType '{text}', an EDS word; CiA 311 writes "
                        f"accessType=\"rw\" with PDOmapping=\"{pdo}\"", *where)
            return word
        return word or None  # kept as written; the objects rules report an invalid AccessType

    def _pdo_word(self, el: etree._Element, where: tuple[int, int | None]) -> str | None:
        text = el.get("PDOmapping")
        if text is None:
            return None
        word = _word(text, PDO_WORDS)
        if word is None and text.strip().lower() in ("0", "1", "false", "true"):
            word = "optional" if text.strip().lower() in ("1", "true") else "no"
        if word is None:
            self.report(XML005, el, "PDOmapping", f"has PDOmapping '{text}', which is not one of "
                        f"{', '.join(PDO_WORDS)}", *where)
            return None
        if word != text:
            self.report(XML012, el, "PDOmapping", f"has PDOmapping '{text}'; CiA 311 writes '{word}'", *where)
        return word

    def _value(self, sub: Sub, keyword: str, dtype: DataType | None, where: tuple[int, int | None], text: str | None,
               el: etree._Element, declared: _Found | None) -> Value | None:
        found = _Found(text, _line(el)) if text is not None else declared
        if found is None:
            return None
        if text is not None and declared is not None and not _same_value(text, declared.text, dtype):
            self.report(XML009, el, keyword, f"has {_ATTRIBUTE_OF[keyword]} '{text}' but its parameter "
                        f"(line {declared.line}) says '{declared.text}'; '{text}' is used", *where)
        sub.lines[keyword] = found.line
        return parse_value(found.text, dtype, found.line)

    def _param_value(self, param: etree._Element | None, name: str) -> _Found | None:
        el = _child(param, name)
        if el is None or el.get("value") is None:
            return None
        return _Found(el.get("value", ""), _line(el))

    def _param_range(self, param: etree._Element | None) -> tuple[_Found | None, _Found | None]:
        """LowLimit/HighLimit as CANopenEditor writes them: allowedValues/range min/max."""
        rng = _child(_child(param, "allowedValues"), "range")
        return _bound(_child(rng, "minValue")), _bound(_child(rng, "maxValue"))

    def _denotation(self, sub: Sub, el: etree._Element, param: etree._Element | None,
                    where: tuple[int, int | None]) -> str | None:
        text = el.get("denotation")
        den = _child(param, "denotation")
        declared = _label(den)
        if text is not None:
            sub.lines["denotation"] = _line(el)
            if declared is not None and text != declared:
                self.report(XML009, el, "denotation", f"has denotation '{text}' but its parameter "
                            f"(line {_line(den)}) says '{declared}'; '{text}' is used", *where)
            return text
        if declared is not None:
            sub.lines["denotation"] = _line(den)
        return declared

    def _properties(self, obj: Obj | None, sub: Sub | None, param: etree._Element | None) -> None:
        """CANopenEditor's <property name="CO_..." value="..."/> on the entry's parameter."""
        for prop in _children(param, "property"):
            name, value, line = prop.get("name", ""), prop.get("value", ""), _line(prop)
            key = name.lower()
            if key == "co_storagegroup":
                for target in (obj, sub):
                    if target is not None:
                        target.storage = value
                        target.lines["storagelocation"] = line
            elif key == "co_countlabel" and obj is not None:
                obj.count_label = value
                obj.lines["countlabel"] = line
            elif sub is not None:  # of a sub-object, or of a VAR, whose keys the EDS reader keeps on subs[0]
                sub.extra[key] = Field(name, value, line)
            elif obj is not None:
                obj.extra[key] = Field(name, value, line)

    def _extra(self, el: etree._Element, extra: dict[str, Field]) -> None:
        """Attributes odgen does not interpret, kept as written."""
        for attr, value in el.attrib.items():
            name = etree.QName(attr).localname
            if name not in ENTRY_ATTRIBUTES:
                extra[name.lower()] = Field(name, str(value), _line(el))

    # -- attribute readers ---------------------------------------------------------

    def _address(self, el: etree._Element, attr: str, index: int | None) -> int | None:
        """index or subIndex; the element is skipped (reported) when it is missing or unreadable."""
        tag, text = etree.QName(el).localname, el.get(attr)
        limit = 0xFFFF if attr == "index" else 0xFE
        number = _hex_number(text) if text is not None else None
        if number is None or number > limit:
            why = "no " + attr if text is None else f"{attr} '{text}', which is not a hex number up to 0x{limit:X}"
            self.report(XML005, el, attr, f"{tag} has {why}; it is skipped", index)
            return None
        self._hex_form(el, attr, (number, None) if attr == "index" else (index, number))
        return number

    def _hex(self, el: etree._Element, attr: str, where: tuple[int, int | None]) -> int | None:
        """dataType or objFlags; None (reported) when unreadable."""
        text = el.get(attr, "")
        number = _hex_number(text)
        if number is None:
            self.report(XML005, el, attr, f"has {attr} '{text}', which is not a hex number", *where)
            return None
        self._hex_form(el, attr, where)
        return number

    def _hex_form(self, el: etree._Element, attr: str, where: tuple[int | None, int | None]) -> None:
        text = el.get(attr, "")
        form, example = HEX_FORMS[attr]
        if not re.fullmatch(form, text):
            self.report(XML012, el, attr, f"has {attr} '{text}'; CiA 311 writes hex digits without 0x, "
                        f"as in '{example}'", *where)

    def _object_type(self, el: etree._Element, index: int, sub: int | None) -> int | None:
        text = el.get("objectType")
        if text is None:
            return None  # required: the schema reports it
        number = _integer(text)
        name = OBJECT_CODE_NAMES.get(text.strip().upper())
        if number is not None and text.strip().isdigit():
            return number
        if number is None and name is None:
            self.report(XML005, el, "objectType", f"has objectType '{text}', which is not an object code", index, sub)
            return None
        code = number if number is not None else name
        self.report(XML012, el, "objectType", f"has objectType '{text}'; CiA 311 writes the decimal code "
                    f"'{code}'", index, sub)
        return code

    def _decimal(self, el: etree._Element, attr: str, index: int, sub: int | None) -> int | None:
        text = el.get(attr, "")
        number = _integer(text)
        if number is None:
            self.report(XML005, el, attr, f"has {attr} '{text}', which is not a number", index, sub)
        elif not text.strip().isdigit():
            self.report(XML012, el, attr, f"has {attr} '{text}'; CiA 311 writes it in decimal", index, sub)
        return number

    def _obj_flags(self, el: etree._Element, index: int, sub: int | None) -> int | None:
        if el.get("objFlags") is None:
            return None
        return self._hex(el, "objFlags", (index, sub))


def _bound(el: etree._Element | None) -> _Found | None:
    if el is None or el.get("value") is None:
        return None
    return _Found(el.get("value", ""), _line(el))


def _hex_number(text: str) -> int | None:
    match = re.fullmatch(r"\s*(?:0[xX])?([0-9A-Fa-f]+)\s*", text)
    return bounded_int(match.group(1), 16) if match else None


# Access words that already imply a PDO direction: read-only entries go to TPDOs, write-only to RPDOs.
_IMPLIES = {"TPDO": ("ro", "const", "rwr"), "RPDO": ("wo", "rww")}
_ACCESS_NAME = {eds: xdd for xdd, eds in PARAMETER_ACCESS.items() if eds}
_ATTRIBUTE_OF = {"defaultvalue": "defaultValue", "lowlimit": "lowLimit", "highlimit": "highLimit",
                 "parametervalue": "actualValue"}


def _integer(text: str) -> int | None:
    """A decimal or 0x-hex integer; leading zeros are decimal here (XML, not CiA 306)."""
    match = re.fullmatch(r"\s*(?:0[xX]([0-9A-Fa-f]+)|(\d+))\s*", text)
    if match is None:
        return None
    return bounded_int(match.group(1), 16) if match.group(1) else bounded_int(match.group(2))


def _word(text: str, words) -> str | None:
    """The word of `words` matching `text`, ignoring case and surrounding space."""
    wanted = text.strip().lower()
    return next((w for w in words if w.lower() == wanted), None)


def _compatible(code: int, iec: str) -> bool:
    """Whether a CiA 301 data type code can be declared as IEC type `iec`."""
    if code not in BASIC_TYPES:
        return True  # a complex or custom type: nothing to compare with
    if iec == "BITSTRING":
        return code in BITSTRING_CODES
    return IEC_TYPES[iec] == code


def _same_access(written: str, declared: str) -> bool:
    return written == declared or (written == "rw" and declared in ("rwr", "rww"))


def _same_value(a: str, b: str, dtype: DataType | None) -> bool:
    if a.strip() == b.strip():
        return True
    pa, pb = parse_value(a, dtype), parse_value(b, dtype)
    return pa.error is None and pb.error is None and (pa.parsed, pa.nodeid) == (pb.parsed, pb.nodeid) \
        and pa.parsed is not None


# -- schema validation ------------------------------------------------------------

_VALUE_ERROR = re.compile(r"is not a valid value|\[facet|is not accepted by the pattern|not an element of the set")
_ELEMENT_ATTR = re.compile(r"^Element '([^']+)'(?:, attribute '([^']+)')?: (.*)$", re.S)
_NAMESPACED = re.compile(r"\{[^}\s']*\}")  # {namespace}name, not an enumeration set
_MISSING = re.compile(r"The attribute '([^']+)' is required but missing")


def _validate(doc: etree._Element, source: str, diags: Diagnostics, reader: _Reader) -> None:
    """Report schema violations, once per distinct message, dropping what the reader reported."""
    schema = etree.XMLSchema(etree.parse(str(schema_path())))
    if schema.validate(doc):
        return
    groups: dict[str, list[int]] = {}
    for err in cast(Iterable[Any], schema.error_log):
        message = _NAMESPACED.sub("", err.message).strip()
        match = _ELEMENT_ATTR.match(message)
        element, attr = (match.group(1), match.group(2) or "") if match else ("", "")
        missing = _MISSING.search(message)
        attr = missing.group(1) if missing and not attr else attr
        if (err.line, attr) in reader.reported:
            continue
        if (element, attr) in READER_OWNED and _VALUE_ERROR.search(message):
            continue
        if missing and attr == "name" and element in ("CANopenObject", "CANopenSubObject"):
            continue  # the objects rules report a missing name (OBJ001) for every format
        groups.setdefault(_schema_message(message), []).append(err.line)
    for message, lines in groups.items():
        index, sub = reader.subjects.get(lines[0], (None, None))
        more = f" (and on {len(lines) - 1} more line{'s' if len(lines) > 2 else ''})" if len(lines) > 1 else ""
        diags.add(XML004, Loc(source, lines[0]), message + more, index, sub)


def _schema_message(message: str) -> str:
    """libxml2's wording, shortened to read after an object address."""
    match = _ELEMENT_ATTR.match(message)
    if match is None:
        return message
    element, attr, rest = match.groups()
    rest = rest.rstrip(".")
    missing = re.fullmatch(r"The attribute '([^']+)' is required but missing", rest)
    if missing:
        return f"{element} lacks the required attribute '{missing.group(1)}'"
    if attr and rest == f"The attribute '{attr}' is not allowed":
        return f"{element} has attribute '{attr}', which CiA 311 does not define there"
    if rest.startswith("This element is not expected"):
        return f"{element} is not expected here" + rest[len("This element is not expected"):].replace(
            ". Expected is", "; expected").replace(" ( ", " ").replace(" )", "")
    if attr:
        for pattern, wording in _VALUE_WORDING:
            value = re.search(pattern, rest)
            if value:
                return f"{element} {attr} '{value.group(1)}' {wording.format(*value.groups()[1:])}"
        return f"{element} attribute '{attr}': {rest}"
    return f"{element}: {rest}"


_VALUE_WORDING = (
    (r"The value '(.*)' is not an element of the set \{(.*)\}$", "is not one of {0}"),
    (r"The value '(.*)' is not accepted by the pattern '(.*)'$", "does not match the pattern '{0}'"),
    (r"^'(.*)' is not a valid value of the (?:atomic|local atomic) type '?([^']*)'?$", "is not a valid {0}"),
)
