"""`odgen profile ds401` round trips on a CAN bus: the ds401-io loop-back node (examples/ds401-io)
built for several grid points, all checked in one tools/vcan/run.py session.

Each node program is the generated dictionary + the glue (runtime/profiles/ds401.c, configured by
the generated ds401_app.h) + the example's sim.c (outputs wired to inputs), built by
odgen.roundtrip.build like `odgen node`. Over vcan, python canopen uploads the profile objects by
SDO (expected: the description's defaults) and sends RPDO1 (0x6200) / RPDO2 (analog outputs),
which must come back as change-of-state TPDO1 (0x6000) / TPDO2 (analog inputs) with the
looped-back values.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from odgen.pipeline import Request
from odgen.model import ObjectDictionary
from odgen.model.cia301 import RPDO_COMM as RPDO
from odgen.model.cia301 import TPDO_COMM as TPDO
from odgen.profiles.ds401 import PROFILE, Ds401, build, glue_files, mapping_layout, options_toml, write
from odgen.roundtrip.build import build_node

from .conftest import ROOT
from .test_profile_ds401 import GRID

SIM = ROOT / "examples" / "ds401-io" / "sim.c"
GLUE = ROOT / "runtime" / "profiles" / "ds401.c"
NODE_ID = 5
POINTS = ["16-16-4-4", "one-each", "8bit", "32bit", "di-only-max", "maxima"]
SIZES = {0x0001: 1, 0x0002: 1, 0x0003: 2, 0x0004: 4, 0x0005: 1, 0x0006: 2, 0x0007: 4}
ANALOG_OUT = (10, -20, 30, -40)  # within every width


def _le(value: int, size: int) -> str:
    return (value & ((1 << 8 * size) - 1)).to_bytes(size, "little").hex()


def _expected(od: ObjectDictionary, index: int, sub: int) -> list[object]:
    entry = od.find(index, sub)
    assert entry is not None and entry.default is not None
    value = entry.default.parsed + (NODE_ID if entry.default.nodeid else 0)
    return [index, sub, _le(value, SIZES[entry.data_type])]


def _uploads(spec: Ds401, od: ObjectDictionary) -> list[list[object]]:
    """The identity, every PDO mapping count, and sub0, sub1 and the last sub of each profile object."""
    pairs = [(0x1000, 0), (0x1018, 1), (0x1018, 2)] + [(base + 0x200 + n, 0) for base in (RPDO, TPDO) for n in range(4)]
    for row in PROFILE:
        obj = od.objects.get(row.index)
        if obj is not None:
            pairs += sorted({(row.index, s) for s in (0, 1, max(obj.subs))} if row.array else {(row.index, 0)})
    return [_expected(od, index, sub) for index, sub in pairs]


def _loop(spec: Ds401, kind_out: str, kind_in: str, rpdo: int, tpdo: int, values: list[int]) -> list[object] | None:
    """RPDO with `values` on the output channels it maps -> TPDO with the looped-back inputs."""
    layout = mapping_layout(spec)
    outs, ins = layout[rpdo], layout[tpdo]
    if not outs or not ins:
        return None
    out_w, in_w = spec.width(kind_out), spec.width(kind_in)
    wire = {n: values[n] for n in range(len(outs))}
    top = (1 << (in_w - 1)) - 1
    looped = [wire.get(n, 0) for n in range(len(ins))]
    if kind_in == "ai":  # sim.c saturates a wider output at the input's range
        looped = [max(-top - 1, min(top, v)) for v in looped]
    size_out, size_in = out_w // 8, in_w // 8
    return [0x200 + 0x100 * (rpdo - RPDO) + NODE_ID, "".join(_le(v, size_out) for v in wire.values()),
            0x180 + 0x100 * (tpdo - TPDO) + NODE_ID, "".join(_le(v, size_in) for v in looped)]


def _plan(name: str, exe: Path, spec: Ds401) -> dict[str, object]:
    od = build(spec)
    digital = [[(0x5A + 0x25 * g) & 0xFF for g in range(8)], [(0xA5 - 0x13 * g) & 0xFF for g in range(8)]]
    steps = [_loop(spec, "do", "di", RPDO, TPDO, v) for v in digital]
    steps.append(_loop(spec, "ao", "ai", RPDO + 1, TPDO + 1, list(ANALOG_OUT)))
    writes = [[0x6423, 0, "01"]] if spec.ai else []  # analog events on (CiA 401 default off)
    return {"name": name, "exe": str(exe), "sdo": _uploads(spec, od), "writes": writes,
            "steps": [s for s in steps if s is not None]}


def test_ds401_loop_back_nodes_on_vcan(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, vcan_bus) -> None:
    monkeypatch.setenv("ODGEN_CACHE", str(ROOT / "build" / "node-cache"))
    plans: list[dict[str, object]] = []
    loops = 0
    for name in POINTS:
        spec = GRID[name]
        eds = tmp_path / name / "io.eds"
        eds.parent.mkdir()
        write(spec, eds)
        exe, result = build_node(Request(eds, name="io", defaults=options_toml(spec)), extra=glue_files(spec),
                                 sources=[SIM, GLUE], defines=["ODG_APP", "ODG_NODE_TPDO_COS=0"])
        assert result.files
        plan = _plan(name, exe, spec)
        loops += len(plan["steps"])  # type: ignore[arg-type]
        plans.append(plan)
    assert loops == 15  # 2 digital + 1 analog loops for the five points that have every function
    plan_file = tmp_path / "plan.json"
    plan_file.write_text(json.dumps(plans), encoding="utf-8")
    done = vcan_bus.run([sys.executable, str(ROOT / "tests" / "vcan" / "ds401_io.py"), str(plan_file)], cwd=ROOT,
                        timeout=300)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    lines = done.stdout.strip().splitlines()
    assert lines[-1] == "ds401 vcan: ok" and len(lines) == len(POINTS) + 1, output[-6000:]

