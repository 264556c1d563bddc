"""`odgen network`: a network file to each slave's DCF and concise DCF and the master's dictionary."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..choices import LOOKUPS


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    net = commands.add_parser("network", help="generate a network: slaves' DCFs and concise DCFs, the master's C "
                              "dictionary (docs/network.md)")
    net.add_argument("input", type=Path, metavar="NET.toml", help="the network file")
    net.add_argument("-o", "--output", type=Path, required=True, metavar="DIR",
                     help="folder for the files (created when missing)")
    net.add_argument("--lookup", choices=LOOKUPS, default="hash", help="index lookup of the master's dictionary")


def run(args: argparse.Namespace) -> int:
    from ..fileio import output_dir, write_files
    from ..network import build

    built = build(args.input, args.lookup)
    for d in built.findings:
        print(d.text(), file=sys.stderr)
    if built.refused:
        print(f"odgen: {args.input}: errors in the network, nothing written", file=sys.stderr)
        return 1
    out = output_dir(args.output)
    write_files({out / name: content for name, content in built.files.items()})
    return 0
