"""The lint pass: rule families, each a module of small checks over the model.

A family module holds the checks (the `@check` decorator) of the rules its
family defines in the catalogue (odgen.catalogue); readers report most SYN and
all XML rules themselves, the generator the GEN rules.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

from ..diagnostics import Diagnostics
from ..model import ObjectDictionary


@dataclass(frozen=True)
class LintOptions:
    node_id: int | None = None  # check $NODEID values for this node-id only
    can_fd: bool = False  # PDO payload up to 512 bits instead of 64


Check = Callable[[ObjectDictionary, Diagnostics, LintOptions], None]
CHECKS: list[Check] = []


def check(fn: Check) -> Check:
    CHECKS.append(fn)
    return fn


# Value notes first, then the semantic passes in pipeline order.
FAMILIES = ("syntax", "header", "lists", "objects", "pdo", "comm", "cobids", "network")
for _family in FAMILIES:
    importlib.import_module(f"{__name__}.{_family}")


def run_rules(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for fn in CHECKS:
        fn(od, diags, options)
