"""`odgen profile ds401`: a CiA 401 (generic I/O module) description from channel counts.

The CiA 401 objects come from one table (`PROFILE`); the communication objects and the
default PDO mapping follow CiA 301 / CiA 401. The result is an `ObjectDictionary` written
by the ordinary EDS writer, so the same arguments always give the same bytes. Where each
type, access and default comes from is in docs/ds401.md.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ..choices import DS401_MAX_ANALOG as MAX_ANALOG
from ..choices import DS401_MAX_DIGITAL as MAX_DIGITAL
from ..choices import DS401_NAME
from ..choices import DS401_WIDTHS as WIDTHS
from ..fileio import write_atomic
from ..model import ARRAY, RECORD, VAR, BASIC_TYPES, Obj, ObjectDictionary, Sub, parse_value
from ..model.cia301 import COB_INVALID, PDO_BASE_STEP, RPDO_BASE, RPDO_COMM, TPDO_BASE, TPDO_COMM

if TYPE_CHECKING:
    from ..pipeline import Result

U8, U16, U32, BOOL = 0x0005, 0x0006, 0x0007, 0x0001
INT_OF_WIDTH = {8: 0x0002, 16: 0x0003, 32: 0x0004}
MAX_GROUPS = 254  # sub-indices 1..0xFE of an ARRAY: MAX_DIGITAL is MAX_GROUPS * 8 bits (a test checks)
FUNCTION_BITS = {"di": 16, "do": 17, "ai": 18, "ao": 19}  # CiA 401 device type, additional information


@dataclass(frozen=True)
class Ds401:
    """What `odgen profile ds401` was asked for; digital counts in bits."""

    di: int = 0
    do: int = 0
    ai: int = 0
    ao: int = 0
    ai_width: int = 16
    ao_width: int = 16
    name: str = DS401_NAME
    vendor_id: int = 0
    product_code: int = 0
    revision: int = 0

    def channels(self, kind: str) -> int:
        """Sub-indices per kind: 8-bit groups for digital, channels for analog."""
        count: int = getattr(self, kind)
        return (count + 7) // 8 if kind in ("di", "do") else count

    def width(self, kind: str) -> int:
        return {"di": 8, "do": 8, "ai": self.ai_width, "ao": self.ao_width}[kind]

    def problems(self) -> list[str]:
        out = [f"--{k} must be 0..{m}, not {getattr(self, k)}"
               for k, m in (("di", MAX_DIGITAL), ("do", MAX_DIGITAL), ("ai", MAX_ANALOG), ("ao", MAX_ANALOG))
               if not 0 <= getattr(self, k) <= m]
        out += [f"--{k.replace('_', '-')} must be 8, 16 or 32" for k in ("ai_width", "ao_width")
                if getattr(self, k) not in WIDTHS]
        out += [f"--{k.replace('_', '-')} must be 0..0xFFFFFFFF" for k in ("vendor_id", "product_code", "revision")
                if not 0 <= getattr(self, k) <= 0xFFFFFFFF]
        if not self.name.strip() or any(c in self.name for c in "\r\n"):
            out.append("--name must be one non-empty line")
        return out


@dataclass(frozen=True)
class ProfileObject:
    """One CiA 401 object: an ARRAY over the kind's channels, or a VAR when `array` is False."""

    index: int
    kind: str  # di | do | ai | ao: whose count makes it present and sizes it
    name: str
    sub_name: str  # {n}: channel number; {lo}/{hi}: first/last line of an 8-bit group
    data_type: int | None  # None: INTEGERn of the kind's width
    access: str
    pdo: bool
    default: str
    array: bool = True
    width: int | None = None  # only present when the kind's width is this


# CiA 401 objects; sources per row in docs/ds401.md.
PROFILE = (
    ProfileObject(0x6000, "di", "Read input 8-bit", "Read input {lo} to {hi}", U8, "ro", True, "0x00"),
    ProfileObject(0x6002, "di", "Polarity input 8-bit", "Polarity input {lo} to {hi}", U8, "rw", False, "0x00"),
    ProfileObject(0x6005, "di", "Global interrupt enable digital 8-bit", "", BOOL, "rw", False, "1", array=False),
    ProfileObject(0x6006, "di", "Interrupt mask any change 8-bit", "Interrupt any change {lo} to {hi}",
                  U8, "rw", False, "0xFF"),
    ProfileObject(0x6007, "di", "Interrupt mask low-to-high 8-bit", "Interrupt low-to-high {lo} to {hi}",
                  U8, "rw", False, "0x00"),
    ProfileObject(0x6008, "di", "Interrupt mask high-to-low 8-bit", "Interrupt high-to-low {lo} to {hi}",
                  U8, "rw", False, "0x00"),
    ProfileObject(0x6200, "do", "Write output 8-bit", "Write output {lo} to {hi}", U8, "rww", True, "0x00"),
    ProfileObject(0x6202, "do", "Change polarity output 8-bit", "Polarity output {lo} to {hi}", U8, "rw", False,
                  "0x00"),
    ProfileObject(0x6206, "do", "Error mode output 8-bit", "Error mode output {lo} to {hi}", U8, "rw", False, "0xFF"),
    ProfileObject(0x6207, "do", "Error value output 8-bit", "Error value output {lo} to {hi}", U8, "rw", False,
                  "0x00"),
    ProfileObject(0x6400, "ai", "Read analog input 8-bit", "Analog input {n}", None, "ro", True, "0", width=8),
    ProfileObject(0x6401, "ai", "Read analog input 16-bit", "Analog input {n}", None, "ro", True, "0", width=16),
    ProfileObject(0x6402, "ai", "Read analog input 32-bit", "Analog input {n}", None, "ro", True, "0", width=32),
    ProfileObject(0x6410, "ao", "Write analog output 8-bit", "Analog output {n}", None, "rww", True, "0", width=8),
    ProfileObject(0x6411, "ao", "Write analog output 16-bit", "Analog output {n}", None, "rww", True, "0", width=16),
    ProfileObject(0x6412, "ao", "Write analog output 32-bit", "Analog output {n}", None, "rww", True, "0", width=32),
    ProfileObject(0x6421, "ai", "Analog input interrupt trigger selection", "Trigger selection input {n}", U8, "rw",
                  False, "0x07"),
    ProfileObject(0x6423, "ai", "Analog input global interrupt enable", "", BOOL, "rw", False, "0", array=False),
    ProfileObject(0x6424, "ai", "Analog input interrupt upper limit integer", "Upper limit input {n}", 0x0004, "rw",
                  False, "0"),
    ProfileObject(0x6425, "ai", "Analog input interrupt lower limit integer", "Lower limit input {n}", 0x0004, "rw",
                  False, "0"),
    ProfileObject(0x6426, "ai", "Analog input interrupt delta unsigned", "Delta input {n}", U32, "rw", False, "0"),
    ProfileObject(0x6443, "ao", "Analog output error mode", "Error mode output {n}", U8, "rw", False, "0x01"),
    ProfileObject(0x6444, "ao", "Analog output error value integer", "Error value output {n}", 0x0004, "rw", False,
                  "0"),
)

PROCESS_OBJECTS = {("di", 8): 0x6000, ("do", 8): 0x6200, ("ai", 8): 0x6400, ("ai", 16): 0x6401,
                   ("ai", 32): 0x6402, ("ao", 8): 0x6410, ("ao", 16): 0x6411, ("ao", 32): 0x6412}
MAP_SUBS = 8  # every mapping record offers 8 entries, used or not


def value_sub(subindex: int, name: str, data_type: int, access: str, default: str, pdo: bool = False) -> Sub:
    return Sub(subindex, name, object_type=VAR, data_type=data_type, access=access, pdo_mapping=pdo,
               default=parse_value(default, BASIC_TYPES[data_type]))


def var(index: int, name: str, data_type: int, access: str, default: str) -> Obj:
    return Obj(index, name, object_code=VAR, subs={0: value_sub(0, "", data_type, access, default)})


def container(index: int, name: str, subs: list[Sub], code: int = ARRAY, highest: int | None = None) -> Obj:
    """An ARRAY/RECORD with sub0 = highest sub-index (or `highest`, e.g. a mapping's entry count)."""
    top = highest if highest is not None else max((s.subindex for s in subs), default=0)
    access = "rw" if highest is not None else "ro"
    sub0 = value_sub(0, "Highest sub-index supported" if highest is None else "Number of mapped objects",
                     U8, access, str(top))
    return Obj(index, name, object_code=code, subs={s.subindex: s for s in [sub0, *subs]}, sub_number=len(subs) + 1)


def mapping_layout(p: Ds401) -> dict[int, list[tuple[int, int, int]]]:
    """CiA 401 default mapping: PDO communication index -> [(index, sub, bits)], within 64 bits each."""
    layout: dict[int, list[tuple[int, int, int]]] = {}
    for kind, base in (("di", TPDO_COMM), ("do", RPDO_COMM), ("ai", TPDO_COMM), ("ao", RPDO_COMM)):
        width, count = p.width(kind), p.channels(kind)
        index = PROCESS_OBJECTS[(kind, width)]
        if kind in ("di", "do"):
            layout[base] = [(index, s, 8) for s in range(1, min(count, 8) + 1)]
            continue
        per_pdo = min(4, 64 // width)  # 4 channels as CiA 401 for 8/16 bit, 2 for 32 bit
        for n in range(3):
            subs = range(n * per_pdo + 1, min(count, (n + 1) * per_pdo) + 1)
            layout[base + 1 + n] = [(index, s, width) for s in subs]
    return layout


def _pdo_objects(p: Ds401) -> list[Obj]:
    objects = []
    layout = mapping_layout(p)
    for n in range(4):
        for base, kind, cob in ((RPDO_COMM, "RPDO", RPDO_BASE), (TPDO_COMM, "TPDO", TPDO_BASE)):
            entries = layout[base + n]
            cob_id = f"$NODEID+0x{(0 if entries else COB_INVALID) + cob + PDO_BASE_STEP * n:X}"
            comm = [value_sub(1, f"COB-ID used by {kind}", U32, "rw", cob_id),
                    value_sub(2, "Transmission type", U8, "rw", "0xFF")]
            if kind == "TPDO":
                comm += [value_sub(3, "Inhibit time", U16, "rw", "0"), value_sub(5, "Event timer", U16, "rw", "0")]
            objects.append(container(base + n, f"{kind} communication parameter {n + 1}", comm, RECORD))
            maps = [value_sub(s, f"Mapped object {s}", U32, "rw",
                              "0x{:04X}{:02X}{:02X}".format(*entries[s - 1]) if s <= len(entries) else "0x00000000")
                    for s in range(1, MAP_SUBS + 1)]
            objects.append(container(base + 0x200 + n, f"{kind} mapping parameter {n + 1}", maps, RECORD,
                                     highest=len(entries)))
    return objects


def _profile_objects(p: Ds401) -> list[Obj]:
    objects = []
    for row in PROFILE:
        count, width = p.channels(row.kind), p.width(row.kind)
        if count == 0 or (row.width is not None and row.width != width):
            continue
        data_type = row.data_type or INT_OF_WIDTH[width]
        if not row.array:
            objects.append(var(row.index, row.name, data_type, row.access, row.default))
            continue
        subs = [value_sub(n, row.sub_name.format(n=n, lo=8 * n - 7, hi=8 * n), data_type, row.access,
                          row.default, row.pdo) for n in range(1, count + 1)]
        objects.append(container(row.index, row.name, subs))
    return objects


def _communication_objects(p: Ds401) -> list[Obj]:
    device_type = 0x0191 | sum(1 << bit for kind, bit in FUNCTION_BITS.items() if p.channels(kind))
    identity = [value_sub(1, "Vendor-ID", U32, "ro", f"0x{p.vendor_id:08X}"),
                value_sub(2, "Product code", U32, "ro", f"0x{p.product_code:08X}"),
                value_sub(3, "Revision number", U32, "ro", f"0x{p.revision:08X}"),
                value_sub(4, "Serial number", U32, "ro", "0x00000000")]
    parts = ("all", "communication", "application")
    store = [value_sub(s, f"Save {what} parameters", U32, "rw", "0x00000001") for s, what in enumerate(parts, 1)]
    restore = [value_sub(s, f"Restore {what} default parameters", U32, "rw", "0x00000001")
               for s, what in enumerate(parts, 1)]
    sdo = [value_sub(1, "COB-ID client to server", U32, "ro", "$NODEID+0x600"),
           value_sub(2, "COB-ID server to client", U32, "ro", "$NODEID+0x580")]
    return [var(0x1000, "Device type", U32, "ro", f"0x{device_type:08X}"),
            var(0x1001, "Error register", U8, "ro", "0x00"),
            container(0x1010, "Store parameters", store),
            container(0x1011, "Restore default parameters", restore),
            var(0x1017, "Producer heartbeat time", U16, "rw", "0"),
            container(0x1018, "Identity object", identity, RECORD),
            container(0x1200, "SDO server parameter", sdo, RECORD)]


def _arguments(p: Ds401) -> str:
    return (f"--di {p.di} --do {p.do} --ai {p.ai} --ao {p.ao} --ai-width {p.ai_width} --ao-width {p.ao_width} "
            f"--vendor-id 0x{p.vendor_id:08X} --product-code 0x{p.product_code:08X} --revision 0x{p.revision:08X}")


def build(p: Ds401, file_name: str = "ds401.eds") -> ObjectDictionary:
    od = ObjectDictionary(source=file_name, format="eds")
    info = od.ensure_section("FileInfo")
    for key, text in (("FileName", file_name), ("FileVersion", "1"), ("FileRevision", "0"), ("EDSVersion", "4.0"),
                      ("Description", f"CiA 401 generic I/O module: {p.di} DI, {p.do} DO, {p.ai} AI, {p.ao} AO"),
                      ("CreatedBy", "odgen profile ds401")):
        info.set(key, text)
    device = od.ensure_section("DeviceInfo")
    for key, text in (("VendorName", ""), ("VendorNumber", f"0x{p.vendor_id:08X}"), ("ProductName", p.name),
                      ("ProductNumber", f"0x{p.product_code:08X}"), ("RevisionNumber", f"0x{p.revision:08X}"),
                      ("OrderCode", ""), *((f"BaudRate_{r}", "1" if r >= 125 else "0")
                                          for r in (10, 20, 50, 125, 250, 500, 800, 1000)),
                      ("SimpleBootUpMaster", "0"), ("SimpleBootUpSlave", "1"), ("Granularity", "8"),
                      ("DynamicChannelsSupported", "0"), ("GroupMessaging", "0"), ("NrOfRXPDO", "4"),
                      ("NrOfTXPDO", "4"), ("LSS_Supported", "0")):
        device.set(key, text)
    comments = od.ensure_section("Comments")
    comments.set("Lines", "1")
    comments.set("Line1", f"odgen profile ds401 {_arguments(p)}")
    for obj in [*_communication_objects(p), *_pdo_objects(p), *_profile_objects(p)]:
        od.objects[obj.index] = obj
    return od


def options_toml(p: Ds401) -> str:
    """Generator options: hooks on the process data, persistence for the parameters."""
    present = {row.index for row in PROFILE if p.channels(row.kind) and row.width in (None, p.width(row.kind))}
    inputs = [PROCESS_OBJECTS[(k, p.width(k))] for k in ("di", "ai") if p.channels(k)]
    outputs = [PROCESS_OBJECTS[(k, p.width(k))] for k in ("do", "ao") if p.channels(k)]
    parameters = sorted(present - set(inputs) - set(outputs))
    lines = ['[[entry]]', 'match = ["0x1017", "0x1400-0x1A03"]', 'storage = "persist:comm"', ""]
    if parameters:
        lines += ["[[entry]]", f"match = {_quoted(f'0x{i:04X}' for i in parameters)}",
                  'storage = "persist:app"', ""]
    # Inputs are refreshed before every read (SDO upload or TPDO); outputs applied after every write,
    # and again when their polarity (0x6202) changes.
    outputs += [0x6202] if p.channels("do") else []
    for indices, hook in ((inputs, "pre_read"), (outputs, "post_write")):
        if indices:
            lines += ["[[entry]]", f"match = {_quoted(f'0x{i:04X}sub1-fe' for i in indices)}",
                      f'hooks = ["{hook}"]', ""]
    return "\n".join(lines)


C_INT = {8: "int8_t", 16: "int16_t", 32: "int32_t"}
GLUE = ("ds401_app.h",)


def glue_files(p: Ds401) -> dict[str, str]:
    """The header that configures the application glue, runtime/profiles/ds401.c (hooks, polarity,
    change-of-state TPDOs): channel counts, the analog objects and their C types."""
    from ..codegen.render import environment  # jinja2: only when C is generated

    env = environment()
    values = {"arguments": _arguments(p), "di": p.channels("di"), "do": p.channels("do"), "ai": p.ai, "ao": p.ao,
              "ai_index": PROCESS_OBJECTS[("ai", p.ai_width)], "ao_index": PROCESS_OBJECTS[("ao", p.ao_width)],
              "ai_ctype": C_INT[p.ai_width], "ao_ctype": C_INT[p.ao_width], "ai_width": p.ai_width,
              "ao_width": p.ao_width}
    return {name: env.get_template(f"{name}.j2").render(**values) for name in GLUE}


def generate_c(p: Ds401, eds: Path, name: str | None = None, node_id: int | None = None) -> Result:
    """`--generate`: the dictionary C of the written EDS with the profile's options, plus the glue."""
    from ..pipeline import Request, generate

    result = generate(Request(eds, name=name, node_id=node_id, defaults=options_toml(p)))
    if result.files:
        result.files.update(glue_files(p))
    return result


def _quoted(items: Iterable[str]) -> str:
    return "[" + ", ".join(f'"{item}"' for item in items) + "]"


def write(p: Ds401, path: Path) -> str:
    """The EDS text for `p`, written atomically to `path`."""
    from ..formats.eds_writer import write_eds  # the readers and rules: not needed to build the parser

    text = write_eds(build(p, path.name))
    write_atomic(path, text)
    return text
