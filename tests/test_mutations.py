"""Hostile variations of real files: every one yields a model or diagnostics, never an exception.

Seeded structural mutations of each corpus file (delete, duplicate and swap lines,
numbers pushed to type limits, `$NODEID` forms, truncation, attribute values
replaced in XML). The same seeds run every time, so a failure reproduces.
"""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from odgen.formats import load_bytes
from odgen.lint.driver import lint_model
from odgen.lint.passes import LintOptions

from .conftest import corpus_params

MUTANTS_PER_FILE = 6
TOKENS = ["0", "-1", "0xFFFFFFFFFFFFFFFF", "$NODEID+0x180", "0x180+$nodeid", "", "rw", "rww", "const",
          "readWriteInput", "noAccess", "0x0099", "010", "1e999", "nan", "x", "[", "=", "0x8", "255", "65536"]


def _mutate_lines(text: str, rng: random.Random) -> str:
    lines = text.splitlines()
    for _ in range(rng.randint(1, 8)):
        if not lines:
            break
        i = rng.randrange(len(lines))
        op = rng.randrange(5)
        if op == 0:
            del lines[i]
        elif op == 1:
            lines.insert(i, lines[rng.randrange(len(lines))])
        elif op == 2:
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == 3:
            lines[i] = re.sub(r"=.*$", "=" + rng.choice(TOKENS), lines[i])
        else:
            lines = lines[: i + 1]
    return "\n".join(lines)


def _mutate_xml(text: str, rng: random.Random) -> str:
    spots = list(re.finditer(r'="[^"]*"', text))
    for _ in range(rng.randint(1, 8)):
        if not spots:
            break
        m = rng.choice(spots)
        text = text[: m.start()] + f'="{rng.choice(TOKENS)}"' + text[m.end():]
        spots = list(re.finditer(r'="[^"]*"', text))
    if rng.random() < 0.2:
        text = text[: rng.randrange(len(text) or 1)]
    return text


@pytest.mark.parametrize("path", corpus_params())
def test_mutants_never_raise(path: Path) -> None:
    data = path.read_bytes()
    fmt = {".xdd": "xdd", ".xpd": "xdd", ".xdc": "xdc", ".dcf": "dcf"}.get(path.suffix.lower(), "eds")
    text = data.decode("utf-8", errors="replace")
    for seed in range(MUTANTS_PER_FILE):
        rng = random.Random(f"{path.name}:{seed}")
        mutant = _mutate_xml(text, rng) if fmt in ("xdd", "xdc") else _mutate_lines(text, rng)
        od, diags = load_bytes(mutant.encode("utf-8"), f"{path.name}~{seed}", fmt)
        if od is not None:
            lint_model(od, diags, LintOptions())
        assert od is not None or len(diags) > 0, f"seed {seed}: rejected without a diagnostic"
