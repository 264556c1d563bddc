"""Generated C is compiled and run: the matrix, golden files, CMake (the corpus: test_corpus_generate.py).

`odgen check` builds the dictionary with the runtime and a generated self-test that
compares every entry with values computed from the description, exercises hooks and
the persistence cycle, and prints `N passed, M failed`.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from odgen import toolchain
from odgen.check import run_check
from odgen.pipeline import Request, generate

from .conftest import FIXTURES, ROOT

GEN = FIXTURES / "generate"
GOLDEN = Path(__file__).resolve().parent / "golden"
ALLTYPES = Request(GEN / "alltypes.eds", options=GEN / "alltypes.toml")
EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
SANITIZE = ("-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-g")
GOLDEN_CASES = {
    "io_node": Request(EXAMPLE),
    "io_node_persist": Request(EXAMPLE, name="io_node_persist", options=EXAMPLE.with_suffix(".toml")),
    "alltypes": ALLTYPES,
    "plain_bsearch": Request(GEN / "plain.eds", name="plain_bsearch", lookup="bsearch"),
}


def _compiler(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is missing: `make test` installs it (make sysdeps)"
    return path


def _assert_passed(outcome) -> None:
    assert outcome.ok, outcome.output[-3000:]
    assert outcome.output.rstrip().endswith("0 failed")


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("lookup", ["switch", "bsearch", "hash"])
def test_all_types_storage_classes_and_hooks(cc: str, lookup: str) -> None:
    request = Request(ALLTYPES.input, options=ALLTYPES.options, lookup=lookup)
    _assert_passed(run_check(request, cc=_compiler(cc)))


def test_a_hash_of_more_than_256_slots_finds_every_entry(tmp_path: Path) -> None:
    """300 entries need a perfect hash of 512 slots, whose tables are uint16_t: the dictionary
    turns ODG_CFG_HASH_WIDE on (a smaller one leaves that path out), and the self-test finds
    every entry through it."""
    base = (GEN / "plain.eds").read_text(encoding="utf-8").split("[ManufacturerObjects]")[0]
    extra = "".join(f"\n[{0x2000 + k:04X}]\nParameterName=Value {k}\nObjectType=0x7\nDataType=0x0007\n"
                    f"AccessType=rw\nDefaultValue={k}\nPDOMapping=0\n" for k in range(300))
    listed = "".join(f"{k + 1}=0x{0x2000 + k:04X}\n" for k in range(300))
    eds = tmp_path / "wide.eds"
    eds.write_text(f"{base}\n[ManufacturerObjects]\nSupportedObjects=300\n{listed}{extra}", encoding="utf-8")
    request = Request(eds, name="wide", lookup="hash")
    assert "#define ODG_CFG_HASH_WIDE 1" in generate(request).files["wide_config.h"]
    assert "#define ODG_CFG_HASH_WIDE 0" in generate(Request(GEN / "plain.eds", lookup="hash")).files["plain_config.h"]
    _assert_passed(run_check(request, cc=_compiler("gcc")))


def test_all_types_under_sanitizers() -> None:
    _assert_passed(run_check(ALLTYPES, cc=_compiler("clang"), cflags=SANITIZE))


def test_persisted_strings_domains_and_a_blank_group_read_their_defaults() -> None:
    """Groups' defaults as spreads of runs (spread.py): a string cut at its trailing zeros, a
    unicode string, 64-bit values, zeros inside runs, a group with no default but zero. The
    self-test reads each default, also after a "load"; under the sanitizers."""
    request = Request(ALLTYPES.input, options=GEN / "alltypes_persisted.toml")
    source = generate(request).files["alltypes.c"]
    assert ".defaults = NULL, .spread = alltypes_persist_blank_spread" in source
    assert "ODG_END(alltypes_persist_app_t, x2009_device_label[20])" in source  # 21 of 41 bytes
    assert "x200B_unicode_label[2])" in source
    _assert_passed(run_check(request, cc=_compiler("clang"), cflags=SANITIZE))


@pytest.mark.parametrize("migration", ["true", "false"])
def test_a_group_of_numbers_whose_defaults_are_all_zero_verifies(migration: str, tmp_path: Path) -> None:
    """A group whose every default is zero has no defaults (`.defaults = NULL`, no runs): its
    numbers lie in its mirror all the same, and odg_verify (run by the self-test) accepts them."""
    base = (GEN / "plain.eds").read_text(encoding="utf-8").split("[ManufacturerObjects]")[0]
    values = ((0x2000, 0x07), (0x2001, 0x0C))  # UNSIGNED32, TIME_OF_DAY
    extra = "".join(f"\n[{index:04X}]\nParameterName=Zero {index:04X}\nObjectType=0x7\nDataType=0x{dtype:04X}\n"
                    "AccessType=rw\nDefaultValue=0\nPDOMapping=0\n" for index, dtype in values)
    eds = tmp_path / "zeros.eds"
    eds.write_text(f"{base}\n[ManufacturerObjects]\nSupportedObjects=2\n1=0x2000\n2=0x2001\n{extra}", encoding="utf-8")
    options = tmp_path / "zeros.toml"
    options.write_text(f'[persist]\nmigration = {migration}\n\n[[entry]]\nmatch = ["0x2000", "0x2001"]\n'
                       'storage = "persist:zeros"\n', encoding="utf-8")
    request = Request(eds, name="zeros", options=options)
    assert ".defaults = NULL, .spread = zeros_persist_zeros_spread" in generate(request).files["zeros.c"]
    _assert_passed(run_check(request, cc=_compiler("gcc")))


@pytest.mark.parametrize("case", sorted(GOLDEN_CASES))
def test_golden_files(case: str) -> None:
    """Set ODGEN_UPDATE_GOLDEN=1 to rewrite tests/golden after an intended change."""
    result = generate(GOLDEN_CASES[case])
    assert result.files
    folder = GOLDEN / case
    if os.environ.get("ODGEN_UPDATE_GOLDEN") == "1":
        folder.mkdir(parents=True, exist_ok=True)
        for name, text in result.files.items():
            (folder / name).write_text(text, encoding="utf-8")
    for name, text in result.files.items():
        assert (folder / name).read_text(encoding="utf-8") == text, f"{case}/{name} changed: review, then update"


def test_hostile_names_give_safe_c(tmp_path: Path) -> None:
    hostile = 'x */ #define BAD 1 /* "q" \\\\ \u00e9' + "A" * 10000
    text = (GEN / "plain.eds").read_text().replace("ParameterName=Speed", f"ParameterName={hostile}")
    path = tmp_path / "hostile.eds"
    path.write_text(text, encoding="utf-8")
    outcome = run_check(Request(path), cc=_compiler("gcc"))
    _assert_passed(outcome)
    for text in generate(Request(path)).files.values():
        assert not any(line.lstrip().startswith("#define BAD") for line in text.splitlines())
        assert all(len(line) < 400 for line in text.splitlines()), "names and comments are clipped"


def test_cmake_firmware_example_builds_and_runs(tmp_path: Path) -> None:
    cmake = _compiler("cmake")
    source = ROOT / "examples" / "cmake-firmware"
    env = dict(os.environ, PATH=f"{ROOT / '.venv' / 'bin'}{os.pathsep}{os.environ.get('PATH', '')}")
    configure = [cmake, "-S", str(source), "-B", str(tmp_path), "-DODGEN_WERROR=ON"]
    for cmd in (configure, [cmake, "--build", str(tmp_path)]):
        done = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
        assert done.returncode == 0, done.stdout + done.stderr
    ran = subprocess.run([str(tmp_path / "firmware")], capture_output=True, text=True, check=False)
    assert ran.returncode == 0 and "looped back" in ran.stdout, ran.stdout + ran.stderr
    assert "0x1017 = 1000 ms read by SDO, operational" in ran.stdout  # odgen::node served it
    # odgen::runtime and odgen::node: the dictionary's NAME_config.h, the toolchain's sources
    for target, sources in (("runtime", toolchain.core_sources()), ("node", toolchain.service_sources())):
        flags = (tmp_path / "CMakeFiles" / f"io_node_od_{target}.dir" / "flags.make").read_text()
        assert '-DODG_CONFIG=\\"io_node_config.h\\"' in flags and "-Werror" in flags, flags
        built = {p.name.removesuffix(".o") for p in (tmp_path / "CMakeFiles").glob(f"io_node_od_{target}.dir/**/*.o")}
        assert built == {p.name for p in sources}
    # odgen::master (the CiA 302 master) is built when linked, or asked for, with -Werror too
    done = subprocess.run([cmake, "--build", str(tmp_path), "--target", "io_node_od_master"], capture_output=True,
                          text=True, env=env, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    built = {p.name.removesuffix(".o") for p in (tmp_path / "CMakeFiles").glob("io_node_od_master.dir/**/*.o")}
    assert built == {p.name for p in toolchain.master_sources()}
    # without ODGEN_WERROR the targets keep the warnings but do not stop on them
    done = subprocess.run([cmake, "-S", str(source), "-B", str(tmp_path / "plain")], capture_output=True, text=True,
                          env=env, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    flags = (tmp_path / "plain" / "CMakeFiles" / "io_node_od_node.dir" / "flags.make").read_text()
    assert "-Wall -Wextra -pedantic" in flags and "-Werror" not in flags, flags
    report = (tmp_path / "odgen" / "io_node" / "io_node-report.html").read_text(encoding="utf-8")
    assert report.startswith("<!DOCTYPE html>") and "0x6200" in report  # REPORT html: the page of the same input


def test_string_longer_than_c99_literal_limit(tmp_path: Path) -> None:
    label = 'DefaultValue=odgen "test" */ label'
    text = (GEN / "alltypes.eds").read_text().replace(label, "DefaultValue=" + "x" * 5000)
    path = tmp_path / "longstring.eds"
    path.write_text(text, encoding="utf-8")
    _assert_passed(run_check(Request(path), cc=_compiler("gcc")))
