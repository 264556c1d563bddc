"""The C runtime (runtime/): built with gcc and clang under strict C99 warnings, and once with
AddressSanitizer and UndefinedBehaviorSanitizer; the C test programs in tests/runtime/ run
against a hand-written dictionary and must end with "N passed, 0 failed".

Everything is built in pytest's temporary directory, never in the repository.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from .conftest import ROOT

RUNTIME = ROOT / "runtime"
CTESTS = ROOT / "tests" / "runtime"
STRICT = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic")
# Warnings beyond STRICT that the runtime sources (not the tests) are kept free of.
EXTRA = ("-Wconversion", "-Wsign-conversion", "-Wshadow", "-Wcast-qual", "-Wstrict-prototypes",
         "-Wmissing-prototypes", "-Wundef")
SANITIZE = ("-O1", "-g", "-fno-omit-frame-pointer", "-fsanitize=address,undefined", "-fno-sanitize-recover=all")

CORE = ("odg.c", "odg_persist.c")
PROGRAMS: dict[str, tuple[Path, ...]] = {
    "test_core": (CTESTS / "test_core.c", CTESTS / "td.c", *(RUNTIME / s for s in CORE)),
    "test_persist": (CTESTS / "test_persist.c", CTESTS / "td.c", *(RUNTIME / s for s in CORE),
                     RUNTIME / "odg_nv_file.c"),
}
BUILDS: dict[str, tuple[str, tuple[str, ...]]] = {
    "gcc": ("gcc", ("-O2",)),
    "clang": ("clang", ("-O2",)),
    "gcc-sanitize": ("gcc", SANITIZE),
}
RESULT = re.compile(r"(\d+) passed, (\d+) failed")


def compiler(cc: str) -> str:
    path = shutil.which(cc)
    if path is None:
        hint = "; `make test` installs it (make sysdeps: apt-get install clang)" if cc == "clang" else ""
        pytest.fail(f"{cc} is not installed{hint}")
    return path


def build(cc: str, flags: tuple[str, ...], sources: tuple[Path, ...], out: Path) -> None:
    cmd = [compiler(cc), *STRICT, *flags, f"-I{RUNTIME}", f"-I{CTESTS}", *map(str, sources), "-o", str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, f"compile failed: {' '.join(cmd)}\n{done.stdout}{done.stderr}"


def run(exe: Path, workdir: Path) -> str:
    done = subprocess.run([str(exe), str(workdir)], capture_output=True, text=True, check=False, timeout=600,
                          cwd=workdir, env={**os.environ, "UBSAN_OPTIONS": "print_stacktrace=1"})
    output = done.stdout + done.stderr
    lines = done.stdout.strip().splitlines()
    last = RESULT.fullmatch(lines[-1]) if lines else None
    assert done.returncode == 0 and last is not None and last.group(2) == "0", output[-6000:]
    assert int(last.group(1)) > 0
    return output


@pytest.mark.parametrize("build_name", list(BUILDS))
@pytest.mark.parametrize("program", list(PROGRAMS))
def test_program(program: str, build_name: str, tmp_path: Path) -> None:
    cc, flags = BUILDS[build_name]
    exe = tmp_path / program
    build(cc, flags, PROGRAMS[program], exe)
    run(exe, tmp_path)


def test_without_abort_texts(tmp_path: Path) -> None:
    """-DODG_NO_ABORT_TEXT drops the text table: odg_abort_text returns ""."""
    exe = tmp_path / "test_core"
    build("gcc", ("-O2", "-DODG_NO_ABORT_TEXT"), PROGRAMS["test_core"], exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("defines", [(), ("-DODG_NO_PERSIST",), ("-DODG_NO_ABORT_TEXT",)], ids=["default", "no-persist",
                                                                                                 "no-text"])
def test_runtime_sources_warning_free(cc: str, defines: tuple[str, ...], tmp_path: Path) -> None:
    """Each runtime source compiles alone, also -Wconversion clean, with every build option."""
    for source in ("odg.c", "odg_persist.c", "odg_nv_file.c"):
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
