"""`odgen convert`: write a description as EDS or DCF."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import OdgenError
from .common import add_input_format

if TYPE_CHECKING:
    from ..model import ObjectDictionary


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    convert = commands.add_parser("convert", help="write a description as EDS (or DCF)")
    convert.add_argument("input", type=Path, metavar="IN", help="the description to read (EDS, DCF, XDD or XDC)")
    convert.add_argument("output", type=Path, metavar="OUT", help="the file to write: OUT.eds, or OUT.dcf for a "
                         "configured device")
    convert.add_argument("--force", action="store_true", help="allow OUT to be IN (rewrite the input in place)")
    add_input_format(convert)


def _same_file(a: Path, b: Path) -> bool:
    try:
        return b.exists() and a.samefile(b)
    except OSError:
        return False


def run(args: argparse.Namespace) -> int:
    from ..diagnostics import Severity
    from ..fileio import write_atomic
    from ..formats import load_path
    from ..formats.eds_writer import write_eds

    if args.output.suffix.lower() not in (".eds", ".dcf"):
        raise OdgenError(f"{args.output}: convert writes .eds or .dcf files")
    if _same_file(args.input, args.output) and not args.force:
        raise OdgenError(f"{args.output} is the input file: name another output, or add --force to rewrite it")
    od, diags = load_path(args.input, args.input_format)
    for d in diags.sorted():
        if d.severity >= Severity.WARNING:
            print(d.text(), file=sys.stderr)
    if od is None:
        print(f"odgen: {args.input}: nothing written", file=sys.stderr)
        return 1
    _leave_out_disabled(od)
    write_atomic(args.output, write_eds(od))
    return 0


def _leave_out_disabled(od: ObjectDictionary) -> None:
    """Objects an XDD marks CO_disabled are left out of the EDS, as CANopenEditor's own exports leave
    them out: the EDS has no way to say "disabled", and kept they would be PDOs the device does not
    have (NrOfRXPDO counts them out). Said on stderr, since the EDS holds fewer objects than the XDD."""
    from ..lint.passes.common import disabled

    gone = [index for index, obj in od.objects.items() if disabled(obj)]
    for index in gone:
        del od.objects[index]
    if gone:
        print(f"odgen convert: {', '.join(f'0x{i:04X}' for i in sorted(gone))} left out: disabled (CO_disabled) "
              "in the XDD", file=sys.stderr)
