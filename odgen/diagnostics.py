"""Located, coded diagnostics: what readers, rules and the generator found.

Every finding names a rule of the catalogue (odgen.catalogue). `Diagnostics.add`
lists at most the rule's cap of findings per file and counts the rest;
the reporters write one "N more" line per capped rule from `omitted`.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from .catalogue import RULES, Rule, Severity

MAX_MESSAGE = 400  # characters of a message

__all__ = ["RULES", "Diagnostic", "Diagnostics", "Loc", "Rule", "Severity", "more_line", "where"]


@dataclass(frozen=True)
class Loc:
    """A place in an input file; line 0 means "the file as a whole"."""

    file: str
    line: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file


def where(index: int | None, sub: int | None = None) -> str:
    """The conventional spelling of an object address: 0x1A00sub3."""
    if index is None:
        return ""
    return f"0x{index:04X}" if sub is None else f"0x{index:04X}sub{sub}"


@dataclass(frozen=True)
class Diagnostic:
    rule: str
    severity: Severity
    message: str
    loc: Loc
    index: int | None = None
    sub: int | None = None
    blocking: bool = True  # False: this finding does not block although its rule can (the rule's `blocking` says when)

    def text(self) -> str:
        subject = where(self.index, self.sub)
        body = f"{subject} {self.message}" if subject else self.message
        return f"{self.loc}: {self.severity.label}[{self.rule}]: {body}"

    @property
    def blocks(self) -> bool:
        """Whether this finding makes `generate` refuse the file."""
        return self.blocking and RULES[self.rule].blocks


def more_line(source: str, rule_id: str, more: int) -> str:
    """The reporters' line for findings of a rule past its cap."""
    rule = RULES[rule_id]
    return (f"{source}: {rule.severity.label}[{rule.id}]: {more} more {rule.id} findings not listed "
            f"(at most {rule.cap} per rule and file)")


@dataclass
class Diagnostics:
    """Collects diagnostics; readers and rules append, reporters read."""

    items: list[Diagnostic] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)  # findings per rule, listed or not

    def add(
        self,
        rule: Rule,
        loc: Loc,
        message: str,
        index: int | None = None,
        sub: int | None = None,
        blocks: bool = True,
        severity: Severity | None = None,
    ) -> None:
        """`blocks=False`: this finding does not block generation although its rule can; `severity`:
        this finding is milder than its rule (the rule's `blocking` text says when)."""
        # A hostile file can repeat one mistake millions of times: list up to the cap, count the rest.
        count = self.counts[rule.id] = self.counts.get(rule.id, 0) + 1
        if count > rule.cap:
            return
        if len(message) > MAX_MESSAGE:  # a message quoting a hostile 5000-digit value
            message = message[: MAX_MESSAGE - 3] + "..."
        self.items.append(Diagnostic(rule.id, severity if severity is not None else rule.severity, message, loc,
                                     index, sub, blocks))

    def omitted(self) -> dict[str, int]:
        """Rule id -> findings counted but not listed (past the rule's cap)."""
        return {rule_id: n - RULES[rule_id].cap for rule_id, n in sorted(self.counts.items())
                if n > RULES[rule_id].cap}

    def sorted(self) -> list[Diagnostic]:
        return sorted(
            self.items,
            key=lambda d: (d.loc.file, d.loc.line, d.rule, d.index or 0, d.sub or 0, d.message),
        )

    def count(self, severity: Severity) -> int:
        return sum(1 for d in self.items if d.severity == severity)

    def __iter__(self) -> Iterator[Diagnostic]:
        return iter(self.items)

    def __len__(self) -> int:
        return len(self.items)
