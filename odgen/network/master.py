"""The master's model: its description as configured (PDO wiring included), plus the CiA 302-2
objects its configuration manager reads (docs/network.md lists them, with their layout).

Arrays indexed by node-id hold a sub-entry per slave only: sub 0 is the highest node-id of a
slave, and the runtime reads a missing sub-entry as 0 (not a slave, nothing to check).
"""

from __future__ import annotations

import copy

from ..lint.netconfig import NodeModel, expected_identity
from ..lint.network import BOOT_STATUS
from ..model import ObjectDictionary
from ..model.datatypes import BASIC_TYPES, UNSIGNED8, UNSIGNED32, DataType
from ..model.edit import with_object
from ..model.od import ARRAY, VAR, Obj, Sub
from ..model.values import Value, parse_value

DOMAIN = BASIC_TYPES[0x000F]  # the concise DCFs

# 0x1F80 NMT start-up (CiA 302-2): bit -> ([master] key, the value of the key that sets the bit)
STARTUP_BITS = ((1, "start_all", True), (2, "start_self", False), (3, "start_slaves", False),
                (4, "reset_all", True), (6, "stop_all", True))
# 0x1F81 NMT slave assignment
ERROR_BEHAVIOUR = 0x1029
SLAVE, BOOT_AGAIN, MANDATORY, KEEP_ALIVE = 1 << 0, 1 << 2, 1 << 3, 1 << 4
IDENTITY_ARRAYS = ((0x1F85, "Vendor identification", 1), (0x1F86, "Product code", 2),
                   (0x1F87, "Revision number", 3), (0x1F88, "Serial number", 4))


def master_model(master: NodeModel, slaves: list[NodeModel], concise: dict[int, bytes],
                 files: dict[int, str]) -> ObjectDictionary:
    """`concise` and `files`: each slave's concise DCF and the name of its .bin, by node-id."""
    od = master.configured_od()
    for obj in _objects(master, slaves, concise):
        if obj.index == 0x1F22:
            for node_id, name in files.items():
                obj.subs[node_id].upload_file = name  # CiA 306: a DOMAIN's content is named by its file
        od = _put(od, obj)
    return od


def _objects(master: NodeModel, slaves: list[NodeModel], concise: dict[int, bytes]) -> list[Obj]:
    ids = [s.node_id for s in slaves]
    startup = 1 | sum(1 << bit for bit, key, sets in STARTUP_BITS
                      if master.spec.options.get(key, not sets) == sets)
    objects = [
        _var(0x1F80, "NMT start-up", startup),
        _var(0x1F89, "Boot time", int(master.spec.options.get("boot_time", 0))),
        _array(0x1F81, "NMT slave assignment", {s.node_id: _assignment(s) for s in slaves}),
        _array(0x1F84, "Device type identification", {s.node_id: s.in_force(0x1000, 0) or 0 for s in slaves}),
        _array(0x1F26, "Expected configuration date", dict.fromkeys(ids, 0)),
        _array(0x1F27, "Expected configuration time", dict.fromkeys(ids, 0)),
        _array(0x1F22, "Concise DCF", {n: concise[n].hex().upper() for n in ids}, DOMAIN, "const"),
        _boot_status(ids),
    ]
    objects += [_array(index, name, {s.node_id: expected_identity(s).get(sub, 0) for s in slaves})
                for index, name, sub in IDENTITY_ARRAYS]
    behaviour = _error_behaviour(master)
    objects += [behaviour] if behaviour is not None else []
    heartbeats = [(s.node_id << 16) | int(s.spec.options.get("heartbeat", 0)) for s in slaves
                  if s.spec.options.get("heartbeat")]
    if heartbeats:
        objects.append(_array(0x1016, "Consumer heartbeat time", dict(enumerate(heartbeats, start=1))))
    return objects


def _boot_status(ids: list[int]) -> Obj:
    """0x5F81, 0 at reset. The runtime writes it (odg_set) and a TPDO may publish it: PDO-mappable,
    so that `odgen network` and `odgen generate` of the master's DCF alike place it in RAM (a
    read-only entry that is not mappable goes to ROM)."""
    obj = _array(BOOT_STATUS, "Slave boot status", dict.fromkeys(ids, 0), UNSIGNED8, "ro")
    for sub in obj.subs.values():
        sub.pdo_mapping = sub.subindex > 0
    return obj


def _error_behaviour(master: NodeModel) -> Obj | None:
    """0x1029 sub 1 = 1 (no state change), unless `[master.values]` sets it: the master's own node
    is heartbeat consumer of the slaves (0x1016), and a communication error would otherwise take it
    to pre-operational and stop its PDOs; a lost slave is its configuration manager's to handle, as
    0x1F80 and 0x1F81 say (docs/network.md)."""
    if (ERROR_BEHAVIOUR, 1) in master.values:
        return None
    old = master.od.objects.get(ERROR_BEHAVIOUR)
    if old is None or 1 not in old.subs:
        obj = Obj(ERROR_BEHAVIOUR, "Error behavior", object_code=ARRAY)
        obj.subs = dict(old.subs) if old is not None else {}
        obj.subs[0] = Sub(0, "Highest sub-index supported", data_type=UNSIGNED8.code, access="ro",
                          default=_value(max([1, *obj.subs]), UNSIGNED8))
        obj.subs[1] = Sub(1, "Communication error", data_type=UNSIGNED8.code, access="rw",
                          default=_value(1, UNSIGNED8))
        return obj
    obj = copy.copy(old)
    obj.subs = dict(old.subs)
    obj.subs[1] = copy.copy(old.subs[1])
    obj.subs[1].default = _value(1, UNSIGNED8)
    obj.subs[1].parameter_value = None  # a DCF's value in force would win over the default
    return obj


def _assignment(slave: NodeModel) -> int:
    options = slave.spec.options
    return SLAVE | BOOT_AGAIN | (MANDATORY if options.get("mandatory") else 0) \
        | (KEEP_ALIVE if options.get("keep_alive") else 0)


def _var(index: int, name: str, value: int) -> Obj:
    obj = Obj(index, name, object_code=VAR)
    obj.subs[0] = Sub(0, name, data_type=UNSIGNED32.code, access="rw", default=_value(value, UNSIGNED32))
    return obj


def _array(index: int, name: str, values: dict[int, int] | dict[int, str], dtype: DataType = UNSIGNED32,
           access: str = "rw") -> Obj:
    """An ARRAY with a sub-entry per key of `values` (sub 0: the highest)."""
    obj = Obj(index, name, object_code=ARRAY)
    obj.subs[0] = Sub(0, "Highest sub-index supported", data_type=UNSIGNED8.code, access="ro",
                      default=_value(max(values, default=0), UNSIGNED8))
    for sub, value in sorted(values.items()):
        text = f"0x{value:X}" if isinstance(value, int) else str(value)
        obj.subs[sub] = Sub(sub, f"{name} {sub}", data_type=dtype.code, access=access,
                            default=parse_value(text, dtype))
    return obj


def _value(n: int, dtype: DataType) -> Value:
    return parse_value(f"0x{n:X}", dtype)


def _put(od: ObjectDictionary, obj: Obj) -> ObjectDictionary:
    """The model with `obj`, in place of the description's object at its index if there is one."""
    old = od.objects.get(obj.index)
    if old is None:
        return with_object(od, obj)
    obj.object_list, obj.sub_number = old.object_list, len(obj.subs)
    od.objects = {**od.objects, obj.index: obj}
    return od
