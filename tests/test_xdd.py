"""XDD/XDC (CiA 311) reader: XML rules, the XDD -> model mapping, safety, the corpus, EDS twins."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from odgen.diagnostics import RULES, Diagnostics, Severity
from odgen.formats import load_path
from odgen.assets import schema_path
from odgen.formats.xdd import load_xdd
from odgen.model import Obj, ObjectDictionary, Sub, Value

from .conftest import FIXTURES, expectations, lint, rendered

XDD = FIXTURES / "xdd"
CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus" / "files"
XML_SUFFIXES = (".xdd", ".xpd", ".xdc")


def load(text: str | bytes, source: str = "t.xdd") -> tuple[ObjectDictionary | None, Diagnostics]:
    diags = Diagnostics()
    data = text.encode("utf-8") if isinstance(text, str) else text
    return load_xdd(data, source, diags), diags


def rules_of(diags: Diagnostics) -> list[str]:
    return [d.rule for d in diags]


def document(objects: str, parameters: str = "", network: str = "") -> str:
    """A minimal CiA 311 document with the given CANopenObject and parameter elements."""
    process = f"<ApplicationProcess><parameterList>{parameters}</parameterList></ApplicationProcess>"
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        '<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1">\n'
        f"<ISO15745Profile><ProfileHeader/><ProfileBody>{process if parameters else ''}</ProfileBody>"
        "</ISO15745Profile>\n"
        "<ISO15745Profile><ProfileHeader/><ProfileBody>\n"
        f"<ApplicationLayers><CANopenObjectList>\n{objects}\n</CANopenObjectList></ApplicationLayers>\n"
        f"{network}</ProfileBody></ISO15745Profile>\n"
        "</ISO15745ProfileContainer>\n"
    )


# -- one failing fixture per rule ------------------------------------------------


@pytest.mark.parametrize("fixture", sorted(XDD.glob("XML*.xdd")), ids=lambda p: p.stem)
def test_fixture_reports_its_rule(fixture: Path) -> None:
    wanted = expectations(fixture)
    assert wanted, f"{fixture.name} has no '<!-- expect: -->' line"
    got = rendered(lint(fixture))
    for line in wanted:
        assert line in got, f"{fixture.name}: expected {line!r}, got {got}"
    assert all(f"[{fixture.stem}]" in w for w in wanted)
    assert [g for g in got if "[XML" in g] == wanted, "no other XML diagnostic than the expected ones"


def test_every_xml_rule_has_a_fixture() -> None:
    have = {p.stem for p in XDD.glob("XML*.xdd")}
    assert {r for r in RULES if r.startswith("XML")} == have


def test_rule_texts_are_documentation() -> None:
    for rule in (r for r in RULES.values() if r.id.startswith("XML")):
        assert rule.title and rule.why and rule.example and rule.fix and rule.ref.startswith(("CiA", "XML"))


# -- the passing fixtures and the mapping ----------------------------------------------


def test_valid_fixture_is_clean() -> None:
    result = lint(XDD / "valid.xdd")
    assert result.od is not None
    assert [d.text() for d in result.diagnostics if d.rule.startswith(("XML", "SYN"))] == []
    assert result.count(Severity.ERROR) == 0, rendered(result)


def test_valid_fixture_model() -> None:
    od, diags = load_path(XDD / "valid.xdd")
    assert od is not None and od.format == "xdd" and od.node_id is None and not list(diags)
    assert sorted(od.objects) == [0x1000, 0x1001, 0x1017, 0x1018, 0x2000, 0x6000, 0x6200]

    device = od.objects[0x1000]
    var = device.subs[0]
    assert (device.name, device.object_code, list(device.subs)) == ("Device type", 7, [0])
    assert (var.name, var.data_type, var.access, var.pdo_mapping) == ("Device type", 7, "ro", False)
    assert var.default is not None and var.default.parsed == 0x30191 and var.default.line == 65
    assert device.line == var.line == 65

    assert od.objects[0x1001].subs[0].pdo_mapping and "pdomapping" not in od.objects[0x1001].subs[0].extra

    identity = od.objects[0x1018]
    assert (identity.object_code, identity.sub_number, sorted(identity.subs)) == (9, 5, [0, 1, 2, 3, 4])
    assert identity.subs[0].access == "const" and identity.subs[1].object_type == 7
    assert identity.subs[1].line == 70 and identity.subs[1].default.parsed == 0x123


def test_values_from_the_referenced_parameter() -> None:
    od, _ = load_path(XDD / "valid.xdd")
    speed = od.objects[0x2000]
    sub = speed.subs[0]
    # UINT -> UNSIGNED16; readWriteOutput (written by RPDO) -> rww; range -> limits
    assert (sub.data_type, sub.access, sub.pdo_mapping, sub.extra) == (6, "rww", True, {})
    assert (sub.default.parsed, sub.low.parsed, sub.high.parsed) == (100, 0, 3000)
    assert (sub.default.line, sub.low.line, sub.high.line) == (35, 38, 39)
    assert sub.lines["defaultvalue"] == 35 and sub.lines["accesstype"] == 32 and sub.lines["datatype"] == 34
    assert (speed.storage, sub.storage, speed.count_label) == ("PERSIST_APP", "PERSIST_APP", "SPEED")
    assert speed.lines["storagelocation"] == 42 and speed.lines["countlabel"] == 43


def test_pdo_direction_and_flags() -> None:
    od, _ = load_path(XDD / "valid.xdd")
    inputs = od.objects[0x6000].subs[1]
    assert (inputs.access, inputs.pdo_mapping, inputs.extra, inputs.obj_flags) == ("ro", True, {}, 1)
    outputs = od.objects[0x6200].subs[1]
    assert (outputs.access, outputs.pdo_mapping, outputs.extra) == ("rww", True, {})


@pytest.mark.parametrize("access,pdo,kept", [
    ("ro", "TPDO", False), ("rw", "TPDO", False), ("wo", "RPDO", False), ("rw", "RPDO", False),
    ("ro", "RPDO", True), ("wo", "TPDO", True), ("const", "RPDO", True),
])
def test_pdo_direction_word_is_kept_when_access_does_not_say_it(access: str, pdo: str, kept: bool) -> None:
    obj = (f'<CANopenObject index="2000" name="x" objectType="7" dataType="0005" accessType="{access}" '
           f'PDOmapping="{pdo}"/>')
    od, _ = load(document(obj))
    extra = od.objects[0x2000].subs[0].extra
    word = extra["pdomapping"].text if "pdomapping" in extra else None
    assert word == (pdo if kept else None)


def test_header_sections() -> None:
    od, _ = load_path(XDD / "valid.xdd")
    info = od.section("DeviceInfo")
    assert {k: info.text(k) for k in ("VendorName", "VendorNumber", "ProductName", "ProductNumber",
                                      "OrderCode")} == {
        "VendorName": "odgen", "VendorNumber": "0x00000123", "ProductName": "Test node",
        "ProductNumber": "0x00000042", "OrderCode": "T-42"}
    rates = {k: info.text(f"BaudRate_{k}") for k in (10, 20, 50, 125, 250, 500, 800, 1000)}
    assert rates == {10: "0", 20: "0", 50: "0", 125: "1", 250: "1", 500: "1", 800: "0", 1000: "0"}
    assert (info.text("Granularity"), info.text("LSS_Supported"), info.text("NrOfRXPDO")) == ("8", "1", "0")
    files = od.section("FileInfo")
    assert {k: files.text(k) for k in ("FileName", "FileVersion", "CreatedBy", "CreationDate",
                                       "CreationTime", "Description")} == {
        "FileName": "valid.xdd", "FileVersion": "2", "CreatedBy": "odgen tests",
        "CreationDate": "03-05-2024", "CreationTime": "02:07PM",
        "Description": "A node for the XDD reader tests."}
    dummies = od.section("DummyUsage")
    assert (dummies.text("Dummy0001"), dummies.text("Dummy0005")) == ("0", "1")
    assert od.section("DeviceComissioning") is None


def test_editor_style_xdc() -> None:
    """CANopenEditor's layout: unqualified elements, values only in parameters, CO_* properties."""
    result = lint(XDD / "editor-style.xdc")
    assert [d.text() for d in result.diagnostics if d.rule.startswith(("XML", "SYN"))] == []
    od = result.od
    assert od is not None and od.format == "xdc" and od.node_id == 5
    commissioning = od.section("DeviceComissioning")
    assert {f.key: f.text for f in commissioning.fields.values()} == {
        "NodeID": "5", "NodeName": "node5", "Baudrate": "250", "NetNumber": "1", "NetworkName": "bench",
        "CANopenManager": "0"}
    files = od.section("FileInfo")
    assert (files.text("CreationTime"), files.text("ModificationDate"), files.text("ModificationTime"),
            files.text("ModifiedBy")) == ("12:30AM", "12-31-2024", "11:59PM", "someone")

    device = od.objects[0x1000]
    assert (device.storage, device.count_label, device.subs[0].data_type) == ("PERSIST_COMM", "NMT", 7)
    assert device.subs[0].access == "ro"  # a parameter without access is "read"
    heartbeat = od.objects[0x1017].subs[0]
    assert (heartbeat.access, heartbeat.default.parsed, heartbeat.parameter_value.parsed) == ("rw", 0, 500)
    assert heartbeat.denotation == "Heartbeat of node 5" and heartbeat.lines["parametervalue"] == 46
    name = od.objects[0x1008].subs[0]
    assert (name.data_type, name.access, name.default.parsed) == (9, "const", "odgen node")
    log = od.objects[0x2100]
    assert log.subs[0].data_type == 0x0F  # BITSTRING without a default value: DOMAIN
    assert log.subs[0].extra["co_disabled"].text == "true"  # a VAR's keys live on its value
    outputs = od.objects[0x6200]
    assert outputs.extra["co_flagspdo"].text == "true" and outputs.sub_number == 2
    out1 = outputs.subs[1]
    assert (out1.access, out1.parameter_value.parsed, out1.extra["co_accesssrdo"].text) == ("rww", 15, "rx")


@pytest.mark.parametrize("written,declared,pdo,expected", [
    ('accessType="ro"', None, "no", "ro"),
    ('accessType="const"', None, "no", "const"),
    ('accessType="wo"', None, "RPDO", "wo"),
    ('accessType="rw"', None, "optional", "rw"),
    ('accessType="rw"', None, "TPDO", "rwr"),  # CiA 311 spells EDS rwr as rw + TPDO
    ('accessType="rw"', None, "RPDO", "rww"),  # and EDS rww as rw + RPDO
    (None, "read", "no", "ro"),
    (None, "write", "no", "wo"),
    (None, "readWrite", "no", "rw"),
    (None, "readWrite", "TPDO", "rwr"),
    (None, "readWriteInput", "optional", "rwr"),  # process input, read by a TPDO
    (None, "readWriteOutput", "optional", "rww"),  # process output, written by an RPDO
    (None, "const", "no", "const"),
    (None, "", "no", "ro"),  # a parameter without access: the schema default "read"
    ('accessType="rw"', "readWriteOutput", "no", "rww"),  # the parameter refines rw
])
def test_access_mapping(written: str | None, declared: str | None, pdo: str, expected: str) -> None:
    ref = ' uniqueIDRef="P"' if declared is not None else ""
    access = f' access="{declared}"' if declared else ""
    param = f'<parameter uniqueID="P"{access}><label lang="en">x</label><UINT/></parameter>' if ref else ""
    obj = (f'<CANopenObject index="2000" name="x" objectType="7" dataType="0006" {written or ""} '
           f'PDOmapping="{pdo}"{ref}/>')
    od, diags = load(document(obj, param))
    assert not list(diags) and od is not None
    assert od.objects[0x2000].subs[0].access == expected


@pytest.mark.parametrize("namespace", ["http://www.canopen.org/xml/1.0", None])
def test_namespace_variants_give_the_same_model(namespace: str | None) -> None:
    text = (XDD / "valid.xdd").read_text(encoding="utf-8")
    reference, _ = load(text, "valid.xdd")
    old = ' xmlns="http://www.canopen.org/xml/1.1"'
    variant = text.replace(old, f' xmlns="{namespace}"' if namespace else "")
    od, diags = load(variant, "valid.xdd")
    assert od is not None and reference is not None
    assert od.objects == reference.objects and od.sections == reference.sections
    expected = [] if namespace else ["XML004"]  # an unqualified root is read, and reported
    assert rules_of(diags) == expected


def test_format_from_content_then_suffix() -> None:
    commissioning = ('<NetworkManagement><CANopenGeneralFeatures granularity="8"/>'
                     '<deviceCommissioning NodeID="3"/></NetworkManagement>')
    obj = '<CANopenObject index="1000" name="Device type" objectType="7" dataType="0007" accessType="ro"/>'
    assert load(document(obj), "a.xdd")[0].format == "xdd"
    assert load(document(obj), "a.xdc")[0].format == "xdc"
    configured, _ = load(document(obj, network=commissioning), "a.xdd")
    assert configured.format == "xdc" and configured.node_id == 3


def test_schema_validates_a_plain_file_as_it_is() -> None:
    schema = etree.XMLSchema(etree.parse(str(schema_path())))
    assert schema.validate(etree.parse(str(XDD / "valid.xdd"))), schema.error_log


def test_repeated_schema_errors_are_reported_once() -> None:
    subs = "\n".join(f'<CANopenSubObject subIndex="{i:02X}" name="s" objectType="7" dataType="0005" '
                     f'accessType="ro" bogus="1"/>' for i in range(3))
    obj = f'<CANopenObject index="2000" name="x" objectType="8" subNumber="3">\n{subs}\n</CANopenObject>'
    _, diags = load(document(obj))
    texts = [d.text() for d in diags]
    assert texts == ["t.xdd:7: error[XML004]: 0x2000sub0 CANopenSubObject has attribute 'bogus', which CiA 311 "
                     "does not define there (and on 2 more lines)"]


# -- never raise, never expand ------------------------------------------------------------


@pytest.mark.parametrize("use,rule", [
    ("<vendorName>&xxe;</vendorName>", "XML003"),  # in text: parsed unexpanded, then refused
    ('<vendorName x="&xxe;"/>', "XML001"),  # in an attribute: libxml2 refuses it while parsing
])
def test_xxe_is_not_read(use: str, rule: str) -> None:
    text = ('<?xml version="1.0"?>\n<!DOCTYPE ISO15745ProfileContainer [\n'
            '<!ENTITY xxe SYSTEM "file:///etc/passwd">\n]>\n'
            '<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1"><ISO15745Profile>'
            f"<ProfileHeader/><ProfileBody><DeviceIdentity>{use}</DeviceIdentity>"
            "</ProfileBody></ISO15745Profile></ISO15745ProfileContainer>")
    od, diags = load(text)
    assert od is None and rules_of(diags) == [rule]
    assert all("root:" not in d.message for d in diags)


def test_billion_laughs_is_refused() -> None:
    entities = ['<!ENTITY lol0 "lol">'] + [
        f'<!ENTITY lol{i} "{f"&lol{i - 1};" * 10}">' for i in range(1, 10)]
    text = ('<?xml version="1.0"?>\n<!DOCTYPE ISO15745ProfileContainer [\n' + "\n".join(entities) + "\n]>\n"
            '<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1" a="&lol9;">&lol9;'
            "</ISO15745ProfileContainer>\n")
    od, diags = load(text)
    assert od is None and rules_of(diags) in (["XML001"], ["XML003"])


def test_external_dtd_is_not_fetched() -> None:
    text = ('<?xml version="1.0"?>\n<!DOCTYPE ISO15745ProfileContainer SYSTEM "http://192.0.2.1/x.dtd">\n'
            '<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1"/>\n')
    od, diags = load(text)
    assert od is None and rules_of(diags) == ["XML003"]


@pytest.mark.parametrize("data", [
    b"", b"\x00\xff\xfe", b"<", b"not xml at all", b"\xef\xbb\xbf", "<a>caf\u00e9</a>".encode("latin-1"),
    '<?xml version="1.0" encoding="utf-16"?><a/>'.encode("utf-16"),
    b'<?xml version="1.0"?><ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1"/>',
    b'<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1"><ISO15745Profile><ProfileBody>'
    b'<ApplicationLayers><CANopenObjectList><CANopenObject/><CANopenObject index="1000" objectType="x">'
    b'<CANopenSubObject subIndex="1FF"/></CANopenObject></CANopenObjectList></ApplicationLayers>'
    b"</ProfileBody></ISO15745Profile></ISO15745ProfileContainer>",
], ids=lambda d: repr(d[:20]))
def test_bad_input_never_raises(data: bytes) -> None:
    od, diags = load(data)
    assert od is not None or any(d.severity == Severity.ERROR for d in diags)
    assert all(d.rule in RULES and d.loc.line >= 0 for d in diags)


# -- the corpus ------------------------------------------------------------------------------


def corpus_xml_files() -> list:
    if not CORPUS.is_dir():
        return [pytest.param(None, marks=pytest.mark.skip(reason="../shared/corpus is absent"))]
    files = sorted(p for p in CORPUS.iterdir() if p.suffix.lower() in XML_SUFFIXES)
    return [pytest.param(p, id=p.name) for p in files]


@pytest.mark.parametrize("path", corpus_xml_files())
def test_corpus_file_loads(path: Path) -> None:
    od, diags = load_path(path)
    n_lines = len(path.read_bytes().splitlines())
    for d in diags:
        assert d.rule in RULES and 0 <= d.loc.line <= n_lines, d.text()
        if d.rule == "XML004":
            assert d.loc.line > 0 and d.message, d.text()
    if od is None:
        assert {d.rule for d in diags} & {"XML001", "XML002", "XML003"}, "a file not read must say why"
    else:
        assert od.format in ("xdd", "xdc") and od.objects
        assert all(obj.line > 0 and all(sub.line > 0 for sub in obj.subs.values()) for obj in od.objects.values())


# -- EDS twins ----------------------------------------------------------------------------------

# (xdd, eds) pairs in the corpus that describe the same device.
TWINS = [
    ("canopendemo__demoDevice.xdd", "canopendemo__demoDevice.eds"),
    ("canopensocket__CANopenSocket_v1.3.xdd", "canopensocket__CANopenSocket_v1.3.eds"),
    ("canopennode__DS301_profile.xpd", "canopennode__DS301_profile.eds"),
]
SAMPLE = ("pycanopen__sample.xdd", "pycanopen__sample.eds")

Difference = tuple[int, int | None, str]


def _value(value: Value | None) -> object:
    """A value as compared: an empty EDS `DefaultValue=` is no value, as an absent defaultValue, and
    strings without trailing blanks, which an INI reader cannot keep but an XML attribute does."""
    if value is None or value.empty:
        return None
    parsed = value.parsed.rstrip() if isinstance(value.parsed, str) else value.parsed
    return parsed, value.nodeid


def _sub_differences(index: int, a: Sub, b: Sub) -> set[Difference]:
    out: set[Difference] = set()
    for name in ("name", "data_type", "access", "pdo_mapping", "obj_flags", "denotation"):
        if getattr(a, name) != getattr(b, name):
            out.add((index, a.subindex, name))
    for name in ("default", "low", "high", "parameter_value"):
        if _value(getattr(a, name)) != _value(getattr(b, name)):
            out.add((index, a.subindex, name))
    # XDD sub-objects must state objectType, EDS sub-sections may omit it
    if None not in (a.object_type, b.object_type) and a.object_type != b.object_type:
        out.add((index, a.subindex, "object_type"))
    # CANopenEditor's EDS writes its default group (;StorageLocation=RAM) where the XDD states none
    if a.storage is not None and a.storage != b.storage:
        out.add((index, a.subindex, "storage"))
    return out


def _object_differences(a: Obj, b: Obj) -> set[Difference]:
    out: set[Difference] = set()
    for name in ("name", "object_code", "sub_number", "obj_flags"):
        if getattr(a, name) != getattr(b, name):
            out.add((a.index, None, name))
    if a.storage is not None and a.storage != b.storage:
        out.add((a.index, None, "storage"))
    # CANopenEditor's EDS export cannot carry CO_countLabel, so only a label the EDS has is compared
    if b.count_label is not None and a.count_label != b.count_label:
        out.add((a.index, None, "count_label"))
    for subindex in sorted(set(a.subs) | set(b.subs)):
        if subindex not in a.subs or subindex not in b.subs:
            out.add((a.index, subindex, "only in " + ("eds" if subindex in b.subs else "xdd")))
        else:
            out |= _sub_differences(a.index, a.subs[subindex], b.subs[subindex])
    return out


def disabled(obj: Obj) -> bool:
    holder = obj.subs[0].extra if obj.is_var and 0 in obj.subs else obj.extra
    return "co_disabled" in holder and holder["co_disabled"].text == "true"


def twin_differences(xdd: ObjectDictionary, eds: ObjectDictionary) -> set[Difference]:
    out: set[Difference] = set()
    for index in sorted(set(xdd.objects) | set(eds.objects)):
        a, b = xdd.objects.get(index), eds.objects.get(index)
        if a is None:
            out.add((index, None, "only in eds"))
        elif b is None:
            # CANopenEditor leaves objects with CO_disabled=true out of the EDS it exports
            if not disabled(a):
                out.add((index, None, "only in xdd"))
        else:
            out |= _object_differences(a, b)
    return out


def _load_twin(xdd_name: str, eds_name: str) -> tuple[ObjectDictionary, ObjectDictionary]:
    if not CORPUS.is_dir():
        pytest.skip("../shared/corpus is absent")
    xdd, _ = load_path(CORPUS / xdd_name)
    eds, _ = load_path(CORPUS / eds_name)
    assert xdd is not None and eds is not None
    return xdd, eds


@pytest.mark.parametrize("xdd_name,eds_name", TWINS, ids=[t[0] for t in TWINS])
def test_xdd_gives_the_model_of_its_eds_twin(xdd_name: str, eds_name: str) -> None:
    xdd, eds = _load_twin(xdd_name, eds_name)
    assert twin_differences(xdd, eds) == set()
    assert set(eds.objects) == {i for i, o in xdd.objects.items() if not disabled(o)}


def test_pycanopen_sample_differs_only_where_the_files_differ() -> None:
    """sample.xdd was converted from an older sample.eds by CANopenEditor and corrected by hand (its
    header comment says so); these are the differences in the files themselves, each checked by hand."""
    xdd, eds = _load_twin(*SAMPLE)
    expected: set[Difference] = {
        # SubNumber in the EDS counts sub-objects it leaves out "for testing"
        (0x1003, None, "sub_number"), (0x1018, None, "sub_number"), (0x3050, None, "sub_number"),
        # ParameterValue and a LowLimit written only in the EDS
        (0x1017, 0, "parameter_value"), (0x1018, 0, "parameter_value"), (0x1018, 1, "parameter_value"),
        (0x3002, 0, "parameter_value"), (0x3002, 0, "low"),
        # EDS DataType=0x40 (a DEFSTRUCT), which CANopenEditor turned into INTEGER32; its values then parse
        (0x2020, 0, "data_type"), (0x2020, 0, "default"), (0x2020, 0, "low"), (0x2020, 0, "high"),
        # "Fixed incorrect ReadRawValue object" and "Valve % open": different objects in the two files
        (0x3003, None, "object_code"), (0x3003, 0, "only in xdd"),
        (0x3010, 0, "data_type"), (0x3010, 0, "pdo_mapping"),
        # CompactSubObj in the EDS (no SubNumber, default on the object) vs written-out sub-objects
        (0x3004, None, "sub_number"), (0x3006, None, "sub_number"),
        (0x3004, 1, "default"), (0x3004, 2, "default"),
    }
    # CANopenEditor named the expanded 0x3006 elements with a hex suffix ("Valve 1 % Open0a")
    expected |= {(0x3006, sub, "name") for sub in range(1, 25)}
    assert twin_differences(xdd, eds) == expected
    assert (xdd.objects[0x3006].subs[10].name, eds.objects[0x3006].subs[10].name) == (
        "Valve 1 % Open0a", "Valve 1 % Open10")


@pytest.mark.parametrize("spelling", ["nodeID", "NodeID"])
def test_node_id_in_either_spelling(spelling: str) -> None:
    """CiA 311 spells the commissioning attribute `nodeID`; some tools write `NodeID`: both give the node-id."""
    objects = ('<CANopenObject index="1000" name="Device type" objectType="7" dataType="0007" accessType="ro" '
               'defaultValue="0"/>')
    network = f'<NetworkManagement><deviceCommissioning {spelling}="5" nodeName="n"/></NetworkManagement>'
    od, diags = load(document(objects, network=network), "t.xdc")
    assert od is not None and od.node_id == 5
    assert rules_of(diags) == []
    assert od.section("DeviceComissioning").text("NodeID") == "5"


def test_node_id_missing_is_reported() -> None:
    network = '<NetworkManagement><deviceCommissioning nodeName="n"/></NetworkManagement>'
    od, diags = load(document("", network=network), "t.xdc")
    assert od is not None and od.node_id is None
    assert "XML005" in rules_of(diags)
