"""What boot migration of stored parameters costs (docs/persistence.md), with it and without it.

FLASH on Cortex-M4 (the flags of footprint.py): odg_persist.o built as is and with
-DODG_NO_MIGRATION, and a generated dictionary with `[persist] migration` true and false (the
firmware's layout descriptors are read from the dictionary's tables: no FLASH table of their
own). NV bytes per persisted entry: two slots of the self-describing image ("ODG2": 24-byte
header, entry count, descriptor, wire values) against two slots of the RAM mirror ("ODG1":
20-byte header, the C struct), and the regions with headroom.
Inputs: the io-node example and synth_250 with every manufacturer object persisted. run.py runs
this part (--parts migration).
"""

from __future__ import annotations

import subprocess
from pathlib import Path

from common import BUILD as BENCH
from common import ODGEN, synth_label
from footprint import CFLAGS, RUNTIME, ensure_toolchain, sections, symbols

from odgen.pipeline import Request, prepare
from odgen.place.layout import group_layouts
from odgen.place.nvmap import nv_map, slot_bytes

BUILD = BENCH / "migration"
ROOT = Path(__file__).resolve().parent.parent
PERSIST_ALL = '[[entry]]\nmatch = "0x2000-0x5FFF"\nstorage = "persist:app"\n'


def flash(obj: Path) -> int:
    sec = sections(obj)
    return sec["text"] + sec["rodata"] + sec["data"]


def runtime_flash() -> dict[str, int]:
    BUILD.mkdir(parents=True, exist_ok=True)
    sizes = {}
    for label, defines in (("on", []), ("off", ["-DODG_CFG_PERSIST_MIGRATION=0"])):
        sizes[label] = 0
        for source in sorted(RUNTIME.glob("odg_persist*.c")):  # the layer, its slots and both formats
            obj = BUILD / f"{source.stem}-{label}.o"
            subprocess.run(["arm-none-eabi-gcc", *CFLAGS, *defines, f"-I{RUNTIME}", "-c", str(source), "-o", str(obj)],
                           check=True, capture_output=True, text=True)
            sizes[label] += flash(obj)
    return sizes


def measure(label: str, eds: Path, options: str) -> dict[str, object]:
    row: dict[str, object] = {"input": label}
    for migration in (True, False):
        work = BUILD / f"{label}-{'on' if migration else 'off'}"
        work.mkdir(parents=True, exist_ok=True)
        toml = work / "od.toml"
        toml.write_text(options + f"\n[persist]\nmigration = {'true' if migration else 'false'}\n", encoding="utf-8")
        gen = subprocess.run([*ODGEN, "generate", str(eds), "-o", str(work), "--name", "od", "--options", str(toml)],
                             capture_output=True, text=True, check=False)
        if gen.returncode != 0:
            row["refused"] = gen.stderr.strip().splitlines()[-1:] or ["?"]
            return row
        subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-I{RUNTIME}", "-c", str(work / "od.c"), "-o",
                        str(work / "od.o")], check=True, capture_output=True, text=True)
        syms = symbols(work / "od.o")
        key = "on" if migration else "off"
        row[f"flash_{key}"] = flash(work / "od.o")
        row[f"mirror_{key}"] = {k[len("od_persist_"):]: v for k, v in syms.items()
                                if k.startswith("od_persist_") and not k.endswith(("_defaults", "_spread", "_layout"))}
        row["layout_bytes"] = row.get("layout_bytes") or sum(v for k, v in syms.items() if k.endswith("_layout"))
    prepared = prepare(Request(eds, name="od", options=BUILD / f"{label}-on" / "od.toml"))
    assert prepared.od is not None and prepared.placements is not None
    layouts = group_layouts(prepared.od, prepared.placements)
    entries = sum(len(g.entries) for g in layouts.values())
    mirrors: dict[str, int] = row["mirror_off"]  # type: ignore[assignment]
    odg2 = sum(2 * slot_bytes(g) for g in layouts.values())
    odg1 = sum(2 * _round8(20 + mirrors[name]) for name in layouts)
    regions = sum(r.size for r in nv_map(layouts).values())
    row.update(entries=entries, nv_on=odg2, nv_off=odg1, regions=regions,
               nv_per_entry_on=odg2 / entries, nv_per_entry_off=odg1 / entries, region_per_entry=regions / entries)
    return row


def _round8(n: int) -> int:
    return (n + 7) // 8 * 8


def markdown(runtime: dict[str, int], rows: list[dict[str, object]]) -> str:
    lines = ["## Boot migration of stored parameters (Cortex-M4, arm-none-eabi-gcc -Os)", "",
             f"- odg_persist.o: {runtime['on']} bytes of FLASH with migration, {runtime['off']} with "
             f"`-DODG_NO_MIGRATION`: the migration code costs {runtime['on'] - runtime['off']} bytes.", "",
             "| input | persisted entries | dictionary FLASH on / off | layout descriptor tables | "
             "NV, two slots on / off | per entry on / off | regions with headroom (per entry) |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        if "refused" in r:
            lines.append(f"| {r['input']} | refused: {r['refused']} | | | | | |")
            continue
        lines.append(f"| {r['input']} | {r['entries']} | {r['flash_on']} / {r['flash_off']} | {r['layout_bytes']} | "
                     f"{r['nv_on']} / {r['nv_off']} | {r['nv_per_entry_on']:.1f} / {r['nv_per_entry_off']:.1f} | "
                     f"{r['regions']} ({r['region_per_entry']:.1f}) |")
    lines += ["", "NV with migration: per slot a 24-byte header, the entry count, 6 descriptor bytes per entry and "
              "the values in wire format; without: a 20-byte header and the C struct of the mirror (padding and "
              "string terminators included). Both slots are counted; regions add the headroom (need + 50 %, "
              "rounded up to a power of two). The firmware's own descriptor is not a table: the runtime reads "
              "each record (index, sub, type, length) from the dictionary's entries and sub-entries.", ""]
    return "\n".join(lines)


def run(labels: dict[str, Path]) -> dict[str, object]:
    ensure_toolchain()
    runtime = runtime_flash()
    inputs = [("io-node", ROOT / "examples" / "io-node" / "io-node.eds",
               (ROOT / "examples" / "io-node" / "io-node.toml").read_text(encoding="utf-8"))]
    if synth_label(250) in labels:
        inputs.append((synth_label(250) + " (all persisted)", labels[synth_label(250)], PERSIST_ALL))
    rows = [measure(label, eds, options) for label, eds, options in inputs]
    return {"runtime": runtime, "rows": rows, "targets": [], "markdown": markdown(runtime, rows)}
