"""The kinds of change `odgen diff` reports, each in one of three classes, and the Change record."""

from __future__ import annotations

from dataclasses import dataclass

from ..diagnostics import where

BREAKING, STORED, COMPATIBLE = "breaking", "stored", "compatible"
CLASSES = (BREAKING, STORED, COMPATIBLE)  # most severe first
CLASS_TITLES = {BREAKING: "(a) breaks a master's configuration", STORED: "(b) affects stored parameters",
                COMPATIBLE: "(c) compatible"}


@dataclass(frozen=True)
class Kind:
    id: str
    cls: str  # the class of its changes; DIF4xx take the class of the changes they are about
    title: str
    why: str


KINDS: dict[str, Kind] = {k.id: k for k in (
    Kind("DIF101", BREAKING, "object removed", "A master that reads, writes or maps it gets an SDO abort."),
    Kind("DIF102", BREAKING, "sub-entry removed", "A master that reads, writes or maps it gets an SDO abort."),
    Kind("DIF103", BREAKING, "data type changed", "A master's configuration writes values of the old length and type."),
    Kind("DIF104", BREAKING, "object code changed", "VAR, ARRAY and RECORD are addressed differently."),
    Kind("DIF105", BREAKING, "access narrowed", "A master that wrote (or read) the entry gets an SDO abort."),
    Kind("DIF106", BREAKING, "no longer PDO-mappable", "A master's PDO mapping of the entry is refused."),
    Kind("DIF107", BREAKING, "communication default changed",
         "PDO mappings, COB-IDs and transmission types a master relies on changed without being written."),
    Kind("DIF108", BREAKING, "limits narrowed", "Values a master's configuration writes may now be refused."),
    Kind("DIF109", BREAKING, "string capacity shrank",
         "The capacity follows the default's length: a master's write of the old length is refused."),
    Kind("DIF201", STORED, "stored value converted", "Boot migration widens the stored integer."),
    Kind("DIF202", STORED, "stored capacity changed", "Boot migration keeps what fits of the stored string or domain."),
    Kind("DIF203", STORED, "stored value dropped", "Boot migration forgets the stored value."),
    Kind("DIF204", STORED, "stored value defaulted", "Boot migration serves the default instead of the stored value."),
    Kind("DIF205", STORED, "stored value checked against narrower limits",
         "A stored value outside the new limits is replaced by the default at boot."),
    Kind("DIF206", STORED, "default of a stored parameter changed",
         "Devices that stored the parameter keep their value (unless narrower limits refuse it); "
         "only the others see the new default."),
    Kind("DIF207", STORED, "persistence group moves in NV",
         "The runtime looks for the group's image at its new place and does not find it: DEFAULTS "
         "on erased NV, else DAMAGED and the storage EMCY."),
    Kind("DIF301", COMPATIBLE, "object added", "Nothing a master configured before refers to it."),
    Kind("DIF302", COMPATIBLE, "sub-entry added", "Nothing a master configured before refers to it."),
    Kind("DIF303", COMPATIBLE, "name changed", "Names are documentation; masters address by index and sub-index."),
    Kind("DIF304", COMPATIBLE, "access widened or respelled", "Every access a master made before still works."),
    Kind("DIF305", COMPATIBLE, "now PDO-mappable", "Every mapping a master made before still works."),
    Kind("DIF306", COMPATIBLE, "limits widened", "Every value a master wrote before is still accepted."),
    Kind("DIF307", COMPATIBLE, "default changed", "The device starts differently; a master's writes still work."),
    Kind("DIF308", COMPATIBLE, "attribute changed",
         "ObjFlags, Denotation or ParameterValue, which do not change access."),
    Kind("DIF401", BREAKING, "identity revision not raised",
         "CiA 301: the major revision (0x1018sub3, upper 16 bits) changes with the CANopen behaviour, "
         "the revision number with any change a device user must know of."),
    Kind("DIF402", BREAKING, "file version not raised",
         "Tools and users tell descriptions apart by FileVersion/FileRevision (fileVersion in XDD)."),
)}


@dataclass(frozen=True)
class Change:
    """One change, located in NEW (`line` 0: the file as a whole; `old_line` where OLD had it)."""

    kind: str
    message: str
    index: int | None = None
    sub: int | None = None
    line: int = 0
    old_line: int = 0
    cls: str = ""  # defaults to the kind's class

    @property
    def change_class(self) -> str:
        return self.cls or KINDS[self.kind].cls

    @property
    def subject(self) -> str:
        return where(self.index, self.sub)

    def text(self, new: str, old: str) -> str:
        place = f"{new}:{self.line}" if self.line else new
        body = f"{self.subject} {self.message}" if self.subject else self.message
        was = f" (was {old}:{self.old_line})" if self.old_line and not self.line else ""
        return f"{place}: {self.change_class}[{self.kind}]: {body}{was}"


def worst(changes: list[Change], among: tuple[str, ...] = CLASSES) -> str | None:
    """The most severe class of the changes, considering only `among`."""
    present = {c.change_class for c in changes}
    return next((cls for cls in CLASSES if cls in present and cls in among), None)
