"""The model-based persistence test at its `make fuzz` budget: random firmware sequences through
the C runtime, checked against the rule set of docs/persistence.md (tests/persist_model.py).

    python fuzz/persist_sequences.py --sequences 20000 [--seed N] [--keep] [--loads]

Sequences run in layout sets of 100 (one build of four firmware versions each). Every violation
is printed with its set seed; `--keep` appends the failing set seeds to
tests/fixtures/persist_model/regressions.txt, which `make test` replays. Exit 1 on a violation.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.persist_model import load_script, run_set, set_seed_of  # noqa: E402

REGRESSIONS = Path(__file__).resolve().parents[1] / "tests" / "fixtures" / "persist_model" / "regressions.txt"
PER_SET = 100


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sequences", type=int, default=20_000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--keep", action="store_true", help="append failing set seeds to the regressions")
    parser.add_argument("--loads", action="store_true", help="sequences around loads (load_script)")
    args = parser.parse_args(argv)
    started, failing, steps, done = time.monotonic(), [], 0, 0
    for k in range((args.sequences + PER_SET - 1) // PER_SET):
        set_seed = set_seed_of(args.seed, k)
        count = min(PER_SET, args.sequences - done)
        violations, n = run_set(set_seed, count, steps_of=load_script if args.loads else None)
        done, steps = done + count, steps + n
        for v in violations[:5]:
            print(v, flush=True)
        if violations:
            failing.append((set_seed, count))
    print(f"persist sequences: {done} sequences, {steps} steps, {len(failing)} failing layout set(s), "
          f"{time.monotonic() - started:.0f} s")
    if failing and args.keep:
        with REGRESSIONS.open("a", encoding="utf-8") as out:
            kind = " loads" if args.loads else ""
            out.writelines(f"{s} {n}{kind}  # fuzz/persist_sequences.py --seed {args.seed}{' --loads' * args.loads}\n"
                           for s, n in failing)
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
