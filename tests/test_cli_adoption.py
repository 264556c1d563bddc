"""What a new user meets first: one rule explained, a folder linted, typos answered, odd input refused."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from odgen.catalogue import RULES
from odgen.cli import main

from .conftest import FIXTURES

OCTAL = FIXTURES / "syntax" / "SYN006.eds"
SIGNED = FIXTURES / "syntax" / "SYN008.eds"
XDD = FIXTURES / "xdd" / "valid.xdd"


# --- odgen rule ID ---------------------------------------------------------------------------------

@pytest.mark.parametrize("rule_id", ["PDO003", "SYN008", "COM007"])
def test_rule_prints_what_the_catalogue_says(rule_id: str, capsys: pytest.CaptureFixture[str]) -> None:
    rule = RULES[rule_id]
    assert main(["rule", rule_id.lower()]) == 0
    out = capsys.readouterr().out
    flat = " ".join(out.split())
    assert out.startswith(f"{rule.id}: {rule.title}\n")
    assert f"Severity: {rule.severity.label}" in flat
    generation = "Generation: blocks" if rule.blocks else "Generation: goes on"
    assert generation in flat
    assert " ".join(rule.why.split()) in flat and " ".join(rule.fix.split()) in flat
    assert all(f"    {line}" in out.splitlines() for line in rule.example.splitlines())


def test_every_rule_can_be_explained(capsys: pytest.CaptureFixture[str]) -> None:
    for rule_id in RULES:
        assert main(["rule", rule_id]) == 0
    out = capsys.readouterr().out
    assert out.count("\nWhy:\n") == out.count("\nExample:\n") == out.count("\nFix:\n") == len(RULES)


@pytest.mark.parametrize(("typed", "suggested"), [("PD0003", "PDO003"), ("PDO", "PDO001"), ("SYN08", "SYN008")])
def test_unknown_rule_is_exit_2_with_the_closest_ids(typed: str, suggested: str,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rule", typed]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"'{typed}' is not a rule id" in err and suggested in err


def test_rules_lists_all_or_a_family_and_explains_one(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["rules"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == len(RULES)
    assert main(["rules", "pdo"]) == 0
    listed = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert listed == [r for r in RULES if r.startswith("PDO")]
    assert main(["rules", "PDO003"]) == 0
    assert capsys.readouterr().out.startswith("PDO003: ")
    assert main(["rules", "PDX"]) == 2


# --- odgen lint PATH... ----------------------------------------------------------------------------

def _tree(root: Path) -> Path:
    """devices/{a/SYN006.eds, b/node.xdd, vendor/SYN008.eds, .cache/hidden.eds, notes.txt}"""
    devices = root / "devices"
    for folder in ("a", "b", "vendor", ".cache"):
        (devices / folder).mkdir(parents=True)
    shutil.copy(OCTAL, devices / "a" / "SYN006.eds")
    shutil.copy(XDD, devices / "b" / "node.xdd")
    shutil.copy(SIGNED, devices / "vendor" / "SYN008.eds")
    shutil.copy(OCTAL, devices / ".cache" / "hidden.eds")
    (devices / "notes.txt").write_text("not a description\n", encoding="utf-8")
    return devices


def _files_linted(out: str) -> list[str]:
    return sorted({line.split(":")[0] for line in out.splitlines() if "[" in line})


def test_lint_a_folder_reads_its_descriptions_sorted_with_one_summary(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    _tree(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(["lint", "devices"]) == 1
    out = capsys.readouterr().out
    summaries = [line for line in out.splitlines() if "file(s) checked" in line]
    assert summaries == [summaries[0]] and summaries[0].startswith("3 file(s) checked")
    assert "hidden.eds" not in out and "notes.txt" not in out
    order = [line.split(":")[0] for line in out.splitlines() if "[" in line]
    assert order == sorted(order, key=lambda p: p.rsplit("/", 1)[0])  # a/ then b/ then vendor/
    assert main(["lint", "devices"]) == 1
    assert capsys.readouterr().out == out  # deterministic


def test_lint_expands_a_quoted_glob(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                    monkeypatch: pytest.MonkeyPatch) -> None:
    _tree(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(["lint", "devices/**/*.eds"]) == 1
    assert _files_linted(capsys.readouterr().out) == ["devices/a/SYN006.eds", "devices/vendor/SYN008.eds"]


def test_exclude_in_the_settings_file(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                      monkeypatch: pytest.MonkeyPatch) -> None:
    _tree(tmp_path)
    (tmp_path / "pyproject.toml").write_text('[tool.odgen]\nexclude = ["devices/vendor/", "*.xdd"]\n',
                                             encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["lint", "devices"]) == 1
    out = capsys.readouterr().out
    assert _files_linted(out) == ["devices/a/SYN006.eds"] and "1 file(s) checked" in out
    assert main(["lint", "devices/vendor/SYN008.eds", "--select", "SYN"]) == 0  # a file named is read
    assert "1 file(s) checked" in capsys.readouterr().out
    assert main(["lint", "devices/vendor"]) == 2
    assert "left out by the config file's exclude" in capsys.readouterr().err


@pytest.mark.parametrize("argument", ["empty", "nothing/*.eds"])
def test_a_folder_or_glob_without_descriptions_is_exit_2(argument: str, tmp_path: Path,
                                                         capsys: pytest.CaptureFixture[str],
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "empty").mkdir()
    (tmp_path / "empty" / "README.md").write_text("x\n", encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert main(["lint", argument]) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "no description file" in captured.err and not captured.out


@pytest.mark.parametrize("text", ["tool = 5\n", 'tool = "odgen"\n', "[tool]\nodgen = 5\n",
                                  '[tool.odgen]\nexclude = "vendor"\n', "[tool.odgen]\nselect = 5\n"])
def test_a_malformed_tool_odgen_is_exit_2_in_one_sentence(text: str, tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "pyproject.toml").write_text(text, encoding="utf-8")
    shutil.copy(OCTAL, tmp_path / "x.eds")
    assert main(["lint", str(tmp_path / "x.eds")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "pyproject.toml" in err and "internal error" not in err
