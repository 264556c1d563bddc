"""The conformance client: python canopen on a CAN interface, talking to a live node.

Unlike `odgen roundtrip` it starts nothing: the node is already on the bus, built by anyone.
It listens to the node's boot-up/heartbeat (0x700 + id), EMCY (its 0x1014 COB-ID) and
TPDOs as they come, so a check waits on frames instead of sleeping.
"""

from __future__ import annotations

import logging
import statistics
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from copy import deepcopy

from ..model.expect import expected_bytes
from ..errors import OdgenError
from ..formats.eds_writer import write_eds
from ..model import ARRAY, RECORD, ObjectDictionary
from ..model.cia301 import CAN_ID_MASK, COB_EXTENDED, COB_INVALID, DEVICE_TYPE, EMCY_COB_ID, SDO_REQUEST, \
    SDO_RESPONSE, SDO_SERVER, is_pdo_mapping
from ..model.datatypes import BASIC_TYPES

# Waits end at the awaited frame; the deadlines only bound a failure, so they are generous.
DEADLINE = 10.0
SDO_TIMEOUT = 2.0
# How long silence must last to count as "no answer" (a stopped node's SDO server).
SILENCE = 0.5


@dataclass(frozen=True)
class Settings:
    """What the battery may do to the node and what it knows beyond the description.

    destructive: checks that erase stored parameters (0x1011 "load"), reset the node or its
    communication, or play another node's heartbeat on the bus may run (`--allow destructive`).
    fresh: the node runs with its described values (odgen's own node, freshly built), so writable
    entries are compared with them. stored: the entries the options put in a stored group
    (None: nobody said, so nothing is known to be stored).
    """

    destructive: bool = False
    fresh: bool = False
    stored: frozenset[tuple[int, int]] | None = None


NO_ANSWER = -1  # what upload/download return when the node did not answer in time


class Client:
    def __init__(self, od: ObjectDictionary, iface: str, node_id: int, workdir: Path,
                 settings: Settings | None = None) -> None:
        import can
        import canopen

        logging.getLogger("canopen").setLevel(logging.CRITICAL)
        self.canopen, self.od, self.node_id, self.settings = canopen, od, node_id, settings or Settings()
        eds = workdir / "client.eds"
        eds.write_text(client_eds(od), encoding="utf-8")
        self.network = canopen.Network()
        self.network.NOTIFIER_CYCLE = 0.1
        try:
            self.network.connect(interface="socketcan", channel=iface)
        except (OSError, can.CanError) as err:
            raise OdgenError(f"cannot open CAN interface '{iface}' ({err}): name an existing SocketCAN "
                             "interface with --iface") from None
        try:
            self.node = canopen.RemoteNode(node_id, str(eds))
        except Exception as err:  # canopen's own reader: not odgen's fault, one sentence
            self.network.disconnect()
            raise OdgenError(f"python canopen cannot load the description: {type(err).__name__}: {err}") from None
        # where 0x1200 says (run() refused a disabled server)
        self.sdo_rx, self.sdo_tx = sdo_server_cob_ids(od, node_id) or (SDO_REQUEST + node_id, SDO_RESPONSE + node_id)
        self.node.sdo.rx_cobid, self.node.sdo.tx_cobid = self.sdo_rx, self.sdo_tx
        self.network.add_node(self.node)
        self.node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT
        self.frames: list[tuple[float, int, bytes]] = []  # (time, COB-ID, data) of watched frames
        self.stamps: list[tuple[float, int, float]] = []  # (time, COB-ID, the kernel's receive time)
        self.lock = threading.Condition()
        self.watched: set[int] = set()
        for other in range(1, 128):  # the node's heartbeat, and who else is on the bus
            self.watch(0x700 + other)

    def close(self) -> None:
        self.network.disconnect()

    # -- frames ----------------------------------------------------------------------------

    def watch(self, cob: int) -> None:
        if cob not in self.watched:
            self.network.subscribe(cob, self._seen)
            self.watched.add(cob)

    def _seen(self, cob: int, data: bytearray, timestamp: float) -> None:
        with self.lock:
            now = time.monotonic()
            self.frames.append((now, cob, bytes(data)))
            self.stamps.append((now, cob, timestamp))
            self.lock.notify_all()

    def wait_frame(self, since: float, match: Callable[[int, bytes], bool], deadline: float = DEADLINE
                   ) -> bytes | None:
        """The first watched frame after `since` that `match` accepts, or None by the deadline."""
        end = time.monotonic() + deadline
        with self.lock:
            while True:
                for t, cob, data in self.frames:
                    if t >= since and match(cob, data):
                        return data
                left = end - time.monotonic()
                if left <= 0:
                    return None
                self.lock.wait(left)

    def frames_since(self, since: float, cob: int) -> list[tuple[float, bytes]]:
        with self.lock:
            return [(t, d) for t, c, d in self.frames if t >= since and c == cob]

    def received_since(self, since: float, cob: int) -> list[float]:
        """When the kernel received each frame of `cob` since `since` (for periods: no Python delays)."""
        with self.lock:
            return [stamp for t, c, stamp in self.stamps if t >= since and c == cob]

    def period(self, cob: int, window: float, good: Callable[[float], bool]) -> list[float | None]:
        """Median gap (ms) between frames of `cob`, by the kernel's receive times, over `window`
        seconds; a machine stalled for a while stretches one window, so up to three are measured
        until one is `good`. Returns the medians measured (None: fewer than two frames)."""
        medians: list[float | None] = []
        while len(medians) < 3 and not (medians and medians[-1] is not None and good(medians[-1])):
            start = time.monotonic()
            time.sleep(window)  # a measuring window, not a wait for an event
            stamps = self.received_since(start, cob)
            gaps = [1000 * (b - a) for a, b in zip(stamps, stamps[1:], strict=False)]
            medians.append(statistics.median(gaps) if gaps else None)
        return medians

    def send(self, cob: int, data: bytes, remote: bool = False) -> None:
        self.network.send_message(cob, data, remote=remote)

    def nmt(self, command: str) -> float:
        """Send an NMT command to the node; returns the time it was sent."""
        now = time.monotonic()
        self.node.nmt.state = command
        return now

    def heartbeat_state(self, since: float, state: int, deadline: float = DEADLINE) -> bool:
        return self.wait_frame(since, lambda c, d: c == 0x700 + self.node_id and d[:1] == bytes([state]),
                               deadline) is not None

    # -- SDO -------------------------------------------------------------------------------

    def upload(self, index: int, sub: int) -> tuple[bytes | None, int]:
        """(data, 0) or (None, abort code); NO_ANSWER when the node did not answer."""
        try:
            return bytes(self.node.sdo.upload(index, sub)), 0
        except self.canopen.SdoAbortedError as err:
            return None, err.code
        except self.canopen.SdoCommunicationError:
            return None, NO_ANSWER

    def download(self, index: int, sub: int, data: bytes) -> int:
        """0, the abort code, or NO_ANSWER."""
        try:
            self.node.sdo.download(index, sub, data)
            return 0
        except self.canopen.SdoAbortedError as err:
            return err.code
        except self.canopen.SdoCommunicationError:
            return NO_ANSWER

    def number(self, index: int, sub: int = 0) -> int | None:
        """An entry uploaded as an unsigned number, or None when it cannot be read."""
        data = self.upload(index, sub)[0]
        return int.from_bytes(data, "little") if data else None

    def emcy_cob(self) -> int | None:
        """The EMCY COB-ID entry (0x1014, bit 31: disabled), the default one without 0x1014."""
        return self.number(EMCY_COB_ID) if self.od.find(EMCY_COB_ID) is not None else 0x80 + self.node_id

    def answers(self, patience: bool = False) -> bool:
        """Whether the SDO server answers at all, within SILENCE (for states where it must not),
        or with `patience` within the usual SDO timeout (is the node still there?)."""
        self.node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT if patience else SILENCE
        try:
            return self.upload(DEVICE_TYPE, 0)[1] != NO_ANSWER
        finally:
            self.node.sdo.RESPONSE_TIMEOUT = SDO_TIMEOUT


# ---- the node's SDO server and the description as python canopen reads it --------------------


def sdo_server_cob_ids(od: ObjectDictionary, node_id: int) -> tuple[int, int] | None:
    """The COB-IDs (request, response) the default SDO server of a node built from `od` uses:
    0x1200 sub 1 and 2 as described ($NODEID applied), the pre-defined 0x600/0x580 + node-id
    without them; None when bit 31 (or 29) of either disables the server (runtime/NODE.md)."""
    ids = []
    for subindex, base in ((1, SDO_REQUEST), (2, SDO_RESPONSE)):
        sub = od.find(SDO_SERVER, subindex)
        dtype = BASIC_TYPES.get(sub.data_type or 0) if sub is not None else None
        data = expected_bytes(od, sub, dtype, node_id) if sub is not None and dtype is not None else None
        ids.append(int.from_bytes(data, "little") if data else base + node_id)
    if (ids[0] | ids[1]) & (COB_INVALID | COB_EXTENDED):
        return None
    return ids[0] & CAN_ID_MASK, ids[1] & CAN_ID_MASK


def reachable_sdo_server(od: ObjectDictionary, node_id: int, path: object) -> tuple[int, int]:
    """sdo_server_cob_ids, or an OdgenError saying the description leaves nothing to talk to."""
    cobs = sdo_server_cob_ids(od, node_id)
    if cobs is None:
        raise OdgenError(f"{path}: 0x1200 disables the default SDO server (COB-ID bit 31), so a node built "
                         "from it answers no SDO request: describe 0x1200 sub 1/2 as $NODEID+0x600/$NODEID+0x580")
    return cobs


def client_eds(od: ObjectDictionary) -> str:
    """The description as EDS for python canopen, which stops on header numbers it cannot read
    (`VendorNumber=` empty, `001`) or sections it reads strictly (a sparse [DummyUsage], [Comments]
    whose `Lines` counts a `line5` it looks up as `Line5`): those are left out, they play no part in
    the checks."""
    lines, section = [], ""
    for line in write_eds(_expanded(od)).splitlines():
        if line.startswith("["):
            section = line.lower()
        key, _, value = line.partition("=")
        if section == "[deviceinfo]" and key in _CANOPEN_INT_KEYS and not _python_int(value):
            continue
        if section in ("[dummyusage]", "[comments]"):  # canopen needs all seven keys / every LineN
            continue
        lines.append(line)
    return "\n".join(lines) + "\n"


def _expanded(od: ObjectDictionary) -> ObjectDictionary:
    """A copy with CompactSubObj written out as sub-sections: canopen expands only compact ARRAYs.
    PDO mapping objects written as ARRAYs become the RECORDs CiA 301 defines: canopen sizes an ARRAY by
    the sub0 it reads from the device, so a remap (sub0 = 0, entries, sub0 = n) would write no entry."""
    copy = deepcopy(od)
    for obj in copy.objects.values():
        if is_pdo_mapping(obj.index) and obj.object_code == ARRAY:
            obj.object_code = RECORD
        if obj.compact_sub_obj:
            obj.compact_sub_obj, obj.sub_number = None, len(obj.subs)
            for sub in obj.subs.values():
                sub.compact = False
    return copy


_CANOPEN_INT_KEYS = {"VendorNumber", "ProductNumber", "RevisionNumber", "NrOfRXPDO", "NrOfTXPDO", "Granularity",
                     "BaudRate_10", "BaudRate_20", "BaudRate_50", "BaudRate_125", "BaudRate_250", "BaudRate_500",
                     "BaudRate_800", "BaudRate_1000", "SimpleBootUpMaster", "SimpleBootUpSlave",
                     "DynamicChannelsSupported", "GroupMessaging", "LSS_Supported"}


def _python_int(text: str) -> bool:
    try:
        int(text.strip(), 0)
        return True
    except ValueError:
        return False
