"""The `odgen conformance` subcommand: its arguments and what it does with them."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from ..errors import OdgenError


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser], node_id: Callable[[str], int]) -> None:
    conf = commands.add_parser("conformance", help="check a live node on a CAN bus against its description")
    conf.add_argument("input", type=Path, metavar="FILE")
    conf.add_argument("--iface", required=True, metavar="CAN", help="SocketCAN interface the node is on")
    conf.add_argument("--node-id", type=node_id, required=True, help="the node's node-id (1..127)")
    conf.add_argument("--junit", type=Path, metavar="XML", help="also write the results as JUnit XML")


def command(args: argparse.Namespace) -> int:
    from . import run, text_lines, write_junit  # needs python canopen

    if not args.input.is_file():
        raise OdgenError(f"{args.input}: no such file; give the node's EDS/DCF/XDD/XDC description")
    results = run(args.input, args.iface, args.node_id)
    print("\n".join(text_lines(args.input, args.node_id, results)), flush=True)
    if args.junit:
        write_junit(args.junit, args.input, args.node_id, results)
    return 1 if any(r.failed for r in results) else 0
