"""`odgen conformance`: the CiA 301 battery against a live node."""

from __future__ import annotations

import argparse
from pathlib import Path

from .battery import add_conformance_arguments
from .common import node_id_type


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    conf = commands.add_parser("conformance", help="check a live node on a CAN bus against its description")
    conf.add_argument("input", type=Path, metavar="FILE", help="the node's description (EDS, DCF, XDD or XDC)")
    conf.add_argument("--iface", required=True, metavar="CAN", help="SocketCAN interface the node is on")
    conf.add_argument("--node-id", type=node_id_type, required=True, help="the node's node-id (1..127)")
    conf.add_argument("--junit", type=Path, metavar="XML", help="also write the results as JUnit XML")
    add_conformance_arguments(conf)


def run(args: argparse.Namespace) -> int:
    from .battery import command

    return command(args)
