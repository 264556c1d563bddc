"""The LSS slave: when a node is built with it (`odgen node`: LSS_Supported=1 or the options'
[node] lss), how `odgen node` starts it without --node-id, and end to end: python canopen's LSS
master finds an unconfigured node program by fastscan on vcan0 (tools/vcan: the host's vcan,
else a User-Mode Linux guest), assigns node-id 10 and stores it; the node boots as node 10,
answers SDO, and comes up as node 10 after a restart. The fake-bus tests of every LSS command
are tests/node/test_node_lss.c (run by test_node.py).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from odgen import cli
from odgen.pipeline import Request, generate as generate_dict

from .cprog import build
from .test_node import LINUX, LSS, NODE_TESTS, PROGRAM_SOURCES, ROOT, RUNTIME, generate


def test_lss_master_configures_unconfigured_node(tmp_path: Path, vcan_bus) -> None:
    gen = generate("lss_node", tmp_path / "lss_node")
    exe = tmp_path / "lss-node"
    build("gcc", ("-O2", "-DODG_DICT=lss_node", *LSS), (*PROGRAM_SOURCES, gen / "lss_node.c"), (gen, RUNTIME, LINUX),
          exe)
    cmd = [sys.executable, str(NODE_TESTS / "vcan_lss.py"), str(exe), str(tmp_path)]
    done = vcan_bus.run(cmd, cwd=ROOT, timeout=200)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "vcan lss: ok", output[-6000:]


@pytest.mark.parametrize(("eds", "options", "lss"), [
    ("lss-node.eds", "", True),  # LSS_Supported=1
    ("pdo-node.eds", "", False),  # LSS_Supported=0
    ("pdo-node.eds", "[node]\nlss = true\n", True),
    ("lss-node.eds", "[node]\nlss = false\n", True),  # the description's word stands
])
def test_lss_built_in_when_supported_or_asked(eds: str, options: str, lss: bool, tmp_path: Path) -> None:
    opts = tmp_path / "opts.toml"
    opts.write_text(options, encoding="utf-8")
    result = generate_dict(Request(NODE_TESTS / eds, name="od", options=opts))
    assert result.files and result.lss is lss


@pytest.mark.parametrize("text", ["[node]\nlss = 1\n", "[node]\nlsss = true\n", "node = 3\n"])
def test_node_options_mistakes(text: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    opts = tmp_path / "opts.toml"
    opts.write_text(text, encoding="utf-8")
    assert cli.main(["generate", str(NODE_TESTS / "lss-node.eds"), "--options", str(opts), "-o",
                     str(tmp_path / "out")]) != 0
    err = capsys.readouterr().err
    assert "error[GEN001]" in err
    assert "[node] takes lss and sdo_block = true or false" in err or "[node] has no key 'lsss'" in err


@pytest.mark.parametrize(("eds", "args", "node_args"), [
    ("lss-node.eds", [], []),  # no --node-id: the node waits for an LSS master
    ("lss-node.eds", ["--node-id", "9"], ["--node-id", "9"]),
    ("pdo-node.eds", [], ["--node-id", "5"]),  # no LSS: the default node-id
])
def test_odgen_node_without_node_id(eds: str, args: list[str], node_args: list[str], tmp_path: Path,
                                    monkeypatch: pytest.MonkeyPatch) -> None:
    import odgen.hostneeds

    calls: list[list[str]] = []

    def call(cmd: list[str]) -> int:
        calls.append(cmd)
        return 0

    monkeypatch.setenv("ODGEN_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(odgen.hostneeds, "require_socketcan", lambda iface: None)
    monkeypatch.setattr(subprocess, "call", call)
    assert cli.main(["node", str(NODE_TESTS / eds), "--iface", "vcan9", *args]) == 0
    assert calls and calls[0][1:] == ["--iface", "vcan9", *node_args]
    usage = subprocess.run([calls[0][0]], capture_output=True, text=True, check=False)
    assert ("none: wait for LSS" in usage.stderr) is (eds == "lss-node.eds")  # built with or without LSS
