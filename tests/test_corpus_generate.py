"""Every real file a firmware team brings either generates, or is refused for a finding that blocks.

Refused files are listed below with the blocking rules and why the dictionary would be wrong;
every other corpus file must generate, compile with gcc and clang under -Wall -Wextra -Werror
-pedantic and pass `odgen check`'s self-test (round trips on vcan: test_roundtrip_vcan.py).
A file that starts or stops generating fails here until the table says why.
"""

from __future__ import annotations

import shutil

import pytest

from odgen.check import run_check
from odgen.pipeline import Request, generate

from .conftest import BUILD, corpus_files

# file -> (blocking rules it is refused for, what makes its dictionary wrong or ambiguous)
REFUSED: dict[str, tuple[set[str], str]] = {
    "eyou__YiyouServo_V1.4.eds": ({"OBJ014"}, "UNSIGNED16 HighLimit 65536"),
    "gocanopen__base.eds": ({"OBJ011"}, "read-only sub0 5 below sub-index 6 of 0x1400-0x1403"),
    "kacanopen__605.3150.51-V-EK-2-60.eds": ({"OBJ015", "OBJ017"}, "INTEGER8 limits as bit patterns: 0..-1"),
    "kacanopen__605.3150.71-A-EK-2-60.eds": ({"OBJ015", "OBJ017"},
                                             "INTEGER8 limits as bit patterns; a COB-ID above its HighLimit"),
    "kacanopen__CiA_profiles_301.eds": ({"OBJ006", "SYN011"}, "a template: prose as values, ARRAYs without size"),
    "kacanopen__Easy-ak_v1.30.eds": ({"OBJ010", "SYN003"}, "UNSIGNED32 sub0 of 0x1003; duplicate keys"),
    "kacanopen__roboteq_motor_controllers_v2.0-30-01-2019.eds": ({"OBJ011", "PDO008"},
                                                                 "TPDO5 mapping without its communication object"),
    "kacanopen__roboteq_motor_controllers_v80beta-old.eds": ({"PDO008"},
                                                             "TPDO5 mapping without its communication object"),
    "mabcandle__MD80_latest.eds": ({"OBJ011", "OBJ017"}, "sub0 6 over 2 sub-objects; defaults outside limits"),
    "nodecanopen__test.eds": ({"OBJ012"}, "DataType 0x0020 neither basic nor defined"),
    "nodecanopen__tiny_sample.eds": ({"COM010", "OBJ010"}, "a record with a VISIBLE_STRING sub0"),
    "oresatmon__oresat_c3.dcf": ({"PDO003", "PDO005"}, "mapping lengths unlike their objects; 128-bit RPDOs"),
    "pycanopen__sample.eds": ({"OBJ006", "OBJ010", "OBJ012", "PDO001"},
                              "test file: maps absent objects, REAL32 sub0, undefined type"),
    "pycanopen__sample.xdd": ({"OBJ015", "OBJ017", "PDO001"}, "LowLimit above HighLimit; maps absent objects"),
    "pycanopen__sender.eds": ({"OBJ006", "OBJ011", "PDO002", "SYN016"},
                              "CompactSubObj=255; maps an entry with PDOMapping=0"),
    "pycanopen__sensor.eds": ({"PDO002", "SYN016"}, "CompactSubObj=255; maps an entry with PDOMapping=0"),
    "roscanopen__Elmo.dcf": ({"PDO003"}, "a 64-bit object mapped as 32 bits, which the odg runtime refuses"),
    "roscanopen__Schunk.eds": ({"PDO004"}, "an RPDO maps a read-only entry"),
    "roscanopen__prbt_0_1.dcf": ({"OBJ010"}, "an ARRAY without sub0"),
    "victron__curtis_e.eds": ({"OBJ010"}, "0x1018 without sub0"),
    "victron__emsiso.eds": ({"OBJ011"}, "read-only sub0 announces sub-objects that do not exist"),
    "wustsat__lora.xdc": ({"XML002"}, "a PROFINET GSDML profile, not CANopen"),
}


def test_refused_corpus_files_are_refused_for_blocking_findings_as_listed() -> None:
    files = corpus_files()
    if not files:
        pytest.skip("../shared/corpus is absent")
    got = {}
    for path in files:
        name, result = path.name, generate(Request(path, name="od"))
        if result.files:
            continue
        assert result.refused and all(d.blocks for d in result.refused), f"{name}: refused without a blocking finding"
        got[name] = {d.rule for d in result.refused}
    assert got == {name: rules for name, (rules, _) in REFUSED.items()}


def _compiler(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is missing: `make test` installs it (make sysdeps)"
    return path


def test_every_other_corpus_file_generates_compiles_and_checks() -> None:
    files = [p for p in corpus_files() if p.name not in REFUSED]
    if not files:
        pytest.skip("../shared/corpus is absent")
    failures, lines = [], []
    for path in files:
        for cc in ("gcc", "clang"):
            outcome = run_check(Request(path, name="od"), cc=_compiler(cc))
            summary = outcome.output.strip().splitlines()[-1] if outcome.output.strip() else "not generated"
            accepted = len([d for d in outcome.result.diags if d.severity.label != "info"])
            lines.append(f"| {path.name} | {cc} | {accepted} | {'ok' if outcome.ok else 'FAILED'} | {summary} |")
            if not outcome.ok:
                failures.append(f"{path.name} ({cc}): {outcome.output[-800:] or outcome.result.refused}")
    BUILD.mkdir(parents=True, exist_ok=True)
    (BUILD / "corpus-check.md").write_text(
        f"# odgen check on the {len(files)} corpus files that generate\n\n"
        "| file | cc | findings accepted | result | self-test |\n|---|---|---|---|---|\n"
        + "\n".join(lines) + "\n", encoding="utf-8")
    assert not failures, "\n\n".join(failures)
