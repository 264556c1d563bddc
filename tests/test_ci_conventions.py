"""CI conventions: GitHub annotations, --statistics, the config file, rule-id checks,
SARIF regions and base ids, generate --check's listing, and a light start for `odgen lint`."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from odgen import choices, cli
from odgen.cli import main
from odgen.cli.lint import lint_settings
from odgen.lint import reporters

from .conftest import FIXTURES, ROOT, corpus_files

EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
DUPLICATE = FIXTURES / "syntax" / "SYN003.eds"
OCTAL = FIXTURES / "syntax" / "SYN006.eds"


def test_cli_choices_are_what_their_modules_implement() -> None:
    """odgen.choices is the one list; each module that acts on a choice has one way per choice."""
    assert set(choices.REPORT_FORMATS) == set(reporters.RENDERERS)
    from odgen.diff import CLASSES
    from odgen.diff.report import RENDERERS as DIFF_RENDERERS

    assert set(choices.DIFF_FORMATS) == set(DIFF_RENDERERS)
    assert (*CLASSES, "none") == choices.DIFF_FAIL_ON
    from odgen.profiles import ds401

    assert ds401.MAX_DIGITAL == ds401.MAX_GROUPS * 8 and set(ds401.WIDTHS) == set(ds401.INT_OF_WIDTH)
    for argv in (["generate", "x.eds", "-o", "out", "--lookup", "nope"], ["lint", "--input-format", "nope"],
                 ["report", "x.eds", "-o", "x.html", "--format", "nope"]):
        with pytest.raises(SystemExit):
            cli.build_parser().parse_args(argv)


def test_github_annotations(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", "--format", "github", str(DUPLICATE)]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert f"::error file={DUPLICATE},line=4,title=SYN003::SYN003 key '1' repeats line 3 in [ManufacturerObjects]; " \
           "this one is ignored" in lines
    assert f"::warning file={DUPLICATE},line=1,title=HDR014::HDR014 [FileInfo] is missing" in lines
    assert all(re.match(r"::(error|warning|notice) file=[^,]+,line=\d+,title=[A-Z]+\d+::", x) for x in lines)


def test_github_escapes_properties_and_messages() -> None:
    from odgen.lint.reporters.github import _escape

    assert _escape("a,b:c%d", prop=True) == "a%2Cb%3Ac%25d"
    assert _escape("one\ntwo, three: four") == "one%0Atwo, three: four"


def test_statistics_counts_per_rule(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", str(DUPLICATE), str(OCTAL)]) == 1
    found = [x for x in capsys.readouterr().out.splitlines() if "[" in x]
    assert main(["lint", "--statistics", str(DUPLICATE), str(OCTAL)]) == 1
    rows = capsys.readouterr().out.splitlines()
    counted = {row.split()[1]: int(row.split()[0]) for row in rows}
    expected: dict[str, int] = {}
    for line in found:
        rule = re.search(r"\[([A-Z]+\d+)\]", line).group(1)  # type: ignore[union-attr]
        expected[rule] = expected.get(rule, 0) + 1
    assert counted == expected
    assert [int(r.split()[0]) for r in rows] == sorted((int(r.split()[0]) for r in rows), reverse=True)


@pytest.mark.parametrize("argv", [["--select", "PD0"], ["--ignore", "PDO999"], ["--select", "SYN003,XYZ"]])
def test_unknown_rule_ids_exit_two_naming_close_ones(argv: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["lint", *argv, str(EXAMPLE)]) == 2
    err = capsys.readouterr().err
    assert "is not a rule id or prefix" in err and ("did you mean" in err or "odgen rules" in err)
    if argv[1] == "PD0":
        assert "PDO" in err.split("did you mean", 1)[1]


def _project(tmp_path: Path, config: str, name: str = "odgen.toml") -> Path:
    project = tmp_path / "project"
    (project / "devices").mkdir(parents=True)
    (project / name).write_text(config, encoding="utf-8")
    for fixture in (DUPLICATE, OCTAL):
        (project / "devices" / fixture.name).write_bytes(fixture.read_bytes())
    return project


def test_config_file_found_upward_and_overridden(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    project = _project(tmp_path, '[tool.odgen]\nselect = ["SYN006"]\nstrict = true\n', "pyproject.toml")
    octal = project / "devices" / "SYN006.eds"
    assert main(["lint", str(octal)]) == 1  # the warning fails under the config's strict
    assert all("[SYN006]" in x for x in capsys.readouterr().out.splitlines() if "[" in x)
    assert main(["lint", "--select", "SYN003", str(project / "devices" / "SYN003.eds")]) == 1
    assert "[SYN003]" in capsys.readouterr().out  # --select replaces the config's select


def test_config_per_file_ignores_and_node_id(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    config = 'node-id = 5\nignore = ["COM", "HDR"]\n[per-file-ignores]\n"devices/SYN003.eds" = ["SYN", "LST"]\n'
    project = _project(tmp_path, config)
    assert main(["lint", str(project / "devices" / "SYN003.eds")]) == 0
    out = capsys.readouterr().out
    assert "0 error(s), 0 warning(s)" in out and "[" not in out
    assert main(["lint", str(project / "devices" / "SYN006.eds")]) == 0  # per-file: SYN006 still reported
    assert "[SYN006]" in capsys.readouterr().out
    assert main(["lint", str(project / "devices" / "SYN006.eds"), "--strict"]) == 1
    for argv, node_id in (([], 5), (["--node-id", "9"], 9)):  # the command line overrides the file
        args = cli.build_parser().parse_args(["lint", *argv, str(project / "devices" / "SYN006.eds")])
        assert lint_settings(args, args.files[0])[1].node_id == node_id


@pytest.mark.parametrize("config, message", [
    ('ignore = ["PDO999"]\n', "'PDO999' is not a rule id"),
    ('[per-file-ignores]\n"*.eds" = ["SYN0O3"]\n', "'SYN0O3' is not a rule id"),
    ('selct = ["SYN"]\n', "unknown key 'selct'"),
    ('strict = "yes"\n', "strict must be true or false"),
    ('node-id = 300\n', "node-id must be a number in 1..127"),
    ("select = [\n", "not valid TOML"),
])
def test_config_mistakes_exit_two(config: str, message: str, tmp_path: Path,
                                  capsys: pytest.CaptureFixture[str]) -> None:
    project = _project(tmp_path, config)
    assert main(["lint", str(project / "devices" / "SYN003.eds")]) == 2
    err = capsys.readouterr().err
    assert message in err and "odgen.toml" in err


def test_sarif_every_result_has_a_region_and_base_ids(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    files = corpus_files() or sorted((FIXTURES / "syntax").glob("*.eds"))
    monkeypatch.chdir(ROOT.parent)
    main(["lint", "--format", "sarif", *map(str, files)])
    run = json.loads(capsys.readouterr().out)["runs"][0]
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == ROOT.parent.resolve().as_uri() + "/"
    assert run["results"]
    for result in run["results"]:
        physical = result["locations"][0]["physicalLocation"]
        assert physical["region"]["startLine"] >= 1
        assert physical["artifactLocation"]["uriBaseId"] == "%SRCROOT%"
        assert not physical["artifactLocation"]["uri"].startswith(("/", "file:"))


def test_sarif_outside_the_working_directory_is_absolute(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    main(["lint", "--format", "sarif", str(DUPLICATE)])
    physical = json.loads(capsys.readouterr().out)["runs"][0]["results"][0]["locations"][0]["physicalLocation"]
    assert physical["artifactLocation"] == {"uri": DUPLICATE.resolve().as_uri()}


def test_generate_check_lists_missing_changed_and_extra(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    argv = ["generate", str(EXAMPLE), "-o", str(out)]
    assert main(argv) == 0
    assert main([*argv, "--name", "old_name"]) == 0  # a stale generation from the same input
    (tmp_path / "other.eds").write_bytes(DUPLICATE.read_bytes().replace(b"1=", b"2=", 0))
    (out / "io_node.h").unlink()
    with (out / "io_node.c").open("a") as c:
        c.write("/* edited */\n")
    (out / ".io_node.c.x1y2.tmp").write_text("left by a killed run")
    (out / "notes.txt").write_text("the user's own file")
    assert main([*argv, "--check"]) == 1
    err = capsys.readouterr().err
    assert f"{out / 'io_node.h'}: missing" in err
    assert f"{out / 'io_node.c'}: changed" in err
    assert f"{out / 'old_name.c'}: extra" in err and f"{out / '.io_node.c.x1y2.tmp'}: extra" in err
    assert "notes.txt" not in err
    assert f"regenerate with: odgen generate {EXAMPLE} -o {out}" in err
    assert main(argv) == 0
    assert not (out / ".io_node.c.x1y2.tmp").exists(), "the next run removes temp files a killed run left"


def test_generate_keeps_mtime_of_unchanged_files(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0
    os.utime(out / "io_node.c", (1_000_000, 1_000_000))
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0
    assert (out / "io_node.c").stat().st_mtime == 1_000_000


def _modules_after(argv: list[str]) -> set[str]:
    code = ("import sys; from odgen.cli import main; code = main(sys.argv[1:]); "
            "print(' '.join(sorted(sys.modules)))")
    done = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, check=False)
    return set(done.stdout.split())


def test_lint_of_an_eds_and_version_import_no_heavy_dependency() -> None:
    heavy = {"jinja2", "lxml", "canopen", "can"}
    assert not heavy & _modules_after(["lint", str(EXAMPLE)])
    version = subprocess.run([sys.executable, "-X", "importtime", "-m", "odgen", "--version"],
                             capture_output=True, text=True, check=True)
    imported = {line.split("|")[-1].strip().split(".")[0] for line in version.stderr.splitlines()}
    assert not heavy & imported and version.stdout.startswith("odgen ")
    assert "lxml" in _modules_after(["lint", str(FIXTURES / "xdd" / "valid.xdd")])
