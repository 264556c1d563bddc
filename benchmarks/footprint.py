"""Footprint of generated dictionaries and of the runtime on Cortex-M4, next to CANopenNode v4.

Compiles with `arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -Os -ffunction-sections
-fdata-sections` (installed from apt when missing) and reads section and symbol sizes.
FLASH = text + rodata + data, RAM = data + bss, as in ../shared/notes/peer-measurements.md,
whose CANopenNode v4 figures (CANopenEditor's exporter, per object file) are the reference.
objdictgen's C is compiled too when CanFestival's headers are given (CANFESTIVAL_INCLUDE): its
PyPI package ships none. run.py runs this part.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from common import BUILD as BENCH
from common import ODGEN, PEER_VENV, Target, failure

from odgen import toolchain

BUILD = BENCH / "footprint"
# The Cortex-M4 target's flags (the first five, used alone for peers' C), then odgen's own C flags.
CFLAGS = ["-mcpu=cortex-m4", "-mthumb", "-Os", "-ffunction-sections", "-fdata-sections", *toolchain.CFLAGS]
RUNTIME = toolchain.include_dirs()[0]

# CANopenNode v4 per input, from the notes: (ROM = text + rodata, RAM = data + bss, data).
CANOPENNODE = {
    "ds301_canopennode": (1688, 976, 976),
    "demodevice_canopendemo": (1984, 1596, 1596),
    "sample_canopen": (1116, 784, 784),
    "big_e35": (8476, 5164, 5164),
    "synth_250_common": (6040, 6068, 6068),
    "synth_1000_common": (26076, 25284, 25284),
    "synth_2000_common": (50400, 50172, 50172),
    "synth_4000_common": (101980, 100644, 100644),
}
LINKED = ("ds301_canopennode", "demodevice_canopendemo")  # compared linked instead: linked.py
def ensure_toolchain() -> None:
    if shutil.which("arm-none-eabi-gcc"):
        return
    subprocess.run(["apt-get", "update", "-qq"], check=True)
    subprocess.run(["apt-get", "install", "-y", "-qq", "gcc-arm-none-eabi"], check=True)


def sections(obj: Path) -> dict[str, int]:
    out = subprocess.run(["arm-none-eabi-size", "-A", str(obj)], capture_output=True, text=True, check=True).stdout
    totals = {"text": 0, "rodata": 0, "data": 0, "bss": 0}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 2 and parts[0].startswith(".") and parts[1].isdigit():
            kind = parts[0].split(".")[1]
            if kind in totals:
                totals[kind] += int(parts[1])
    return totals


def symbols(obj: Path) -> dict[str, int]:
    out = subprocess.run(["arm-none-eabi-nm", "-S", str(obj)], capture_output=True, text=True, check=True).stdout
    return {p[3]: int(p[1], 16) for p in (line.split() for line in out.splitlines()) if len(p) == 4}


def _first_error(stderr: str) -> str:
    line = next((ln for ln in stderr.splitlines() if "error" in ln), "compile failed")
    return line.split("/")[-1][:140]


def compile_one(source: Path, out: Path) -> Path:
    subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-I{RUNTIME}", "-c", str(source), "-o", str(out)],
                   check=True, capture_output=True, text=True)
    return out


def by_class(syms: dict[str, int]) -> dict[str, int]:
    """Bytes of values per storage class, from the generated symbols of dictionary `od`."""
    classes = {"rom values (FLASH)": syms.get("od_rom", 0), "ram values (RAM)": syms.get("od_ram", 0),
               "ram defaults (FLASH)": syms.get("od_ram_defaults", 0)}
    classes["persist mirrors (RAM)"] = sum(v for k, v in syms.items()
                                           if k.startswith("od_persist_") and not k.endswith(("_defaults", "_spread")))
    classes["persist defaults (FLASH)"] = sum(v for k, v in syms.items()
                                              if k.startswith("od_persist_") and k.endswith(("_defaults", "_spread")))
    classes["tables (FLASH)"] = sum(syms.get(f"od_{t}", 0) for t in ("entries", "subs", "limits", "domains",
                                                                   "hook_map", "groups")) + syms.get("od", 0)
    classes["hook slots + state (RAM)"] = syms.get("od_hook_slots", 0) + syms.get("od_state", 0)
    return classes


def measure(label: str, eds: Path, lookup: str) -> dict[str, object]:
    work = BUILD / f"{label}-{lookup}"
    gen = subprocess.run([*ODGEN, "generate", str(eds), "-o", str(work), "--name", "od", "--lookup", lookup],
                         capture_output=True, text=True, check=False)
    row: dict[str, object] = {"input": label, "lookup": lookup}
    if gen.returncode != 0:
        row["refused"] = failure(gen.stderr)
        return row
    comp = subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-I{RUNTIME}", "-c", str(work / "od.c"), "-o",
                           str(work / "od.o")], capture_output=True, text=True, check=False)
    if comp.returncode != 0:
        row["compile_failed"] = _first_error(comp.stderr)
        return row
    obj = work / "od.o"
    sec = sections(obj)
    flash, ram = sec["text"] + sec["rodata"] + sec["data"], sec["data"] + sec["bss"]
    row.update(sec, flash=flash, ram=ram, classes=by_class(symbols(obj)))
    ref = CANOPENNODE.get(label)
    if ref is not None:
        rom, ref_ram, data = ref
        row["cnn_flash"], row["cnn_ram"] = rom + data, ref_ram
        row["flash_ratio"], row["ram_ratio"] = flash / (rom + data), ram / ref_ram
        if ram > ref_ram / 2 and lookup == "bsearch" and label not in LINKED:  # RAM goal not met: what it holds
            row["ram_why"] = ram_reasons(eds)
    return row


def ram_reasons(eds: Path) -> dict[str, int]:
    """Bytes of the dictionary's RAM values by why odgen placed each there (the placement's reason,
    as `odgen explain` prints it), from odgen's own view-model; padding between values not counted."""
    from odgen.codegen.viewmodel import member_bytes
    from odgen.pipeline import Request, run

    result = run(Request(eds, name="od", lookup="bsearch"), until="view")
    view = result.view
    if result.placements is None or view is None:
        return {}
    reasons: dict[str, int] = {}
    for member in (m for struct in view.structs if struct.name == "od_ram" for m in struct.members):
        why = result.placements[member.key].storage_from
        reasons[why] = reasons.get(why, 0) + member_bytes(member)
    return dict(sorted(reasons.items(), key=lambda kv: -kv[1]))


def _core_path(work: Path, defines: list[str]) -> int:
    """Bytes of runtime code the linker keeps for odg_find + odg_read + odg_write (libc not counted)."""
    core = work / "core.c"
    core.write_text('#include "odg.h"\nextern const odg_dict_t d;\nint main(void);\n'
                    "int main(void) { odg_ref_t r; unsigned char b[8]; uint32_t n;\n"
                    "  if (odg_find(&d, 0x1000, 0, &r)) return 1;\n"
                    "  if (odg_read(&r, 0, b, sizeof b, &n)) return 2;\n"
                    "  return (int)odg_write(&r, b, n); }\n")
    tag = "-".join(d.lstrip("-D").lower() for d in defines) or "default"
    objs = []
    for source in toolchain.core_sources():
        obj = work / f"{source.stem}-{tag}.o"
        subprocess.run(["arm-none-eabi-gcc", *CFLAGS, *defines, f"-I{RUNTIME}", "-c",
                        str(source), "-o", str(obj)], check=True, capture_output=True)
        objs.append(obj)
    out = work / f"core-{tag}.elf"
    subprocess.run(["arm-none-eabi-gcc", *CFLAGS, *defines, f"-I{RUNTIME}", str(core), *map(str, objs),
                    "--specs=nosys.specs", "-nostartfiles", "-Wl,--gc-sections", "-Wl,--defsym=d=0",
                    "-Wl,-e,main", "-o", str(out)], check=True, capture_output=True, text=True)
    ours = set().union(*(symbols(obj).keys() for obj in objs))
    return sum(v for k, v in symbols(out).items() if k in ours)


def runtime_sizes() -> dict[str, int]:
    work = BUILD / "runtime"
    work.mkdir(parents=True, exist_ok=True)
    sizes = {}
    for source in toolchain.core_sources():
        sec = sections(compile_one(source, work / f"{source.stem}.o"))
        sizes[source.stem] = sec["text"] + sec["rodata"] + sec["data"]
    sizes["core"] = _core_path(work, ["-DODG_NO_ABORT_TEXT"])
    return sizes


def objdictgen_sizes(labels: dict[str, Path]) -> tuple[str, list[dict[str, object]]]:
    """objdictgen's C for the same inputs, compiled the same way when CanFestival's headers are at hand."""
    include = [d for d in os.environ.get("CANFESTIVAL_INCLUDE", "").split(":") if d]
    odg = PEER_VENV / "bin" / "odg"
    if not odg.is_file():
        return "objdictgen is not installed (build/bench-venv): its C was not measured.", []
    if not include:
        return ("objdictgen's C was not compiled: the objdictgen 3.5.5 package ships no CanFestival headers "
                "(data.h, applicfg.h and the rest are not in the wheel) and CanFestival is not on any registry "
                "this machine reaches. Set CANFESTIVAL_INCLUDE=dir1:dir2 to a CanFestival include/ and "
                "include/<arch> to measure it."), []
    rows = []
    for label, eds in labels.items():
        work = BUILD / f"{label}-objdictgen"
        work.mkdir(parents=True, exist_ok=True)
        source = work / f"{label}.c"
        gen = subprocess.run([str(odg), "convert", str(eds), str(source)], capture_output=True, text=True, check=False)
        if gen.returncode != 0:
            rows.append({"input": label, "failed": "odg convert failed"})
            continue
        comp = subprocess.run(["arm-none-eabi-gcc", *CFLAGS[:5], *(f"-I{d}" for d in include), f"-I{work}", "-c",
                               str(source), "-o", str(work / f"{label}.o")], capture_output=True, text=True)
        if comp.returncode != 0:
            rows.append({"input": label, "failed": _first_error(comp.stderr)})
            continue
        sec = sections(work / f"{label}.o")
        rows.append({"input": label, **sec, "flash": sec["text"] + sec["rodata"] + sec["data"],
                     "ram": sec["data"] + sec["bss"]})
    return "objdictgen's generated C, compiled with the same flags against CANFESTIVAL_INCLUDE.", rows


def targets(rows: list[dict[str, object]]) -> list[Target]:
    """Per object file, for the inputs without a linked comparison (linked.py has DS301 and demoDevice)."""
    out = []
    for label, (rom, ref_ram, data) in CANOPENNODE.items():
        mine = [r for r in rows if r["input"] == label]
        if not mine or label in LINKED:
            continue
        flash_name, ram_name = f"FLASH vs CANopenNode v4 OD.c, {label}", f"RAM vs CANopenNode v4 OD.c, {label}"
        bad = next((r for r in mine if "refused" in r or "compile_failed" in r), None)
        if bad is not None:
            why = (f"odgen refuses the input ({bad['refused']})" if "refused" in bad
                   else f"generated C does not compile: {bad['compile_failed']}")
            met = None if "refused" in bad else False
            out += [Target(flash_name, "<= 100%", why, "-", met), Target(ram_name, "<= 50%", why, "-", met)]
            continue
        best = min(mine, key=lambda r: int(r["flash"]))  # type: ignore[call-overload]
        each = ", ".join(f"{r['lookup']} {r['flash']} B" for r in mine)
        out.append(Target(flash_name, "<= 100%", f"{each} / {rom + data} B",
                          f"{best['flash_ratio']:.0%} ({best['lookup']})", float(best["flash_ratio"]) <= 1.0))  # type: ignore[arg-type]
        out.append(Target(ram_name, "<= 50%", f"{best['ram']} B / {ref_ram} B",
                          f"{best['ram_ratio']:.0%}", float(best["ram_ratio"]) <= 0.5))  # type: ignore[arg-type]
    return out


def _ram_notes(rows: list[dict[str, object]]) -> list[str]:
    """Where the RAM goal (<= 50%) is not met: the RAM values by why each is in RAM."""
    notes = [f"- {r['input']}: RAM {r['ram']} B; its values by why they are in RAM: "
             + ", ".join(f"{why} {n} B" for why, n in r["ram_why"].items())  # type: ignore[attr-defined]
             for r in rows if r.get("ram_why")]
    if not notes:
        return []
    return ["", "### Where the RAM goal is not met", "",
            "odgen keeps a value in RAM only when a write may change it (over SDO or a PDO, or by the stack) or "
            "when it depends on the node-id; the rest is const in FLASH. Measured here (bsearch; `odgen explain` "
            "gives the reason per entry):", "", *notes]


def markdown(rows: list[dict[str, object]], runtime: dict[str, int], odg_note: str,
             odg_rows: list[dict[str, object]]) -> str:
    lines = ["## Footprint on Cortex-M4 (arm-none-eabi-gcc -Os, per object file)", "",
             "FLASH = text + rodata + data, RAM = data + bss. CANopenNode v4 figures from "
             "../shared/notes/peer-measurements.md (CANopenEditor's exporter; its FLASH = ROM + data image).", "",
             "| input | lookup | text | rodata | data | bss | FLASH | RAM | CANopenNode FLASH / RAM "
             "| FLASH % | RAM % |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if "refused" in r or "compile_failed" in r:
            why = f"refused: {r['refused']}" if "refused" in r else f"C does not compile: {r['compile_failed']}"
            lines.append(f"| {r['input']} | {r['lookup']} | {why} | | | | | | | | |")
            continue
        ref = f"{r.get('cnn_flash', '-')} / {r.get('cnn_ram', '-')}"
        fr = f"{r['flash_ratio']:.0%}" if "flash_ratio" in r else "-"
        rr = f"{r['ram_ratio']:.0%}" if "ram_ratio" in r else "-"
        lines.append(f"| {r['input']} | {r['lookup']} | {r['text']} | {r['rodata']} | {r['data']} | {r['bss']} "
                     f"| {r['flash']} | {r['ram']} | {ref} | {fr} | {rr} |")
    classes = next((r["classes"] for r in rows if "classes" in r), {})
    first = str(rows[0]["lookup"]) if rows else ""
    lines += ["", f"### Bytes by storage class ({first} lookup; the other modes differ only in lookup code)", "",
              "| input | " + " | ".join(classes) + " |", "|---|" + "---:|" * len(classes)]  # type: ignore[arg-type]
    for r in rows:
        if "classes" in r and r["lookup"] == first:
            lines.append(f"| {r['input']} | " + " | ".join(str(v) for v in r["classes"].values()) + " |")  # type: ignore[attr-defined]
    lines += _ram_notes(rows)
    lines += ["", "### objdictgen (CanFestival) generated C", "", odg_note]
    if odg_rows:
        lines += ["", "| input | text | rodata | data | bss | FLASH | RAM |", "|---|---:|---:|---:|---:|---:|---:|"]
        lines += [f"| {r['input']} | FAIL: {r['failed']} | | | | | |" if "failed" in r else
                  f"| {r['input']} | {r['text']} | {r['rodata']} | {r['data']} | {r['bss']} | {r['flash']} "
                  f"| {r['ram']} |" for r in odg_rows]
    lines += ["", "### Runtime", "",
              f"- odg.o: {runtime['odg']} bytes of FLASH; odg_persist.o: {runtime['odg_persist']} bytes",
              f"- core path (odg_find + odg_read + odg_write and what they call, linked with --gc-sections, "
              f"ODG_NO_ABORT_TEXT; odg_persist.o is offered to the linker but only attaches as a client, so "
              f"nothing of it is kept): {runtime['core']} bytes", ""]
    return "\n".join(lines)


def run(labels: dict[str, Path], modes: tuple[str, ...]) -> dict[str, object]:
    ensure_toolchain()
    BUILD.mkdir(parents=True, exist_ok=True)
    rows = [measure(label, path, lookup) for label, path in labels.items() for lookup in modes]
    runtime = runtime_sizes()
    odg_note, odg_rows = objdictgen_sizes(labels)
    return {"rows": rows, "runtime": runtime, "objdictgen": {"note": odg_note, "rows": odg_rows},
            "targets": targets(rows), "markdown": markdown(rows, runtime, odg_note, odg_rows)}
