"""Linting: rule families, each a module of small passes over the model.

A family module holds the lint passes (functions registered with `@lint_pass`,
each reporting one or more of the rules its family defines in the catalogue,
odgen.catalogue); readers report most SYN and all XML rules themselves, the
generator the GEN rules. The OBJ family's questions are asked object by object
(`@object_check` in objects.py) in one lint pass that walks the dictionary once.
"check" is kept for checking built code against the description (`odgen check`,
the round-trip checks).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

from ...diagnostics import Diagnostics
from ...model import ObjectDictionary


@dataclass(frozen=True)
class LintOptions:
    node_id: int | None = None  # check $NODEID values for this node-id only
    can_fd: bool = False  # PDO payload up to 512 bits instead of 64


LintPass = Callable[[ObjectDictionary, Diagnostics, LintOptions], None]
LINT_PASSES: list[LintPass] = []


def lint_pass(fn: LintPass) -> LintPass:
    LINT_PASSES.append(fn)
    return fn


# Value notes first, then the semantic passes in pipeline order. The network family (NET) has no
# per-file passes: odgen.lint.network imports it for `odgen lint --network`.
FAMILIES = ("syntax", "header", "lists", "objects", "pdo", "comm", "cobids")
for _family in FAMILIES:
    importlib.import_module(f"{__name__}.{_family}")


def run_rules(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for fn in LINT_PASSES:
        fn(od, diags, options)
