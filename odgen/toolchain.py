"""The runtime's C sources and compiler flags, defined once.

`odgen check`, the node build (`odgen node`, `odgen roundtrip`), the CMake module (through
`odgen --toolchain cmake`) and the benchmarks all build the runtime from these lists.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from . import __version__
from .assets import runtime_dir
from .errors import OdgenError

STANDARD = "-std=c99"
WARNINGS = ("-Wall", "-Wextra", "-Werror", "-pedantic")
CFLAGS = (STANDARD, *WARNINGS)
# the dictionary runtime a firmware links: the core and the persistence layer
CORE_SOURCES = ("odg.c", "odg_persist.c", "odg_persist_slot.c", "odg_persist_fixed.c", "odg_persist_migrate.c")
NODE_MAIN = "linux/odg_node_main.c"  # the SocketCAN node program's main(); apps bring their own


def compiler() -> str:
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        raise OdgenError("no C compiler found (set CC, or install gcc)")
    return cc


def core_sources() -> list[Path]:
    return [runtime_dir() / name for name in CORE_SOURCES]


def node_sources() -> list[Path]:
    """The core, the node layer (SDO, PDO, NV file) and the Linux adapter, without the node main."""
    runtime = runtime_dir()
    top = sorted(runtime.glob("odg*.c"))
    linux = sorted(p for p in (runtime / "linux").glob("*.c") if p != runtime / NODE_MAIN)
    return top + linux


def include_dirs(node: bool = False) -> list[Path]:
    return [runtime_dir(), runtime_dir() / "linux"] if node else [runtime_dir()]


def cmake_script() -> str:
    """What `odgen --toolchain cmake` prints: the same lists as CMake variables (odgen.cmake includes it)."""
    def cmake_list(items: list[str] | tuple[str, ...]) -> str:
        return '"' + ";".join(items) + '"'
    return "\n".join([
        f'set(ODGEN_VERSION "{__version__}")',
        f'set(ODGEN_RUNTIME_DIR "{runtime_dir().as_posix()}")',
        f"set(ODGEN_RUNTIME_SOURCES {cmake_list([p.as_posix() for p in core_sources()])})",
        f"set(ODGEN_C_WARNINGS {cmake_list(WARNINGS)})",
        ""])
