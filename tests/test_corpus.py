"""Every real file loads or is rejected with located diagnostics, never a traceback.

Per-file outcomes go to build/test-reports/corpus.md (a generated report, not
expectations): the assertions are invariants that hold for any input.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from odgen.cli import main
from odgen.diagnostics import RULES, Severity
from odgen.lint.driver import exit_code

from .conftest import BUILD, corpus_files, corpus_params, lint


@pytest.mark.parametrize("path", corpus_params())
def test_corpus_file_invariants(path: Path) -> None:
    result = lint(path)
    n_lines = len(path.read_bytes().splitlines())
    for d in result.diagnostics:
        assert d.rule in RULES
        assert 0 <= d.loc.line <= n_lines, d.text()
        assert d.loc.file == str(path)
    if result.od is None:
        assert result.count(Severity.ERROR) > 0, "a file that is not loaded must say why"
    assert exit_code([result], strict=False) in (0, 1)
    assert [d.text() for d in lint(path).diagnostics] == [d.text() for d in result.diagnostics]


@pytest.mark.parametrize("path", corpus_params())
def test_cli_exit_code_on_corpus(path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", str(path)]) in (0, 1)
    assert "Traceback" not in capsys.readouterr().err


def test_write_corpus_report() -> None:
    files = corpus_files()
    if not files:
        pytest.skip("../shared/corpus is absent")
    rows = ["| file | loaded | objects | errors | warnings | infos | rules |", "|---|---|---|---|---|---|---|"]
    for path in files:
        r = lint(path)
        rules = Counter(d.rule for d in r.diagnostics)
        top = ", ".join(f"{k}×{v}" for k, v in sorted(rules.items()))
        rows.append(f"| {path.name} | {'yes' if r.od else 'no'} | {len(r.od.objects) if r.od else 0} | "
                    f"{r.count(Severity.ERROR)} | {r.count(Severity.WARNING)} | {r.count(Severity.INFO)} | {top} |")
    BUILD.mkdir(parents=True, exist_ok=True)
    report = BUILD / "corpus.md"
    report.write_text("# Corpus lint outcomes\n\n" + "\n".join(rows) + "\n", encoding="utf-8")
    assert report.stat().st_size > 0 and len(rows) == len(files) + 2
