"""`odgen lint --network NET.toml`: each NET rule on a failing network, a clean network, SARIF."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from odgen.cli import main

from .conftest import FIXTURES
from .test_cli import _sarif_schema

NET = FIXTURES / "network"


def _lint(capsys: pytest.CaptureFixture[str], toml: str, *extra: str) -> tuple[int, list[dict]]:
    code = main(["lint", "--format", "json", "--network", str(NET / toml), *extra])
    doc = json.loads(capsys.readouterr().out)
    return code, [d for f in doc["files"] for d in f["diagnostics"]]


def _net(findings: list[dict]) -> list[tuple[str, str, int, str]]:
    return [(d["rule"], Path(d["file"]).name, d["line"], d["text"].split(": ", 1)[1])
            for d in findings if d["rule"].startswith("NET")]


@pytest.mark.parametrize(("toml", "code", "expected"), [
    ("NET001.toml", 1, ("NET001", "NET001.toml", 5,
                        "error[NET001]: [[node]] needs `file` (a string) and `node_id` (an integer)")),
    ("NET002.toml", 1, ("NET002", "NET002.toml", 5, "error[NET002]: node_id 1 is also the node at line 1")),
    ("NET003.toml", 2, ("NET003", "NET003.toml", 5, "error[NET003]: " + str(NET / "missing.eds")
                        + ": cannot read: No such file or directory")),
    ("NET004.toml", 1, ("NET004", "dup.eds", 87, "error[NET004]: 0x1800sub1 node 4 TPDO1 transmits COB-ID "
                        f"0x182, as node 2 TPDO1 does ({NET / 'slave_a.eds'}:135)")),
    ("NET005.toml", 0, ("NET005", "master.eds", 139, "warning[NET005]: 0x1401sub1 node 1 RPDO2 receives "
                        "COB-ID 0x183, which no node transmits")),
    ("NET006.toml", 1, ("NET006", "master.eds", 162, "error[NET006]: 0x1601sub1 node 1 RPDO2 maps 1 entry "
                        f"(16 bit) but node 3 TPDO1 ({NET / 'slave_a.eds'}:135) transmits 2 entries (8, 8 bit)")),
    ("NET007.toml", 1, ("NET007", "emcy.eds", 87, "error[NET007]: 0x1800sub1 node 4 TPDO1 uses COB-ID 0x83, "
                        "the EMCY COB-ID of node 3")),
    ("NET015.toml", 0, ("NET015", "NET015.toml", 25, "warning[NET015]: 0x1800sub2 a: TPDO1 (transmission type 1) "
                        "transmits only at SYNC, and no node of the network produces SYNC (0x1005 bit 30 and "
                        "0x1006 > 0)")),
])
def test_each_rule_is_located(toml: str, code: int, expected: tuple[str, str, int, str],
                              capsys: pytest.CaptureFixture[str]) -> None:
    got, findings = _lint(capsys, toml)
    assert got == code
    assert expected in _net(findings)


# NET015.toml with one change: the clock produces SYNC (bit 30 and a period), the PDO is event-driven,
# or the clock is set to generate with no period, or the PDO is wired off
@pytest.mark.parametrize(("change", "warned"), [
    ('"0x1006" = 10000\n', ('"0x1005" = 0x40000080\n"0x1006" = 10000\n', False)),
    ("transmission = 1\n", ("transmission = 254\n", False)),
    ('"0x1006" = 10000\n', ('"0x1005" = 0x40000080\n"0x1006" = 0\n', True)),
    ("transmission = 1\n", ("transmission = 252\n", True)),  # a TPDO sampled at SYNC, sent on request
])
def test_sync_producer_silences_net015(change: str, warned: tuple[str, bool], tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    text = (NET / "NET015.toml").read_text(encoding="utf-8").replace('file = "', f'file = "{NET}/')
    assert change in text
    text = text.replace(change, warned[0])
    (tmp_path / "net.toml").write_text(text, encoding="utf-8")
    line = next(n for n, ln in enumerate(text.splitlines(), 1) if ln.startswith("transmission"))
    code = main(["lint", "--format", "json", "--network", str(tmp_path / "net.toml")])
    doc = json.loads(capsys.readouterr().out)
    found = [(d["line"], d["text"]) for f in doc["files"] for d in f["diagnostics"] if d["rule"] == "NET015"]
    assert code == 0
    if warned[1]:
        assert found and all(at == line for at, _ in found), found
    else:
        assert found == []


@pytest.mark.parametrize(("values", "line"), [
    ('"0x1800sub2" = 1\n', 5),  # configured synchronous, not wired: at its line
    ('"0x1A00sub0" = 1\n', 5),  # its mapping configured, synchronous as described (0x1800sub2 = 1 below)
    ('"0x1800sub2" = 1\n"0x1800sub1" = 0x80000182\n', None),  # switched off
])
def test_net015_on_configured_pdos(values: str, line: int | None, tmp_path: Path,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    eds = (NET / "slave_a.eds").read_text(encoding="utf-8")
    (tmp_path / "a.eds").write_text(eds.replace("[1800sub2]\nParameterName=Transmission type\nDataType=0x0005\n"
                                                "AccessType=rw\nDefaultValue=254",
                                                "[1800sub2]\nParameterName=Transmission type\nDataType=0x0005\n"
                                                "AccessType=rw\nDefaultValue=1"), encoding="utf-8")
    (tmp_path / "net.toml").write_text(f'[[node]]\nfile = "a.eds"\nnode_id = 2\n[node.values]\n{values}',
                                       encoding="utf-8")
    assert main(["lint", "--format", "json", "--select", "NET015", "--network", str(tmp_path / "net.toml")]) == 0
    doc = json.loads(capsys.readouterr().out)
    found = [(d["line"], d["index"]) for f in doc["files"] for d in f["diagnostics"]]
    assert found == ([] if line is None else [(line, 0x1800)])


def test_node_id_out_of_range(capsys: pytest.CaptureFixture[str]) -> None:
    _, findings = _lint(capsys, "NET002.toml")
    assert ("NET002", "NET002.toml", 9, "error[NET002]: node_id 128 is outside 1..127") in _net(findings)


def test_warning_fails_under_strict(capsys: pytest.CaptureFixture[str]) -> None:
    assert _lint(capsys, "NET005.toml", "--strict")[0] == 1


def test_clean_network_has_no_net_findings(capsys: pytest.CaptureFixture[str]) -> None:
    code, findings = _lint(capsys, "ok.toml")
    assert code == 0 and _net(findings) == []
    files = {Path(d["file"]).name for d in findings}
    assert files <= {"master.eds", "slave_a.eds", "slave_b.eds"}  # the nodes are linted too


def test_node_ids_apply_to_nodeid_values(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the slaves swap node-ids: $NODEID+0x180 now puts each slave's TPDO1 on the other's COB-ID
    net = tmp_path / "NET.toml"
    net.write_text("".join(f'[[node]]\nfile = "{NET / f}"\nnode_id = {n}\n'
                           for f, n in (("master.eds", 1), ("slave_a.eds", 3), ("slave_b.eds", 2))))
    assert main(["lint", "--network", str(net), "--select", "NET"]) == 1
    out = capsys.readouterr().out
    assert "master.eds:116: error[NET006]: 0x1600sub1 node 1 RPDO1 maps 2 entries (8, 8 bit) but node 2 TPDO1" in out
    assert "master.eds:162: error[NET006]: 0x1601sub1 node 1 RPDO2 maps 1 entry (16 bit) but node 3 TPDO1" in out


def test_select_filters_network_findings(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", "--network", str(NET / "NET007.toml"), "--ignore", "NET007"]) == 0
    assert "NET007" not in capsys.readouterr().out


def test_sarif_of_a_network_is_valid(tmp_path: Path) -> None:
    out = tmp_path / "net.sarif"
    assert main(["lint", "--format", "sarif", "-o", str(out), "--network", str(NET / "NET006.toml")]) == 1
    doc = json.loads(out.read_text(encoding="utf-8"))
    jsonschema.validate(doc, _sarif_schema())
    hit = next(r for r in doc["runs"][0]["results"] if r["ruleId"] == "NET006")
    assert hit["locations"][0]["physicalLocation"]["region"] == {"startLine": 162}


def test_lint_needs_files_or_network(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint"]) == 2
    assert "--network" in capsys.readouterr().err
