"""Concise DCF (CiA 306 part 1, "concise DCF"): the binary a master downloads into a slave.

    UNSIGNED32 number of entries
    per entry: UNSIGNED16 index, UNSIGNED8 sub-index, UNSIGNED32 size in bytes, the data

all little-endian, each entry's data as the slave's SDO server takes it. `ordered` puts the
entries in the order CiA 301 requires for changing a PDO; `encode` and `decode` write and read
the binary.
"""

from __future__ import annotations

import struct
from collections.abc import Iterable, Mapping

from ..model.cia301 import RPDO_COMM, RPDO_MAPPING, TPDO_COMM, TPDO_MAPPING

Entry = tuple[int, int, bytes]  # index, sub-index, data

_COUNT = struct.Struct("<I")
_HEAD = struct.Struct("<HBI")
PDO_INVALID = 0x80000000
MAPPING_OFFSET = RPDO_MAPPING - RPDO_COMM  # 0x200: a PDO's mapping object from its communication object


class ConciseError(ValueError):
    """The bytes are not a concise DCF; the message says where they stop being one."""


def encode(entries: Iterable[Entry]) -> bytes:
    body = [_HEAD.pack(index, sub, len(data)) + data for index, sub, data in entries]
    return _COUNT.pack(len(body)) + b"".join(body)


def decode(data: bytes) -> list[Entry]:
    if len(data) < _COUNT.size:
        raise ConciseError(f"{len(data)} bytes: too short for the entry count")
    (count,), at, entries = _COUNT.unpack_from(data), _COUNT.size, []
    for n in range(count):
        if at + _HEAD.size > len(data):
            raise ConciseError(f"entry {n + 1} of {count}: its header runs past the end at byte {at}")
        index, sub, size = _HEAD.unpack_from(data, at)
        at += _HEAD.size
        if at + size > len(data):
            raise ConciseError(f"entry {n + 1} of {count} (0x{index:04X}sub{sub}): {size} bytes of data "
                               f"run past the end at byte {at}")
        entries.append((index, sub, bytes(data[at:at + size])))
        at += size
    if at != len(data):
        raise ConciseError(f"{len(data) - at} bytes after the last of {count} entries")
    return entries


def is_pdo_parameter(index: int) -> bool:
    return RPDO_COMM <= index < RPDO_COMM + 0x200 or TPDO_COMM <= index < TPDO_COMM + 0x200 \
        or RPDO_MAPPING <= index < RPDO_MAPPING + 0x200 or TPDO_MAPPING <= index < TPDO_MAPPING + 0x200


def communication_of(index: int) -> int:
    """The communication object (0x1400.., 0x1800..) of a PDO parameter object."""
    return index - MAPPING_OFFSET if RPDO_MAPPING <= index < RPDO_MAPPING + 0x200 \
        or TPDO_MAPPING <= index < TPDO_MAPPING + 0x200 else index


def ordered(values: Mapping[tuple[int, int], bytes], cob_ids: Mapping[int, int]) -> list[Entry]:
    """The entries that write `values` ((index, sub) -> data) into a slave, by index and sub-index,
    except that each PDO whose parameters are written is changed as CiA 301 requires: its COB-ID
    with bit 31 set (invalid), its other communication parameters, its mapping's sub 0 = 0, the
    mapping entries, the mapping's sub 0, and the COB-ID as configured last. `cob_ids` holds the
    COB-ID in force (configured, else the description's) of every communication object concerned."""
    pdos = sorted({communication_of(i) for i, _ in values if is_pdo_parameter(i)})
    blocks = {comm: _pdo_block(comm, values, cob_ids[comm]) for comm in pdos}
    entries: list[Entry] = []
    for index, sub in sorted(values):
        if not is_pdo_parameter(index):
            entries.append((index, sub, values[(index, sub)]))
        elif index in blocks:
            entries += blocks.pop(index)
    for comm in sorted(blocks):  # only the mapping of these PDOs is configured
        entries += blocks[comm]
    return entries


def _pdo_block(comm: int, values: Mapping[tuple[int, int], bytes], cob_id: int) -> list[Entry]:
    mapping = comm + MAPPING_OFFSET
    final = values.get((comm, 1), cob_id.to_bytes(4, "little"))
    block: list[Entry] = [(comm, 1, (int.from_bytes(final, "little") | PDO_INVALID).to_bytes(4, "little"))]
    block += [(comm, sub, values[(comm, sub)]) for c, sub in sorted(values) if c == comm and sub != 1]
    mapped = sorted(sub for index, sub in values if index == mapping)
    if mapped:
        count = values.get((mapping, 0), bytes([max(mapped)]))
        block.append((mapping, 0, bytes(len(count))))
        block += [(mapping, sub, values[(mapping, sub)]) for sub in mapped if sub > 0]
        block.append((mapping, 0, count))
    if not int.from_bytes(final, "little") & PDO_INVALID:
        block.append((comm, 1, final))
    return block
