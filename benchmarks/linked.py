"""Linked firmware footprint on Cortex-M4: the dictionary and the code that serves it, next to
CANopenNode v4's published figures.

Method (the one ../shared/notes/peer-measurements.md, section 6, used for CANopenNode):
arm-none-eabi-gcc `-mcpu=cortex-m4 -mthumb -Os -ffunction-sections -fdata-sections`, one ELF per
dictionary linked with `--specs=nosys.specs -Wl,--gc-sections`, whose `main` initialises the
dictionary, finds one entry (index and sub-index from volatile variables), reads it and writes
it back through the generic access API; the figures of an ELF whose `main` only returns a
volatile int are subtracted. FLASH = .text + .rodata + .data, RAM = .data + .bss.

odgen's side is measured live, in each lookup mode, in three builds: with the persistence layer
(`odg_persist_init` with an NV driver of three empty functions, so 0x1010/0x1011 work) for the
dictionary generated with `[persist] migration = false` (power-safe store and restore, as a
firmware without boot migration has it), the same with boot migration (odgen's default: stored
parameters survive a firmware update, which CANopenNode does not offer), and without persistence.
The runtime is compiled with the dictionary's generated configuration (NAME_config.h) and
`-DODG_NO_ABORT_TEXT`. CANopenNode's code is not part of this project: its figures are the
published ones below. run.py runs this part.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from common import BUILD as BENCH
from common import CORPUS, ODGEN, Target, failure
from footprint import ensure_toolchain, sections, symbols

from odgen import toolchain

BUILD = BENCH / "linked"
CPU = ["-mcpu=cortex-m4", "-mthumb", "-Os", "-ffunction-sections", "-fdata-sections"]
LINK = ["--specs=nosys.specs", "-Wl,--gc-sections"]
FLASH_GOAL, FLASH_GOAL_NO_PERSIST, RAM_GOAL = 1.0, 0.75, 0.5
CORE_GOAL = 1024

# CANopenNode v4 (OD.c + 301/CO_ODinterface.c), linked as above: (FLASH, RAM), and the input
# odgen generates the same device from.
PUBLISHED = {
    "ds301_canopennode": ((3544, 1044), "canopennode__DS301_profile.eds",
                          "CANopenNode's example/OD.c (the device of DS301_profile.eds)"),
    "demodevice_canopendemo": ((5368, 2572), "canopendemo__demoDevice.xdd",
                               "CANopenDemo's committed demo/OD.c, made from demoDevice.xdd"),
}
METHOD = ("published in ../shared/notes/peer-measurements.md section 6 (arm-none-eabi-gcc 12.2, same "
          "flags, main: OD_find + OD_getSub + io.read + io.write, empty main subtracted)")

# Where the FLASH of the build without persistence goes (symbols of the linked ELF).
PARTS = {"sub-entry descriptors": "od_subs", "entries": "od_entries", "reset (defaults)": "od_reset",
         "memcpy (libc)": "memcpy", "odg_find": "odg_find", "odg_write": "odg_write", "odg_read": "odg_read"}

NOT_MET = """\
What was tried, and the measured reason where a FLASH goal is not met (DS301 bsearch figures):

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

USE_MAIN = r"""
#include "od.h"
volatile uint16_t v_index = 0x1000;
volatile uint8_t v_sub = 0;
#ifdef WITH_PERSIST
static int nv_read(void *c, uint32_t a, void *b, uint32_t l) { (void)c; (void)a; (void)b; (void)l; return 0; }
static int nv_write(void *c, uint32_t a, const void *b, uint32_t l) { (void)c; (void)a; (void)b; (void)l; return 0; }
static int nv_erase(void *c, uint32_t a, uint32_t l) { (void)c; (void)a; (void)l; return 0; }
static const odg_nv_driver_t nv = {nv_read, nv_write, nv_erase, 0};
static odg_persist_t persist;
#endif
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


def build(work: Path, main: str, tag: str, defines: list[str]) -> tuple[Path | None, str]:
    (work / f"{tag}.c").write_text(main)
    elf = work / f"{tag}.elf"
    flags = [*CPU, *toolchain.CFLAGS, "-DODG_NO_ABORT_TEXT", *config_defines(work), *defines,
             f"-I{toolchain.include_dirs()[0]}", f"-I{work}"]
    sources = [str(work / f"{tag}.c"), str(work / "od.c"), *map(str, toolchain.core_sources())]
    comp = _cc([*flags, *sources, *LINK, "-o", str(elf)])
    if comp.returncode != 0:
        return None, next((ln for ln in comp.stderr.splitlines() if "error" in ln), "link failed")[-140:]
    return elf, ""


def core_bytes(work: Path) -> int:
    """Runtime code kept for odg_find + odg_read + odg_write (the dictionary and libc not counted)."""
    elf, _ = build(work, CORE_MAIN, "core", [])
    if elf is None:
        return -1
    objs = []
    for source in toolchain.core_sources():
        obj = work / f"{source.stem}.o"
        _cc([*CPU, *toolchain.CFLAGS, "-DODG_NO_ABORT_TEXT", *config_defines(work),
             f"-I{toolchain.include_dirs()[0]}", f"-I{work}", "-c", str(source), "-o", str(obj)]).check_returncode()
        objs.append(obj)
    ours = set().union(*(symbols(obj).keys() for obj in objs))
    return sum(v for k, v in symbols(elf).items() if k in ours)


# The three firmware builds: key, what the row says, FLASH goal, options file, main's define.
BUILDS: tuple[tuple[str, str, float, str, list[str]], ...] = (
    ("persist", "with persistence (0x1010/0x1011; `[persist] migration = false`)", FLASH_GOAL,
     "[persist]\nmigration = false\n", ["-DWITH_PERSIST"]),
    ("migrate", "with persistence and boot migration (the default)", FLASH_GOAL, "", ["-DWITH_PERSIST"]),
    ("no_persist", "without persistence", FLASH_GOAL_NO_PERSIST, "", []),
)


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

    def work(options: str) -> Path:
        return base / "no-migration" if options else base

    for options in dict.fromkeys(b[3] for b in BUILDS):  # one dictionary per options file
        refused = generate(source, work(options), lookup, options)
        if refused:
            row["refused"] = refused
            return row
    for key, _, _, options, defines in BUILDS:
        elf, why = build(work(options), USE_MAIN, key, defines)
        if elf is None:
            row[key] = {"failed": why}
            continue
        flash, ram = flash_ram(sections(elf))
        row[key] = {"flash": flash - empty[0], "ram": ram - empty[1]}
        if key == "no_persist":
            syms = symbols(elf)
            row["parts"] = {name: syms.get(sym, 0) for name, sym in PARTS.items()}
    row["core"] = core_bytes(base)
    return row


def targets(rows: list[dict[str, object]]) -> list[Target]:
    out = []
    for label, ((ref_flash, ref_ram), _, _) in PUBLISHED.items():
        mine = [r for r in rows if r["input"] == label]
        if not mine or any("refused" in r for r in mine):
            why = "input absent" if not mine else "odgen refuses the input"
            out.append(Target(f"linked FLASH vs CANopenNode v4, {label}", "<= 100%", why, "-", None))
            continue
        for key, text, goal, _, _ in BUILDS:
            ok = [r for r in mine if "flash" in r[key]]  # type: ignore[operator]
            if not ok:
                out.append(Target(f"linked FLASH {text} vs CANopenNode v4, {label}", f"<= {goal:.0%}",
                                  "does not link", "-", False))
                continue
            best = min(ok, key=lambda r: r[key]["flash"])  # type: ignore[index]
            flash = int(best[key]["flash"])  # type: ignore[index]
            each = ", ".join(f"{r['lookup']} {r[key]['flash']}" for r in ok)  # type: ignore[index]
            out.append(Target(f"linked FLASH {text} vs CANopenNode v4, {label}", f"<= {goal:.0%}",
                              f"{each} B / {ref_flash} B (published)", f"{flash / ref_flash:.0%} ({best['lookup']})",
                              flash <= goal * ref_flash))
        ram = max(int(r[key]["ram"]) for r in mine for key in ("persist", "migrate")  # type: ignore[index]
                  if "ram" in r[key])  # type: ignore[operator]
        out.append(Target(f"linked RAM vs CANopenNode v4, {label}", f"<= {RAM_GOAL:.0%}",
                          f"{ram} B / {ref_ram} B (published)", f"{ram / ref_ram:.0%}", ram <= RAM_GOAL * ref_ram))
    ds301 = [r for r in rows if r["input"] == "ds301_canopennode" and int(r.get("core", -1)) > 0]  # type: ignore[call-overload]
    if ds301:
        core = min(int(r["core"]) for r in ds301)  # type: ignore[call-overload]
        out.append(Target("runtime core (odg_find + odg_read + odg_write) built for DS301, Cortex-M4",
                          f"<= {CORE_GOAL} B", f"{core} B", f"{core / CORE_GOAL:.0%}", core <= CORE_GOAL))
    return out


def markdown(rows: list[dict[str, object]], empty: tuple[int, int]) -> str:
    lines = ["## Linked firmware footprint on Cortex-M4 (dictionary + access runtime)", "",
             __doc__.split("\n\n", 1)[1].split("run.py")[0].strip(), "",
             f"Empty `main` (subtracted): FLASH {empty[0]} B, RAM {empty[1]} B.", "",
             "| input | odgen lookup | FLASH / RAM with persistence | ... and boot migration | FLASH / RAM without "
             "| core find/read/write | CANopenNode v4 FLASH / RAM (published) |",
             "|---|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        (ref_flash, ref_ram), _, what = PUBLISHED[str(r["input"])]
        if "refused" in r:
            lines.append(f"| {r['input']} | {r['lookup']} | refused: {r['refused']} | | | | |")
            continue
        cells = []
        for key, _, _, _, _ in BUILDS:
            fig = r[key]
            cells.append(f"failed: {fig['failed']}" if "failed" in fig  # type: ignore[operator,index]
                         else f"{fig['flash']} / {fig['ram']}")  # type: ignore[index]
        lines.append(f"| {r['input']} | {r['lookup']} | {cells[0]} | {cells[1]} | {cells[2]} | {r['core']} B "
                     f"| {ref_flash} / {ref_ram} |")
    lines += ["", "Where the FLASH goes without persistence (bytes of the linked ELF):", "",
              "| input | lookup | " + " | ".join(PARTS) + " |", "|---|---|" + "---:|" * len(PARTS)]
    lines += [f"| {r['input']} | {r['lookup']} | " + " | ".join(str(v) for v in r["parts"].values()) + " |"  # type: ignore[attr-defined]
              for r in rows if "parts" in r]
    lines += ["", NOT_MET]
    lines += ["", "CANopenNode v4 figures: " + METHOD + ".", ""]
    lines += [f"- {label}: {what}; odgen generates from `{name}`." for label, (_, name, what) in PUBLISHED.items()]
    return "\n".join(lines) + "\n"


def run(modes: tuple[str, ...]) -> dict[str, object]:
    ensure_toolchain()
    empty = empty_baseline()
    rows = [measure(label, CORPUS / name, mode, empty) for label, (_, name, _) in PUBLISHED.items()
            if (CORPUS / name).is_file() for mode in modes]
    return {"rows": rows, "empty": list(empty), "targets": targets(rows), "markdown": markdown(rows, empty)}


if __name__ == "__main__":
    from odgen.choices import LOOKUPS
    print(run(LOOKUPS)["markdown"])
