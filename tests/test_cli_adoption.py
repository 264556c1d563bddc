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
    (tmp_path / "pyproject.toml").write_text('[tool.odgen]\nexclude = ["./devices/vendor/", "*.xdd"]\n',
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


# --- frictions ---------------------------------------------------------------------------------------

EXAMPLE = FIXTURES.parent.parent / "examples" / "io-node" / "io-node.eds"


@pytest.mark.parametrize(("argv", "hint"), [
    (["lint", "--stats", str(OCTAL)], "did you mean --statistics?"),
    (["lint", "--strcit", str(OCTAL)], "did you mean --strict?"),
    (["generat", str(OCTAL)], "did you mean generate?"),
])
def test_a_typo_gets_the_closest_option_or_command(argv: list[str], hint: str,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2 and hint in capsys.readouterr().err


def _actions_without_help() -> list[str]:
    import argparse

    from odgen.cli import build_parser

    missing = []

    def walk(parser: argparse.ArgumentParser, where: str) -> None:
        for action in parser._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            if isinstance(action, argparse._SubParsersAction):
                helps = {choice.dest: choice.help for choice in action._choices_actions}
                for name, sub in action.choices.items():
                    if not (helps.get(name) or "").strip():
                        missing.append(f"{where} {name}")
                    walk(sub, f"{where} {name}")
            elif not (action.help or "").strip():
                missing.append(f"{where} {'/'.join(action.option_strings) or action.dest}")

    walk(build_parser(), "odgen")
    return missing


def test_every_command_and_option_has_help() -> None:
    assert sorted(_actions_without_help()) == []


def test_report_refuses_a_suffix_it_does_not_write(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pdf = tmp_path / "out.pdf"
    assert main(["report", str(EXAMPLE), "-o", str(pdf)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and ".html" in err and "--format" in err and not pdf.exists()
    assert main(["report", str(EXAMPLE), "-o", str(pdf), "--format", "html"]) == 0
    assert pdf.read_text(encoding="utf-8").lstrip().lower().startswith("<!doctype html")


def test_explain_and_report_count_alike(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import re

    assert main(["explain", str(EXAMPLE), "0x1017"]) == 0
    explained = re.search(r"dictionary: (\d+) objects, (\d+) entries counting each sub-index", capsys.readouterr().out)
    assert main(["report", str(EXAMPLE), "-o", str(tmp_path / "r.md")]) == 0
    page = (tmp_path / "r.md").read_text(encoding="utf-8")
    reported = re.search(r"(\d+) objects, (\d+) entries counting each sub-index", page)
    said = re.search(r"(\d+) objects, (\d+) entries counting each sub-index", capsys.readouterr().err)
    assert explained and reported and said
    assert explained.groups() == reported.groups() == said.groups()
    objects, entries = map(int, explained.groups())
    assert objects < entries  # the two numbers count different things, and say so


def test_signed_hex_in_three_keys_is_one_finding_naming_them(tmp_path: Path) -> None:
    from .conftest import lint

    text = SIGNED.read_text(encoding="utf-8").replace("DefaultValue=0xFFFF",
                                                      "LowLimit=0xFFFF\nHighLimit=0xFFFF\nDefaultValue=0xFFFF")
    path = tmp_path / "signed.eds"
    path.write_text(text, encoding="utf-8")
    found = [d for d in lint(path).diagnostics if d.rule == "SYN008"]
    assert len(found) == 1
    low_line = text.splitlines().index("LowLimit=0xFFFF") + 1
    assert found[0].loc.line == low_line
    assert found[0].message == "LowLimit, HighLimit, DefaultValue: '0xFFFF' read as the 16-bit two's complement -1"


def test_check_size_rows_line_up_whatever_the_names() -> None:
    from odgen.check import aligned_sizes

    printed = [  # as the self-test prints them: "%-13s %6lu"
        "values  rom               28 bytes  FLASH",
        "values  persist_communication     32 bytes  RAM, and as much FLASH for its defaults",
        "tables  hook slots     1234567 bytes  RAM",
        "267 passed, 0 failed",
    ]
    lines = aligned_sizes(printed)
    assert lines[3] == printed[3]
    assert len({line.index(" bytes") for line in lines[:3]}) == 1
    assert [line.split()[:2] for line in lines[:3]] == [["values", "rom"], ["values", "persist_communication"],
                                                        ["tables", "hook"]]
    assert lines[2].startswith("tables  hook slots ")


@pytest.mark.parametrize("command", ["conformance", "node", "roundtrip"])
def test_bus_commands_without_the_can_extra_say_what_to_install(command: str, monkeypatch: pytest.MonkeyPatch,
                                                                capsys: pytest.CaptureFixture[str]) -> None:
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "can" else real(name, *a))
    argv = [command, str(EXAMPLE), "--iface", "vcan0"] + (["--node-id", "5"] if command == "conformance" else [])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "python-can" in err and "odgen[can]" in err


@pytest.mark.parametrize("command", ["conformance", "node", "roundtrip"])
def test_bus_commands_without_the_interface_say_what_to_do(command: str, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("can")
    pytest.importorskip("canopen")
    argv = [command, str(EXAMPLE), "--iface", "odgnone0"] + (["--node-id", "5"] if command == "conformance" else [])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "ip link add dev vcan0 type vcan" in err


# --- convert: odgen's output passes odgen's lint ---------------------------------------------------

def _convert(source: Path, out: Path) -> None:
    assert main(["convert", str(source), str(out)]) == 0


def test_xdd_properties_become_comments_and_string_padding_stays(tmp_path: Path) -> None:
    from .conftest import lint

    xdd = XDD.read_text(encoding="utf-8")
    padded = "Trace1" + " " * 24
    xdd = xdd.replace('<CANopenObject index="1017"',
                      '<CANopenObject index="2100" name="Label" objectType="7" dataType="0009" accessType="rw" '
                      f'defaultValue="{padded}" PDOmapping="no" CO_flagsPDO="true"/>\n          '
                      '<CANopenObject index="1017"')
    source = tmp_path / "node.xdd"
    source.write_text(xdd, encoding="utf-8")
    out = tmp_path / "node.eds"
    _convert(source, out)
    written = out.read_text(encoding="utf-8")
    assert "\n;CO_flagsPDO=true\n" in written and "\nCO_flagsPDO" not in written
    assert f"\nDefaultValue={padded}\n" in written
    result = lint(out)
    assert not [d for d in result.diagnostics if d.rule == "OBJ025"]
    assert result.od is not None and result.od.objects[0x2100].subs[0].default.parsed == padded


def _strict_clean(path: Path) -> bool:
    from odgen.diagnostics import Severity

    from .conftest import lint

    return not [d for d in lint(path).diagnostics if d.severity >= Severity.WARNING]


def test_convert_output_lints_clean_where_its_input_does(tmp_path: Path) -> None:
    from .conftest import corpus_files

    sources = [p for p in corpus_files(".eds", ".dcf", ".xdd", ".xdc", ".xpd") if _strict_clean(p)]
    if not sources:
        pytest.skip("../shared/corpus is absent")
    failed = []
    for n, source in enumerate(sources):
        config = source.suffix.lower() in (".dcf", ".xdc")
        out = tmp_path / f"{n}.{'dcf' if config else 'eds'}"
        _convert(source, out)
        if not _strict_clean(out):
            failed.append(source.name)
    assert not failed


def test_converted_demo_device_has_the_findings_of_its_xdd(tmp_path: Path) -> None:
    from .conftest import CORPUS, lint

    source = CORPUS / "canopendemo__demoDevice.xdd"
    if not source.is_file():
        pytest.skip("../shared/corpus is absent")
    out = tmp_path / "demo.eds"
    _convert(source, out)
    converted = lint(out)
    assert converted.od is not None and 0x1280 not in converted.od.objects  # CO_disabled: left out
    kept = [(d.rule, d.index, d.sub) for d in lint(source).diagnostics if d.index != 0x1280]
    assert sorted(kept, key=str) == sorted(((d.rule, d.index, d.sub) for d in converted.diagnostics), key=str)
    assert "OBJ020" in {rule for rule, _, _ in kept}  # the '€' the XDD holds: a finding of both, not of convert


# --- report: Markdown is inert -----------------------------------------------------------------------

def test_markdown_report_writes_names_and_values_inert(tmp_path: Path) -> None:
    import re

    hostile = '<script>alert(1)</script> `x` [l](javascript:alert(1)) & <img src=x onerror=alert(1)>'
    text = EXAMPLE.read_text(encoding="utf-8")
    text = re.sub(r"(?m)^ProductName=.*$", f"ProductName={hostile}", text)
    text = re.sub(r"(?m)^ParameterName=Producer heartbeat time$", f"ParameterName={hostile}", text)
    source = tmp_path / "hostile.eds"
    source.write_text(text, encoding="utf-8")
    assert main(["report", str(source), "-o", str(tmp_path / "r.md")]) == 0
    page = (tmp_path / "r.md").read_text(encoding="utf-8")
    assert set(re.findall(r"<[^>]*>", page)) <= {"<br>"}  # the template's own line breaks only
    assert "](javascript:" not in page and "`x`" not in page
    assert page.count("&lt;script&gt;alert(1)&lt;/script&gt;") >= 2  # the name and the entry, shown as written


def test_eds_string_padding_is_read_as_written(tmp_path: Path) -> None:
    """A CANopenNode EDS pads a string to reserve its capacity; numbers and other keys stay stripped."""
    from .conftest import lint

    text = SIGNED.read_text(encoding="utf-8").replace("DataType=0x0003\n", "DataType=0x0009\n", 1)
    text = text.replace("DefaultValue=0xFFFF", "DefaultValue = Trace1" + " " * 24 + "\nLowLimit=1   ")
    path = tmp_path / "padded.eds"
    path.write_text(text.replace("\n", "\r\n"), encoding="utf-8")
    od = lint(path).od
    assert od is not None
    sub = od.objects[0x2000].subs[0]
    assert sub.default is not None and sub.default.parsed == "Trace1" + " " * 24
    assert sub.low is not None and sub.low.text == "1"
