"""Footprint of generated dictionaries and of the runtime on Cortex-M4, next to CANopenNode v4.

Compiles with `arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -Os -ffunction-sections
-fdata-sections` (installed from apt when missing) and reads section and symbol sizes.
FLASH = text + rodata + data, RAM = data + bss, as in ../shared/notes/peer-measurements.md,
whose CANopenNode v4 figures (CANopenEditor's exporter, per object file) are the reference.
Writes benchmarks/results/footprint-latest.md and .json.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

from synth import synth_eds

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BUILD = ROOT / "build" / "bench" / "footprint"
RESULTS = HERE / "results"
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
ODGEN = [sys.executable, "-m", "odgen"]
CFLAGS = ["-mcpu=cortex-m4", "-mthumb", "-Os", "-ffunction-sections", "-fdata-sections", "-std=c99",
          "-Wall", "-Wextra", "-Werror", "-pedantic"]

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
CORPUS_INPUTS = {
    "ds301_canopennode": "canopennode__DS301_profile.eds",
    "demodevice_canopendemo": "canopendemo__demoDevice.eds",
    "sample_canopen": "pycanopen__sample.eds",
    "big_e35": "pycanopen__e35.eds",
    "ds401_canfestival": "canfestival__DS401_Slave_Gui.eds",
}
SYNTH = {"synth_250_common": 250, "synth_1000_common": 1000, "synth_2000_common": 2000, "synth_4000_common": 4000}


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


def compile_one(source: Path, out: Path) -> Path:
    subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-I{ROOT / 'runtime'}", "-c", str(source), "-o", str(out)],
                   check=True, capture_output=True, text=True)
    return out


def by_class(syms: dict[str, int]) -> dict[str, int]:
    """Bytes of values per storage class, from the generated symbols of dictionary `od`."""
    classes = {"rom values (FLASH)": syms.get("od_rom", 0), "ram values (RAM)": syms.get("od_ram", 0),
               "ram defaults (FLASH)": syms.get("od_ram_defaults", 0)}
    classes["persist mirrors (RAM)"] = sum(v for k, v in syms.items()
                                           if k.startswith("od_persist_") and not k.endswith("_defaults"))
    classes["persist defaults (FLASH)"] = sum(v for k, v in syms.items()
                                              if k.startswith("od_persist_") and k.endswith("_defaults"))
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
        errors = sum(1 for line in gen.stderr.splitlines() if ": error[" in line)
        row["refused"] = f"lint: {errors} error(s)"
        return row
    obj = compile_one(work / "od.c", work / "od.o")
    sec = sections(obj)
    flash, ram = sec["text"] + sec["rodata"] + sec["data"], sec["data"] + sec["bss"]
    row.update(sec, flash=flash, ram=ram, classes=by_class(symbols(obj)))
    ref = CANOPENNODE.get(label)
    if ref is not None:
        rom, ref_ram, data = ref
        row["cnn_flash"], row["cnn_ram"] = rom + data, ref_ram
        row["flash_ratio"], row["ram_ratio"] = flash / (rom + data), ram / ref_ram
    return row


def runtime_sizes() -> dict[str, object]:
    work = BUILD / "runtime"
    work.mkdir(parents=True, exist_ok=True)
    sizes = {}
    for name in ("odg", "odg_persist"):
        sec = sections(compile_one(ROOT / "runtime" / f"{name}.c", work / f"{name}.o"))
        sizes[name] = sec["text"] + sec["rodata"] + sec["data"]
    core = work / "core.c"
    core.write_text('#include "odg.h"\nextern const odg_dict_t d;\nint main(void);\n'
                    "int main(void) { odg_ref_t r; unsigned char b[8]; uint32_t n;\n"
                    "  if (odg_find(&d, 0x1000, 0, &r)) return 1;\n"
                    "  if (odg_read(&r, 0, b, sizeof b, &n)) return 2;\n"
                    "  return (int)odg_write(&r, b, n); }\n")
    out = work / "core.elf"
    runtime_objs = []
    for name in ("odg", "odg_persist"):
        obj = work / f"{name}-notext.o"
        subprocess.run(["arm-none-eabi-gcc", *CFLAGS, "-DODG_NO_ABORT_TEXT", f"-I{ROOT / 'runtime'}", "-c",
                        str(ROOT / "runtime" / f"{name}.c"), "-o", str(obj)], check=True, capture_output=True)
        runtime_objs.append(obj)
    subprocess.run(["arm-none-eabi-gcc", *CFLAGS, f"-I{ROOT / 'runtime'}", str(core), *map(str, runtime_objs),
                    "--specs=nosys.specs", "-nostartfiles", "-Wl,--gc-sections", "-Wl,--defsym=d=0",
                    "-Wl,-e,main", "-o", str(out)], check=True, capture_output=True, text=True)
    ours = set().union(*(symbols(obj).keys() for obj in runtime_objs))
    # what the linker kept of the runtime: libc's memcpy/memset are not counted
    sizes["core_find_read_write"] = sum(v for k, v in symbols(out).items() if k in ours)
    return sizes


def _markdown(rows: list[dict[str, object]], runtime: dict[str, object]) -> str:
    lines = ["# Footprint on Cortex-M4 (arm-none-eabi-gcc -Os, per object file)", "",
             "FLASH = text + rodata + data, RAM = data + bss. CANopenNode v4 figures from "
             "../shared/notes/peer-measurements.md (its FLASH = ROM + data image). Targets: RAM <= 50%, "
             "FLASH <= 100%.", "",
             "| input | lookup | text | rodata | data | bss | FLASH | RAM | CANopenNode FLASH / RAM "
             "| FLASH % | RAM % |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        if "refused" in r:
            lines.append(f"| {r['input']} | {r['lookup']} | {r['refused']} | | | | | | | | |")
            continue
        ref = f"{r.get('cnn_flash', '-')} / {r.get('cnn_ram', '-')}"
        fr = f"{100 * r['flash_ratio']:.0f}%" if "flash_ratio" in r else "-"
        rr = f"{100 * r['ram_ratio']:.0f}%" if "ram_ratio" in r else "-"
        lines.append(f"| {r['input']} | {r['lookup']} | {r['text']} | {r['rodata']} | {r['data']} | {r['bss']} "
                     f"| {r['flash']} | {r['ram']} | {ref} | {fr} | {rr} |")
    lines += ["", "## Where the bytes go (switch lookup)", "", "| input | " +
              " | ".join(next(iter([r["classes"] for r in rows if "classes" in r]), {}).keys()) + " |"]
    lines.append("|---|" + "---:|" * len(next(iter([r["classes"] for r in rows if "classes" in r]), {})))
    for r in rows:
        if "classes" in r and r["lookup"] == "switch":
            lines.append(f"| {r['input']} | " + " | ".join(str(v) for v in r["classes"].values()) + " |")
    lines += ["", "## Runtime", "",
              f"- odg.o: {runtime['odg']} bytes of FLASH; odg_persist.o: {runtime['odg_persist']} bytes",
              f"- core path (odg_find + odg_read + odg_write and what they call, linked with --gc-sections, "
              f"no abort texts): {runtime['core_find_read_write']} bytes; target 1024 bytes: "
              f"{'met' if int(runtime['core_find_read_write']) <= 1024 else 'NOT met'}"]
    return "\n".join(lines) + "\n"


def main() -> None:
    ensure_toolchain()
    BUILD.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    inputs = {label: CORPUS / name for label, name in CORPUS_INPUTS.items() if (CORPUS / name).is_file()}
    for label, n in SYNTH.items():
        path = BUILD / f"{label}.eds"
        path.write_text(synth_eds(n), encoding="utf-8")
        inputs[label] = path
    rows = [measure(label, path, lookup) for label, path in inputs.items() for lookup in ("switch", "bsearch")]
    runtime = runtime_sizes()
    (RESULTS / "footprint-latest.json").write_text(json.dumps({"rows": rows, "runtime": runtime}, indent=2) + "\n")
    report = _markdown(rows, runtime)
    (RESULTS / "footprint-latest.md").write_text(report)
    print(report)


if __name__ == "__main__":
    main()
