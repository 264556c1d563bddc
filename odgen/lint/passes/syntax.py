"""SYN: file-level syntax rules, reported by the readers, and value notes.

The INI and EDS readers emit most of these while reading; the one check here
reports what value parsing noticed (octal, `$NODEID` forms, unreadable values)
for every reader alike.
"""

from __future__ import annotations

from ...catalogue.rule import Rule
from ...catalogue.syntax import SYN011
from ...diagnostics import Diagnostics, Loc
from ...model import Obj, ObjectDictionary, Value
from .base import LintOptions, LintPass



# The key each value of a sub-entry is written under, in the EDS/DCF and in the XDD/XDC forms.
VALUE_KEYS = {"default": ("DefaultValue", "defaultValue"), "low": ("LowLimit", "lowLimit"),
              "high": ("HighLimit", "highLimit"), "parameter_value": ("ParameterValue", "actualValue")}


def value_notes(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    """Report what parsing each value noticed, and values that did not parse: one finding per note of
    a sub-entry, naming the keys it applies to (LowLimit, HighLimit and DefaultValue alike 0xFFFF: one)."""
    form = 1 if od.format in ("xdd", "xdc") else 0
    for obj in od.objects.values():
        for sub in obj.subs.values():
            found: dict[tuple[Rule, str], list[tuple[int, str]]] = {}
            for attr, keys in VALUE_KEYS.items():
                value: Value | None = getattr(sub, attr)
                if value is None:
                    continue
                problems = value.notes + (((SYN011, value.error),) if value.error else ())
                for note in problems:
                    found.setdefault(note, []).append((value.line, keys[form]))
            for (rule, message), places in found.items():
                places.sort()
                diags.add(rule, Loc(od.source, places[0][0]), f"{', '.join(k for _, k in places)}: {message}",
                          obj.index, _sub_of(obj, sub.subindex))


def _sub_of(obj: Obj, subindex: int) -> int | None:
    return None if obj.is_var else subindex


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (value_notes,)
