"""The factory defaults of a persistence group as its non-zero runs.

A group's defaults stay in FLASH for the persistence layer (a boot or a "load" puts them back),
and most of a group's values start at zero (PDO mappings, heartbeat consumers, identity), so
the generated C keeps only the runs of the mirror's bytes that are not all zero: a `spread`
table of (start, end) offsets into the mirror (uint16_t pairs, ended by 0, 0) and the runs' bytes
one after the other in a struct of their own (`defaults`). Offsets and lengths are the
compiler's (offsetof), and the values are C initializers, so the bytes are right on any CPU's
byte order and padding; the runtime spreads them with `odg_group_defaults`.

A run is a sequence of whole members of the mirror (the members are ordered by alignment,
widest first, so no padding lies between them), except that a string's or domain's trailing
zeros end it. Zero members between two non-zero ones join the run when they take no more
bytes than a run's (start, end) pair would.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

RUN_BYTES = 4  # a spread row: start and end, uint16_t each


class RunMember(Protocol):
    """What a run needs of a struct member (viewmodel.Member)."""

    @property
    def name(self) -> str: ...
    @property
    def ctype(self) -> str: ...
    @property
    def array(self) -> str: ...  # "" or "[n]"
    @property
    def init(self) -> str: ...
    @property
    def used(self) -> int: ...  # elements up to the last non-zero one
    @property
    def head(self) -> str: ...  # their initializer


@dataclass
class Piece:
    """A member of a run: whole, or the first `used` elements of an array (its last piece)."""

    member: RunMember
    whole: bool

    @property
    def ctype(self) -> str:
        return "uint8_t" if self.member.ctype == "char" and not self.whole else self.member.ctype

    @property
    def array(self) -> str:
        return self.member.array if self.whole else f"[{self.member.used}]"

    @property
    def init(self) -> str:
        return self.member.init if self.whole else self.member.head


@dataclass
class Run:
    pieces: list[Piece] = field(default_factory=list)

    def start(self, type_name: str) -> str:
        return f"offsetof({type_name}, {self.pieces[0].member.name})"

    def end(self, type_name: str) -> str:
        last = self.pieces[-1]
        if last.whole:
            return f"ODG_END({type_name}, {last.member.name})"
        return f"ODG_END({type_name}, {last.member.name}[{last.member.used - 1}])"


def elements(m: RunMember) -> int:
    return int(m.array[1:-1]) if m.array else 1


def member_size(m: RunMember, align: dict[str, int]) -> int:
    """Bytes of a member: its elements, each of its C type's alignment (which is its size)."""
    return align[m.ctype] * elements(m)


def flash_bytes(found: list[Run], align: dict[str, int]) -> int:
    """FLASH the spread takes: the runs' bytes and their table (without the padding a compiler
    may add after the runs' struct)."""
    runs_bytes = sum(member_size(p.member, align) if p.whole else align[p.member.ctype] * p.member.used
                     for r in found for p in r.pieces)
    return runs_bytes + 2 * (2 * len(found) + 2)


def runs(members: Sequence[RunMember], align: dict[str, int]) -> list[Run]:
    """The non-zero runs of a struct whose members are in layout order."""
    out: list[Run] = []
    gap: list[RunMember] = []  # zero members since the last non-zero one
    open_run = False  # whether the last run may go on (it ended with a whole member)
    for m in members:
        if m.used == 0:
            gap.append(m)
            continue
        whole = m.used == elements(m)
        if open_run and sum(member_size(g, align) for g in gap) <= RUN_BYTES:
            out[-1].pieces += [Piece(g, True) for g in gap]
        else:
            out.append(Run())
        out[-1].pieces.append(Piece(m, whole))
        open_run, gap = whole, []
    return out
