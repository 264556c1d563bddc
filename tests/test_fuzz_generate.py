"""The generator's property under mutated input: a description `generate` accepts gives C that
compiles warning-free and whose self-test passes (`odgen check`); one it does not accept is
refused with located findings, never an exception.

tests/fuzz/regressions/generate/ keeps the inputs that broke it (the self-test's memcmp warning);
the seeded batch draws mutants of the repository's own description files (fuzz/mutate.py).
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from fuzz import mutate
from odgen.check import run_check
from odgen.pipeline import Request, generate

REGRESSIONS = sorted((mutate.REGRESSIONS / "generate").glob("*.*"))
SEED, MUTANTS, CHECKED = 20261125, 3000, 30  # 30 distinct accepted dictionaries: about 10 s of gcc


def _property(path: Path) -> str | None:
    """What is wrong with generating `path`, or None."""
    result = generate(Request(path, name="od"))
    if not result.files:
        return None if result.refused else "refused without a blocking finding"
    outcome = run_check(Request(path, name="od"))
    return None if outcome.ok else outcome.output[-1500:]


@pytest.mark.parametrize("path", REGRESSIONS, ids=[p.name for p in REGRESSIONS])
def test_regression_input_generates_c_that_passes_its_self_test(path: Path) -> None:
    assert _property(path) is None


def test_regression_inputs_are_kept() -> None:
    assert REGRESSIONS, "tests/fuzz/regressions/generate/ holds the inputs earlier findings were fixed with"


def test_seeded_mutants_generate_c_that_passes_its_self_test(tmp_path: Path) -> None:
    rng = random.Random(SEED)
    seen: set[str] = set()
    failures: dict[str, str] = {}
    for i, mutant in enumerate(mutate.mutants(mutate.load_seeds(with_corpus=False), rng, MUTANTS)):
        path = tmp_path / f"m{i}.{mutant.fmt}"
        path.write_bytes(mutant.data)
        result = generate(Request(path, name="od"))
        if not result.files:
            assert result.refused, f"{mutant.ops}: refused without a blocking finding"
            continue
        if result.files["od.c"] in seen:
            continue
        seen.add(result.files["od.c"])
        problem = _property(path)
        if problem is not None:
            failures.setdefault(" ".join(mutant.ops), problem)
        if len(seen) == CHECKED:
            break
    assert len(seen) == CHECKED, f"only {len(seen)} distinct dictionaries from {MUTANTS} mutants"
    assert not failures, failures
