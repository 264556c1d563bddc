"""Command line: `odgen lint`, `odgen convert`, `odgen rules`.

Exit codes: 0 clean, 1 findings (errors, or warnings under --strict),
2 usage error or unreadable input. Only odgen's own bugs raise past main(),
and then as one line unless --debug asks for the traceback.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__
from .diagnostics import Severity
from .errors import OdgenError
from .fileio import write_atomic
from .formats import load_path
from .formats.eds_writer import write_eds
from .lint import RuleFilter, exit_code, lint_path
from .report import RENDERERS
from .rules import LintOptions
from .rules.catalogue import render_markdown, render_table


def _node_id(text: str) -> int:
    try:
        value = int(text, 0)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not 1 <= value <= 127:
        raise argparse.ArgumentTypeError(f"node-id {value} is outside 1..127")
    return value


def _rule_list(text: str) -> list[str]:
    return [part.strip().upper() for part in text.split(",") if part.strip()]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="odgen", description="CANopen EDS/DCF/XDD linter and C generator")
    parser.add_argument("--version", action="version", version=f"odgen {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    commands = parser.add_subparsers(dest="command", required=True)

    lint = commands.add_parser("lint", help="check device descriptions against the rule catalogue")
    lint.add_argument("files", nargs="+", type=Path, metavar="FILE")
    lint.add_argument("--format", choices=sorted(RENDERERS), default="text")
    lint.add_argument("--output", "-o", type=Path, help="write the report to a file instead of stdout")
    lint.add_argument("--strict", action="store_true", help="warnings fail too (exit 1)")
    lint.add_argument("--node-id", type=_node_id, help="check $NODEID values for this node-id only")
    lint.add_argument("--can-fd", action="store_true", help="allow PDOs of up to 512 bits")
    lint.add_argument("--select", type=_rule_list, action="extend", default=[], metavar="RULES",
                      help="report only these rule ids or prefixes (comma-separated)")
    lint.add_argument("--ignore", type=_rule_list, action="extend", default=[], metavar="RULES",
                      help="do not report these rule ids or prefixes (comma-separated)")

    convert = commands.add_parser("convert", help="write a description as EDS (or DCF)")
    convert.add_argument("input", type=Path, metavar="IN")
    convert.add_argument("output", type=Path, metavar="OUT")

    rules = commands.add_parser("rules", help="list the rule catalogue")
    rules.add_argument("--markdown", action="store_true", help="as docs/rules.md")
    return parser


def cmd_lint(args: argparse.Namespace) -> int:
    options = LintOptions(node_id=args.node_id, can_fd=args.can_fd)
    rule_filter = RuleFilter(tuple(args.select), tuple(args.ignore))
    results, unreadable = [], False
    for path in args.files:
        try:
            results.append(lint_path(path, options, rule_filter))
        except OdgenError as err:
            print(f"odgen: {err}", file=sys.stderr)
            unreadable = True
    report = RENDERERS[args.format](results)
    if args.output:
        write_atomic(args.output, report)
    else:
        sys.stdout.write(report)
    return 2 if unreadable else exit_code(results, args.strict)


def cmd_convert(args: argparse.Namespace) -> int:
    if args.output.suffix.lower() not in (".eds", ".dcf"):
        raise OdgenError(f"{args.output}: convert writes .eds or .dcf files")
    od, diags = load_path(args.input)
    for d in diags.sorted():
        if d.severity >= Severity.WARNING:
            print(d.text(), file=sys.stderr)
    if od is None:
        print(f"odgen: {args.input}: nothing written", file=sys.stderr)
        return 1
    write_atomic(args.output, write_eds(od))
    return 0


def cmd_rules(args: argparse.Namespace) -> int:
    sys.stdout.write(render_markdown() if args.markdown else render_table())
    return 0


COMMANDS = {"lint": cmd_lint, "convert": cmd_convert, "rules": cmd_rules}


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return COMMANDS[args.command](args)
    except OdgenError as err:
        print(f"odgen: {err}", file=sys.stderr)
        return err.exit_code
    except KeyboardInterrupt:
        return 130
    except Exception as err:  # odgen's own bug: one line, traceback on request
        if args.debug:
            raise
        print(f"odgen: internal error: {type(err).__name__}: {err} (run with --debug for the traceback)",
              file=sys.stderr)
        return 3
