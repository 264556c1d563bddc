"""The C runtime (runtime/): built with gcc and clang under strict C99 warnings, and once with
AddressSanitizer and UndefinedBehaviorSanitizer; the C test programs in tests/runtime/ run
against a hand-written dictionary and must end with "N passed, 0 failed".

Everything is built in pytest's temporary directory, never in the repository.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from odgen import toolchain

from .cprog import BUILDS, EXTRA, STRICT, build, compiler, run
from .conftest import ROOT

RUNTIME = ROOT / "runtime"
CTESTS = ROOT / "tests" / "runtime"

CORE = toolchain.CORE_SOURCES
PROGRAMS: dict[str, tuple[Path, ...]] = {
    # the core alone: persistence is a layer above it, not linked in (0x1010/0x1011 abort)
    "test_core": (CTESTS / "test_core.c", CTESTS / "td.c", RUNTIME / "odg.c", RUNTIME / "odg_verify.c"),
    "test_persist": (CTESTS / "test_persist.c", CTESTS / "td.c", *(RUNTIME / s for s in CORE),
                     RUNTIME / "odg_nv_file.c"),
    "test_faults": (CTESTS / "test_faults.c", CTESTS / "nv_fault.c", CTESTS / "td.c", *(RUNTIME / s for s in CORE)),
}





@pytest.mark.parametrize("build_name", list(BUILDS))
@pytest.mark.parametrize("program", list(PROGRAMS))
def test_program(program: str, build_name: str, tmp_path: Path) -> None:
    cc, flags = BUILDS[build_name]
    exe = tmp_path / program
    build(cc, flags, PROGRAMS[program], (RUNTIME, CTESTS), exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_packed_commands_act_on_their_groups(cc: str, tmp_path: Path) -> None:
    """0x1010 / 0x1011 whose "save" and "load" sub-indices share one descriptor (generated so
    when the dictionary packs another entry, here the identity): each sub-index acts on its
    own groups across reboots, reads its capabilities, and refuses the wrong word."""
    out = tmp_path / "gen"
    done = subprocess.run([sys.executable, "-m", "odgen", "generate", str(CTESTS / "commands.eds"), "--options",
                           str(CTESTS / "commands.toml"), "-o", str(out), "--name", "cmd"],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    c = (out / "cmd.c").read_text()
    assert "{.index = 0x1010, .first = 2, .count = 2, .code = ODG_OBJ_ARRAY | ODG_E_DENSE | ODG_E_PACKED}" in c
    exe = tmp_path / "test_commands"
    build(cc, ("-O2", '-DODG_CONFIG="cmd_config.h"'),
          (CTESTS / "test_commands.c", CTESTS / "nv_fault.c", out / "cmd.c", *(RUNTIME / s for s in CORE)),
          (RUNTIME, CTESTS, out), exe)
    run(exe, tmp_path)


def test_verify_refuses_groups_a_one_pass_build_cannot_boot(tmp_path: Path) -> None:
    """A runtime built for one persistence group (ODG_CFG_PERSIST_TWO_PASS 0, as NAME_config.h says
    for such a dictionary) would boot the hand-written dictionary's two groups in one pass, where a
    group's boot may write over another's image before it moves home: odg_verify refuses it."""
    main = tmp_path / "main.c"
    main.write_text('#include "td.h"\n'
                    "odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,\n"
                    "                      uint32_t len, void *ctx);\n"
                    "odg_abort_t td_notice(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data,\n"
                    "                      uint32_t len, void *ctx)\n"
                    "{\n    (void)ref; (void)kind; (void)data; (void)len; (void)ctx;\n    return ODG_OK;\n}\n"
                    "int main(void)\n{\n    uint16_t bad = 0;\n"
                    "    return odg_init(&td, 5) == ODG_OK && odg_verify(&td, &bad) == ODG_ABORT_INTERNAL ? 0 : 1;\n"
                    "}\n", encoding="utf-8")
    exe = tmp_path / "one_pass"
    build("gcc", ("-O1", "-DODG_CFG_PERSIST_TWO_PASS=0"), (main, CTESTS / "td.c", RUNTIME / "odg.c",
                                                           RUNTIME / "odg_verify.c"), (RUNTIME, CTESTS), exe)
    assert subprocess.run([str(exe)], check=False, timeout=60).returncode == 0


def test_fault_figures(tmp_path: Path) -> None:
    """test_faults writes its figures (as fuzz/runtime/run.sh asks for fuzz/results/faults.json):
    every cut point, write failure, flip and cycle accounted for, and no mixed image."""
    exe = tmp_path / "test_faults"
    build("gcc", ("-O2",), PROGRAMS["test_faults"], (RUNTIME, CTESTS), exe)
    out = tmp_path / "faults.json"
    done = subprocess.run([str(exe), str(tmp_path), "--json", str(out)], capture_output=True, text=True, check=False,
                          timeout=300)
    assert done.returncode == 0, done.stdout[-4000:]
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["columns"][0] == "fault" and len(data["rows"]) == 4
    for row in data["rows"]:
        assert len(row) == len(data["columns"])
        assert row[1] == sum(row[2:6]) and row[1] > 0, row  # every boot has one outcome
        assert row[6] == 0, row  # no mixed image


def test_without_abort_texts(tmp_path: Path) -> None:
    """-DODG_NO_ABORT_TEXT drops the text table: odg_abort_text returns ""."""
    exe = tmp_path / "test_core"
    build("gcc", ("-O2", "-DODG_NO_ABORT_TEXT"), PROGRAMS["test_core"], (RUNTIME, CTESTS), exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("program", list(PROGRAMS))
def test_portable_byte_order_path(program: str, tmp_path: Path) -> None:
    """The path a big-endian target takes (wire bytes built with shifts), forced on this host."""
    exe = tmp_path / program
    build("gcc", ("-O2", "-DODG_LITTLE_ENDIAN=0"), PROGRAMS[program], (RUNTIME, CTESTS), exe)
    run(exe, tmp_path)


# Every ODG_CFG_* switch off (what a generated NAME_config.h may turn off), and the portable path.
ALL_OFF = tuple(f"-DODG_CFG_{f}=0" for f in ("INT64", "STRINGS", "UNICODE", "DOMAINS", "HOOKS", "LIMITS",
                                              "REAL_LIMITS", "GROUPS", "STORE", "HASH", "HASH_WIDE", "PACKED", "SHARED",
                                              "PERSIST_STREAMS", "PERSIST_STATUS", "PERSIST_ODG1", "PERSIST_TWO_PASS",
                                              "PERSIST_MIGRATION"))


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("defines", [(), ("-DODG_NO_ABORT_TEXT",), ALL_OFF, ("-DODG_LITTLE_ENDIAN=0",)],
                         ids=["default", "no-text", "config-all-off", "portable-byte-order"])
def test_runtime_sources_warning_free(cc: str, defines: tuple[str, ...], tmp_path: Path) -> None:
    """Each runtime source compiles alone, also -Wconversion clean, with every build option."""
    for source in (*CORE, "odg_nv_file.c"):
        cmd = [compiler(cc), *STRICT, *EXTRA, *defines, "-Os", f"-I{RUNTIME}", "-c", str(RUNTIME / source), "-o",
               str(tmp_path / (source + ".o"))]
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        assert done.returncode == 0, f"{' '.join(cmd)}\n{done.stderr}"


def test_core_has_no_stdio_or_heap() -> None:
    """The core and the persistence code run on bare metal: no stdio, no malloc."""
    forbidden = re.compile(r"#\s*include\s*<(stdio|stdlib|malloc)\.h>|\b(malloc|calloc|realloc|free|printf)\s*\(")
    for source in CORE:
        text = (RUNTIME / source).read_text(encoding="utf-8")
        assert not forbidden.search(text), f"{source}: {forbidden.search(text)}"
