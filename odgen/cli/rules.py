"""`odgen rules`: the rule catalogue, or the rules of some ids or families (`odgen rules PDO`)."""

from __future__ import annotations

import argparse
import sys

from ..errors import OdgenError


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rules = commands.add_parser("rules", help="list the rule catalogue (`odgen rule ID` explains one rule)")
    rules.add_argument("selectors", nargs="*", metavar="ID",
                       help="list only these rule ids or prefixes (PDO, SYN01); one full id prints that rule")
    rules.add_argument("--markdown", action="store_true", help="the whole catalogue as docs/rules.md")


def run(args: argparse.Namespace) -> int:
    from ..catalogue import RULES
    from ..catalogue.render import render_markdown, render_table
    from ..lint.settings import check_rule_ids
    from .rule import describe

    wanted = tuple(s.strip().upper() for s in args.selectors)
    if args.markdown and wanted:
        raise OdgenError("--markdown writes the whole catalogue: give no rule ids with it")
    check_rule_ids(wanted, "rules")
    if len(wanted) == 1 and wanted[0] in RULES:
        sys.stdout.write(describe(RULES[wanted[0]]))
    elif args.markdown:
        sys.stdout.write(render_markdown())
    else:
        sys.stdout.write(render_table(wanted))
    return 0
