"""Start-up, whole process: `odgen --version` and `odgen lint` of a small EDS, next to the bare
interpreter (`python -c pass`, the floor any Python tool pays), taking turns in one run.

A pre-commit hook or an editor runs `odgen lint` on every save or commit, so its start-up is
what users feel; lint of an EDS imports neither jinja2 nor lxml for that reason. The package's
bytecode is compiled first, as `pip install` does: with PYTHONDONTWRITEBYTECODE set (as on
these machines) a source checkout would otherwise be compiled anew on every run.
"""

from __future__ import annotations

import compileall
import sys

from common import ODGEN, ROOT, Target, interleaved, median, timed

REPEAT = 21
SMALL_EDS = ROOT / "examples" / "io-node" / "io-node.eds"
TARGETS_MS = {"odgen --version": 60.0, "odgen lint (small EDS)": 100.0}


def _commands() -> dict:
    return {
        "python -c pass": lambda: timed([sys.executable, "-c", "pass"]),
        "odgen --version": lambda: timed([*ODGEN, "--version"]),
        "odgen lint (small EDS)": lambda: timed([*ODGEN, "lint", str(SMALL_EDS)]),
    }


def run() -> dict[str, object]:
    compileall.compile_dir(str(ROOT / "odgen"), quiet=1)
    runs = interleaved(_commands(), REPEAT)
    rows = [{"command": name, "median_ms": round(median(r) * 1000, 1),
             "min_ms": round(min(x.seconds for x in r) * 1000, 1), "runs": len(r),
             "failed": sum(1 for x in r if x.returncode != 0)} for name, r in runs.items()]
    floor = rows[0]["median_ms"]
    targets = [Target(f"{name}, whole process", f"<= {goal:.0f} ms", f"{row['median_ms']} ms",
                      f"{row['median_ms'] / goal:.0%}", row["median_ms"] <= goal and not row["failed"])
               for name, goal in TARGETS_MS.items() for row in rows if row["command"] == name]
    lines = ["## Start-up", "", f"Median of {REPEAT} whole-process runs each, taking turns; `{SMALL_EDS.name}` is "
             f"{SMALL_EDS.stat().st_size} bytes; bytecode compiled beforehand, as an install does. The interpreter "
             "alone is the floor.", "",
             "| command | median | fastest | × interpreter |", "|---|---|---|---|"]
    lines += [f"| `{r['command']}` | {r['median_ms']} ms | {r['min_ms']} ms | {r['median_ms'] / floor:.1f} |"
              + (f" ({r['failed']} failed)" if r["failed"] else "") for r in rows]
    return {"rows": rows, "targets": targets, "markdown": "\n".join(lines) + "\n"}
