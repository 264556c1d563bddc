"""`odgen diff`: what an update of a description breaks or changes."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..choices import DIFF_FAIL_ON, DIFF_FORMATS


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    diff = commands.add_parser("diff", help="what an update of a description breaks or changes (docs/diff.md)")
    diff.add_argument("old", type=Path, metavar="OLD", help="the description as released (EDS, DCF, XDD or XDC)")
    diff.add_argument("new", type=Path, metavar="NEW", help="the description as changed")
    diff.add_argument("--options", type=Path, metavar="OPTS", help="options file (persistence groups) of both")
    diff.add_argument("--old-options", type=Path, metavar="OPTS", help="options file of OLD")
    diff.add_argument("--new-options", type=Path, metavar="OPTS", help="options file of NEW")
    diff.add_argument("--format", choices=DIFF_FORMATS, default="text", help="report format (default text)")
    diff.add_argument("--output", "-o", type=Path, help="write the report to a file instead of stdout")
    diff.add_argument("--fail-on", choices=DIFF_FAIL_ON, default="breaking",
                      help="exit 1 on changes of this class or a more severe one (default: breaking)")


def run(args: argparse.Namespace) -> int:
    from ..diff import diff_paths, fails
    from ..diff.report import RENDERERS as DIFF_RENDERERS
    from ..fileio import write_atomic

    result = diff_paths(args.old, args.new, args.old_options or args.options, args.new_options or args.options)
    for d in result.read_errors:
        print(d.text(), file=sys.stderr)
    report = DIFF_RENDERERS[args.format](result)
    if args.output:
        write_atomic(args.output, report)
    else:
        sys.stdout.write(report)
    return 1 if fails(result, args.fail_on) else 0
