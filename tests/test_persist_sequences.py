"""The firmware sequences of the persistence issue, each a regression test through the C runtime
(tests/runtime/model_main.c), checked against the rule set of docs/persistence.md by the model
of tests/persist_model.py and against what each sequence got wrong."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from .persist_model import (DAMAGED, DEFAULTS, LOADED, LOST_BITS, MIGRATED, NV_ERROR, U8, U16, U32, VS, Param,
                            Version, run_script, saves)
from .persist_model import version as app

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")

SAVE_OK = "save 00000000"
LOAD_OK = "load 00000000"


def small() -> Version:
    return app(Param(0x2000, U8, "app", 1), Param(0x2001, U16, "app", 2))


def grown(n: int) -> Version:
    v = small()
    v.params.update({0x2002 + k: Param(0x2002 + k, U32, "app", 3) for k in range(n)})
    return v


def test_sequence_2_a_rollback_never_locks_a_group(tmp_path: Path) -> None:
    """v1 {U8, U16}; v2 adds 40 UNSIGNED32; the NV driver shows each firmware its NAME_NV_SIZE.
    v1 store -> v2 boot -> v2 store -> v1 boot: v1's save and load work, and its next boot loads."""
    sizes = ("window 384", "window 2176")
    violations, boots, answers = run_script([small(), grown(40)], [
        "nv 384", "boot 0", "set 2000 00 05", "save", sizes[1], "boot 1", "set 2001 00 0700", "save", sizes[0],
        "boot 0", "save", "load", "boot 0", "set 2000 00 09", "save", "boot 0"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    rollback = boots[2]
    assert rollback.groups[0]["status"] != NV_ERROR and rollback.seen[0] & LOST_BITS  # v2's image: a loss
    assert answers[-4:] == [SAVE_OK, LOAD_OK, "set 00000000", SAVE_OK]
    assert boots[-1].groups[0]["status"] == LOADED and boots[-1].values[(0x2000, 0)] == "09"


def test_sequence_3_a_moved_group_is_never_served_a_stale_image(tmp_path: Path) -> None:
    """v1 comm {0x1017} in 128 bytes, app in 256; v2's comm takes 256, so app's region starts at
    its old slot B. App stored four times (1..4): v2 never serves 3, and says what it lost."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"comm": 128, "app": 256})
    v2 = app(Param(0x2000, U32, "app", 0), pins={"comm": 256, "app": 256})
    stores = saves(0x2000, [f"{k:02X}000000" for k in range(1, 5)])
    violations, boots, _ = run_script([v1, v2], ["nv 512", "boot 0", *stores, "boot 1", "boot 1"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    moved = boots[1]
    assert moved.values[(0x2000, 0)] in ("04000000", "00000000")
    assert moved.groups[0]["status"] == DAMAGED and moved.seen[0] & LOST_BITS
    assert boots[2].groups[0]["status"] == LOADED and not boots[2].seen[0] & LOST_BITS


def test_an_image_loaded_from_past_the_region_is_moved_home(tmp_path: Path) -> None:
    """v1 pins comm to 256 bytes, v2 to 128 with app right after it: comm's newest store, in v1's
    slot B (byte 128), lies in v2's app region. v2 loads it unchanged (LOADED), and must move it
    home before app's boot (its defaults stored, its region cleared) writes over it; else the next
    boot serves comm's store before (slot A)."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"comm": 256, "app": 512})
    v2 = app(Param(0x2000, U32, "app", 0), pins={"comm": 128, "app": 512})
    stores = saves(0x1017, ["0100", "0200", "0300"])  # slots B, A, B
    violations, boots, answers = run_script([v1, v2], ["nv 1024", "boot 0", *stores, "boot 1", "boot 1", "boot 1"],
                                            tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert answers.count(SAVE_OK) == 3
    for boot in boots[1:]:
        assert boot.values[(0x1017, 0)] == "0300"
        assert boot.groups[1]["status"] == LOADED  # comm (the groups by name: app, comm)


def string_shrinks() -> list[Version]:
    """v1 gives app a string of 200 bytes in a region of 1024, v2 one of 8 in 128, with aux after
    it (STRING_STORES stores "aa" in slot B, then "bb" in slot A: 232 bytes, past v2's region)."""
    return [app(Param(0x2000, VS, "app", "ab", capacity=200), Param(0x2001, U32, "aux", 0), pins={"app": 1024}),
            app(Param(0x2000, VS, "app", "ab", capacity=8), Param(0x2001, U32, "aux", 0), pins={"app": 128})]


STRING_STORES = saves(0x2000, [b"aa".hex(), b"bb".hex()])


def test_an_image_loaded_that_reaches_past_the_region_is_moved_home(tmp_path: Path) -> None:
    """v1 gives app a string of 200 bytes in a region of 1024, v2 one of 8 in 128, with aux after
    it: app's newest store, in slot A, is loaded unchanged (its short string fits) but reaches past
    v2's region into aux's; it must be stored home before aux's boot clears it, else the next boot
    serves app's store before (slot B of the old region, which slot A's header names)."""
    violations, boots, _ = run_script(string_shrinks(), ["nv 4096", "boot 0", *STRING_STORES, "boot 1", "boot 1"],
                                      tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert [b.values[(0x2000, 0)][:4] for b in boots[1:]] == ["6262", "6262"]


def test_a_power_cut_while_the_newest_is_written_over_never_serves_an_older_store(tmp_path: Path) -> None:
    """As above: app's newest store (slot A, string capacity 200) reaches into slot B of v2's
    smaller region, so v2's store home writes over it. A power cut at any point of that store
    leaves the newest, the new image, or neither; with neither, the boot must not find app's
    older store (slot B of the old region, past v2's NV, which slot A's header names): it
    reports the loss (DAMAGED) with the default."""
    cuts = range(0, 420, 4)
    commands = [c for n in cuts for c in ("nv 4096", "boot 0", *STRING_STORES, f"cut {n}", "boot 1", "power", "boot 1")]
    _, boots, _ = run_script(string_shrinks(), commands, tmp_path)
    after = boots[2::3]  # the boot after each power cut
    assert len(after) == len(cuts)
    served = {(b.values[(0x2000, 0)][:4], b.groups[0]["status"]) for b in after}
    assert served <= {("6262", LOADED), ("6162", DAMAGED)}, served  # "bb", or the default and the loss
    assert ("6162", DAMAGED) in served  # some cut fell inside the store


def test_a_power_cut_in_a_load_serves_the_newest_or_the_defaults_never_an_older_store(tmp_path: Path) -> None:
    """A load stores its mark as a save stores an image. App stores 1, 2, 3 (slots A, B, A: the
    older 2 beside the newest, where the mark goes); a power cut at any NV step of the load
    leaves 3 (LOADED) or the mark (DEFAULTS), never 2 or 1."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"app": 256})
    stores = saves(0x2000, ["01000000", "02000000", "03000000"])
    cuts = range(0, 400, 3)
    commands = [c for n in cuts for c in ("nv 4096", "boot 0", *stores, f"cut {n}", "load", "power", "boot 0")]
    _, boots, _ = run_script([v1], commands, tmp_path)
    after = boots[1::2]  # the boot after each power cut
    served = {(b.values[(0x2000, 0)], b.groups[0]["status"]) for b in after}
    assert served <= {("03000000", LOADED), ("00000000", DEFAULTS)}, served
    assert ("03000000", LOADED) in served and ("00000000", DEFAULTS) in served  # cuts before and after the mark


def test_a_rollback_finds_the_load_mark_past_its_nv_and_stores_after_it(tmp_path: Path) -> None:
    """v2 (app pinned to 512 bytes) boots (its defaults in slot A), stores 1 (slot B) and 2 (slot
    A), and loads: the mark goes to slot B, past v1's NAME_NV_SIZE (app pinned to 256). v1 finds
    it through slot A's header (DEFAULTS), and its own stores follow it: v1 stores 5, and v2 then
    serves 5. Had the load erased slot A, v1 would not find the mark, would number its stores
    from 1, and v2 would take the mark for the newest and serve the default."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"app": 256})
    v2 = app(Param(0x2000, U32, "app", 0), pins={"app": 512})
    commands = ["nv 4096", "boot 1", *saves(0x2000, ["01000000", "02000000"]), "load", "boot 0",
                *saves(0x2000, ["05000000"]), "boot 1"]
    violations, boots, answers = run_script([v1, v2], commands, tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert LOAD_OK in answers
    assert [(b.values[(0x2000, 0)], b.groups[0]["status"]) for b in boots[1:]] == [
        ("00000000", DEFAULTS), ("05000000", LOADED)]


def test_slot_b_of_a_region_above_64_kib_is_found_when_the_region_changes(tmp_path: Path) -> None:
    """comm pinned to 128 KiB, then to 256 KiB: its newest store, in the old slot B (64 KiB into
    the region), is found by the new firmware although it is at no place of its region."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"comm": 0x20000})
    v2 = app(Param(0x2000, U32, "app", 0), pins={"comm": 0x40000})
    stores = saves(0x1017, ["0100", "0200", "0300"])  # slots B, A, B
    violations, boots, _ = run_script([v1, v2], ["nv 300000", "boot 0", *stores, "boot 1", "boot 1"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert [b.values[(0x1017, 0)] for b in boots[1:]] == ["0300", "0300"]


def test_sequence_4_save_works_after_a_rollback_on_the_same_nv(tmp_path: Path) -> None:
    """v1 app 2 entries; v2 adds 12 UNSIGNED32; one NV for both. v1 store -> v2 boot -> v2
    store -> v1 boot: the drop is reported once, then saves work and nothing more is reported,
    and 0x1017 (group comm) is saved too."""
    violations, boots, answers = run_script([small(), grown(12)], [
        "nv 640", "boot 0", "save", "boot 1", "save", "boot 0", "set 1017 00 F401", "save", "boot 0", "boot 0"],
        tmp_path)
    assert not violations, "\n".join(map(str, violations))
    rollback, after = boots[2], boots[3]
    assert rollback.groups[0]["status"] == MIGRATED and rollback.groups[0]["dropped"] == 12
    assert rollback.seen[0] & 0x80
    assert answers[-1] == SAVE_OK
    assert [g["status"] for g in after.groups] == [LOADED, LOADED] and not after.seen[0] & LOST_BITS
    assert after.values[(0x1017, 0)] == "F401"


def test_sequence_5_the_emcy_says_exactly_what_was_lost(tmp_path: Path) -> None:
    """Adding a parameter loses nothing: MIGRATED, `added` 1, no EMCY bits. A group whose region
    moved onto another group's image (comm's region shrank, app moved into its old slot B)
    boots DAMAGED: a loss, reported; comm finds its image and keeps it."""
    added = app(*small().params.values(), Param(0x2003, U16, "app", 4))
    violations, boots, _ = run_script([small(), added], ["nv 384", "boot 0", "save", "boot 1"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    up = boots[1].groups[0]
    assert (up["status"], up["added"], up["defaulted"]) == (MIGRATED, 1, 0)
    assert not boots[1].seen[0] & LOST_BITS
    pins = '[[group]]\nname = "comm"\nregion = {}\n\n'
    v1 = app(Param(0x2000, U32, "app", 0), options=pins.format(256))
    v2 = app(Param(0x2000, U32, "app", 0), options=pins.format(128))
    moved = tmp_path / "moved"
    moved.mkdir()
    violations, boots, _ = run_script([v1, v2], ["nv 1024", "boot 0", "set 2000 00 07000000", "save", "boot 1"],
                                      moved)
    assert not violations, "\n".join(map(str, violations))
    assert boots[1].values[(0x2000, 0)] == "00000000"
    assert boots[1].groups[0]["status"] == DAMAGED and boots[1].seen[0] & LOST_BITS
    assert boots[1].groups[1]["status"] == LOADED


def test_sequence_6_array_sub0_follows_the_array(tmp_path: Path) -> None:
    """An ARRAY of 4 elements grows to 6 (and back): sub 0 serves the new count, counted as
    converted (no loss); the elements keep their values both ways."""
    four = app(Param(0x2005, U16, "app", 1, elements=4))
    six = app(Param(0x2005, U16, "app", 1, elements=6))
    violations, boots, _ = run_script([four, six], [
        "nv 1024", "boot 0", "set 2005 02 2200", "save", "boot 1", "boot 0"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    grew, shrank = boots[1], boots[2]
    assert grew.values[(0x2005, 0)] == "06" and grew.values[(0x2005, 2)] == "2200"
    assert grew.groups[0]["converted"] == 1 and not grew.seen[0] & LOST_BITS
    # back to 4 elements: the newest image lies past this firmware's NV, so it finds the one the
    # newest was migrated from (the same values; docs/persistence.md)
    assert shrank.values[(0x2005, 0)] == "04" and shrank.values[(0x2005, 2)] == "2200"


def test_an_nv_smaller_than_the_firmware_s_is_an_nv_error_and_save_aborts(tmp_path: Path) -> None:
    violations, boots, answers = run_script([small()], ["nv 383", "boot 0", "save", "nv 384", "boot 0"], tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert all(g["status"] == NV_ERROR for g in boots[0].groups)
    assert answers[1] == "save 08000020"
    assert all(g["status"] == DEFAULTS for g in boots[1].groups)


RECORD = """
[2100]
ParameterName=Settings
ObjectType=0x9
;StorageLocation=PERSIST_COMM
SubNumber=3

[2100sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
;StorageLocation=RAM
DataType=0x0005
AccessType=ro
DefaultValue=2

[2100sub1]
ParameterName=Setting 1
ObjectType=0x7
;StorageLocation=RAM
DataType=0x0007
AccessType=rw
DefaultValue=7

[2100sub2]
ParameterName=Setting 2
ObjectType=0x7
;StorageLocation=RAM
DataType=0x0005
AccessType=rw
DefaultValue=254
"""


def test_sequence_1_canopennode_style_files_persist_their_pdo_settings(tmp_path: Path) -> None:
    """An object-level `;StorageLocation=PERSIST_COMM` places every sub-entry in group comm although
    each says `;StorageLocation=RAM` (CANopenNode's "no preference"); a sub-level group still wins."""
    from odgen.pipeline import Request, prepare

    from .test_migration_runtime import HEADER

    text = HEADER.format(heartbeat=1000).replace("SupportedObjects=3\n1=0x1010", "SupportedObjects=4\n1=0x1010")
    text = text.replace("3=0x1017\n", "3=0x1017\n4=0x2100\n") + RECORD
    text = text.replace("[2100sub2]\nParameterName=Setting 2\nObjectType=0x7\n;StorageLocation=RAM",
                        "[2100sub2]\nParameterName=Setting 2\nObjectType=0x7\n;StorageLocation=PERSIST_APP")
    path = tmp_path / "od.eds"
    path.write_text(text, encoding="utf-8")
    result = prepare(Request(path, name="od"))
    placed = result.placements
    assert placed is not None, [d.text() for d in result.refused]
    assert placed[(0x2100, 0)].storage == "persist:comm" and placed[(0x2100, 1)].storage == "persist:comm"
    assert placed[(0x2100, 2)].storage == "persist:app"


def test_sequence_7_without_migration_tightened_limits_give_the_default(tmp_path: Path) -> None:
    """`[persist] migration = false`: a stored 80 under a HighLimit tightened from 100 to 50 is
    not served as LOADED; it takes its default, the group reports the loss (MIGRATED, defaulted
    1, EMCY bit) and the corrected image is stored."""
    from .test_migration_runtime import Param as P
    from .test_migration_runtime import firmware, run

    off = "[persist]\nmigration = false\n"
    v1, _ = firmware(tmp_path, "v1", (P(0x2000, U8, "7", "0", "100"),), 1000, False, off)
    v2, _ = firmware(tmp_path, "v2", (P(0x2000, U8, "7", "0", "50"),), 1000, False, off)
    nv = tmp_path / "od.nv"
    run(v1, nv, "set:2000:00:50", "store")
    got = run(v2, nv, "dump")
    assert got.values[(0x2000, 0)] == "07"
    assert got.groups[0]["status"] == MIGRATED and got.groups[0]["defaulted"] == 1 and got.seen[0] & 0x80
    again = run(v2, nv, "dump")
    assert again.groups[0]["status"] == LOADED and again.values[(0x2000, 0)] == "07"


PREDICTED = {
    "added": (small(), app(*small().params.values(), Param(0x2003, U16, "app", 4))),
    "removed": (app(*small().params.values(), Param(0x2003, U16, "app", 4)), small()),
    "narrowed": (app(Param(0x2000, U32, "app", 1)), app(Param(0x2000, U16, "app", 1))),
    "widened": (app(Param(0x2000, U16, "app", 1)), app(Param(0x2000, U32, "app", 1))),
    "array_grown": (app(Param(0x2005, U16, "app", 1, elements=4)), app(Param(0x2005, U16, "app", 1, elements=6))),
    "moved_to_erased_nv": (small(), app(*small().params.values(), Param(0x2200, U32, "comm", 1, elements=30))),
    "moved_onto_another_group": (
        app(Param(0x2000, U32, "app", 0), options='[[group]]\nname = "comm"\nregion = 256\n\n'),
        app(Param(0x2000, U32, "app", 0), options='[[group]]\nname = "comm"\nregion = 128\n\n')),
}


@pytest.mark.parametrize("name", list(PREDICTED))
def test_odgen_diff_predicts_what_the_boot_reports(name: str, tmp_path: Path) -> None:
    """docs/diff.md "What a boot will report": per group, the status and whether the storage EMCY
    follows, from `odgen diff --options` alone, against the C runtime's boot of the new version on
    NV the old one saved."""
    from odgen.diff import diff_paths

    from .persist_model import eds, options

    old, new = PREDICTED[name]
    for tag, v in (("old", old), ("new", new)):
        (tmp_path / f"{tag}.eds").write_text(eds(v), encoding="utf-8")
        (tmp_path / f"{tag}.toml").write_text(options(v), encoding="utf-8")
    changes = diff_paths(tmp_path / "old.eds", tmp_path / "new.eds", tmp_path / "old.toml",
                         tmp_path / "new.toml").changes
    work = tmp_path / "run"
    work.mkdir()
    violations, boots, _ = run_script([old, new], ["nv 4096", "boot 0", "save", "boot 1"], work)
    assert not violations, "\n".join(map(str, violations))
    boot = boots[1]
    names = sorted({p.group for p in new.params.values()} | {"comm"})  # NAME_GROUP_* order
    emcy = False
    for n, group in enumerate(names):
        mine = [c for c in changes if f"group '{group}'" in c.message]
        status = boot.groups[n]["status"]
        if any(c.kind == "DIF207" for c in mine):
            assert status in (DEFAULTS, DAMAGED), (group, status)
            emcy = emcy or status == DAMAGED
        elif any(c.kind in ("DIF201", "DIF202", "DIF203", "DIF204") for c in mine):
            assert status == MIGRATED, (group, status, [c.message for c in mine])
            emcy = emcy or any("a loss" in c.message for c in mine)
        else:
            assert status == LOADED, (group, status)
    assert bool(boot.seen[0] & LOST_BITS) == emcy, (boot.groups, [c.message for c in changes])


def test_save_goes_on_past_a_failing_group(tmp_path: Path) -> None:
    """0x1010 sub 1 stores every group even when the driver fails for one (group app, stored
    first): the answer is that group's abort code, and group comm is saved all the same."""
    violations, boots, answers = run_script([small()], [
        "nv 384", "boot 0", "set 2000 00 05", "set 1017 00 F401", "failwrite 1", "save", "boot 0"], tmp_path)
    assert answers[-1] == "save 06060000"  # HARDWARE: app's store failed
    # the model flags the failing save (R4: a failing driver is no working NV) and then knows no
    # longer what NV holds; the values say it
    assert violations and violations[0].rule == "R4" and "save on working NV" in violations[0].text
    after = boots[-1]
    assert after.values[(0x1017, 0)] == "F401"
    assert after.values[(0x2000, 0)] == "01"


def test_a_load_mark_past_a_windowed_rollback_s_nv_is_a_mark_not_a_loss(tmp_path: Path) -> None:
    """v2 (app pinned to 512 bytes, 21 more entries) stores its defaults (slot A), a save (slot B)
    and loads: the mark goes to slot A and runs past the 256 bytes the driver shows v1 (app pinned
    to 128). v1 reads the mark's header but cannot check its image: the newest is a load mark all
    the same, so the group boots DEFAULTS (docs/persistence.md section 4) with no loss reported;
    nothing stored was lost, as the user asked for the defaults."""
    v1 = app(Param(0x2000, U32, "app", 0), pins={"app": 128})
    v2 = app(Param(0x2000, U32, "app", 0), Param(0x2200, U32, "app", 1, elements=20), pins={"app": 512})
    commands = ["nv 640", "boot 1", *saves(0x2000, ["07000000"]), "load", "window 256", "boot 0", "boot 0"]
    violations, boots, answers = run_script([v1, v2], commands, tmp_path)
    assert not violations, "\n".join(map(str, violations))
    assert answers[-2:] == [LOAD_OK, "ok"]
    rollback = boots[1]
    assert rollback.values[(0x2000, 0)] == "00000000"
    assert rollback.groups[0]["status"] == DEFAULTS, rollback.groups  # app (the groups by name: app, comm)
    assert not rollback.seen[0] & LOST_BITS, rollback.seen
    assert boots[2].groups[0]["status"] == LOADED and not boots[2].seen[0] & LOST_BITS
