"""The object-dictionary model shared by every reader, rule and generator."""

from .datatypes import BASIC_TYPES, DataType, lookup
from .od import (
    ACCESS_TYPES,
    ARRAY,
    DEFSTRUCT,
    DEFTYPE,
    DOMAIN,
    RECORD,
    VAR,
    Field,
    Obj,
    ObjectDictionary,
    ObjectList,
    Section,
    Sub,
)
from .values import Value, parse_value

__all__ = [
    "ACCESS_TYPES", "ARRAY", "BASIC_TYPES", "DEFSTRUCT", "DEFTYPE", "DOMAIN", "RECORD", "VAR",
    "DataType", "Field", "Obj", "ObjectDictionary", "ObjectList", "Section", "Sub", "Value",
    "lookup", "parse_value",
]
