"""Command line: `odgen lint`, `convert`, `generate`, `explain`, `rules`, `diff`.

Exit codes: 0 clean, 1 findings (errors, or warnings under --strict),
2 usage error or unreadable input. Only odgen's own bugs raise past main(),
and then as one line unless --debug asks for the traceback.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import os
import signal
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from . import __version__
from .errors import OdgenError

if TYPE_CHECKING:
    from .codegen.generate import Request
    from .diagnostics import Diagnostic, Diagnostics
    from .lint import FileResult, RuleFilter
    from .rules import LintOptions

# Commands import what they use when they run: `odgen lint` of an EDS and `odgen --version`
# start without jinja2, lxml or canopen (a pre-commit hook pays the start-up on every commit).
LOOKUPS = ("switch", "bsearch", "hash")  # codegen.generate.LOOKUPS, checked equal by a test
REPORT_FORMATS = ("github", "json", "sarif", "text")  # report.RENDERERS, checked equal by a test
INPUT_FORMATS = ("eds", "dcf", "xdd", "xdc")  # formats.INPUT_FORMATS, checked equal by a test
DIFF_FORMATS = ("json", "sarif", "text")  # diff.report.RENDERERS, checked equal by a test
PAGE_FORMATS = ("html", "md")  # htmlreport.render.FORMATS, checked equal by a test
# profiles.ds401's MAX_DIGITAL, MAX_ANALOG, WIDTHS and default name, checked equal by a test
DS401_MAX_DIGITAL, DS401_MAX_ANALOG, DS401_WIDTHS, DS401_NAME = 2032, 254, (8, 16, 32), "DS401 I/O module"


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


def _add_generation_policy(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--strict", action="store_true", help="refuse on any error or warning, not only on "
                        "findings that block generation")
    parser.add_argument("--select", type=_rule_list, action="extend", default=[], metavar="RULES",
                        help="report only these rule ids or prefixes (findings that block are always reported)")
    parser.add_argument("--ignore", type=_rule_list, action="extend", default=[], metavar="RULES",
                        help="do not report these rule ids or prefixes (findings that block still refuse)")


def _existing_file(what: str) -> Callable[[str], Path]:
    """An argument naming a file that must exist: a missing one is the user's mistake (exit 2), named."""
    def check(text: str) -> Path:
        path = Path(text)
        if not path.is_file():
            raise argparse.ArgumentTypeError(f"{what} {text} {'is not a file' if path.exists() else 'does not exist'}")
        return path
    return check


class _PrintAndExit(argparse.Action):
    """--cmake-dir, --runtime-dir, --toolchain cmake: what a firmware build asks the installed odgen."""

    def __init__(self, option_strings: list[str], dest: str, what: str, nargs: int | None = 0, **kw: object) -> None:
        self.what = what
        super().__init__(option_strings, dest, nargs=nargs, **kw)  # type: ignore[arg-type]

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: object,
                 option_string: str | None = None) -> None:
        from . import assets, toolchain

        texts = {"cmake-dir": lambda: f"{assets.cmake_dir()}\n", "runtime-dir": lambda: f"{assets.runtime_dir()}\n",
                 "toolchain": toolchain.cmake_script}
        sys.stdout.write(texts[self.what]())
        parser.exit(0)


def _add_location_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--cmake-dir", action=_PrintAndExit, what="cmake-dir",
                        help="print the folder of odgen.cmake (include it from a CMake project)")
    parser.add_argument("--runtime-dir", action=_PrintAndExit, what="runtime-dir",
                        help="print the folder of the C runtime's sources and headers")
    parser.add_argument("--toolchain", action=_PrintAndExit, what="toolchain", nargs=1, choices=["cmake"],
                        help="print the runtime's sources and C flags as CMake variables")


def _input_format(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--input-format", choices=INPUT_FORMATS,
                        help="read the input as this format (needed when its suffix is not .eds/.dcf/.xdd/.xpd/.xdc)")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The `odgen` parser; with `command` (a key of PARSERS) that command's arguments only: the
    parsers of all twelve commands take ~7 ms to build, one about half of that."""
    parser = argparse.ArgumentParser(prog="odgen", description="CANopen EDS/DCF/XDD linter and C generator")
    parser.add_argument("--version", action="version", version=f"odgen {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    _add_location_options(parser)
    commands = parser.add_subparsers(dest="command", required=True)
    for name, add in PARSERS.items():
        if command in (None, name):
            add(commands)
    return parser


def add_lint_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    lint = commands.add_parser("lint", help="check device descriptions against the rule catalogue")
    lint.add_argument("files", nargs="*", type=Path, metavar="FILE")
    lint.add_argument("--network", type=Path, metavar="NET.toml", help="lint a network's nodes and their PDOs")
    lint.add_argument("--format", choices=REPORT_FORMATS, default="text",
                      help="github: workflow annotations for GitHub Actions")
    lint.add_argument("--output", "-o", type=Path, help="write the report to a file instead of stdout")
    lint.add_argument("--strict", action="store_true", help="warnings fail too (exit 1)")
    lint.add_argument("--node-id", type=_node_id, help="check $NODEID values for this node-id only")
    lint.add_argument("--can-fd", action="store_true", help="allow PDOs of up to 512 bits")
    lint.add_argument("--select", type=_rule_list, action="extend", default=[], metavar="RULES",
                      help="report only these rule ids or prefixes (comma-separated)")
    lint.add_argument("--ignore", type=_rule_list, action="extend", default=[], metavar="RULES",
                      help="do not report these rule ids or prefixes (comma-separated)")
    lint.add_argument("--statistics", action="store_true", help="print the number of findings per rule instead")
    lint.add_argument("--config", type=_existing_file("config file"), metavar="TOML",
                      help="settings file (default: odgen.toml or [tool.odgen] in pyproject.toml, found upward)")
    _input_format(lint)


def add_convert_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    convert = commands.add_parser("convert", help="write a description as EDS (or DCF)")
    convert.add_argument("input", type=Path, metavar="IN")
    convert.add_argument("output", type=Path, metavar="OUT")
    convert.add_argument("--force", action="store_true", help="allow OUT to be IN (rewrite the input in place)")
    _input_format(convert)


def add_generate_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    gen = commands.add_parser("generate", help="generate the C object dictionary (NAME.h, NAME.c)")
    gen.add_argument("input", type=Path, metavar="FILE")
    gen.add_argument("-o", "--output", type=Path, required=True, metavar="DIR")
    gen.add_argument("--name", help="C name of the dictionary (default: from the file name)")
    gen.add_argument("--options", type=_existing_file("options file"), metavar="OPTS",
                     help="options file (TOML): placement, hooks")
    gen.add_argument("--node-id", type=_node_id, help="check $NODEID values for this node-id")
    gen.add_argument("--lookup", choices=LOOKUPS, default="hash",
                     help="index lookup: hash (perfect hash, the default), bsearch (no tables), switch")
    gen.add_argument("--check", action="store_true",
                     help="write nothing; exit 1 listing missing, changed and extra files if DIR is not up to date")
    _input_format(gen)
    _add_generation_policy(gen)


def add_explain_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    explain = commands.add_parser("explain", help="show placement and hooks of an entry and their origin")
    explain.add_argument("input", type=Path, metavar="FILE")
    explain.add_argument("index", metavar="INDEX", help="e.g. 0x6040 or 0x6200sub1")
    explain.add_argument("--options", type=_existing_file("options file"), metavar="OPTS")
    explain.add_argument("--lookup", choices=LOOKUPS, default="hash", help="the lookup to explain (as for generate)")
    _input_format(explain)


def add_check_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    chk = commands.add_parser("check", help="generate, compile and run a self-test of the dictionary")
    chk.add_argument("input", type=Path, metavar="FILE")
    chk.add_argument("--name", help="C name of the dictionary")
    chk.add_argument("--options", type=_existing_file("options file"), metavar="OPTS")
    chk.add_argument("--node-id", type=_node_id, help="node-id the self-test runs with (default 5)")
    chk.add_argument("--lookup", choices=LOOKUPS, default="hash")
    chk.add_argument("--keep", type=Path, metavar="DIR", help="build in DIR and keep the files")
    chk.add_argument("--verbose", "-v", action="store_true", help="print the whole self-test output")
    chk.add_argument("--cc", metavar="COMPILER", help="build the self-test with this C compiler (default: $CC, "
                     "else cc, gcc or clang), e.g. a cross compiler")
    chk.add_argument("--cflags", metavar="ARGS", help="more compiler arguments, split as a shell does: target "
                     "options, a startup file, a linker script (a single option: --cflags=-static)")
    chk.add_argument("--run", metavar="COMMAND", help="run the self-test through this command, split as a shell "
                     "does, e.g. an emulator: --run 'qemu-ppc -L /usr/powerpc-linux-gnu'")
    _input_format(chk)
    _add_generation_policy(chk)


def add_node_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    node = commands.add_parser("node", help="build a CANopen node from a description and run it on SocketCAN")
    node.add_argument("input", type=Path, metavar="FILE")
    node.add_argument("--iface", default="vcan0")
    node.add_argument("--node-id", type=_node_id, help="default 5; none waits for an LSS master when the node has LSS")
    node.add_argument("--nv", type=Path, help="file that keeps stored parameters (default: none)")
    node.add_argument("--options", type=_existing_file("options file"), metavar="OPTS")
    _input_format(node)


def add_roundtrip_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rt = commands.add_parser("roundtrip", help="check a node built from FILE with python canopen on a CAN bus")
    rt.add_argument("files", nargs="+", type=Path, metavar="FILE")
    rt.add_argument("--iface", default="vcan0")
    rt.add_argument("--node-id", type=_node_id, default=5)
    rt.add_argument("--options", type=_existing_file("options file"), metavar="OPTS")
    rt.add_argument("--report", type=Path, help="write the results as JSON")
    _input_format(rt)


def add_rules_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    rules = commands.add_parser("rules", help="list the rule catalogue")
    rules.add_argument("--markdown", action="store_true", help="as docs/rules.md")


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


def add_conformance_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    conf = commands.add_parser("conformance", help="check a live node on a CAN bus against its description")
    conf.add_argument("input", type=Path, metavar="FILE")
    conf.add_argument("--iface", required=True, metavar="CAN", help="SocketCAN interface the node is on")
    conf.add_argument("--node-id", type=_node_id, required=True, help="the node's node-id (1..127)")
    conf.add_argument("--junit", type=Path, metavar="XML", help="also write the results as JUnit XML")


def add_profile_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    profile = commands.add_parser("profile", help="write a device-profile description from channel counts")
    profiles = profile.add_subparsers(dest="profile", required=True)
    ds401 = profiles.add_parser("ds401", help="CiA 401 generic I/O module (docs/ds401.md)")
    for kind, maximum, what in (("di", DS401_MAX_DIGITAL, "digital inputs (bits)"),
                                ("do", DS401_MAX_DIGITAL, "digital outputs (bits)"),
                                ("ai", DS401_MAX_ANALOG, "analog inputs"),
                                ("ao", DS401_MAX_ANALOG, "analog outputs")):
        ds401.add_argument(f"--{kind}", type=_count(maximum), default=0, metavar="N", help=f"{what}, 0..{maximum}")
    for kind in ("ai", "ao"):
        ds401.add_argument(f"--{kind}-width", type=int, choices=DS401_WIDTHS, default=16)
    ds401.add_argument("--name", default=DS401_NAME, help="product name")
    for key in ("vendor-id", "product-code", "revision"):
        ds401.add_argument(f"--{key}", type=_count(0xFFFFFFFF), default=0, metavar="N")
    ds401.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.eds")
    ds401.add_argument("--generate", type=Path, metavar="DIR", help="also generate the C dictionary into DIR")


def add_diff_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    diff = commands.add_parser("diff", help="what an update of a description breaks or changes (docs/diff.md)")
    diff.add_argument("old", type=Path, metavar="OLD")
    diff.add_argument("new", type=Path, metavar="NEW")
    diff.add_argument("--options", type=Path, metavar="OPTS", help="options file (persistence groups) of both")
    diff.add_argument("--old-options", type=Path, metavar="OPTS", help="options file of OLD")
    diff.add_argument("--new-options", type=Path, metavar="OPTS", help="options file of NEW")
    diff.add_argument("--format", choices=DIFF_FORMATS, default="text")
    diff.add_argument("--output", "-o", type=Path, help="write the report to a file instead of stdout")
    diff.add_argument("--fail-on", choices=("breaking", "stored", "compatible", "none"), default="breaking",
                      help="exit 1 on changes of this class or a more severe one (default: breaking)")


def cmd_diff(args: argparse.Namespace) -> int:
    from .diff import diff_paths, fails
    from .diff.report import RENDERERS as DIFF_RENDERERS
    from .fileio import write_atomic

    result = diff_paths(args.old, args.new, args.old_options or args.options, args.new_options or args.options)
    for d in result.read_errors:
        print(d.text(), file=sys.stderr)
    report = DIFF_RENDERERS[args.format](result)
    if args.output:
        write_atomic(args.output, report)
    else:
        sys.stdout.write(report)
    return 1 if fails(result, args.fail_on) else 0


def add_report_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    report = commands.add_parser("report", help="write an HTML (or Markdown) report of a description")
    report.add_argument("input", type=Path, metavar="FILE")
    report.add_argument("-o", "--output", type=Path, required=True, metavar="OUT")
    report.add_argument("--format", choices=PAGE_FORMATS, help="html (default) or md; default from OUT's suffix")
    report.add_argument("--options", type=Path, metavar="OPTS", help="options file (TOML): placement, hooks")
    report.add_argument("--network", type=Path, metavar="NET.toml", help="add the network's PDO matrix")
    report.add_argument("--node-id", type=_node_id, help="check $NODEID values for this node-id")
    report.add_argument("--can-fd", action="store_true", help="PDOs of up to 512 bits")


def cmd_report(args: argparse.Namespace) -> int:
    from .htmlreport import write_report as write_page

    return write_page(args)


def cmd_profile(args: argparse.Namespace) -> int:
    from .fileio import output_dir, write_files
    from .profiles import ds401 as ds401_profile

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
    out = output_dir(args.generate)
    write_files({out / name: text for name, text in result.files.items()}, only_changed=True)
    return 0


def _lint_settings(args: argparse.Namespace, path: Path) -> tuple[RuleFilter, LintOptions, bool]:
    """The rule filter, lint options and strictness for one file: its config file, then the command line."""
    from .config import config_for
    from .lint import RuleFilter
    from .rules import LintOptions

    config = config_for(path, args.config)
    select = tuple(args.select) or config.select
    rule_filter = RuleFilter(select, config.ignores_for(path) + tuple(args.ignore))
    node_id = args.node_id if args.node_id is not None else config.node_id
    return rule_filter, LintOptions(node_id=node_id, can_fd=args.can_fd), args.strict or config.strict


def cmd_lint(args: argparse.Namespace) -> int:
    from .config import check_rule_ids
    from .lint import exit_code, lint_path

    if not args.files and args.network is None:
        raise OdgenError("lint needs FILE arguments or --network NET.toml")
    check_rule_ids(args.select, "--select")
    check_rule_ids(args.ignore, "--ignore")
    results: list[FileResult] = []
    unreadable = failed = False
    if args.network:
        from .lint_network import lint_network

        rule_filter, options, strict = _lint_settings(args, args.network)
        results, unreadable = lint_network(args.network, options, rule_filter)
        failed = exit_code(results, strict) != 0
    for path in args.files:
        rule_filter, options, strict = _lint_settings(args, path)
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
    from .fileio import write_atomic

    if args.statistics:
        from .report.statistics import render_statistics

        report = render_statistics(results)
    else:
        from .report import RENDERERS

        report = RENDERERS[args.format](results)
    if args.output:
        write_atomic(args.output, report)
    else:
        sys.stdout.write(report)


def _same_file(a: Path, b: Path) -> bool:
    try:
        return b.exists() and a.samefile(b)
    except OSError:
        return False


def cmd_convert(args: argparse.Namespace) -> int:
    from .diagnostics import Severity
    from .fileio import write_atomic
    from .formats import load_path
    from .formats.eds_writer import write_eds

    if args.output.suffix.lower() not in (".eds", ".dcf"):
        raise OdgenError(f"{args.output}: convert writes .eds or .dcf files")
    if _same_file(args.input, args.output) and not args.force:
        raise OdgenError(f"{args.output} is the input file: name another output, or add --force to rewrite it")
    od, diags = load_path(args.input, args.input_format)
    for d in diags.sorted():
        if d.severity >= Severity.WARNING:
            print(d.text(), file=sys.stderr)
    if od is None:
        print(f"odgen: {args.input}: nothing written", file=sys.stderr)
        return 1
    write_atomic(args.output, write_eds(od))
    return 0


def _print_findings(diags: Diagnostics, request: Request | None = None) -> None:
    from .codegen.generate import Request, reported

    for d in reported(diags, request or Request(Path())):
        print(d.text(), file=sys.stderr)


def _generate_request(args: argparse.Namespace) -> Request:
    from .codegen.generate import Request, valid_name

    if args.name is not None and not valid_name(args.name):
        raise OdgenError(f"--name '{args.name}' must be a C identifier of at most 32 characters")
    from .config import check_rule_ids
    from .lint import RuleFilter

    check_rule_ids(args.select, "--select")
    check_rule_ids(args.ignore, "--ignore")
    return Request(args.input, args.name, args.options, args.node_id, args.lookup, input_format=args.input_format,
                   strict=args.strict, rule_filter=RuleFilter(tuple(args.select), tuple(args.ignore)))


def _refusal(args: argparse.Namespace, refused: list[Diagnostic], what: str = "written") -> str:
    why = "blocking findings" if any(d.blocks for d in refused) else "findings (--strict)"
    return f"odgen: {args.input}: {len(refused)} {why}, nothing {what}"


def cmd_generate(args: argparse.Namespace) -> int:
    from .codegen.generate import generate
    from .fileio import output_dir, write_files

    request = _generate_request(args)
    result = generate(request)
    _print_findings(result.diags, request)
    if not result.files:
        print(_refusal(args, result.refused), file=sys.stderr)
        return 1
    if args.check:
        from .codegen.outcheck import check_outputs

        return check_outputs(args.output, result.files, args.argv)
    out = output_dir(args.output)
    write_files({out / name: text for name, text in result.files.items()}, only_changed=True)
    _remove_stale_temps(out, result.files)
    return 0


def _remove_stale_temps(out: Path, files: dict[str, str]) -> None:
    """Temporary files a killed run left beside these outputs (a run that ends otherwise removes its own)."""
    from .codegen.outcheck import extra_files
    from .fileio import TMP_SUFFIX

    for path in extra_files(out, files):
        if path.name.endswith(TMP_SUFFIX):
            path.unlink(missing_ok=True)


def cmd_explain(args: argparse.Namespace) -> int:
    from .codegen.explain import explain_lines, lookup_lines
    from .codegen.generate import Request, prepare
    from .codegen.options import parse_pattern

    pattern = parse_pattern(args.index)
    if pattern is None:
        raise OdgenError(f"'{args.index}' is not an index (0x6040) or sub-entry (0x6040sub1)")
    result = prepare(Request(args.input, options=args.options, input_format=args.input_format))
    _print_findings(result.diags)
    if result.od is None or result.placements is None:
        return 1
    lines = explain_lines(result.od, result.placements, pattern)
    if not lines:
        raise OdgenError(f"{args.input} has no entry {args.index}")
    print("\n".join(lines + lookup_lines(result.od, args.lookup)))
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    from .codegen.check import run_check, target

    where = target(args.cc, args.cflags, args.run)
    request = _generate_request(args)
    outcome = run_check(request, workdir=args.keep, cc=where.cc, cflags=where.cflags, run=where.run)
    _print_findings(outcome.result.diags, request)
    if not outcome.result.files:
        print(_refusal(args, outcome.result.refused, "generated"), file=sys.stderr)
        return 1
    lines = outcome.output.splitlines()
    shown = lines if args.verbose or not outcome.ok else [x for x in lines if not x.startswith("FAIL")]
    print("\n".join(shown))
    print(f"odgen check: {args.input}: {'ok' if outcome.ok else 'FAILED'}")
    return 0 if outcome.ok else 1


def cmd_node(args: argparse.Namespace) -> int:
    from .codegen.generate import Request
    from .hostneeds import require_can_extra, require_socketcan
    from .roundtrip.build import build_node

    require_can_extra("node")
    require_socketcan(args.iface)
    program, result = build_node(Request(args.input, name="od", options=args.options, node_id=args.node_id or 5,
                                         input_format=args.input_format))
    _print_findings(result.diags)
    import subprocess

    node_id = [] if args.node_id is None and result.lss else ["--node-id", str(args.node_id or 5)]
    cmd = [str(program), "--iface", args.iface, *node_id]
    if args.nv is not None:
        cmd += ["--nv", str(args.nv)]
    return subprocess.call(cmd)


def cmd_conformance(args: argparse.Namespace) -> int:
    from .hostneeds import require_can_extra

    require_can_extra("conformance")
    from .conformance.cli import command

    return command(args)


def cmd_roundtrip(args: argparse.Namespace) -> int:
    from .hostneeds import require_can_extra, require_socketcan

    require_can_extra("roundtrip")
    require_socketcan(args.iface)
    from .roundtrip import FileOutcome, roundtrip_file, summary_lines, write_report

    outcomes = []
    for path in args.files:
        try:
            outcome = roundtrip_file(path, args.iface, args.node_id, args.options, args.input_format)
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
    from .catalogue.render import render_markdown, render_table

    sys.stdout.write(render_markdown() if args.markdown else render_table())
    return 0


COMMANDS = {"lint": cmd_lint, "convert": cmd_convert, "generate": cmd_generate, "explain": cmd_explain,
            "check": cmd_check, "node": cmd_node, "roundtrip": cmd_roundtrip, "rules": cmd_rules,
            "profile": cmd_profile, "diff": cmd_diff, "report": cmd_report,
            "conformance": cmd_conformance}
# Each command's arguments, in the order `odgen --help` lists them.
PARSERS = {"lint": add_lint_parser, "convert": add_convert_parser, "generate": add_generate_parser,
           "explain": add_explain_parser, "check": add_check_parser, "node": add_node_parser,
           "roundtrip": add_roundtrip_parser, "profile": add_profile_parser, "diff": add_diff_parser,
           "report": add_report_parser, "conformance": add_conformance_parser, "rules": add_rules_parser}


def _terminate(signum: int, frame: object) -> None:
    """SIGTERM ends odgen as Ctrl-C does, so half-written temporary files are removed on the way out."""
    raise KeyboardInterrupt


# Commands that only read and write files: once their output is flushed, the interpreter's teardown
# (a last collection, then freeing every object of a large model) is time the user waits for and
# nothing needs; these end with os._exit.
QUICK_EXIT = frozenset({"lint", "convert", "generate", "explain", "rules", "diff"})


def run() -> None:
    """The `odgen` command."""
    args = _arguments(None)
    quick = args.command in QUICK_EXIT
    if quick:  # no cyclic collection at all: the process ends without one anyway (gcpause.py)
        gc.disable()
    code = _dispatch(args)
    if quick and sys.getprofile() is None and sys.gettrace() is None:  # profilers write at exit
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):  # a closed pipe: nothing more reaches the reader
                stream.flush()
        os._exit(code)
    raise SystemExit(code)


def main(argv: Sequence[str] | None = None) -> int:
    return _dispatch(_arguments(argv))


def _arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    words = list(sys.argv[1:] if argv is None else argv)
    # The command is the first word that is not an option (the options before it take no value but
    # --toolchain's, which ends the run); anything else gets the whole parser, to list the commands.
    command = next((w for w in words if not w.startswith("-")), None)
    args = build_parser(command if command in PARSERS else None).parse_args(words)
    args.argv = words  # for the command `generate --check` suggests
    return args


def _dispatch(args: argparse.Namespace) -> int:
    previous = signal.signal(signal.SIGTERM, _terminate)
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
    finally:
        signal.signal(signal.SIGTERM, previous)
