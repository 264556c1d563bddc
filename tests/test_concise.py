"""Concise DCF: what odgen writes is what a reader written from CiA 306 alone decodes.

python canopen has no concise DCF reader, so `_cia306_read` below is one, written from the
standard's layout (not from odgen.formats.concise): it reads byte by byte, little-endian.
"""

from __future__ import annotations

import pytest

from odgen.formats.concise import ConciseError, decode, encode, ordered


def _le(data: bytes) -> int:
    return sum(b << (8 * n) for n, b in enumerate(data))


def _cia306_read(data: bytes) -> list[tuple[int, int, bytes]]:
    count, pos, out = _le(data[0:4]), 4, []
    for _ in range(count):
        index, sub, size = _le(data[pos:pos + 2]), data[pos + 2], _le(data[pos + 3:pos + 7])
        pos += 7
        out.append((index, sub, data[pos:pos + size]))
        pos += size
    assert pos == len(data), "bytes left after the last entry"
    return out


def test_encode_is_what_cia306_reads() -> None:
    entries = [(0x1017, 0, b"\x64\x00"), (0x2000, 3, b"hello"), (0x1800, 1, b"\x82\x01\x00\x80")]
    data = encode(entries)
    assert data[:4] == b"\x03\x00\x00\x00"
    assert data[4:11] == b"\x17\x10\x00\x02\x00\x00\x00"  # index 0x1017, sub 0, size 2
    assert _cia306_read(data) == entries
    assert decode(data) == entries


def test_empty() -> None:
    assert encode([]) == b"\x00\x00\x00\x00"
    assert decode(b"\x00\x00\x00\x00") == []


@pytest.mark.parametrize("data", [b"", b"\x01\x00", b"\x01\x00\x00\x00\x17\x10",
                                  b"\x01\x00\x00\x00\x17\x10\x00\x05\x00\x00\x00ab",
                                  b"\x00\x00\x00\x00\xff"])
def test_decode_refuses_truncated_or_trailing_bytes(data: bytes) -> None:
    with pytest.raises(ConciseError):
        decode(data)


def u32(n: int) -> bytes:
    return n.to_bytes(4, "little")


def test_pdo_written_in_cia301_order() -> None:
    values = {(0x1017, 0): b"\x64\x00", (0x1800, 1): u32(0x182), (0x1800, 2): b"\xfe",
              (0x1A00, 0): b"\x02", (0x1A00, 1): u32(0x60000108), (0x1A00, 2): u32(0x60000208),
              (0x6200, 1): b"\x00"}
    entries = ordered(values, {0x1800: 0x182})
    assert [(i, s, d) for i, s, d in entries] == [
        (0x1017, 0, b"\x64\x00"),
        (0x1800, 1, u32(0x80000182)),  # invalid first
        (0x1800, 2, b"\xfe"),
        (0x1A00, 0, b"\x00"),  # mapping disabled
        (0x1A00, 1, u32(0x60000108)),
        (0x1A00, 2, u32(0x60000208)),
        (0x1A00, 0, b"\x02"),  # mapping enabled
        (0x1800, 1, u32(0x182)),  # valid last
        (0x6200, 1, b"\x00"),
    ]


def test_mapping_only_takes_the_cob_id_in_force() -> None:
    values = {(0x1600, 0): b"\x01", (0x1600, 1): u32(0x62000108)}
    entries = ordered(values, {0x1400: 0x202})
    assert entries[0] == (0x1400, 1, u32(0x80000202))
    assert entries[-1] == (0x1400, 1, u32(0x202))
    assert [e[:2] for e in entries] == [(0x1400, 1), (0x1600, 0), (0x1600, 1), (0x1600, 0), (0x1400, 1)]


def test_disabled_pdo_stays_disabled() -> None:
    entries = ordered({(0x1801, 1): u32(0x80000282)}, {0x1801: 0x80000282})
    assert entries == [(0x1801, 1, u32(0x80000282))]
