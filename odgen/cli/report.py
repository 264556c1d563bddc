"""`odgen report`: an HTML or Markdown page about a description."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..choices import PAGE_FORMATS
from .common import node_id_type


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    report = commands.add_parser("report", help="write an HTML (or Markdown) report of a description")
    report.add_argument("input", type=Path, metavar="FILE", help="the description (EDS, DCF, XDD or XDC)")
    report.add_argument("-o", "--output", type=Path, required=True, metavar="OUT",
                        help="the page to write: OUT.html (one self-contained file) or OUT.md (with OUT-svg/)")
    report.add_argument("--format", choices=PAGE_FORMATS,
                        help="html or md; needed only when OUT's suffix is not .html, .htm or .md")
    report.add_argument("--options", type=Path, metavar="OPTS", help="options file (TOML): placement, hooks")
    report.add_argument("--network", type=Path, metavar="NET.toml", help="add the network's PDO matrix")
    report.add_argument("--node-id", type=node_id_type, help="check $NODEID values for this node-id")
    report.add_argument("--can-fd", action="store_true", help="PDOs of up to 512 bits")


def run(args: argparse.Namespace) -> int:
    from ..report import write_report as write_page

    return write_page(args)
