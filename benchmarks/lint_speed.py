"""Whole-process lint speed: `odgen lint` against `canopen.import_od`, same inputs, same run.

Writes benchmarks/results/lint-latest.md and lint-latest.json. Figures are
medians of repeated whole-process runs (interpreter start-up included, as in
../shared/notes/peer-measurements.md); the comparison is a ratio from this run.
"""

from __future__ import annotations

import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

from synth import synth_eds

HERE = Path(__file__).resolve().parent
BUILD = HERE.parent / "build" / "bench"
RESULTS = HERE / "results"
SIZES = (1000, 4000)
REPEAT = 5
TARGET_S = 0.3  # parse + lint of 4000 objects


def _median_seconds(cmd: list[str]) -> float:
    times = []
    for _ in range(REPEAT):
        start = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, check=False)
        times.append(time.perf_counter() - start)
        if proc.returncode not in (0, 1):
            raise SystemExit(f"{cmd} failed: {proc.stderr.decode(errors='replace')}")
    return statistics.median(times)


def _in_process_lint(path: Path) -> float:
    code = ("import time,sys; from odgen.lint import lint_path; from odgen.rules import LintOptions;"
            "t=time.perf_counter(); lint_path(sys.argv[1], LintOptions()); print(time.perf_counter()-t)")
    runs = [float(subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True,
                                 text=True, check=True).stdout) for _ in range(REPEAT)]
    return statistics.median(runs)


def measure(n: int) -> dict[str, float | int]:
    path = BUILD / f"synth_{n}.eds"
    path.write_text(synth_eds(n), encoding="utf-8")
    odgen = _median_seconds([sys.executable, "-m", "odgen", "lint", str(path)])
    peer = _median_seconds([sys.executable, "-c",
                            "import sys, canopen; canopen.import_od(sys.argv[1])", str(path)])
    return {"objects": n, "odgen_lint_s": odgen, "odgen_parse_lint_in_process_s": _in_process_lint(path),
            "canopen_import_od_s": peer, "speedup": peer / odgen}


def _markdown(rows: list[dict], machine: dict) -> str:
    lines = [f"# Lint speed (whole process, median of {REPEAT})", "",
             f"Machine: {machine['cpu']} ({machine['cores']} cores), Python {machine['python']}", "",
             "| objects | odgen lint | parse+lint in process | canopen import_od | odgen speed-up |",
             "|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['objects']} | {r['odgen_lint_s']:.3f} s | {r['odgen_parse_lint_in_process_s']:.3f} s "
                     f"| {r['canopen_import_od_s']:.3f} s | {r['speedup']:.1f}x |")
    big = next(r for r in rows if r["objects"] == 4000)
    met = "met" if big["odgen_parse_lint_in_process_s"] <= TARGET_S else "NOT met"
    lines += ["", f"Target: parse+lint of 4000 objects under {TARGET_S} s: "
              f"{big['odgen_parse_lint_in_process_s']:.3f} s, {met}."]
    return "\n".join(lines) + "\n"


def main() -> None:
    BUILD.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    machine = {"cpu": platform.processor() or platform.machine(), "cores": os.cpu_count(),
               "python": platform.python_version(), "system": platform.platform()}
    rows = [measure(n) for n in SIZES]
    (RESULTS / "lint-latest.json").write_text(json.dumps({"machine": machine, "results": rows}, indent=2) + "\n")
    report = _markdown(rows, machine)
    (RESULTS / "lint-latest.md").write_text(report)
    print(report)


if __name__ == "__main__":
    main()
