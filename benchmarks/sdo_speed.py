"""SDO speed over vcan: odgen's node against python canopen's LocalNode, same bus, same client.

Run inside a vcan session (make bench does: tools/vcan/run.py -- python benchmarks/sdo_speed.py).
Measures expedited upload round trips per second and block-upload throughput of a 4 KiB
VISIBLE_STRING; the peer is canopen's LocalNode serving the same description. Writes
benchmarks/results/sdo-latest.md and .json.
"""

from __future__ import annotations

import json
import logging
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import canopen

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from odgen.pipeline import Request  # noqa: E402
from odgen.roundtrip.build import build_node  # noqa: E402

RESULTS = HERE / "results"
ROUNDS, BLOCK = 500, 4096
EDS = ROOT / "examples" / "io-node" / "io-node.eds"
OPTIONS = f'[[entry]]\nmatch = "0x2100"\ncapacity = {BLOCK}\n'
BIG_STRING = f"""
[2100]
ParameterName=Big text
ObjectType=0x7
DataType=0x0009
AccessType=rw
DefaultValue={"x" * BLOCK}
PDOMapping=0
"""


def _description(tmp: Path) -> Path:
    text = EDS.read_text().replace("[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n",
                                   "[ManufacturerObjects]\nSupportedObjects=2\n1=0x2000\n2=0x2100\n")
    path = tmp / "bench.eds"
    path.write_text(text.rstrip("\n") + "\n" + BIG_STRING)
    return path


def _measure(client: canopen.RemoteNode) -> dict[str, float]:
    times = []
    for _ in range(ROUNDS):
        start = time.perf_counter()
        client.sdo.upload(0x1000, 0)
        times.append(time.perf_counter() - start)
    start = time.perf_counter()
    size = len(client.sdo.upload(0x2100, 0))
    segmented = size / 1024 / (time.perf_counter() - start)
    try:
        start = time.perf_counter()
        with client.sdo.open(0x2100, 0, "rb", block_transfer=True) as f:
            size = len(f.read())
        block: float | None = size / 1024 / (time.perf_counter() - start)
    except canopen.SdoCommunicationError:
        block = None  # the server does not offer block transfer
    return {"expedited_per_s": 1 / statistics.median(times), "segmented_kib_per_s": segmented,
            "block_kib_per_s": block}


def main() -> None:
    logging.getLogger("canopen").setLevel(logging.CRITICAL)
    with tempfile.TemporaryDirectory() as tmp:
        eds = _description(Path(tmp))
        (Path(tmp) / "o.toml").write_text(OPTIONS)
        program, _ = build_node(Request(eds, name="od", options=Path(tmp) / "o.toml"))
        net = canopen.Network()
        net.connect(interface="socketcan", channel="vcan0")
        results = {}
        node = subprocess.Popen([str(program), "--iface", "vcan0", "--node-id", "5"])
        time.sleep(0.5)
        results["odgen node"] = _measure(net.add_node(5, str(eds)))
        node.terminate()
        node.wait()
        server = canopen.Network()  # the peer serves from its own network object, as a device would
        server.connect(interface="socketcan", channel="vcan0")
        server.add_node(canopen.LocalNode(6, str(eds)))
        results["canopen LocalNode"] = _measure(net.add_node(6, str(eds)))
        server.disconnect()
        net.disconnect()
    ours, peer = results["odgen node"], results["canopen LocalNode"]
    lines = ["# SDO speed over vcan (same client: python canopen)", "",
             f"{ROUNDS} expedited uploads (median round trip), a {BLOCK}-byte string by segmented and by block "
             "upload.", "",
             "| server | expedited uploads/s | segmented KiB/s | block KiB/s |", "|---|---:|---:|---:|"]
    for k, v in results.items():
        block = f"{v['block_kib_per_s']:.1f}" if v["block_kib_per_s"] else "not offered"
        lines.append(f"| {k} | {v['expedited_per_s']:.0f} | {v['segmented_kib_per_s']:.1f} | {block} |")
    lines += ["", f"Ratio odgen/canopen: expedited {ours['expedited_per_s'] / peer['expedited_per_s']:.2f}x, "
              f"segmented {ours['segmented_kib_per_s'] / peer['segmented_kib_per_s']:.2f}x."]
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "sdo-latest.json").write_text(json.dumps(results, indent=2) + "\n")
    (RESULTS / "sdo-latest.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
