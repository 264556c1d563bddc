"""The network file's configuration and wiring (docs/network.md): each NET rule it can break, at
the line of the network file that breaks it; a refused network writes nothing."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from odgen.cli import main
from odgen.diagnostics import Diagnostics
from odgen.lint.netfile import parse_network

from .conftest import FIXTURES

BAD = FIXTURES / "network" / "config" / "bad.toml"


def _findings(capsys: pytest.CaptureFixture[str], toml: Path) -> tuple[int, set[tuple[str, str, int]]]:
    code = main(["lint", "--format", "json", "--select", "NET", "--network", str(toml)])
    doc = json.loads(capsys.readouterr().out)
    return code, {(d["rule"], Path(d["file"]).name, d["line"]) for f in doc["files"] for d in f["diagnostics"]}


def test_each_mistake_at_its_line(capsys: pytest.CaptureFixture[str]) -> None:
    code, found = _findings(capsys, BAD)
    assert code == 1
    assert {
        ("NET013", "bad.toml", 10),  # heartbeat 500 ms, the slave produces every 800 ms
        ("NET011", "bad.toml", 11),  # vendor_id contradicts 0x1018sub1
        ("NET009", "bad.toml", 13),  # 0x1000 is ro
        ("NET010", "bad.toml", 14),  # 70000 in an UNSIGNED16
        ("NET008", "bad.toml", 15),  # no such name
        ("NET008", "bad.toml", 17),  # a name of two entries
        ("NET001", "bad.toml", 25),  # unknown key
        ("NET010", "bad.toml", 27),  # above HighLimit
        ("NET008", "bad.toml", 28),  # no such sub-entry
        ("NET004", "bad.toml", 29),  # the configured COB-ID is another node's TPDO's
        ("NET012", "bad.toml", 31),  # UNSIGNED16 wired to UNSIGNED8
        ("NET012", "bad.toml", 38),  # the producer has no TPDO2
        ("NET012", "bad.toml", 45),  # UNSIGNED32 wired to UNSIGNED8
    } <= found


def test_serial_of_a_generic_description_is_not_a_mismatch(capsys: pytest.CaptureFixture[str]) -> None:
    _, found = _findings(capsys, BAD)  # io: serial = 7, io-node.eds's 0x1018sub4 is 0 (any unit)
    assert ("NET011", "bad.toml", 24) not in found


def test_refused_network_writes_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    assert main(["network", str(BAD), "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert "bad.toml:14: error[NET010]" in err and "nothing written" in err
    assert not out.exists()


def test_network_needs_a_master(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["network", str(FIXTURES / "network" / "ok.toml"), "-o", str(tmp_path / "out")]) == 2
    assert "needs a [master]" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_master_declaring_the_boot_status_object(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    eds = (FIXTURES / "network" / "master.eds").read_text()
    (tmp_path / "master.eds").write_text(eds + "\n[5F81]\nParameterName=Mine\nObjectType=0x7\nDataType=0x0005\n"
                                         "AccessType=rw\nDefaultValue=0\n")
    (tmp_path / "slave_a.eds").write_text((FIXTURES / "network" / "slave_a.eds").read_text())
    (tmp_path / "net.toml").write_text('[master]\nfile = "master.eds"\nnode_id = 1\n'
                                       '[[node]]\nfile = "slave_a.eds"\nnode_id = 2\n')
    _, found = _findings(capsys, tmp_path / "net.toml")
    assert any(rule == "NET014" and name == "master.eds" for rule, name, _ in found)


def test_heartbeat_without_producer(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "slave_a.eds").write_text((FIXTURES / "network" / "slave_a.eds").read_text())
    (tmp_path / "net.toml").write_text('[[node]]\nfile = "slave_a.eds"\nnode_id = 2\nheartbeat = 300\n'
                                       '[node.values]\n"0x1017" = 0\n')
    _, found = _findings(capsys, tmp_path / "net.toml")
    assert ("NET013", "net.toml", 4) in found


def test_lines_of_tables_and_keys() -> None:
    text = ('[master]\nfile = "m.eds"\nnode_id = 1\n\n[[node]]\nfile = "a.eds"\nnode_id = 2\n'
            '[node.values]\n"0x1017" = 100\n\n[[node]]\nname = "b"\nfile = "b.eds"\nnode_id = 3\n'
            'heartbeat = 200\n[node.values]\n  Setpoint = 5\n"0x1017" = 150\n'
            '[[pdo]]\nfrom = "b"\ntpdo = 1\nto = "master"\nrpdo = 1\nentries = [\n  ["x", "y"],\n]\n')
    diags = Diagnostics()
    spec = parse_network(text, Path("net.toml"), diags)
    assert not list(diags)
    master, a, b = spec.nodes
    assert (master.master, master.loc.line, a.loc.line, b.loc.line) == (True, 1, 5, 11)
    assert [(s.key, s.line) for s in a.settings] == [("0x1017", 9)]
    assert [(s.key, s.line) for s in b.settings] == [("Setpoint", 17), ("0x1017", 18)]
    assert b.line("heartbeat") == 15 and b.name == "b" and a.name == "node2"
    assert spec.pdos[0].loc.line == 19 and spec.pdos[0].entries == (("x", "y"),)


@pytest.mark.parametrize(("text", "line", "words"), [
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\nmandatory = "yes"\n', 4, "must be true or false"),
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\nheartbeat = 70000\n', 4, "must be an integer 0..65535"),
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\n[[node]]\nname = "node2"\nfile = "b.eds"\nnode_id = 3\n', 5,
     "is also the node at line 1"),
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\n[[pdo]]\nfrom = "a"\ntpdo = 0\nto = "b"\nrpdo = 1\n'
     'entries = [["x", "y"]]\n', 6, "`tpdo` must be an integer 1..512"),
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\n[[pdo]]\nfrom = "a"\ntpdo = 1\nto = "b"\nrpdo = 1\n'
     'entries = ["x"]\n', 9, "entries"),
    ('[[node]]\nfile = "a.eds"\nnode_id = 2\n[other]\nx = 1\n', 1, "unknown table or key `other`"),
])
def test_file_mistakes(text: str, line: int, words: str) -> None:
    diags = Diagnostics()
    parse_network(text, Path("net.toml"), diags)
    assert [(d.rule, d.loc.line) for d in diags if words in d.message] == [("NET001", line)], list(diags)


def test_values_from_a_dcf(tmp_path: Path) -> None:
    """`dcf = ...`: its ParameterValues that differ from the description's are configured, under
    `[node.values]`; the concise DCF holds them, as a reader written from CiA 306 decodes it."""
    from .test_concise import _cia306_read

    eds = (FIXTURES / "network" / "slave_a.eds").read_text()
    (tmp_path / "slave_a.eds").write_text(eds)
    dcf = eds.replace("[1017]\n", "[1017]\nParameterValue=250\n", 1) \
        .replace("[1400sub2]\n", "[1400sub2]\nParameterValue=254\n", 1) \
        .replace("[2001]\n", "[2001]\nParameterValue=7\n", 1)
    assert dcf.count("ParameterValue") == 3
    (tmp_path / "a.dcf").write_text(dcf)
    (tmp_path / "master.eds").write_text((FIXTURES / "network" / "master.eds").read_text())
    (tmp_path / "net.toml").write_text('[master]\nfile = "master.eds"\nnode_id = 1\n'
                                       '[[node]]\nname = "a"\nfile = "slave_a.eds"\nnode_id = 2\ndcf = "a.dcf"\n'
                                       '[node.values]\n"Process value 16 bit" = 9\n')
    assert main(["network", str(tmp_path / "net.toml"), "-o", str(tmp_path / "out")]) == 0
    entries = _cia306_read((tmp_path / "out" / "a.bin").read_bytes())
    assert entries == [(0x1017, 0, (250).to_bytes(2, "little")), (0x2001, 0, (9).to_bytes(2, "little"))]


def test_master_values_lines() -> None:
    text = ('[[node]]\nfile = "a.eds"\nnode_id = 2\n[node.values]\n"0x1017" = 1\n'
            '[master]\nfile = "m.eds"\nnode_id = 1\n[master.values]\n"0x1017" = 2\n')
    diags = Diagnostics()
    spec = parse_network(text, Path("net.toml"), diags)
    assert not list(diags)
    assert [(n.name, [(s.value, s.line) for s in n.settings]) for n in spec.nodes] == [
        ("master", [(2, 10)]), ("node2", [(1, 5)])]


def test_mapping_of_a_pdo_without_cob_id(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    eds = (FIXTURES / "network" / "slave_a.eds").read_text()
    cut = eds.index("[1800sub1]")
    eds = eds[:cut] + eds[eds.index("[1800sub2]"):]  # TPDO1 without its COB-ID
    (tmp_path / "slave_a.eds").write_text(eds)
    (tmp_path / "net.toml").write_text('[[node]]\nfile = "slave_a.eds"\nnode_id = 2\n[node.values]\n'
                                       '"0x1A00sub1" = 0x20010010\n')
    _, found = _findings(capsys, tmp_path / "net.toml")
    assert ("NET009", "net.toml", 5) in found


def _network(tmp_path: Path, body: str) -> Path:
    for name in ("master.eds", "slave_a.eds", "slave_b.eds"):
        (tmp_path / name).write_text((FIXTURES / "network" / name).read_text())
    (tmp_path / "net.toml").write_text('[master]\nfile = "master.eds"\nnode_id = 1\n'
                                       '[[node]]\nname = "a"\nfile = "slave_a.eds"\nnode_id = 2\n'
                                       '[[node]]\nname = "b"\nfile = "slave_b.eds"\nnode_id = 3\n' + body)
    return tmp_path / "net.toml"


def test_names_ignore_case_spaces_and_underscores(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from .test_concise import _cia306_read

    net = _network(tmp_path, '[node.values]\n"producer_HEARTBEAT   time" = 120\n')
    assert main(["network", str(net), "-o", str(tmp_path / "out")]) == 0
    assert _cia306_read((tmp_path / "out" / "b.bin").read_bytes()) == [(0x1017, 0, (120).to_bytes(2, "little"))]
    assert "\n[DeviceComissioning]\nNodeID=0x03\n" in (tmp_path / "out" / "b.dcf").read_text()


@pytest.mark.parametrize(("body", "line", "words"), [
    # two tables set master's RPDO1 two ways
    ('[[pdo]]\nfrom = "a"\ntpdo = 1\nto = "master"\nrpdo = 1\nentries = [["0x2000", "0x2000"]]\n'
     '[[pdo]]\nfrom = "b"\ntpdo = 1\nto = "master"\nrpdo = 1\nentries = [["0x2001", "0x2001"]]\n', 18,
     "this wiring sets"),
    # 3 x 32 bit
    ('[[pdo]]\nfrom = "a"\ntpdo = 1\nto = "master"\nrpdo = 1\n'
     'entries = [["0x2002", "0x2002"], ["0x2002", "0x2002"], ["0x2002", "0x2002"]]\n', 12, "96 bit mapped"),
    # TPDO5 has no predefined COB-ID
    ('[[pdo]]\nfrom = "a"\ntpdo = 5\nto = "master"\nrpdo = 1\nentries = [["0x2000", "0x2000"]]\n', 12,
     "give `cob_id`"),
    # a node the network does not have
    ('[[pdo]]\nfrom = "c"\ntpdo = 1\nto = "master"\nrpdo = 1\nentries = [["0x2000", "0x2000"]]\n', 13,
     "is no node of the network"),
])
def test_wiring_mistakes(tmp_path: Path, body: str, line: int, words: str) -> None:
    from odgen.lint.driver import RuleFilter
    from odgen.lint.network import lint_network_nodes
    from odgen.lint.passes import LintOptions

    linted = lint_network_nodes(_network(tmp_path, body), LintOptions(), RuleFilter())
    found = [(d.rule, d.loc.line) for r in linted.results for d in r.diagnostics if words in d.message]
    assert found and found[0][1] == line and found[0][0] in ("NET001", "NET012"), found


def test_one_tpdo_feeds_two_consumers(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    wire = '[[pdo]]\nfrom = "a"\ntpdo = 1\nto = "{}"\nrpdo = 1\nentries = [["0x2000", "0x2000"]]\n'
    net = _network(tmp_path, wire.format("master") + wire.format("b"))
    _, found = _findings(capsys, net)
    assert not {f for f in found if f[0] in ("NET004", "NET006", "NET012")}, found


@pytest.mark.parametrize(("keys", "startup"), [
    ("", 0x01),
    ("start_all = true\n", 0x03),
    ("start_self = false\n", 0x05),
    ("start_slaves = false\n", 0x09),
    ("reset_all = true\nstop_all = true\n", 0x51),
])
def test_nmt_startup_bits(tmp_path: Path, keys: str, startup: int) -> None:
    import canopen

    net = _network(tmp_path, "")
    net.write_text(net.read_text().replace("node_id = 1\n", "node_id = 1\n" + keys, 1))
    assert main(["network", str(net), "-o", str(tmp_path / "out")]) == 0
    od = canopen.import_od(str(tmp_path / "out" / "master.dcf"), 1)
    assert od[0x1F80].default == startup
    assert [od[0x1F81][n].default for n in (2, 3)] == [0x05, 0x05]  # slave, booted again after an error
