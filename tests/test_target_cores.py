"""The self-test on the cores the runtime claims to serve, through `odgen check --cc --cflags --run`.

Each core is emulated: a Cortex-M0 (micro:bit: no unaligned access, the self-test hands the
runtime data at odd addresses) and a Cortex-M4 with its FPU (mps2-an386) under
qemu-system-arm with semihosting, a big-endian PowerPC under qemu-user, and an 8-bit AVR with
16-bit `int` and 4-byte `double` under simavr. The compilers, C libraries and emulators are the
Debian packages `make sysdeps` installs: under make (`make test`) a missing one fails the test;
elsewhere it skips, naming the tool.
"""

from __future__ import annotations

import os
import shlex
import shutil
from dataclasses import dataclass
from pathlib import Path

import pytest

from odgen.assets import runtime_dir
from odgen.cli import main
from odgen import check
from odgen.pipeline import Request

from .conftest import FIXTURES, ROOT

SUPPORT = Path(__file__).resolve().parent / "targets"
EXAMPLES = ROOT / "examples"
IO_NODE = (EXAMPLES / "io-node" / "io-node.eds", EXAMPLES / "io-node" / "io-node.toml")
ALLTYPES = (FIXTURES / "generate" / "alltypes.eds", FIXTURES / "generate" / "alltypes.toml")
# every kind of value in persistence groups: their defaults' runs in the target's byte order
PERSISTED = (ALLTYPES[0], FIXTURES / "generate" / "alltypes_persisted.toml")
PLASMA = EXAMPLES / "plasma-equipment"
SEMIHOSTING = "qemu-system-arm -nographic -monitor none -serial none -semihosting-config enable=on,target=native"
CORTEX_M = f"-mthumb --specs=nano.specs -nostartfiles -T {SUPPORT / 'cortex_m.ld'} {SUPPORT / 'cortex_m.c'}"


@dataclass(frozen=True)
class Core:
    cc: str
    cflags: str
    run: str

    @property
    def tools(self) -> list[str]:
        return [self.cc, shlex.split(self.run)[0]]

    def args(self) -> list[str]:
        return ["--cc", self.cc, f"--cflags={self.cflags}", "--run", self.run]


CORES = {
    "cortex-m0": Core("arm-none-eabi-gcc", f"-mcpu=cortex-m0 {CORTEX_M}", f"{SEMIHOSTING} -M microbit -kernel"),
    "cortex-m4": Core("arm-none-eabi-gcc", f"-mcpu=cortex-m4 -mfloat-abi=hard -mfpu=fpv4-sp-d16 {CORTEX_M}",
                      f"{SEMIHOSTING} -M mps2-an386 -kernel"),
    "powerpc": Core("powerpc-linux-gnu-gcc", "-static", "qemu-ppc"),
    "avr": Core("avr-gcc", f"-mmcu=atmega1284p -Wl,--section-start=.mmcu=0x910000 {SUPPORT / 'avr_simavr.c'}",
                "simavr -m atmega1284p -f 16000000"),
}


def _core(name: str) -> Core:
    """The core, its tools present: under make a missing tool fails (make sysdeps installs it)."""
    core = CORES[name]
    missing = [tool for tool in core.tools if not shutil.which(tool)]
    if missing and "MAKELEVEL" in os.environ:
        pytest.fail(f"{', '.join(missing)} missing: `make sysdeps` installs the emulated cores' tools")
    if missing:
        pytest.skip(f"{', '.join(missing)} not installed (`make sysdeps` installs it)")
    return core


def _check(core: Core, description: Path, options: Path | None, capsys: pytest.CaptureFixture[str],
           *more: str) -> tuple[int, str]:
    argv = ["check", str(description), *(["--options", str(options)] if options else []), *core.args(), *more]
    code = main(argv)
    captured = capsys.readouterr()
    return code, captured.out + captured.err


# One real description per core, and the fixture of every type on the 32-bit ones (AVR: below).
RUNS = [
    ("cortex-m0", *IO_NODE),
    ("cortex-m0", *ALLTYPES),
    ("cortex-m0", *PERSISTED),
    ("cortex-m4", PLASMA / "master.eds", None),
    ("cortex-m4", *ALLTYPES),
    ("powerpc", PLASMA / "flow_meter.eds", None),
    ("powerpc", *ALLTYPES),
    ("powerpc", *PERSISTED),
    ("avr", PLASMA / "hv_supply.eds", None),
    ("avr", *IO_NODE),
]


@pytest.mark.parametrize(("core", "description", "options"), RUNS,
                         ids=[f"{core}-{(options or path).stem}" for core, path, options in RUNS])
def test_self_test_passes_on_the_core(core: str, description: Path, options: Path | None,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    code, out = _check(_core(core), description, options, capsys, "--verbose")
    assert code == 0, out[-3000:]
    passed = check.SUMMARY.findall(out)
    assert passed and int(passed[-1][0]) > 100 and passed[-1][1] == "0", out[-2000:]
    assert f"odgen check: {description}: ok" in out


def test_a_dictionary_with_real64_values_refuses_to_build_where_double_has_4_bytes(
        capsys: pytest.CaptureFixture[str]) -> None:
    code, out = _check(_core("avr"), *ALLTYPES, capsys)
    assert code == 1
    assert "alltypes_assert_real_sizes" in out and "negative" in out


def _real32_description(tmp_path: Path, limits: bool) -> Path:
    """The plain fixture with its manufacturer entry made a REAL32, with limits or without."""
    text = (FIXTURES / "generate" / "plain.eds").read_text(encoding="utf-8")
    head, entry = text.split("[2000]")
    entry = entry.replace("DataType=0x0006", "DataType=0x0008").replace("DefaultValue=10", "DefaultValue=1.5")
    path = tmp_path / ("real32_limits.eds" if limits else "real32.eds")
    path.write_text(f"{head}[2000]{entry.rstrip()}\n" + ("LowLimit=-2.5\nHighLimit=100\n" if limits else ""),
                    encoding="utf-8")
    return path


def test_real32_values_serve_where_double_has_4_bytes_but_real_limits_need_8(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """float is IEEE single on AVR; the runtime compares limits on reals through a double."""
    avr = _core("avr")
    code, out = _check(avr, _real32_description(tmp_path, limits=False), None, capsys)
    assert code == 0, out[-2000:]
    code, out = _check(avr, _real32_description(tmp_path, limits=True), None, capsys)
    assert code == 1
    assert "real32_limits_assert_real_sizes" in out and "negative" in out


def test_an_unaligned_load_in_the_runtime_traps_on_the_cortex_m0(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    """The runtime with one wire number loaded as a uint32_t: the self-test's odd buffers make it
    trap, so the passing runs above show that the real runtime makes no such access."""
    source = (runtime_dir() / "odg.c").read_text(encoding="utf-8")
    careful = "    odg_copy(&v, b, n);"
    assert source.count(careful) == 1
    hasty = "    if (n == 4u) { v = *(const uint32_t *)(const void *)b; } else { odg_copy(&v, b, n); }"
    mutant = tmp_path / "odg.c"
    mutant.write_text(source.replace(careful, hasty), encoding="utf-8")
    persistence = [p for p in check.core_sources() if p.name != "odg.c"]
    monkeypatch.setattr(check, "core_sources", lambda: [mutant, *persistence])
    code, out = _check(_core("cortex-m0"), *IO_NODE, capsys)
    assert code == 1
    assert "HardFault" in out


def test_success_needs_the_summary_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A runner that ends with status 0 without running the program is no success."""
    code = main(["check", str(IO_NODE[0]), "--run", "true"])
    out = capsys.readouterr().out
    assert code == 1
    assert "without its summary line" in out and "FAILED" in out


def test_nv_size_follows_the_build(capsys: pytest.CaptureFixture[str]) -> None:
    """The RAM NV of the self-test is the dictionary's NV map, and a build can set it: one too
    small for the map makes the persistence checks fail."""
    outcome = check.run_check(Request(IO_NODE[0], options=IO_NODE[1]), cflags=("-DNV_SIZE=64u",))
    assert not outcome.ok
    assert "FAIL persistence: first boot uses defaults" in outcome.output


@pytest.mark.parametrize(("args", "message"), [
    (["--cc", "no-such-cc"], "--cc 'no-such-cc' is not an executable program"),
    (["--run", ""], "--run is empty"),
    (["--run", "no-such-emulator -x"], "no-such-emulator is not an executable program"),
    (["--cflags=-I'unclosed"], "cannot be split into words as a shell would"),
])
def test_target_option_mistakes_exit_2_in_one_sentence(args: list[str], message: str, tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["check", str(IO_NODE[0]), "--keep", str(tmp_path / "kept"), *args])
    err = capsys.readouterr().err
    assert code == 2
    assert message in err and err.count("\n") == 1
    assert not (tmp_path / "kept").exists()  # refused before anything was generated


def test_a_program_for_another_core_without_run_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    core = _core("avr")  # no binfmt_misc handler runs an AVR program
    code = main(["check", str(IO_NODE[0]), "--cc", core.cc, f"--cflags={core.cflags}"])
    err = capsys.readouterr().err
    assert code == 2
    assert "the self-test cannot run here (Exec format error): give --run the emulator" in err
