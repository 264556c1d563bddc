"""What a rule is: id, severity, text, how many findings a file lists, whether it blocks generation and
what `--fix` does about it.

The blocking policy, one rule for every family: a finding blocks `odgen generate` only when the
generated C would not compile, would not match the description, or the node would misbehave on
the bus. Every error says in `blocking` which of these it is, or why it is none of them; a rule
that blocks either has a repair (`repair`, applied by `generate --fix` / `--unsafe-fixes` and
`odgen fix`) or says in `no_repair` why no repair can be right.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass


class Severity(enum.IntEnum):
    INFO = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()


E, W, INFO = Severity.ERROR, Severity.WARNING, Severity.INFO
CAP = 500  # findings of one rule listed per file; the rest are counted in one line


@dataclass(frozen=True)
class Rule:
    id: str
    severity: Severity
    title: str
    why: str
    example: str
    fix: str
    ref: str = ""  # row(s) of the CiA 306 rule table or clause this implements
    blocks: bool = False  # the policy above: `generate` refuses the file (a finding may say it does not)
    cap: int = CAP  # findings listed per file; the reporters write one "N more" line for the rest
    blocking: str = ""  # one line: why the rule blocks generation, or why it does not
    repair: str = ""  # what --fix does: "safe: ..." or "unsafe: ..." (both may be named, "; "-separated)
    no_repair: str = ""  # a blocking rule without a repair: why none can be right

    def __post_init__(self) -> None:
        if self.blocks and self.severity != Severity.ERROR:
            raise ValueError(f"{self.id}: only an error can block generation")
        if self.severity == Severity.ERROR and not self.blocking:
            raise ValueError(f"{self.id}: an error says why it blocks generation or why not")
        if self.blocks and not (self.repair or self.no_repair):
            raise ValueError(f"{self.id}: a blocking rule has a repair or says why none can be right")

    @property
    def blocking_reason(self) -> str:
        """The one-line reason of the catalogue; warnings and information never block."""
        return self.blocking or f"A{'n' if self.severity == Severity.INFO else ''} {self.severity.label} never blocks."

    @property
    def safe_repair(self) -> bool:
        return "safe:" in self.repair.replace("unsafe:", "")

    @property
    def unsafe_repair(self) -> bool:
        return "unsafe:" in self.repair

    def __str__(self) -> str:
        return self.id


def define(
    rule_id: str,
    severity: Severity,
    title: str,
    *,
    why: str,
    example: str,
    fix: str,
    ref: str = "",
    blocks: bool = False,
    cap: int = CAP,
    blocking: str = "",
    repair: str = "",
    no_repair: str = "",
) -> Rule:
    return Rule(rule_id, severity, title, why.strip(), example.strip(), fix.strip(), ref, blocks, cap,
                " ".join(blocking.split()), " ".join(repair.split()), " ".join(no_repair.split()))
