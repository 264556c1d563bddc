"""Linked firmware footprint on Cortex-M4: the dictionary and the code that serves it, next to
CANopenNode v4's published figures.

Method (the one ../shared/notes/peer-measurements.md, sections 6 and 7, used for CANopenNode):
arm-none-eabi-gcc `-mcpu=cortex-m4 -mthumb -Os -ffunction-sections -fdata-sections`, one ELF per
build linked with `--specs=nosys.specs -Wl,--gc-sections`, whose `main` initialises the
dictionary, finds one entry (index and sub-index from volatile variables), reads it and writes
it back through the generic access API; the figures of an ELF whose `main` only returns a
volatile int are subtracted. FLASH = .text + .rodata + .data, RAM = .data + .bss.

odgen's side is measured live, in each lookup mode (the default is hash), in five builds: with
the persistence layer (`odg_persist_init` with an NV driver of byte loops over a 4096-byte RAM
array, as the notes' CANopenNode build with CO_storageEeprom has; the array is taken out of RAM)
for the dictionary generated with `[persist] migration = false`, the same with boot migration
(odgen's default: stored parameters survive a firmware update, which CANopenNode does not
offer), without persistence, and the whole device (`odg_node_init`, `odg_node_receive` and
`odg_node_tick` with every service: NMT, heartbeat producer and consumer, SDO server, 4 + 4
PDOs, SYNC, EMCY, TIME, LSS slave, persistence with migration; a CAN send that does nothing and
the same NV driver), once with the SDO server CANopenNode's figure has (expedited and segmented:
its default CO_CONFIG_SDO_SRV has no block transfer; `[node] sdo_block = false`) and once as
odgen generates it by default, with block transfer. The runtime is compiled with the
dictionary's generated configuration (NAME_config.h) and `-DODG_NO_ABORT_TEXT`. CANopenNode's
code is not part of this project: its figures are the published ones below. run.py runs this part (`--parts linked`).
"""

from __future__ import annotations

import re
import subprocess
from collections import Counter
from pathlib import Path

from common import BUILD as BENCH
from common import CORPUS, ODGEN, Target, failure
from footprint import ensure_toolchain, sections, symbols

from odgen import toolchain

BUILD = BENCH / "linked"
CPU = ["-mcpu=cortex-m4", "-mthumb", "-Os", "-ffunction-sections", "-fdata-sections"]
LINK = ["--specs=nosys.specs", "-Wl,--gc-sections"]
NV_ARRAY = 4096  # the RAM array behind the NV driver, not counted (as in the notes)
CORE_GOAL = 1024
DEFAULT_LOOKUP = "hash"

# CANopenNode v4, linked as above (FLASH, RAM), published in the notes: the dictionary with
# CO_ODinterface.c (section 6), the same with CO_storageEeprom (section 7), the whole device
# (section 7, DS301 only); and the input odgen generates the same device from.
PUBLISHED = {
    "ds301_canopennode": {"access": (3544, 1044), "storage": (5308, 1136), "device": (16496, 5580),
                          "input": "canopennode__DS301_profile.eds",
                          "what": "CANopenNode's example/OD.c (the device of DS301_profile.eds)"},
    "demodevice_canopendemo": {"access": (5368, 2572), "storage": (7132, 2664),
                               "input": "canopendemo__demoDevice.xdd",
                               "what": "CANopenDemo's committed demo/OD.c, made from demoDevice.xdd"},
}
METHOD = ("published in ../shared/notes/peer-measurements.md sections 6 and 7 (arm-none-eabi-gcc 12.2, same "
          "flags, main: OD_find + OD_getSub + io.read + io.write, with storage CO_storageEeprom_init + "
          "CO_storageEeprom_auto_process over a 4096-byte RAM EEPROM; the whole device: CANopenNode's "
          "example/ with its blank driver and CO_USE_GLOBALS; empty main subtracted)")

NO_MIGRATION = "[persist]\nmigration = false\n"
NO_BLOCK = "[node]\nsdo_block = false\n"
# each options file's dictionary in a folder of its own
OPTION_DIRS = {"": ".", NO_MIGRATION: "no-migration", NO_BLOCK: "no-block"}

# The builds: key, what the row says, which CANopenNode figure it compares with, FLASH goal (None:
# shown, not a target), RAM goal or None, options file, main, whether the services are linked.
BUILDS: tuple[tuple[str, str, str, float | None, float | None, str, str, bool], ...] = (
    ("persist", "dictionary + access, persistence without migration (`[persist] migration = false`)",
     "storage", 1.0, None, NO_MIGRATION, "use", False),
    ("migrate", "dictionary + access, persistence with boot migration (the default)",
     "storage", 1.0, None, "", "use", False),
    ("no_persist", "dictionary + access, without persistence", "access", 0.75, None, "", "access", False),
    ("device", "whole device (NMT, HB producer + consumer, SDO server expedited and segmented as CANopenNode's "
     "(`[node] sdo_block = false`), 4 + 4 PDOs, SYNC, EMCY, TIME, LSS, persistence with migration)",
     "device", 0.85, 0.40, NO_BLOCK, "node", True),
    ("device_block", "whole device, odgen's default: the same with SDO block transfer", "device", None, None, "",
     "node", True),
)

# Where the bytes go: each object file of ours, by what it serves.
PART_OF = {"od.o": "dictionary tables (od.c)", "odg.o": "core access (odg.c)",
           "odg_persist.o": "persistence: layer", "odg_persist_slot.o": "persistence: slots, CRC",
           "odg_persist_fixed.o": "persistence: fixed images", "odg_persist_migrate.o": "persistence: migration",
           "odg_verify.o": "self-check (odg_verify.c)", "main.o": "main and NV driver (the bench's)"}
# the dictionary's tables by symbol (od.c; regular expressions), in the build with migration
DICT_PARTS = {"sub-entry descriptors": "od_subs", "entries": "od_entries", "reset (defaults)": "od_reset",
              "persisted defaults": r"od_persist_\w+_(defaults|spread)", "lookup tables": r"od_(hash|find)\w*",
              "dictionary": "od", "groups": "od_groups"}

FOOTPRINT_NOTES = """\
Every footprint goal above is met (hash, the default lookup; DS301 unless named; 2026-11-28). The
rows with boot migration are the closest: DS301 5304 B against 5308 B (99.9%), demoDevice 7040 B
against 7132 B (99%). The persistence layer links 3280 B for DS301 (the ELF minus the row without
persistence; demoDevice 3840 B), against about 1764 B that CANopenNode's CO_storage,
CO_storageEeprom and CRC-16 add (5308 - 3544); the dictionary and the core are at 57% of
CANopenNode's (the row without persistence), which pays for the rest. What the layer links beyond
CANopenNode's storage: stored values survive a firmware update that changes the layout (entry by
entry kept, widened, defaulted, dropped or added, checked against the current limits), images are
found where an older NV map put them (the places a region that grew or shrank left them, the boot
of several groups in the order of their regions, the scrub of a region after boot), and a
power-safe A/B commit with read-back.

- How the rows with boot migration came within their goals on 2026-11-28 (DS301 5728 -> 5304 B,
  demoDevice 7496 -> 7040 B):
  - Runs of alike entries of consecutive indices (the RPDO and TPDO communication and mapping
    records) share one list of sub-entry descriptors (`ODG_E_SHARED`): each shared descriptor
    keeps the stride of its values in the high byte of `size` and an offset biased by the run's
    first index, so a member's value is at offset + index * stride with no walk over the run.
    DS301's descriptors 664 -> 312 B; the runtime +152 B (the lookup's copy into the reference,
    the walks over the entries); -204 B on this row, -244 B without persistence. The copy costs
    the lookup about 11 instructions on the entries of a run; `ODG_CFG_HASH_WIDE` (the 16-bit hash
    tables' path only for hashes of more than 256 slots) gave back 9 (DS301 65 -> 68 instructions
    per lookup in all, goal 71) and 12 B.
  - A "load" (0x1011) stores a load mark as a "save" stores an image (bit 0 of its region word),
    instead of an erase ordered so that no older image outlives the newest: -164 B (demoDevice
    -156 B). A first version erased the rest of the region after the mark; `make fuzz`'s model
    found that a rollback whose NV ended before the mark then missed it and numbered its stores
    below it, and, once the mark no longer hid it behind another group's EMCY, that a store's
    erase of its own image past its region left the next group's region blank (a loss reported as
    a first boot, reachable with a store too): the mark is stored as a save is, and that erase
    takes only the image's header.
  - `NAME_config.h` of a dictionary with migration gives the end of the groups' NV as a distance
    from the first group's region (`ODG_PERSIST_NV_TAIL`, checked by `NAME.c`): -24 B. A group
    with no image checks its region blank in one pass and looks for an "ODG1" mark at its start
    only, and the record count is read with the slot header: -40 B. `odg_group_reset`, the CRC
    read inline and the ordered boot keeping the lowest start: -16 B (demoDevice -60 B).
  - An adversarial review of the shared runs and the load mark then fixed two promises, +24 B
    (demoDevice +32 B): a load mark that a rollback's driver shows only in part (it lies past
    the NV the driver shows) is a mark (`DEFAULTS`), not a loss; and no place inside slot A's image
    is taken when that image runs past the NV the driver shows (a stored OCTET_STRING could hold
    one), the store that follows erasing that header once its own image is committed.
  - Tried and dropped: the boot counts copied as one block (0 B, demoDevice +12 B); the bsearch
    lookup (76 B less, but it misses the lookup goal: 134 instructions); the dictionary's fields
    of features a build leaves out (about 20 B, but a runtime and a dictionary built with
    different switches would then disagree on the struct's layout with no error).
- Measured for this row earlier on 2026-11-28, and what became of it:
  - Two more rounds of behaviour-preserving rewrites: the migration DS301 -100 B, demoDevice
    -104 B; the layer and the slots DS301 -44 B, demoDevice -96 B.
  - The groups boot in the order of their regions in NV instead of in rounds that looked for
    every other group's newest image: demoDevice -172 B, and no case left without a safe order.
  - Correctness fixes (rule 1: an older store, or values never stored, were served), +92 B in
    all: an image loaded unchanged that reaches past the group's region is stored home; a store
    that writes over the newest image invalidates the group's images past the region first; no
    image is taken inside slot A's valid image; boot looks for slot B of regions up to 16 MiB. A
    pinned region of a group with migration must be a power of two.
- Measured for this row on 2026-11-27 (second half of the day), and what became of it:
  - A persistence group's defaults are the runs of its mirror that are not all zero
    (`NAME_persist_GROUP_defaults`, placed by a (start, end) table) instead of a whole copy of the
    mirror: DS301's defaults 432 -> 104 B of FLASH; DS301 with persistence -228 B (without -252 B,
    whole device -240 B).
  - `odg_init` adds the node-id to `$NODEID` values in one loop, which a group's defaults share,
    instead of a statement per value in the generated reset (tried and dropped earlier because an
    older generated file would add the node-id twice; a generated file now checks `ODG_TABLES`):
    -56 B with persistence, +20 B without.
  - The migration in two rounds of behaviour-preserving rewrites (header words read inline,
    the place walk reading the NV size itself, results in one struct, a few helpers kept out of
    line, dropped entries counted once, the layer's boot writing counts straight into the
    caller's array, ...): DS301 -448 B, demoDevice -604 B in all.
  - A correctness fix cost demoDevice +124 B (DS301 boots its one group alone): the groups boot
    in dependency order (a group once its region holds no byte of another group's newest image),
    since a chain of displaced images, and an image whose tail reached into a third region (both
    found by `make fuzz`), let one group's boot clear another's newest image before it moved home.
  - Structural change considered then: ARRAYs and RECORDs alike in everything but their offsets
    sharing one descriptor list (made on 2026-11-28, above, without a walk over the run).
  - Tried and dropped then: one switch for 16-bit hash tables and one for dictionaries without
    sparse entries (-12 B and 0 B here); the first was taken up on 2026-11-28 (above), when it
    also paid for the shared runs' lookup.
- Measured for this row on 2026-11-27 (first half of the day), and what became of it:
  - One walk over a group's places serves store, erase, scrub and boot: -208 B, then +64 B to
    keep the boot's peak stack where it was; later the walk lost its list of images (0x1011
    erases the images past the region on a second walk, the scrub visits the region's places in
    address order) and reads the place slot A names once: -74 B.
  - A dictionary with one persistence group boots it in one pass (`ODG_CFG_PERSIST_TWO_PASS 0`):
    -160 B (DS301; demoDevice has three groups).
  - The boot of a migrated group stores and scrubs at one place, and an "ODG1" image there is
    known by its commit mark, so a build whose groups all migrate links no "ODG1" reader: -148 B.
  - The 0x1010/0x1011 commands share one descriptor when the dictionary packs another entry:
    -48 B on every DS301 row (demoDevice -80 B).
  - The boot status object's counts worked out only when the dictionary has the object: -28 B.
  - The NV driver of this bench is volatile, so its byte loops stay loops: before, GCC made them
    calls of libc's memcpy (308 B, counted here), which CANopenNode's figures carry anyway (its
    dictionary access copies with memcpy) and odgen's runtime does not use.
  - A correctness fix cost +28 B (demoDevice +72 B): sub 0 of an entry whose highest sub-index
    changed follows it only when its stored value would be kept or widened (a value narrowed
    there is a loss, now reported).
  - Tried then, made later in the day (above): the node-id added by one loop in `odg_init`
    (-60 B then); the header word reader inline (-8 B then, more with the later rewrites).
    Tried and dropped: the walk's three passes over the layout as one function (+48 B); the
    record walk without its count of records left (+16 B).
  - Earlier: `odg_verify` is not linked by a firmware that does not call it; CRC-32 bit by bit
    (44 B, no table); hash links 88 B more than bsearch, which misses the lookup goal; the
    persisted group's defaults as generated code instead of a table (-296 B) would need a
    per-value default for the readers of single defaults (`odg_comm.c`, `odg_verify`, the "ODG1"
    limit re-check) that costs what it saves.

The **whole device** meets its goal since 2026-11-27: 13228 B against 14021 B (80% of 16496 B;
with SDO block transfer, odgen's default, 14268 B; 2026-11-28: -52 B, the migration and the
layer smaller by 144 B, the fixes +92 B). It was 15204 B on the morning of 2026-11-27: the services
-656 B (SDO 1152 -> 784 B: a build without strings or domains leaves the streamed transfers
out, one whose values are all numbers of at most 4 bytes answers every upload expedited; PDO,
EMCY, heartbeat, SYNC and communication values each a little smaller), the LSS configuration in
a record store of its own instead of "ODG1" slots (-192 B) and the LSS slave and that store
-130 B, the migration and the layer about -800 B, the defaults as runs -240 B, the packed
commands -48 B. Its services link 6992 B (`odg_pdo.c` 1988, `odg_node.c` 1054, `odg_err.c`
1012, `odg_sdo.c` 784, `odg_hb.c` 694, `odg_lss.c` 674, `odg_comm.c` 396, `odg_sync.c` 240,
`odg_node_io.c` 118, `odg_time.c` 32), the persistence 3622 B (the LSS record store 356 of it),
the dictionary 1221 B and the core 1092 B. RAM, 1772 B (32%), meets its goal too.

Earlier shrinks, measured the same way (the figures of their day, with an NV driver of three empty
functions and before the stored-values rule set):

- The runtime compiled to what the dictionary uses (`NAME_config.h`: no 64-bit arithmetic, strings,
  hooks or limits when the dictionary has none; one lookup path): the core find/read/write of the
  CiA 301 profile went from 1652 to the figure in the table (the "core" column), the linked firmware
  without persistence from 3844 to 3052.
- Uniform ARRAY and RECORD elements share one descriptor (`ODG_E_PACKED`: 0x1003, 0x1016, the PDO
  mapping records, 0x1018): descriptors 1360 -> 712 B, without persistence 2688 -> 2156 B;
  demoDevice's descriptors 2288 -> 992 B.
- The runtime copies with a byte loop of its own (`odg_copy`), and so does the generated reset
  for the persistence groups' defaults (in FLASH for the layer anyway) and for a RAM block of
  which a quarter or more starts non-zero; a sparser RAM block is assigned, which GCC turns into
  a memset and a few stores with no defaults table (DS301). libc's memcpy (308 B), which
  demoDevice linked through its reset's struct copies, is no longer linked: demoDevice without
  persistence 3984 -> 3668 B; on the corpus no dictionary links more than before (4 B at most).
- Persistence (`odg_persist.c`), 8248 -> 5632 B with boot migration: built to the dictionary's
  groups (`ODG_CFG_PERSIST_STREAMS`, `ODG_CFG_PERSIST_ODG1`, `ODG_CFG_PERSIST_STATUS`; numbers as
  32 bits without 64-bit types), the layout descriptors read from the tables instead of const
  tables (demoDevice: 1128 B), CRC-32 bit by bit (no 64-byte table), no libc memcmp. Then
  5632 -> 5408 B (demoDevice 7764 -> 7464 B), behaviour and NV format unchanged: both image
  formats share the header read and the CRC loop, the read-back of a store and the boot's second
  read compare the CRC instead of the header bytes, the slot B that slot A names is found once
  for the restore too, the record walk keeps the descriptor of the packed elements it walks and
  makes them on one path, the erasures of a restore are ranges, a domain is written by the
  string loop and resized by the OCTET_STRING path, and the migration counts go from the boot
  of a group straight to the totals.
- Persistence without migration (`[persist] migration = false`), 3700 -> 3504 B (demoDevice 5536
  -> 5048 B, 316 B of it the reset's copies above): the generated configuration leaves the
  migration out (`ODG_CFG_PERSIST_MIGRATION 0`, which before took `-DODG_NO_MIGRATION` by
  hand), "no image" checks both slots as one erased range, the boot checks the layout signature
  on the header read with the image, the store's read-back compares the CRC it wrote, store and
  restore share one entry point, and the counts only a migration produces are left out. The
  layer is then about 1.36 KB (boot, power-safe store with read-back, restore in power-safe
  order, CRC): both dictionaries are within CANopenNode's figure, which links no storage at all
  (its CO_storage is not in its main).
- With boot migration (odgen's default) the goal is not met: the migration entry by entry (record
  walk, widening and limits, streams, the store of the migrated image, the "ODG1" check that tells
  an old image from damage) adds about 1.9 KB linked. It is what lets stored parameters survive a
  firmware update, which no peer's figure includes; reaching 100% with it would need the whole
  layer in the size the layer without migration has now.
- Lookup modes: the perfect hash costs its tables (80 B for the CiA 301 profile) over the binary
  search, the switch about 12 B per index: bsearch is the smallest, hash the fastest.
"""

EMPTY_MAIN = "volatile int v;\nint main(void);\nint main(void) { return v; }\n"

# An NV driver of byte loops over a RAM array, as the notes' CO_eeprom_* functions. The array is
# volatile, as the registers of an EEPROM or a flash controller are, so that its loops stay
# loops: GCC would otherwise make them calls of libc's memcpy (308 B), which CANopenNode's
# figures carry anyway (its dictionary access copies with memcpy) and odgen's runtime does not use.
NV_DRIVER = f"""
static volatile uint8_t nv_mem[{NV_ARRAY}];
static int nv_read(void *c, uint32_t a, void *b, uint32_t l)
{{
    uint8_t *p = (uint8_t *)b;
    (void)c;
    if (a + l > sizeof nv_mem) return 1;
    while (l--) *p++ = nv_mem[a++];
    return 0;
}}
static int nv_write(void *c, uint32_t a, const void *b, uint32_t l)
{{
    const uint8_t *p = (const uint8_t *)b;
    (void)c;
    if (a + l > sizeof nv_mem) return 1;
    while (l--) nv_mem[a++] = *p++;
    return 0;
}}
static int nv_erase(void *c, uint32_t a, uint32_t l)
{{
    (void)c;
    if (a + l > sizeof nv_mem) return 1;
    while (l--) nv_mem[a++] = 0xFFu;
    return 0;
}}
static const odg_nv_driver_t nv = {{nv_read, nv_write, nv_erase, 0}};
"""

ACCESS_MAIN = r"""
#include "od.h"
volatile uint16_t v_index = 0x1000;
volatile uint8_t v_sub = 0;
int main(void);
int main(void)
{
    odg_ref_t r;
    uint8_t b[8];
    uint32_t n;
    if (odg_init(&od, 1)) return 1;
#ifdef WITH_PERSIST
    (void)odg_persist_init(&persist, &od, &nv, 0);
#endif
    if (odg_find(&od, v_index, v_sub, &r)) return 2;
    if (odg_read(&r, 0, b, sizeof b, &n)) return 3;
    return (int)odg_write(&r, b, n);
}
"""
USE_MAIN = ("#include \"od.h\"\n#include \"odg_persist.h\"\n#define WITH_PERSIST 1\n" + NV_DRIVER
            + "static odg_persist_t persist;\n" + ACCESS_MAIN)

NODE_MAIN = ("#include <string.h>\n#include \"od.h\"\n#include \"odg_node.h\"\n" + NV_DRIVER + r"""
volatile uint32_t v_now, v_id;
volatile uint8_t v_len, v_data[8];
static int can_send(void *ctx, const odg_frame_t *f) { (void)ctx; (void)f; return 0; }
int main(void);
int main(void)
{
    static odg_node_t node;
    odg_node_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dict = &od;
    cfg.node_id = 5;
    cfg.nv = &nv;
    cfg.send = can_send;
    (void)odg_node_init(&node, &cfg);
    for (;;) {
        odg_frame_t f;
        unsigned i;
        memset(&f, 0, sizeof f);
        f.id = v_id;
        f.len = v_len;
        for (i = 0; i < 8u; i++) f.data[i] = v_data[i];
        odg_node_receive(&node, &f);
        odg_node_tick(&node, v_now);
    }
}
""")
MAINS = {"use": USE_MAIN, "access": ACCESS_MAIN, "node": NODE_MAIN}

# The core closure: odg_find + odg_read + odg_write alone (what runtime/README.md calls the core).
CORE_MAIN = r"""
#include "od.h"
int main(void);
int main(void) { odg_ref_t r; unsigned char b[8]; uint32_t n;
  if (odg_find(&od, 0x1000, 0, &r)) return 1;
  if (odg_read(&r, 0, b, sizeof b, &n)) return 2;
  return (int)odg_write(&r, b, n); }
"""


def flash_ram(sec: dict[str, int]) -> tuple[int, int]:
    return sec["text"] + sec["rodata"] + sec["data"], sec["data"] + sec["bss"]


def _cc(args: list[str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["arm-none-eabi-gcc", *args], capture_output=True, text=True, check=False)


def empty_baseline() -> tuple[int, int]:
    BUILD.mkdir(parents=True, exist_ok=True)
    (BUILD / "empty.c").write_text(EMPTY_MAIN)
    elf = BUILD / "empty.elf"
    _cc([*CPU, *toolchain.CFLAGS, str(BUILD / "empty.c"), *LINK, "-o", str(elf)]).check_returncode()
    return flash_ram(sections(elf))


def config_defines(work: Path) -> list[str]:
    """The runtime built for this dictionary: its generated configuration header, when there is one."""
    cfg = work / "od_config.h"
    return [f"-DODG_CONFIG=\"{cfg.name}\""] if cfg.is_file() else []


def flags(work: Path) -> list[str]:
    return [*CPU, *toolchain.CFLAGS, "-DODG_NO_ABORT_TEXT", *config_defines(work),
            f"-I{toolchain.include_dirs()[0]}", f"-I{work}"]


def map_sizes(path: Path) -> Counter[str]:
    """FLASH bytes (.text, .rodata, .data) each input object put into the linked ELF, from the link map."""
    sizes: Counter[str] = Counter()
    text = path.read_text().split("Linker script and memory map", 1)[-1]
    kind = None
    for line in text.splitlines():
        alone = re.match(r"^ \.(text|rodata|data|bss)\S*\s*$", line)
        if alone:
            kind = alone.group(1)
            continue
        m = re.match(r"^ (?:\.(text|rodata|data|bss)\S*)?\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+\.o\)?)$", line)
        if m and (m.group(1) or kind) in ("text", "rodata", "data"):
            name = m.group(3).rsplit("/", 1)[-1]
            sizes[name] += int(m.group(2), 16)
        kind = None
    return sizes


def build(work: Path, main: str, tag: str, services: bool) -> tuple[Path | None, str, Counter[str]]:
    """One ELF from separately compiled objects (so the link map names each), its FLASH per object."""
    objs_dir = work / f"{tag}.objs"
    objs_dir.mkdir(parents=True, exist_ok=True)
    (objs_dir / "main.c").write_text(main)
    sources = [objs_dir / "main.c", work / "od.c", *toolchain.core_sources()]
    if services:
        sources += toolchain.service_sources()
    objs = []
    for source in sources:
        obj = objs_dir / f"{source.stem}.o"
        comp = _cc([*flags(work), "-c", str(source), "-o", str(obj)])
        if comp.returncode != 0:
            return None, next((ln for ln in comp.stderr.splitlines() if "error" in ln), "failed")[-140:], Counter()
        objs.append(str(obj))
    elf = work / f"{tag}.elf"
    comp = _cc([*CPU, *objs, *LINK, f"-Wl,-Map={elf}.map", "-o", str(elf)])
    if comp.returncode != 0:
        return None, next((ln for ln in comp.stderr.splitlines() if "error" in ln), "link failed")[-140:], Counter()
    ours = {Path(o).name for o in objs}
    return elf, "", Counter({k: v for k, v in map_sizes(Path(f"{elf}.map")).items() if k in ours})


def core_bytes(work: Path) -> int:
    """Runtime code kept for odg_find + odg_read + odg_write (the dictionary and libc not counted)."""
    elf, _, sizes = build(work, CORE_MAIN, "core", False)
    if elf is None:
        return -1
    return sum(v for k, v in sizes.items() if k.startswith("odg"))


def generate(source: Path, work: Path, lookup: str, options: str) -> str:
    """The dictionary as od.[ch] in `work`; "" or why odgen refused it."""
    work.mkdir(parents=True, exist_ok=True)
    extra = []
    if options:
        (work / "options.toml").write_text(options)
        extra = ["--options", str(work / "options.toml")]
    gen = subprocess.run([*ODGEN, "generate", str(source), "-o", str(work), "--name", "od", "--lookup", lookup,
                          *extra], capture_output=True, text=True, check=False)
    return failure(gen.stderr) if gen.returncode != 0 else ""


def measure(label: str, source: Path, lookup: str, empty: tuple[int, int]) -> dict[str, object]:
    row: dict[str, object] = {"input": label, "lookup": lookup}
    base = BUILD / f"{label}-{lookup}"
    published = PUBLISHED[label]

    def work(options: str) -> Path:
        return base / OPTION_DIRS[options]

    for options in dict.fromkeys(b[5] for b in BUILDS):  # one dictionary per options file
        refused = generate(source, work(options), lookup, options)
        if refused:
            row["refused"] = refused
            return row
    for key, _, ref, _, _, options, main, services in BUILDS:
        if ref not in published:
            continue
        elf, why, parts = build(work(options), MAINS[main], key, services)
        if elf is None:
            row[key] = {"failed": why}
            continue
        flash, ram = flash_ram(sections(elf))
        nv = NV_ARRAY if main != "access" else 0
        row[key] = {"flash": flash - empty[0], "ram": ram - empty[1] - nv, "parts": dict(sorted(parts.items())),
                    "libc": flash - empty[0] - sum(parts.values())}
        if key == "migrate":
            syms = symbols(elf)
            row["dict_parts"] = {name: sum(v for k, v in syms.items() if re.fullmatch(sym, k))
                                 for name, sym in DICT_PARTS.items()}
    row["core"] = core_bytes(base)
    return row


def _goal_target(label: str, key: str, text: str, ref: tuple[int, int], goal: float, ram_goal: float | None,
                 mine: list[dict[str, object]]) -> list[Target]:
    ok = [r for r in mine if key in r and "flash" in r[key]]  # type: ignore[operator]
    name = f"linked FLASH, {text} vs CANopenNode v4, {label}"
    if not ok:
        return [Target(name, f"<= {goal:.0%}", "does not link", "-", False)]
    default = next((r for r in ok if r["lookup"] == DEFAULT_LOOKUP), ok[0])
    flash = int(default[key]["flash"])  # type: ignore[index]
    each = ", ".join(f"{r['lookup']} {r[key]['flash']}" for r in ok)  # type: ignore[index]
    out = [Target(name, f"<= {goal:.0%} ({int(goal * ref[0])} B)", f"{each} B / {ref[0]} B (published)",
                  f"{flash / ref[0]:.0%} ({default['lookup']}, the default)", flash <= goal * ref[0])]
    if ram_goal is not None:
        ram = int(default[key]["ram"])  # type: ignore[index]
        out.append(Target(f"linked RAM, {text} vs CANopenNode v4, {label}", f"<= {ram_goal:.0%}",
                          f"{ram} B / {ref[1]} B (published)", f"{ram / ref[1]:.0%}", ram <= ram_goal * ref[1]))
    return out


def targets(rows: list[dict[str, object]]) -> list[Target]:
    out = []
    for label, published in PUBLISHED.items():
        mine = [r for r in rows if r["input"] == label]
        if not mine or any("refused" in r for r in mine):
            why = "input absent" if not mine else "odgen refuses the input"
            out.append(Target(f"linked FLASH vs CANopenNode v4, {label}", "<= 100%", why, "-", None))
            continue
        for key, text, ref, goal, ram_goal, _, _, _ in BUILDS:
            if ref in published and goal is not None:
                out += _goal_target(label, key, text, published[ref], goal, ram_goal, mine)  # type: ignore[arg-type]
    ds301 = [r for r in rows if r["input"] == "ds301_canopennode" and int(r.get("core", -1)) > 0]  # type: ignore[call-overload]
    if ds301:
        core = min(int(r["core"]) for r in ds301)  # type: ignore[call-overload]
        out.append(Target("runtime core (odg_find + odg_read + odg_write) built for DS301, Cortex-M4",
                          f"<= {CORE_GOAL} B", f"{core} B", f"{core / CORE_GOAL:.0%}", core <= CORE_GOAL))
    return out


def _cell(fig: dict[str, object] | None) -> str:
    if fig is None:
        return "-"
    return f"failed: {fig['failed']}" if "failed" in fig else f"{fig['flash']} / {fig['ram']}"


def _parts_table(rows: list[dict[str, object]], key: str, title: str) -> list[str]:
    mine = [r for r in rows if key in r and "parts" in r[key]]  # type: ignore[operator]
    if not mine:
        return []
    names: list[str] = list(dict.fromkeys(n for r in mine for n in r[key]["parts"]))  # type: ignore[index]
    names.sort(key=lambda n: (n not in PART_OF, n))
    lines = ["", title, "", "| object file | what | " + " | ".join(f"{r['input']} {r['lookup']}" for r in mine) + " |",
             "|---|---|" + "---:|" * len(mine)]
    for n in names:
        what = PART_OF.get(n, "service" if n.startswith("odg_") else "")
        lines.append(f"| {n} | {what} | " + " | ".join(str(r[key]["parts"].get(n, 0)) for r in mine) + " |")  # type: ignore[index]
    lines.append("| libc (beyond the empty main) | alignment, and what libc the build calls | "
                 + " | ".join(str(r[key]["libc"]) for r in mine) + " |")  # type: ignore[index]
    return lines


def markdown(rows: list[dict[str, object]], empty: tuple[int, int]) -> str:
    lines = ["## Linked firmware footprint on Cortex-M4 (dictionary + runtime)", "",
             __doc__.split("\n\n", 1)[1].split("run.py")[0].strip(), "",
             f"Empty `main` (subtracted): FLASH {empty[0]} B, RAM {empty[1]} B. Lookup: `{DEFAULT_LOOKUP}` is "
             "odgen's default; every mode is measured.", "",
             "| input | odgen lookup | FLASH / RAM with persistence, no migration | ... with boot migration "
             "| without persistence | whole device (SDO as CANopenNode's) | ... with SDO block transfer "
             "| core find/read/write | CANopenNode v4 FLASH / RAM (published): access; with storage; whole device |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        pub = PUBLISHED[str(r["input"])]
        refs = "; ".join(f"{pub[k][0]} / {pub[k][1]}" for k in ("access", "storage", "device") if k in pub)  # type: ignore[index]
        if "refused" in r:
            lines.append(f"| {r['input']} | {r['lookup']} | refused: {r['refused']} | | | | | | |")
            continue
        cells = [_cell(r.get(key)) for key, *_ in BUILDS]  # type: ignore[arg-type]
        lines.append(f"| {r['input']} | {r['lookup']} | " + " | ".join(cells) + f" | {r['core']} B | {refs} |")
    lines += _parts_table(rows, "migrate", "Where the FLASH goes, dictionary + access with persistence and boot "
                          "migration (bytes each object file puts into the linked ELF):")
    lines += _parts_table(rows, "device", "Where the FLASH goes, whole device with the SDO server CANopenNode's "
                          "figure has (bytes each object file puts into the linked ELF):")
    lines += ["", "The dictionary's tables, with persistence and boot migration (symbols of od.c in the linked ELF):",
              "",
              "| input | lookup | " + " | ".join(DICT_PARTS) + " |", "|---|---|" + "---:|" * len(DICT_PARTS)]
    lines += [f"| {r['input']} | {r['lookup']} | " + " | ".join(str(v) for v in r["dict_parts"].values()) + " |"  # type: ignore[attr-defined]
              for r in rows if "dict_parts" in r]
    lines += ["", FOOTPRINT_NOTES]
    lines += ["", "CANopenNode v4 figures: " + METHOD + ".", ""]
    lines += [f"- {label}: {pub['what']}; odgen generates from `{pub['input']}`." for label, pub in PUBLISHED.items()]
    return "\n".join(lines) + "\n"


def run(modes: tuple[str, ...]) -> dict[str, object]:
    ensure_toolchain()
    empty = empty_baseline()
    rows = [measure(label, CORPUS / str(pub["input"]), mode, empty) for label, pub in PUBLISHED.items()
            if (CORPUS / str(pub["input"])).is_file() for mode in modes]
    return {"rows": rows, "empty": list(empty), "targets": targets(rows), "markdown": markdown(rows, empty)}


if __name__ == "__main__":
    from odgen.choices import LOOKUPS
    print(run(LOOKUPS)["markdown"])
