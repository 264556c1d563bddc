"""The rule catalogue: the ground floor every reader, rule and reporter refers to."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from odgen import catalogue
from odgen.catalogue import FAMILIES, RULES, Severity, is_selector, lookup
from odgen.diagnostics import Diagnostics, Loc

ROOT = Path(__file__).resolve().parents[1]


def test_every_rule_is_a_constant_named_by_its_id_in_its_family_module() -> None:
    for prefix, (_, module) in FAMILIES.items():
        for rule_id in (r for r in RULES if r.startswith(prefix)):
            assert getattr(module, rule_id) is RULES[rule_id]


def test_only_errors_block_generation() -> None:
    assert all(r.severity == Severity.ERROR for r in RULES.values() if r.blocks)



def test_code_refers_to_rules_as_constants_not_strings() -> None:
    quoted = re.compile(r'"(?:' + "|".join(FAMILIES) + r')\d{3}"')
    found = [f"{p}:{n}" for p in (ROOT / "odgen").rglob("*.py") if "catalogue" not in p.parts
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if quoted.search(line)]
    assert found == []


def test_readers_do_not_import_the_rule_checks() -> None:
    probe = "import sys, odgen.formats; print(sorted(m for m in sys.modules if m.startswith('odgen.lint.passes')))"
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True, cwd=ROOT)
    assert done.stdout.strip() == "[]"


def test_lookup_and_selectors() -> None:
    assert lookup("pdo001") is catalogue.pdo.PDO001
    assert is_selector("PDO") and is_selector("syn01") and not is_selector("PDX") and not is_selector("")


def test_add_counts_past_the_cap_and_lists_up_to_it() -> None:
    diags = Diagnostics()
    rule = catalogue.syntax.SYN014
    for line in range(1, 5):
        diags.add(rule, Loc("f.eds", line), "comment")
    assert [d.loc.line for d in diags] == [1] and diags.omitted() == {"SYN014": 3}
