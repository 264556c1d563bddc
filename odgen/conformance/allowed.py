"""What CiA 301 lets a device answer beyond what its description states.

A description gives an entry's type, access and limits; CiA 301 adds ranges and conditions of
its own for some communication objects, and a device may refuse a write for those reasons with
the abort code CiA 301 names for it. The battery accepts such an answer (and says why); any
other code still fails, named beside the one expected. Run-time state (the error register, the
error history, time stamps) is never compared with a described default, only checked for
consistency (docs/conformance.md).
"""

from __future__ import annotations

from ..model.values import number
from ..model.cia301 import CONSUMER_HEARTBEAT, ERROR_BEHAVIOUR, ERROR_HISTORY, ERROR_REGISTER, SYNC_OVERFLOW, \
    SYNC_PERIOD
from .client import NO_ANSWER, Client

RANGE, HIGH, LOW = 0x06090030, 0x06090031, 0x06090032
INCOMPATIBLE = 0x06040043
DEVICE_STATE = 0x08000022  # "data cannot be transferred because of the present device state"
NO_DATA = 0x08000024  # "no data available": a 0x1003 sub-entry beyond the errors recorded
MANUFACTURER_STATUS, HIGH_RESOLUTION_TIME = 0x1002, 0x1013
# Values the device changes itself: checked for consistency, never against a default.
RUN_TIME_STATE = frozenset({ERROR_REGISTER, MANUFACTURER_STATUS, ERROR_HISTORY, HIGH_RESOLUTION_TIME})


def code_text(code: int) -> str:
    return "no answer" if code == NO_ANSWER else f"0x{code:08X}"


def watched_elsewhere(c: Client, sub: int) -> set[int]:
    """The node-ids the node's other used 0x1016 sub-entries watch (as uploaded now)."""
    out = set()
    obj = c.od.objects.get(CONSUMER_HEARTBEAT)
    for other in sorted(obj.subs) if obj is not None else []:
        if other not in (0, sub):
            value = c.number(CONSUMER_HEARTBEAT, other) or 0
            if value >> 16 & 0xFF and value & 0xFFFF:
                out.add(value >> 16 & 0xFF)
    return out


def write_refusals(c: Client, index: int, sub: int, data: bytes) -> dict[int, str]:
    """Abort codes CiA 301 lets the node give for this write whatever the description's limits
    say: code -> the reason."""
    value = int.from_bytes(data, "little")
    out: dict[int, str] = {}
    if index == SYNC_OVERFLOW:
        if len(data) == 1 and (value == 1 or value > 240):
            why = f"CiA 301 reserves 0x1019 = {value} (only 0 and 2..240 are defined)"
            out.update({RANGE: why, HIGH: why, LOW: why})
        period = c.number(SYNC_PERIOD) if c.od.find(SYNC_PERIOD) is not None else 0
        if period:  # whatever the length: CiA 301 does not say which a device looks at first
            out[DEVICE_STATE] = f"0x1019 may only be written while 0x1006 is 0 (it is {period})"
    elif index == CONSUMER_HEARTBEAT and sub >= 1 and len(data) == 4:
        node, ms = value >> 16 & 0xFF, value & 0xFFFF
        if node > 127:
            out[RANGE] = f"node-id {node} is not one of 1..127"
        elif node and ms and node in watched_elsewhere(c, sub):
            out[INCOMPATIBLE] = f"node {node} is already watched by another 0x1016 sub-entry"
    elif index == ERROR_BEHAVIOUR and sub >= 1 and len(data) == 1 and 3 <= value <= 127:
        why = f"CiA 301 reserves 0x1029 = {value} (0, 1, 2 and 128..255 are defined)"
        out.update({RANGE: why, HIGH: why, LOW: why})
    return out


def consumer_room(c: Client, sub: int) -> str:
    """Why the description leaves 0x1016 `sub` no room to watch a node (its HighLimit below what the
    entry's node-id, bits 16-23, needs), or "": a check that must watch one cannot be judged then."""
    entry = c.od.find(CONSUMER_HEARTBEAT, sub)
    limit = entry.high if entry is not None else None
    high = number(limit) if limit is not None and not limit.nodeid else None
    if limit is not None and high is not None and high < 1 << 16:
        return f"0x1016sub{sub}'s HighLimit {limit.text.strip()} leaves no room for a node-id (bits 16-23)"
    return ""
