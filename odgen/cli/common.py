"""What several commands share: argument types, the generation policy options, printing findings."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from ..choices import INPUT_FORMATS
from ..errors import OdgenError

if TYPE_CHECKING:
    from ..pipeline import Request
    from ..diagnostics import Diagnostic, Diagnostics


def node_id_type(text: str) -> int:
    try:
        value = int(text, 0)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not 1 <= value <= 127:
        raise argparse.ArgumentTypeError(f"node-id {value} is outside 1..127")
    return value


def rule_list_type(text: str) -> list[str]:
    return [part.strip().upper() for part in text.split(",") if part.strip()]


def add_generation_policy(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--strict", action="store_true", help="refuse on any error or warning, not only on "
                        "findings that block generation")
    parser.add_argument("--select", type=rule_list_type, action="extend", default=[], metavar="RULES",
                        help="report only these rule ids or prefixes (findings that block are always reported)")
    parser.add_argument("--ignore", type=rule_list_type, action="extend", default=[], metavar="RULES",
                        help="do not report these rule ids or prefixes (findings that block still refuse)")


def add_fix_options(parser: argparse.ArgumentParser) -> None:
    fix = parser.add_mutually_exclusive_group()
    fix.add_argument("--fix", dest="fix_level", action="store_const", const="safe", default="",
                     help="repair what the findings say in memory first, where the meaning is certain "
                     "(docs/rules.md); every repair is listed on stderr and in the generated header")
    fix.add_argument("--unsafe-fixes", dest="fix_level", action="store_const", const="unsafe",
                     help="as --fix, and also the repairs that guess or let the node accept more than the file says")


def existing_file(what: str) -> Callable[[str], Path]:
    """An argument naming a file that must exist: a missing one is the user's mistake (exit 2), named."""
    def check(text: str) -> Path:
        path = Path(text)
        if not path.is_file():
            raise argparse.ArgumentTypeError(f"{what} {text} {'is not a file' if path.exists() else 'does not exist'}")
        return path
    return check


def add_input_format(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--input-format", choices=INPUT_FORMATS,
                        help="read the input as this format (needed when its suffix is not .eds/.dcf/.xdd/.xpd/.xdc)")


def count_type(maximum: int) -> Callable[[str], int]:
    def parse(text: str) -> int:
        try:
            value = int(text, 0)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
        if not 0 <= value <= maximum:
            raise argparse.ArgumentTypeError(f"{value} is outside 0..{maximum}")
        return value
    return parse


def print_findings(diags: Diagnostics, request: Request | None = None,
                   marks: dict[Diagnostic, str] | None = None) -> None:
    """Findings on stderr; `marks` (odgen.repair.blocking_marks) follow the message of those that block."""
    from ..pipeline import Request, reported

    for d in reported(diags, request or Request(Path())):
        print(d.text() + (marks or {}).get(d, ""), file=sys.stderr)


def generate_request(args: argparse.Namespace) -> Request:
    from ..pipeline import Request, valid_name

    if args.name is not None and not valid_name(args.name):
        raise OdgenError(f"--name '{args.name}' must be a C identifier of at most 32 characters")
    from ..lint.settings import check_rule_ids
    from ..lint.driver import RuleFilter

    check_rule_ids(args.select, "--select")
    check_rule_ids(args.ignore, "--ignore")
    return Request(args.input, args.name, args.options, args.node_id, args.lookup, input_format=args.input_format,
                   strict=args.strict, rule_filter=RuleFilter(tuple(args.select), tuple(args.ignore)),
                   fix=getattr(args, "fix_level", ""))


def refusal(args: argparse.Namespace, refused: list[Diagnostic], what: str = "written",
            repairable: tuple[int, int] | None = None) -> str:
    """The last line of a refused generation; with `repairable`, the blocking findings by rule and how
    many of them --fix and --unsafe-fixes would repair."""
    blocking = [d for d in refused if d.blocks]
    if not blocking or repairable is None:
        why = "blocking findings" if blocking else "findings (--strict)"
        return f"odgen: {args.input}: {len(refused)} {why}, nothing {what}"
    rules: dict[str, int] = {}
    for d in blocking:
        rules[d.rule] = rules.get(d.rule, 0) + 1
    by_rule = ", ".join(f"{rule} {n}" for rule, n in sorted(rules.items()))
    safe, unsafe = repairable
    verb = "finding blocks" if len(blocking) == 1 else "findings block"
    return (f"odgen: {args.input}: {len(blocking)} {verb} generation "
            f"({by_rule}); --fix would repair {safe}, --unsafe-fixes {unsafe}; nothing {what}")
