"""`odgen lint`: description files or a network file against the rule catalogue."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ..choices import REPORT_FORMATS
from ..errors import OdgenError
from .common import add_input_format, existing_file, node_id_type, rule_list_type

if TYPE_CHECKING:
    from ..lint.driver import FileResult, RuleFilter
    from ..lint.passes import LintOptions


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    lint = commands.add_parser("lint", help="check device descriptions against the rule catalogue")
    lint.add_argument("files", nargs="*", type=Path, metavar="PATH",
                      help="description files, folders (their .eds/.dcf/.xdd/.xdc/.xpd files, recursively) "
                      "or quoted globs such as 'devices/**/*.eds'")
    lint.add_argument("--network", type=Path, metavar="NET.toml", help="lint a network's nodes and their PDOs")
    lint.add_argument("--format", choices=REPORT_FORMATS, default="text",
                      help="github: workflow annotations for GitHub Actions")
    lint.add_argument("--output", "-o", type=Path, help="write the report to a file instead of stdout")
    lint.add_argument("--strict", action="store_true", help="warnings fail too (exit 1)")
    lint.add_argument("--node-id", type=node_id_type, help="check $NODEID values for this node-id only")
    lint.add_argument("--can-fd", action="store_true", help="allow PDOs of up to 512 bits")
    lint.add_argument("--select", type=rule_list_type, action="extend", default=[], metavar="RULES",
                      help="report only these rule ids or prefixes (comma-separated)")
    lint.add_argument("--ignore", type=rule_list_type, action="extend", default=[], metavar="RULES",
                      help="do not report these rule ids or prefixes (comma-separated)")
    lint.add_argument("--statistics", action="store_true", help="print the number of findings per rule instead")
    lint.add_argument("--config", type=existing_file("config file"), metavar="TOML",
                      help="settings file (default: odgen.toml or [tool.odgen] in pyproject.toml, found upward)")
    add_input_format(lint)


def lint_settings(args: argparse.Namespace, path: Path) -> tuple[RuleFilter, LintOptions, bool]:
    """The rule filter, lint options and strictness for one file: its config file, then the command line."""
    from ..lint.settings import config_for
    from ..lint.driver import RuleFilter
    from ..lint.passes import LintOptions

    config = config_for(path, args.config)
    select = tuple(args.select) or config.select
    rule_filter = RuleFilter(select, config.ignores_for(path) + tuple(args.ignore))
    node_id = args.node_id if args.node_id is not None else config.node_id
    return rule_filter, LintOptions(node_id=node_id, can_fd=args.can_fd), args.strict or config.strict


def run(args: argparse.Namespace) -> int:
    from ..lint.settings import check_rule_ids
    from ..lint.driver import exit_code, expand_paths, lint_path
    from ..lint.settings import config_for

    if not args.files and args.network is None:
        raise OdgenError("lint needs PATH arguments (files, folders or globs) or --network NET.toml")
    check_rule_ids(args.select, "--select")
    check_rule_ids(args.ignore, "--ignore")
    results: list[FileResult] = []
    unreadable = failed = False
    if args.network:
        from ..lint.network import lint_network

        rule_filter, options, strict = lint_settings(args, args.network)
        results, unreadable = lint_network(args.network, options, rule_filter)
        failed = exit_code(results, strict) != 0
    for path in expand_paths(args.files, lambda found: config_for(found, args.config).excludes(found)):
        rule_filter, options, strict = lint_settings(args, path)
        try:
            result = lint_path(path, options, rule_filter, args.input_format)
        except OdgenError as err:
            print(f"odgen: {err}", file=sys.stderr)
            unreadable = True
            continue
        results.append(result)
        failed = failed or exit_code([result], strict) != 0
    _write_report(args, results)
    return 2 if unreadable else int(failed)


def _write_report(args: argparse.Namespace, results: list[FileResult]) -> None:
    from ..fileio import write_atomic

    if args.statistics:
        from ..lint.reporters.statistics import render_statistics

        report = render_statistics(results)
    else:
        from ..lint.reporters import RENDERERS

        report = RENDERERS[args.format](results)
    if args.output:
        write_atomic(args.output, report)
    else:
        sys.stdout.write(report)
