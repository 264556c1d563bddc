"""The blocking policy's non-blocking contradictions (docs/generate.md, docs/rules.md): a file that
contradicts itself where the node can still do what it describes generates with a warning, and the
node built from it is compiled and run (odgen check's self-test, and tests/node/test_node_policy.c
over the fake CAN transport); the same findings where the node could not do so still block."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from odgen.check import run_check
from odgen.pipeline import Request, generate

from .conftest import FIXTURES
from .cprog import BUILDS, build, run
from .test_node import CHECK_H, CORE, NODE, NODE_TESTS, RUNTIME

POLICY = FIXTURES / "policy" / "policy-node.eds"
# rule -> the finding's subject, each a warning that does not block
WARNED = {("OBJ015", 0x2000, None), ("OBJ017", 0x2000, None), ("OBJ017", 0x2001, None),
          ("PDO002", 0x1600, 1), ("PDO002", 0x1A00, 1), ("PDO004", 0x1601, 1)}


def test_contradictions_the_node_can_serve_are_warnings() -> None:
    result = generate(Request(POLICY, name="policy_node"))
    assert result.files, [d.text() for d in result.refused]
    found = {(d.rule, d.index, d.sub) for d in result.diags if d.rule in ("OBJ015", "OBJ017", "PDO002", "PDO004")}
    assert found == WARNED
    assert all(d.severity.label == "warning" and not d.blocks for d in result.diags if d.rule in ("OBJ015", "OBJ017",
                                                                                                  "PDO002", "PDO004"))
    assert result.view is not None and not result.view.limits  # 0x2000 and 0x2001 are the only entries with limits


@pytest.mark.parametrize("node_id", [5, 127])
def test_generated_dictionary_passes_its_self_test(node_id: int) -> None:
    """At node-id 127 0x2001 ($NODEID+0x180) lies above its HighLimit 0x18F: the table check passes."""
    outcome = run_check(Request(POLICY, name="policy_node", node_id=node_id), cc=shutil.which("gcc") or "gcc")
    assert outcome.ok, outcome.output[-3000:]


@pytest.fixture(scope="module")
def policy_dict(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("policy")
    result = generate(Request(POLICY, name="policy_node"))
    for name, text in result.files.items():
        (out / name).write_text(text, encoding="utf-8")
    return out


@pytest.mark.parametrize("build_name", ["clang", "gcc-sanitize"])
def test_node_does_what_the_file_describes(build_name: str, policy_dict: Path, tmp_path: Path) -> None:
    cc, flags = BUILDS[build_name]
    exe = tmp_path / "test_node_policy"
    sources = (NODE_TESTS / "test_node_policy.c", policy_dict / "policy_node.c", *CORE, *NODE)
    build(cc, flags, sources, (policy_dict, RUNTIME, NODE_TESTS, CHECK_H), exe)
    run(exe, tmp_path)


def _section(text: str, name: str) -> tuple[int, int]:
    start = text.index(f"[{name}]\n")
    end = text.find("\n[", start + 1)
    return start, len(text) if end < 0 else end + 1


def _edit(text: str, section: str, old: str, new: str) -> str:
    start, end = _section(text, section)
    body = text[start:end]
    assert old in body, (section, old)
    return text[:start] + body.replace(old, new) + text[end:]


# The same contradictions where the node could not do what the file says: each still blocks.
BLOCKING = {
    "limits of a writable entry": (("2000", "AccessType=ro", "AccessType=rw"), {"OBJ015", "OBJ017"}),
    "a default a master could not write back": (("2001", "AccessType=ro", "AccessType=rw"), {"OBJ017"}),
    "an enabled PDO mapping a read-only entry": (("1401sub1", "$NODEID+0x80000300", "$NODEID+0x300"), {"PDO004"}),
    "an unmappable type": (("2004", "DataType=0x0006", "DataType=0x0009"), {"PDO002"}),
    "a dummy the runtime would serve against [DummyUsage]": (("1601sub1", "0x20030010", "0x00050008"), {"PDO001"}),
    "a disabled PDO whose COB-ID a node-id enables": (("1401sub1", "$NODEID+0x80000300", "$NODEID+0x7FFFFF90"),
                                                      {"PDO004"}),
}


@pytest.mark.parametrize("case", list(BLOCKING))
def test_where_the_node_could_not_the_finding_blocks(case: str, tmp_path: Path) -> None:
    (section, old, new), rules = BLOCKING[case]
    path = tmp_path / "policy-node.eds"
    path.write_text(_edit(POLICY.read_text(encoding="utf-8"), section, old, new), encoding="utf-8")
    result = generate(Request(path, name="policy_node"))
    assert not result.files
    assert {d.rule for d in result.refused} == rules, [d.text() for d in result.refused]


@pytest.mark.parametrize("asked", ["", "rom"])
def test_const_nodeid_value_lives_in_ram_unless_rom_is_asked(asked: str, tmp_path: Path) -> None:
    """A const entry with a $NODEID value (OBJ030) is worked out at start-up: the automatic rule places it
    in RAM, read-only as before; an options file that asks for rom still gets GEN003."""
    path = tmp_path / "policy-node.eds"
    path.write_text(_edit(POLICY.read_text(encoding="utf-8"), "2001", "AccessType=ro", "AccessType=const"),
                    encoding="utf-8")
    options = None
    if asked:
        options = tmp_path / "rom.toml"
        options.write_text('[[entry]]\nmatch = "0x2001"\nstorage = "rom"\n', encoding="utf-8")
    result = generate(Request(path, name="policy_node", options=options))
    if asked:
        assert not result.files and {d.rule for d in result.refused} == {"GEN003"}
        return
    assert result.files and result.placements is not None
    assert result.placements[(0x2001, 0)].storage == "ram"
    outcome = run_check(Request(path, name="policy_node"), cc=shutil.which("gcc") or "gcc")
    assert outcome.ok, outcome.output[-3000:]
