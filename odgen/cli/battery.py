"""The arguments `odgen conformance` and `odgen roundtrip` share, and what `odgen conformance` does with them.

The battery itself (odgen/conformance) is imported only when a command runs it, so that building
the command line (and `odgen --version`) stays quick.

Each check's verdict is printed as soon as it is known, and `--junit` is rewritten after each,
so a run against a slow device shows progress and an interrupted one keeps what it found.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import OdgenError

if TYPE_CHECKING:
    from ..conformance import Selection

ALLOW = ("destructive",)


def add_arguments(conf: argparse.ArgumentParser) -> None:
    """The options `odgen conformance` and `odgen roundtrip` share."""
    conf.add_argument("--select", type=_ids, action="extend", default=[], metavar="CHECKS",
                      help="run only these check ids or prefixes (comma-separated: nmt,store.signature)")
    conf.add_argument("--ignore", type=_ids, action="extend", default=[], metavar="CHECKS",
                      help="do not run these check ids or prefixes")


def add_conformance_arguments(conf: argparse.ArgumentParser) -> None:
    add_arguments(conf)
    conf.add_argument("--allow", choices=ALLOW, action="append", default=[],
                      help="destructive: also run the checks that reset the node, erase its stored parameters "
                           "(0x1011 'load') or play another node's heartbeat")
    conf.add_argument("--options", type=Path, metavar="OPTS",
                      help="the placement options the node was built with: which entries 0x1010 stores")


def _ids(text: str) -> list[str]:
    return [part.strip().lower() for part in text.split(",") if part.strip()]


def selection(args: argparse.Namespace, known: Sequence[str] | None = None) -> Selection:
    """--select/--ignore as given, every id checked against the known check ids (the battery's)."""
    from ..conformance import CHECK_IDS, Selection, check_selectors

    for ids, origin in ((args.select, "--select"), (args.ignore, "--ignore")):
        check_selectors(ids, origin, known or CHECK_IDS)
    return Selection(tuple(args.select), tuple(args.ignore))


def stored_entries(path: Path, options: Path | None, node_id: int, defaults: str = "") -> frozenset[tuple[int, int]]:
    """The entries `options` put in a stored (persist:) group of the dictionary built from `path`."""
    from ..pipeline import Request, prepare

    result = prepare(Request(path, name="od", options=options, node_id=node_id, defaults=defaults))
    if result.placements is None:
        texts = "; ".join(d.text() for d in result.refused or result.diags.sorted())[:500]
        raise OdgenError(f"{options}: the placement cannot be worked out: {texts}")
    return frozenset(key for key, placement in result.placements.items() if placement.group)


def command(args: argparse.Namespace) -> int:
    """`odgen conformance` (odgen/cli/conformance.py defines its arguments)."""
    from ..conformance import header_line, read_description, result_lines, run, summary_line, write_junit
    from ..conformance.client import Settings, reachable_sdo_server

    from ..hostneeds import require_can_extra, require_socketcan

    if not args.input.is_file():
        raise OdgenError(f"{args.input}: no such file; give the node's EDS/DCF/XDD/XDC description")
    if args.options is not None and not args.options.is_file():
        raise OdgenError(f"{args.options}: no such options file; give the placement options the node was built with")
    chosen = selection(args)
    reachable_sdo_server(read_description(args.input), args.node_id, args.input)  # the description's mistakes first
    require_can_extra("conformance")
    require_socketcan(args.iface)
    stored = stored_entries(args.input, args.options, args.node_id) if args.options else None
    settings = Settings(destructive="destructive" in args.allow, stored=stored)
    done: list = []

    def report(result) -> None:  # type: ignore[no-untyped-def]
        done.append(result)
        if args.junit:  # first: once a line is shown, the file has it
            write_junit(args.junit, args.input, args.node_id, done)
        print("\n".join(result_lines(result)), flush=True)

    print(header_line(args.input, args.node_id), flush=True)
    results = run(args.input, args.iface, args.node_id, chosen, settings, report)
    print(summary_line(results), flush=True)
    return 1 if any(r.failed for r in results) else 0
