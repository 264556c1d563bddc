"""Regressions: sequences through the C runtime (tests/runtime/model_main.c) after which a boot
once served a value of an older store, against rule 1 of docs/persistence.md ("newest or
default"): power cuts while a store writes over the newest image's tail, and a stored
OCTET_STRING holding an image of its own group. Each asserts the values served explicitly: the
model's checker is lenient about images past NAME_NV_SIZE, and run_script does not tell it which
steps a power cut interrupts. The power cut in the store home of a loaded image is
test_persist_sequences.py's test_a_power_cut_while_the_newest_is_written_over_never_serves_an_older_store."""

from __future__ import annotations

import re
import shutil
import struct
import zlib
from pathlib import Path

import pytest

from .persist_model import DAMAGED, I16, LOADED, LOST_BITS, U16, U32, VS, Param, Version, build, run_script, saves
from .persist_model import version as app

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")

OCTET_STRING = 0x0A


def test_a_power_cut_in_a_rollback_s_first_boot_serves_no_older_store(tmp_path: Path) -> None:
    """Default regions on one NV of v1's NAME_NV_SIZE: v1 adds an ARRAY of 3 UNSIGNED16 to comm
    (region 128 -> 256) and stores 0x1017 = 1, 2, 3 (slot B, A, B after its migration store;
    the last in slot A, 72 bytes, past v0's slot B at byte 64). v0's first boot migrates it and
    stores it into slot B, erasing slot A's last 8 bytes; a power cut there leaves slot A's header
    naming region 256, and the next boot takes 2 from v1's slot B (byte 128, in v0's aux region,
    which aux had not cleared yet)."""
    v0 = app(Param(0x2000, I16, "aux", 0), Param(0x2009, U16, "aux", 0))
    v1 = app(Param(0x2000, I16, "aux", 0), Param(0x2009, U16, "aux", 0), Param(0x2003, U16, "comm", 1, elements=3))
    cmds = ["nv 512", "boot 0", "boot 1", *saves(0x1017, ["0100", "0200", "0300"]), "cut 0", "boot 0", "power",
            "boot 0"]
    violations, boots, _ = run_script([v0, v1], cmds, tmp_path)
    assert boots[-1].values[(0x1017, 0)] in ("0300", "E803")
    assert not [v for v in violations if v.rule == "R1"], "\n".join(map(str, violations))


def test_a_power_cut_in_the_rollback_s_migration_store_serves_no_older_store(tmp_path: Path) -> None:
    """v2 adds a bulk array to app (default region 2048), v1 has none (128); v1's aux region
    (pinned 2048) covers v2's app slot B, so every image lies inside v1's NAME_NV_SIZE. v2 stores
    1, 2, 3 (slot B, A, B... the last in slot A, reaching past v1's region). v1's first boot
    migrates it and stores it into slot B, erasing the tail of slot A; a power cut there leaves
    slot A's header naming region 2048, and the next boot takes 2 from v2's slot B."""
    bulk = Param(0x2200, U32, "app", 1, elements=30)
    v1 = app(Param(0x2000, U32, "app", 0), Param(0x2001, U32, "aux", 0), pins={"aux": 2048})
    v2 = app(Param(0x2000, U32, "app", 0), bulk, Param(0x2001, U32, "aux", 0))
    cmds = ["nv 2304", "boot 0", "boot 1", *saves(0x2000, ["01000000", "02000000", "03000000"]),
            "cut 0", "boot 0", "power", "boot 0", "boot 0"]
    _, boots, _ = run_script([v1, v2], cmds, tmp_path)
    assert [b.values[(0x2000, 0)] for b in boots[-2:]] in (["03000000"] * 2, ["00000000"] * 2)


def test_a_power_cut_in_a_save_after_a_rollback_serves_no_older_store(tmp_path: Path) -> None:
    """app's string of 200 bytes in a region of 512 (v1), 8 bytes in 256 (v2). v1 stores "aa"
    (slot B, byte 256) and "bb" (slot A, 232 bytes). v2 loads "bb" unchanged and inside its region
    (not stored home), but it reaches into v2's slot B (byte 128). v2's next save erases slot B,
    so the tail of its newest image: a power cut there, and the next boot serves "aa", which the
    broken slot A's header still names (LOADED, no loss reported)."""
    v1 = app(Param(0x2000, VS, "app", "ab", capacity=200), pins={"app": 512})
    v2 = app(Param(0x2000, VS, "app", "ab", capacity=8), pins={"app": 256})
    cmds = ["nv 4096", "boot 0", *saves(0x2000, ["6161", "6262"]), "boot 1", "set 2000 00 6363", "cut 0", "save",
            "power", "boot 1"]
    _, boots, _ = run_script([v1, v2], cmds, tmp_path)
    assert boots[-1].values[(0x2000, 0)][:4] in ("6262", "6363", "6162")


def test_a_stored_octet_string_is_never_taken_for_an_image(tmp_path: Path) -> None:
    """An OCTET_STRING value holding a valid image of its own group (plain group id, header
    naming region 128) at byte 64 of slot A, a place the walk visits for slot B of a region of
    128: the next boot takes it as the newest and serves 0x2001 = 0x0BAD, never stored."""
    v1 = app(Param(0x2000, OCTET_STRING, "app", "", capacity=100), Param(0x2001, U32, "app", 0))
    payload = _octet_string_holding_an_image([v1], tmp_path / "ids", 100)
    run = tmp_path / "run"
    run.mkdir()
    _, boots, _ = run_script([v1], ["nv 4096", "boot 0", f"set 2000 00 {payload}", "save", "save", "boot 0"], run)
    assert boots[-1].values[(0x2001, 0)] == "00000000"
    assert boots[-1].values[(0x2000, 0)] == payload.upper()


def _octet_string_holding_an_image(vs: list[Version], work: Path, capacity: int) -> str:
    """An OCTET_STRING value of `capacity` bytes (hex) holding, from its byte 26, a valid image of
    group app (plain group id, header naming region 128) that serves 0x2001 = 0x0BAD: once stored
    in slot A, after the slot header and the record count and records before it (38 bytes), the
    image lies at byte 64, a place the walk visits for slot B of a region of 128."""
    work.mkdir()
    build(vs, work)
    found = re.search(r"_NV_APP_REGION, \.id = 0x([0-9A-F]+)u", (work / "v0.c").read_text(encoding="utf-8"))
    assert found is not None
    image = struct.pack("<H", 1) + struct.pack("<HBBH", 0x2001, 0, U32, 4) + struct.pack("<I", 0xBAD)
    head = b"ODG2" + struct.pack("<IIII", 1000, int(found.group(1), 16), 128, len(image))
    payload = bytes(26) + head + struct.pack("<I", zlib.crc32(head + image)) + image  # 38 + 26 = byte 64
    return (payload + bytes(capacity - len(payload))).hex()


def test_a_store_that_erases_an_image_past_its_region_leaves_the_next_group_its_loss(tmp_path: Path) -> None:
    """v1 has comm (256 bytes) and app (256 bytes, after it); v2 has comm alone in 512 bytes, and
    its stores lie over app's region. v1 stores app, v2 boots (comm's migrated image in its slot
    B, over app's region) and stores (comm's newest in slot A, reaching past v1's comm region).
    Back on v1, comm's store writes over that newest, and first invalidates its own older image
    in app's region: app must still see that its region held another group's bytes (DAMAGED,
    the loss reported), not a blank region (a first boot). A load by v2 instead of the store
    gives the same."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"comm": 256, "app": 256})
    v2 = app(*[Param(0x2100 + k, U32, "comm", 0) for k in range(20)], pins={"comm": 512})
    for last in ("save", "load"):
        work = tmp_path / last
        work.mkdir()
        violations, boots, _ = run_script([v1, v2], ["nv 2048", "boot 0", *saves(0x2000, ["05000000"]), "boot 1",
                                                     last, "boot 0"], work)
        assert not violations, "\n".join(map(str, violations))
        back = boots[-1]
        assert back.groups[0]["status"] == DAMAGED and back.seen[0] & LOST_BITS  # app (the groups by name)
        assert back.values[(0x2000, 0)] == "00000000"


def _windowed_octet_string(tmp_path: Path) -> tuple[list[Version], list[str]]:
    """v2 (app pinned to 512) stores an OCTET_STRING of 200 bytes holding, at byte 64 of slot A,
    a valid image of its own group (plain group id, header naming region 128) that serves 0x2001
    = 0x0BAD; v1 (app pinned to 128) sees through its driver only its own 256 bytes of NV, so
    slot A's image runs past them: v1 cannot check it, and byte 64 is v1's slot B."""
    v1 = app(Param(0x2001, U32, "app", 0), pins={"app": 128})
    v2 = app(Param(0x2000, OCTET_STRING, "app", "", capacity=200), Param(0x2001, U32, "app", 0), pins={"app": 512})
    payload = _octet_string_holding_an_image([v1, v2], tmp_path / "ids", 200)
    return [v1, v2], ["nv 640", "boot 1", f"set 2000 00 {payload}", "save", "save", "window 256"]


def test_an_octet_string_in_a_slot_a_image_past_a_windowed_rollback_s_nv_is_never_taken(tmp_path: Path) -> None:
    """The boot takes no image inside slot A's image also when it cannot read that image to its
    end (past the NV its driver shows): its header says how far it goes. v1 boots DAMAGED (v2's
    values are lost to it) with the default, never 0x0BAD; its store home goes to slot B and
    the unreadable slot A's header goes after it, so the next boot loads that store."""
    versions, steps = _windowed_octet_string(tmp_path)
    run = tmp_path / "run"
    run.mkdir()
    violations, boots, _ = run_script(versions, [*steps, "boot 0", "boot 0", "set 2001 00 05000000", "save", "boot 0"],
                                      run)
    assert not violations, "\n".join(map(str, violations))
    rollback, again, saved = boots[1:]
    assert rollback.values[(0x2001, 0)] == "00000000"
    assert rollback.groups[0]["status"] == DAMAGED and rollback.seen[0] & LOST_BITS
    assert again.groups[0]["status"] == LOADED and not again.seen[0] & LOST_BITS
    assert saved.groups[0]["status"] == LOADED and saved.values[(0x2001, 0)] == "05000000"


def test_a_power_cut_in_that_rollback_s_boot_never_serves_the_octet_string_s_image(tmp_path: Path) -> None:
    """As above, with the power cut at every fifth byte v1's first boot programs or erases (its
    store home, then the erase of slot A's header): the boot after serves the default or what
    that store wrote, never 0x0BAD, and the boot after it loads."""
    versions, steps = _windowed_octet_string(tmp_path)
    cuts = range(0, 200, 5)
    run = tmp_path / "run"
    run.mkdir()
    commands = [c for n in cuts for c in (*steps, f"cut {n}", "boot 0", "power", "boot 0", "boot 0")]
    _, boots, _ = run_script(versions, commands, run)
    per = len(boots) // len(cuts)
    for k in range(len(cuts)):
        after, last = boots[k * per + per - 2], boots[k * per + per - 1]
        assert after.values[(0x2001, 0)] == "00000000" and last.values[(0x2001, 0)] == "00000000", cuts[k]
        assert last.groups[0]["status"] == LOADED, (cuts[k], last.groups)
