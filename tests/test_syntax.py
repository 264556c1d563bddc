"""SYN rules: one failing fixture per rule, checked by exact line and message."""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.diagnostics import RULES
from odgen.formats import load_bytes, load_path
from odgen.lint.driver import lint_path
from odgen.lint.reporters import render_text
from odgen.lint.passes import LintOptions
from odgen.model.values import parse_value, split_nodeid
from odgen.model.datatypes import BY_NAME

from .conftest import FIXTURES, expectations, lint, rendered

SYNTAX = FIXTURES / "syntax"


@pytest.mark.parametrize("fixture", sorted(SYNTAX.glob("SYN*.eds")), ids=lambda p: p.stem)
def test_fixture_reports_its_rule(fixture: Path) -> None:
    wanted = expectations(fixture)
    assert wanted, f"{fixture.name} has no '; expect:' line"
    got = rendered(lint(fixture))
    for line in wanted:
        assert line in got, f"{fixture.name}: expected {line!r}, got {got}"
    assert all(f"[{fixture.stem}]" in w for w in wanted)


def test_every_syn_rule_has_a_fixture() -> None:
    have = {p.stem for p in SYNTAX.glob("SYN*.eds")}
    # fixtures would be 16 MiB or 65,600 keys: tests/test_hostile.py makes them in a temporary folder
    too_large = {"SYN018", "SYN021"}
    assert {r for r in RULES if r.startswith("SYN")} - too_large == have


def test_crlf_bom_tabs_and_case_insensitive_names(tmp_path: Path) -> None:
    text = "\ufeff[fileinfo]\r\nFileName=x.eds\r\n[2000]\r\n\tPARAMETERNAME = Spaced\t\r\n" \
           "datatype=0x0006\r\naccesstype=RW\r\nDefaultValue=\r\n"
    path = tmp_path / "x.eds"
    path.write_bytes(text.encode("utf-8"))
    od, diags = load_path(path)
    sub = od.objects[0x2000].var
    assert (sub.name, sub.data_type, sub.access) == ("Spaced", 6, "rw")
    assert sub.default is not None and sub.default.empty and sub.default.parsed is None
    assert od.section("FileInfo").text("FileName") == "x.eds"
    assert sub.line == 3 and sub.default.line == 7


@pytest.mark.parametrize("text,relative,rest", [
    ("$NODEID+0x180", True, "0x180"),
    ("0x180+$NODEID", True, "0x180"),
    ("$nodeid + 0x180", True, "0x180"),
    ("$NODEID", True, "0"),
    ("0x180", False, "0x180"),
])
def test_nodeid_forms(text: str, relative: bool, rest: str) -> None:
    assert split_nodeid(text)[:2] == (relative, rest)


@pytest.mark.parametrize("text,type_name,parsed", [
    ("001", "UNSIGNED32", 1),
    ("-5", "INTEGER8", -5),
    ("-0x10", "INTEGER16", -16),
    ("0x80", "INTEGER8", -128),
    ("1.5", "REAL32", 1.5),
    ("3", "REAL64", 3.0),
    ("0x3F800000", "REAL32", 1.0),
    ("01 02 ff", "OCTET_STRING", b"\x01\x02\xff"),
    ("hello; world", "VISIBLE_STRING", "hello; world"),
    ("1", "BOOLEAN", 1),
    ("365 43200000", "TIME_OF_DAY", (365 << 32) | 43200000),
    ("1000", "TIME_DIFFERENCE", 1000),
])
def test_value_parsing(text: str, type_name: str, parsed: object) -> None:
    value = parse_value(text, BY_NAME[type_name])
    assert value.error is None and value.parsed == parsed


def test_nodeid_value_resolves_per_node() -> None:
    value = parse_value("$NODEID+0x180", BY_NAME["UNSIGNED32"])
    assert value.nodeid and value.resolve(5) == 0x185


def test_compact_sub_obj_is_expanded(tmp_path: Path) -> None:
    path = tmp_path / "c.dcf"
    path.write_text("[1003]\nParameterName=Errors\nObjectType=0x8\nCompactSubObj=3\nDataType=0x0007\n"
                    "AccessType=ro\nDefaultValue=0\n[1003Name]\nNrOfEntries=1\n2=Second\n"
                    "[1003Value]\nNrOfEntries=1\n3=0x10\n")
    od, diags = load_path(path)
    obj = od.objects[0x1003]
    assert sorted(obj.subs) == [0, 1, 2, 3]
    assert obj.subs[0].default.parsed == 3 and obj.subs[0].data_type == 5
    assert obj.subs[2].name == "Second" and obj.subs[1].name == "Errors1"
    assert obj.subs[3].parameter_value.parsed == 0x10
    assert all(s.compact for s in obj.subs.values()) and not list(diags)


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-16-be", "utf-32"])
def test_wide_encodings_are_decoded_and_reported(encoding: str) -> None:
    text = "[FileInfo]\nFileName=w.eds\n\n[1000]\nParameterName=Gr\u00f6\u00dfe\nDataType=0x0007\n"
    od, diags = load_bytes(text.encode(encoding), "w.eds", "eds")
    assert od is not None and od.objects[0x1000].name == "Gr\u00f6\u00dfe"
    assert [d.rule for d in diags] == ["SYN004"]


def test_capped_rules_are_counted_past_their_cap_and_reported_in_one_line(tmp_path: Path) -> None:
    text = "[FileInfo]\n" + "junk\n" * 600 + "".join(f"K{i}=1 ; note\n" for i in range(3))
    od, diags = load_bytes(text.encode(), "c.eds", "eds")
    assert sum(d.rule == "SYN001" for d in diags) == 500
    assert [d.message for d in diags if d.rule == "SYN014"] == [
        "inline comment '; note' after the value of 'K0' is dropped"]
    assert diags.omitted() == {"SYN001": 100, "SYN014": 2}
    path = tmp_path / "c.eds"
    path.write_text(text)
    report = render_text([lint_path(path, LintOptions())])
    assert f"{path}: error[SYN001]: 100 more SYN001 findings not listed (at most 500 per rule and file)" in report
    assert f"{path}: warning[SYN014]: 2 more SYN014 findings not listed (at most 1 per rule and file)" in report


def test_lines_end_at_cr_and_lf_only() -> None:
    text = "[2000]\nParameterName=a\x0cb\x85c\u2028d\r\nDataType=0x0007\rAccessType=rw\n"
    od, diags = load_bytes(text.encode(), "l.eds", "eds")
    assert od is not None and od.objects[0x2000].name == "a\x0cb\x85c\u2028d"
    assert od.objects[0x2000].subs[0].access == "rw" and not [d for d in diags if d.rule == "SYN001"]


def test_an_index_without_leading_zeros_is_read_and_listed() -> None:
    result = lint(SYNTAX / "SYN019.eds")
    assert result.od is not None and 0x00A0 in result.od.objects
    assert not [d for d in result.diagnostics if d.rule in ("LST005", "SYN010")]
