"""The LSS slave end to end: python canopen's LSS master finds an unconfigured node program by
fastscan on vcan0 (tools/vcan: the host's vcan, else a User-Mode Linux guest), assigns node-id
10 and stores it; the node boots as node 10, answers SDO, and comes up as node 10 after a
restart. The fake-bus tests of every LSS command are tests/node/test_node_lss.c (test_node.py).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from .cprog import build
from .test_node import LINUX, LSS, NODE_TESTS, PROGRAM_SOURCES, ROOT, RUNTIME, VCAN_RUN, generate


def test_lss_master_configures_unconfigured_node(tmp_path: Path) -> None:
    setup = subprocess.run(["bash", str(ROOT / "tools" / "vcan" / "setup.sh")], capture_output=True, text=True,
                           timeout=600, check=False)
    assert setup.returncode == 0, f"tools/vcan/setup.sh failed:\n{setup.stderr}"
    gen = generate("lss_node", tmp_path / "lss_node")
    exe = tmp_path / "lss-node"
    build("gcc", ("-O2", "-DODG_DICT=lss_node", *LSS), (*PROGRAM_SOURCES, gen / "lss_node.c"), (gen, RUNTIME, LINUX),
          exe)
    cmd = [sys.executable, str(VCAN_RUN), "--rw", str(tmp_path), "--timeout", "150", "--",
           sys.executable, str(NODE_TESTS / "vcan_lss.py"), str(exe), str(tmp_path)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=200, stdin=subprocess.DEVNULL,
                          cwd=ROOT)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "vcan lss: ok", output[-6000:]
