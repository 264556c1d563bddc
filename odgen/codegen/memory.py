"""Bytes per storage class and table, as the self-test of `odgen check` prints them.

The self-test prints `sizeof` of each value block and of the tables, compiled for the host;
`memory_rows` gives the same rows from the view-model (members are ordered by alignment, so a
block is its members' bytes rounded up to its widest alignment), for `odgen report`.
tests/test_htmlreport.py compares the two on corpus files.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

from .spread import flash_bytes
from .viewmodel import ALIGN, DictView, StorageStruct, member_bytes

ENTRY_BYTES = 6  # odg_entry_t: uint16 index, uint16 first, uint8 count, uint8 code
SUB_BYTES = 8  # odg_sub_t: uint16 offset, uint16 size, four uint8
HOOK_SLOT_BYTES = 2 * struct.calcsize("P")  # odg_hook_slot_t: function pointer and context pointer


@dataclass(frozen=True)
class MemoryRow:
    kind: str  # values | tables
    label: str
    var: str  # the C expression of its bytes the self-test prints ("" for tables)
    size: int
    place: str  # FLASH | RAM | RAM+FLASH (a RAM block with its const defaults copy)

    @property
    def where(self) -> str:
        """The words the self-test prints in its last column."""
        return "RAM, and as much FLASH for its defaults" if self.place == "RAM+FLASH" else self.place

    @property
    def flash(self) -> int:
        return self.size if "FLASH" in self.place else 0

    @property
    def ram(self) -> int:
        return self.size if "RAM" in self.place else 0


def block_bytes(block: StorageStruct) -> int:
    total = sum(map(member_bytes, block.members))
    align = max((m.align for m in block.members), default=1)
    return -(-total // align) * align


def value_rows(view: DictView) -> list[MemoryRow]:
    rows: list[MemoryRow] = []
    groups = 0  # the groups come in the order of their structs (viewmodel._groups)
    for s in view.structs:
        label = s.name.removeprefix(view.name + "_")
        if not s.group:
            rows.append(MemoryRow("values", label, f"sizeof {s.name}", block_bytes(s),
                                  "FLASH" if s.const else "RAM+FLASH"))
            continue
        # a group's defaults are its spread (spread.py): the runs that are not all zero, and their table
        rows += [MemoryRow("values", label, f"sizeof {s.name}", block_bytes(s), "RAM"),
                 MemoryRow("values", f"{label} defaults", f"spread_bytes(&d->groups[{groups}])",
                           flash_bytes(s.runs, ALIGN), "FLASH")]
        groups += 1
    return rows


def memory_rows(view: DictView) -> list[MemoryRow]:
    return value_rows(view) + [
        MemoryRow("tables", "entries", "", len(view.entries) * ENTRY_BYTES, "FLASH"),
        MemoryRow("tables", "sub-entries", "", len(view.subs) * SUB_BYTES, "FLASH"),
        MemoryRow("tables", "hook slots", "", len(view.hooks) * HOOK_SLOT_BYTES, "RAM"),
    ]
