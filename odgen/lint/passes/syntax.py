"""SYN: file-level syntax rules, reported by the readers, and value notes.

The INI and EDS readers emit most of these while reading; the one check here
reports what value parsing noticed (octal, `$NODEID` forms, unreadable values)
for every reader alike.
"""

from __future__ import annotations

from ...catalogue.syntax import SYN011
from ...diagnostics import Diagnostics, Loc
from ...model import ObjectDictionary, Value
from .base import LintOptions, LintPass



def value_notes(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    """Report what parsing each value noticed, and values that did not parse."""
    for obj in od.objects.values():
        for sub in obj.subs.values():
            for value in (sub.default, sub.low, sub.high, sub.parameter_value):
                if value is not None and (value.notes or value.error):
                    _report_value(od.source, value, obj.index, _sub_of(obj, sub.subindex), diags)


def _sub_of(obj, subindex: int) -> int | None:
    return None if obj.is_var else subindex


def _report_value(source: str, value: Value, index: int, sub: int | None, diags: Diagnostics) -> None:
    loc = Loc(source, value.line)
    for rule, message in value.notes:
        diags.add(rule, loc, message, index, sub)
    if value.error:
        diags.add(SYN011, loc, value.error, index, sub)


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (value_notes,)
