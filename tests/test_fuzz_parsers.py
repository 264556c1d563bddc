"""The parser fuzzing property, replayed: saved findings and a small seeded batch of mutants.

Every input must yield diagnostics or a model, never an exception (fuzz/mutate.py
`check`). tests/fuzz/regressions/ keeps each input the fuzz run (`make fuzz`) or
a bug report found; the batch draws a few hundred fresh mutants of the repository's
own description files with a fixed seed.
"""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from fuzz import mutate

REGRESSIONS = sorted(p for p in mutate.REGRESSIONS.rglob("*") if p.is_file() and p.suffix.lower() in mutate.FORMATS)
BATCH, SEED = 500, 20261121


def _fmt(path: Path) -> str:
    return mutate.FORMATS[path.suffix.lower()]


@pytest.mark.parametrize("path", REGRESSIONS, ids=[p.name for p in REGRESSIONS])
def test_regression_input_keeps_the_property(path: Path) -> None:
    outcome = mutate.check(path.read_bytes(), _fmt(path))
    assert outcome.failure is None, outcome.detail


def test_regression_corpus_is_not_empty() -> None:
    assert REGRESSIONS, "tests/fuzz/regressions/ holds the inputs earlier findings were fixed with"


def test_seeded_mutants_keep_the_property() -> None:
    seeds = mutate.load_seeds(with_corpus=False)
    rng = random.Random(SEED)
    failures = {}
    models = 0
    for mutant in mutate.mutants(seeds, rng, BATCH):
        outcome = mutate.check(mutant.data, mutant.fmt)
        models += outcome.model
        if outcome.failure:
            failures.setdefault(outcome.failure, (mutant.ops, outcome.detail))
    assert not failures, failures
    assert 0 < models < BATCH, "the batch has both readable and unreadable inputs"


def test_mutations_change_the_input() -> None:
    seed = mutate.split("t.eds", "eds", "[1000]\nParameterName=Device type\nDataType=0x0007\nDefaultValue=0x191\n")
    rng = random.Random(1)
    original = mutate._join(seed.frame, seed.groups)
    for name, op in mutate.TEXT_OPS.items():
        changed = {op(original, rng) for _ in range(20)}
        assert changed - {original}, f"{name} never changed the input"


def test_encodings_round_the_text() -> None:
    rng = random.Random(3)
    seen = set()
    for _ in range(200):
        data, label = mutate.encode("[1000]\nParameterName=\u00e9\n", "eds", rng)
        seen.add(label.split()[0])
        assert data
    assert {"enc:utf-16", "enc:latin-1", "enc:utf-8-sig"} <= seen


def test_report_renders_tables_and_what_did_not_run(tmp_path: Path) -> None:
    from fuzz import report

    (tmp_path / "parsers.json").write_text(json.dumps({
        "title": "T", "summary": "12 inputs", "columns": ["a", "b|c"], "rows": [[1, "x|y"]], "notes": ["n1"]}))
    (tmp_path / "extra.json").write_text(json.dumps({"title": "E", "columns": ["k"], "rows": [[2]], "notes": []}))
    text = report.build("{{summary}}\n\n{{table parsers.json}}\n\n{{table runtime.json}}\n\n{{others}}\n", tmp_path)
    assert "- T: 12 inputs" in text and "- runtime.json: not run." in text
    assert "| a | b\\|c |\n| --- | --- |\n| 1 | x\\|y |\n\n- n1" in text
    assert "Not run: fuzz/results/runtime.json is missing." in text
    assert "## Other results" in text and "| 2 |" in text
