"""`odgen profile ds401`: CiA 401 descriptions from channel counts (docs/ds401.md)."""

from __future__ import annotations

import dataclasses
import subprocess
from pathlib import Path

import pytest

from odgen.toolchain import CORE_SOURCES
from odgen.cli import main
from odgen.codegen.check import run_check
from odgen.codegen.generate import Request
from odgen.formats import load_path
from odgen.model import ObjectDictionary
from odgen.profiles.ds401 import (MAX_ANALOG, MAX_DIGITAL, Ds401, build, generate_c, mapping_layout, options_toml,
                                  write)

from .conftest import CORPUS, ROOT, lint
from .cprog import BUILDS, EXTRA, STRICT, build as build_c, compiler, run

RUNTIME = ROOT / "runtime"

GRID = {
    "none": Ds401(),
    "one-each": Ds401(1, 1, 1, 1),
    "16-16-4-4": Ds401(16, 16, 4, 4),
    "8bit": Ds401(16, 16, 4, 4, ai_width=8, ao_width=8),
    "32bit": Ds401(16, 16, 6, 6, ai_width=32, ao_width=32),
    "uneven": Ds401(9, 3, 13, 5, ai_width=16, ao_width=32),
    "di-only-max": Ds401(di=MAX_DIGITAL),
    "maxima": Ds401(MAX_DIGITAL, MAX_DIGITAL, MAX_ANALOG, MAX_ANALOG),
}
PROCESS = {8: (0x6400, 0x6410), 16: (0x6401, 0x6411), 32: (0x6402, 0x6412)}


def _mapped(od: ObjectDictionary, map_index: int) -> list[tuple[int, int, int]]:
    obj = od.objects[map_index]
    count = obj.subs[0].default.parsed
    out = []
    for s in range(1, count + 1):
        raw = obj.subs[s].default.parsed
        out.append((raw >> 16, (raw >> 8) & 0xFF, raw & 0xFF))
    return out


@pytest.mark.parametrize("spec", GRID.values(), ids=GRID.keys())
def test_lint_clean_and_byte_identical(spec: Ds401, tmp_path: Path) -> None:
    path = tmp_path / "io.eds"
    first = write(spec, path)
    result = lint(path)
    assert [d.text() for d in result.diagnostics] == []
    write(spec, path)
    assert path.read_text(encoding="utf-8") == first
    assert "Date" not in first and "Time=" not in first  # nothing that changes between runs


@pytest.mark.parametrize("spec", GRID.values(), ids=GRID.keys())
def test_device_type_and_pdo_layout(spec: Ds401) -> None:
    od = build(spec)
    bits = [16 * bool(spec.di), 17 * bool(spec.do), 18 * bool(spec.ai), 19 * bool(spec.ao)]
    assert od.objects[0x1000].subs[0].default.parsed == 0x0191 | sum(1 << b for b in bits if b)
    ai_obj, ao_obj = PROCESS[spec.ai_width][0], PROCESS[spec.ao_width][1]
    per_ai, per_ao = min(4, 64 // spec.ai_width), min(4, 64 // spec.ao_width)
    expected = {
        0x1A00: [(0x6000, s, 8) for s in range(1, min(spec.channels("di"), 8) + 1)],
        0x1600: [(0x6200, s, 8) for s in range(1, min(spec.channels("do"), 8) + 1)],
        **{0x1A01 + n: [(ai_obj, s, spec.ai_width) for s in range(n * per_ai + 1, min(spec.ai, (n + 1) * per_ai) + 1)]
           for n in range(3)},
        **{0x1601 + n: [(ao_obj, s, spec.ao_width) for s in range(n * per_ao + 1, min(spec.ao, (n + 1) * per_ao) + 1)]
           for n in range(3)},
    }
    for map_index, entries in expected.items():
        assert _mapped(od, map_index) == entries, hex(map_index)
        assert sum(bits for _, _, bits in entries) <= 64
        for index, sub, _ in entries:
            assert od.find(index, sub).pdo_mapping
        cob = od.objects[map_index - 0x200].subs[1].default
        assert cob.nodeid and bool(cob.parsed & 0x80000000) == (not entries), hex(map_index)
        kind_base = 0x180 if map_index >= 0x1A00 else 0x200
        assert cob.parsed & 0x7FF == kind_base + 0x100 * (map_index & 3)
    assert {k: v for k, v in mapping_layout(spec).items() if v} == {k - 0x200: v for k, v in expected.items() if v}


def test_ds401_16_16_4_4_is_the_cia401_default_mapping() -> None:
    od = build(GRID["16-16-4-4"])
    assert _mapped(od, 0x1A00) == [(0x6000, 1, 8), (0x6000, 2, 8)]
    assert _mapped(od, 0x1600) == [(0x6200, 1, 8), (0x6200, 2, 8)]
    assert _mapped(od, 0x1A01) == [(0x6401, s, 16) for s in range(1, 5)]
    assert _mapped(od, 0x1601) == [(0x6411, s, 16) for s in range(1, 5)]
    assert _mapped(od, 0x1A02) == _mapped(od, 0x1602) == []
    assert od.objects[0x1000].subs[0].default.text == "0x000F0191"
    assert od.objects[0x1200].subs[1].default.text == "$NODEID+0x600"


def _changed(a: Ds401, b: Ds401) -> set[int]:
    one, two = build(a).objects, build(b).objects
    return {i for i in one.keys() | two.keys() if one.get(i) != two.get(i)}


@pytest.mark.parametrize(("change", "expected"), [
    ({"di": 24}, {0x6000, 0x6002, 0x6006, 0x6007, 0x6008, 0x1A00}),
    ({"di": 15}, set()),  # still two 8-bit groups
    ({"do": 8}, {0x6200, 0x6202, 0x6206, 0x6207, 0x1600}),
    ({"ai": 5}, {0x6401, 0x6421, 0x6424, 0x6425, 0x6426, 0x1802, 0x1A02}),
    ({"ao": 3}, {0x6411, 0x6443, 0x6444, 0x1601}),
    ({"ai_width": 32}, {0x6401, 0x6402, 0x1A01, 0x1802, 0x1A02}),
    ({"vendor_id": 0x1234}, {0x1018}),
])
def test_a_change_changes_only_what_it_must(change: dict, expected: set[int]) -> None:
    base = GRID["16-16-4-4"]
    assert _changed(base, dataclasses.replace(base, **change)) == expected


# 0x6000-0x6FFF differences from kacanopen__CiA_profiles_401.eds; each is explained in docs/ds401.md.
SAMPLE_DIFFERENCES = {
    (0x6400, "pdo_mapping"): (True, False),
    (0x6402, "pdo_mapping"): (True, False),
    (0x6402, "access"): ("ro", "rwr"),
    (0x6410, "pdo_mapping"): (True, False),
    (0x6412, "pdo_mapping"): (True, False),
}


def test_profile_objects_agree_with_the_cia401_sample() -> None:
    sample = CORPUS / "kacanopen__CiA_profiles_401.eds"
    if not sample.is_file():
        pytest.skip("../shared/corpus is absent")
    ref, _ = load_path(sample)
    assert ref is not None
    found: dict[tuple[int, str], tuple[object, object]] = {}
    for width in (8, 16, 32):
        od = build(Ds401(8, 8, 2, 2, width, width))
        for obj in od.sorted_objects():
            if not 0x6000 <= obj.index <= 0x6FFF:
                continue
            theirs = ref.objects.get(obj.index)
            assert theirs is not None, f"0x{obj.index:04X} is not in the CiA 401 sample"
            assert obj.object_code == theirs.object_code, hex(obj.index)
            for sub in obj.subs.values():
                other = theirs.subs.get(sub.subindex)
                if other is None:  # the sample declares fewer channels of some objects
                    assert sub.subindex > 1, f"0x{obj.index:04X}sub{sub.subindex}"
                    continue
                for attr in ("data_type", "access", "pdo_mapping"):
                    if getattr(sub, attr) != getattr(other, attr):
                        found[(obj.index, attr)] = (getattr(sub, attr), getattr(other, attr))
    assert found == SAMPLE_DIFFERENCES


@pytest.mark.parametrize("name", ["16-16-4-4", "uneven", "maxima"])
def test_generated_c_passes_odgen_check(name: str, tmp_path: Path) -> None:
    spec = GRID[name]
    path = tmp_path / "io.eds"
    write(spec, path)
    outcome = run_check(Request(path, defaults=options_toml(spec)))
    assert outcome.ok, outcome.output[-2000:]
    assert not [d.text() for d in outcome.result.diags if d.severity > 0]
    header = outcome.result.files["io.h"]
    for index in (0x6000, 0x6200, PROCESS[spec.ai_width][0], PROCESS[spec.ao_width][1]):
        assert f"IO_IDX_X{index:04X}" in header


def test_cli_writes_eds_and_c(tmp_path: Path) -> None:
    out, gen = tmp_path / "io.eds", tmp_path / "gen"
    args = ["profile", "ds401", "--di", "16", "--do", "16", "--ai", "4", "--ao", "4", "--vendor-id", "0x1234",
            "--name", "Test I/O", "-o", str(out), "--generate", str(gen)]
    assert main(args) == 0
    assert sorted(p.name for p in gen.iterdir()) == ["ds401_app.h", "io.c", "io.h", "io_config.h"]
    assert out.read_text(encoding="utf-8") == write(Ds401(16, 16, 4, 4, name="Test I/O", vendor_id=0x1234), out)
    assert main(["lint", "--strict", str(out)]) == 0


@pytest.mark.parametrize("bad", [["--di", "-1"], ["--do", str(MAX_DIGITAL + 1)], ["--ai", "255"],
                                 ["--ao", "x"], ["--ai-width", "12"], ["--vendor-id", "0x100000000"]])
def test_cli_bad_arguments_exit_2(bad: list[str], tmp_path: Path) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["profile", "ds401", *bad, "-o", str(tmp_path / "x.eds")])
    assert exc.value.code == 2
    assert not (tmp_path / "x.eds").exists()


def test_cli_refuses_other_suffix(tmp_path: Path) -> None:
    assert main(["profile", "ds401", "-o", str(tmp_path / "x.xdd")]) == 2


DS401_TESTS = ROOT / "tests" / "ds401"
DS401_GLUE = RUNTIME / "profiles" / "ds401.c"


@pytest.fixture(scope="module")
def io_16_16_4_4(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """`--generate` output for 16 DI / 16 DO / 4 AI / 4 AO: io.[ch] and ds401_app.h."""
    gen = tmp_path_factory.mktemp("ds401")
    spec = GRID["16-16-4-4"]
    write(spec, gen / "io.eds")
    result = generate_c(spec, gen / "io.eds")
    assert sorted(result.files) == ["ds401_app.h", "io.c", "io.h", "io_config.h"]
    for name, text in result.files.items():
        (gen / name).write_text(text, encoding="utf-8")
    return gen


@pytest.mark.parametrize("build_name", list(BUILDS))
def test_glue_change_of_state_on_a_node(build_name: str, io_16_16_4_4: Path, tmp_path: Path) -> None:
    """tests/ds401/test_ds401_app.c: hooks, polarity, 0x6005-0x6008 and 0x6421-0x6426 events,
    remapped TPDOs and transmission type 0, over the fake transport."""
    cc, flags = BUILDS[build_name]
    gen = io_16_16_4_4
    sources = (DS401_TESTS / "test_ds401_app.c", DS401_GLUE, gen / "io.c",
               *(RUNTIME / s for s in (*CORE_SOURCES, "odg_node.c", "odg_sdo.c", "odg_pdo.c", "odg_err.c",
                                       "odg_sync.c", "odg_hb.c", "odg_lss.c", "odg_time.c")))
    exe = tmp_path / "test_ds401_app"
    build_c(cc, (*flags, "-DODG_NODE_TPDO_COS=0"), sources, (gen, RUNTIME, ROOT / "tests" / "node",
                                                            ROOT / "tests" / "runtime"), exe)
    run(exe, tmp_path)


@pytest.mark.parametrize("name", list(GRID))
@pytest.mark.parametrize("cc", ["gcc", "clang"])
def test_glue_compiles_warning_free(name: str, cc: str, tmp_path: Path) -> None:
    """runtime/profiles/ds401.c configured by every grid point's header, under the strict and extra warnings."""
    spec = GRID[name]
    write(spec, tmp_path / "io.eds")
    result = generate_c(spec, tmp_path / "io.eds")
    for file_name, text in result.files.items():
        (tmp_path / file_name).write_text(text, encoding="utf-8")
    cmd = [compiler(cc), *STRICT, *EXTRA, "-O1", f"-I{RUNTIME}", f"-I{tmp_path}", "-c", str(DS401_GLUE), "-o",
           str(tmp_path / "ds401_app.o")]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert generate_c(spec, tmp_path / "io.eds").files == result.files  # deterministic
