"""`odgen rule ID`: one rule of the catalogue, as `odgen rules --markdown` describes it, for a terminal."""

from __future__ import annotations

import argparse
import sys
import textwrap
from typing import TYPE_CHECKING

from ..errors import OdgenError

if TYPE_CHECKING:
    from ..catalogue.rule import Rule


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rule = commands.add_parser("rule", help="explain one rule: severity, whether it blocks generation, "
                               "what it means, an example, the fix")
    rule.add_argument("rule_id", metavar="ID", help="a rule id as lint prints it, e.g. PDO003")


def run(args: argparse.Namespace) -> int:
    from ..catalogue import RULES

    rule = RULES.get(args.rule_id.strip().upper())
    if rule is None:
        raise OdgenError(f"'{args.rule_id}' is not a rule id{_suggestion(args.rule_id, sorted(RULES))}")
    sys.stdout.write(describe(rule))
    return 0


def _suggestion(text: str, known: list[str]) -> str:
    """The closest ids, or the ids of a family when `text` is its prefix (`PDO`)."""
    import difflib

    key = text.strip().upper()
    family = [r for r in known if key and r.startswith(key)][:5]
    close = family or difflib.get_close_matches(key, known, n=3, cutoff=0.5)
    return f"; did you mean {', '.join(close)}?" if close else "; `odgen rules` lists them"


def describe(rule: Rule) -> str:
    """The rule as plain text: the facts, then why, example and fix, wrapped for a terminal."""
    generation = "blocks (`odgen generate` refuses the file)" if rule.blocks else \
        "goes on (`odgen generate --strict` refuses the file)" if rule.severity.label != "info" else "goes on"
    lines = [f"{rule.id}: {rule.title}", "",
             f"Severity:   {rule.severity.label}", f"Generation: {generation}"]
    if rule.ref:
        lines.append(f"Reference:  {rule.ref}")
    lines += ["", "Why:", *_wrap(rule.why), "", "Example:"]
    lines += [f"    {line}" for line in rule.example.splitlines()]
    lines += ["", "Fix:", *_wrap(rule.fix)]
    return "\n".join(lines) + "\n"


def _wrap(text: str) -> list[str]:
    return textwrap.wrap(text, width=96, initial_indent="    ", subsequent_indent="    ",
                         break_on_hyphens=False, break_long_words=False)
