"""odgen.model.cia301 and odgen.model.wire against the runtime's C, which mirrors their numbers.

The C cannot import the Python module, so these tests read the C sources and fail when a
number there and its name here disagree.
"""

from __future__ import annotations

import re

import pytest

from odgen.model import cia301
from odgen.model.datatypes import BASIC_TYPES, BY_NAME, DataType
from odgen.model.wire import wire_bytes, wire_number

from .conftest import ROOT

RUNTIME = ROOT / "runtime"
# The runtime files that address the dictionary by index (odg_sdo.c's only 0x1xxx is a CRC polynomial).
INDEXED = ("odg_node.c", "odg_pdo.c", "profiles/ds401.c")


def _code(name: str) -> str:
    """A C file without its comments."""
    text = (RUNTIME / name).read_text(encoding="utf-8")
    return re.sub(r"//[^\n]*", "", re.sub(r"/\*.*?\*/", "", text, flags=re.S))


def _function(name: str, function: str) -> str:
    code = _code(name)
    start = code.index(f" {function}(")
    return code[start:code.index("\n}", start)]


def _hex(text: str) -> set[int]:
    return {int(h, 16) for h in re.findall(r"\b0x([0-9A-Fa-f]+)u?\b", text)}


def test_abort_codes_are_the_runtimes() -> None:
    header = (RUNTIME / "odg.h").read_text(encoding="utf-8")
    rows = re.findall(r"#define (ODG_ABORT_\w+)\s+UINT32_C\((0x[0-9A-Fa-f]+)\)", header)
    assert {name: int(code, 16) for name, code in rows} == cia301.ABORT_CODES
    assert set(re.findall(r"X\((ODG_ABORT_\w+),", header)) == set(cia301.ABORT_CODES)  # each has a text


def test_store_and_restore_command_words_are_the_runtimes() -> None:
    words = dict(re.findall(r"#define (CMD_SAVE|CMD_LOAD) (0x[0-9A-Fa-f]+)u", _code("odg.c")))
    assert int(words["CMD_SAVE"], 16) == int.from_bytes(cia301.SAVE, "little")
    assert int(words["CMD_LOAD"], 16) == int.from_bytes(cia301.LOAD, "little")


@pytest.mark.parametrize("name", INDEXED)
def test_every_index_the_runtime_names_is_named_here(name: str) -> None:
    named = {v for v in vars(cia301).values() if isinstance(v, int)}
    named |= {n for v in vars(cia301).values() if isinstance(v, tuple) for n in v if isinstance(n, int)}  # areas
    named.add(cia301.TPDO_MAPPING + cia301.PDO_COUNT)  # the end of the PDO records
    indices = {n for n in _hex(_code(name)) if 0x1000 <= n <= 0x1FFF}
    assert indices, f"{name}: no index found; has the file moved?"
    assert indices <= named, f"{name}: {sorted(hex(i) for i in indices - named)} not in odgen/model/cia301.py"


def test_predefined_can_ids_are_the_runtimes() -> None:
    code = _code("odg_node.c")
    for base in (cia301.SDO_REQUEST, cia301.SDO_RESPONSE, cia301.HEARTBEAT, cia301.EMCY_BASE):
        assert re.search(rf"0x{base:X}u \+ (id|n->cfg\.node_id)\b", code), f"0x{base:X} + node-id"


def test_restricted_can_ids_are_the_runtimes() -> None:
    bounds = {n for pair in cia301.RESTRICTED_CAN_IDS for n in pair} - {0, cia301.CAN_ID_MASK}
    assert _hex(_function("odg_pdo.c", "restricted")) == bounds


def test_predefined_connection_set() -> None:
    assert cia301.predefined_cob_id(cia301.RPDO_COMM + 3, 1) == (0x500, "RPDO4")
    assert cia301.predefined_cob_id(cia301.TPDO_COMM, 1) == (0x180, "TPDO1")
    assert cia301.predefined_cob_id(cia301.EMCY_COB_ID, 0) == (0x80, "EMCY")
    assert cia301.predefined_cob_id(cia301.TPDO_COMM + 4, 1) is None


def test_unused_manufacturer_index() -> None:
    assert cia301.unused_manufacturer_index({0x5FFF, 0x5FFE}) == 0x5FFD


@pytest.mark.parametrize("dtype", [t for t in BASIC_TYPES.values() if t.is_numeric], ids=lambda t: t.name)
def test_numbers_round_trip_through_the_wire(dtype: DataType) -> None:
    for value in (dtype.min, dtype.max, 1):
        data = wire_bytes(value, dtype)
        assert len(data) == max(dtype.bits // 8, 1)
        assert wire_number(data, dtype) == pytest.approx(value)


def test_wire_encoding_is_little_endian_and_twos_complement() -> None:
    assert wire_bytes(-2, BY_NAME["INTEGER16"]) == b"\xfe\xff"
    assert wire_bytes(0x123456, BY_NAME["UNSIGNED24"]) == b"\x56\x34\x12"
    assert wire_bytes(1.0, BY_NAME["REAL32"]) == b"\x00\x00\x80\x3f"
    assert wire_bytes("ab", BY_NAME["UNICODE_STRING"]) == b"a\x00b\x00"
    assert wire_bytes("ab", BY_NAME["VISIBLE_STRING"]) == b"ab"
