"""`odgen conformance`: the CiA 301 battery against a live node."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import OdgenError
from .common import node_id_type


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    conf = commands.add_parser("conformance", help="check a live node on a CAN bus against its description")
    conf.add_argument("input", type=Path, metavar="FILE", help="the node's description (EDS, DCF, XDD or XDC)")
    conf.add_argument("--iface", required=True, metavar="CAN", help="SocketCAN interface the node is on")
    conf.add_argument("--node-id", type=node_id_type, required=True, help="the node's node-id (1..127)")
    conf.add_argument("--junit", type=Path, metavar="XML", help="also write the results as JUnit XML")


def run(args: argparse.Namespace) -> int:
    from ..hostneeds import require_can_extra, require_socketcan

    if not args.input.is_file():
        raise OdgenError(f"{args.input}: no such file; give the node's EDS/DCF/XDD/XDC description")
    require_can_extra("conformance")
    require_socketcan(args.iface)
    from ..conformance import run as run_battery
    from ..conformance import text_lines, write_junit

    results = run_battery(args.input, args.iface, args.node_id)
    print("\n".join(text_lines(args.input, args.node_id, results)), flush=True)
    if args.junit:
        write_junit(args.junit, args.input, args.node_id, results)
    return 1 if any(r.failed for r in results) else 0
