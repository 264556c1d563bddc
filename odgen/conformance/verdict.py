"""A check's verdict, and what the checks of `odgen conformance` and `odgen roundtrip` expect alike."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..model.cia301 import ABORT_CODES, EMCY_COB_ID, EMCY_INHIBIT, ERROR_HISTORY, PDO_COUNT, PRODUCER_HEARTBEAT, \
    RESTORE, SDO_SERVER, STORE, SYNC_COB_ID, SYNC_PERIOD, SYNC_WINDOW, TIME_COB_ID, TPDO_MAPPING

ABORTS = {"ODG_OK": 0, **ABORT_CODES}
WRITE_ONLY, NO_OBJECT, NO_SUB = (ABORT_CODES["ODG_ABORT_WRITE_ONLY"], ABORT_CODES["ODG_ABORT_NO_OBJECT"],
                                 ABORT_CODES["ODG_ABORT_NO_SUB"])
# Objects whose writes change how the node talks (SDO/PDO/SYNC/EMCY/heartbeat) or act as
# commands: checked by their own steps, not by the generic downloads.
ACTIVE = frozenset({ERROR_HISTORY, SYNC_COB_ID, SYNC_PERIOD, SYNC_WINDOW, STORE, RESTORE, TIME_COB_ID, EMCY_COB_ID,
                    EMCY_INHIBIT, PRODUCER_HEARTBEAT}) | frozenset(range(SDO_SERVER, TPDO_MAPPING + PDO_COUNT))

@dataclass
class Check:
    name: str
    passed: int = 0
    failures: list[str] = field(default_factory=list)
    skipped: str = ""
    notes: list[str] = field(default_factory=list)  # what the node did that CiA 301 allows, and why

    def expect(self, ok: bool, what: str) -> None:
        if ok:
            self.passed += 1
        else:
            self.failures.append(what)

    def as_dict(self) -> dict[str, object]:
        return {"name": self.name, "passed": self.passed, "failed": len(self.failures),
                "failures": self.failures[:50], "skipped": self.skipped, "notes": self.notes}
