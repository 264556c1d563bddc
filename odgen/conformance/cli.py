"""What `odgen conformance` does with its arguments (odgen/cli.py defines them)."""

from __future__ import annotations

import argparse

from ..errors import OdgenError


def command(args: argparse.Namespace) -> int:
    from . import run, text_lines, write_junit  # needs python canopen

    if not args.input.is_file():
        raise OdgenError(f"{args.input}: no such file; give the node's EDS/DCF/XDD/XDC description")
    results = run(args.input, args.iface, args.node_id)
    print("\n".join(text_lines(args.input, args.node_id, results)), flush=True)
    if args.junit:
        write_junit(args.junit, args.input, args.node_id, results)
    return 1 if any(r.failed for r in results) else 0
