"""A concise DCF (CiA 306, the binary 0x1F22 holds) for the tests: the entry count, then each
entry's index (2 bytes), sub-index (1), data size (4) and data, little endian. The master's
tests write their own so that they do not depend on the generator's writer; `read` decodes one
the same way (tests compare what the slaves hold with it)."""

from __future__ import annotations

import struct

Entry = tuple[int, int, bytes]


def write(entries: list[Entry]) -> bytes:
    out = bytearray(struct.pack("<I", len(entries)))
    for index, sub, data in entries:
        out += struct.pack("<HBI", index, sub, len(data)) + data
    return bytes(out)


def read(blob: bytes) -> list[Entry]:
    (count,), at, entries = struct.unpack_from("<I", blob), 4, []
    for _ in range(count):
        index, sub, size = struct.unpack_from("<HBI", blob, at)
        entries.append((index, sub, blob[at + 7:at + 7 + size]))
        at += 7 + size
    assert at == len(blob), "bytes after the last entry"
    return entries


def final_values(entries: list[Entry]) -> dict[tuple[int, int], bytes]:
    """What each configured entry holds once the DCF is downloaded: the last value written to it."""
    return {(index, sub): data for index, sub, data in entries}
