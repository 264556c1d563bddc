"""Every real file a firmware team brings either generates, or is refused for a finding that blocks.

Refused files are listed below with the blocking rules and why the dictionary would be wrong;
every other corpus file must generate, compile with gcc and clang under -Wall -Wextra -Werror
-pedantic and pass `odgen check`'s self-test (round trips on vcan: test_roundtrip_vcan.py).
With --unsafe-fixes (odgen/repair) all but UNREPAIRABLE generate, and must do the same.
A file that starts or stops generating fails here until the table says why.
"""

from __future__ import annotations

import shutil

import pytest

from odgen.check import run_check
from odgen.pipeline import Request, generate

from .conftest import BUILD, corpus_files

# Refused without a flag: file -> (the rules that block, what makes the C or the node wrong). Each not in
# UNREPAIRABLE generates with --unsafe-fixes (the repairs are guesses: docs/rules.md); none with --fix alone.
REFUSED: dict[str, tuple[set[str], str]] = {
    "kacanopen__CiA_profiles_301.eds": ({"SYN011"}, "a template: prose as values"),
    "mabcandle__MD80_latest.eds": ({"COM016", "OBJ017"}, "SDO server 1 on server 0's CAN-IDs (two answers to one "
                                   "request); a writable default below its LowLimit (written back, it is refused)"),
    "nodecanopen__test.eds": ({"OBJ012"}, "DataType 0x0020-0x0023 neither basic nor defined"),
    "nodecanopen__tiny_sample.eds": ({"COM010", "OBJ010"}, "a record with a VISIBLE_STRING sub0 in the SDO range"),
    "oresatmon__oresat_c3.dcf": ({"PDO003", "PDO005"}, "enabled RPDOs map 16-bit entries with 32 bits: 128 bits "
                                 "for a 64-bit frame"),
    "oresatmon__oresat_gps.xdd": ({"COM016"}, "enabled TPDO5/TPDO6 send other mappings on TPDO1/TPDO2's CAN-IDs: "
                                  "receivers cannot tell the frames apart"),
    "pycanopen__sample.eds": ({"OBJ006", "OBJ010", "OBJ012", "PDO001"},
                              "test file: maps absent objects, REAL32 sub0, undefined type, an ARRAY header as a "
                              "value"),
    "pycanopen__sample.xdd": ({"OBJ015", "OBJ017", "PDO001"}, "a writable entry with LowLimit above HighLimit; "
                              "enabled PDOs map absent objects"),
    "pycanopen__sender.eds": ({"OBJ006"}, "an ARRAY header as a value"),
    "wustsat__lora.xdc": ({"XML002"}, "a PROFINET GSDML profile, not CANopen"),
}

# Refused even with --unsafe-fixes: file -> (the rules that still block, why no repair can be right).
UNREPAIRABLE: dict[str, tuple[set[str], str]] = {
    "kacanopen__CiA_profiles_301.eds": ({"SYN011"}, "values are prose (\"see manufacturer\"): no number is meant"),
    "nodecanopen__tiny_sample.eds": ({"COM010", "OBJ010"},
                                     "0x1234 is an SDO parameter without COB-IDs and its sub0 is text: the "
                                     "channel's CAN-IDs are unknown"),
    "wustsat__lora.xdc": ({"XML002"}, "not a CANopen description at all"),
}


def _refusals(fix: str) -> dict[str, set[str]]:
    got = {}
    for path in corpus_files():
        name, result = path.name, generate(Request(path, name="od", fix=fix))
        if result.files:
            continue
        assert result.refused and all(d.blocks for d in result.refused), f"{name}: refused without a blocking finding"
        got[name] = {d.rule for d in result.refused}
    return got


def test_refused_corpus_files_are_refused_for_blocking_findings_as_listed() -> None:
    if not corpus_files():
        pytest.skip("../shared/corpus is absent")
    assert _refusals("") == {name: rules for name, (rules, _) in REFUSED.items()}
    assert len(corpus_files()) - len(REFUSED) >= 60


def test_with_unsafe_fixes_only_the_unrepairable_files_are_refused() -> None:
    if not corpus_files():
        pytest.skip("../shared/corpus is absent")
    assert _refusals("unsafe") == {name: rules for name, (rules, _) in UNREPAIRABLE.items()}
    assert len(corpus_files()) - len(UNREPAIRABLE) >= 67


def _compiler(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is missing: `make test` installs it (make sysdeps)"
    return path


@pytest.mark.parametrize("cc", ["gcc", "clang"])  # one test per compiler: pytest-xdist runs them side by side
@pytest.mark.parametrize("fix", ["", "unsafe"])
def test_every_other_corpus_file_generates_compiles_and_checks(fix: str, cc: str) -> None:
    """Without a flag: every file not in REFUSED; with --unsafe-fixes: the files only the repairs let through."""
    refused = REFUSED if not fix else UNREPAIRABLE
    files = [p for p in corpus_files() if p.name not in refused and (not fix or p.name in REFUSED)]
    if not files:
        pytest.skip("../shared/corpus is absent")
    failures, lines = [], []
    for path in files:
        outcome = run_check(Request(path, name="od", fix=fix), cc=_compiler(cc))
        summary = outcome.output.strip().splitlines()[-1] if outcome.output.strip() else "not generated"
        accepted = len([d for d in outcome.result.diags if d.severity.label != "info"])
        lines.append(f"| {path.name} | {cc} | {accepted} | {'ok' if outcome.ok else 'FAILED'} | {summary} |")
        if not outcome.ok:
            failures.append(f"{path.name} ({cc}): {outcome.output[-800:] or outcome.result.refused}")
    BUILD.mkdir(parents=True, exist_ok=True)
    (BUILD / f"corpus-check{'-' + fix if fix else ''}-{cc}.md").write_text(
        f"# odgen check on the {len(files)} corpus files that generate{' with --' + fix + '-fixes' if fix else ''}\n\n"
        "| file | cc | findings accepted | result | self-test |\n|---|---|---|---|---|\n"
        + "\n".join(lines) + "\n", encoding="utf-8")
    assert not failures, "\n\n".join(failures)
