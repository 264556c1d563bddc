"""Hostile descriptions and arguments: safe C, no path escapes, bounded memory.

Already covered elsewhere and not repeated here: a hostile ParameterName through
`odgen check` (test_codegen_c.py::test_hostile_names_give_safe_c), a 5000-character
string default (test_codegen_c.py::test_string_longer_than_c99_literal_limit), XXE,
billion laughs and external DTDs (test_xdd.py). This file adds string values with
C syntax in them, read back through the runtime and compared byte for byte with the
description; line breaks in XDD names and values; output names; a 100 MB file; very
many findings; deep XML nesting. Memory is measured as the peak RSS of a subprocess.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from odgen.toolchain import CORE_SOURCES
from odgen.cli import main
from odgen.codegen.check import run_check
from odgen.codegen.generate import Request, generate

from .conftest import FIXTURES, ROOT
from .cprog import build, run

GEN = FIXTURES / "generate"
RUNTIME = ROOT / "runtime"
HOSTILE_STRINGS = {
    0x2100: 'ends a comment */ here',
    0x2101: 'quote " and backslash \\ and \\n written out',
    0x2102: "trigraph ??/ and ??= and ??' stay",
    0x2103: "%s%n%x printf",
    0x2104: "Gr\u00fc\u00dfe \u2713 \u65e5\u672c",
    0x2105: "tab\there",
    0x2106: ("x" * 9990 + '*/"\\??/'),
}


def _string_objects(kind: int) -> str:
    out = []
    for index, value in HOSTILE_STRINGS.items():
        out.append(f"[{index:04X}]\nParameterName=s{index:04X} */ \"name\" \\\nObjectType=0x7\nDataType=0x{kind:04X}\n"
                   f"AccessType=rw\nDefaultValue={value}\nPDOMapping=0\n\n")
    return "".join(out)


def _hostile_eds(tmp_path: Path, kind: int) -> Path:
    text = (GEN / "plain.eds").read_text(encoding="utf-8")
    listed = "".join(f"{n}=0x{index:04X}\n" for n, index in enumerate(HOSTILE_STRINGS, start=2))
    text = text.replace("[ManufacturerObjects]\nSupportedObjects=1\n1=0x2000\n",
                        f"[ManufacturerObjects]\nSupportedObjects={1 + len(HOSTILE_STRINGS)}\n1=0x2000\n{listed}")
    path = tmp_path / "strings.eds"
    path.write_text(text + "\n" + _string_objects(kind), encoding="utf-8")
    return path


def _reader_program(name: str, expected: dict[int, bytes]) -> str:
    """A C program reading each string through odg_read and comparing it with bytes written here."""
    checks = []
    for index, data in expected.items():
        array = ", ".join(f"0x{b:02X}" for b in data) or "0"
        checks.append(f"    {{ static const uint8_t want[] = {{ {array} }};\n"
                      f"      failed += check(0x{index:04X}, want, {len(data)}u); }}")
    body = "\n".join(checks)
    return f"""#include <stdio.h>
#include <string.h>
#include "odg.h"
#include "{name}.h"

static uint8_t got[20000];
static unsigned passed;

static int check(uint16_t index, const uint8_t *want, uint32_t len)
{{
    odg_ref_t ref;
    uint32_t n = 0, total = 0;
    if (odg_find(&{name}, index, 0, &ref) != 0) {{ printf("0x%04X missing\\n", index); return 1; }}
    do {{
        if (odg_read(&ref, total, got + total, 7, &n) != 0) {{ printf("0x%04X read failed\\n", index); return 1; }}
        total += n;
    }} while (n == 7 && total + 7 <= sizeof got);
    if (total != len || memcmp(got, want, len) != 0) {{
        printf("0x%04X: %u bytes read, %u expected\\n", index, (unsigned)total, (unsigned)len);
        return 1;
    }}
    passed++;
    return 0;
}}

int main(void)
{{
    unsigned failed = 0;
    if (odg_init(&{name}, 5) != 0) {{ puts("init failed"); return 1; }}
{body}
    printf("%u passed, %u failed\\n", passed, failed);
    return failed != 0;
}}
"""


@pytest.mark.parametrize("kind,encoding", [(0x0009, "utf-8"), (0x000B, "utf-16-le")], ids=["visible", "unicode"])
def test_hostile_string_values_compile_and_read_back(tmp_path: Path, kind: int, encoding: str) -> None:
    path = _hostile_eds(tmp_path, kind)
    result = generate(Request(path, name="hostile"))
    assert result.files, [d.text() for d in result.diags]
    for fname, text in result.files.items():
        (tmp_path / fname).write_text(text, encoding="utf-8")
        assert not any(line.lstrip().startswith("#define") and "printf" in line for line in text.splitlines())
    expected = {index: value.encode(encoding) for index, value in HOSTILE_STRINGS.items()}
    (tmp_path / "reader.c").write_text(_reader_program("hostile", expected), encoding="utf-8")
    exe = tmp_path / "reader"
    sources = (tmp_path / "reader.c", tmp_path / "hostile.c", *(RUNTIME / s for s in CORE_SOURCES))
    build("gcc", ("-O1", "-trigraphs"), sources, (RUNTIME, tmp_path), exe)
    assert f"{len(HOSTILE_STRINGS)} passed, 0 failed" in run(exe, tmp_path)


def test_hostile_string_values_pass_the_self_test(tmp_path: Path) -> None:
    outcome = run_check(Request(_hostile_eds(tmp_path, 0x0009)), cc="clang")
    assert outcome.ok, outcome.output[-3000:]
    assert outcome.output.rstrip().endswith(" 0 failed")


XDD_BREAKS = (GEN.parent / "xdd" / "valid.xdd").read_text(encoding="utf-8").replace(
    'name="Producer heartbeat time"', 'name="beat&#10;#define BAD_NAME 1&#13;&#10;*/ x"').replace(
    '<CANopenObject index="2000"',
    '<CANopenObject index="2001" name="Label" objectType="7" dataType="0009" accessType="rw" '
    'defaultValue="a&#10;#define BAD_VALUE 1 */ &quot;\\" PDOmapping="no"/>\n<CANopenObject index="2000"')


def test_line_breaks_in_xdd_names_and_values_stay_inside_c(tmp_path: Path) -> None:
    path = tmp_path / "breaks.xdd"
    path.write_text(XDD_BREAKS, encoding="utf-8")
    result = generate(Request(path))
    assert result.files, [d.text() for d in result.diags]
    for text in result.files.values():
        assert not any(line.lstrip().startswith("#define BAD") for line in text.splitlines())
    outcome = run_check(Request(path), cc="gcc")
    assert outcome.ok, outcome.output[-3000:]
    assert outcome.output.rstrip().endswith(" 0 failed")


# -- output names ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["../../x", "/tmp/odgen-hostile", "a/b", "..", "x.h", ""])
@pytest.mark.parametrize("command", ["generate", "check"])
def test_path_like_names_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str,
                                     name: str) -> None:
    out = tmp_path / "out" / "deeper"
    args = ["generate", str(GEN / "plain.eds"), "-o", str(out)] if command == "generate" else [
        "check", str(GEN / "plain.eds"), "--keep", str(out)]
    assert main([*args, "--name", name]) == 2
    assert f"--name '{name}' must be a C identifier" in capsys.readouterr().err
    assert not (tmp_path / "out").exists() and not Path("/tmp/odgen-hostile.c").exists()
    assert not (tmp_path / "x.c").exists() and not (ROOT.parent / "x.c").exists()


def test_profile_name_is_a_value_not_a_path(tmp_path: Path) -> None:
    """The product name goes into the EDS as text; files are named after -o only."""
    work = tmp_path / "work"
    work.mkdir()
    out, gen = work / "io.eds", work / "gen"
    assert main(["profile", "ds401", "--di", "8", "--name", "../../x */ \"q\"", "-o", str(out),
                 "--generate", str(gen)]) == 0
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")) == [
        "work", "work/gen", "work/gen/ds401_app.h", "work/gen/io.c", "work/gen/io.h", "work/gen/io_config.h",
        "work/io.eds"]
    assert "ProductName=../../x */ \"q\"" in out.read_text(encoding="utf-8")


def test_profile_name_with_a_line_break_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "io.eds"
    assert main(["profile", "ds401", "--name", "x\n[1000]", "-o", str(out)]) == 2
    assert "--name must be one non-empty line" in capsys.readouterr().err
    assert not out.exists()


def test_names_inside_the_description_never_name_files(tmp_path: Path) -> None:
    text = (GEN / "plain.eds").read_text(encoding="utf-8").replace("FileName=gen.eds", "FileName=../../evil.eds")
    src = tmp_path / "in" / "dev.eds"
    src.parent.mkdir()
    src.write_text(text, encoding="utf-8")
    assert main(["convert", str(src), str(tmp_path / "out.eds")]) == 0
    assert main(["generate", str(src), "-o", str(tmp_path / "gen")]) == 0
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*")) == [
        "gen", "gen/dev.c", "gen/dev.h", "gen/dev_config.h", "in", "in/dev.eds", "out.eds"]


def test_convert_into_a_missing_folder_writes_nothing(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["convert", str(GEN / "plain.eds"), str(tmp_path / "missing" / "out.eds")]) == 2
    assert "cannot write" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


# -- size, repetition, nesting: bounded memory ----------------------------------------------------------

_PROBE = """
import json, resource, sys
from odgen.lint.driver import lint_path
from odgen.lint.passes import LintOptions
result = lint_path(sys.argv[1], LintOptions())
rules = {}
for d in result.diagnostics:
    rules[d.rule] = rules.get(d.rule, 0) + 1
print(json.dumps({"model": result.od is not None, "rules": rules, "omitted": result.omitted,
                  "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def _lint_in_subprocess(path: Path) -> dict:
    done = subprocess.run([sys.executable, "-c", _PROBE, str(path)], capture_output=True, text=True, check=False,
                          cwd=ROOT, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout)


def _baseline_mb() -> float:
    return _lint_in_subprocess(GEN / "plain.eds")["rss_mb"]


@pytest.mark.parametrize("suffix", [".eds", ".xdd"])
def test_100_mb_file_is_refused_unread(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"huge{suffix}"
    unit = (GEN / "plain.eds").read_bytes() if suffix == ".eds" else (GEN.parent / "xdd" / "valid.xdd").read_bytes()
    with path.open("wb") as out:
        for _ in range(100 * 1024 * 1024 // len(unit) + 1):
            out.write(unit)
    assert path.stat().st_size >= 100 * 1024 * 1024
    try:
        got = _lint_in_subprocess(path)
    finally:
        path.unlink()  # pytest keeps the temporary folders of recent runs
    assert got["rules"] == {"SYN018": 1} and not got["model"]
    assert got["rss_mb"] < _baseline_mb() + 64, got


def test_a_mistake_repeated_a_million_times_is_counted_not_listed(tmp_path: Path) -> None:
    path = tmp_path / "junk.eds"
    path.write_bytes(b"[FileInfo]\n" + b"not ini\n" * 1_000_000)
    got = _lint_in_subprocess(path)
    assert got["rules"]["SYN001"] == 500 and got["omitted"] == {"SYN001": 999500}
    assert got["rss_mb"] < _baseline_mb() + 150, got


def test_deeply_nested_xml_is_refused_in_bounded_memory(tmp_path: Path) -> None:
    depth = 1_000_000
    path = tmp_path / "deep.xdd"
    path.write_bytes(b'<ISO15745ProfileContainer xmlns="http://www.canopen.org/xml/1.1">' + b"<a>" * depth
                     + b"</a>" * depth + b"</ISO15745ProfileContainer>")
    got = _lint_in_subprocess(path)
    assert got["rules"] == {"XML001": 1} and not got["model"], got
    assert got["rss_mb"] < _baseline_mb() + 150, got


def _short_keys(path: Path, keys_per_section: int | None) -> int:
    """16 MiB of `<hex>=1` lines, in one section or in sections of `keys_per_section` keys."""
    lines, size, n = ["[FileInfo]\n"], 11, 0
    while size < 16 * 1024 * 1024 - 64:
        if keys_per_section and n and n % keys_per_section == 0:
            lines.append(f"[S{n}]\n")
            size += len(lines[-1])
        lines.append(f"{n:x}=1\n")
        size += len(lines[-1])
        n += 1
    path.write_text("".join(lines), encoding="ascii")
    return n


@pytest.mark.parametrize("keys_per_section", [None, 60_000], ids=["one-section", "many-sections"])
def test_millions_of_short_keys_stay_under_20_times_the_file_in_memory(tmp_path: Path,
                                                                      keys_per_section: int | None) -> None:
    path = tmp_path / "keys.eds"
    keys = _short_keys(path, keys_per_section)
    size_mb = path.stat().st_size / 2**20
    try:
        got = _lint_in_subprocess(path)
    finally:
        path.unlink()
    assert keys > 1_900_000 and got["model"]
    assert got["rules"]["SYN021"] == 1, got  # the one place where keys stop being kept
    assert got["rss_mb"] < 20 * size_mb, got
