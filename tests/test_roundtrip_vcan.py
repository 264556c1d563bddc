"""odgen roundtrip on a CAN bus: the examples and every corpus file odgen generates, in one vcan session.

Node programs are built on the host first (into a cache the guest shares), then one run of
tools/vcan/run.py checks them all: on the host's vcan when it has one, else inside one
User-Mode Linux guest. The per-check results land in build/test-reports/roundtrip.json.
"""

from __future__ import annotations

import json
import os
import sys

import pytest

from odgen.pipeline import Request
from odgen.formats import load_path
from odgen.roundtrip import ROUNDTRIP_DEFAULTS
from odgen.roundtrip.build import build_node
from odgen.errors import OdgenError
from odgen.roundtrip.checks import reachable_sdo_server, sdo_server_cob_ids

from .conftest import BUILD, ROOT, corpus_files, generates

CACHE = ROOT / "build" / "node-cache"


def sdo_reachable(path) -> bool:
    """Whether the node built from `path` answers SDO at all (0x1200 may disable its server)."""
    od = load_path(path)[0]
    return od is not None and sdo_server_cob_ids(od, 5) is not None


def vcan_files() -> list:
    """The descriptions checked on a bus (here and by tests/test_conformance.py): the example and
    every corpus file `odgen generate` accepts whose SDO server is not disabled by 0x1200 (both
    tools refuse those: test_disabled_sdo_server_refused)."""
    return [ROOT / "examples" / "io-node" / "io-node.eds"] + [p for p in corpus_files() if generates(p)
                                                             and sdo_reachable(p)]


def test_disabled_sdo_server_refused(tmp_path) -> None:
    """A description whose 0x1200 disables the default SDO server leaves a round trip or a
    conformance run nothing to talk to: both say so instead of timing out on every request."""
    from .test_conformance import PDO_NODE, sdo_server_at

    off = sdo_server_at(PDO_NODE, tmp_path / "off.eds", "0x80000000", "$NODEID+0x580")
    disabled = [off] + [p for p in corpus_files() if generates(p) and not sdo_reachable(p)]
    for path in disabled:
        od = load_path(path)[0]
        assert od is not None
        with pytest.raises(OdgenError, match="0x1200 disables the default SDO server"):
            reachable_sdo_server(od, 5, path)
    od = load_path(PDO_NODE)[0]
    assert od is not None and reachable_sdo_server(od, 5, PDO_NODE) == (0x605, 0x585)


def test_roundtrip_examples_and_corpus_on_vcan(vcan_bus) -> None:
    files = vcan_files()
    env = dict(os.environ, ODGEN_CACHE=str(CACHE))
    os.environ["ODGEN_CACHE"] = str(CACHE)
    try:
        for path in files:
            build_node(Request(path, name="od", node_id=5, defaults=ROUNDTRIP_DEFAULTS))
    finally:
        os.environ.pop("ODGEN_CACHE", None)
    report = BUILD / "roundtrip.json"
    BUILD.mkdir(parents=True, exist_ok=True)
    cmd = [sys.executable, "-m", "odgen", "roundtrip", "--report", str(report), *map(str, files)]
    run = vcan_bus.run(cmd, env=env, cwd=ROOT, timeout=1200)
    assert report.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    doc = json.loads(report.read_text())
    failed = [f for f in doc["files"] if not f["ok"]]
    assert not failed, run.stdout[-6000:]
    assert run.returncode == 0 and len(doc["files"]) == len(files)
