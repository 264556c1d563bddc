"""The runtime's C sources and compiler flags, defined once.

`odgen check`, the node build (`odgen node`, `odgen roundtrip`), the CMake module (through
`odgen --toolchain cmake`) and the benchmarks all build the runtime from these lists.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Callable
from pathlib import Path

from . import __version__
from .assets import runtime_dir
from .errors import OdgenError

STANDARD = "-std=c99"
WARNINGS = ("-Wall", "-Wextra", "-Werror", "-pedantic")
CFLAGS = (STANDARD, *WARNINGS)
# the dictionary runtime a firmware links (CMake: odgen::runtime): the core and the persistence layer
CORE_SOURCES = ("odg.c", "odg_verify.c", "odg_persist.c", "odg_persist_slot.c", "odg_persist_fixed.c",
                "odg_persist_migrate.c")
# The node (CMake: odgen::node), lowest first (docs/design.md, "The node runtime"): the shared
# helpers, the services (TIME, LSS, communication values, EMCY, heartbeat, PDOs, SYNC, SDO server)
# and the hub (NMT, dispatch).
SERVICE_SOURCES = ("odg_node_io.c", "odg_time.c", "odg_lss.c", "odg_comm.c", "odg_err.c", "odg_hb.c", "odg_pdo.c",
                   "odg_sync.c", "odg_sdo.c", "odg_node.c")
# The CiA 302 master above the node (CMake: odgen::master): SDO clients, NMT and LSS master, configuration manager.
MASTER_SOURCES = ("odg_sdo_client.c", "odg_nmt_master.c", "odg_lss_master.c", "odg_master.c")
MASTER_MAIN = "linux/odg_master_main.c"  # the SocketCAN master program's main()
HOST_SOURCES = ("odg_nv_file.c", "linux/odg_socketcan.c")  # NV in a file and SocketCAN: POSIX hosts only
NODE_MAIN = "linux/odg_node_main.c"  # the SocketCAN node program's main(); apps bring their own


def compiler() -> str:
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        raise OdgenError("no C compiler found (set CC, or install gcc)")
    return cc


def core_sources() -> list[Path]:
    return [runtime_dir() / name for name in CORE_SOURCES]


def service_sources() -> list[Path]:
    return [runtime_dir() / name for name in SERVICE_SOURCES]


def master_sources() -> list[Path]:
    return [runtime_dir() / name for name in MASTER_SOURCES]


def host_sources() -> list[Path]:
    return [runtime_dir() / name for name in HOST_SOURCES]


def node_sources() -> list[Path]:
    """The core, the node's services and the POSIX host's NV file and SocketCAN, without the node main."""
    return [*core_sources(), *service_sources(), *host_sources()]


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
        f"set(ODGEN_NODE_SOURCES {cmake_list([p.as_posix() for p in service_sources()])})",
        f"set(ODGEN_MASTER_SOURCES {cmake_list([p.as_posix() for p in master_sources()])})",
        f"set(ODGEN_C_WARNINGS {cmake_list(WARNINGS)})",
        ""])


def make_script() -> str:
    """What `odgen --toolchain make` prints: the same lists as make variables (examples/*/Makefile
    include it). Paths with spaces do not survive make's word lists."""
    def words(paths: list[Path]) -> str:
        return " ".join(p.as_posix() for p in paths)
    return "\n".join([
        f"ODGEN_VERSION := {__version__}",
        f"ODGEN_RUNTIME_DIR := {runtime_dir().as_posix()}",
        f"ODGEN_RUNTIME_SOURCES := {words(core_sources())}",
        f"ODGEN_NODE_SOURCES := {words(service_sources())}",
        f"ODGEN_MASTER_SOURCES := {words(master_sources())}",
        f"ODGEN_HOST_SOURCES := {words(host_sources())}",
        f"ODGEN_NODE_MAIN := {(runtime_dir() / NODE_MAIN).as_posix()}",
        f"ODGEN_CFLAGS := {' '.join(CFLAGS)}",
        ""])


SCRIPTS: dict[str, Callable[[], str]] = {"cmake": cmake_script, "make": make_script}
