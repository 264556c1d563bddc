"""`odgen conformance` on a CAN bus: every node the round trips build (the corpus sample in `make
test`, the whole corpus in `make corpus`: tests/test_roundtrip_vcan.py vcan_files) passes the battery, and
nodes with an injected defect (tests/conformance/defects.c, one per check family) fail the
check meant to catch it, so each check is shown able to fail. Nodes that behave as CiA 301
allows though odgen's own node does not (defects.c's allowed behaviours, descriptions that
watch node 6 or have a SYNC period) pass or skip, saying why: the battery is fair.

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
from odgen.model.expect import expected_bytes, write_cases
from odgen.formats import load_path
from odgen.model.datatypes import BASIC_TYPES
from odgen.errors import OdgenError
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
                 17: "sync.window", 18: "sdo.limits"}
ALLOWED_ERROR_AT_BOOT, ALLOWED_PREOP_ON_ERROR, ALLOWED_NO_SYNC_PRODUCER = 19, 20, 21
# The description each defect's node is built from: the example, one with a SYNC producer, a
# heartbeat consumer, an EMCY inhibit time and guarding, or one with the LSS slave.
PDO_NODE = ROOT / "tests" / "node" / "pdo-node.eds"
LSS_NODE = ROOT / "tests" / "node" / "lss-node.eds"
DEFECT_FILES = {n: PDO_NODE if n == 18 else LSS_NODE if n >= 16 else PDO_NODE if n >= 9 else EXAMPLE
                for n in DEFECT_CHECKS}
# Each defect's node runs only the check meant to catch it (a check waiting in vain for a frame takes
# seconds), but for defect 1's, which also shows what the command prints for a whole run
DEFECT_SELECT = {n: [check] for n, check in DEFECT_CHECKS.items() if n != 1}
CHECKS = 24  # node.answers and the battery (odgen/conformance/__init__.py)
# What the battery skips on odgen's own node of the example, of each corpus description and of the
# test descriptions (with --allow destructive and the build's stored entries known): node -> the
# ids of the checks skipped, each for one of the reasons REASONS gives its id, all of them for what
# the description lacks. A new skip (or one gone) fails the test: fairness cannot hide a check.
REASONS = {
    "access.write-only": ("no write-only entry",),
    "sdo.limits": ("no writable number outside the communication objects",),
    "sdo.lengths": ("no writable number outside the communication objects",),
    "nmt.heartbeat": ("no 0x1017",),
    "nmt.hb-consumer": ("no writable 0x1016 sub 1, or EMCY disabled", "leaves no room for a node-id"),
    "nmt.guarding": ("no 0x100C/0x100D, or a heartbeat that cannot be switched off",),
    "nmt.reset-comm": ("no communication entry a client may change",),
    "sync.producer": ("0x1005 and 0x1006 are not both writable",),
    "sync.window": ("0x1005, 0x1006 and 0x1007 are not all writable", "no TPDO the description lets a client map"),
    "pdo.sequence": ("no TPDO the description lets a client map",),
    "pdo.tpdo-types": ("no TPDO the description lets a client map",),
    "emcy.rpdo-length": ("no RPDO the description lets a client map",),
    "emcy.inhibit": ("no RPDO the description lets a client map", "no writable 0x1015, or EMCY disabled"),
    "emcy.error-register": ("no RPDO the description lets a client map",),
    "sdo.server": ("no 0x1200 sub 1/2",),
    "lss.inquire": ("the description does not say LSS_Supported=1",),
    "store.signature": ("no 0x1010/0x1011 sub 1",),
    "store.save-load": ("no 0x1010/0x1011 sub 1",),
}
SKIPS = {
    "eyou__YiyouServo_V1.4.eds": "access.write-only lss.inquire",
    "gocanopen__base.eds": "nmt.guarding",
    "kacanopen__Easy-ak_v1.30.eds": "access.write-only nmt.heartbeat emcy.inhibit nmt.hb-consumer lss.inquire",
    "kacanopen__roboteq_motor_controllers_v2.0-30-01-2019.eds":
        "sync.producer sync.window emcy.inhibit sdo.server lss.inquire store.signature store.save-load",
    "kacanopen__roboteq_motor_controllers_v80beta-old.eds":
        "sync.producer sync.window emcy.inhibit sdo.server lss.inquire store.signature store.save-load",
    "roscanopen__Elmo.dcf":
        "sync.producer sync.window emcy.inhibit nmt.hb-consumer nmt.guarding sdo.server lss.inquire",
    "roscanopen__prbt_0_1.dcf": "sync.producer sync.window emcy.inhibit store.signature store.save-load",
    "victron__curtis_e.eds":
        "sdo.limits sdo.lengths access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence "
        "pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding "
        "nmt.reset-comm sdo.server lss.inquire store.signature store.save-load",
    "victron__emsiso.eds":
        "sdo.limits sdo.lengths access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence "
        "pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding "
        "nmt.reset-comm sdo.server lss.inquire store.signature store.save-load",
    "io-node.eds": "access.write-only sync.producer sync.window emcy.inhibit nmt.hb-consumer nmt.guarding lss.inquire",
    "canfestival__DS401_Slave_Gui.eds": "access.write-only sync.producer sync.window emcy.inhibit lss.inquire",
    "canopendemo__demoDevice.eds": "access.write-only nmt.guarding",
    "canopendemo__demoDevice.xdd": "access.write-only nmt.guarding",
    "canopeneditor__DSP302-NMTMaster.xpd":
        "access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence "
        "pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer "
        "nmt.guarding sdo.server lss.inquire store.signature store.save-load",
    "canopeneditor__demo_io.eds":
        "access.write-only sync.producer sync.window nmt.hb-consumer nmt.guarding "
        "lss.inquire store.signature store.save-load",
    "canopeneditor__demo_sensor.eds":
        "access.write-only sync.producer sync.window emcy.rpdo-length emcy.inhibit "
        "emcy.error-register nmt.hb-consumer nmt.guarding lss.inquire store.signature "
        "store.save-load",
    "canopeneditor__minimal_project.xdd":
        "access.write-only sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length "
        "emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding sdo.server "
        "lss.inquire store.signature store.save-load",
    "canopennode__DS301_profile.eds":
        "access.write-only sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length "
        "emcy.inhibit emcy.error-register nmt.guarding",
    "canopennode__DS301_profile.xpd":
        "sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length emcy.inhibit "
        "emcy.error-register",
    "canopennode__IO.eds": "access.write-only nmt.guarding lss.inquire",
    "canopensocket__CANopenSocket_v1.3.eds": "access.write-only lss.inquire",
    "canopensocket__CANopenSocket_v1.3.xdd": "access.write-only lss.inquire",
    "canopensocket__basicDevice.eds": "access.write-only nmt.guarding",
    "corc__CANopenSocket.eds": "access.write-only nmt.guarding lss.inquire",
    "eyou__YiyouServo_V1.4.dcfgen.eds": "access.write-only lss.inquire",
    "jinr__JINR_HV_DAC_00010001.eds":
        "access.write-only emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer lss.inquire",
    "kacanopen__3301002_1.eds": "access.write-only sync.producer sync.window emcy.inhibit",
    "kacanopen__605.3150.51-V-EK-2-60.eds":
        "access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer",
    "kacanopen__605.3150.67-B-EK-2-60.eds": "sync.producer sync.window emcy.inhibit",
    "kacanopen__605.3150.71-A-EK-2-60.eds":
        "access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer",
    "kacanopen__CL4-E-2-12.eds": "sync.producer sync.window emcy.inhibit sdo.server lss.inquire",
    "kacanopen__CiA_profiles_401.eds":
        "access.write-only sync.producer sync.window emcy.inhibit nmt.hb-consumer "
        "nmt.guarding sdo.server store.signature store.save-load",
    "kacanopen__CiA_profiles_402.eds":
        "sync.producer sync.window emcy.inhibit nmt.hb-consumer nmt.guarding sdo.server "
        "store.signature store.save-load",
    "kacanopen__IoX1_16DI_8DO.eds": "sync.producer sync.window emcy.inhibit",
    "kacanopen__IoX2_24DI.eds":
        "sync.producer sync.window emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer",
    "kacanopen__IoX3_24DO.eds": "sync.producer sync.window pdo.sequence pdo.tpdo-types emcy.inhibit",
    "kacanopen__IoX5_8RTD.eds":
        "sync.producer sync.window emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer",
    "kacanopen__MM217_V3Y_0.eds": "access.write-only sync.producer sync.window emcy.inhibit",
    "kacanopen__cia_301_minimal.eds":
        "sdo.limits sdo.lengths access.write-only nmt.heartbeat sync.producer sync.window "
        "pdo.sequence pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer nmt.guarding nmt.reset-comm sdo.server store.signature "
        "store.save-load",
    "kacanopen__epos2_347717.eds": "sync.producer sync.window emcy.inhibit",
    "kacanopen__phyPS409Y.eds": "sync.producer sync.window emcy.inhibit sdo.server",
    "lelycore__co-nmt-slave.dcf":
        "sync.producer sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length "
        "emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding sdo.server "
        "store.signature store.save-load",
    "lelycore__co-sdev.dcf":
        "access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence "
        "pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer "
        "nmt.guarding nmt.reset-comm sdo.server lss.inquire store.signature "
        "store.save-load",
    "lelycore__coapp-fiber-master.dcf":
        "access.write-only sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length "
        "emcy.inhibit emcy.error-register nmt.guarding sdo.server store.signature "
        "store.save-load",
    "lelycore__coctl.dcf":
        "access.write-only sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length "
        "emcy.inhibit emcy.error-register sdo.server store.signature store.save-load",
    "objdictgen__objdictgen_slave.eds":
        "sdo.limits sdo.lengths access.write-only nmt.heartbeat sync.producer sync.window "
        "pdo.sequence pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer nmt.guarding nmt.reset-comm lss.inquire store.signature "
        "store.save-load",
    "oresatmon__oresat_test.eds":
        "sdo.limits sdo.lengths access.write-only nmt.heartbeat sync.producer sync.window "
        "pdo.sequence pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register "
        "nmt.hb-consumer nmt.guarding nmt.reset-comm sdo.server lss.inquire "
        "store.signature store.save-load",
    "pycanopen__datatypes.eds":
        "access.write-only nmt.heartbeat sync.producer sync.window pdo.sequence "
        "pdo.tpdo-types emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer "
        "nmt.guarding nmt.reset-comm sdo.server lss.inquire store.signature "
        "store.save-load",
    "pycanopen__e35.eds": "emcy.inhibit nmt.hb-consumer",
    "pycanopen__e35_broken_vendor001.eds": "emcy.inhibit nmt.hb-consumer",
    "pycanopen__sensor.eds":
        "access.write-only sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding "
        "sdo.server lss.inquire store.signature store.save-load",
    "redpesk__m150c.dcf":
        "access.write-only sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.guarding sdo.server "
        "lss.inquire store.signature store.save-load",
    "ros2canopen__technosoft.eds": "sync.window emcy.inhibit nmt.hb-consumer",
    "roscanopen__ISD860.eds": "sync.window emcy.inhibit nmt.hb-consumer lss.inquire store.signature store.save-load",
    "roscanopen__Schunk.eds": "sync.producer sync.window emcy.inhibit store.signature store.save-load",
    "roscanopen__Schunk_0_63.dcf": "sync.producer sync.window emcy.inhibit store.signature store.save-load",
    "roscanopen__cia402_slave.eds": "access.write-only sync.producer sync.window sdo.server lss.inquire",
    "roscanopen__concurrency_master.dcf":
        "sync.window pdo.sequence pdo.tpdo-types emcy.rpdo-length emcy.inhibit "
        "emcy.error-register nmt.guarding sdo.server store.signature store.save-load",
    "roscanopen__simple.eds":
        "access.write-only sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.guarding sdo.server "
        "store.signature store.save-load",
    "roscanopen__technosoft_ipos_robot_control_cia402_slave.eds": "sync.window emcy.inhibit nmt.hb-consumer",
    "wustsat__lora.eds":
        "access.write-only sync.producer sync.window pdo.sequence pdo.tpdo-types "
        "emcy.rpdo-length emcy.inhibit emcy.error-register nmt.hb-consumer nmt.guarding "
        "sdo.server lss.inquire store.signature store.save-load",
    "pdo-node.eds": "access.write-only sync.window lss.inquire store.signature store.save-load",
    "lss-node.eds": "access.write-only emcy.inhibit nmt.hb-consumer nmt.guarding",
    "sdo-moved.eds": "access.write-only sync.window lss.inquire store.signature store.save-load",
}


def described_as(path: Path, out: Path, values: dict[str, str]) -> Path:
    """`path` with the DefaultValue of each section named (`1200sub1`, `1006`) changed."""
    text = path.read_text(encoding="utf-8")
    for section, value in values.items():
        start = text.index(f"[{section}]")
        line = text.index("DefaultValue=", start)
        text = text[:line] + f"DefaultValue={value}" + text[text.index("\n", line):]
    out.write_text(text, encoding="utf-8")
    return out


def sdo_server_at(path: Path, out: Path, request: str, response: str) -> Path:
    """`path` with 0x1200 sub 1/2 described as `request`/`response`: a node whose SDO server is
    elsewhere than the pre-defined COB-IDs (the battery follows the description), or disabled."""
    return described_as(path, out, {"1200sub1": request, "1200sub2": response})


def _build(path: Path, defect: int = 0) -> tuple[Path, list[list[int]]]:
    """The node program, and the entries its build stores (the round trip defaults' persist group)."""
    extra = {"sources": [DEFECTS], "defines": ["ODG_APP", f"ODG_DEFECT={defect}"]} if defect else {}
    exe, result = build_node(Request(path, name="od", node_id=5, defaults=ROUNDTRIP_DEFAULTS), **extra)  # type: ignore[arg-type]
    return exe, sorted([index, sub] for (index, sub), placement in (result.placements or {}).items() if placement.group)


def _node(name: str, path: Path, defect: int = 0, select: list[str] | None = None, destructive: bool = True,
          cli: list[str] | None = None) -> dict:
    exe, stored = _build(path, defect)
    return {"name": name, "exe": str(exe), "file": str(path), "cli": cli, "select": select or [],
            "settings": {"destructive": destructive, "stored": stored}}


def _variants(tmp: Path) -> dict[str, Path]:
    return {"sdo-moved.eds": sdo_server_at(PDO_NODE, tmp / "sdo-moved.eds", "$NODEID+0x640", "$NODEID+0x5C0"),
            # watches node 6: the node-id next to 5 the heartbeat-consumer check must not take
            "watch-6.eds": described_as(PDO_NODE, tmp / "watch-6.eds", {"1016sub2": "0x000601F4"}),
            # a SYNC period configured: 0x1019 refuses every write with 0x08000022
            "sync-period.eds": described_as(PDO_NODE, tmp / "sync-period.eds", {"1006": "10000"}),
            # 0x1029 sub 1 = 1: a communication error must not change the state
            "no-change.eds": described_as(PDO_NODE, tmp / "no-change.eds", {"1029sub1": "1"})}


def _configuration(path: Path, node: dict) -> list[list[object]]:
    """Two stored numbers of the node given a valid value other than the described one: what an
    integrator configured and saved before the battery ran."""
    od = load_path(path)[0]
    assert od is not None
    out: list[list[object]] = []
    for index, sub in node["settings"]["stored"]:
        entry = od.find(index, sub)
        dtype = BASIC_TYPES.get(entry.data_type or 0) if entry is not None else None
        if entry is None or dtype is None or not (entry.writable and entry.readable and dtype.is_numeric):
            continue
        described = expected_bytes(od, entry, dtype, 5)
        value = next((d for d, expect in write_cases(entry, dtype) if expect == "ODG_OK" and d != described), None)
        if value is not None and len(out) < 2:
            out.append([index, sub, value.hex()])
    assert out
    return out


@pytest.fixture(scope="module")
def results(vcan_bus, tmp_path_factory: pytest.TempPathFactory, monkeypatch_module) -> dict[str, dict]:
    monkeypatch_module.setenv("ODGEN_CACHE", str(CACHE))
    junit = BUILD / "conformance"
    junit.mkdir(parents=True, exist_ok=True)
    variants = _variants(tmp_path_factory.mktemp("variants"))
    options = tmp_path_factory.mktemp("options") / "roundtrip-defaults.toml"
    options.write_text(ROUNDTRIP_DEFAULTS, encoding="utf-8")
    example_cli = ["--allow", "destructive", "--options", str(options)]
    plan = [_node(path.name, path, cli=example_cli if path == EXAMPLE else None)
            for path in [*vcan_files(), PDO_NODE, LSS_NODE, variants["sdo-moved.eds"]]]
    plan += [_node(f"defect-{n}", DEFECT_FILES[n], n, DEFECT_SELECT.get(n), cli=[] if n == 1 else None)
             for n in DEFECT_CHECKS]
    plan += [_node("allowed-error-at-boot", PDO_NODE, ALLOWED_ERROR_AT_BOOT),
             _node("allowed-preop", PDO_NODE, ALLOWED_PREOP_ON_ERROR, ["sdo.upload", "nmt.states"]),
             _node("allowed-preop-no-1029", EXAMPLE, ALLOWED_PREOP_ON_ERROR, ["nmt.states"]),
             _node("preop-against-1029", variants["no-change.eds"], ALLOWED_PREOP_ON_ERROR, ["nmt.states"]),
             _node("no-sync-producer", LSS_NODE, ALLOWED_NO_SYNC_PRODUCER, ["sync"]),
             _node("watch-6", variants["watch-6.eds"], select=["nmt.hb-consumer", "sdo.limits"]),
             _node("sync-period", variants["sync-period.eds"], select=["sdo.limits", "sync.producer"]),
             {**_node("not-destructive", EXAMPLE, destructive=False,
                      cli=["--select", "node,sdo.upload,nmt.heartbeat", "--junit", str(junit / "interrupted.xml")]),
              "interrupt_after": "sdo.upload"},
             {**_node("gone-silent", EXAMPLE, select=["sdo.upload", "access"]), "stop_after": "sdo.upload"}]
    plan += [{**plan[0], "name": f"again-{k}", "cli": None} for k in (2, 3)]  # the example again: stable verdicts
    plan.append({**plan[0], "name": "configured", "cli": None, "configure": _configuration(EXAMPLE, plan[0])})
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


def _clean(results: dict[str, dict]) -> dict[str, dict]:
    names = {path.name for path in vcan_files()} | {PDO_NODE.name, LSS_NODE.name, "sdo-moved.eds"}
    return {name: node for name, node in results.items() if name in names}


def _text(node: dict) -> str:
    return "\n".join(node["text"])


def test_every_built_node_passes(results: dict[str, dict]) -> None:
    clean = _clean(results)
    assert len(clean) == len(vcan_files()) + 3
    failing = {name: _text(node) for name, node in clean.items() if node["failed"]}
    assert not failing, "\n\n".join(failing.values())[-6000:]
    assert all(node["checks"] == CHECKS for node in clean.values())


def test_every_skip_on_odgen_nodes_is_listed(results: dict[str, dict]) -> None:
    """Each check skipped on odgen's own node of a corpus description, with its reason: a new skip
    (or one gone) changes this list, so fairness to other stacks cannot hide a check."""
    clean = _clean(results)
    found = {name: " ".join(node["skipped"]) for name, node in clean.items()}
    assert found == {name: SKIPS.get(name, "") for name in clean}
    unexplained = {(name, check): why for name, node in clean.items() for check, why in node["skipped"].items()
                   if not any(reason in why for reason in REASONS[check])}
    assert not unexplained, unexplained


def test_moved_sdo_server(results: dict[str, dict]) -> None:
    """A node whose 0x1200 says 0x640/0x5C0 + id serves SDO there only, and the battery follows it."""
    text = _text(results["sdo-moved.eds"])
    assert " ok   sdo.server:" in text and " ok   nmt.reset-comm:" in text, text


def test_lss_node(results: dict[str, dict]) -> None:
    """The LSS and SYNC window checks ran (not skipped) against the node with the LSS slave."""
    text = _text(results[LSS_NODE.name])
    assert " ok   lss.inquire:" in text and " ok   sync.window:" in text, text


@pytest.mark.parametrize("defect", list(DEFECT_CHECKS))
def test_each_defect_is_caught(results: dict[str, dict], defect: int) -> None:
    node = results[f"defect-{defect}"]
    assert DEFECT_CHECKS[defect] in node["failed"] and "raised" not in _text(node), _text(node)


def test_wrong_refusal_names_both_codes(results: dict[str, dict]) -> None:
    """0x1019 = 255 refused with a code CiA 301 does not give for it: both codes in the finding."""
    text = _text(results["defect-18"])
    assert "0x1019sub0: download ff gave 0x08000000, expected 0x00000000, or 0x06090030" in text, text


def test_error_at_boot_is_allowed(results: dict[str, dict]) -> None:
    """An error history entry and an error active from boot, 0x1003 beyond the errors answering
    0x08000024: every check passes or skips (run-time state is not a default), saying why."""
    node = results["allowed-error-at-boot"]
    assert not node["failed"] and node["checks"] == CHECKS, _text(node)
    assert "an error of the node's own is active" in node["skipped"]["emcy.inhibit"], _text(node)
    assert any("0x1001 was 0x81 before the check" in n for n in node["notes"]["emcy.error-register"]), _text(node)


def test_0x1019_reserved_values_refused(results: dict[str, dict]) -> None:
    """odgen's own node refuses 0x1019 = 255 (CiA 301 reserves it) and the battery accepts that."""
    node = results[PDO_NODE.name]
    assert any("0x1019sub0: ff refused with 0x06090030: CiA 301 reserves" in n for n in node["notes"]["sdo.limits"]), \
        _text(node)


def test_sync_period_refusal_is_allowed(results: dict[str, dict]) -> None:
    """A DCF-like description with 0x1006 = 10 ms: 0x1019 writes answer 0x08000022, which CiA 301 requires."""
    node = results["sync-period"]
    assert not node["failed"] and "sdo.limits" not in node["skipped"], _text(node)
    assert any("0x08000022: 0x1019 may only be written while 0x1006 is 0" in n for n in node["notes"]["sdo.limits"])


def test_no_sync_producer_is_allowed(results: dict[str, dict]) -> None:
    """A node that refuses 0x1005 bit 30 with 0x06090030 (it cannot produce SYNC, as CiA 301 allows):
    the SYNC checks skip, saying so."""
    node = results["no-sync-producer"]
    assert not node["failed"], _text(node)
    assert all("the node is no SYNC producer" in node["skipped"].get(check, "")
               for check in ("sync.producer", "sync.window")), _text(node)


def test_duplicate_consumer_avoided(results: dict[str, dict]) -> None:
    """0x1016 sub 2 watches node 6: the heartbeat-consumer check plays another node-id, and passes."""
    node = results["watch-6"]
    assert not node["failed"] and " ok   nmt.hb-consumer:" in _text(node), _text(node)


def test_preop_with_active_error(results: dict[str, dict]) -> None:
    """A node that stays pre-operational after "start" with a communication error active: allowed by
    0x1029 sub 1 = 0 (said in a note), a failure naming 0x1029 where it says 1, a skip without 0x1029."""
    allowed, against, unknown = (results[name] for name in ("allowed-preop", "preop-against-1029",
                                                            "allowed-preop-no-1029"))
    assert not allowed["failed"] and "as 0x1029sub1 = 0 (pre-operational) asks" in _text(allowed), _text(allowed)
    assert against["failed"] == ["nmt.states"] and "but 0x1029sub1 = 1 asks for no change of state" in _text(against)
    assert "no 0x1029 sub 1 to judge by" in unknown["skipped"].get("nmt.states", ""), _text(unknown)


def test_not_destructive_by_default(results: dict[str, dict]) -> None:
    """Without --allow destructive nothing resets the node, erases what it stores or plays another
    node's heartbeat; without --options nothing is known to be stored."""
    node = results["not-destructive"]
    assert not node["failed"], _text(node)
    for check in ("nmt.boot-up", "nmt.reset-comm", "store.save-load"):
        assert "--allow destructive" in node["skipped"][check] or "--options" in node["skipped"][check], _text(node)


def test_node_gone_silent(results: dict[str, dict]) -> None:
    """The node stops after sdo.upload: each check after it fails saying so, none raises."""
    node = results["gone-silent"]
    assert node["failed"] == ["access.read-only", "access.write-only", "access.missing"], _text(node)
    assert _text(node).count("does not answer an SDO upload of 0x1000 any more") == 3 and "raised" not in _text(node)


def test_verdicts_stream(results: dict[str, dict]) -> None:
    """Each result is reported when its check ends, not at the end of the run: by the API (in the
    order run, each at about the sum of the durations so far) and by the CLI (a line per check,
    --junit rewritten after each, so a run interrupted after sdo.upload, while nmt.heartbeat measures,
    keeps what it found)."""
    node = results[PDO_NODE.name]
    ids, times = zip(*node["heard"], strict=True)
    assert list(ids) == ["node.answers", *(line.split()[1].rstrip(":") for line in node["text"][2:-1]
                                           if line.startswith("  ") and not line.startswith("       "))]
    elapsed = [sum(node["durations"][:k + 1]) for k in range(len(times))]
    assert all(abs(t - e) < 1.0 + 0.05 * e for t, e in zip(times, elapsed, strict=True)), (times, elapsed)
    cli = results["not-destructive"]["cli"]
    assert cli["status"] == 130 and "Traceback" not in cli["stderr"], cli
    shown = [text.split()[1].rstrip(":") for _, text in cli["lines"] if text.startswith("  ") and
             not text.startswith("       ")]
    assert shown == ["node.answers", "sdo.upload"], cli
    suite = ET.parse(BUILD / "conformance" / "interrupted.xml").getroot().find("testsuite")
    assert suite is not None and [case.get("name") for case in suite.iter("testcase")] == shown


def test_battery_puts_back_what_it_changed(results: dict[str, dict]) -> None:
    """Stored values configured and saved before the battery (with --allow destructive: save, load,
    resets) are what the node has after it, even after a reset node: written back and saved again."""
    node = results["configured"]
    assert not node["failed"] and " ok   store.save-load:" in _text(node), _text(node)
    assert node["changed"] == [], node["changed"]


def test_same_node_same_verdicts(results: dict[str, dict]) -> None:
    """The example's node checked three times: each check gives the same verdict, passed and failed counts."""
    runs = [results[name]["verdicts"] for name in (EXAMPLE.name, "again-2", "again-3")]
    assert runs[0] == runs[1] == runs[2], runs


def test_selectors_are_checked() -> None:
    from odgen.conformance import CHECK_IDS, Selection, check_selectors

    check_selectors(["nmt", "store.save-load", "sdo."], "--select")
    with pytest.raises(OdgenError, match="'nmt.stats' is not a conformance check id or prefix; did you mean nmt.st"):
        check_selectors(["nmt.stats"], "--select")
    kept = [i for i in CHECK_IDS if Selection(("nmt", "sdo.upload"), ("nmt.hb",)).keeps(i)]
    assert kept == ["sdo.upload", "nmt.states", "nmt.heartbeat", "nmt.guarding", "nmt.boot-up", "nmt.reset-comm"]


def test_destructive_and_stored_need_saying() -> None:
    """Without --allow destructive a destructive check is skipped before it touches the bus; with it
    but without --options, save/load skips: nothing says what 0x1010 stores."""
    from types import SimpleNamespace

    from odgen.conformance import CHECKS, _run_step
    from odgen.conformance.client import Settings
    from odgen.conformance.pdo import check_store_restore
    from odgen.formats import load_path

    od = load_path(EXAMPLE)[0]
    quiet = SimpleNamespace(od=od, settings=Settings())  # any bus access would raise AttributeError
    for step in CHECKS:
        if step.destructive:
            check = _run_step(quiet, step)  # type: ignore[arg-type]
            assert "run with --allow destructive" in check.skipped and not check.failures, (step.id, check)
    check = check_store_restore(SimpleNamespace(od=od, settings=Settings(destructive=True)))  # type: ignore[arg-type]
    assert "name them with --options" in check.skipped and not check.passed


def test_cli_status_text_and_junit(results: dict[str, dict]) -> None:
    """The example's node by the command, with --allow destructive and --options (the round trip
    defaults as an options file): the same skips as in-process; a defect: exit 1 and JUnit."""
    good, bad = results[EXAMPLE.name]["cli"], results["defect-1"]["cli"]
    skipped = len(SKIPS[EXAMPLE.name].split())
    assert good["status"] == 0 and good["stdout"].splitlines()[-1] == \
        f"odgen conformance: {CHECKS} of {CHECKS} checks passed ({skipped} skipped)", good
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
    assert no_bus.returncode == 2 and ("--iface" in no_bus.stderr or "no SocketCAN" in no_bus.stderr) \
        and "Traceback" not in no_bus.stderr, no_bus  # the interface named, or (host without CAN) how to get one
    assert odgen(str(EXAMPLE), "--iface", "vcan0", "--node-id", "0").returncode == 2
    typo = odgen(str(EXAMPLE), "--iface", "vcan0", "--node-id", "5", "--ignore", "nmt.stats")
    assert typo.returncode == 2 and "'nmt.stats' is not a conformance check id or prefix" in typo.stderr, typo
    no_options = odgen(str(EXAMPLE), "--iface", "vcan0", "--node-id", "5", "--options", str(tmp_path / "none.toml"))
    assert no_options.returncode == 2 and "no such options file" in no_options.stderr, no_options
    assert odgen(str(EXAMPLE), "--iface", "vcan0", "--node-id", "5", "--allow", "everything").returncode == 2
    off = odgen(str(sdo_server_at(PDO_NODE, tmp_path / "off.eds", "0x80000000", "0x80000000")), "--iface", "vcan0",
                "--node-id", "5")
    assert off.returncode == 2 and "0x1200" in off.stderr and "Traceback" not in off.stderr, off
