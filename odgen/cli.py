"""Command line: `odgen lint`, `convert`, `generate`, `explain`, `rules`.

Exit codes: 0 clean, 1 findings (errors, or warnings under --strict),
2 usage error or unreadable input. Only odgen's own bugs raise past main(),
and then as one line unless --debug asks for the traceback.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from . import __version__
from .codegen.check import run_check
from .conformance import cli as conformance_cli
from .roundtrip import FileOutcome, roundtrip_file, summary_lines, write_report
from .roundtrip.build import build_node
from .codegen.explain import explain_lines
from .codegen.generate import LOOKUPS, Request, generate, prepare, valid_name
from .codegen.options import parse_pattern
from .diagnostics import Diagnostics, Severity
from .errors import OdgenError
from .fileio import write_atomic
from .formats import load_path
from .formats.eds_writer import write_eds
from .profiles import ds401 as ds401_profile
from .lint import RuleFilter, exit_code, lint_path
from .network import lint_network
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
    lint.add_argument("files", nargs="*", type=Path, metavar="FILE")
    lint.add_argument("--network", type=Path, metavar="NET.toml", help="lint a network's nodes and their PDOs")
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

    gen = commands.add_parser("generate", help="generate the C object dictionary (NAME.h, NAME.c)")
    gen.add_argument("input", type=Path, metavar="FILE")
    gen.add_argument("-o", "--output", type=Path, required=True, metavar="DIR")
    gen.add_argument("--name", help="C name of the dictionary (default: from the file name)")
    gen.add_argument("--options", type=Path, metavar="OPTS", help="options file (TOML): placement, hooks")
    gen.add_argument("--node-id", type=_node_id, help="check $NODEID values for this node-id")
    gen.add_argument("--lookup", choices=LOOKUPS, default="switch", help="index lookup (default: switch)")
    gen.add_argument("--check", action="store_true", help="exit 1 if DIR differs from what would be generated")

    explain = commands.add_parser("explain", help="show placement and hooks of an entry and their origin")
    explain.add_argument("input", type=Path, metavar="FILE")
    explain.add_argument("index", metavar="INDEX", help="e.g. 0x6040 or 0x6200sub1")
    explain.add_argument("--options", type=Path, metavar="OPTS")

    chk = commands.add_parser("check", help="generate, compile and run a self-test of the dictionary")
    chk.add_argument("input", type=Path, metavar="FILE")
    chk.add_argument("--name", help="C name of the dictionary")
    chk.add_argument("--options", type=Path, metavar="OPTS")
    chk.add_argument("--node-id", type=_node_id, help="node-id the self-test runs with (default 5)")
    chk.add_argument("--lookup", choices=LOOKUPS, default="switch")
    chk.add_argument("--keep", type=Path, metavar="DIR", help="build in DIR and keep the files")
    chk.add_argument("--verbose", "-v", action="store_true", help="print the whole self-test output")

    node = commands.add_parser("node", help="build a CANopen node from a description and run it on SocketCAN")
    node.add_argument("input", type=Path, metavar="FILE")
    node.add_argument("--iface", default="vcan0")
    node.add_argument("--node-id", type=_node_id, default=5)
    node.add_argument("--nv", type=Path, help="file that keeps stored parameters (default: none)")
    node.add_argument("--options", type=Path, metavar="OPTS")

    rt = commands.add_parser("roundtrip", help="check a node built from FILE with python canopen on a CAN bus")
    rt.add_argument("files", nargs="+", type=Path, metavar="FILE")
    rt.add_argument("--iface", default="vcan0")
    rt.add_argument("--node-id", type=_node_id, default=5)
    rt.add_argument("--options", type=Path, metavar="OPTS")
    rt.add_argument("--report", type=Path, help="write the results as JSON")

    add_profile_parser(commands)
    conformance_cli.add_parser(commands, _node_id)

    rules = commands.add_parser("rules", help="list the rule catalogue")
    rules.add_argument("--markdown", action="store_true", help="as docs/rules.md")
    return parser


def _count(maximum: int) -> Callable[[str], int]:
    def parse(text: str) -> int:
        try:
            value = int(text, 0)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
        if not 0 <= value <= maximum:
            raise argparse.ArgumentTypeError(f"{value} is outside 0..{maximum}")
        return value
    return parse


def add_profile_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    profile = commands.add_parser("profile", help="write a device-profile description from channel counts")
    profiles = profile.add_subparsers(dest="profile", required=True)
    ds401 = profiles.add_parser("ds401", help="CiA 401 generic I/O module (docs/ds401.md)")
    for kind, maximum, what in (("di", ds401_profile.MAX_DIGITAL, "digital inputs (bits)"),
                                ("do", ds401_profile.MAX_DIGITAL, "digital outputs (bits)"),
                                ("ai", ds401_profile.MAX_ANALOG, "analog inputs"),
                                ("ao", ds401_profile.MAX_ANALOG, "analog outputs")):
        ds401.add_argument(f"--{kind}", type=_count(maximum), default=0, metavar="N", help=f"{what}, 0..{maximum}")
    for kind in ("ai", "ao"):
        ds401.add_argument(f"--{kind}-width", type=int, choices=ds401_profile.WIDTHS, default=16)
    ds401.add_argument("--name", default=ds401_profile.Ds401.name, help="product name")
    for key in ("vendor-id", "product-code", "revision"):
        ds401.add_argument(f"--{key}", type=_count(0xFFFFFFFF), default=0, metavar="N")
    ds401.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.eds")
    ds401.add_argument("--generate", type=Path, metavar="DIR", help="also generate the C dictionary into DIR")


def cmd_profile(args: argparse.Namespace) -> int:
    spec = ds401_profile.Ds401(args.di, args.do, args.ai, args.ao, args.ai_width, args.ao_width, args.name,
                               args.vendor_id, args.product_code, args.revision)
    problems = spec.problems() + ([] if args.output.suffix.lower() == ".eds" else ["-o must name a .eds file"])
    if problems:
        raise OdgenError("; ".join(problems))
    ds401_profile.write(spec, args.output)
    if args.generate is None:
        return 0
    result = ds401_profile.generate_c(spec, args.output)
    _print_findings(result.diags)
    if not result.files:
        print(f"odgen: {args.output}: errors found, nothing generated", file=sys.stderr)
        return 1
    args.generate.mkdir(parents=True, exist_ok=True)
    for name, text in sorted(result.files.items()):
        write_atomic(args.generate / name, text)
    return 0


def cmd_lint(args: argparse.Namespace) -> int:
    options = LintOptions(node_id=args.node_id, can_fd=args.can_fd)
    rule_filter = RuleFilter(tuple(args.select), tuple(args.ignore))
    if not args.files and args.network is None:
        raise OdgenError("lint needs FILE arguments or --network NET.toml")
    results, unreadable = lint_network(args.network, options, rule_filter) if args.network else ([], False)
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


def _print_findings(diags: Diagnostics) -> None:
    for d in diags.sorted():
        if d.severity >= Severity.WARNING:
            print(d.text(), file=sys.stderr)


def _generate_request(args: argparse.Namespace) -> Request:
    if args.name is not None and not valid_name(args.name):
        raise OdgenError(f"--name '{args.name}' must be a C identifier of at most 32 characters")
    return Request(args.input, args.name, args.options, args.node_id, args.lookup)


def cmd_generate(args: argparse.Namespace) -> int:
    request = _generate_request(args)
    result = generate(request)
    _print_findings(result.diags)
    if not result.files:
        print(f"odgen: {args.input}: errors found, nothing written", file=sys.stderr)
        return 1
    if args.check:
        return _check_outputs(args.output, result.files)
    args.output.mkdir(parents=True, exist_ok=True)
    for name, text in sorted(result.files.items()):
        write_atomic(args.output / name, text)
    return 0


def _check_outputs(out: Path, files: dict[str, str]) -> int:
    stale = [name for name, text in sorted(files.items())
             if not (out / name).is_file() or (out / name).read_text(encoding="utf-8") != text]
    for name in stale:
        print(f"odgen: {out / name} is not what odgen would generate", file=sys.stderr)
    return 1 if stale else 0


def cmd_explain(args: argparse.Namespace) -> int:
    pattern = parse_pattern(args.index)
    if pattern is None:
        raise OdgenError(f"'{args.index}' is not an index (0x6040) or sub-entry (0x6040sub1)")
    result = prepare(Request(args.input, options=args.options))
    _print_findings(result.diags)
    if result.od is None or result.placements is None:
        return 1
    lines = explain_lines(result.od, result.placements, pattern)
    if not lines:
        raise OdgenError(f"{args.input} has no entry {args.index}")
    print("\n".join(lines))
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    request = _generate_request(args)
    outcome = run_check(request, workdir=args.keep)
    _print_findings(outcome.result.diags)
    if not outcome.result.files:
        print(f"odgen: {args.input}: errors found, nothing generated", file=sys.stderr)
        return 1
    lines = outcome.output.splitlines()
    shown = lines if args.verbose or not outcome.ok else [x for x in lines if not x.startswith("FAIL")]
    print("\n".join(shown))
    print(f"odgen check: {args.input}: {'ok' if outcome.ok else 'FAILED'}")
    return 0 if outcome.ok else 1


def cmd_node(args: argparse.Namespace) -> int:
    program, result = build_node(Request(args.input, name="od", options=args.options, node_id=args.node_id))
    _print_findings(result.diags)
    cmd = [str(program), "--iface", args.iface, "--node-id", str(args.node_id)]
    if args.nv is not None:
        cmd += ["--nv", str(args.nv)]
    return subprocess.call(cmd)


def cmd_roundtrip(args: argparse.Namespace) -> int:
    outcomes = []
    for path in args.files:
        try:
            outcome = roundtrip_file(path, args.iface, args.node_id, args.options)
        except OdgenError as err:
            outcome = FileOutcome(str(path), [], str(err))
        outcomes.append(outcome)
        print("\n".join(summary_lines(outcome)), flush=True)
    if args.report:
        write_report(args.report, outcomes)
    passed = sum(1 for o in outcomes if o.ok)
    print(f"odgen roundtrip: {passed} of {len(outcomes)} file(s) passed every check")
    return 0 if passed == len(outcomes) else 1


def cmd_rules(args: argparse.Namespace) -> int:
    sys.stdout.write(render_markdown() if args.markdown else render_table())
    return 0


COMMANDS = {"lint": cmd_lint, "convert": cmd_convert, "generate": cmd_generate, "explain": cmd_explain,
            "check": cmd_check, "node": cmd_node, "roundtrip": cmd_roundtrip, "rules": cmd_rules,
            "profile": cmd_profile, "conformance": conformance_cli.command}


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
