"""`odgen roundtrip`: build a node and check it on a CAN bus with python canopen."""

from __future__ import annotations

import argparse
from pathlib import Path

from .battery import add_arguments
from ..errors import OdgenError
from .common import add_input_format, existing_file, node_id_type


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rt = commands.add_parser("roundtrip", help="check a node built from FILE with python canopen on a CAN bus")
    rt.add_argument("files", nargs="+", type=Path, metavar="FILE", help="descriptions (EDS, DCF, XDD or XDC)")
    rt.add_argument("--iface", default="vcan0", metavar="CAN", help="SocketCAN interface to use (default vcan0)")
    rt.add_argument("--node-id", type=node_id_type, default=5, help="node-id of the built node (default 5)")
    rt.add_argument("--options", type=existing_file("options file"), metavar="OPTS",
                    help="options file (TOML): placement, hooks")
    rt.add_argument("--report", type=Path, help="write the results as JSON")
    add_input_format(rt)
    add_arguments(rt)


def run(args: argparse.Namespace) -> int:
    from ..hostneeds import require_can_extra, require_socketcan

    require_can_extra("roundtrip")
    require_socketcan(args.iface)
    from .battery import selection
    from ..roundtrip import FileOutcome, roundtrip_file, summary_lines, write_report
    from ..roundtrip.checks import CHECK_IDS

    chosen = selection(args, CHECK_IDS)
    outcomes = []
    for path in args.files:
        try:
            outcome = roundtrip_file(path, args.iface, args.node_id, args.options, args.input_format, chosen)
        except OdgenError as err:
            outcome = FileOutcome(str(path), [], str(err))
        outcomes.append(outcome)
        print("\n".join(summary_lines(outcome)), flush=True)
    if args.report:
        write_report(args.report, outcomes)
    passed = sum(1 for o in outcomes if o.ok)
    print(f"odgen roundtrip: {passed} of {len(outcomes)} file(s) passed every check")
    return 0 if passed == len(outcomes) else 1
