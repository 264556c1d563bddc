"""`odgen check`: generate, compile with the host C compiler against the runtime, run the self-test."""

from __future__ import annotations

import re
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .fileio import output_dir, write_files
from .toolchain import CFLAGS, compiler, core_sources, include_dirs
from .codegen.render import environment
from .pipeline import Request, Result, generate
from .codegen.selftest import build_selftest

DEFAULT_NODE_ID = 5


@dataclass
class CheckOutcome:
    ok: bool
    output: str
    result: Result


def _compile(cc: str, workdir: Path, name: str, extra: tuple[str, ...]) -> subprocess.CompletedProcess[str]:
    sources = [str(workdir / f"{name}.c"), str(workdir / f"{name}_selftest.c")]
    sources += [str(p) for p in core_sources()]
    includes = [f"-I{d}" for d in [*include_dirs(), workdir]]
    config = f'-DODG_CONFIG="{name}_config.h"'  # the runtime built to what the dictionary uses
    cmd = [cc, *CFLAGS, "-O1", config, *extra, *includes, *sources, "-lm", "-o", str(workdir / "selftest")]
    return subprocess.run(cmd, capture_output=True, text=True, check=False)


def run_check(request: Request, workdir: Path | None = None, cc: str | None = None,
              cflags: tuple[str, ...] = ()) -> CheckOutcome:
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
        ran = subprocess.run([str(work / "selftest")], capture_output=True, text=True, check=False, timeout=120)
        return CheckOutcome(ran.returncode == 0, ran.stdout + ran.stderr, result)


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
