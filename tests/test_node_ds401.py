"""CiA 401 outputs on communication loss (runtime/profiles/ds401.c, docs/ds401.md): over the fake
transport (tests/node/test_node_ds401.c: heartbeat loss, NMT stop, bus-off, polarity, release by
SDO and RPDO), and on a CAN bus through python canopen: a master's heartbeat stops, and the
node's outputs (looped back to its inputs by examples/ds401-io/sim.c) take their error values.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from odgen import toolchain
from odgen.pipeline import Request
from odgen.profiles.ds401 import generate_c, glue_files, options_toml, write
from odgen.roundtrip.build import build_node

from .conftest import ROOT
from .cprog import BUILDS, build, run
from .test_profile_ds401 import GRID

RUNTIME = ROOT / "runtime"
GLUE = RUNTIME / "profiles" / "ds401.c"
SIM = ROOT / "examples" / "ds401-io" / "sim.c"


@pytest.mark.parametrize("build_name", ["gcc-sanitize"])  # gcc and clang build the glue in test_profile_ds401
def test_outputs_take_error_values_on_a_fake_bus(build_name: str, tmp_path: Path) -> None:
    spec = GRID["16-16-4-4"]
    write(spec, tmp_path / "io.eds")
    for name, text in generate_c(spec, tmp_path / "io.eds").files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    cc, flags = BUILDS[build_name]
    exe = tmp_path / "test_node_ds401"
    build(cc, (*flags, '-DODG_CONFIG="io_config.h"', "-DODG_NODE_TPDO_COS=0"),
          (ROOT / "tests" / "node" / "test_node_ds401.c", GLUE, tmp_path / "io.c", *toolchain.core_sources(),
           *toolchain.service_sources()),
          (tmp_path, RUNTIME, ROOT / "tests" / "node", ROOT / "tests" / "runtime"), exe)
    run(exe, tmp_path)


def test_outputs_take_error_values_when_the_master_heartbeat_stops_on_vcan(tmp_path: Path, vcan_bus) -> None:
    spec = GRID["16-16-4-4"]
    eds = tmp_path / "io.eds"
    write(spec, eds)
    exe, result = build_node(Request(eds, name="io", defaults=options_toml(spec)), extra=glue_files(spec),
                             sources=[SIM, GLUE], defines=["ODG_APP", "ODG_NODE_TPDO_COS=0"])
    assert result.files
    done = vcan_bus.run([sys.executable, str(ROOT / "tests" / "vcan" / "ds401_loss.py"), str(exe), str(eds)],
                        cwd=ROOT, timeout=120)
    output = done.stdout + done.stderr
    assert done.returncode == 0 and done.stdout.strip().splitlines()[-1] == "ds401 loss: ok", output[-6000:]
