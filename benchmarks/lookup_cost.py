"""Instructions per lookup, counted with callgrind: odg_find in each --lookup mode against a
plain binary search over the same sorted const index table (what CANopenNode's OD_find does).

For each input, a driver looks up every index of the dictionary REPEAT times; callgrind's
inclusive instruction count of the lookup function divided by the number of lookups is the
cost. Counts, not seconds, so a noisy machine gives the same figures. Writes
benchmarks/results/lookup-latest.md and .json.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

from synth import synth_eds

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BUILD = ROOT / "build" / "bench" / "lookup"
RESULTS = HERE / "results"
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
REPEAT = 20
INPUTS = {"ds301_canopennode": CORPUS / "canopennode__DS301_profile.eds",
          "demodevice_canopendemo": CORPUS / "canopendemo__demoDevice.eds"}

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


def measure(label: str, eds: Path, lookup: str) -> dict[str, object]:
    work = BUILD / f"{label}-{lookup}"
    subprocess.run([sys.executable, "-m", "odgen", "generate", str(eds), "-o", str(work), "--name", "od",
                    "--lookup", lookup], check=True, capture_output=True)
    (work / "driver.c").write_text(DRIVER)
    exe = work / "driver"
    subprocess.run(["gcc", "-std=gnu99", "-O2", f"-DREPEAT={REPEAT}", f"-I{ROOT / 'runtime'}", f"-I{work}",
                    str(work / "driver.c"), str(work / "od.c"), str(ROOT / "runtime" / "odg.c"),
                    str(ROOT / "runtime" / "odg_persist.c"), "-lm", "-o", str(exe)], check=True)
    counts = _callgrind(exe, work / "callgrind.out")
    found = re.search(r"odg_entry_t od_entries\[(\d+)\]", (work / "od.c").read_text())
    entries = int(found.group(1)) if found else 0
    lookups = REPEAT * entries
    ours, plain = counts["odg_lookup"] / lookups, counts["plain_bsearch"] / lookups
    return {"input": label, "lookup": lookup, "entries": entries, "odg_find": ours, "plain_bsearch": plain,
            "ratio": ours / plain}


def main() -> None:
    BUILD.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    inputs = {k: v for k, v in INPUTS.items() if v.is_file()}
    for n in (250, 4000):
        path = BUILD / f"synth_{n}.eds"
        path.write_text(synth_eds(n))
        inputs[f"synth_{n}_common"] = path
    rows = [measure(label, path, mode) for label, path in inputs.items() for mode in ("switch", "bsearch")]
    lines = ["# Lookup cost (callgrind instructions per lookup, every index of each input)", "",
             "odg_find includes the sub-index step (sub 0) and the call; the plain binary search finds the "
             "index only. Target: odg_find <= 50% of the plain binary search.", "",
             "| input | entries | --lookup | odg_find | plain bsearch | ratio |", "|---|---:|---|---:|---:|---:|"]
    lines += [f"| {r['input']} | {r['entries']} | {r['lookup']} | {r['odg_find']:.1f} | {r['plain_bsearch']:.1f} "
              f"| {100 * float(r['ratio']):.0f}% |" for r in rows]
    (RESULTS / "lookup-latest.json").write_text(json.dumps(rows, indent=2) + "\n")
    (RESULTS / "lookup-latest.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
