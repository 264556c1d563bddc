"""The CANopen node layer (runtime/odg_node*.c, odg_sdo.c, odg_pdo.c) and the SocketCAN node
program (runtime/linux/).

The C tests in tests/node/ drive a node over a fake transport against dictionaries that
`odgen generate` makes here: alltypes (SDO, NMT, heartbeat, EMCY), tests/node/pdo-node.eds
(SYNC, PDOs, remapping) and the io-node example with its hooks (PDOs through hooks,
persistence in a file across a power cycle). Each is built with gcc and clang under strict
C99 warnings and once under AddressSanitizer and UndefinedBehaviorSanitizer, and must end
with "N passed, 0 failed". The node program is compiled against several generated
dictionaries, and run on vcan0 against python-canopen (tools/vcan: the host's vcan, else a
User-Mode Linux guest shared by all CAN tests). Everything is built in pytest's temporary directories.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from odgen import toolchain

from .cprog import BUILDS, EXTRA, STRICT, build, compiler, run
from .conftest import FIXTURES, ROOT

RUNTIME = ROOT / "runtime"
LINUX = RUNTIME / "linux"
NODE_TESTS = ROOT / "tests" / "node"
CHECK_H = ROOT / "tests" / "runtime"  # check.h

CORE = tuple(toolchain.core_sources())  # the lists odgen node, CMake and the examples build from
NODE = tuple(toolchain.service_sources())
PROGRAM_SOURCES = (*CORE, *NODE, *toolchain.host_sources(), RUNTIME / toolchain.NODE_MAIN)

# name -> (EDS, options file or None)
DICTS: dict[str, tuple[Path, Path | None]] = {
    "alltypes": (FIXTURES / "generate" / "alltypes.eds", FIXTURES / "generate" / "alltypes.toml"),
    "io_node": (ROOT / "examples" / "io-node" / "io-node.eds", ROOT / "examples" / "io-node" / "io-node.toml"),
    "pdo_node": (NODE_TESTS / "pdo-node.eds", None),
    "lss_node": (NODE_TESTS / "lss-node.eds", NODE_TESTS / "lss-node.toml"),
    "wide_node": (NODE_TESTS / "wide-node.eds", None),
    "noblock_node": (FIXTURES / "generate" / "alltypes.eds", NODE_TESTS / "noblock-node.toml"),
}
# test program -> (dictionary, extra runtime sources)
PROGRAMS: dict[str, tuple[str, tuple[Path, ...]]] = {
    "test_node_sdo": ("alltypes", ()),
    "test_node_pdo": ("pdo_node", ()),
    "test_node_short": ("pdo_node", ()),  # a 64-bit entry mapped with 32 bits (PDO003)
    "test_node_io": ("io_node", (RUNTIME / "odg_nv_file.c",)),
    "test_node_robust": ("alltypes", ()),
    "test_node_lss": ("lss_node", ()),
    "test_node_time": ("lss_node", ()),
    "test_node_window": ("lss_node", ()),
    "test_node_wide": ("wide_node", ()),
    "test_node_can": ("pdo_node", ()),
    "test_node_noblock": ("noblock_node", ()),  # [node] sdo_block = false: no SDO block transfer
}
LSS = ("-DODG_NODE_LSS=1",)  # the node and the program are built with the LSS slave
NO_BLOCK = ("-DODG_NODE_SDO_BLOCK=0",)  # the SDO server without block transfer
# test_node_wide: sized by the dictionary alone (8 + 8 PDOs, 32 mapping entries), no other define
DEFINES: dict[str, tuple[str, ...]] = {"test_node_lss": LSS, "test_node_wide": ('-DODG_CONFIG="wide_node_config.h"',),
                                       "test_node_noblock": ('-DODG_CONFIG="noblock_node_config.h"',)}



def generate(name: str, out: Path, with_options: bool = True) -> Path:
    eds, options = DICTS[name]
    out.mkdir(parents=True, exist_ok=True)
    cmd = [sys.executable, "-m", "odgen", "generate", str(eds), "-o", str(out), "--name", name]
    if options is not None and with_options:
        cmd += ["--options", str(options)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, f"{' '.join(cmd)}\n{done.stdout}{done.stderr}"
    assert (out / f"{name}.c").is_file()
    return out


@pytest.fixture(scope="module")
def generated(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Every dictionary, generated once for the module: <dir>/<name>/<name>.[ch]."""
    base = tmp_path_factory.mktemp("dicts")
    for name in DICTS:
        generate(name, base / name)
    return base




@pytest.mark.parametrize("build_name", list(BUILDS))
@pytest.mark.parametrize("program", list(PROGRAMS))
def test_node_program(program: str, build_name: str, generated: Path, tmp_path: Path) -> None:
    cc, flags = BUILDS[build_name]
    dict_name, extra = PROGRAMS[program]
    gen = generated / dict_name
    sources = (NODE_TESTS / f"{program}.c", gen / f"{dict_name}.c", *CORE, *NODE, *extra)
    exe = tmp_path / program
    build(cc, (*flags, *DEFINES.get(program, ())), sources, (gen, RUNTIME, NODE_TESTS, CHECK_H), exe)
    run(exe, tmp_path)


def test_sdo_small_block_size(generated: Path, tmp_path: Path) -> None:
    """Build-time limits: with 4 segments per sub-block the SDO tests run block downloads of
    several sub-blocks (and a lost segment in one of them); fewer PDOs still build."""
    gen = generated / "alltypes"
    sources = (NODE_TESTS / "test_node_sdo.c", gen / "alltypes.c", *CORE, *NODE)
    flags = ("-O2", "-DODG_NODE_MAX_RPDO=1u", "-DODG_NODE_MAX_TPDO=1u", "-DODG_NODE_MAX_MAP=2u",
             "-DODG_NODE_SDO_BLKSIZE=4u")
    exe = tmp_path / "test_node_sdo"
    build("gcc", flags, sources, (gen, RUNTIME, NODE_TESTS, CHECK_H), exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("size", [0, 8])
def test_small_communication_copy(size: int, generated: Path, tmp_path: Path) -> None:
    """With room for fewer communication values than the dictionary has, reset communication
    brings back the first objects that fit and leaves the rest as they are (none with 0)."""
    gen = generated / "pdo_node"
    sources = (NODE_TESTS / "test_node_pdo.c", gen / "pdo_node.c", *CORE, *NODE)
    exe = tmp_path / "test_node_pdo"
    build("gcc", ("-O2", f"-DODG_NODE_COMM_BYTES={size}u"), sources, (gen, RUNTIME, NODE_TESTS, CHECK_H), exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_node_sources_warning_free(cc: str, tmp_path: Path) -> None:
    """The node sources compile alone, -Wconversion clean, with and without the LSS slave and SDO
    block transfer; the Linux ones too."""
    for source, defines in [(s, d) for s in (*NODE, LINUX / "odg_socketcan.c") for d in ((), LSS, NO_BLOCK)]:
        cmd = [compiler(cc), *STRICT, *EXTRA, *defines, "-Os", f"-I{RUNTIME}", f"-I{LINUX}", "-c", str(source),
               "-o", str(tmp_path / (source.name + ".o"))]
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        assert done.returncode == 0, f"{' '.join(cmd)}\n{done.stderr}"


def test_no_block_code_without_sdo_block(tmp_path: Path) -> None:
    """Without ODG_NODE_SDO_BLOCK the SDO server has no block transfer code at all (unoptimised,
    so that every static function would show), with it the same names are there."""
    def names(*defines: str) -> set[str]:
        obj = tmp_path / f"odg_sdo{len(defines)}.o"
        subprocess.run([compiler("gcc"), *STRICT, *defines, "-O0", f"-I{RUNTIME}", "-c", str(RUNTIME / "odg_sdo.c"),
                        "-o", str(obj)], check=True)
        out = subprocess.run(["nm", str(obj)], capture_output=True, text=True, check=True).stdout
        return {line.split()[-1] for line in out.splitlines() if line.strip()}

    block = {n for n in names() if "block" in n or "crc" in n}
    assert {"block_download_initiate", "block_upload_initiate", "crc16"} <= block
    assert not names(*NO_BLOCK) & block


def test_node_core_has_no_stdio_or_heap() -> None:
    forbidden = re.compile(r"#\s*include\s*<(stdio|stdlib|malloc)\.h>|\b(malloc|calloc|realloc|free|printf)\s*\(")
    for source in NODE:
        text = source.read_text(encoding="utf-8")
        assert not forbidden.search(text), f"{source.name}: {forbidden.search(text)}"


def node_program(cc: str, name: str, gen: Path, out: Path, *extra: Path) -> Path:
    exe = out / f"{name}-node-{cc}"
    build(cc, ("-O2", f"-DODG_DICT={name}"), (*PROGRAM_SOURCES, gen / f"{name}.c", *extra),
          (gen, RUNTIME, LINUX), exe)
    return exe


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_node_program_builds_against_any_dictionary(cc: str, generated: Path, tmp_path: Path) -> None:
    """odg_node_main.c links with any generated dictionary; hook functions an options file
    names come from another source file. Bad arguments exit 2 with the usage, a missing
    interface 1 with the reason, both on stderr only."""
    plain = generate("io_node", tmp_path / "io_node", with_options=False)  # no hooks to provide
    exes = [
        node_program(cc, "io_node", plain, tmp_path),
        node_program(cc, "pdo_node", generated / "pdo_node", tmp_path),
        node_program(cc, "alltypes", generated / "alltypes", tmp_path, NODE_TESTS / "alltypes_hooks.c"),
    ]
    for exe in exes:
        for args, status, text in [([], 2, "usage"), (["--iface", "x", "--node-id", "0"], 2, "usage"),
                                   (["--iface", "odg-no-such-if", "--node-id", "5"], 1, "odg-no-such-if")]:
            done = subprocess.run([str(exe), *args], capture_output=True, text=True, check=False, timeout=10)
            assert done.returncode == status and done.stdout == "" and text in done.stderr, done


def test_node_program_on_vcan(generated: Path, tmp_path: Path, vcan_bus) -> None:
    """The node program against python-canopen on vcan0: boot-up, heartbeat, NMT, SDO
    expedited/segmented/block, aborts, PDOs, a stored value surviving SIGTERM and a restart."""
    alltypes = node_program("gcc", "alltypes", generated / "alltypes", tmp_path, NODE_TESTS / "alltypes_hooks.c")
    io_node = node_program("gcc", "io_node", generate("io_node", tmp_path / "io_plain", with_options=False), tmp_path)
    cmd = [sys.executable, str(NODE_TESTS / "vcan_node.py"), str(alltypes), str(io_node), str(tmp_path)]
    done = vcan_bus.run(cmd, cwd=ROOT, timeout=300)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "vcan node: ok", output[-6000:]


def test_toolchain_lists_every_runtime_source() -> None:
    """odgen/toolchain.py is the one list of the runtime's C files (CMake, make, odgen node, the tests):
    every file under runtime/ is in it, once, and is either the core, a service, a host file,
    the master or a program's main (the profiles' glue is the application's)."""
    listed = [*toolchain.core_sources(), *toolchain.service_sources(), *toolchain.host_sources(),
              RUNTIME / toolchain.NODE_MAIN, *toolchain.master_sources(), RUNTIME / toolchain.MASTER_MAIN]
    present = {p for p in RUNTIME.rglob("*.c") if "profiles" not in p.parts}
    assert len(listed) == len(set(listed)) and set(listed) == present
    make = dict(line.split(" := ", 1) for line in toolchain.make_script().splitlines())
    assert make["ODGEN_NODE_SOURCES"].split() == [p.as_posix() for p in toolchain.service_sources()]
