"""Model -> EDS -> model keeps every value, for every corpus file and the examples.

Compared: objects (every sub-entry attribute, value texts and parsed values,
unknown keys) and header sections. Not compared, by design: comments, key
order, duplicates the reader already ignored, object-list entries that name
no object (the writer derives the lists from the objects), and an XML file's
properties that are no CiA 306 keyword (CANopenEditor's CO_flagsPDO ...): the
writer keeps them as `;Key=Value` comments. String values keep their trailing
blanks (CANopenNode pads a string to reserve its capacity).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.formats import load_bytes, load_path
from odgen.formats.eds import KEYWORDS
from odgen.formats.eds_writer import list_of, write_eds
from odgen.model import ObjectDictionary

from .conftest import ROOT, corpus_params


def _semantic(od: ObjectDictionary) -> tuple:
    objects = {i: (o, list_of(o)) for i, o in od.objects.items()}
    sections = {k: (s.name, s.fields) for k, s in od.sections.items()}
    return objects, sections, od.node_id


def _drop_xml_properties(od: ObjectDictionary) -> None:
    keywords = {k.lower() for k in KEYWORDS}
    for obj in od.objects.values():
        for extra in (obj.extra, *(sub.extra for sub in obj.subs.values())):
            for key in [k for k, f in extra.items() if f.key not in KEYWORDS and k not in keywords]:
                del extra[key]


def _round_trip(path: Path) -> None:
    first, _ = load_path(path)
    assert first is not None
    if first.format in ("xdd", "xdc"):
        _drop_xml_properties(first)
    fmt = "dcf" if first.is_config else "eds"
    text = write_eds(first)
    second, _ = load_bytes(text.encode("utf-8"), "again." + fmt, fmt)
    assert second is not None
    a, b = _semantic(first), _semantic(second)
    for index in sorted(set(a[0]) | set(b[0])):
        assert a[0].get(index) == b[0].get(index), f"0x{index:04X} differs after the round trip"
    assert a[1:] == b[1:]
    assert write_eds(second) == text, "writing what the writer wrote must be byte-stable"


@pytest.mark.parametrize("path", corpus_params())
def test_corpus_round_trip(path: Path) -> None:
    od, _ = load_path(path)
    if od is None:
        pytest.skip(f"{path.name} is rejected by the reader (see the corpus report)")
    _round_trip(path)


@pytest.mark.parametrize("path", sorted(ROOT.glob("examples/*/*.eds")), ids=lambda p: p.name)
def test_example_round_trip_is_byte_identical(path: Path) -> None:
    _round_trip(path)
    od, _ = load_path(path)
    assert write_eds(od) == path.read_text(encoding="utf-8")
