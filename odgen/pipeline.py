"""The stages from a description to C, as functions every command calls:

    load -> lint -> place -> view -> render

`load` reads the description (or takes a model built in memory) and the options file, each
once, and adds the objects odgen itself puts in the dictionary (the boot status object), so
that `lint` sees them like the rest. `place` decides each value's storage class, `view`
works out everything the C says, `render` prints it. A stage's output is not changed by a
later stage; findings of every stage go into one `Diagnostics`. `run` stops after the stage
asked for, or after the first stage that leaves a blocking finding (any reported finding under
--strict), and records each stage's time.

With --fix / --unsafe-fixes a repair stage follows lint (odgen.repair answers lint's findings): it
takes the loaded model and returns a new one, which is linted again; the later stages work on it.
"""

from __future__ import annotations

import hashlib
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TypeVar

from . import __version__
from .catalogue.gen import GEN008
from .cnames import comment, identifier, is_identifier, name_clash
from .codegen.render import render_files
from .codegen.runtimecfg import node_options
from .codegen.viewmodel import DictView, build
from .diagnostics import Diagnostic, Diagnostics, Loc, Severity, more_line
from .formats import MAX_BYTES, detect_format, load_bytes, read_bytes
from .formats.eds_writer import write_eds
from .gcpause import no_cyclic_gc
from .lint.driver import RuleFilter, lint_model
from .lint.passes import LintOptions
from .model import ObjectDictionary
from .model.edit import with_object
from .model.header import header_field, header_int
from .place.options import Options, PersistOptions, parse_options, read_options
from .place.persistence import status_object
from .place.placement import Placements, place
from .repair import Repair, repair_model

STAGES = ("load", "lint", "place", "view", "render")
_T = TypeVar("_T")


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
    model: ObjectDictionary | None = None  # a model built in memory: `input` then only names it
    fix: str = ""  # "safe" (--fix) or "unsafe" (--unsafe-fixes): repair the description (in memory) first


@dataclass(frozen=True)
class Loaded:
    """The load stage's output: the model with odgen's own objects, the options, and what identifies
    the input (printed in the generated headers)."""

    od: ObjectDictionary | None
    options: Options
    identity: Callable[[], str]  # the input's digest for the headers, worked out when view asks
    lss: bool  # build a node with the LSS slave: LSS_Supported=1 or the options' [node] lss
    diags: Diagnostics  # the findings so far; every later stage adds its own
    node_caps: dict[str, int] = field(default_factory=dict)  # the options' [node] limits


@dataclass(frozen=True)
class Placed:
    placements: Placements
    persist: PersistOptions


@dataclass
class Result:
    diags: Diagnostics
    files: dict[str, str]  # file name -> text; empty when refused or stopped before render
    od: ObjectDictionary | None = None
    placements: Placements | None = None
    view: DictView | None = None
    persist: PersistOptions = field(default_factory=PersistOptions)
    refused: list[Diagnostic] = field(default_factory=list)  # the findings that stopped generation
    lss: bool = False  # build a node with the LSS slave: LSS_Supported=1 or the options' [node] lss
    timings: dict[str, float] = field(default_factory=dict)  # stage -> seconds, for the stages that ran
    repairs: list[Repair] = field(default_factory=list)  # made by --fix / --unsafe-fixes, listed in the header


# -- the stages ----------------------------------------------------------------

def load(request: Request) -> Loaded:
    """Read the description and the options once each; add odgen's own objects to the model."""
    h = hashlib.sha256()
    od = request.model
    if od is None:
        data = read_bytes(request.input, MAX_BYTES)  # larger files are refused unread (SYN018)
        h.update(data)
        od, diags = load_bytes(data, str(request.input), detect_format(request.input, request.input_format))
    else:
        diags = Diagnostics()
    options = _options(request, diags, h)
    h.update(f"|{_name(request)}|{request.lookup}|{request.node_id}|{request.defaults}|{__version__}".encode())
    if request.fix:
        h.update(f"|fix={request.fix}".encode())
    caps = node_options(options.node, options.source, options.text, diags)
    identity = _identity(h, request.model)
    if od is None:
        return Loaded(None, options, identity, False, diags, caps)
    lss = options.node_lss or header_int(header_field(od, "DeviceInfo", "LSS_Supported")) == 1
    return Loaded(_with_odgen_objects(od, options, diags), options, identity, lss, diags, caps)


def _identity(h: hashlib._Hash, model: ObjectDictionary | None) -> Callable[[], str]:
    """The digest of what was read; a model built in memory adds the EDS text it writes, but only
    when the digest is asked for: `diff` loads models and never prints one."""
    if model is None:
        done = h.hexdigest()[:16]
        return lambda: done

    def later() -> str:
        with_model = h.copy()
        with_model.update(write_eds(model).encode())
        return with_model.hexdigest()[:16]
    return later


def lint(loaded: Loaded, request: Request, diags: Diagnostics) -> None:
    assert loaded.od is not None
    lint_model(loaded.od, diags, LintOptions(node_id=request.node_id, can_fd=request.can_fd))
    _check_name(request, diags)


def placed(loaded: Loaded, diags: Diagnostics) -> Placed:
    assert loaded.od is not None
    return Placed(place(loaded.od, loaded.options, diags), loaded.options.persist)


def view(loaded: Loaded, where: Placed, request: Request, diags: Diagnostics) -> DictView:
    """Everything the templates print for a loaded, linted, placed description."""
    assert loaded.od is not None
    return build(loaded.od, where.placements, where.persist, _name(request), version=__version__,
                 digest=loaded.identity(), lookup=request.lookup, diags=diags, lss=loaded.lss,
                 node_caps=loaded.node_caps, sdo_block=loaded.options.node_sdo_block)


def render(dict_view: DictView, request: Request, diags: Diagnostics, repairs: list[Repair] | None = None
           ) -> dict[str, str]:
    return render_files(dict_view, dict_view.name, findings_comment(diags, request), repairs_comment(repairs or []))


# -- the repair stage (--fix / --unsafe-fixes): after lint, whose findings it answers --------

def repaired(loaded: Loaded, read: Diagnostics, request: Request,
             diags: Diagnostics) -> tuple[Loaded, list[Repair]]:
    """The loaded description with a repaired model (odgen.repair makes a new one), its findings (the
    reader's that no repair answered, then the lint passes' on the repaired model), and the repairs."""
    assert loaded.od is not None
    fixed_od, repairs = repair_model(loaded.od, diags.sorted(), unsafe=request.fix == "unsafe")
    answered = {r.finding for r in repairs}
    counts = dict(read.counts)
    for d in answered:
        if d.rule in counts:
            counts[d.rule] -= 1
    fresh = Diagnostics([d for d in read.items if d not in answered], {r: n for r, n in counts.items() if n > 0})
    fixed = replace(loaded, od=fixed_od, diags=fresh)
    lint(fixed, request, fresh)
    return fixed, repairs


def repairs_comment(repairs: list[Repair]) -> list[str]:
    """Lines for the header's comment of repairs: file name (not path) and what was done."""
    return [comment(r.text().replace(r.finding.loc.file, Path(r.finding.loc.file).name, 1), 1000) for r in repairs]


# -- running them ----------------------------------------------------------------

def run(request: Request, until: str = "render") -> Result:
    """The stages up to `until` (one of STAGES); stops early on a refusal."""
    with no_cyclic_gc():
        return _run(request, STAGES.index(until))


def generate(request: Request) -> Result:
    return run(request)


def prepare(request: Request) -> Result:
    """Load, lint and place (what `explain` and the benchmarks look at)."""
    return run(request, "place")


def _run(request: Request, last: int) -> Result:
    timings: dict[str, float] = {}
    timed = _Timer(timings)
    loaded = timed("load", lambda: load(request))
    result = Result(loaded.diags, {}, timings=timings)
    result.od, result.lss, result.persist = loaded.od, loaded.lss, loaded.options.persist
    if _refuse(result, request) or loaded.od is None:  # refused says why, also when nothing was understood
        return result
    read = Diagnostics(list(result.diags.items), dict(result.diags.counts)) if request.fix else None
    timed("lint", lambda: lint(loaded, request, result.diags))
    if read is not None:
        loaded, result.repairs = timed("repair", lambda: repaired(loaded, read, request, result.diags))
        result.od, result.diags = loaded.od, loaded.diags
    if last < STAGES.index("place") or _refuse(result, request):
        return result
    where = timed("place", lambda: placed(loaded, result.diags))
    result.placements = where.placements
    if last < STAGES.index("view") or _refuse(result, request):
        return result
    dict_view = timed("view", lambda: view(loaded, where, request, result.diags))
    if _refuse(result, request):
        return result
    result.view = dict_view
    if last >= STAGES.index("render"):
        result.files = timed("render", lambda: render(dict_view, request, result.diags, result.repairs))
    return result


class _Timer:
    def __init__(self, timings: dict[str, float]) -> None:
        self.timings = timings

    def __call__(self, stage: str, fn: Callable[[], _T]) -> _T:
        start = time.perf_counter()
        try:
            return fn()
        finally:
            self.timings[stage] = time.perf_counter() - start


# -- what the stages share -------------------------------------------------------

def _options(request: Request, diags: Diagnostics, h: hashlib._Hash) -> Options:
    """The built-in defaults (e.g. the round trip's), then the options file, read once."""
    options = parse_options(request.defaults, "(built-in defaults)", diags) if request.defaults else Options()
    if request.options is None:
        return options
    data, user = read_options(request.options, diags)
    h.update(data)
    options.entries += user.entries
    options.persist = user.persist
    options.node_lss = options.node_lss or user.node_lss
    options.node_sdo_block = options.node_sdo_block and user.node_sdo_block
    options.node = {**options.node, **user.node}
    options.source, options.text = user.source, user.text
    return options


def _with_odgen_objects(od: ObjectDictionary, options: Options, diags: Diagnostics) -> ObjectDictionary:
    """The model with the objects odgen adds (the boot status object); the loaded model is not changed."""
    obj = status_object(od, options, diags)
    return od if obj is None else with_object(od, obj)


def _name(request: Request) -> str:
    return request.name or default_name(request.input)


def default_name(path: Path) -> str:
    """The file name as a C identifier; prefixed `od_` where it would clash with the runtime or C library."""
    name = identifier(path.stem, "od")
    return name if name_clash(name) is None else f"od_{name}"


def valid_name(name: str) -> bool:
    """--name must be a plain C identifier: no paths, no reserved words."""
    return is_identifier(name) and len(name) <= 32


def _check_name(request: Request, diags: Diagnostics) -> None:
    why = name_clash(request.name) if request.name else None
    if request.name and why:
        diags.add(GEN008, Loc(str(request.input)), f"--name {request.name} {why}; use e.g. --name od_{request.name}")


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
