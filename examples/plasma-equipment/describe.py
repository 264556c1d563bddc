"""Write the five device descriptions of the plasma-equipment network from one table.

    python describe.py [OUTDIR]      (default: this directory)

The table below is the master's PDO layout of a low-temperature plasma installation: the
master sends each slave its commands in one PDO (slave RPDO1, COB-ID 0x200 + node-id) and
receives each slave's report in one PDO (slave TPDO1, 0x180 + node-id). Every PDO is
synchronous and cyclic (transmission type 1: sent, and applied, at every SYNC). The slaves
are CiA 401 style I/O devices: switches in 0x6200 (write output 8-bit), set-points in
0x6410/0x6411 (write analog output 8/16-bit), states in 0x6000 (read input 8-bit) and
measurements in 0x6401 (read analog input 16-bit). The master holds the mirror image: what
it sends is `rwr` (mappable into its TPDOs), what it receives is `rww` (into its RPDOs).
Output is deterministic; tests check that the committed files are what this script writes.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from pathlib import Path

from odgen.formats import load_bytes
from odgen.formats.eds_writer import write_eds

Mapped = tuple[int, int, int, str]  # index, sub, bits, what it carries


@dataclass(frozen=True)
class Slave:
    file: str
    node_id: int
    product: str
    tag: str  # names the slave in the master's sub-entry names
    commands: tuple[Mapped, ...]  # master TPDO -> slave RPDO1
    report: tuple[Mapped, ...]  # slave TPDO1 -> master RPDO


MASTER_ID = 127  # out of the slaves' way; the master's PDO COB-IDs are fixed, not node-id based

# (index, sub, bits) as the master maps them; the slave maps the same layout onto its own
# sub-indices, numbered from 1 per object.
SLAVES = (
    Slave("hv_supply.eds", 1, "High-voltage supply", "HV",
          ((0x6200, 1, 8, "Start/stop"), (0x6200, 2, 8, "Control mode"), (0x6410, 1, 8, "Output level")),
          ((0x6401, 1, 16, "Output current"), (0x6401, 2, 16, "Output voltage"))),
    Slave("vacuum_gauge.eds", 2, "Vacuum gauge", "Vacuum",
          ((0x6200, 3, 8, "Control mode"), (0x6200, 4, 8, "Start/stop")),
          ((0x6401, 3, 16, "Pressure"), (0x6000, 1, 8, "Control mode state"), (0x6000, 2, 8, "Start/stop state"))),
    Slave("flow_meter.eds", 3, "Flow meter", "Flow",
          ((0x6200, 5, 8, "Control mode"), (0x6200, 6, 8, "Valve mode"), (0x6411, 1, 16, "Flow set-point")),
          ((0x6000, 3, 8, "Control mode state"), (0x6000, 4, 8, "Valve mode state"), (0x6401, 4, 16, "Flow"))),
    Slave("inverter.eds", 4, "Frequency inverter", "Inverter",
          ((0x6200, 7, 8, "Run/stop"), (0x6200, 8, 8, "Control mode"), (0x6411, 2, 16, "Drive frequency")),
          ((0x6000, 5, 8, "Run/stop state"), (0x6000, 6, 8, "Control mode state"))),
)

OBJECTS = {  # CiA 401 name, data type, sub-entry name prefix
    0x6000: ("Read input 8-bit", 0x0005, "Input"),
    0x6200: ("Write output 8-bit", 0x0005, "Output"),
    0x6401: ("Read analog input 16-bit", 0x0003, "Analog input"),
    0x6410: ("Write analog output 8-bit", 0x0002, "Analog output"),
    0x6411: ("Write analog output 16-bit", 0x0003, "Analog output"),
}
INPUTS = (0x6000, 0x6401)


@dataclass(frozen=True)
class Pdo:
    cob_id: str
    maps: tuple[Mapped, ...]


@dataclass(frozen=True)
class Device:
    file: str
    product: str
    product_code: int
    rpdos: tuple[Pdo, ...]
    tpdos: tuple[Pdo, ...]
    access: dict[int, str]  # process object -> access type
    clock: bool = False  # has 0x1006 (communication cycle period, 0: off): can be made the SYNC producer


def devices() -> list[Device]:
    """The master and the four slaves, each with its own PDOs and process objects."""
    master = Device("master.eds", "Plasma equipment master", 0x100,
                    tuple(Pdo(f"0x{0x180 + s.node_id:X}", _tagged(s.tag, s.report)) for s in SLAVES),
                    tuple(Pdo(f"0x{0x200 + s.node_id:X}", _tagged(s.tag, s.commands)) for s in SLAVES),
                    {i: "rww" if i in INPUTS else "rwr" for i in OBJECTS}, clock=True)
    slaves = [Device(s.file, s.product, 0x100 + s.node_id, (Pdo("$NODEID+0x200", renumbered(s.commands)),),
                     (Pdo("$NODEID+0x180", renumbered(s.report)),),
                     {i: "ro" if i in INPUTS else "rww" for i in OBJECTS}) for s in SLAVES]
    return [master, *slaves]


def _tagged(tag: str, maps: tuple[Mapped, ...]) -> tuple[Mapped, ...]:
    return tuple((index, sub, bits, f"{tag} {what[0].lower()}{what[1:]}") for index, sub, bits, what in maps)


def renumbered(maps: tuple[Mapped, ...]) -> tuple[Mapped, ...]:
    """A slave's own sub-indices: 1, 2, ... per object, in mapping order."""
    seen: dict[int, int] = {}
    out = []
    for index, _sub, bits, what in maps:
        seen[index] = seen.get(index, 0) + 1
        out.append((index, seen[index], bits, what))
    return tuple(out)


# ---- EDS text -------------------------------------------------------------------------------

def eds(dev: Device) -> str:
    process = _process_objects(dev)
    comm = [0x1005, *([0x1006] if dev.clock else []), 0x1017, 0x1200] + [0x1400 + n for n in range(len(dev.rpdos))] \
        + [0x1600 + n for n in range(len(dev.rpdos))] + [0x1800 + n for n in range(len(dev.tpdos))] \
        + [0x1A00 + n for n in range(len(dev.tpdos))]
    out = _header(dev)
    out += _list("MandatoryObjects", [0x1000, 0x1001, 0x1018])
    out += _list("OptionalObjects", comm + sorted(process))
    out += _list("ManufacturerObjects", [])
    out += _var(0x1000, "Device type", 0x0007, "ro", f"0x{_device_type(process):08X}")
    out += _var(0x1001, "Error register", 0x0005, "ro", "0")
    out += _var(0x1005, "COB-ID SYNC", 0x0007, "rw", "0x00000080")
    if dev.clock:  # the µs between two SYNCs the node sends once 0x1005 bit 30 is set
        out += _var(0x1006, "Communication cycle period", 0x0007, "rw", "0")
    out += _var(0x1017, "Producer heartbeat time", 0x0006, "rw", "1000")
    out += _record(0x1018, "Identity", [("Vendor-ID", 0x0007, "ro", "0x00000000"),
                                        ("Product code", 0x0007, "ro", f"0x{dev.product_code:08X}")])
    out += _record(0x1200, "SDO server parameter", [("COB-ID client to server (rx)", 0x0007, "ro", "$NODEID+0x600"),
                                                    ("COB-ID server to client (tx)", 0x0007, "ro", "$NODEID+0x580")])
    for kind, base, pdos in (("RPDO", 0x1400, dev.rpdos), ("TPDO", 0x1800, dev.tpdos)):
        for n, pdo in enumerate(pdos):
            out += _pdo(kind, base + n, n + 1, pdo)
    for index in sorted(process):
        out += _array(index, dev.access[index], process[index])
    return "\n".join(out) + "\n"


def _device_type(process: dict[int, dict[int, str]]) -> int:
    """CiA 401 profile number plus a function bit for each kind of I/O present."""
    bits = {0x6000: 16, 0x6200: 17, 0x6401: 18, 0x6410: 19, 0x6411: 19}
    return 0x0191 | sum({1 << bits[i] for i in process})


def _process_objects(dev: Device) -> dict[int, dict[int, str]]:
    objs: dict[int, dict[int, str]] = {}
    for pdo in dev.rpdos + dev.tpdos:
        for index, sub, _bits, what in pdo.maps:
            objs.setdefault(index, {})[sub] = what
    return objs


def _header(dev: Device) -> list[str]:
    return ["[FileInfo]", f"FileName={dev.file}", "FileVersion=1", "FileRevision=0", "EDSVersion=4.0",
            f"Description={dev.product}", "", "[DeviceInfo]", "VendorName=odgen examples", "VendorNumber=0x00000000",
            f"ProductName={dev.product}", "BaudRate_125=1", "BaudRate_250=1", "BaudRate_500=1",
            "SimpleBootUpMaster=0", "SimpleBootUpSlave=1", "Granularity=8", "DynamicChannelsSupported=0",
            "GroupMessaging=0", f"NrOfRXPDO={len(dev.rpdos)}", f"NrOfTXPDO={len(dev.tpdos)}", "LSS_Supported=0", "",
            "[DummyUsage]", *(f"Dummy000{n}=0" for n in range(1, 8)), ""]


def _list(name: str, indices: list[int]) -> list[str]:
    return [f"[{name}]", f"SupportedObjects={len(indices)}",
            *(f"{n}=0x{i:04X}" for n, i in enumerate(indices, 1)), ""]


def _entry(section: str, name: str, dtype: int, access: str, default: str, mappable: bool = False) -> list[str]:
    return [f"[{section}]", f"ParameterName={name}", "ObjectType=0x7", f"DataType=0x{dtype:04X}",
            f"AccessType={access}", f"DefaultValue={default}", f"PDOMapping={int(mappable)}", ""]


def _var(index: int, name: str, dtype: int, access: str, default: str) -> list[str]:
    return _entry(f"{index:04X}", name, dtype, access, default)


def _record(index: int, name: str, subs: list[tuple[str, int, str, str]], code: int = 0x9,
            mappable: bool = False, sub0: tuple[str, str] = ("Highest sub-index supported", "ro")) -> list[str]:
    out = [f"[{index:04X}]", f"ParameterName={name}", f"ObjectType=0x{code:X}", f"SubNumber={len(subs) + 1}", ""]
    out += _entry(f"{index:04X}sub0", sub0[0], 0x0005, sub0[1], str(len(subs)))
    for n, (sub_name, dtype, access, default) in enumerate(subs, 1):
        out += _entry(f"{index:04X}sub{n:X}", sub_name, dtype, access, default, mappable)
    return out


def _pdo(kind: str, index: int, n: int, pdo: Pdo) -> list[str]:
    comm = [(f"COB-ID used by {kind}", 0x0007, "rw", pdo.cob_id), ("Transmission type", 0x0005, "rw", "1")]
    if kind == "TPDO":
        comm += [("Inhibit time", 0x0006, "rw", "0"), ("Reserved", 0x0005, "rw", "0"),
                 ("Event timer", 0x0006, "rw", "0")]
    maps = [(f"Mapped object {k}", 0x0007, "rw", f"0x{i:04X}{s:02X}{b:02X}")
            for k, (i, s, b, _w) in enumerate(pdo.maps, 1)]
    return _record(index, f"{kind}{n} communication parameter", comm) \
        + _record(index + 0x200, f"{kind}{n} mapping parameter", maps, sub0=("Number of mapped objects", "rw"))


def _array(index: int, access: str, subs: dict[int, str]) -> list[str]:
    name, dtype, _prefix = OBJECTS[index]
    items = [(subs.get(n, f"{_prefix} {n}"), dtype, access, "0") for n in range(1, max(subs) + 1)]
    return _record(index, name, items, code=0x8, mappable=True)


def main(argv: list[str]) -> int:
    outdir = Path(argv[1]) if len(argv) > 1 else Path(__file__).parent
    for dev in devices():
        od, _diags = load_bytes(eds(dev).encode("ascii"), dev.file, "eds")
        if od is None:
            print(f"describe.py: {dev.file} does not read back", file=sys.stderr)
            return 1
        (outdir / dev.file).write_text(write_eds(od), encoding="ascii")  # in odgen's canonical EDS form
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
