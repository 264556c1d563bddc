"""odgen's CiA 401 objects against real DS401 descriptions in ../shared/corpus.

For each file, `odgen profile ds401` is built with the file's own channel counts (and with
every analog width, so that 0x6400..0x6412 all appear) and every 0x6000-0x6FFF object both
have is compared: object code, and per common sub-index data type, access and PDO mapping.
The device type and the default TPDO1/RPDO1 mapping for those counts are compared too. Every
difference must be a row of the table in docs/ds401.md ("Differences from the corpus files"),
with its reason, and every row there must still be a difference: the table is the result.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.formats import load_path
from odgen.model import ARRAY, RECORD, VAR, ObjectDictionary
from odgen.profiles.ds401 import Ds401, build

from .conftest import CORPUS, ROOT

# key in the docs table -> corpus file
FILES = {
    "K": "kacanopen__CiA_profiles_401.eds",
    "X1": "kacanopen__IoX1_16DI_8DO.eds",
    "X2": "kacanopen__IoX2_24DI.eds",
    "X3": "kacanopen__IoX3_24DO.eds",
    "D": "canopendemo__demoDevice.eds",
    "F": "canfestival__DS401_Slave_Gui.eds",
}
DOCS = ROOT / "docs" / "ds401.md"
CODES = {VAR: "VAR", ARRAY: "ARRAY", RECORD: "RECORD"}
Row = tuple[str, str, str, str, str]  # file key, entry, attribute, odgen, the file


def _load(name: str) -> ObjectDictionary:
    path = CORPUS / name
    if not path.is_file():
        pytest.skip("../shared/corpus is absent")
    od, _ = load_path(path)
    assert od is not None, name
    return od


def _count(od: ObjectDictionary, index: int) -> int:
    obj = od.objects.get(index)
    return obj.subs[0].default.parsed if obj is not None and obj.subs[0].default is not None else 0


def _counts(od: ObjectDictionary) -> dict[str, int]:
    return {"di": 8 * _count(od, 0x6000), "do": 8 * _count(od, 0x6200), "ai": _count(od, 0x6401),
            "ao": _count(od, 0x6411)}


def _show(attr: str, value: object) -> str:
    if attr == "object code":
        return CODES.get(value, str(value))  # type: ignore[call-overload]
    if attr == "PDO":
        return "yes" if value else "no"
    if attr == "type":
        return f"0x{value:04X}"  # type: ignore[str-format]
    return str(value)


def _mapping(od: ObjectDictionary, index: int) -> str:
    parts: list[tuple[int, int, int]] = []  # (index, first sub, last sub)
    for s in range(1, _count(od, index) + 1):
        raw = od.objects[index].subs[s].default.parsed
        obj, sub = raw >> 16, (raw >> 8) & 0xFF
        if parts and parts[-1][0] == obj and parts[-1][2] == sub - 1:
            parts[-1] = (obj, parts[-1][1], sub)
        else:
            parts.append((obj, sub, sub))
    return ", ".join(f"0x{i:04X} sub{a}" + (f"-{b}" if b > a else "") for i, a, b in parts) or "none"


def _object_rows(key: str, ours: ObjectDictionary, theirs: ObjectDictionary) -> set[Row]:
    rows = set()
    for obj in ours.sorted_objects():
        other = theirs.objects.get(obj.index)
        if not 0x6000 <= obj.index <= 0x6FFF or other is None:
            continue  # objects a file leaves out are optional or absent for its counts
        entry = f"0x{obj.index:04X}"
        if obj.object_code != other.object_code:
            rows.add((key, entry, "object code", _show("object code", obj.object_code),
                      _show("object code", other.object_code)))
        for sub in obj.subs.values():
            them = other.subs.get(sub.subindex)
            if them is None:
                continue
            for attr, field in (("type", "data_type"), ("access", "access"), ("PDO", "pdo_mapping")):
                mine, yours = getattr(sub, field), getattr(them, field)
                if mine != yours:
                    rows.add((key, entry, attr, _show(attr, mine), _show(attr, yours)))
    return rows


def _differences() -> set[Row]:
    rows: set[Row] = set()
    for key, name in FILES.items():
        theirs = _load(name)
        counts = _counts(theirs)
        for width in (8, 16, 32):
            rows |= _object_rows(key, build(Ds401(**counts, ai_width=width, ao_width=width)), theirs)
        ours = build(Ds401(**counts))
        device = (ours.objects[0x1000].subs[0].default.parsed, theirs.objects[0x1000].subs[0].default.parsed)
        if device[0] != device[1]:
            rows.add((key, "0x1000", "value", *(f"0x{v:08X}" for v in device)))
        for index in (0x1A00, 0x1600):
            if index in theirs.objects and _mapping(ours, index) != _mapping(theirs, index):
                rows.add((key, f"0x{index:04X}", "mapping", _mapping(ours, index), _mapping(theirs, index)))
    return rows


def _documented(path: Path) -> dict[Row, str]:
    """The rows of the docs table: file key, entry, attribute, odgen, the file -> why."""
    text = path.read_text(encoding="utf-8")
    section = text.split("### Differences from the corpus files", 1)[1].split("\n#", 1)[0]
    rows = {}
    for line in section.splitlines():
        cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
        if len(cells) == 6 and cells[0] in FILES:
            rows[(cells[0], cells[1], cells[2], cells[3], cells[4])] = cells[5]
    return rows


def test_every_corpus_difference_is_documented() -> None:
    found = _differences()
    documented = _documented(DOCS)
    assert sorted(found - documented.keys()) == [], "differences not in docs/ds401.md"
    assert sorted(documented.keys() - found) == [], "rows in docs/ds401.md that are no longer differences"
    assert all(len(why) >= 5 for why in documented.values()), "every row says why"


def test_io_x_modules_agree_on_shared_objects() -> None:
    """The SYS TEC IO-X1/X2/X3 modules: same types, access, mapping and device type as odgen."""
    assert not [row for row in _differences() if row[0].startswith("X")]
    assert _counts(_load(FILES["X1"])) == {"di": 16, "do": 8, "ai": 0, "ao": 0}
