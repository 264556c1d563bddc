"""examples/bare-metal: the io-node firmware for a Cortex-M, built by its Makefile with
arm-none-eabi-gcc under odgen's warning flags with -Werror, the runtime's sources from
`odgen --toolchain make` and ODG_CONFIG as the only define (docs/porting.md).

Built for a Cortex-M4 and a Cortex-M0 (ARMv6-M: no unaligned access, a smaller instruction
set); the image must start with the vector table the reset sequence reads: the initial stack
pointer, then the Thumb addresses of the handlers the firmware installs.
"""

from __future__ import annotations

import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from odgen import toolchain

from .conftest import ROOT

EXAMPLE = ROOT / "examples" / "bare-metal"
ODGEN = ROOT / ".venv" / "bin" / "odgen"


def _tool(name: str) -> str:
    path = shutil.which(name)
    if path is None:
        pytest.fail(f"{name} is missing: `make sysdeps` installs it (gcc-arm-none-eabi)")
    return path


def _symbols(elf: Path) -> dict[str, int]:
    out = subprocess.run([_tool("arm-none-eabi-nm"), str(elf)], capture_output=True, text=True, check=True).stdout
    rows = [line.split() for line in out.splitlines()]
    return {row[2]: int(row[0], 16) for row in rows if len(row) == 3}


@pytest.mark.parametrize("cpu", ["cortex-m4", "cortex-m0"])
def test_bare_metal_firmware_builds_with_werror(cpu: str, tmp_path: Path) -> None:
    _tool("arm-none-eabi-gcc")
    build = tmp_path / "build"
    done = subprocess.run(["make", "-C", str(EXAMPLE), f"BUILD={build}", f"ODGEN={ODGEN}",
                           f"CPU=-mcpu={cpu} -mthumb"], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    compile_line = next(line for line in done.stdout.splitlines() if line.startswith("arm-none-eabi-gcc"))
    assert "-Werror" in compile_line and "-pedantic" in compile_line
    defines = [word for word in compile_line.split() if word.startswith(("-D", "'-D"))]
    assert defines == ["'-DODG_CONFIG=\"io_node_config.h\"'"], defines
    for source in (*toolchain.core_sources(), *toolchain.service_sources()):
        assert str(source) in compile_line.split()

    elf = build / "firmware.elf"
    symbols = _symbols(elf)
    image = build / "firmware.bin"
    subprocess.run([_tool("arm-none-eabi-objcopy"), "-O", "binary", "-j", ".isr_vector", str(elf), str(image)],
                   check=True)
    vectors = struct.unpack(f"<{len(image.read_bytes()) // 4}I", image.read_bytes())
    assert symbols["vectors"] == 0x08000000, "the vector table at the start of flash"
    assert vectors[0] == symbols["_stack_top"] == 0x20010000
    assert vectors[1] == symbols["Reset_Handler"] | 1, "Thumb"
    assert vectors[15] == symbols["SysTick_Handler"] | 1
    assert vectors[16 + 20] == symbols["CAN_RX_IRQHandler"] | 1
    assert {"odg_node_init", "odg_node_receive", "odg_node_tick", "odg_node_can_state", "can_poll"} <= set(symbols)
