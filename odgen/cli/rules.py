"""`odgen rules`: the rule catalogue."""

from __future__ import annotations

import argparse
import sys



def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rules = commands.add_parser("rules", help="list the rule catalogue")
    rules.add_argument("--markdown", action="store_true", help="as docs/rules.md")


def run(args: argparse.Namespace) -> int:
    from ..catalogue.render import render_markdown, render_table

    sys.stdout.write(render_markdown() if args.markdown else render_table())
    return 0
