"""The model-based persistence test in `make test`: 300 random firmware sequences through the C
runtime (tests/persist_model.py; `make fuzz` runs 20,000), and the layout sets of every failure
found so far (tests/fixtures/persist_model/regressions.txt), each checked against the rule set of
docs/persistence.md."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from .persist_model import load_script, run_set, set_seed_of

REGRESSIONS = Path(__file__).resolve().parent / "fixtures" / "persist_model" / "regressions.txt"
SETS = 6  # layout sets (one build each) of 50 sequences: 300 sequences (as make fuzz makes them:
# some pin regions, some cut the power in a new version's first boot)
SEQUENCES = 50

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")


def regressions() -> list[tuple[int, int, bool]]:
    """(set seed, sequences, whether of load_script: a third word "loads") of each kept failure;
    `#` starts a comment."""
    out = []
    for line in REGRESSIONS.read_text(encoding="utf-8").splitlines():
        words = line.split("#", 1)[0].split()
        if words:
            out.append((int(words[0]), int(words[1]), words[2:] == ["loads"]))
    return out


@pytest.mark.parametrize("set_seed", [set_seed_of(77, k) for k in range(SETS)])
def test_random_sequences_keep_the_rule_set(set_seed: int) -> None:
    violations, steps = run_set(set_seed, SEQUENCES)
    assert steps > SEQUENCES * 4
    assert not violations, "\n".join(map(str, violations[:20]))


@pytest.mark.parametrize("set_seed", [1_000_003 * 78 + k for k in range(2)])
def test_sequences_around_loads_keep_the_rule_set(set_seed: int) -> None:
    """Loads, then boots of the same version or the other one (a rollback, an upgrade), power
    cuts during the load and during the boot after it, drivers that show each version its own
    NV (load_script)."""
    violations, steps = run_set(set_seed, SEQUENCES, steps_of=load_script)
    assert steps > SEQUENCES * 5
    assert not violations, "\n".join(map(str, violations[:20]))


@pytest.mark.parametrize(("set_seed", "sequences", "loads"), regressions())
def test_regression_seeds(set_seed: int, sequences: int, loads: bool) -> None:
    violations, _ = run_set(set_seed, sequences, steps_of=load_script if loads else None)
    assert not violations, "\n".join(map(str, violations[:20]))
