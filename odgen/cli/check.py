"""`odgen check`: generate, compile and run the dictionary's self-test."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..choices import LOOKUPS
from .common import (add_generation_policy, add_input_format, existing_file, generate_request, node_id_type,
                     print_findings, refusal)


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    chk = commands.add_parser("check", help="generate, compile and run a self-test of the dictionary")
    chk.add_argument("input", type=Path, metavar="FILE", help="the description (EDS, DCF, XDD or XDC)")
    chk.add_argument("--name", help="C name of the dictionary")
    chk.add_argument("--options", type=existing_file("options file"), metavar="OPTS",
                     help="options file (TOML): placement, hooks")
    chk.add_argument("--node-id", type=node_id_type, help="node-id the self-test runs with (default 5)")
    chk.add_argument("--lookup", choices=LOOKUPS, default="hash", help="index lookup to build (as for generate)")
    chk.add_argument("--keep", type=Path, metavar="DIR", help="build in DIR and keep the files")
    chk.add_argument("--verbose", "-v", action="store_true", help="print the whole self-test output")
    chk.add_argument("--cc", metavar="COMPILER", help="build the self-test with this C compiler (default: $CC, "
                     "else cc, gcc or clang), e.g. a cross compiler")
    chk.add_argument("--cflags", metavar="ARGS", help="more compiler arguments, split as a shell does: target "
                     "options, a startup file, a linker script (a single option: --cflags=-static)")
    chk.add_argument("--run", metavar="COMMAND", help="run the self-test through this command, split as a shell "
                     "does, e.g. an emulator: --run 'qemu-ppc -L /usr/powerpc-linux-gnu'")
    add_input_format(chk)
    add_generation_policy(chk)


def run(args: argparse.Namespace) -> int:
    from ..check import aligned_sizes, run_check, target

    where = target(args.cc, args.cflags, args.run)
    request = generate_request(args)
    outcome = run_check(request, workdir=args.keep, cc=where.cc, cflags=where.cflags, run=where.run)
    print_findings(outcome.result.diags, request)
    if not outcome.result.files:
        print(refusal(args, outcome.result.refused, "generated"), file=sys.stderr)
        return 1
    lines = outcome.output.splitlines()
    shown = lines if args.verbose or not outcome.ok else [x for x in lines if not x.startswith("FAIL")]
    print("\n".join(aligned_sizes(shown)))
    print(f"odgen check: {args.input}: {'ok' if outcome.ok else 'FAILED'}")
    return 0 if outcome.ok else 1
