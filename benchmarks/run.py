"""`make bench`: runs every benchmark part and writes results/latest.md, latest.json and growth.svg.

Parts (each its own module): startup (whole-process `odgen --version` and `odgen lint` of a
small EDS against the bare interpreter), speed (whole-process generation speed against the peers),
profile (where `odgen generate` spends its time), footprint (Cortex-M4 sizes of each generated
object file against CANopenNode v4's OD.c), linked (dictionary + runtime linked into a firmware,
against CANopenNode v4's published figures), lookup (callgrind instructions per lookup, against
CANopenNode v4's published figures), migration (FLASH and NV cost of the boot migration of
stored parameters, on and off), master (the CiA 302 master's FLASH and RAM for 4 and 16
slaves), master_boot (the example machine's boot to all operational on vcan). Every target of
the benchmark issue is listed at the top of the results with the ratio this run measured, met
or not.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import footprint
import linked
import lookup_cost
import master_boot
import master_cost
import migration_cost
import profile_generate
import speed
import startup
from odgen.choices import LOOKUPS

from common import PEER_PYTHON, RESULTS, SYNTH_SIZES, Target, inputs, synth_label, targets_json

PARTS = ("startup", "speed", "profile", "footprint", "linked", "lookup", "migration", "master", "master_boot")
BUDGET_S = 600


def _first_line(cmd: list[str]) -> str:
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, check=False)
    except OSError:
        return "not installed"
    return (out.stdout or out.stderr).strip().splitlines()[0] if (out.stdout or out.stderr).strip() else "?"


def _peer_versions() -> str:
    if not PEER_PYTHON.is_file():
        return "not installed"
    code = "import importlib.metadata as m; print(', '.join(p + ' ' + m.version(p) for p in ('objdictgen', 'canopen')))"
    return _first_line([str(PEER_PYTHON), "-c", code])


def machine() -> dict[str, object]:
    cpu = next((ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
                if ln.startswith("model name")), platform.processor() or platform.machine())
    return {"cpu": cpu, "cores": os.cpu_count(), "system": platform.platform(),
            "python": platform.python_version(), "gcc": _first_line(["gcc", "--version"]),
            "arm-none-eabi-gcc": _first_line(["arm-none-eabi-gcc", "--version"]),
            "valgrind": _first_line(["valgrind", "--version"]), "peers": _peer_versions(),
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "load_average_start": os.getloadavg()}


def _markdown(info: dict[str, object], targets: list[Target], sections: list[str], wall: float) -> str:
    load = ", ".join(f"{x:.2f}" for x in info["load_average_start"])  # type: ignore[attr-defined]
    end = ", ".join(f"{x:.2f}" for x in info["load_average_end"])  # type: ignore[attr-defined]
    lines = ["# odgen benchmarks", "",
             f"Run {info['date']} on {info['cpu']} ({info['cores']} cores), {info['system']}; Python "
             f"{info['python']}; {info['gcc']}; {info['arm-none-eabi-gcc']}; {info['valgrind']}; peers: "
             f"{info['peers']}.", "",
             f"Load average (1, 5, 15 min) at the start: {load}; at the end: {end}. The machine is shared, so "
             "absolute times move between runs; every comparison below is a ratio of figures measured in this "
             "run, tools taking turns. Instruction counts (callgrind) and sizes do not depend on load.", "",
             f"Benchmark parts took {wall:.0f} s (`make bench` adds setup on a fresh clone; budget {BUDGET_S} s).",
             "", "## Targets", "", "| target | goal | measured | ratio | verdict |", "|---|---|---|---|---|"]
    lines += [t.row() for t in targets]
    return "\n".join(lines + [""] + sections)


def _refused(results: dict[str, dict[str, object]]) -> list[str]:
    rows = results.get("footprint", {}).get("rows", [])
    return list(dict.fromkeys(str(r["input"]) for r in rows if "refused" in r))  # type: ignore[attr-defined]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--parts", default=",".join(PARTS), help="comma-separated subset of " + ", ".join(PARTS))
    parser.add_argument("--sizes", default=",".join(map(str, SYNTH_SIZES)), help="synthetic sizes (objects)")
    parser.add_argument("--started", type=float, help="epoch seconds when `make bench` started (setup included)")
    args = parser.parse_args()
    parts = args.parts.split(",")
    started = args.started or time.time()
    info = machine()
    labels = inputs([int(n) for n in args.sizes.split(",")])
    results: dict[str, dict[str, object]] = {}
    if "startup" in parts:
        results["startup"] = startup.run()
    if "speed" in parts:
        results["speed"] = speed.run(labels)
    if "profile" in parts and synth_label(4000) in labels:
        results["profile"] = profile_generate.run(labels[synth_label(4000)])
    if "footprint" in parts:
        results["footprint"] = footprint.run(labels, LOOKUPS)
    if "linked" in parts:
        results["linked"] = linked.run(LOOKUPS)
    if "lookup" in parts:
        results["lookup"] = lookup_cost.run(LOOKUPS)
    if "migration" in parts:
        results["migration"] = migration_cost.run(labels)
    if "master" in parts:
        results["master"] = master_cost.run()
    if "master_boot" in parts:
        results["master_boot"] = master_boot.run()
    wall = time.time() - started
    info["load_average_end"] = os.getloadavg()
    targets: list[Target] = [t for r in results.values() for t in r.get("targets", [])]  # type: ignore[attr-defined]
    targets.append(Target("`make bench` wall time", f"<= {BUDGET_S} s", f"{wall:.0f} s", f"{wall / BUDGET_S:.0%}",
                          wall <= BUDGET_S))
    sections = [str(r["markdown"]) for r in results.values()]
    sections.append("## Notes\n\n" + NOTES.format(refused=", ".join(_refused(results)) or "none"))
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "latest.md").write_text(_markdown(info, targets, sections, wall))
    if "speed" in results:
        (RESULTS / "growth.svg").write_text(str(results["speed"]["svg"]))
    data = {"machine": info, "wall_s": wall, "targets": targets_json(targets),
            "parts": {k: {kk: vv for kk, vv in v.items() if kk not in ("markdown", "svg", "targets")}
                      for k, v in results.items()}}
    (RESULTS / "latest.json").write_text(json.dumps(data, indent=2) + "\n")
    print((RESULTS / "latest.md").read_text())
    sys.exit(0)


NOTES = """\
- Inputs: the real-world EDS files the notes measured the peers on, found by name in
  ../shared/corpus (ds402_cia402_slave is ros_canopen's copy, 18 bytes shorter than the notes'
  ros2_canopen copy), and synth.py's synthetic EDS files (N objects over 0x2000-0x5FFF, about
  60% VAR / 20% ARRAY / 20% RECORD of the common types, plus 0x1000/0x1001/0x1018, seed 1).
  Ours are the same shape as the notes' synthetic files but not the same files: ours have about
  1.4 sections per object and 260 bytes per object, so the CANopenNode v4 footprint figures for
  synth_* are for inputs of the same shape, not byte-identical ones.
- CANopenEditor (the CANopenNode v4 exporter) runs under Mono and is not installable here: its
  time and its CANopenNode v4 sizes are the notes' figures, labelled so. objdictgen and canopen are
  measured live, from build/bench-venv.
- odgen refuses descriptions with lint errors ({refused}): their generate time is
  the time to find the errors and refuse, and their footprint and lookup targets are marked "not
  measured" (the rule ids and counts are in the tables).
- The SDO speed comparison over vcan is `make bench-sdo` (results/sdo-latest.md): it boots a
  User-Mode Linux guest when the host has no vcan and would not fit the 10-minute budget. The
  master's boot time (master_boot) runs on vcan too, in one short guest (tools/vcan/run.py);
  without vcan its section says "not measured" and the rest of the bench stands.
"""


if __name__ == "__main__":
    main()
