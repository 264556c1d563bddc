"""What a rule is: id, severity, text, how many findings a file lists, and whether it blocks generation."""

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
    blocks: bool = False  # the dictionary would be wrong or ambiguous: `generate` refuses the file
    cap: int = CAP  # findings listed per file; the reporters write one "N more" line for the rest

    def __post_init__(self) -> None:
        if self.blocks and self.severity != Severity.ERROR:
            raise ValueError(f"{self.id}: only an error can block generation")

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
) -> Rule:
    return Rule(rule_id, severity, title, why.strip(), example.strip(), fix.strip(), ref, blocks, cap)
