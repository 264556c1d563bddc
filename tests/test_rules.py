"""HDR, LST, OBJ, PDO and COM rules: one failing fixture per rule, exact lines and messages.

Each `tests/fixtures/rules/<RULE>.eds` (or .dcf) is an otherwise lint-clean device
that breaks one rule; its `; expect:` lines are the complete list of diagnostics
it must produce. `clean.eds` is a complete, realistic device that must produce none.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.diagnostics import RULES, Diagnostics, Severity
from odgen.formats import load_path
from odgen.lint.driver import FileResult
from odgen.model import ARRAY, RECORD, Field, Obj, ObjectDictionary, Sub, parse_value
from odgen.model.datatypes import BY_NAME
from odgen.lint.passes import LintOptions, run_rules

from .conftest import CORPUS, FIXTURES, corpus_params, expectations, lint

RULE_FIXTURES = FIXTURES / "rules"
FAMILIES = ("HDR", "LST", "OBJ", "PDO", "COM")


def fixtures() -> list[Path]:
    return sorted(p for p in RULE_FIXTURES.iterdir() if p.stem.startswith(FAMILIES))


def rendered(result: FileResult) -> list[str]:
    """`LINE: severity[RULE]: message`, line 0 included (the file as a whole)."""
    out = []
    for d in result.diagnostics:
        text = d.text().removeprefix(f"{d.loc}: ")
        out.append(f"{d.loc.line}: {text}")
    return out


@pytest.mark.parametrize("fixture", fixtures(), ids=lambda p: p.stem)
def test_fixture_reports_exactly_its_rule(fixture: Path) -> None:
    wanted = expectations(fixture)
    assert wanted, f"{fixture.name} has no '; expect:' line"
    assert all(f"[{fixture.stem}]" in w for w in wanted)
    assert rendered(lint(fixture)) == wanted


def test_clean_device_has_no_diagnostics() -> None:
    result = lint(RULE_FIXTURES / "clean.eds")
    assert result.od is not None and len(result.od.objects) == 16
    assert rendered(result) == []


def test_every_rule_has_a_fixture() -> None:
    covered = {p.stem for p in fixtures()}
    defined = {r for r in RULES if r.startswith(FAMILIES)}
    assert defined == covered


@pytest.mark.parametrize("rule", sorted(r for r in RULES if r.startswith(FAMILIES)))
def test_rule_is_documented(rule: str) -> None:
    r = RULES[rule]
    assert r.title and r.why and r.example and r.fix and r.ref
    assert r.ref.startswith(("CiA 306", "CiA 301")), r.ref
    if "(verify)" in r.ref:
        assert r.severity < Severity.ERROR and "verify" in r.why


# -- options ------------------------------------------------------------------------

def test_can_fd_allows_512_bits() -> None:
    assert [d.rule for d in lint(RULE_FIXTURES / "PDO005.eds", can_fd=True).diagnostics] == []


def test_nodeid_values_checked_for_the_given_node_only() -> None:
    fixture = RULE_FIXTURES / "COM005.eds"  # TPDO5 at $NODEID+0x700
    assert [d.rule for d in lint(fixture).diagnostics] == ["COM005"]
    assert "0x701 for node-id 1" in lint(fixture).diagnostics[0].message
    assert "0x705" in lint(fixture, node_id=5).diagnostics[0].message


def _od(*subs: tuple[int, Sub], fmt: str = "xdd") -> ObjectDictionary:
    od = ObjectDictionary(source="model", format=fmt)
    for index, sub in subs:
        obj = od.objects.setdefault(index, Obj(index=index, name=f"Object {index:04X}"))
        obj.subs[sub.subindex] = sub
    return od


def _var(value: str, dtype: str, **limits: str) -> Sub:
    t = BY_NAME[dtype]
    sub = Sub(0, "Value", line=3, data_type=t.code, access="rw", default=parse_value(value, t, 4))
    for key, text in limits.items():
        setattr(sub, key, parse_value(text, t, 5))
    return sub


def _rules(od: ObjectDictionary, **options) -> list[str]:
    diags = Diagnostics()
    run_rules(od, diags, LintOptions(**options))
    return [f"{d.rule} {d.message}" for d in diags if d.rule.startswith(("OBJ", "PDO"))]


@pytest.mark.parametrize("value,node_id,found", [
    ("$NODEID+0x81", None, ["OBJ016 DefaultValue=$NODEID+0x81 (= 256 for node-id 127) is above the UNSIGNED8 "
                            "maximum 255"]),
    ("$NODEID+0x81", 1, []),
    ("$NODEID+0xFF", 1, ["OBJ016 DefaultValue=$NODEID+0xFF (= 256 for node-id 1) is above the UNSIGNED8 "
                         "maximum 255"]),
    ("$NODEID+0x80", None, []),
])
def test_nodeid_default_range(value: str, node_id: int | None, found: list[str]) -> None:
    od = _od((0x2000, _var(value, "UNSIGNED8")))
    assert _rules(od, node_id=node_id) == found


def test_nodeid_relative_limits_move_with_the_value() -> None:
    sub = _var("$NODEID+0x180", "UNSIGNED32", low="$NODEID+0x180", high="$NODEID+0x180")
    assert _rules(_od((0x2000, sub))) == []
    sub = _var("$NODEID+0x180", "UNSIGNED32", low="0x181", high="0x18F")
    assert _rules(_od((0x2000, sub))) == [
        "OBJ017 DefaultValue=$NODEID+0x180 is above HighLimit=0x18F for node-id 127"]


def test_signed_hex_limit_shows_its_reading() -> None:
    sub = _var("1", "INTEGER8", low="0x00", high="0xFF")
    assert _rules(_od((0x6061, sub))) == [
        "OBJ015 LowLimit=0x00 is above HighLimit=0xFF (-1)",
        "OBJ017 DefaultValue=1 is above HighLimit=0xFF (-1)",
    ]


def test_two_tpdos_on_one_can_id_are_found_past_a_fixed_one() -> None:
    """RPDO1 on a fixed 0x181 meets TPDO1 ($NODEID+0x180) at node-id 1 only; TPDO5 on TPDO1's COB-ID
    collides at every node-id, whichever use comes first at node-id 1."""
    od = ObjectDictionary(source="model", format="eds")
    for index, cob in ((0x1400, "0x181"), (0x1800, "$NODEID+0x180"), (0x1804, "$NODEID+0x180")):
        obj = od.objects[index] = Obj(index=index, name=f"PDO {index:04X}", object_code=RECORD)
        obj.subs[1] = Sub(1, "COB-ID", line=index, data_type=0x0007, access="rw",
                          default=parse_value(cob, BY_NAME["UNSIGNED32"], index))
    diags = Diagnostics()
    run_rules(od, diags, LintOptions())
    assert [(d.index, d.message) for d in diags if d.rule == "COM016"] == [
        (0x1804, "TPDO5 uses CAN-ID 0x181, as does TPDO1 (0x1800sub1)")]


def test_xdd_models_skip_list_rules_and_xdd_extensions() -> None:
    od = _od((0x2000, _var("1", "UNSIGNED8")))
    od.objects[0x2000].var.extra["co_flagspdo"] = Field("CO_flagsPDO", "0", 7)
    diags = Diagnostics()
    run_rules(od, diags, LintOptions())
    assert not [d for d in diags if d.rule.startswith(("LST00", "HDR001", "OBJ025"))]


def test_mpdo_mapping_is_not_checked_as_a_list() -> None:
    od = _od(fmt="eds")
    mapping = Obj(0x1600, "RPDO mapping", object_code=ARRAY)
    mapping.subs[0] = Sub(0, "Count", data_type=5, access="rw", default=parse_value("0xFE", BY_NAME["UNSIGNED8"]))
    od.objects[0x1600] = mapping
    assert [r for r in _rules(od) if r.startswith(("PDO001", "PDO006"))] == []


def test_disabled_pdos_are_not_counted() -> None:
    """CANopenEditor keeps `CO_disabled` objects in its XDD but exports none of them."""
    od = _od()
    od.ensure_section("DeviceInfo").set("NrOfTXPDO", "1", 9)
    for index in (0x1800, 0x1A00, 0x1804):
        od.objects[index] = Obj(index, f"PDO {index:04X}", object_code=ARRAY)
    od.objects[0x1804].extra["co_disabled"] = Field("CO_disabled", "true", 12)
    diags = Diagnostics()
    run_rules(od, diags, LintOptions())
    assert not [d for d in diags if d.rule in ("PDO008", "PDO009")]


def test_defined_types_are_not_undefined() -> None:
    od = _od((0x2000, _var("0", "UNSIGNED8")))
    od.objects[0x2000].var.data_type = 0x0040
    od.objects[0x0040] = Obj(0x0040, "Vendor type", object_code=0x5)
    od.objects[0x0040].subs[0] = Sub(0, "Vendor type", data_type=7, access="ro")
    assert not [r for r in _rules(od) if r.startswith("OBJ012")]


def test_large_file_lints(tmp_path: Path) -> None:
    """4000 objects (that the time stays linear in the size is measured by `make fuzz`, fuzz/scaling.py)."""
    text = (RULE_FIXTURES / "clean.eds").read_text(encoding="utf-8")
    indices = [0x2100 + i for i in range(4000)]
    entries = "\n".join(f"{n}=0x{index:04X}" for n, index in enumerate(indices, 3))
    text = text.replace("[ManufacturerObjects]\nSupportedObjects=2\n1=0x2000\n2=0x2001",
                        f"[ManufacturerObjects]\nSupportedObjects=4002\n1=0x2000\n2=0x2001\n{entries}")
    text += "".join(f"\n[{index:04X}]\nParameterName=Parameter {index:04X}\nDataType=0x0006\n"
                    f"AccessType=rw\nDefaultValue=5\nLowLimit=0\nHighLimit=100\n" for index in indices)
    path = tmp_path / "large.eds"
    path.write_text(text, encoding="utf-8")
    result = lint(path)
    assert result.od is not None and len(result.od.objects) == 4016 and rendered(result) == []


# -- the corpus ------------------------------------------------------------------------

@pytest.mark.parametrize("path", corpus_params())
def test_rules_run_on_real_files(path: Path) -> None:
    od, diags = load_path(path)
    if od is None:
        return
    run_rules(od, diags, LintOptions())
    run_rules(od, Diagnostics(), LintOptions(node_id=1, can_fd=True))
    ours = [d for d in diags if d.rule.startswith(FAMILIES)]
    # no rule floods a file: aggregated reports keep each rule readable
    per_rule: dict[str, int] = {}
    for d in ours:
        per_rule[d.rule] = per_rule.get(d.rule, 0) + 1
    assert max(per_rule.values(), default=0) <= 150, per_rule


@pytest.mark.parametrize("name,line", [
    ("eyou__YiyouServo_V1.4.eds", "error[OBJ014]: 0x2023 HighLimit=65536 is above the UNSIGNED16 maximum 65535"),
    ("kacanopen__Easy-ak_v1.30.eds", "error[OBJ010]: 0x1003sub0 DataType=0x0007 (UNSIGNED32) is not UNSIGNED8"),
    ("roscanopen__Schunk.eds", "warning[PDO004]: 0x1601sub1 RPDO maps 0x606Bsub0, which is ro; RPDO2 starts disabled"),
    ("pycanopen__e35.eds", "warning[HDR012]: VendorNumber=101 but 0x1018sub1 is 0xFF"),
    ("wustsat__lora.eds", "[MandatoryObjects] entry 3 lists 0x03FA, which has no section "
                          "(1018 is decimal; 0x1018 was probably meant)"),
    ("pycanopen__sensor.eds", "0x1800sub1 COB-ID $NODEID+1024 is not the predefined TPDO1 COB-ID $NODEID+0x180"),
])
def test_real_defects_are_found(name: str, line: str) -> None:
    path = CORPUS / name
    if not path.is_file():
        pytest.skip("../shared/corpus is absent")
    assert any(line in d for d in rendered(lint(path)))


# -- severities decided from what the peers accept (docs/rules.md) ------------------------------

def _variant(tmp_path: Path, fixture: str, *edits: tuple[str, str]) -> list[str]:
    """The rules a rule fixture reports after text edits (its '; expect:' lines dropped)."""
    text = "\n".join(x for x in (RULE_FIXTURES / fixture).read_text().splitlines() if not x.startswith("; expect:"))
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / fixture
    path.write_text(text + "\n")
    return [d.rule for d in lint(path).diagnostics]


def test_a_writable_sub0_may_count_the_valid_entries(tmp_path: Path) -> None:
    """The 0x1003 pattern vendors use for other objects (kacanopen__CL4-E-2-12.eds:6267): sub0 rw, below the highest."""
    sub0 = "[2000sub0]\nParameterName=Highest sub-index supported\nDataType=0x0005\nAccessType="
    assert _variant(tmp_path, "OBJ011.eds", (sub0 + "ro", sub0 + "rw")) == []
    assert _variant(tmp_path, "OBJ011.eds", (sub0 + "ro\nDefaultValue=1", sub0 + "rw\nDefaultValue=3")) == ["OBJ011"]


def test_only_a_configured_baudrate_of_zero_is_a_note(tmp_path: Path) -> None:
    assert _variant(tmp_path, "HDR008.dcf", ("Baudrate=1000", "Baudrate=0")) == ["HDR015"]
    assert _variant(tmp_path, "HDR008.dcf", ("Baudrate=1000", "Baudrate=125")) == ["HDR008"]


def test_unnamed_sub_objects_of_a_record_stay_errors(tmp_path: Path) -> None:
    assert _variant(tmp_path, "OBJ027.eds", ("ObjectType=0x8", "ObjectType=0x9")) == ["OBJ001"]


def test_mixed_array_is_a_record_in_the_model() -> None:
    od = lint(RULE_FIXTURES / "OBJ026.eds").od
    assert od is not None and od.objects[0x2000].object_code == ARRAY and od.objects[0x2000].structure == 0x9


@pytest.mark.parametrize("name,line", [
    ("canfestival__DS401_Slave_Gui.eds", "372: warning[OBJ026]: 0x1400sub2 DataType=0x0005 but sub1 has 0x0007; "
                                         "generated as a RECORD"),
    ("objdictgen__objdictgen_slave.eds", "396: warning[PDO011]: 0x1600sub1 maps nothing (0x00000000) but sub0=8"),
    ("roscanopen__Schunk_0_63.dcf", "1809: error[OBJ008]: 0x200B DataType, AccessType on the RECORD header"),
    ("oresatmon__oresat_c3.dcf", "54: info[HDR015]: Baudrate=0: no bit rate configured"),
])
def test_the_audits_examples_are_reported_as_decided(name: str, line: str) -> None:
    """The audit of real files (docs/rules.md): each finding at the severity decided, none blocking there."""
    path = CORPUS / name
    if not path.is_file():
        pytest.skip("../shared/corpus is absent")
    assert any(d.startswith(line) for d in rendered(lint(path)))


def test_the_audits_writable_sub0_is_not_reported() -> None:
    path = CORPUS / "kacanopen__CL4-E-2-12.eds"
    if not path.is_file():
        pytest.skip("../shared/corpus is absent")
    assert not [d for d in lint(path).diagnostics if d.rule == "OBJ011"]


@pytest.mark.parametrize(("value", "found"), [
    ("0x80000100", ""), ("0x40000100", ""), ("0x00000900", ""),  # not used: the form does not matter
    ("0xA0012345", ""),  # 29-bit
    ("0x80000900", "bits above 0x7FF"), ("0x40000701", "restricted CAN-ID 0x701"),
    ("0x80000000", "restricted CAN-ID 0x000"), ("$NODEID+0x80000100", "depends on $NODEID"),
])
def test_time_cob_id_forms(value: str, found: str, tmp_path: Path) -> None:
    """COM019: a TIME COB-ID in use must be a free 11-bit CAN-ID (or a 29-bit one), the same for every node."""
    path = tmp_path / "time.eds"
    path.write_text((RULE_FIXTURES / "COM019.eds").read_text(encoding="utf-8").replace(
        "DefaultValue=0x80000900", f"DefaultValue={value}"), encoding="utf-8")
    messages = [d.message for d in lint(path).diagnostics if d.rule == "COM019"]
    assert messages == ([] if not found else [messages[0]]) and all(found in m for m in messages)


@pytest.mark.parametrize(("period", "window", "found"), [
    ("10000", "10000", False), ("10000", "10001", True), ("0", "20000", False), ("10000", "0", False),
])
def test_sync_window_against_period(period: str, window: str, found: bool, tmp_path: Path) -> None:
    path = tmp_path / "sync.eds"
    path.write_text((RULE_FIXTURES / "COM020.eds").read_text(encoding="utf-8").replace(
        "DefaultValue=10000", f"DefaultValue={period}").replace("DefaultValue=20000", f"DefaultValue={window}"),
        encoding="utf-8")
    assert [d.rule for d in lint(path).diagnostics if d.rule == "COM020"] == (["COM020"] if found else [])
