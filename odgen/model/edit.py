"""New models from old ones: what odgen adds to a description is added as the description would
declare it, in a copy; the model a stage was given is never changed."""

from __future__ import annotations

import copy

from .cia301 import object_list_for
from .od import Field, Obj, ObjectDictionary, ObjectList
from .values import parse_int_literal

_LIST_NAMES = {"mandatoryobjects": "MandatoryObjects", "optionalobjects": "OptionalObjects",
               "manufacturerobjects": "ManufacturerObjects"}


def with_object(od: ObjectDictionary, obj: Obj) -> ObjectDictionary:
    """A copy of `od` with `obj` added: its SubNumber declared and, in an EDS/DCF that has object
    lists, an entry in the list its index belongs in."""
    added = copy.copy(od)
    obj.sub_number = len(obj.subs) if not obj.is_var else None
    added.objects = {**od.objects, obj.index: obj}
    if od.format in ("xdd", "xdc") or not od.object_lists:
        return added
    key = object_list_for(obj.index)
    obj.object_list = key
    added.object_lists = {**od.object_lists, key: _listed(od.object_lists.get(key), key, obj.index)}
    return added


def _listed(olist: ObjectList | None, key: str, index: int) -> ObjectList:
    """The list with one more entry, its SupportedObjects counting it."""
    entries = list(olist.entries) if olist is not None else []
    declared, _ = parse_int_literal(olist.supported.text) if olist is not None and olist.supported else (None, ())
    number = (declared if declared is not None else len(entries)) + 1
    name = olist.name if olist is not None else _LIST_NAMES[key]
    line = olist.line if olist is not None else 0
    entry = Field(str(number), f"0x{index:04X}")
    return ObjectList(name, line, Field("SupportedObjects", str(number)), [*entries, entry])
