"""`odgen node`: build a node from a description and run it on SocketCAN."""

from __future__ import annotations

import argparse
from pathlib import Path
from .common import add_input_format, existing_file, node_id_type, print_findings



def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    node = commands.add_parser("node", help="build a CANopen node from a description and run it on SocketCAN")
    node.add_argument("input", type=Path, metavar="FILE", help="the description (EDS, DCF, XDD or XDC)")
    node.add_argument("--iface", default="vcan0", metavar="CAN", help="SocketCAN interface to run on (default vcan0)")
    node.add_argument("--node-id", type=node_id_type,
                      help="default 5; none waits for an LSS master when the node has LSS")
    node.add_argument("--nv", type=Path, help="file that keeps stored parameters (default: none)")
    node.add_argument("--options", type=existing_file("options file"), metavar="OPTS",
                      help="options file (TOML): placement, hooks")
    add_input_format(node)


def run(args: argparse.Namespace) -> int:
    from ..pipeline import Request
    from ..hostneeds import require_can_extra, require_socketcan
    from ..roundtrip.build import build_node

    require_can_extra("node")
    require_socketcan(args.iface)
    program, result = build_node(Request(args.input, name="od", options=args.options, node_id=args.node_id or 5,
                                         input_format=args.input_format))
    print_findings(result.diags)
    import subprocess

    node_id = [] if args.node_id is None and result.lss else ["--node-id", str(args.node_id or 5)]
    cmd = [str(program), "--iface", args.iface, *node_id]
    if args.nv is not None:
        cmd += ["--nv", str(args.nv)]
    return subprocess.call(cmd)
