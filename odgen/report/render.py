"""The report as one self-contained HTML page, or as Markdown with its pictures as SVG files."""

from __future__ import annotations

from pathlib import Path

import jinja2
from markupsafe import Markup

from ..assets import templates_dir
from ..diagnostics import RULES
from .svg import memory_svg, pdo_svg
from .view import RULES_DOC, Pdo, Report, rule_anchor


def _environment(markdown: bool) -> jinja2.Environment:
    """HTML escapes as HTML does; Markdown with _markdown_text, since a Markdown renderer passes raw HTML on."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(str(templates_dir())), undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
                             autoescape=True, finalize=_markdown_text if markdown else None)
    env.filters["hex"] = lambda n, width=4: f"0x{n:0{width}X}"
    env.filters["cell"] = _cell
    env.filters["rule_link"] = lambda rule_id: f"{RULES_DOC}#{rule_anchor(rule_id)}"
    env.filters["catalogue"] = lambda text: Markup(_cell(text))  # odgen's own rule texts keep their `code`
    env.globals["rules_doc"] = RULES_DOC
    return env


# What a Markdown renderer would read as HTML, a code span or a link, as character references:
# names and values come from the description, which may hold `<script>` (the renderer shows the
# references as the characters).
_MARKDOWN_ACTIVE = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", "`": "&#96;", "[": "&#91;", "]": "&#93;"})


def _markdown_text(value: object) -> Markup:
    """Every value a Markdown template writes, made inert; a macro's output (Markup) is already."""
    return value if isinstance(value, Markup) else Markup(str(value).translate(_MARKDOWN_ACTIVE))


def _cell(value: object) -> str:
    """A Markdown table cell: one line, pipes escaped."""
    return " ".join(str(value).split()).replace("|", "\\|")


def _rules(report: Report) -> list[object]:
    cited = {f.rule for f in report.general} | {f.rule for r in report.rows for f in r.findings}
    if report.network is not None:
        cited |= {f.rule for f in report.network.findings}
    return [RULES[rule] for rule in sorted(cited)]


def _pictures(report: Report) -> dict[str, str]:
    """SVG text per picture name: one per PDO, the memory map, one per network TPDO."""
    pictures = {p.key: pdo_svg(p) for p in report.pdos}
    if report.memory is not None:
        pictures["memory"] = memory_svg(report.memory)
    flows: list[Pdo] = report.network.flows if report.network is not None else []
    pictures |= {f"net-{p.key}": pdo_svg(p) for p in flows}
    return pictures


def render_html(report: Report) -> str:
    pictures = {name: Markup(svg) for name, svg in _pictures(report).items()}
    template = _environment(markdown=False).get_template("report.html.j2")
    return template.render(r=report, svg=pictures, rules=_rules(report))


def render_markdown(report: Report, output: Path) -> dict[Path, str]:
    """The SVG files (in OUTPUT's stem + `-svg/`) and then the Markdown file that shows them, by path."""
    folder = output.with_name(output.stem + "-svg")
    pictures = _pictures(report)
    links = {name: f"{folder.name}/{name}.svg" for name in pictures}
    text = _environment(markdown=True).get_template("report.md.j2").render(r=report, svg=links, rules=_rules(report))
    return {**{folder / f"{name}.svg": svg for name, svg in pictures.items()}, output: text}
