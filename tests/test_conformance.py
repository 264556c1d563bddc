"""`odgen conformance` on a CAN bus: every node the round trips build passes the battery, and
nodes with an injected defect (tests/conformance/defects.c, one per check family) fail the
check meant to catch it, so each check is shown able to fail.

Node programs are built on the host (cached like the round trips'), then one command in the
shared vcan session runs the battery against each in turn (tests/vcan/conformance_nodes.py).
Per-node results and durations land in build/test-reports/conformance.json; JUnit XML per
node beside it in build/test-reports/conformance/.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from odgen.pipeline import Request
from odgen.roundtrip import ROUNDTRIP_DEFAULTS
from odgen.roundtrip.build import build_node

from .conftest import BUILD, ROOT
from .test_roundtrip_vcan import vcan_files

CACHE = ROOT / "build" / "node-cache"
DEFECTS = ROOT / "tests" / "conformance" / "defects.c"
EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
# ODG_DEFECT number -> the check that must fail (the order of the enum in defects.c)
DEFECT_CHECKS = {1: "sdo.upload", 2: "sdo.limits", 3: "access.read-only", 4: "nmt.states", 5: "nmt.heartbeat",
                 6: "pdo.tpdo-types", 7: "emcy.rpdo-length", 8: "store.signature", 9: "sync.producer",
                 10: "nmt.hb-consumer", 11: "emcy.inhibit", 12: "nmt.guarding", 13: "emcy.error-register",
                 14: "nmt.reset-comm", 15: "sdo.server", 16: "lss.inquire",
                 17: "sync.window"}
# The description each defect's node is built from: the example, one with a SYNC producer, a
# heartbeat consumer, an EMCY inhibit time and guarding, or one with the LSS slave.
PDO_NODE = ROOT / "tests" / "node" / "pdo-node.eds"
LSS_NODE = ROOT / "tests" / "node" / "lss-node.eds"
DEFECT_FILES = {n: LSS_NODE if n >= 16 else PDO_NODE if n >= 9 else EXAMPLE for n in DEFECT_CHECKS}
CHECKS = 24  # node.answers and the battery (odgen/conformance/__init__.py)


def sdo_server_at(path: Path, out: Path, request: str, response: str) -> Path:
    """`path` with 0x1200 sub 1/2 described as `request`/`response`: a node whose SDO server is
    elsewhere than the pre-defined COB-IDs (the battery follows the description), or disabled."""
    text = path.read_text(encoding="utf-8")
    for sub, value in ((1, request), (2, response)):
        head = f"[1200sub{sub}]"
        start = text.index(head)
        line = text.index("DefaultValue=", start)
        text = text[:line] + f"DefaultValue={value}" + text[text.index("\n", line):]
    out.write_text(text, encoding="utf-8")
    return out


def _build(path: Path, defect: int = 0) -> Path:
    extra = {"sources": [DEFECTS], "defines": ["ODG_APP", f"ODG_DEFECT={defect}"]} if defect else {}
    exe, _ = build_node(Request(path, name="od", node_id=5, defaults=ROUNDTRIP_DEFAULTS), **extra)  # type: ignore[arg-type]
    return exe


@pytest.fixture(scope="module")
def results(vcan_bus, tmp_path_factory: pytest.TempPathFactory, monkeypatch_module) -> dict[str, dict]:
    monkeypatch_module.setenv("ODGEN_CACHE", str(CACHE))
    junit = BUILD / "conformance"
    junit.mkdir(parents=True, exist_ok=True)
    moved = sdo_server_at(PDO_NODE, tmp_path_factory.mktemp("moved") / "sdo-moved.eds", "$NODEID+0x640",
                          "$NODEID+0x5C0")
    plan = [{"name": path.name, "exe": str(_build(path)), "file": str(path), "cli": path == EXAMPLE}
            for path in [*vcan_files(), PDO_NODE, LSS_NODE, moved]]
    plan += [{"name": f"defect-{n}", "exe": str(_build(DEFECT_FILES[n], n)), "file": str(DEFECT_FILES[n]),
              "cli": n == 1} for n in DEFECT_CHECKS]
    for node in plan:
        node["junit"] = str(junit / f"{node['name']}.xml")
    tmp = tmp_path_factory.mktemp("conformance")
    (tmp / "plan.json").write_text(json.dumps(plan), encoding="utf-8")
    done = vcan_bus.run([sys.executable, str(ROOT / "tests" / "vcan" / "conformance_nodes.py"), str(tmp / "plan.json"),
                         str(tmp / "out.json")], cwd=ROOT, timeout=1200)
    assert done.returncode == 0 and (tmp / "out.json").is_file(), done.stdout[-4000:] + done.stderr[-4000:]
    out = json.loads((tmp / "out.json").read_text())
    (BUILD / "conformance.json").write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return {node["name"]: node for node in out}


@pytest.fixture(scope="module")
def monkeypatch_module():
    with pytest.MonkeyPatch.context() as mp:
        yield mp


def test_every_built_node_passes(results: dict[str, dict]) -> None:
    clean = {name: node for name, node in results.items() if not name.startswith("defect-")}
    assert len(clean) == len(vcan_files()) + 3
    failing = {name: "\n".join(node["text"]) for name, node in clean.items() if node["failed"]}
    assert not failing, "\n\n".join(failing.values())[-6000:]
    assert all(node["checks"] == CHECKS for node in clean.values())


def test_moved_sdo_server(results: dict[str, dict]) -> None:
    """A node whose 0x1200 says 0x640/0x5C0 + id serves SDO there only, and the battery follows it."""
    text = "\n".join(results["sdo-moved.eds"]["text"])
    assert " ok   sdo.server:" in text and " ok   nmt.reset-comm:" in text, text


def test_lss_node(results: dict[str, dict]) -> None:
    """The LSS and SYNC window checks ran (not skipped) against the node with the LSS slave."""
    text = "\n".join(results[LSS_NODE.name]["text"])
    assert " ok   lss.inquire:" in text and " ok   sync.window:" in text, text


@pytest.mark.parametrize("defect", list(DEFECT_CHECKS))
def test_each_defect_is_caught(results: dict[str, dict], defect: int) -> None:
    node = results[f"defect-{defect}"]
    assert DEFECT_CHECKS[defect] in node["failed"], "\n".join(node["text"])


def test_cli_status_text_and_junit(results: dict[str, dict]) -> None:
    good, bad = results[EXAMPLE.name]["cli"], results["defect-1"]["cli"]
    assert good["status"] == 0 and good["stdout"].splitlines()[-1] == \
        f"odgen conformance: {CHECKS} of {CHECKS} checks passed", good
    assert bad["status"] == 1 and " FAIL sdo.upload: " in bad["stdout"], bad
    suite = ET.parse(BUILD / "conformance" / "defect-1.xml").getroot().find("testsuite")
    assert suite is not None and suite.get("tests") == str(CHECKS) and int(suite.get("failures") or 0) >= 1
    failed = [case.get("name") for case in suite.iter("testcase") if case.find("failure") is not None]
    assert "sdo.upload" in failed


def test_cli_user_errors(tmp_path: Path) -> None:
    def odgen(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, "-m", "odgen", "conformance", *args], capture_output=True, text=True,
                              check=False, env=dict(os.environ, ODGEN_VCAN=""))
    missing = odgen(str(tmp_path / "none.eds"), "--iface", "vcan0", "--node-id", "5")
    assert missing.returncode == 2 and "no such file" in missing.stderr and "Traceback" not in missing.stderr
    no_bus = odgen(str(EXAMPLE), "--iface", "odg-no-such-if", "--node-id", "5")
    assert no_bus.returncode == 2 and "--iface" in no_bus.stderr and "Traceback" not in no_bus.stderr
    assert odgen(str(EXAMPLE), "--iface", "vcan0", "--node-id", "0").returncode == 2
    off = odgen(str(sdo_server_at(PDO_NODE, tmp_path / "off.eds", "0x80000000", "0x80000000")), "--iface", "vcan0",
                "--node-id", "5")
    assert off.returncode == 2 and "0x1200" in off.stderr and "Traceback" not in off.stderr, off
