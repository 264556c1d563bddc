"""odgen roundtrip on a CAN bus: the example and the corpus files odgen generates, in one vcan session
(a sample of them in `make test`, every one in `make corpus`: CORPUS_SAMPLE in tests/conftest.py).

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
from odgen.conformance.client import reachable_sdo_server, sdo_server_cob_ids

from .conftest import BUILD, CORPUS, CORPUS_SAMPLE, ROOT, corpus_files, corpus_sample, generates

CACHE = ROOT / "build" / "node-cache"


def sdo_reachable(path) -> bool:
    """Whether the node built from `path` answers SDO at all (0x1200 may disable its server)."""
    od = load_path(path)[0]
    return od is not None and sdo_server_cob_ids(od, 5) is not None


def vcan_files() -> list:
    """The descriptions checked on a bus (here and by tests/test_conformance.py): the example and
    the corpus files `odgen generate` accepts whose SDO server is not disabled by 0x1200 (both
    tools refuse those: test_disabled_sdo_server_refused), those of the sample (CORPUS_SAMPLE in
    tests/conftest.py) in `make test`, every one in `make corpus`."""
    return [ROOT / "examples" / "io-node" / "io-node.eds"] + [p for p in corpus_sample(corpus_files()) if generates(p)
                                                             and sdo_reachable(p)]


def test_corpus_sample_goes_on_the_bus() -> None:
    """Every file of the sample is in the corpus and is one the bus tests take: a file renamed, or
    refused since it was chosen, would shrink the sample without a word."""
    if not corpus_files():
        pytest.skip("../shared/corpus is absent")
    sample = [CORPUS / name for name in CORPUS_SAMPLE]
    assert [p.name for p in sample if not (p.is_file() and generates(p) and sdo_reachable(p))] == []


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
    # the round trip's own checks here: the conformance battery runs against the same nodes in
    # tests/test_conformance.py, and below against one through `odgen roundtrip`
    cmd = [sys.executable, "-m", "odgen", "roundtrip", "--select", "roundtrip", "--report", str(report),
           *map(str, files)]
    run = vcan_bus.run(cmd, env=env, cwd=ROOT, timeout=1200)
    assert report.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    doc = json.loads(report.read_text())
    failed = [f for f in doc["files"] if not f["ok"]]
    assert not failed, run.stdout[-6000:]
    assert run.returncode == 0 and len(doc["files"]) == len(files)


def test_roundtrip_runs_the_battery(vcan_bus, tmp_path) -> None:
    """`odgen roundtrip` builds the node and runs the conformance battery against it with every
    check allowed and what the build stores known, so checks a foreign device may skip run here:
    save/load, the resets, the heartbeat consumer; --ignore takes the battery's ids too."""
    from .test_conformance import EXAMPLE, PDO_NODE

    env = dict(os.environ, ODGEN_CACHE=str(CACHE))
    report = tmp_path / "report.json"
    cmd = [sys.executable, "-m", "odgen", "roundtrip", "--report", str(report), "--ignore", "roundtrip.,sdo.limits",
           str(EXAMPLE), str(PDO_NODE)]
    run = vcan_bus.run(cmd, env=env, cwd=ROOT, timeout=600)
    assert report.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    assert run.returncode == 0, run.stdout[-4000:]
    example, pdo = ({c["id"]: c for c in f["checks"]} for f in json.loads(report.read_text())["files"])
    assert "roundtrip.uploads" not in example and "sdo.limits" not in example and "sdo.lengths" in example
    for checks, ran in ((example, "store.save-load"), (example, "nmt.boot-up"), (example, "nmt.reset-comm"),
                        (example, "sdo.upload"), (pdo, "nmt.hb-consumer"), (pdo, "emcy.error-register")):
        assert not checks[ran]["skipped"] and checks[ran]["passed"] and not checks[ran]["failed"], checks[ran]


def test_roundtrip_without_block_transfer(vcan_bus, tmp_path) -> None:
    """A node built with `[node] sdo_block = false` answers block initiates with abort 0x05040001, as
    CiA 301 allows: the round trip's strings check notes that block transfer is not supported and
    still checks the segmented transfers, and the battery's SDO checks pass."""
    options = tmp_path / "noblock.toml"
    options.write_text("[node]\nsdo_block = false\n", encoding="utf-8")
    report = tmp_path / "report.json"
    cmd = [sys.executable, "-m", "odgen", "roundtrip", "--report", str(report), "--options", str(options),
           "--select", "roundtrip.strings,sdo", str(ROOT / "tests" / "fixtures" / "generate" / "alltypes.eds")]
    run = vcan_bus.run(cmd, env=dict(os.environ, ODGEN_CACHE=str(CACHE)), cwd=ROOT, timeout=600)
    assert report.is_file(), run.stdout[-3000:] + run.stderr[-3000:]
    assert run.returncode == 0, run.stdout[-4000:]
    checks = {c["id"]: c for c in json.loads(report.read_text())["files"][0]["checks"]}
    strings = checks["roundtrip.strings"]
    assert strings["passed"] and not strings["failed"] and not strings["skipped"], strings
    assert [n.split(":")[0] for n in strings["notes"]] == ["block download not supported",
                                                           "block upload not supported"], strings
    assert "note: block download not supported" in run.stdout
    assert {"sdo.upload", "sdo.limits", "sdo.lengths"} <= set(checks)
    assert all(not c["failed"] for c in checks.values()), checks
