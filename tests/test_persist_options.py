"""The options file's [persist] and [[group]] keys (docs/persistence.md) and what generation makes
of them: migration on/off, headroom, pinned regions, the boot status object."""

from __future__ import annotations

from pathlib import Path

import pytest

from odgen.pipeline import Request, generate, run
from odgen.place.options import parse_options
from odgen.diagnostics import Diagnostics
from odgen.place.migration import EntryLayout, GroupLayout
from odgen.place.nvmap import nv_map

from .test_migration_runtime import BASE, eds, options


def parsed(text: str) -> tuple[object, list[str]]:
    diags = Diagnostics()
    result = parse_options(text, "o.toml", diags)
    return result.persist, [f"{d.loc.line}:{d.rule}:{d.message}" for d in diags.items]


def test_persist_keys_read() -> None:
    persist, found = parsed('[persist]\nmigration = false\nheadroom = 100\nstatus_object = 0x2FF0\nalign = 256\n\n'
                            '[[group]]\nname = "app"\nregion = 1024\n')
    assert found == []
    assert persist.align == 256  # type: ignore[attr-defined]
    assert persist.migration is False and persist.headroom == 100  # type: ignore[attr-defined]
    assert persist.status_object == 0x2FF0 and persist.regions == {"app": 1024}  # type: ignore[attr-defined]


def test_persist_defaults() -> None:
    persist, found = parsed("")
    assert found == []
    assert persist.migration is True and persist.headroom == 50 and persist.status_object is None  # type: ignore


@pytest.mark.parametrize("text, line, words", [
    ("[persist]\nmigration = 1\n", 1, "migration 1 must be true or false"),
    ("x = 1\n[persist]\nheadroom = -5\n", 2, "headroom -5 must be a percentage"),
    ("[persist]\nstatus_object = 0x1000\n", 1, "status_object 4096 must be an index in 0x2000..0x5FFF"),
    ("[persist]\nmigrate = true\n", 1, "unknown key migrate in [persist]"),
    ('[[entry]]\nmatch = "*"\n\n[[group]]\nname = "app"\n', 4, "[[group]] needs name and region"),
    ('[[group]]\nname = "app"\nregion = 100\n', 1, "region 100 must be a number of bytes 64..16 MiB"),
    ('[[group]]\nname = "App"\nregion = 128\n', 1, "group name 'App' is not a persistence group name"),
    ("[persist]\nmigration = true\nalign = 100\n", 3, "align 100 must be a power of two 8..32768"),
    ("[persist]\nalign = 65536\n", 2, "align 65536 must be a power of two"),
])
def test_persist_mistakes(text: str, line: int, words: str) -> None:
    _, found = parsed(text)
    assert any(f.startswith(f"{line}:GEN001:") and words in f for f in found), found


def test_nv_map_pinned_and_headroom() -> None:
    layout = GroupLayout("app", tuple(EntryLayout(0x2000 + k, 0, 0x07, 4) for k in range(10)))
    comm = GroupLayout("comm", (EntryLayout(0x1017, 0, 0x06, 2),))
    need = nv_map({"app": layout})["app"].need  # 2 * (24 + 2 + 60 + 40 -> 128) = 256
    assert need == 256
    assert nv_map({"app": layout})["app"].size == 512  # 256 + 50 % -> 512
    assert nv_map({"app": layout}, headroom=0)["app"].size == 256
    pinned = nv_map({"app": layout, "comm": comm}, pinned={"comm": 1024})
    assert pinned["comm"].size == 1024 and pinned["app"].offset == 1024 and pinned["comm"].offset == 0
    assert not nv_map({"app": layout}, pinned={"app": 128})["app"].fits


def test_nv_map_aligned_to_the_erase_page() -> None:
    """[persist] align: every slot starts on a multiple of it (a region holds two, on a multiple)."""
    layout = GroupLayout("app", tuple(EntryLayout(0x2000 + k, 0, 0x07, 4) for k in range(10)))
    comm = GroupLayout("comm", (EntryLayout(0x1017, 0, 0x06, 2),))
    regions = nv_map({"app": layout, "comm": comm}, align=1024)  # a slot is a page: need 2048, + 50 %
    assert regions["comm"].size == 4096 and regions["app"].offset == 4096 and regions["app"].size == 4096
    assert nv_map({"comm": comm}, align=1024, headroom=0)["comm"].size == 2048
    assert nv_map({"app": layout}, align=8)["app"].size == 512  # the default changes nothing


def test_align_goes_into_the_generated_configuration(tmp_path: Path) -> None:
    """The only define a firmware build passes is ODG_CONFIG: the slot alignment is in NAME_config.h,
    and the generated tables check against it that each slot starts on a page."""
    refused, files, _ = generated(tmp_path, "[persist]\nalign = 512\n")
    assert refused == 0
    assert "#define ODG_PERSIST_ALIGN 512u" in files["od_config.h"]
    assert "#define OD_NV_COMM_REGION 2048u" in files["od.h"] and "#define OD_NV_APP_OFFSET 2048u" in files["od.h"]
    assert "ODG_PERSIST_ALIGN" not in generated(tmp_path / "plain", "")[1]["od_config.h"]


def generated(tmp_path: Path, extra: str) -> tuple[int, dict[str, str], list[str]]:
    tmp_path.mkdir(exist_ok=True)
    (tmp_path / "od.eds").write_text(eds(BASE, 1000, False), encoding="utf-8")
    (tmp_path / "od.toml").write_text(options(BASE, extra), encoding="utf-8")
    result = generate(Request(tmp_path / "od.eds", name="od", options=tmp_path / "od.toml"))
    return len(result.refused), result.files, [f"{d.rule}:{d.message}" for d in result.diags.items]


def test_generated_nv_map_and_layouts(tmp_path: Path) -> None:
    refused, files, _ = generated(tmp_path, '[[group]]\nname = "comm"\nregion = 256\n')
    assert refused == 0
    h, c = files["od.h"], files["od.c"]
    assert "#define OD_NV_COMM_OFFSET 0u" in h and "#define OD_NV_COMM_REGION 256u" in h
    assert "#define OD_NV_APP_OFFSET 256u" in h and "#define OD_PERSIST_MIGRATION 1" in h
    assert ".n_layout = 3u" in c  # the layout descriptor's records, read by the runtime from the tables
    assert ".persist_status" not in c


def test_generated_without_migration_and_with_status(tmp_path: Path) -> None:
    refused, files, _ = generated(tmp_path, "[persist]\nmigration = false\nstatus_object = 0x2FF0\n")
    assert refused == 0
    h, c = files["od.h"], files["od.c"]
    assert ".n_layout = 0u" in c and "#define OD_PERSIST_MIGRATION 0" in h
    assert ".persist_status = 0x2FF0" in c and "0x2FF0" in h


@pytest.mark.parametrize("extra, words", [
    ("[persist]\nstatus_object = 0x2001\n", "status_object 0x2001 is an object of the description"),
    ('[[group]]\nname = "app"\nregion = 64\n', "persistence group app needs"),
    ('[[group]]\nname = "nosuch"\nregion = 64\n', "[[group]] nosuch names no persistence group"),
    ('[persist]\nalign = 256\n\n[[group]]\nname = "app"\nregion = 768\n', "is not a multiple of [persist] align"),
    ('[[group]]\nname = "app"\nregion = 192\n', "is not a power of two; with migration a group looks for its "
     "images at the middle of power-of-two regions (docs/persistence.md, section 1): pin 128 or 256 bytes"),
])
def test_generation_refuses(tmp_path: Path, extra: str, words: str) -> None:
    refused, files, found = generated(tmp_path, extra)
    assert refused and files == {}
    assert any(f.startswith("GEN001:") and words in f for f in found), found


def test_status_object_is_linted_like_the_description(tmp_path: Path) -> None:
    """odgen's own boot status object is added when the description is loaded, before lint, and is
    declared as the description would declare it (SubNumber, an object-list entry): lint sees it and
    finds nothing wrong with it."""
    (tmp_path / "od.eds").write_text(eds(BASE, 1000, False), encoding="utf-8")
    (tmp_path / "od.toml").write_text(options(BASE, "[persist]\nstatus_object = 0x2FF0\n"), encoding="utf-8")
    result = run(Request(tmp_path / "od.eds", name="od", options=tmp_path / "od.toml"), until="lint")
    assert result.od is not None and 0x2FF0 in result.od.objects  # the model lint was given
    assert not [d for d in result.diags.items if d.index == 0x2FF0], result.diags.items
    listed = result.od.object_lists["manufacturerobjects"]
    assert listed.entries[-1].text == "0x2FF0" and listed.supported is not None
    assert int(listed.supported.text) == len(listed.entries)
    reread = Path(tmp_path / "od.eds").read_text(encoding="utf-8")
    assert "2FF0" not in reread.upper()  # the description itself is not changed


def test_aligned_build_passes_its_self_test(tmp_path: Path) -> None:
    """A dictionary generated with [persist] align builds with ODG_CONFIG alone (its tables check
    each slot's alignment at compile time) and its self-test, persistence included, passes."""
    import subprocess
    import sys
    (tmp_path / "od.eds").write_text(eds(BASE, 1000, False), encoding="utf-8")
    (tmp_path / "od.toml").write_text(options(BASE, "[persist]\nalign = 256\n"), encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "odgen", "check", str(tmp_path / "od.eds"), "--options",
                           str(tmp_path / "od.toml"), "--keep", str(tmp_path / "build")],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert "#define ODG_PERSIST_ALIGN 256u" in next((tmp_path / "build").rglob("od_config.h")).read_text()
