"""`odgen check`: generate, compile against the runtime, run the self-test.

By default the self-test is built with the host C compiler and run as it is; `--cc`,
`--cflags` and `--run` build it with a cross compiler and run it under an emulator.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .codegen.render import environment
from .codegen.selftest import build_selftest
from .errors import OdgenError
from .fileio import output_dir, write_files
from .pipeline import Request, Result, generate
from .toolchain import CFLAGS, compiler, core_sources, include_dirs

DEFAULT_NODE_ID = 5
RUN_TIMEOUT = 120  # seconds; an emulated self-test of a large dictionary takes a few
# The self-test's last line. Success needs it with no failure as well as exit status 0: an
# emulator may end with status 0 whatever the program did (simavr), or drop a crashed
# program's output.
SUMMARY = re.compile(r"(\d+) passed, (\d+) failed\s*$", re.MULTILINE)


@dataclass
class CheckOutcome:
    ok: bool
    output: str
    result: Result


@dataclass(frozen=True)
class Target:
    """Where the self-test is built and run: the host, or a cross compiler and an emulator."""

    cc: str | None = None  # None: the host compiler (toolchain.compiler)
    cflags: tuple[str, ...] = ()  # after odgen's own flags: target options, startup files, a linker script
    run: tuple[str, ...] = ()  # command prefix the program's path is appended to; () runs it directly


def target(cc: str | None, cflags: str | None, run: str | None) -> Target:
    """The target of `odgen check --cc --cflags --run`; a mistake in them is an OdgenError (exit 2)."""
    if cc is not None and not shutil.which(cc):
        raise OdgenError(f"--cc {cc!r} is not an executable program: name a compiler on PATH or give its path")
    run_words = _words("--run", run)
    if run is not None and not run_words:
        raise OdgenError("--run is empty: give the command that runs the self-test, "
                         "e.g. --run 'qemu-ppc -L /usr/powerpc-linux-gnu'")
    if run_words and not shutil.which(run_words[0]):
        raise OdgenError(f"--run {run!r}: {run_words[0]} is not an executable program: install it or give its path")
    return Target(cc, _words("--cflags", cflags), run_words)


def _words(option: str, text: str | None) -> tuple[str, ...]:
    try:
        return tuple(shlex.split(text or ""))
    except ValueError as err:
        raise OdgenError(f"{option} {text!r} cannot be split into words as a shell would ({err}): "
                         "check its quotes") from None


def _compile(cc: str, workdir: Path, name: str, extra: tuple[str, ...]) -> subprocess.CompletedProcess[str]:
    sources = [str(workdir / f"{name}.c"), str(workdir / f"{name}_selftest.c")]
    sources += [str(p) for p in core_sources()]
    includes = [f"-I{d}" for d in [*include_dirs(), workdir]]
    config = f'-DODG_CONFIG="{name}_config.h"'  # the runtime built to what the dictionary uses
    cmd = [cc, *CFLAGS, "-O1", config, *extra, *includes, *sources, "-lm", "-o", str(workdir / "selftest")]
    return subprocess.run(cmd, capture_output=True, text=True, check=False)


def _run(program: Path, prefix: tuple[str, ...]) -> tuple[bool, str]:
    try:
        ran = subprocess.run([*prefix, str(program)], capture_output=True, text=True, errors="replace",
                             check=False, timeout=RUN_TIMEOUT)
    except OSError as err:  # built for another core, and no --run
        raise OdgenError(f"the self-test cannot run here ({err.strerror}): "
                         "give --run the emulator of the core --cc builds for") from None
    except subprocess.TimeoutExpired as timeout:
        partial = timeout.stdout or ""  # bytes, whatever `text` says, on some Python versions
        if isinstance(partial, bytes):
            partial = partial.decode(errors="replace")
        return False, f"{partial}the self-test did not end within {RUN_TIMEOUT} s\n"
    output = ran.stdout + ran.stderr
    summary = SUMMARY.findall(output)
    if not summary:
        return False, output + f"the self-test ended (status {ran.returncode}) without its summary line\n"
    passed, failed = (int(n) for n in summary[-1])
    return ran.returncode == 0 and failed == 0 and passed > 0, output


def run_check(request: Request, workdir: Path | None = None, cc: str | None = None,
              cflags: tuple[str, ...] = (), run: tuple[str, ...] = ()) -> CheckOutcome:
    result = generate(request)
    if not result.files or result.view is None or result.od is None or result.placements is None:
        return CheckOutcome(False, "", result)
    with tempfile.TemporaryDirectory(prefix="odgen-check-") as tmp:
        work = workdir or Path(tmp)
        output_dir(work)
        test = build_selftest(result.od, result.placements, result.view, request.node_id or DEFAULT_NODE_ID)
        selftest = environment().get_template("selftest.c.j2").render(t=test)
        # Renamed into place, as `generate` writes: a symlink in --keep DIR is replaced, not written through.
        write_files({work / name: text for name, text in
                     {**result.files, f"{result.view.name}_selftest.c": selftest}.items()})
        built = _compile(cc or compiler(), work, result.view.name, cflags)
        if built.returncode != 0:
            return CheckOutcome(False, "compile failed:\n" + built.stdout + built.stderr, result)
        ok, output = _run(work / "selftest", run)
        return CheckOutcome(ok, output, result)


_SIZE_ROW = re.compile(r"^(values|tables) +(\S.*?) +(\d+) bytes +(.*)$")


def aligned_sizes(lines: list[str]) -> list[str]:
    """The self-test's size rows (`values  ram  12 bytes  RAM`) in aligned columns, whatever the
    length of a group's name or of a size; the other lines as they are. The C side prints the rows
    with fixed widths, which a long persistence group name (or a large block) would push out of line."""
    rows = {n: m.groups() for n, line in enumerate(lines) if (m := _SIZE_ROW.match(line))}
    if not rows:
        return lines
    name_width = max(len(r[1]) for r in rows.values())
    size_width = max(len(r[2]) for r in rows.values())
    return [f"{r[0]}  {r[1]:<{name_width}}  {r[2]:>{size_width}} bytes  {r[3]}" if (r := rows.get(n)) else line
            for n, line in enumerate(lines)]
