"""Lint passes: rule families, each a module of small passes over the model.

A family module lists its lint passes in `PASSES`, each pass reporting one or more of the
rules its family defines in the catalogue (odgen.catalogue); readers report most SYN and
all XML rules themselves, the generator the GEN rules. The OBJ family's questions are asked
object by object (`OBJECT_QUESTIONS` in objects.py) in one lint pass that walks the
dictionary once. "check" is kept for checking built code against the description
(`odgen check`, the round-trip checks).
"""

from __future__ import annotations

from ...diagnostics import Diagnostics
from ...model import ObjectDictionary
from . import cobids, comm, header, lists, objects, pdo, syntax
from .base import LintOptions, LintPass

__all__ = ["LINT_PASSES", "LintOptions", "LintPass", "run_rules"]

# Value notes first, then the semantic passes in pipeline order. The network family (NET) has no
# per-file passes: odgen.lint.network uses it for `odgen lint --network`.
LINT_PASSES: tuple[LintPass, ...] = (*syntax.PASSES, *header.PASSES, *lists.PASSES, *objects.PASSES, *pdo.PASSES,
                                     *comm.PASSES, *cobids.PASSES)


def run_rules(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for fn in LINT_PASSES:
        fn(od, diags, options)
