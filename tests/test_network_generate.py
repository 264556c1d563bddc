"""`odgen network NET.toml -o DIR` on examples/network: what each file holds, read by other means.

- every slave's concise DCF is decoded by a reader written from CiA 306 (tests/test_concise.py),
  and each value it writes is what python canopen reads as the ParameterValue of the slave's DCF;
- the master's C dictionary is compiled with the runtime core and run: each 0x1F22 sub-entry
  reads back, from FLASH, the bytes of the slave's .bin, and refuses a write; the CiA 302-2
  objects and the boot status object 0x5F81 read as docs/network.md says.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import canopen
import pytest

from odgen import toolchain
from odgen.cli import main
from odgen.pipeline import Request, generate

from .conftest import ROOT
from .test_concise import _cia306_read

EXAMPLE = ROOT / "examples" / "network" / "machine.toml"
SLAVES = {"hv": 1, "vacuum": 2, "flow": 3, "inverter": 4, "io": 5}


@pytest.fixture(scope="module")
def out(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("network")
    assert main(["network", str(EXAMPLE), "-o", str(folder)]) == 0
    return folder


def test_files_and_determinism(out: Path, tmp_path: Path) -> None:
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted([*(f"{s}.bin" for s in SLAVES), *(f"{s}.dcf" for s in SLAVES), "controller.dcf",
                            "controller.c", "controller.h", "controller_config.h"])
    assert main(["network", str(EXAMPLE), "-o", str(tmp_path)]) == 0
    for name in names:
        assert (tmp_path / name).read_bytes() == (out / name).read_bytes(), name


@pytest.mark.parametrize("slave", list(SLAVES))
def test_concise_dcf_holds_the_dcf_values(out: Path, slave: str) -> None:
    entries = _cia306_read((out / f"{slave}.bin").read_bytes())
    od = canopen.import_od(str(out / f"{slave}.dcf"), SLAVES[slave])
    final = {(index, sub): data for index, sub, data in entries}  # the last write of each entry stays
    assert final, "nothing configured"
    for (index, sub), data in final.items():
        var = od[index] if isinstance(od[index], canopen.objectdictionary.ODVariable) else od[index][sub]
        assert data == var.encode_raw(var.value), f"{slave} 0x{index:04X}sub{sub}"
    assert final[(0x1017, 0)] == (100 if slave != "io" else 200).to_bytes(2, "little")


def test_pdo_written_in_cia301_order(out: Path) -> None:
    writes = [(i, s, int.from_bytes(d, "little")) for i, s, d in _cia306_read((out / "hv.bin").read_bytes())]
    rpdo = [w for w in writes if w[0] in (0x1400, 0x1600)]
    assert rpdo == [(0x1400, 1, 0x80000201), (0x1400, 2, 1), (0x1600, 0, 0), (0x1600, 1, 0x62000108),
                    (0x1600, 2, 0x62000208), (0x1600, 3, 0x64100108), (0x1600, 0, 3), (0x1400, 1, 0x201)]
    tpdo = [w for w in writes if w[0] in (0x1800, 0x1A00)]
    assert tpdo[0] == (0x1800, 1, 0x80000181) and tpdo[-1] == (0x1800, 1, 0x181)
    assert (0x1A00, 1, 0x64010110) in tpdo and (0x1A00, 2, 0x64010210) in tpdo


PROGRAM = r"""
#include <stdio.h>
#include "odg.h"
#include "controller.h"

static unsigned long u32(uint16_t index, uint8_t sub)
{
    uint32_t v = 0;
    return odg_get(&controller, index, sub, &v, sizeof v) == ODG_OK ? (unsigned long)v : 0xDEADBEEFul;
}

int main(void)
{
    static uint8_t buf[4096];
    odg_ref_t ref;
    uint32_t n = 0;
    unsigned i;
    uint8_t node, status = 0xFF;
    if (odg_init(&controller, 127) != ODG_OK) return 1;
    for (node = 1; node <= 6; node++) {
        if (odg_find(&controller, 0x1F22, node, &ref) != ODG_OK) { printf("1F22 %u none\n", node); continue; }
        if (odg_read(&ref, 0, buf, sizeof buf, &n) != ODG_OK) return 2;
        printf("1F22 %u ", node);
        for (i = 0; i < n; i++) printf("%02X", buf[i]);
        printf(" write=%08lX\n", (unsigned long)odg_write(&ref, buf, n));
        printf("1F81 %u %08lX\n", node, u32(0x1F81, node));
        printf("1F86 %u %08lX\n", node, u32(0x1F86, node));
        (void)odg_get(&controller, 0x5F81, node, &status, 1);
        printf("5F81 %u %u", node, status);
        /* the runtime writes the boot status (odg_set); SDO may not (read-only) */
        (void)odg_set_u8(&controller, 0x5F81, node, (uint8_t)(0x40u + node));
        (void)odg_get(&controller, 0x5F81, node, &status, 1);
        if (odg_find(&controller, 0x5F81, node, &ref) == ODG_OK) {
            printf(" set=%u sdo=%08lX", status, (unsigned long)odg_write(&ref, &status, 1));
        }
        printf("\n");
    }
    (void)odg_get(&controller, 0x1029, 1, &status, 1);
    printf("1029 1 %u\n", status);
    (void)odg_get(&controller, 0x1016, 0, &status, 1);
    printf("1F80 %08lX\n1F89 %lu\n1016 %u %08lX %08lX\n", u32(0x1F80, 0), u32(0x1F89, 0),
           status, u32(0x1016, 1), u32(0x1016, 5));
    return 0;
}
"""


def test_master_dictionary_compiled_and_read(out: Path, tmp_path: Path) -> None:
    if shutil.which(toolchain.compiler()) is None:
        pytest.skip("no C compiler")
    (tmp_path / "main.c").write_text(PROGRAM)
    exe = tmp_path / "master"
    cmd = [toolchain.compiler(), *toolchain.CFLAGS, "-I", str(out), *(f"-I{d}" for d in toolchain.include_dirs()),
           str(tmp_path / "main.c"), str(out / "controller.c"), *map(str, toolchain.core_sources()), "-o", str(exe)]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    lines = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.splitlines()
    got = {tuple(line.split()[:2]): line.split()[2:] for line in lines}
    for slave, node in SLAVES.items():
        data, write = got[("1F22", str(node))]
        assert bytes.fromhex(data) == (out / f"{slave}.bin").read_bytes()
        assert write == "write=06010002"  # read-only: the bytes are in FLASH
        assert got[("5F81", str(node))] == ["0", f"set={0x40 + node}", "sdo=06010002"]
    assert got[("1F22", "6")] == ["none"]
    # hv and vacuum are mandatory, inverter keeps alive; every slave is booted again after an error
    assert [got[("1F81", str(n))][0] for n in range(1, 6)] == ["0000000D", "0000000D", "00000005", "00000015",
                                                               "00000005"]
    for slave, node in SLAVES.items():  # the product code checked is the description's
        product = canopen.import_od(str(out / f"{slave}.dcf"), node)[0x1018][2].default
        assert int(got[("1F86", str(node))][0], 16) == product != 0
    assert ("1F80", "00000001") in got  # NMT master; starts itself and the slaves one by one
    assert ("1F89", "5000") in got
    # a slave's lost heartbeat leaves the master's own node as it is: its configuration manager
    # handles the loss (docs/network.md); the description has no 0x1029, odgen network adds it
    assert got[("1029", "1")] == ["1"]
    assert got[("1016", "5")] == ["0001012C", "000501F4"]  # 5 consumers: node 1 300 ms ... node 5 500 ms


def test_domain_in_rom_only_when_its_value_is_fixed() -> None:
    from odgen.diagnostics import Diagnostics
    from odgen.model.od import DOMAIN, Obj, ObjectDictionary, Sub
    from odgen.model.values import Value
    from odgen.place.options import Options, parse_options
    from odgen.place.placement import place

    od = ObjectDictionary("t.eds", "eds")
    for index, access, default in ((0x2000, "const", "0A0B"), (0x2001, "const", None), (0x2002, "rw", "0A0B")):
        obj = Obj(index, "d", object_code=DOMAIN)
        obj.subs[0] = Sub(0, "d", data_type=0x000F, access=access,
                          default=Value(default) if default is not None else None)
        od.objects[index] = obj
    diags = Diagnostics()
    got = place(od, Options(), diags)
    assert [got[(i, 0)].storage for i in (0x2000, 0x2001, 0x2002)] == ["rom", "ram", "ram"]
    assert not list(diags)
    forced = parse_options('[[entry]]\nmatch = "0x2002"\nstorage = "rom"\n', "o.toml", diags)
    place(od, forced, diags)
    assert [(d.rule, d.index) for d in diags] == [("GEN003", 0x2002)]
    assert "not const keeps its buffer" in next(iter(diags)).message


def test_report_shows_boot_configuration_and_wiring(tmp_path: Path) -> None:
    page = tmp_path / "r.md"
    assert main(["report", str(ROOT / "examples" / "plasma-equipment" / "master.eds"), "--network", str(EXAMPLE),
                 "-o", str(page)]) == 0
    text = page.read_text()
    assert "| 127 | controller | master; starts the slaves one by one; boot time 5000 ms |" in text
    assert "| 4 | inverter | optional slave, kept alive | product_code 0x104 | 300 ms | 1 |" in text
    assert "| controller TPDO1 | hv RPDO1 | 0x201 | HV start/stop → Start/stop," in text
    # the PDOs are those of the network as configured: io's RPDO1 is disabled by the network file
    assert "node 5 RPDO1" not in text


def _master_slaves(source: Path, options: str | None, tmp_path: Path) -> tuple[int | None, list[str]]:
    path = None
    if options is not None:
        path = tmp_path / "o.toml"
        path.write_text(options)
    result = generate(Request(source, name="m", options=path))
    found = re.search(r"#define ODG_MASTER_MAX_SLAVES (\d+)u", result.files.get("m_config.h", ""))
    return (int(found.group(1)) if found else None), [d.text() for d in result.diags.sorted() if "GEN010" in d.rule]


def test_master_sized_by_the_slaves_it_assigns(out: Path, tmp_path: Path) -> None:
    """NAME_config.h sizes the master (ODG_MASTER_MAX_SLAVES) to the slaves 0x1F81 assigns, so that
    ODG_CONFIG stays the only define (the vcan test of tests/test_master.py builds it so)."""
    assert "#define ODG_MASTER_MAX_SLAVES 5u" in (out / "controller_config.h").read_text()
    assert _master_slaves(out / "controller.dcf", None, tmp_path) == (5, [])
    assert _master_slaves(out / "controller.dcf", "[node]\nslaves = 12\n", tmp_path) == (12, [])
    got, refused = _master_slaves(out / "controller.dcf", "[node]\nslaves = 4\n", tmp_path)
    assert got is None and len(refused) == 1 and "0x1F81 assigns 5 slaves" in refused[0]
    # a master whose 0x1F81 is filled at run time: the runtime's default; a slave: no master at all
    assert _master_slaves(ROOT / "tests" / "master" / "master.eds", None, tmp_path) == (8, [])
    assert _master_slaves(ROOT / "examples" / "plasma-equipment" / "hv_supply.eds", None, tmp_path) == (None, [])


def test_master_dcf_generates_the_same_dictionary(out: Path, tmp_path: Path) -> None:
    """`odgen generate controller.dcf` (the CMake route: odgen_add_object_dictionary on the DCF
    `odgen network` wrote) gives the dictionary `odgen network` gives, but for the header comment
    (the boot status 0x5F81 in RAM in both: the runtime writes it)."""
    assert main(["generate", str(out / "controller.dcf"), "--name", "controller", "--node-id", "127",
                 "-o", str(tmp_path)]) == 0

    def body(path: Path) -> list[str]:  # the file past its leading comments
        lines = path.read_text().splitlines()
        while lines and lines[0].startswith(("/*", " *")):
            lines.pop(0)
        return lines

    for name in ("controller.c", "controller.h", "controller_config.h"):
        assert body(tmp_path / name) == body(out / name), name
    assert "x5F81_slave_boot_status_s1_slave_boot_status_1), .size = 1, .sub = 5, .type = 0x05, " \
           ".attr = ODG_A_READ | ODG_A_TPDO, .storage = ODG_S_RAM}" in (out / "controller.c").read_text()


@pytest.mark.parametrize(("master", "values", "expected"), [
    (ROOT / "examples" / "plasma-equipment" / "master.eds", "", 1),  # no 0x1029: added
    (ROOT / "tests" / "node" / "pdo-node.eds", "", 1),  # 0x1029 sub 1 = 0 described: set to 1
    (ROOT / "tests" / "node" / "pdo-node.eds", '[master.values]\n"0x1029sub1" = 2\n', 2),  # the user's choice
])
def test_master_error_behaviour(master: Path, values: str, expected: int, tmp_path: Path) -> None:
    """The master's own node keeps its state when a slave's heartbeat is lost (0x1029 sub 1 = 1),
    unless the network file configures 0x1029 sub 1: the configuration manager handles the loss."""
    slave = ROOT / "examples" / "plasma-equipment" / "hv_supply.eds"
    net = tmp_path / "net.toml"
    net.write_text(f'[master]\nfile = "{master}"\nnode_id = 127\n{values}\n[[node]]\nfile = "{slave}"\nnode_id = 1\n')
    assert main(["network", str(net), "-o", str(tmp_path / "out")]) == 0
    sub = canopen.import_od(str(tmp_path / "out" / "master.dcf"), 127)[0x1029][1]
    assert (sub.value if sub.value is not None else sub.default) == expected


CMAKE_MASTER = """cmake_minimum_required(VERSION 3.16)
project(network_master C)
include("{root}/cmake/odgen.cmake")
odgen_add_object_dictionary(controller_od NAME controller EDS "{dcf}" NODE_ID 127)
add_executable(master "{root}/runtime/linux/odg_master_main.c" {host})
target_compile_definitions(master PRIVATE ODG_DICT=controller)
target_include_directories(master PRIVATE "{root}/runtime/linux")
target_link_libraries(master PRIVATE controller_od odgen::master)
"""


def test_master_program_built_with_cmake(out: Path, tmp_path: Path) -> None:
    """docs/network.md's CMake route: the master's DCF as the dictionary, odgen::master linked,
    built with -Werror and NAME_config.h the only define (it sizes the master: 5 slaves)."""
    cmake = shutil.which("cmake")
    if cmake is None:
        pytest.skip("no cmake")
    project = tmp_path / "project"
    project.mkdir()
    host = " ".join(f'"{p}"' for p in toolchain.host_sources())
    (project / "CMakeLists.txt").write_text(CMAKE_MASTER.format(root=ROOT, dcf=out / "controller.dcf", host=host))
    build = tmp_path / "build"
    for cmd in ([cmake, "-S", str(project), "-B", str(build), "-DODGEN_WERROR=ON"],
                [cmake, "--build", str(build), "--target", "master"]):
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        assert done.returncode == 0, done.stdout + done.stderr
    flags = (build / "CMakeFiles" / "controller_od_master.dir" / "flags.make").read_text()
    assert '-DODG_CONFIG=\\"controller_config.h\\"' in flags and "-Werror" in flags
    assert "ODG_MASTER_MAX_SLAVES" not in flags  # from controller_config.h
    assert "#define ODG_MASTER_MAX_SLAVES 5u" in (build / "odgen" / "controller" / "controller_config.h").read_text()
    usage = subprocess.run([str(build / "master")], capture_output=True, text=True, check=False)
    assert usage.returncode == 2 and "--node-id" in usage.stderr
