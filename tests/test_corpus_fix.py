"""`odgen fix` on every real EDS/DCF with findings it repairs: only the lines it lists change, the repaired
rules are gone when the result is linted again, the result generates, and repairing it again changes
nothing. In-process and cheap; `odgen check` builds two of the results."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from odgen.cli.fix import Fixed, fix_file
from odgen.check import run_check
from odgen.pipeline import Request, generate
from odgen.formats import load_bytes
from odgen.lint.driver import lint_model
from odgen.lint.passes import LintOptions

from .conftest import corpus_files
from .test_corpus_generate import UNREPAIRABLE
from .test_repair import assert_only_named_lines_change

CHECKED = ("gocanopen__base.eds", "mabcandle__MD80_latest.eds")  # built and self-tested after the repair


def _fixed(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, Fixed]]:
    out = tmp_path_factory.mktemp("fixed")
    results = {}
    for path in corpus_files(".eds", ".dcf"):
        fixed = fix_file(path, unsafe=True)
        if fixed.repairs:
            target = out / path.name
            target.write_bytes(fixed.data)
            results[path.name] = (target, fixed)
    return results


@pytest.fixture(scope="module")
def fixed_corpus(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[Path, Fixed]]:
    if not corpus_files():
        pytest.skip("../shared/corpus is absent")
    return _fixed(tmp_path_factory)


def test_fix_repairs_real_files_line_by_line(fixed_corpus: dict[str, tuple[Path, Fixed]]) -> None:
    assert len(fixed_corpus) >= 10
    originals = {p.name: p for p in corpus_files()}
    for name, (target, fixed) in fixed_corpus.items():
        assert_only_named_lines_change(originals[name].read_bytes(), fixed)
        od, diags = load_bytes(target.read_bytes(), str(target), target.suffix[1:].lower())
        assert od is not None, name
        lint_model(od, diags, LintOptions())
        # a repaired finding is gone: no finding of its rule, at its entry, saying what it said
        left = {(d.rule, d.index, d.sub, d.message) for d in diags} & \
            {(r.rule, r.finding.index, r.finding.sub, r.finding.message) for r in fixed.repairs}
        assert not left, f"{name}: {sorted(left, key=str)} still reported after the repair"


def test_fixed_files_generate_and_a_second_fix_changes_nothing(fixed_corpus: dict[str, tuple[Path, Fixed]]) -> None:
    for name, (target, fixed) in fixed_corpus.items():
        again = fix_file(target, unsafe=True)
        assert again.data == fixed.data and not again.repairs, name
        if name not in UNREPAIRABLE:
            result = generate(Request(target, name="od"))
            assert result.files, f"{name}: {[d.text() for d in result.refused][:3]}"


@pytest.mark.parametrize("name", CHECKED)
def test_fixed_files_pass_odgen_check(name: str, fixed_corpus: dict[str, tuple[Path, Fixed]]) -> None:
    assert name in fixed_corpus
    cc = shutil.which("gcc")
    assert cc, "gcc is missing: `make test` installs it (make sysdeps)"
    outcome = run_check(Request(fixed_corpus[name][0], name="od"), cc=cc)
    assert outcome.ok, outcome.output[-800:]
