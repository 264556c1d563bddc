"""Replays the runtime fuzz corpora (fuzz/runtime/seeds/ and the regression inputs in
fuzz/runtime/regressions/) through each harness built without libFuzzer: replay.c feeds
the files to LLVMFuzzerTestOneInput, under AddressSanitizer and UndefinedBehaviorSanitizer
with -fno-sanitize-recover, so any memory error, undefined behaviour or broken property
(abort) fails the test. `make fuzz` (fuzz/runtime/run.sh) runs the harnesses with libFuzzer.
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from odgen import toolchain

from .conftest import ROOT
from .cprog import SANITIZE, build
from .test_node import generate

FUZZ = ROOT / "fuzz" / "runtime"
RUNTIME = ROOT / "runtime"
NODE_SOURCES = (*toolchain.core_sources(), *toolchain.service_sources())
HARNESSES = {"sdo": "alltypes", "pdo": "pdo_node", "od": "alltypes"}


def corpus(harness: str) -> list[Path]:
    files = [p for d in ("seeds", "regressions") for p in sorted((FUZZ / d / harness).glob("*"))
             if p.is_file() and not p.name.startswith(".")]
    assert any(p.parent.parent.name == "seeds" for p in files), f"no seeds for {harness}"
    return files


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("harness", list(HARNESSES))
def test_replay_corpus(harness: str, cc: str, tmp_path: Path) -> None:
    name = HARNESSES[harness]
    gen = generate(name, tmp_path / name)
    exe = tmp_path / f"replay_{harness}"
    build(cc, SANITIZE, (FUZZ / f"fuzz_{harness}.c", FUZZ / "replay.c", gen / f"{name}.c", *NODE_SOURCES),
          (gen, RUNTIME, FUZZ), exe)
    files = corpus(harness)
    done = subprocess.run([str(exe), *map(str, files)], capture_output=True, text=True, check=False, timeout=300,
                          env={**os.environ, "UBSAN_OPTIONS": "print_stacktrace=1"})
    assert done.returncode == 0, (done.stdout + done.stderr)[-6000:]
    assert done.stdout.strip() == f"replayed {len(files)} inputs"



def test_replay_sdo_without_block_transfer(tmp_path: Path) -> None:
    """The SDO corpus (block transfers among it) against a server built without block transfer
    (ODG_NODE_SDO_BLOCK 0): every block frame is then a command it refuses, and the harness's
    properties hold as with it."""
    gen = generate("alltypes", tmp_path / "alltypes")
    exe = tmp_path / "replay_sdo_noblock"
    build("gcc", (*SANITIZE, "-DODG_NODE_SDO_BLOCK=0"),
          (FUZZ / "fuzz_sdo.c", FUZZ / "replay.c", gen / "alltypes.c", *NODE_SOURCES), (gen, RUNTIME, FUZZ), exe)
    files = corpus("sdo")
    done = subprocess.run([str(exe), *map(str, files)], capture_output=True, text=True, check=False, timeout=300,
                          env={**os.environ, "UBSAN_OPTIONS": "print_stacktrace=1"})
    assert done.returncode == 0, (done.stdout + done.stderr)[-6000:]
    assert done.stdout.strip() == f"replayed {len(files)} inputs"
