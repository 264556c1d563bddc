"""Building and running the C test programs: shared by the runtime and node tests."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from odgen.toolchain import CFLAGS

STRICT = CFLAGS  # the flags odgen check, the node build and the CMake module use
# Warnings beyond STRICT that the runtime sources (not the tests) are kept free of.
EXTRA = ("-Wconversion", "-Wsign-conversion", "-Wshadow", "-Wcast-qual", "-Wstrict-prototypes",
         "-Wmissing-prototypes", "-Wundef")
SANITIZE = ("-O1", "-g", "-fno-omit-frame-pointer", "-fsanitize=address,undefined", "-fno-sanitize-recover=all")
BUILDS: dict[str, tuple[str, tuple[str, ...]]] = {
    "gcc": ("gcc", ("-O2",)),
    "clang": ("clang", ("-O2",)),
    "gcc-sanitize": ("gcc", SANITIZE),
}
RESULT = re.compile(r"(\d+) passed, (\d+) failed")


def compiler(cc: str) -> str:
    path = shutil.which(cc)
    if path is None:
        pytest.fail(f"{cc} is not installed; `make test` installs it (make sysdeps)")
    return path


def build(cc: str, flags: tuple[str, ...], sources: tuple[Path, ...], includes: tuple[Path, ...], out: Path) -> None:
    cmd = [compiler(cc), *STRICT, *flags, *(f"-I{i}" for i in includes), *map(str, sources), "-o", str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, f"compile failed: {' '.join(cmd)}\n{done.stdout}{done.stderr}"


def run(exe: Path, workdir: Path) -> str:
    """Run a test program; it must exit 0 and end with `N passed, 0 failed` (N > 0)."""
    done = subprocess.run([str(exe), str(workdir)], capture_output=True, text=True, check=False, timeout=600,
                          cwd=workdir, env={**os.environ, "UBSAN_OPTIONS": "print_stacktrace=1"})
    output = done.stdout + done.stderr
    lines = done.stdout.strip().splitlines()
    last = RESULT.fullmatch(lines[-1]) if lines else None
    assert done.returncode == 0 and last is not None and last.group(2) == "0", output[-6000:]
    assert int(last.group(1)) > 0
    return output
