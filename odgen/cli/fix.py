"""`odgen fix`: write the repaired description, changing only the lines the repairs name."""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import OdgenError
from .common import add_input_format, node_id_type

if TYPE_CHECKING:
    from ..diagnostics import Diagnostic
    from ..repair import Repair


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    fix = commands.add_parser("fix", help="write the description with its findings repaired (EDS/DCF)",
                              description="Repair what the findings say, changing only the lines repaired "
                              "(docs/rules.md lists the repairs). Exit 1 when findings that block generation "
                              "remain, 2 for an XDD/XDC or an unreadable file.")
    fix.add_argument("input", type=Path, metavar="FILE", help="the EDS or DCF to repair")
    fix.add_argument("-o", "--output", type=Path, metavar="OUT",
                     help="write the repaired description here (default: standard output; the input only "
                     "with --force)")
    fix.add_argument("--unsafe-fixes", action="store_true",
                     help="also make the repairs that guess (docs/rules.md says which)")
    fix.add_argument("--node-id", type=node_id_type, help="check $NODEID values for this node-id")
    fix.add_argument("--force", action="store_true", help="allow OUT to be FILE (rewrite the input in place)")
    add_input_format(fix)


@dataclass
class Fixed:
    """What `odgen fix` makes of a file: the new text, the repairs written, those it could not
    write (entries without lines of their own), and the findings that still block."""

    data: bytes
    repairs: list[Repair] = field(default_factory=list)
    unwritten: list[Repair] = field(default_factory=list)
    blocking: list[Diagnostic] = field(default_factory=list)


def fix_file(path: Path, unsafe: bool = False, node_id: int | None = None, fmt: str | None = None) -> Fixed:
    """The repaired text of an EDS/DCF file (`path` is not changed)."""
    from ..formats import detect_format, load_bytes, read_bytes
    from ..lint.driver import lint_model
    from ..lint.passes import LintOptions
    from ..repair import apply_edits, repair_model

    kind = detect_format(path, fmt)
    if kind not in ("eds", "dcf"):
        raise OdgenError(f"{path}: odgen fix rewrites EDS and DCF files; for XDD/XDC, `odgen generate --fix` "
                         "repairs in memory")
    data = read_bytes(path)
    od, diags = load_bytes(data, str(path), kind)
    if od is None:
        return Fixed(data, blocking=[d for d in diags.sorted() if d.blocks])
    lint_model(od, diags, LintOptions(node_id=node_id))
    _, repairs = repair_model(od, diags.sorted(), unsafe=unsafe)
    written = [r for r in repairs if r.writable]
    fixed = apply_edits(data, [e for r in sorted(written, key=lambda r: r.order) for e in r.edits])
    new_od, new_diags = load_bytes(fixed, str(path), kind)
    if new_od is not None:
        lint_model(new_od, new_diags, LintOptions(node_id=node_id))
    return Fixed(fixed, written, [r for r in repairs if not r.writable],
                 [d for d in new_diags.sorted() if d.blocks])


def _same_file(a: Path, b: Path) -> bool:
    try:
        return b.exists() and a.samefile(b)
    except OSError:
        return False


def _write_bytes(path: Path, data: bytes) -> None:
    """Whole or not at all, as odgen.fileio writes text: the file's bytes are kept as they are
    (its encoding and line ends), which a text write would not do."""
    import os
    import tempfile

    from ..fileio import TMP_SUFFIX, temp_prefix

    try:
        fd, tmp = tempfile.mkstemp(prefix=temp_prefix(path.name), suffix=TMP_SUFFIX, dir=path.parent or ".")
        try:
            with os.fdopen(fd, "wb") as out:
                out.write(data)
                out.flush()
                os.fsync(out.fileno())
            os.chmod(tmp, 0o644)
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise
    except OSError as err:
        raise OdgenError(f"cannot write {path}: {err.strerror or err}") from None


def run(args: argparse.Namespace) -> int:
    if args.output is not None and _same_file(args.input, args.output) and not args.force:
        raise OdgenError(f"{args.output} is the input file: name another output, or add --force to rewrite it")
    if not args.input.is_file():
        raise OdgenError(f"{args.input} {'is not a file' if args.input.exists() else 'does not exist'}")
    result = fix_file(args.input, args.unsafe_fixes, args.node_id, args.input_format)
    for r in result.repairs:
        print(r.text(), file=sys.stderr)
    for r in result.unwritten:
        print(f"{r.text()} (not written: the entry has no lines of its own; generate --fix makes it)",
              file=sys.stderr)
    for d in result.blocking:
        print(d.text(), file=sys.stderr)
    if args.output is None:
        sys.stdout.buffer.write(result.data)
        sys.stdout.flush()
    else:
        _write_bytes(args.output, result.data)
    print(f"odgen: {args.input}: {len(result.repairs)} repair{'' if len(result.repairs) == 1 else 's'}"
          + (f", {len(result.blocking)} findings still block generation" if result.blocking else ""),
          file=sys.stderr)
    return 1 if result.blocking else 0
