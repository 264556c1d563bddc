"""odgen generate: GEN rules by fixture, refusal, determinism, --check, names, placement."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from odgen.cli import main
from odgen.check import run_check
from odgen.pipeline import Request, generate
from odgen.cnames import comment, identifier, name_clash, string_literal
from odgen.model.expect import expected_bytes
from odgen.diagnostics import RULES
from odgen.model.datatypes import BASIC_TYPES

from .conftest import FIXTURES, ROOT

GEN = FIXTURES / "generate"
PLAIN = GEN / "plain.eds"
EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
EXAMPLE_OPTIONS = ROOT / "examples" / "io-node" / "io-node.toml"


def _rendered(result) -> list[str]:
    prefix = f"{GEN}/"
    return [d.text().replace(prefix, "").replace(f"{ROOT}/", "") for d in result.diags.sorted()]


def _fixture_cases() -> list[tuple[str, Path, Path | None]]:
    cases = []
    for path in sorted(GEN.glob("GEN*")):
        if path.suffix == ".toml":  # applied to plain.eds, or to the description its `# eds: PATH` line names
            named = [x[len("# eds: "):] for x in path.read_text().splitlines() if x.startswith("# eds: ")]
            cases.append((path.stem, (GEN / named[0]).resolve() if named else PLAIN, path))
        else:
            cases.append((path.stem, path, None))
    return cases


def _name(path: Path) -> str | None:
    """A fixture's `; name: X` line: the --name it is generated with."""
    return next((x[len("; name: "):] for x in path.read_text().splitlines() if x.startswith("; name: ")), None)


def _expectations(path: Path) -> list[str]:
    marker = "# expect: " if path.suffix == ".toml" else "; expect: "
    return [x[len(marker):] for x in path.read_text().splitlines() if x.startswith(marker)]


@pytest.mark.parametrize("rule,eds,options", _fixture_cases(), ids=lambda c: c if isinstance(c, str) else "")
def test_gen_fixture(rule: str, eds: Path, options: Path | None) -> None:
    result = generate(Request(eds, name=_name(eds), options=options))
    wanted = _expectations(options or eds)
    assert wanted and all(f"[{rule}]" in w for w in wanted)
    got = _rendered(result)
    for line in wanted:
        assert line in got, f"expected {line!r}, got {got}"
    if RULES[rule].blocks:
        assert result.files == {}, "generation must stop on a blocking finding"


def test_every_gen_rule_has_a_fixture() -> None:
    assert {r for r in RULES if r.startswith("GEN")} == {rule for rule, _, _ in _fixture_cases()}


def test_a_description_without_objects_is_refused_not_turned_into_empty_tables(tmp_path: Path) -> None:
    """Only header sections: C99 has no zero-size arrays, so there is nothing to generate (GEN009)."""
    header = PLAIN.read_text().split("[MandatoryObjects]")[0]
    bare = tmp_path / "bare.eds"
    bare.write_text(header)
    result = generate(Request(bare, name="od"))
    assert result.files == {} and [d.rule for d in result.refused] == ["GEN009"], _rendered(result)
    assert f"{bare}: error[GEN009]: the description has no object from 0x1000 on: nothing to generate" \
        in _rendered(result)


def test_a_nodeid_minus_default_of_an_unsigned_type_reads_node_id_minus_one(tmp_path: Path) -> None:
    """`$NODEID-1` (SYN007: not the CiA 306 form, read anyway) is stored as the offset -1 modulo
    2^bits, as C converts it; the reset adds the node-id. It was printed as `UINT32_C(0x-1)`."""
    objects = "".join(f"[{index:04X}]\nParameterName=N{index:X}\nObjectType=0x7\nDataType=0x{code:04X}\n"
                      "AccessType=rw\nDefaultValue=$NODEID-1\nPDOMapping=0\n\n"
                      for index, code in ((0x2100, 0x0007), (0x2101, 0x001B), (0x2102, 0x0005)))
    eds = tmp_path / "minus.eds"
    listed = "[ManufacturerObjects]\nSupportedObjects=4\n1=0x2000\n2=0x2100\n3=0x2101\n4=0x2102\n"
    eds.write_text(PLAIN.read_text().replace("[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n", listed)
                   + "\n" + objects)
    result = generate(Request(eds, name="od"))
    assert "UINT32_C(0xFFFFFFFF)" in result.files["od.c"] and "UINT64_C(0xFFFFFFFFFFFFFFFF)" in result.files["od.c"]
    for index, code, size in ((0x2100, 0x0007, 4), (0x2101, 0x001B, 8), (0x2102, 0x0005, 1)):
        sub = result.od.objects[index].subs[0]  # what the self-test expects a read to give, node-id 5
        assert expected_bytes(result.od, sub, BASIC_TYPES[code], 5) == (4).to_bytes(size, "little")
    outcome = run_check(Request(eds, name="od", node_id=5))  # and the C gives it
    assert outcome.ok, outcome.output


def test_refuses_on_lint_errors_and_writes_nothing(tmp_path: Path) -> None:
    bad = FIXTURES / "syntax" / "SYN003.eds"
    assert main(["generate", str(bad), "-o", str(tmp_path / "out")]) == 1
    assert not (tmp_path / "out").exists()


NOT_LISTED = FIXTURES / "rules" / "LST007.eds"  # an error that does not block generation


def test_goes_on_past_findings_that_do_not_block_and_lists_them_in_the_header(tmp_path: Path, capsys) -> None:
    assert main(["generate", str(NOT_LISTED), "-o", str(tmp_path), "--name", "od"]) == 0
    assert f"{NOT_LISTED}:68: error[LST007]: 0x2000 is in no object list" in capsys.readouterr().err
    header = (tmp_path / "od.h").read_text()
    assert " *   LST007.eds:68: error[LST007]: 0x2000 is in no object list (belongs in [ManufacturerObjects])" in header
    assert str(NOT_LISTED.parent) not in header, "the header names the file, not the path it was read from"


def test_strict_refuses_on_any_error_or_warning(tmp_path: Path, capsys) -> None:
    assert main(["generate", str(NOT_LISTED), "-o", str(tmp_path / "out"), "--strict"]) == 1
    assert "1 findings (--strict), nothing written" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_ignored_findings_are_neither_printed_nor_listed(tmp_path: Path, capsys) -> None:
    assert main(["generate", str(NOT_LISTED), "-o", str(tmp_path), "--name", "od", "--ignore", "LST",
                 "--strict"]) == 0
    assert "LST007" not in capsys.readouterr().err and "[LST007]" not in (tmp_path / "od.h").read_text()


def test_blocking_findings_refuse_even_when_ignored(tmp_path: Path, capsys) -> None:
    bad = FIXTURES / "rules" / "OBJ015.eds"
    assert main(["generate", str(bad), "-o", str(tmp_path / "out"), "--ignore", "OBJ015"]) == 1
    err = capsys.readouterr().err
    assert "error[OBJ015]" in err and "1 finding blocks generation (OBJ015 1)" in err and "nothing written" in err


def test_a_misspelt_rule_id_is_a_usage_error(tmp_path: Path, capsys) -> None:
    assert main(["generate", str(PLAIN), "-o", str(tmp_path), "--select", "PDO001,XYZ12"]) == 2
    assert "'XYZ12' is not a rule id or prefix" in capsys.readouterr().err


def test_output_is_deterministic_and_hash_tracks_options(tmp_path: Path) -> None:
    one, two, three = (tmp_path / n for n in ("one", "two", "three"))
    assert main(["generate", str(EXAMPLE), "-o", str(one)]) == 0
    assert main(["generate", str(EXAMPLE), "-o", str(two)]) == 0
    assert main(["generate", str(EXAMPLE), "-o", str(three), "--options", str(EXAMPLE_OPTIONS)]) == 0
    files = sorted(p.name for p in one.iterdir())
    assert files == ["io_node.c", "io_node.h", "io_node_config.h"]
    for name in files:
        assert (one / name).read_bytes() == (two / name).read_bytes()
    assert (one / "io_node.h").read_text() != (three / "io_node.h").read_text()
    header = (one / "io_node.h").read_text()
    assert "hash" in header and not re.search(r"\d{4}-\d\d-\d\d|\d\d:\d\d:\d\d", header), "no timestamps"


def test_template_cache_gives_the_same_files_and_a_missing_one_only_costs_time(tmp_path: Path,
                                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """Compiled templates come from jinja2's cache when it can be had; the files are the same
    with a fresh cache, a warm one, and none (its folder cannot be made: a file stands there)."""
    import tempfile

    from odgen.codegen.render import environment

    outputs = []
    blocked = tmp_path / "not-a-folder"
    blocked.write_text("", encoding="utf-8")
    (tmp_path / "tmp").mkdir()
    for n, tmp in enumerate((tmp_path / "tmp", tmp_path / "tmp", blocked)):
        monkeypatch.setattr(tempfile, "tempdir", str(tmp))
        assert (environment().bytecode_cache is None) == (tmp == blocked)
        out = tmp_path / f"out{n}"
        assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0
        outputs.append({p.name: p.read_bytes() for p in out.iterdir()})
    assert list((tmp_path / "tmp").glob("_jinja2-cache-*/odgen-*.cache")), "the first run fills the cache"
    assert outputs[0] == outputs[1] == outputs[2]


def test_check_flag_reports_stale_files(tmp_path: Path) -> None:
    out = tmp_path / "gen"
    assert main(["generate", str(EXAMPLE), "-o", str(out), "--check"]) == 1
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0
    assert main(["generate", str(EXAMPLE), "-o", str(out), "--check"]) == 0
    (out / "io_node.c").write_text("/* edited */\n")
    assert main(["generate", str(EXAMPLE), "-o", str(out), "--check"]) == 1


@pytest.mark.parametrize("name", ["../../x", "/abs/x", "int", "9lives", "a-b", "x" * 40])
def test_unsafe_names_are_rejected(tmp_path: Path, name: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["generate", str(EXAMPLE), "-o", str(tmp_path), "--name", name]) == 2
    assert "C identifier" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_sanitizer() -> None:
    assert identifier("Vendor-ID") == "vendor_id"
    assert identifier("1st value") == "n1st_value"
    assert identifier("int") == "int_"
    assert identifier("***") == "entry"
    assert "*/" not in comment("evil */ #define X")
    assert "\n" not in comment("two\nlines")
    assert string_literal('a"b\\c??=\n\xe9'.encode()) == '"a\\"b\\\\c\\?\\?=\\012\\303\\251"'


def test_explain_names_the_origin(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["explain", str(EXAMPLE), "0x6200sub1", "--options", str(EXAMPLE_OPTIONS)]) == 0
    out = capsys.readouterr().out
    assert "storage: ram" in out and "auto: writable or PDO-mappable" in out
    assert "pre_write, post_write -> io_node_apply_outputs()" in out and "io-node.toml:21" in out
    assert main(["explain", str(EXAMPLE), "0x2000", "--options", str(EXAMPLE_OPTIONS)]) == 0
    assert "persist:app" in capsys.readouterr().out


def test_uniform_elements_share_one_descriptor(capsys: pytest.CaptureFixture[str]) -> None:
    """0x1018 sub 1..4 (UNSIGNED32, ro) are one descriptor; 0x1200's $NODEID COB-IDs and the hooked
    0x6200 stay one each. explain says which."""
    result = generate(Request(EXAMPLE, options=EXAMPLE_OPTIONS))
    c = next(text for name, text in result.files.items() if name.endswith(".c") and "_subs[" in text)
    assert "{.index = 0x1018, .first = 7, .count = 2, .code = ODG_OBJ_RECORD | ODG_E_DENSE | ODG_E_PACKED}" in c
    assert "_assert_packed_1018[" in c and "0x1200, .first = 9, .count = 3" in c
    assert main(["explain", str(EXAMPLE), "0x1018sub2", "--options", str(EXAMPLE_OPTIONS)]) == 0
    assert "packed: sub-indices 1..4 alike share one descriptor" in capsys.readouterr().out
    assert main(["explain", str(EXAMPLE), "0x1200sub1", "--options", str(EXAMPLE_OPTIONS)]) == 0
    assert "packed" not in capsys.readouterr().out


def test_placement_rules() -> None:
    result = generate(Request(EXAMPLE, options=EXAMPLE_OPTIONS))
    placements = result.placements
    assert placements is not None
    assert placements[(0x1018, 1)].storage == "rom"  # ro, not mappable
    assert placements[(0x1001, 0)].storage == "ram"  # ro but PDO-mappable
    assert placements[(0x1200, 1)].storage == "ram"  # $NODEID-relative
    assert placements[(0x1010, 1)].storage == "command"
    assert placements[(0x1017, 0)].storage == "persist:comm"
    assert placements[(0x2000, 0)].storage == "persist:app"


# -- names that compile -------------------------------------------------------------------------

CLASHING = ["odg", "ODG", "main", "stdint", "string", "memcpy", "size_t", "uint8_t", "odg_init", "odg_read",
            "_Atomic", "errno", "stdio", "printf"]


@pytest.mark.parametrize("name", CLASHING)
def test_a_name_that_clashes_is_refused_when_given_and_prefixed_when_taken_from_the_file(
        name: str, tmp_path: Path, capsys) -> None:
    assert main(["generate", str(PLAIN), "-o", str(tmp_path / "given"), "--name", name]) == 1
    assert f"error[GEN008]: --name {name} " in capsys.readouterr().err and not (tmp_path / "given").exists()
    path = tmp_path / f"{name}.eds"
    path.write_text(PLAIN.read_text())
    outcome = run_check(Request(path), cc=shutil.which("gcc"))
    assert outcome.ok, outcome.output[-2000:]
    assert outcome.result.view is not None and name_clash(outcome.result.view.name) is None


@pytest.mark.parametrize("second", ["a_t", "a_defaults", "a_spread", "a_defaults_t"])
def test_persistence_groups_whose_c_names_meet_are_refused(second: str, tmp_path: Path) -> None:
    options = tmp_path / "groups.toml"
    options.write_text(f'[[entry]]\nmatch = "0x2000"\nstorage = "persist:a"\n\n'
                       f'[[entry]]\nmatch = "0x1017"\nstorage = "persist:{second}"\n')
    result = generate(Request(PLAIN, options=options))
    assert not result.files and [d.rule for d in result.refused] == ["GEN004"], _rendered(result)
    assert f"is generated for both plain_persist_a and plain_persist_{second}" in result.refused[0].message


# -- one value in force ---------------------------------------------------------------------------

def _configured(tmp_path: Path, suffix: str) -> Path:
    """The clean rule fixture with ParameterValue=245 (a reserved TPDO transmission type) on 0x1800sub2."""
    text = (FIXTURES / "rules" / "clean.eds").read_text()
    entry = ("[1800sub2]\nParameterName=Transmission type\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\n"
             "DefaultValue=254\n")
    assert entry in text
    text = text.replace(entry, entry + "ParameterValue=245\n")
    if suffix == ".dcf":
        text = text.replace("\n[DummyUsage]", "\n[DeviceComissioning]\nNodeID=5\nBaudrate=250\n\n[DummyUsage]", 1)
    path = tmp_path / f"dev{suffix}"
    path.write_text(text)
    return path


@pytest.mark.parametrize("suffix,value", [(".dcf", 245), (".eds", 254)])
def test_rules_generate_check_and_explain_take_the_same_value(suffix: str, value: int, tmp_path: Path, capsys) -> None:
    """A DCF's ParameterValue is in force; an EDS's is ignored (OBJ024) by every stage alike."""
    path = _configured(tmp_path, suffix)
    result = generate(Request(path, name="dev"))
    rules = {d.rule: d.message for d in result.diags}
    assert ("COM011" in rules) == (value == 245) and ("OBJ024" in rules) == (suffix == ".eds")
    assert f".x1800_tpdo1_communication_parameter_s2_transmission_type = {value}," in result.files["dev.c"]
    if value == 245:
        assert "warning[COM011]: 0x1800sub2 transmission type 245 is reserved" in result.files["dev.h"]
    assert main(["explain", str(path), "0x1800sub2"]) == 0
    source = "ParameterValue" if suffix == ".dcf" else "DefaultValue"
    out = capsys.readouterr().out
    assert f"value:   {value}" in out and f"from {source}" in out
    outcome = run_check(Request(path, name="dev"), cc=shutil.which("gcc"))
    assert outcome.ok, outcome.output[-2000:]


def test_a_described_rom_location_on_a_writable_entry_is_canopennode_v1_persistence(tmp_path: Path) -> None:
    """CANopenNode v1 keeps `;StorageLocation=ROM` entries in RAM and saves them by 0x1010; an options file's
    `storage = "rom"` on a writable entry stays GEN003 (tests/fixtures/generate/GEN003.toml)."""
    path = tmp_path / "v1.eds"
    path.write_text(PLAIN.read_text().replace("DefaultValue=10\n", "DefaultValue=10\n;StorageLocation=ROM\n")
                    .replace("ParameterName=Producer heartbeat time\n", "ParameterName=Producer heartbeat time\n"
                             ";StorageLocation=ROM\n").replace("DataType=0x0006\nAccessType=rw\nDefaultValue=1000",
                                                               "DataType=0x0006\nAccessType=const\nDefaultValue=1000"))
    result = generate(Request(path, name="v1"))
    assert result.placements is not None and result.files, _rendered(result)
    assert result.placements[(0x2000, 0)].storage == "persist:rom"
    assert result.placements[(0x1017, 0)].storage == "rom"
