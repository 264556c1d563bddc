"""Instructions per lookup, counted with callgrind, next to CANopenNode v4's published figures.

Method (../shared/notes/peer-measurements.md, sections 5 and 6): x86-64 gcc -O2; for every index
of the dictionary, find it and open sub-index 0 so that a read or write could follow (odgen:
`odg_find(&od, index, 0, &ref)`; CANopenNode: `OD_find` + `OD_getSub`), ROUNDS rounds;
valgrind callgrind's instructions of that run minus those of a run with 0 rounds, divided by the
lookups (so the loop's own few instructions are included, as in the published figures). Counts,
not seconds: a noisy machine gives the same figures. run.py runs this part.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

from common import BUILD as BENCH
from common import CORPUS, ODGEN, Target, synth_eds

from odgen import toolchain

BUILD = BENCH / "lookup"
ROUNDS = 200
TARGET = 0.5

# Inputs with the entry counts the issue names, and CANopenNode v4's instructions per lookup there.
# DS301's OD_find + OD_getSub is published (143); for the others only OD_find is (section 5: 131 at
# 211 entries, 165 at 1003, 197 at 4003), to which DS301's OD_getSub share (143 - 90 = 53) is added.
# demoDevice (47 entries) has no published figure: DS301's 143 stands in, a floor, since a binary
# search over more entries costs no less.
REFERENCE = {
    "ds301_canopennode": (143, "published"),
    "demodevice_canopendemo": (143, "DS301's figure (floor)"),
    "synth_208_common": (131 + 53, "OD_find published + DS301's OD_getSub"),
    "synth_1000_common": (165 + 53, "OD_find published + DS301's OD_getSub"),
    "synth_4000_common": (197 + 53, "OD_find published + DS301's OD_getSub"),
}
CORPUS_INPUTS = {"ds301_canopennode": "canopennode__DS301_profile.eds",
                 "demodevice_canopendemo": "canopendemo__demoDevice.xdd"}

DRIVER = r"""
#include <stdlib.h>
#include "od.h"
int main(int argc, char **argv)
{
    volatile uint32_t sink = 0;
    odg_ref_t ref;
    const odg_entry_t *e, *end = od.entries + od.n_entries;
    unsigned r, rounds = argc > 1 ? (unsigned)atoi(argv[1]) : 0u;
    for (r = 0; r < rounds; r++) {
        for (e = od.entries; e < end; e++) {
            sink += odg_find(&od, e->index, 0, &ref);
        }
    }
    return sink == 12345u;
}
"""


def lookup_inputs() -> dict[str, Path]:
    found = {label: CORPUS / name for label, name in CORPUS_INPUTS.items() if (CORPUS / name).is_file()}
    BENCH.mkdir(parents=True, exist_ok=True)
    for n in (208, 1000, 4000):  # plus 0x1000, 0x1001, 0x1018: 211, 1003 and 4003 entries
        path = BENCH / f"synth_{n}_common.eds"
        text = synth_eds(n)
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
        found[f"synth_{n}_common"] = path
    return found


def _instructions(exe: Path, out: Path, rounds: int) -> int:
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe), str(rounds)],
                   capture_output=True, text=True, check=False)
    found = re.search(r"^summary:\s*(\d+)", out.read_text(), re.MULTILINE)
    if found is None:
        raise RuntimeError(f"callgrind wrote no summary for {exe}")
    return int(found.group(1))


def ensure_valgrind() -> None:
    if shutil.which("valgrind"):
        return
    subprocess.run(["apt-get", "update", "-qq"], check=True)
    subprocess.run(["apt-get", "install", "-y", "-qq", "valgrind"], check=True)


def measure(label: str, source: Path, lookup: str) -> dict[str, object]:
    work = BUILD / f"{label}-{lookup}"
    gen = subprocess.run([*ODGEN, "generate", str(source), "-o", str(work), "--name", "od", "--lookup", lookup],
                         capture_output=True, check=False)
    if gen.returncode != 0:
        return {"input": label, "lookup": lookup, "refused": True}
    (work / "driver.c").write_text(DRIVER)
    exe = work / "driver"
    includes = [f"-I{d}" for d in [*toolchain.include_dirs(), work]]
    config = [f"-DODG_CONFIG=\"{(work / 'od_config.h').name}\""] if (work / "od_config.h").is_file() else []
    comp = subprocess.run(["gcc", "-std=gnu99", "-O2", *config, *includes, str(work / "driver.c"),
                           str(work / "od.c"), *map(str, toolchain.core_sources()), "-lm", "-o", str(exe)],
                          capture_output=True, text=True, check=False)
    if comp.returncode != 0:
        first = next((ln for ln in comp.stderr.splitlines() if "error" in ln), "compile failed")
        return {"input": label, "lookup": lookup, "compile_failed": first.split("/")[-1][:140]}
    entries = int(re.search(r"odg_entry_t od_entries\[(\d+)\]", (work / "od.c").read_text()).group(1))  # type: ignore[union-attr]
    loop = _instructions(exe, work / "callgrind.out", ROUNDS) - _instructions(exe, work / "callgrind0.out", 0)
    ours = loop / (ROUNDS * entries)
    ref, how = REFERENCE[label]
    return {"input": label, "lookup": lookup, "entries": entries, "odg_find": ours, "canopennode": ref,
            "reference": how, "ratio": ours / ref}


def targets(rows: list[dict[str, object]]) -> list[Target]:
    out = []
    for label in dict.fromkeys(str(r["input"]) for r in rows):
        mine = [r for r in rows if r["input"] == label and "ratio" in r]
        name = f"lookup vs CANopenNode OD_find + OD_getSub, {label}"
        if not mine:
            out.append(Target(name, f"<= {TARGET:.0%}", "odgen refuses the input or its C does not compile",
                              "-", None))
            continue
        best = min(mine, key=lambda r: float(r["ratio"]))  # type: ignore[arg-type]
        each = ", ".join(f"{r['lookup']} {float(r['odg_find']):.0f}" for r in mine)  # type: ignore[arg-type]
        out.append(Target(f"{name} ({best['entries']} entries)", f"<= {TARGET:.0%}",
                          f"{each} / {best['canopennode']} instr ({best['reference']})",
                          f"{float(best['ratio']):.0%} ({best['lookup']})",  # type: ignore[arg-type]
                          float(best["ratio"]) <= TARGET))  # type: ignore[arg-type]
    return out


def markdown(rows: list[dict[str, object]]) -> str:
    lines = ["## Lookup cost (callgrind instructions per find of index and sub-index 0)", "",
             __doc__.split("\n\n", 1)[1].split("run.py")[0].strip(), "",
             "| input | entries | --lookup | odgen | CANopenNode v4 | reference | ratio |",
             "|---|---:|---|---:|---:|---|---:|"]
    for r in rows:
        if "ratio" not in r:
            why = "refused" if "refused" in r else f"does not compile: {r['compile_failed']}"
            lines.append(f"| {r['input']} | - | {r['lookup']} | {why} | | | |")
            continue
        lines.append(f"| {r['input']} | {r['entries']} | {r['lookup']} | {float(r['odg_find']):.1f} "  # type: ignore[arg-type]
                     f"| {r['canopennode']} | {r['reference']} | {float(r['ratio']):.0%} |")  # type: ignore[arg-type]
    return "\n".join(lines) + "\n"


def run(modes: tuple[str, ...]) -> dict[str, object]:
    ensure_valgrind()
    BUILD.mkdir(parents=True, exist_ok=True)
    rows = [measure(label, path, mode) for label, path in lookup_inputs().items() for mode in modes]
    return {"rows": rows, "targets": targets(rows), "markdown": markdown(rows)}


if __name__ == "__main__":
    from odgen.choices import LOOKUPS
    print(run(LOOKUPS)["markdown"])
