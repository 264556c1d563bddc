"""Helpers the rule families share; no rules or checks of their own.

Values: the node-ids a `$NODEID` value must work for, a value's number, the
value in force in a DCF and where to point at it. Entries: the sub-index to
name in a message and CANopenEditor's `CO_disabled`. Header sections: keys
read as integers, Granularity and [DummyUsage].
"""

from __future__ import annotations

from ...model import Field, Obj, ObjectDictionary, Sub, Value
from ...model.header import header_field, header_int
from ...model.values import number
from .base import LintOptions

_NODE_IDS = (1, 127)


# -- values ----------------------------------------------------------------------

def node_span(od: ObjectDictionary, options: LintOptions) -> tuple[int, int]:
    """The node-ids a `$NODEID` value must work for: the given one, a DCF's, or 1..127."""
    if options.node_id is not None:
        return options.node_id, options.node_id
    if od.is_config and od.node_id is not None and 1 <= od.node_id <= 127:
        return od.node_id, od.node_id
    return _NODE_IDS


def at(value: Value, node_id: int) -> int | float | None:
    """A value's number for a node-id: `$NODEID+v` is v + node_id."""
    n = number(value)
    if n is None:
        return None
    return n + node_id if value.nodeid else n


def value_in_force(od: ObjectDictionary, sub: Sub) -> tuple[Value | None, str]:
    """The value in force (ObjectDictionary.value_in_force), with the keyword to point at."""
    value = od.value_in_force(sub)
    return value, "parametervalue" if value is not None and value is sub.parameter_value else "defaultvalue"


def value_line(sub: Sub, value: Value | None, keyword: str) -> int:
    """The line of a value, else of its keyword, else of the entry."""
    if value is not None and value.line:
        return value.line
    return sub.line_of(keyword)


def default_line(sub: Sub) -> int:
    return value_line(sub, sub.default, "defaultvalue")


# -- entries ---------------------------------------------------------------------

def addr(obj: Obj, sub: Sub) -> int | None:
    """The sub-index to name in a message: none for single-value objects."""
    return None if obj.is_var else sub.subindex


def disabled(obj: Obj) -> bool:
    """CANopenEditor's `CO_disabled`: kept in the project, left out of every export."""
    flag = obj.extra.get("co_disabled")
    return flag is not None and flag.text.strip().lower() == "true"


def gaps(count: int, present: set[int], limit: int = 5) -> tuple[list[int], int]:
    """The first `limit` numbers of 1..count not in `present`, and how many are missing.

    Bounded by the entries present, not by `count`: a file may claim a count of 10**9.
    """
    inside = sum(1 for n in present if 1 <= n <= count)
    first = [n for n in range(1, min(count, inside + limit) + 1) if n not in present][:limit]
    return first, count - inside


# -- header sections -------------------------------------------------------------

def granularity(od: ObjectDictionary) -> tuple[int | None, Field | None]:
    """[DeviceInfo] Granularity as a number, and its field."""
    fld = header_field(od, "DeviceInfo", "Granularity")
    return header_int(fld), fld


def dummy_enabled(od: ObjectDictionary, index: int) -> bool:
    """Whether [DummyUsage] enables the data type at `index` as a dummy mapping entry."""
    return header_int(header_field(od, "DummyUsage", f"Dummy{index:04X}")) == 1
