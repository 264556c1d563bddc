"""Located, coded diagnostics and the rule catalogue they refer to.

Every finding odgen reports, whether from a reader (syntax) or from a rule pass
(semantics), names a rule defined here through `define_rule`, so the catalogue,
the SARIF rule metadata and docs/rules.md come from one place.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable
from dataclasses import dataclass, field, replace


class Severity(enum.IntEnum):
    INFO = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()


@dataclass(frozen=True)
class Loc:
    """A place in an input file; line 0 means "the file as a whole"."""

    file: str
    line: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}" if self.line else self.file


@dataclass(frozen=True)
class Rule:
    id: str
    severity: Severity
    title: str
    why: str
    example: str
    fix: str
    ref: str = ""  # row(s) of the CiA 306 rule table or clause this implements


RULES: dict[str, Rule] = {}
MAX_PER_RULE = 500  # findings of one rule listed per file; the rest are counted in one line
MAX_MESSAGE = 400  # characters of a message


def define_rule(
    rule_id: str,
    severity: Severity,
    title: str,
    *,
    why: str,
    example: str,
    fix: str,
    ref: str = "",
) -> Rule:
    """Register a rule in the catalogue; ids are stable and unique."""
    if rule_id in RULES:
        raise ValueError(f"rule {rule_id} defined twice")
    rule = Rule(rule_id, severity, title, why.strip(), example.strip(), fix.strip(), ref)
    RULES[rule_id] = rule
    return rule


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

    def text(self) -> str:
        subject = where(self.index, self.sub)
        body = f"{subject} {self.message}" if subject else self.message
        return f"{self.loc}: {self.severity.label}[{self.rule}]: {body}"


@dataclass
class Diagnostics:
    """Collects diagnostics; readers and rules append, reporters read."""

    items: list[Diagnostic] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)  # findings per rule, listed or not
    summaries: dict[str, int] = field(default_factory=dict)  # rule -> position of its "N more" line

    def add(
        self,
        rule_id: str,
        loc: Loc,
        message: str,
        index: int | None = None,
        sub: int | None = None,
    ) -> None:
        rule = RULES[rule_id]
        count = self.counts[rule_id] = self.counts.get(rule_id, 0) + 1
        if count <= MAX_PER_RULE:
            if len(message) > MAX_MESSAGE:  # a message quoting a hostile 5000-digit value
                message = message[: MAX_MESSAGE - 3] + "..."
            self.items.append(Diagnostic(rule_id, rule.severity, message, loc, index, sub))
            return
        # A hostile file can repeat one mistake millions of times: list the first ones, count the rest
        # in one line whose message _settle writes when the diagnostics are read.
        if rule_id not in self.summaries:
            self.summaries[rule_id] = len(self.items)
            self.items.append(Diagnostic(rule_id, rule.severity, "", loc, index, sub))

    def _settle(self) -> None:
        for rule_id, at in self.summaries.items():
            more = self.counts[rule_id] - MAX_PER_RULE
            message = f"{more} more {rule_id} findings not listed (at most {MAX_PER_RULE} per rule and file)"
            if self.items[at].message != message:
                self.items[at] = replace(self.items[at], message=message)

    def collapse(self, rule_id: str) -> None:
        """Keep the first finding of a rule that repeats line after line, with a count of the rest."""
        self._settle()
        hits = [d for d in self.items if d.rule == rule_id]
        if len(hits) < 2:
            return
        first = hits[0]
        more = self.counts.get(rule_id, len(hits)) - 1
        others = {rule: self.items[at] for rule, at in self.summaries.items() if rule != rule_id}
        summary = replace(first, message=f"{first.message} (and {more} more lines like it)")
        self.items = [summary if d is first else d for d in self.items if d.rule != rule_id or d is first]
        self.summaries = {d.rule: at for at, d in enumerate(self.items) if others.get(d.rule) is d}

    def extend(self, other: Iterable[Diagnostic]) -> None:
        self.items.extend(other)

    def sorted(self) -> list[Diagnostic]:
        self._settle()
        return sorted(
            self.items,
            key=lambda d: (d.loc.file, d.loc.line, d.rule, d.index or 0, d.sub or 0, d.message),
        )

    def count(self, severity: Severity) -> int:
        return sum(1 for d in self.items if d.severity == severity)

    def __iter__(self):
        self._settle()
        return iter(self.items)

    def __len__(self) -> int:
        return len(self.items)
