"""`odgen explain`: where an entry is placed and why."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..choices import LOOKUPS
from ..errors import OdgenError
from .common import add_input_format, existing_file, print_findings


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    explain = commands.add_parser("explain", help="show placement and hooks of an entry and their origin")
    explain.add_argument("input", type=Path, metavar="FILE", help="the description (EDS, DCF, XDD or XDC)")
    explain.add_argument("index", metavar="INDEX", help="e.g. 0x6040 or 0x6200sub1")
    explain.add_argument("--options", type=existing_file("options file"), metavar="OPTS",
                         help="options file (TOML): placement, hooks")
    explain.add_argument("--lookup", choices=LOOKUPS, default="hash", help="the lookup to explain (as for generate)")
    add_input_format(explain)


def run(args: argparse.Namespace) -> int:
    from ..codegen.explain import explain_lines, lookup_lines
    from ..pipeline import Request, prepare
    from ..place.options import parse_pattern

    pattern = parse_pattern(args.index)
    if pattern is None:
        raise OdgenError(f"'{args.index}' is not an index (0x6040) or sub-entry (0x6040sub1)")
    result = prepare(Request(args.input, options=args.options, input_format=args.input_format))
    print_findings(result.diags)
    if result.od is None or result.placements is None:
        return 1
    lines = explain_lines(result.od, result.placements, pattern)
    if not lines:
        raise OdgenError(f"{args.input} has no entry {args.index}")
    print("\n".join(lines + lookup_lines(result.od, args.lookup)))
    return 0
