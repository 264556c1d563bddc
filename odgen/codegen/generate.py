"""`odgen generate`: description -> lint -> placement -> view-model -> NAME.h / NAME.c."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

import jinja2

from .. import __version__
from ..diagnostics import Diagnostics, Severity
from ..formats import load_path, read_bytes
from ..gcpause import no_cyclic_gc
from ..lint import lint_model
from ..model import ObjectDictionary
from ..rules import LintOptions
from .names import identifier, is_identifier
from .options import Options, load_options, parse_options
from .placement import Placement, place
from .viewmodel import DictView, build

TEMPLATES = Path(__file__).resolve().parents[2] / "templates"
LOOKUPS = ("switch", "bsearch")


@dataclass
class Request:
    input: Path
    name: str | None = None
    options: Path | None = None
    node_id: int | None = None
    lookup: str = "switch"
    defaults: str = ""  # options (TOML) applied before the options file, e.g. by `odgen roundtrip`


@dataclass
class Result:
    diags: Diagnostics
    files: dict[str, str]  # file name -> text; empty when refused
    od: ObjectDictionary | None = None
    placements: dict[tuple[int, int], Placement] | None = None
    view: DictView | None = None


def default_name(path: Path) -> str:
    return identifier(path.stem, "od")


def environment() -> jinja2.Environment:
    return jinja2.Environment(loader=jinja2.FileSystemLoader(str(TEMPLATES)), undefined=jinja2.StrictUndefined,
                              trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
                              autoescape=False)


def digest(request: Request, name: str) -> str:
    h = hashlib.sha256(read_bytes(request.input))
    if request.options is not None:
        h.update(read_bytes(request.options))
    h.update(f"|{name}|{request.lookup}|{request.node_id}|{request.defaults}|{__version__}".encode())
    return h.hexdigest()[:16]


def prepare(request: Request) -> Result:
    """Load, lint, read options and place; stops early when errors were found."""
    od, diags = load_path(request.input)
    result = Result(diags, {}, od)
    if od is None:
        return result
    lint_model(od, diags, LintOptions(node_id=request.node_id))
    options = parse_options(request.defaults, "(built-in defaults)", diags) if request.defaults else Options()
    if request.options:
        user = load_options(request.options, diags)
        options.entries += user.entries
    if diags.count(Severity.ERROR):
        return result
    result.placements = place(od, options, diags)
    return result


def generate(request: Request) -> Result:
    with no_cyclic_gc():
        return _generate(request)


def _generate(request: Request) -> Result:
    name = request.name or default_name(request.input)
    result = prepare(request)
    if result.od is None or result.placements is None or result.diags.count(Severity.ERROR):
        return result
    view = build(result.od, result.placements, name, version=__version__, digest=digest(request, name),
                 lookup=request.lookup, diags=result.diags)
    if result.diags.count(Severity.ERROR):
        return result
    env = environment()
    result.view = view
    result.files = {f"{name}.h": env.get_template("dict.h.j2").render(v=view),
                    f"{name}.c": env.get_template("dict.c.j2").render(v=view)}
    return result


def valid_name(name: str) -> bool:
    """--name must be a plain C identifier: no paths, no reserved words."""
    return is_identifier(name) and len(name) <= 32
