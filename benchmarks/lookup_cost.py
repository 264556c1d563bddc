"""Instructions per lookup, counted with callgrind: odg_find in each --lookup mode against a
plain binary search over the same sorted const index table (what CANopenNode's OD_find does).

For each input, a driver looks up every index of the dictionary REPEAT times; callgrind's
inclusive instruction count of the lookup function divided by the number of lookups is the
cost. Counts, not seconds, so a noisy machine gives the same figures. run.py runs this part.
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

from common import BUILD as BENCH
from common import ODGEN, Target

from odgen import toolchain

BUILD = BENCH / "lookup"
REPEAT = 20
TARGET = 0.5
MODES = ("switch", "bsearch")

DRIVER = r"""
#include "odg.h"
#include "od.h"
/* What CANopenNode's OD_find does: binary search over the sorted index table. */
__attribute__((noinline)) static int32_t plain_bsearch(const odg_entry_t *e, uint16_t n, uint16_t index)
{
    uint16_t lo = 0, hi = n;
    while (lo < hi) {
        uint16_t mid = (uint16_t)((lo + hi) / 2u);
        if (e[mid].index == index) return mid;
        if (e[mid].index < index) lo = (uint16_t)(mid + 1u); else hi = mid;
    }
    return -1;
}
__attribute__((noinline)) static odg_abort_t odg_lookup(uint16_t index, odg_ref_t *ref)
{
    return odg_find(&od, index, 0, ref);
}
int main(void)
{
    volatile int32_t sink = 0;
    odg_ref_t ref;
    unsigned r, i;
    for (r = 0; r < REPEAT; r++) {
        for (i = 0; i < od.n_entries; i++) {
            sink += (int32_t)odg_lookup(od.entries[i].index, &ref);
            sink += plain_bsearch(od.entries, od.n_entries, od.entries[i].index);
        }
    }
    return sink == 12345;
}
"""


def _callgrind(exe: Path, out: Path) -> dict[str, int]:
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe)],
                   capture_output=True, text=True, check=False)
    report = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(out)], capture_output=True, text=True,
                            check=True).stdout
    counts = {}
    for line in report.splitlines():
        m = re.match(r"\s*([\d,]+)\s.*?:(odg_lookup|plain_bsearch)\b", line)
        if m:
            counts[m.group(2)] = int(m.group(1).replace(",", ""))
    return counts


def ensure_valgrind() -> None:
    if shutil.which("valgrind"):
        return
    subprocess.run(["apt-get", "update", "-qq"], check=True)
    subprocess.run(["apt-get", "install", "-y", "-qq", "valgrind"], check=True)


def measure(label: str, eds: Path, lookup: str) -> dict[str, object]:
    work = BUILD / f"{label}-{lookup}"
    gen = subprocess.run([*ODGEN, "generate", str(eds), "-o", str(work), "--name", "od", "--lookup", lookup],
                         capture_output=True, check=False)
    if gen.returncode != 0:
        return {"input": label, "lookup": lookup, "refused": True}
    (work / "driver.c").write_text(DRIVER)
    exe = work / "driver"
    includes = [f"-I{d}" for d in [*toolchain.include_dirs(), work]]
    comp = subprocess.run(["gcc", "-std=gnu99", "-O2", f"-DREPEAT={REPEAT}", *includes, str(work / "driver.c"),
                           str(work / "od.c"), *map(str, toolchain.core_sources()), "-lm", "-o", str(exe)],
                          capture_output=True, text=True, check=False)
    if comp.returncode != 0:
        first = next((ln for ln in comp.stderr.splitlines() if "error" in ln), "compile failed")
        return {"input": label, "lookup": lookup, "compile_failed": first.split("/")[-1][:140]}
    counts = _callgrind(exe, work / "callgrind.out")
    found = re.search(r"odg_entry_t od_entries\[(\d+)\]", (work / "od.c").read_text())
    entries = int(found.group(1)) if found else 0
    lookups = REPEAT * entries
    ours, plain = counts["odg_lookup"] / lookups, counts["plain_bsearch"] / lookups
    return {"input": label, "lookup": lookup, "entries": entries, "odg_find": ours, "plain_bsearch": plain,
            "ratio": ours / plain}


def targets(rows: list[dict[str, object]]) -> list[Target]:
    out = []
    for label in dict.fromkeys(str(r["input"]) for r in rows):
        mine = {str(r["lookup"]): r for r in rows if r["input"] == label}
        if any("refused" in r for r in mine.values()):
            out.append(Target(f"lookup cost vs plain binary search, {label}", f"<= {TARGET:.0%}",
                              "odgen refuses the input", "-", None))
            continue
        sw, bs = mine["switch"], mine["bsearch"]
        if "compile_failed" in sw or "compile_failed" in bs:
            out.append(Target(f"lookup cost vs plain binary search, {label}", f"<= {TARGET:.0%}",
                              "generated C does not compile", "-", False))
            continue
        out.append(Target(f"lookup cost vs plain binary search, {label} ({sw['entries']} entries)",
                          f"<= {TARGET:.0%}",
                          f"switch {sw['odg_find']:.0f}, bsearch {bs['odg_find']:.0f}, plain "
                          f"{sw['plain_bsearch']:.0f} instr/lookup",
                          f"switch {sw['ratio']:.0%}, bsearch {bs['ratio']:.0%}",
                          min(float(sw["ratio"]), float(bs["ratio"])) <= TARGET))  # type: ignore[arg-type]
    return out


def markdown(rows: list[dict[str, object]]) -> str:
    lines = ["## Lookup cost (callgrind instructions per lookup, every index of each input)", "",
             f"x86-64 gcc -O2; each index looked up {REPEAT} times. odg_find includes the sub-index step (sub 0) "
             "and the call; the plain binary search over the same sorted const table finds the index only.", "",
             "| input | entries | --lookup | odg_find | plain bsearch | ratio |", "|---|---:|---|---:|---:|---:|"]
    for r in rows:
        if "refused" in r or "compile_failed" in r:
            why = "refused" if "refused" in r else f"does not compile: {r['compile_failed']}"
            lines.append(f"| {r['input']} | - | {r['lookup']} | {why} | | |")
            continue
        lines.append(f"| {r['input']} | {r['entries']} | {r['lookup']} | {r['odg_find']:.1f} "
                     f"| {r['plain_bsearch']:.1f} | {float(r['ratio']):.0%} |")  # type: ignore[arg-type]
    return "\n".join(lines) + "\n"


def run(labels: dict[str, Path], broken: dict[tuple[str, str], str] | None = None) -> dict[str, object]:
    """`broken`: (input, mode) whose generated C is known not to compile (gcc can take minutes to say so)."""
    ensure_valgrind()
    BUILD.mkdir(parents=True, exist_ok=True)
    broken = broken or {}
    rows = [{"input": label, "lookup": mode, "compile_failed": broken[(label, mode)]} if (label, mode) in broken
            else measure(label, path, mode) for label, path in labels.items() for mode in MODES]
    return {"rows": rows, "targets": targets(rows), "markdown": markdown(rows)}
