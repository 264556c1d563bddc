"""What the CiA 302 master costs on a Cortex-M4 (docs/master.md), for 4 and 16 slaves.

FLASH: the master's four files (MASTER_SOURCES of odgen/toolchain.py) compiled with the flags of
footprint.py and -DODG_MASTER_MAX_SLAVES=n. RAM: sizeof(odg_master_t) at n slaves, read from an
object that holds it as a constant (the application's static odg_master_t). The node and the
dictionary the master runs beside are footprint.py's and linked.py's. The boot time on vcan is
master_boot.py's. run.py runs this part (--parts master).
"""

from __future__ import annotations

import subprocess

from common import BUILD as BENCH
from footprint import CFLAGS, RUNTIME, ensure_toolchain, sections

from odgen import toolchain

BUILD = BENCH / "master"
SLAVES = (4, 16)
SIZEOF = '#include "odg_master.h"\nconst unsigned long odg_master_bytes = sizeof(odg_master_t);\n'


def _compile(source: str, obj: str, slaves: int) -> None:
    subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-DODG_MASTER_MAX_SLAVES={slaves}u", f"-I{RUNTIME}", "-c", source,
                    "-o", obj], check=True, capture_output=True, text=True)


def _ram(slaves: int) -> int:
    """sizeof(odg_master_t): the constant's four bytes in the object's .rodata, little endian."""
    src, obj = BUILD / "sizeof.c", BUILD / f"sizeof-{slaves}.o"
    src.write_text(SIZEOF, encoding="utf-8")
    _compile(str(src), str(obj), slaves)
    dump = subprocess.run(["arm-none-eabi-objcopy", "-O", "binary", "--only-section=.rodata*", str(obj), "/dev/stdout"],
                          check=True, capture_output=True).stdout
    return int.from_bytes(dump[:4], "little")


def measure(slaves: int) -> dict[str, int]:
    flash = 0
    for source in toolchain.master_sources():
        obj = BUILD / f"{source.stem}-{slaves}.o"
        _compile(str(source), str(obj), slaves)
        sec = sections(obj)
        flash += sec["text"] + sec["rodata"] + sec["data"]
    return {"slaves": slaves, "flash": flash, "ram": _ram(slaves)}


def run() -> dict[str, object]:
    ensure_toolchain()
    BUILD.mkdir(parents=True, exist_ok=True)
    rows = [measure(n) for n in SLAVES]
    lines = ["## The CiA 302 master (Cortex-M4)", "",
             "The master's four files (SDO client, NMT master, LSS master, configuration manager) with "
             "`-DODG_MASTER_MAX_SLAVES`; RAM is its state, one `odg_master_t` (docs/master.md).", "",
             "| slaves | FLASH (bytes) | RAM (bytes) |", "|---|---|---|"]
    lines += [f"| {r['slaves']} | {r['flash']} | {r['ram']} |" for r in rows]
    return {"rows": rows, "targets": [], "markdown": "\n".join(lines) + "\n"}
