"""`odgen generate`: description -> lint -> placement -> view-model -> NAME.h / NAME.c."""

from __future__ import annotations

import contextlib
import hashlib
import operator
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import jinja2

from .. import __version__
from ..assets import templates_dir
from ..catalogue.gen import GEN008
from ..diagnostics import Diagnostic, Diagnostics, Loc, Severity, more_line
from ..formats import load_path, read_bytes
from ..gcpause import no_cyclic_gc
from ..lint.driver import RuleFilter, lint_model
from ..model import ObjectDictionary
from ..lint.passes import LintOptions
from ..model.header import header_field, header_int
from ..cnames import comment, identifier, is_identifier, name_clash
from ..place.options import Options, PersistOptions, load_options, parse_options
from ..place.persistence import add_status_object, persist_view
from ..place.placement import Placement, place
from ..repair import Repair, repair_model
from .lookup import perfect_hash
from .runtimecfg import runtime_config
from .viewmodel import DictView, build


@dataclass
class Request:
    input: Path
    name: str | None = None
    options: Path | None = None
    node_id: int | None = None
    lookup: str = "hash"
    defaults: str = ""  # options (TOML) applied before the options file, e.g. by `odgen roundtrip`
    can_fd: bool = False  # lint PDOs against a CAN FD frame (512 bits)
    input_format: str | None = None  # eds/dcf/xdd/xdc when the suffix does not say
    strict: bool = False  # refuse on any error or warning, not only on blocking findings
    rule_filter: RuleFilter = RuleFilter()  # --select/--ignore: the findings reported (blocking ones always are)
    fix: str = ""  # "safe" (--fix) or "unsafe" (--unsafe-fixes): repair the description in memory first


@dataclass
class Result:
    diags: Diagnostics
    files: dict[str, str]  # file name -> text; empty when refused
    od: ObjectDictionary | None = None
    placements: dict[tuple[int, int], Placement] | None = None
    view: DictView | None = None
    persist: PersistOptions = field(default_factory=PersistOptions)
    refused: list[Diagnostic] = field(default_factory=list)  # the findings that stopped generation
    lss: bool = False  # build a node with the LSS slave: LSS_Supported=1 or the options' [node] lss
    repairs: list[Repair] = field(default_factory=list)  # made by --fix / --unsafe-fixes, listed in the header


def reported(diags: Diagnostics, request: Request) -> list[Diagnostic]:
    """The findings `generate` prints and lists in the header: errors and warnings the rule filter keeps,
    and every blocking finding, since the refusal must say why."""
    return [d for d in diags.sorted()
            if d.blocks or (d.severity >= Severity.WARNING and request.rule_filter.keeps(d.rule))]


def refusals(diags: Diagnostics, request: Request) -> list[Diagnostic]:
    """Blocking findings; under --strict, every reported finding."""
    return [d for d in reported(diags, request) if d.blocks or request.strict]


def _refuse(result: Result, request: Request) -> bool:
    result.refused = refusals(result.diags, request)
    return bool(result.refused)


def findings_comment(diags: Diagnostics, request: Request) -> list[str]:
    """Lines for the header's comment of accepted findings: file name (not path) and message."""
    lines = []
    for d in reported(diags, request):
        name = Path(d.loc.file).name
        lines.append(comment(d.text().replace(d.loc.file, name, 1), 1000))
    source = Path(request.input).name
    lines += [comment(more_line(source, rule_id, n), 1000) for rule_id, n in diags.omitted().items()
              if request.rule_filter.keeps(rule_id)]
    return lines


def default_name(path: Path) -> str:
    """The file name as a C identifier; prefixed `od_` where it would clash with the runtime or C library."""
    name = identifier(path.stem, "od")
    return name if name_clash(name) is None else f"od_{name}"


class _TemplateCache(jinja2.FileSystemBytecodeCache):
    """Compiled templates kept between runs in jinja2's per-user cache folder (compiling them is a
    twentieth of a large generation). jinja2 checks each against its template's source, so a cached
    one is never stale; a cache that cannot be written only makes the next run compile again."""

    def dump_bytecode(self, bucket: jinja2.bccache.Bucket) -> None:
        with contextlib.suppress(OSError):
            super().dump_bytecode(bucket)


def _template_cache() -> jinja2.BytecodeCache | None:
    try:
        return _TemplateCache(pattern="odgen-%s.cache")
    except (OSError, RuntimeError):  # no private temporary folder to be had
        return None


def environment() -> jinja2.Environment:
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(templates_dir())), undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
                             autoescape=False, bytecode_cache=_template_cache())
    env.filters["rows"] = rows
    return env


def rows(items: Iterable[tuple[Any, ...]], line: str, *fields: str) -> str:
    """The lines of a large table: each item through the printf-style `line`, which takes the item's
    `fields` (by name) or else the whole tuple; every line ends with a newline.

    dict.c.j2 and dict.h.j2 print their per-sub-entry tables with it (`{{ v.macros | rows("#define %s
    %s /* %s */") }}`): a jinja2 loop pays for every field and piece of text of every row, which in a
    large dictionary is most of the render; the line's C stays in the template all the same."""
    line += "\n"
    if not fields:
        return "".join([line % item for item in items])
    get = operator.attrgetter(*fields)
    if len(fields) == 1:
        return "".join([line % (value,) for value in map(get, items)])
    return "".join([line % values for values in map(get, items)])


def digest(request: Request, name: str) -> str:
    h = hashlib.sha256(read_bytes(request.input))
    if request.options is not None:
        h.update(read_bytes(request.options))
    h.update(f"|{name}|{request.lookup}|{request.node_id}|{request.defaults}|{__version__}".encode())
    if request.fix:
        h.update(f"|fix={request.fix}".encode())
    return h.hexdigest()[:16]


def prepare(request: Request) -> Result:
    """Load, lint, read options and place; stops early on a blocking finding (any, under --strict)."""
    od, diags = load_path(request.input, request.input_format)
    result = Result(diags, {}, od)
    if od is None:  # nothing understood: the reader's findings say why
        result.refused = refusals(diags, request)
        return result
    read = Diagnostics(list(diags.items), dict(diags.counts)) if request.fix else None  # the reader's findings
    lint_model(od, diags, LintOptions(node_id=request.node_id, can_fd=request.can_fd))
    if read is not None:
        od, diags, result.repairs = repaired(od, read, diags, request)
        result.od, result.diags = od, diags
    _check_name(request, diags)
    options = parse_options(request.defaults, "(built-in defaults)", diags) if request.defaults else Options()
    if request.options:
        user = load_options(request.options, diags)
        options.entries += user.entries
        options.persist = user.persist
        options.node_lss = options.node_lss or user.node_lss
    result.lss = options.node_lss or header_int(header_field(od, "DeviceInfo", "LSS_Supported")) == 1
    if _refuse(result, request):
        return result
    result.placements = place(od, options, diags)
    result.persist = options.persist
    add_status_object(od, result.placements, options.persist, diags)
    return result


# ---- repairs (--fix / --unsafe-fixes): between load and placement, on a copy of the model ----

def repaired(od: ObjectDictionary, read: Diagnostics, diags: Diagnostics,
             request: Request) -> tuple[ObjectDictionary, Diagnostics, list[Repair]]:
    """The repaired model, its findings (the reader's that no repair answered, and the lint passes'
    on the repaired model) and the repairs made."""
    fixed_od, repairs = repair_model(od, diags.sorted(), unsafe=request.fix == "unsafe")
    answered = {r.finding for r in repairs}
    kept = [d for d in read.items if d not in answered]
    counts = dict(read.counts)
    for d in answered:
        if d.rule in counts:
            counts[d.rule] -= 1
    fresh = Diagnostics(kept, {rule: n for rule, n in counts.items() if n > 0})
    lint_model(fixed_od, fresh, LintOptions(node_id=request.node_id, can_fd=request.can_fd))
    return fixed_od, fresh, repairs


def repairs_comment(repairs: list[Repair]) -> list[str]:
    """Lines for the header's comment of repairs: file name (not path) and what was done."""
    return [comment(r.text().replace(r.finding.loc.file, Path(r.finding.loc.file).name, 1), 1000) for r in repairs]


def generate(request: Request) -> Result:
    with no_cyclic_gc():
        return _generate(request)


def _generate(request: Request) -> Result:
    name = request.name or default_name(request.input)
    result = prepare(request)
    if result.od is None or result.placements is None or _refuse(result, request):
        return result
    view = view_model(result, name, request.lookup, digest(request, name))
    if _refuse(result, request):
        return result
    result.view = view
    result.files = render(view, name, findings_comment(result.diags, request), repairs_comment(result.repairs))
    return result


def view_model(result: Result, name: str, lookup: str, source_digest: str) -> DictView:
    """Everything the templates print for a prepared (loaded, linted, placed) description;
    `source_digest` is digest() of the request, printed in the headers."""
    assert result.od is not None and result.placements is not None
    view = build(result.od, result.placements, name, version=__version__, digest=source_digest, lookup=lookup,
                 diags=result.diags)
    view.persist = persist_view(result.od, result.placements, result.persist, result.diags)
    view.config = runtime_config(view)
    if lookup == "hash":
        view.hash = perfect_hash([e.index for e in view.entries])
    return view


def render(view: DictView, name: str, findings: list[str], repairs: list[str] | None = None) -> dict[str, str]:
    env = environment()
    return {f"{name}.h": env.get_template("dict.h.j2").render(v=view, findings=findings, repairs=repairs or []),
            f"{name}.c": env.get_template("dict.c.j2").render(v=view),
            f"{name}_config.h": env.get_template("dict_config.h.j2").render(v=view)}


def _check_name(request: Request, diags: Diagnostics) -> None:
    why = name_clash(request.name) if request.name else None
    if request.name and why:
        diags.add(GEN008, Loc(str(request.input)), f"--name {request.name} {why}; use e.g. --name od_{request.name}")


def valid_name(name: str) -> bool:
    """--name must be a plain C identifier: no paths, no reserved words."""
    return is_identifier(name) and len(name) <= 32
