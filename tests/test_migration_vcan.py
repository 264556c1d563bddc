"""On vcan: the node built from v1 stores values through 0x1010 written by python-canopen, restarts
as v2 on the same NV file, and python-canopen reads the migrated values, the boot status object and
the storage EMCY (tests/node/vcan_migration.py; tools/vcan: the host's vcan, else a guest)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import CORPUS, ROOT
from .test_migration_runtime import BASE, Param, eds, options
from .test_node import NODE_TESTS, node_program

V2 = (Param(0x2000, 0x07, "7"), BASE[1], Param(0x2002, 0x03, "-5", "-100", "100"), Param(0x2003, 0x07, "42"))


def generate(tmp: Path, tag: str, params: tuple[Param, ...]) -> Path:
    out = tmp / tag
    out.mkdir()
    (out / "od.eds").write_text(eds(params, 1000, False), encoding="utf-8")
    (out / "od.toml").write_text(options(params, "[persist]\nstatus_object = 0x2FF0\n"), encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "odgen", "generate", str(out / "od.eds"), "--name", "od",
                           "--options", str(out / "od.toml"), "-o", str(out)], capture_output=True, text=True,
                          check=False, cwd=ROOT)
    assert done.returncode == 0, done.stdout + done.stderr
    return out


def test_stored_values_migrate_on_vcan(tmp_path: Path, vcan_bus) -> None:
    v1 = node_program("gcc", "od", generate(tmp_path, "v1", BASE), tmp_path / "v1")
    v2 = node_program("gcc", "od", generate(tmp_path, "v2", V2), tmp_path / "v2")
    cmd = [sys.executable, str(NODE_TESTS / "vcan_migration.py"), str(v1), str(v2), str(tmp_path)]
    done = vcan_bus.run(cmd, cwd=ROOT, timeout=180)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "vcan migration: ok", output[-6000:]


def test_canopennode_style_configuration_survives_save_and_reset_on_vcan(tmp_path: Path, vcan_bus) -> None:
    """Issue 25, sequence 1: canopennode__DS301_profile.eds (object-level PERSIST_COMM, sub-level RAM)
    keeps a TPDO's transmission type and event timer, an SDO client's server node-id and the heartbeat
    time across "save" + reset node and a power cycle (tests/node/vcan_canopennode_save.py)."""
    source = CORPUS / "canopennode__DS301_profile.eds"
    if not source.is_file():
        pytest.skip("../shared/corpus is absent")
    out = tmp_path / "gen"
    done = subprocess.run([sys.executable, "-m", "odgen", "generate", str(source), "--name", "od", "-o", str(out)],
                          capture_output=True, text=True, check=False, cwd=ROOT)
    assert done.returncode == 0, done.stdout + done.stderr
    exe = node_program("gcc", "od", out, tmp_path)
    cmd = [sys.executable, str(NODE_TESTS / "vcan_canopennode_save.py"), str(exe), str(tmp_path)]
    done = vcan_bus.run(cmd, cwd=ROOT, timeout=180)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "vcan canopennode save: ok", output[-6000:]
