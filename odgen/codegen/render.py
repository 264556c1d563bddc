"""The render stage: a finished view-model through the jinja2 templates into NAME.h, NAME.c and
NAME_config.h. The templates decide nothing; they print the view's lists."""

from __future__ import annotations

import contextlib
import operator
from collections.abc import Iterable
from typing import Any

import jinja2

from ..assets import templates_dir
from .viewmodel import DictView


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


def render_files(view: DictView, name: str, findings: list[str], repairs: list[str] | None = None) -> dict[str, str]:
    env = environment()
    return {f"{name}.h": env.get_template("dict.h.j2").render(v=view, findings=findings, repairs=repairs or []),
            f"{name}.c": env.get_template("dict.c.j2").render(v=view),
            f"{name}_config.h": env.get_template("dict_config.h.j2").render(v=view)}
