"""Coverage-guided fuzzing of the readers, the linter and the EDS writer with atheris (libFuzzer).

    python fuzz/guided.py CORPUS_DIR -runs=N -seed=S ...   (run by fuzz/parsers.py --guided)

odgen's Python code is instrumented, so libFuzzer keeps the inputs that reach new
branches. An input is one format byte (EDS, DCF, XDD, XDC) and the file; the mutator
alternates libFuzzer's byte mutations with the structural mutations of fuzz/mutate.py.
A broken property is saved under tests/fuzz/regressions/ and appended to the file
named by ODGEN_FUZZ_FINDINGS; fuzzing goes on.
"""

from __future__ import annotations

import json
import os
import random
import sys
from pathlib import Path

import atheris

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

with atheris.instrument_imports(include=["odgen"]):
    from fuzz import mutate

FORMATS = ("eds", "dcf", "xdd", "xdc")
_SEEN: set[str] = set()


def pack(fmt: str, data: bytes) -> bytes:
    return bytes([FORMATS.index(fmt)]) + data


def unpack(data: bytes) -> tuple[str, bytes]:
    return (FORMATS[data[0] % len(FORMATS)], data[1:]) if data else ("eds", b"")


def test_one_input(data: bytes) -> None:
    fmt, body = unpack(data)
    outcome = mutate.check(body, fmt)
    if outcome.failure and outcome.failure not in _SEEN:
        _SEEN.add(outcome.failure)
        path = mutate.save_regression(mutate.minimise(body, fmt, outcome.failure), fmt, outcome.failure)
        log = os.environ.get("ODGEN_FUZZ_FINDINGS")
        if log:
            with open(log, "a", encoding="utf-8") as out:
                out.write(json.dumps({"failure": outcome.failure, "file": str(path.relative_to(mutate.ROOT)),
                                      "detail": outcome.detail}) + "\n")


def custom_mutator(data: bytes, max_size: int, seed: int) -> bytes:
    fmt, body = unpack(data)
    rng = random.Random(seed)
    body = atheris.Mutate(body, max(1, max_size - 1)) if rng.random() < 0.5 else _structural(fmt, body, rng)
    return pack(fmt, body)[:max_size]


def _structural(fmt: str, body: bytes, rng: random.Random) -> bytes:
    seed = mutate.split("input", fmt, mutate.decode(body))
    if rng.random() < 0.3 and seed.groups:
        rng.choice(list(mutate.UNIT_OPS.values()))(seed.groups, rng)
    text = mutate._join(seed.frame, seed.groups)
    table = {**mutate.TEXT_OPS, **(mutate.XML_OPS if fmt in ("xdd", "xdc") else {})}
    text = rng.choice(list(table.values()))(text, rng)
    if rng.random() < 0.2:
        return mutate.encode(text, fmt, rng)[0]
    return text.encode("utf-8")


def write_corpus(folder: Path, rng: random.Random, per_seed: int = 3) -> int:
    """Slices of every seed file as the starting corpus (small files fuzz faster)."""
    folder.mkdir(parents=True, exist_ok=True)
    count = 0
    for seed in mutate.load_seeds():
        for n in range(per_seed):
            text = mutate._join(seed.frame, mutate.slice_units(seed.groups, rng))
            (folder / f"{seed.name}.{n}").write_bytes(pack(seed.fmt, text.encode("utf-8")))
            count += 1
    return count


def main() -> None:
    atheris.Setup(sys.argv, test_one_input, custom_mutator=custom_mutator)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
