"""`odgen report`: a description as one self-contained HTML page (or Markdown with SVG files):
identity, the object dictionary with storage, hooks and findings at their entries, a bit picture
per PDO, the memory map and, with --network, who sends which PDO bits to whom.

Stages: view.py (and network.py) decide what is shown, svg.py draws, render.py lays it out
through templates/report.html.j2 and report.md.j2.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..diagnostics import Severity
from ..errors import OdgenError
from ..fileio import write_atomic
from .network import build_network
from .render import render_html, render_markdown
from .view import build_report


def _make_folder(folder: Path) -> None:
    try:
        folder.mkdir(exist_ok=True)  # the Markdown form's SVG folder; OUT's own folder exists
    except OSError as err:
        raise OdgenError(f"{folder}: cannot create: {err.strerror or err}") from None


PAGE_SUFFIXES = {".html": "html", ".htm": "html", ".md": "md", ".markdown": "md"}


def page_format(output: Path) -> str:
    """The page's format from OUT's suffix; another suffix (out.pdf) needs --format, as nothing else is written."""
    fmt = PAGE_SUFFIXES.get(output.suffix.lower())
    if fmt is None:
        suffix = f"'{output.suffix}'" if output.suffix else "no suffix"
        raise OdgenError(f"{output}: {suffix} is not a report's suffix: name it .html, .htm or .md "
                         "(odgen writes HTML or Markdown), or give --format html|md")
    return fmt


def write_report(args: argparse.Namespace) -> int:
    """`odgen report` (its parser is in odgen.cli, which imports this module only when it runs)."""
    fmt = args.format or page_format(args.output)
    if args.output.is_dir():
        raise OdgenError(f"{args.output} is a folder: give the report's file name with -o")
    if not args.output.parent.is_dir():
        raise OdgenError(f"{args.output.parent} does not exist: create it, or write the report elsewhere")
    if args.options is not None and not args.options.is_file():
        raise OdgenError(f"{args.options}: no such options file (check the --options path)")
    report, diags = build_report(args.input, args.options, args.node_id, args.can_fd)
    if report is None:
        for d in diags:
            print(d.text(), file=sys.stderr)
        print(f"odgen: {args.input}: cannot be read, no report written", file=sys.stderr)
        return 1
    if args.network is not None:
        report.network = build_network(args.network, args.input, args.can_fd)
    files = render_markdown(report, args.output) if fmt == "md" else {args.output: render_html(report)}
    for path, text in files.items():
        _make_folder(path.parent)
        write_atomic(path, text)
    errors = sum(1 for d in diags if d.severity == Severity.ERROR)
    objects = len({row.index for row in report.rows})
    print(f"odgen report: {args.output}: {objects} objects, {len(report.rows)} entries counting each sub-index, "
          f"{len(report.pdos)} PDOs, "
          f"{errors} error(s) found", file=sys.stderr)
    return 0
