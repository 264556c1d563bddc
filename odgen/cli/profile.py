"""`odgen profile`: device-profile descriptions from channel counts."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..choices import DS401_MAX_DIGITAL, DS401_MAX_ANALOG, DS401_WIDTHS, DS401_NAME
from ..errors import OdgenError
from .common import count_type, print_findings


def add_parser(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    profile = commands.add_parser("profile", help="write a device-profile description from channel counts")
    profiles = profile.add_subparsers(dest="profile", required=True)
    ds401 = profiles.add_parser("ds401", help="CiA 401 generic I/O module (docs/ds401.md)")
    for kind, maximum, what in (("di", DS401_MAX_DIGITAL, "digital inputs (bits)"),
                                ("do", DS401_MAX_DIGITAL, "digital outputs (bits)"),
                                ("ai", DS401_MAX_ANALOG, "analog inputs"),
                                ("ao", DS401_MAX_ANALOG, "analog outputs")):
        ds401.add_argument(f"--{kind}", type=count_type(maximum), default=0, metavar="N", help=f"{what}, 0..{maximum}")
    for kind in ("ai", "ao"):
        ds401.add_argument(f"--{kind}-width", type=int, choices=DS401_WIDTHS, default=16,
                           help=f"bits per analog {'input' if kind == 'ai' else 'output'} (default 16)")
    ds401.add_argument("--name", default=DS401_NAME, help="product name")
    for key in ("vendor-id", "product-code", "revision"):
        ds401.add_argument(f"--{key}", type=count_type(0xFFFFFFFF), default=0, metavar="N",
                           help=f"identity object 0x1018's {key.replace('-', ' ')} (default 0)")
    ds401.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.eds", help="the EDS to write")
    ds401.add_argument("--generate", type=Path, metavar="DIR", help="also generate the C dictionary into DIR")


def run(args: argparse.Namespace) -> int:
    from ..fileio import output_dir, write_files
    from ..profiles import ds401 as ds401_profile

    spec = ds401_profile.Ds401(args.di, args.do, args.ai, args.ao, args.ai_width, args.ao_width, args.name,
                               args.vendor_id, args.product_code, args.revision)
    problems = spec.problems() + ([] if args.output.suffix.lower() == ".eds" else ["-o must name a .eds file"])
    if problems:
        raise OdgenError("; ".join(problems))
    ds401_profile.write(spec, args.output)
    if args.generate is None:
        return 0
    result = ds401_profile.generate_c(spec, args.output)
    print_findings(result.diags)
    if not result.files:
        print(f"odgen: {args.output}: errors found, nothing generated", file=sys.stderr)
        return 1
    out = output_dir(args.generate)
    write_files({out / name: text for name, text in result.files.items()}, only_changed=True)
    return 0
