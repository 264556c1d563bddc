"""`odgen generate`: the C object dictionary."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ..choices import LOOKUPS
from .common import (add_fix_options, add_generation_policy, add_input_format, existing_file, generate_request,
                     node_id_type, print_findings, refusal)

if TYPE_CHECKING:
    from ..pipeline import Result


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    gen = commands.add_parser("generate", help="generate the C object dictionary (NAME.h, NAME.c)")
    gen.add_argument("input", type=Path, metavar="FILE", help="the description (EDS, DCF, XDD or XDC)")
    gen.add_argument("-o", "--output", type=Path, required=True, metavar="DIR",
                     help="folder for NAME.h, NAME.c and NAME_config.h (created when missing)")
    gen.add_argument("--name", help="C name of the dictionary (default: from the file name)")
    gen.add_argument("--options", type=existing_file("options file"), metavar="OPTS",
                     help="options file (TOML): placement, hooks")
    gen.add_argument("--node-id", type=node_id_type, help="check $NODEID values for this node-id")
    gen.add_argument("--lookup", choices=LOOKUPS, default="hash",
                     help="index lookup: hash (perfect hash, the default), bsearch (no tables), switch")
    gen.add_argument("--check", action="store_true",
                     help="write nothing; exit 1 listing missing, changed and extra files if DIR is not up to date")
    add_input_format(gen)
    add_generation_policy(gen)
    add_fix_options(gen)


def run(args: argparse.Namespace) -> int:
    from ..pipeline import generate
    from ..repair import blocking_marks
    from ..fileio import output_dir, write_files

    request = generate_request(args)
    result = generate(request)
    for repair in result.repairs:
        print(repair.text(), file=sys.stderr)
    marks = blocking_marks(result.od, result.diags.sorted()) if not result.files else {}
    print_findings(result.diags, request, marks)
    if not result.files:
        print(refusal(args, result.refused, repairable=_repairable(result)), file=sys.stderr)
        return 1
    if args.check:
        from ..codegen.outcheck import check_outputs

        return check_outputs(args.output, result.files, args.argv)
    out = output_dir(args.output)
    write_files({out / name: text for name, text in result.files.items()}, only_changed=True)
    _remove_stale_temps(out, result.files)
    return 0


def _repairable(result: Result) -> tuple[int, int] | None:
    """How many of the findings that block --fix and --unsafe-fixes would repair."""
    from ..repair import would_repair

    blocking = [d for d in result.refused if d.blocks]
    if result.od is None or not blocking:
        return None
    safe, unsafe = would_repair(result.od, result.diags.sorted())
    return sum(d in safe for d in blocking), sum(d in unsafe for d in blocking)


def _remove_stale_temps(out: Path, files: dict[str, str]) -> None:
    """Temporary files a killed run left beside these outputs (a run that ends otherwise removes its own)."""
    from ..codegen.outcheck import extra_files
    from ..fileio import TMP_SUFFIX

    for path in extra_files(out, files):
        if path.name.endswith(TMP_SUFFIX):
            path.unlink(missing_ok=True)
