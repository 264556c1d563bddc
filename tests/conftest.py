"""Shared test helpers: where the corpus is, and linting a file in-process."""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.codegen.generate import Request, generate
from odgen.lint import FileResult, lint_path
from odgen.rules import LintOptions

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
FIXTURES = Path(__file__).resolve().parent / "fixtures"
BUILD = ROOT / "build" / "test-reports"


def corpus_files(*suffixes: str) -> list[Path]:
    """Every corpus file with one of the suffixes (all when none given); [] when absent."""
    if not CORPUS.is_dir():
        return []
    files = sorted(p for p in CORPUS.iterdir() if p.is_file())
    return [p for p in files if not suffixes or p.suffix.lower() in suffixes]


def generates(path: Path) -> bool:
    """Whether `odgen generate` writes a dictionary for the file (no blocking finding)."""
    return bool(generate(Request(path, name="od")).files)


def corpus_params(*suffixes: str) -> list:
    files = corpus_files(*suffixes)
    if not files:
        return [pytest.param(None, marks=pytest.mark.skip(reason="../shared/corpus is absent"))]
    return [pytest.param(p, id=p.name) for p in files]


def lint(path: Path, **options) -> FileResult:
    return lint_path(path, LintOptions(**options))


def expectations(path: Path) -> list[str]:
    """`; expect: LINE: severity[RULE]: message` lines of a fixture (XML: `<!-- expect: ... -->`)."""
    out = []
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        for marker in ("; expect: ", "<!-- expect: "):
            if line.startswith(marker):
                out.append(line[len(marker):].removesuffix(" -->").strip())
    return out


def rendered(result: FileResult) -> list[str]:
    """Diagnostics as `LINE: severity[RULE]: message`, without the file name."""
    prefix = f"{result.source}:"
    return [d.text().removeprefix(prefix) for d in result.diagnostics]
