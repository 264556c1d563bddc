"""COM: the COB-IDs of one device: the default SDO server's, and no two enabled objects on one CAN-ID.

`odgen lint --network` finds collisions across devices (NET004, NET007); these
checks look inside one description, with each value in force for the node-ids
it must work for (rules.common.node_span).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from ...catalogue.comm import COM016, COM017, COM018, COM019
from ...diagnostics import Diagnostics, Loc, where
from ...model import Obj, ObjectDictionary, Sub
from ...model.cia301 import (
    COB_EXTENDED, COB_INVALID, COB_PRODUCER, EMCY_COB_ID, ERROR_HISTORY, RESTRICTED_CAN_IDS, SDO_CLIENT, SDO_SERVER,
    SYNC_COB_ID, TIME_COB_ID, is_sdo_parameter, pdo_communication)
from .base import LintOptions, LintPass
from .common import addr, at, node_span, value_in_force, value_line

READ_ONLY = ("ro", "const")
SERVICES = {SYNC_COB_ID: "SYNC", TIME_COB_ID: "TIME", EMCY_COB_ID: "EMCY"}


@dataclass(frozen=True)
class Use:
    """One enabled object that sends or receives on a COB-ID."""

    name: str
    index: int
    sub: int | None
    line: int


def _named_entries(od: ObjectDictionary) -> Iterator[tuple[str, Obj, Sub | None]]:
    """(name, object, sub-entry) of every COB-ID entry CiA 301 defines (PDO, SDO, EMCY, SYNC, TIME)."""
    for index in sorted(od.objects):
        if index >= 0x2000:
            break  # all of them are communication profile objects (0x1000-0x1FFF)
        obj = od.objects[index]
        pdo = pdo_communication(index)
        if pdo is not None:
            yield f"{pdo}{(index & 0x1FF) + 1}", obj, obj.subs.get(1)
        elif is_sdo_parameter(index):
            kind = "SDO server" if index < SDO_CLIENT else "SDO client"
            yield f"{kind} {index & 0x7F} client-to-server", obj, obj.subs.get(1)
            yield f"{kind} {index & 0x7F} server-to-client", obj, obj.subs.get(2)
        elif index in SERVICES and obj.is_var:
            yield SERVICES[index], obj, obj.var


def _uses(od: ObjectDictionary, node_id: int) -> Iterator[tuple[int, Use]]:
    """(CAN-ID, use) of every enabled 11-bit COB-ID at `node_id` (heartbeat's 0x700+node-id is COM005's)."""
    for name, obj, sub in _named_entries(od):
        if sub is None:
            continue
        value, keyword = value_in_force(od, sub)
        raw = at(value, node_id) if value is not None else None
        if not isinstance(raw, int) or raw < 0 or raw & (COB_INVALID | COB_EXTENDED) or not raw & 0x7FF:
            continue  # disabled, a 29-bit identifier, or not yet configured (0)
        if obj.index in (SYNC_COB_ID, TIME_COB_ID) and not raw & COB_PRODUCER:
            continue  # SYNC/TIME consumed only: receiving what another node produces is the point
        yield raw & 0x7FF, Use(name, obj.index, addr(obj, sub), value_line(sub, value, keyword))


def _collisions(od: ObjectDictionary, node_id: int) -> dict[tuple[Use, Use], int]:
    """(later use, earlier use) -> CAN-ID of every two uses that share a CAN-ID at `node_id`. Every
    pair, not only the first use of a CAN-ID: which use comes first can change with the node-id (a
    fixed 0x181 before $NODEID+0x180 at node-id 1 only), and a pair is reported where it holds at both."""
    seen: dict[int, list[Use]] = {}
    found: dict[tuple[Use, Use], int] = {}
    for can_id, use in _uses(od, node_id):
        earlier = seen.setdefault(can_id, [])
        for first in earlier:
            found[use, first] = can_id
        earlier.append(use)
    return found


def cob_id_collisions(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    """Collisions at every node-id the file must work for: a fixed COB-ID that meets a `$NODEID` one at a
    single node-id (a master receiving node 127's TPDO1 on 0x1FF) is left to `lint --network`."""
    lo, hi = node_span(od, options)
    found = _collisions(od, lo)
    if hi != lo:
        at_hi = _collisions(od, hi)
        found = {pair: can_id for pair, can_id in found.items() if pair in at_hi}
    reported: set[Use] = set()
    for (use, first), can_id in found.items():
        if use in reported:
            continue
        reported.add(use)
        diags.add(COM016, Loc(od.source, use.line),
                  f"{use.name} uses CAN-ID 0x{can_id:X}{'' if hi != lo else f' (node-id {lo})'}, as does "
                  f"{first.name} ({where(first.index, first.sub)})", use.index, use.sub)


def default_sdo_server(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(SDO_SERVER)
    if obj is None or obj.is_var:
        return
    for subindex, base in ((1, 0x600), (2, 0x580)):
        sub = obj.subs.get(subindex)
        if sub is None:
            continue
        if sub.access not in READ_ONLY:
            diags.add(COM017, Loc(od.source, sub.line_of("accesstype")),
                      f"is {sub.access}; the default SDO server's COB-IDs are read-only", SDO_SERVER, subindex,
                      blocks=False)
        value, keyword = value_in_force(od, sub)
        wrong = [n for n in set(node_span(od, options)) if value is not None and at(value, n) != base + n]
        if value is not None and wrong and not value.error:
            diags.add(COM017, Loc(od.source, value_line(sub, value, keyword)),
                      f"COB-ID {value.text.strip()} is not $NODEID+0x{base:X}", SDO_SERVER, subindex)


def error_history_count(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(ERROR_HISTORY)
    sub0 = obj.subs.get(0) if obj is not None and not obj.is_var else None
    if sub0 is not None and sub0.access is not None and not sub0.writable:
        diags.add(COM018, Loc(od.source, sub0.line_of("accesstype")),
                  f"is {sub0.access}; writing 0 to it clears the error history", ERROR_HISTORY, 0)


def time_cob_id(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    obj = od.objects.get(0x1012)
    sub = obj.var if obj is not None else None
    value, keyword = value_in_force(od, sub) if sub is not None else (None, "")
    if sub is None or value is None or value.error or not isinstance(value.parsed, int):
        return
    problem = _time_problem(value.parsed, value.nodeid)
    if problem:
        diags.add(COM019, Loc(od.source, value_line(sub, value, keyword)),
                  f"COB-ID {value.text.strip()} {problem}", 0x1012, 0)


def _time_problem(raw: int, nodeid: bool) -> str | None:
    if nodeid:
        return "depends on $NODEID; TIME is one CAN-ID for the whole network"
    if raw < 0 or raw > 0xFFFFFFFF or not raw & 0xC0000000 or raw & COB_EXTENDED:
        return None  # out of UNSIGNED32 (the value checks say so), not used, or 29-bit
    if raw & 0x1FFFF800:
        return "sets CAN-ID bits above 0x7FF without the 29-bit flag (bit 29)"
    can_id = raw & 0x7FF
    if any(lo <= can_id <= hi for lo, hi in RESTRICTED_CAN_IDS):
        return f"gives the restricted CAN-ID 0x{can_id:03X}"
    return None


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (cob_id_collisions, default_sdo_server, error_history_count, time_cob_id)
