"""Repairs of descriptions (odgen/repair, `odgen fix`, `generate --fix`) and the readers' fixes they came
with, each from a minimal fixture: what is repaired, which lines change, and what the repaired file is."""

from __future__ import annotations

import difflib
import subprocess
import sys
from pathlib import Path

import pytest

from odgen.catalogue import RULES
from odgen.cli.fix import Fixed, fix_file
from odgen.pipeline import Request, generate
from odgen.formats import load_path
from odgen.lint.driver import lint_model
from odgen.lint.passes import LintOptions
from odgen.repair import REPAIRABLE, repair_model
from odgen.repair.apply import ADD_KEY, DELETE, INSERT_BEFORE, SET

from .conftest import FIXTURES, expectations, lint, rendered

REPAIR = FIXTURES / "repair"
REPAIRS = REPAIR / "repairs.eds"
SAFE = {"OBJ010", "OBJ011", "OBJ014", "OBJ030", "SYN007", "SYN015"}
UNSAFE = {"OBJ015", "OBJ017", "PDO001", "PDO002"}
UNSAFE_BLOCKING = UNSAFE - {"PDO002"}  # a number the file's own mapping maps: the C makes it mappable, a warning


def odgen(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "odgen", *map(str, args)], capture_output=True, text=True,
                          check=False)


def changed_lines(before: bytes, after: bytes) -> set[int]:
    """Lines of `before` (1-based) that were replaced or removed."""
    a, b = before.split(b"\n"), after.split(b"\n")
    touched: set[int] = set()
    for tag, i1, i2, _, _ in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if tag in ("replace", "delete"):
            touched.update(range(i1 + 1, i2 + 1))
    return touched


def named_lines(fixed: Fixed) -> tuple[set[int], int]:
    """The lines the repairs say they replace or remove, and how many lines the file gains."""
    edits = [e for r in fixed.repairs for e in r.edits]
    touched = {e.line for e in edits if e.kind in (SET, DELETE)}
    inserted = sum(1 for e in edits if e.kind == ADD_KEY) + sum(len(e.lines) for e in edits if e.kind == INSERT_BEFORE)
    return touched, inserted - len({e.line for e in edits if e.kind == DELETE})


def assert_only_named_lines_change(before: bytes, fixed: Fixed) -> None:
    named, gained = named_lines(fixed)
    assert changed_lines(before, fixed.data) <= named
    assert len(fixed.data.split(b"\n")) - len(before.split(b"\n")) == gained


def relint(data: bytes, source: str) -> list[str]:
    from odgen.formats import load_bytes

    od, diags = load_bytes(data, source, "eds")
    assert od is not None
    lint_model(od, diags, LintOptions())
    return [d.rule for d in diags.sorted()]


def test_sub0_is_checked_on_the_value_in_force() -> None:
    """A DCF's ParameterValue, not a stale DefaultValue, is what OBJ011 compares with the sub-indices."""
    fixture = REPAIR / "sub0-in-force.dcf"
    assert expectations(fixture)
    assert rendered(lint(fixture)) == expectations(fixture)


def test_every_repair_is_described_in_the_catalogue() -> None:
    assert {r.id for r in RULES.values() if r.repair} == REPAIRABLE
    for rule in RULES.values():
        assert not rule.blocks or rule.repair or rule.no_repair, rule.id


def test_safe_fixes_repair_only_what_is_certain() -> None:
    before = REPAIRS.read_bytes()
    fixed = fix_file(REPAIRS)
    assert {r.rule for r in fixed.repairs} == SAFE and all(r.safe for r in fixed.repairs)
    assert {d.rule for d in fixed.blocking} == UNSAFE_BLOCKING  # what only a guess repairs still blocks
    assert REPAIRS.read_bytes() == before  # the input is never written
    lines = fixed.data.decode().splitlines()
    assert "[2004sub0]" in lines and "ObjFlags=" not in lines and "HighLimit=70000" not in lines


@pytest.mark.parametrize("unsafe", [False, True])
def test_fix_changes_only_the_lines_it_lists(unsafe: bool) -> None:
    fixed = fix_file(REPAIRS, unsafe=unsafe)
    assert fixed.repairs
    assert_only_named_lines_change(REPAIRS.read_bytes(), fixed)


def test_unsafe_fixes_repair_everything_and_a_second_run_changes_nothing(tmp_path: Path) -> None:
    fixed = fix_file(REPAIRS, unsafe=True)
    assert {r.rule for r in fixed.repairs} == SAFE | UNSAFE
    assert {r.rule for r in fixed.repairs if not r.safe} == UNSAFE
    assert fixed.blocking == [] and not fixed.unwritten
    assert not set(relint(fixed.data, "fixed.eds")) & (SAFE | UNSAFE)
    lines = fixed.data.decode().splitlines()
    assert lines[lines.index("[2007]") + 5] == "DefaultValue=10"  # clamped to LowLimit=10
    assert "LowLimit=0x00" not in lines and "HighLimit=0xFF" not in lines  # INTEGER8 bit patterns removed
    copy = tmp_path / "repairs-fixed.eds"  # a repaired file repaired again is the same file
    copy.write_bytes(fixed.data)
    second = fix_file(copy, unsafe=True)
    assert second.repairs == [] and second.data == fixed.data


def test_repair_leaves_the_loaded_model_alone() -> None:
    od, diags = load_path(REPAIRS)
    assert od is not None
    lint_model(od, diags, LintOptions())
    snapshot = repr(od)
    repaired, repairs = repair_model(od, diags.sorted(), unsafe=True)
    assert repairs and repaired is not od and repr(od) == snapshot and repaired != od


def test_generate_refuses_with_one_line_saying_what_fix_would_repair(tmp_path: Path) -> None:
    done = odgen("generate", REPAIRS, "-o", tmp_path)
    assert done.returncode == 1 and not list(tmp_path.iterdir())
    last = done.stderr.strip().splitlines()[-1]
    assert last == (f"odgen: {REPAIRS}: 4 findings block generation (OBJ015 1, OBJ017 2, PDO001 1); "
                    "--fix would repair 0, --unsafe-fixes 4; nothing written")
    assert f"{REPAIRS}:467: error[OBJ017]: 0x2007 DefaultValue=5 is below LowLimit=10 " \
           "[blocks generate; --unsafe-fixes repairs it]" in done.stderr.splitlines()


def test_generate_with_unsafe_fixes_lists_every_repair(tmp_path: Path) -> None:
    done = odgen("generate", REPAIRS, "-o", tmp_path, "--unsafe-fixes", "--name", "rep")
    assert done.returncode == 0, done.stderr
    header = (tmp_path / "rep.h").read_text()
    result = generate(Request(REPAIRS, name="rep", fix="unsafe"))
    assert len(result.repairs) == 11
    for repair in result.repairs:
        assert repair.text() in done.stderr
        assert repair.text().replace(str(REPAIRS), REPAIRS.name) in header
    assert generate(Request(REPAIRS, name="rep", fix="unsafe")).files == result.files  # deterministic


def test_generate_without_a_flag_repairs_nothing() -> None:
    result = generate(Request(REPAIR / "sub0-in-force.dcf", name="x"))
    assert result.files and result.repairs == []
    assert "odgen repaired" not in result.files["x.h"]


def test_lint_marks_only_the_findings_that_block() -> None:
    done = odgen("lint", REPAIRS)
    marked = [line for line in done.stdout.splitlines() if "[blocks generate;" in line]
    assert len(marked) == 4 and all("--unsafe-fixes repairs it]" in line for line in marked)
    assert all(line.startswith(f"{REPAIRS}:") and "error[" in line for line in marked)
    github = odgen("lint", "--format", "github", REPAIRS).stdout
    assert github.count("[blocks generate; --unsafe-fixes repairs it]") == 4
    sarif = odgen("lint", "--format", "sarif", REPAIRS).stdout
    assert sarif.count('"blocksGenerate": true') == 4


def test_fix_command_writes_stdout_or_a_named_file_never_the_input(tmp_path: Path) -> None:
    done = odgen("fix", REPAIRS)
    assert done.returncode == 1  # findings only a guess repairs still block
    assert done.stdout.encode() == fix_file(REPAIRS).data
    refused = odgen("fix", REPAIRS, "-o", REPAIRS)
    assert refused.returncode == 2 and "--force" in refused.stderr
    out = tmp_path / "out.eds"
    assert odgen("fix", REPAIRS, "--unsafe-fixes", "-o", out).returncode == 0
    assert out.read_bytes() == fix_file(REPAIRS, unsafe=True).data


def test_fix_keeps_encoding_and_line_ends(tmp_path: Path) -> None:
    crlf = tmp_path / "crlf.eds"
    crlf.write_bytes(REPAIRS.read_bytes().replace(b"\n", b"\r\n").replace(b"Sub0 stale", b"Sub0 \xe9t\x85"))
    fixed = fix_file(crlf).data
    assert b"\r\n" in fixed and fixed.count(b"\n") == fixed.count(b"\r\n")
    assert b"Sub0 \xe9t\x85" in fixed


def test_fix_refuses_xml(tmp_path: Path) -> None:
    done = odgen("fix", FIXTURES / "xdd" / "valid.xdd")
    assert done.returncode == 2 and "generate --fix" in done.stderr


def test_a_64_bit_entry_mapped_with_32_bits_is_a_warning_that_does_not_block(tmp_path: Path) -> None:
    """The runtime serves it as CANopenNode does (tests/node/test_node_short.c); other short mappings block."""
    node = FIXTURES.parent / "node" / "pdo-node.eds"
    text = node.read_text(encoding="utf-8")
    short = tmp_path / "short.eds"
    short.write_text(text.replace("DefaultValue=0x20000008", "DefaultValue=0x20030020", 1), encoding="utf-8")
    found = [d for d in lint(short).diagnostics if d.rule == "PDO003"]
    assert [(d.severity.label, d.blocks) for d in found] == [("warning", False)]
    assert "low-order 32 bits" in found[0].message
    assert generate(Request(short, name="short")).files
    narrow = tmp_path / "narrow.eds"  # a 32-bit entry mapped with 16 bits still blocks
    narrow.write_text(text.replace("DefaultValue=0x20000008", "DefaultValue=0x20020010", 1), encoding="utf-8")
    found = [d for d in lint(narrow).diagnostics if d.rule == "PDO003"]
    assert [(d.severity.label, d.blocks) for d in found] == [("error", True)]
