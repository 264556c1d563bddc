"""Where the time of `odgen generate` goes for 4000 objects: stage times (fresh process per run,
median) and a cProfile summary by area of the code, so optimisation follows measurement.

Run as a module by run.py; `python profile_generate.py --stages FILE` is the child that times
one generation stage by stage and prints JSON.
"""

from __future__ import annotations

import json
import pstats
import statistics
import subprocess
import sys
import time
from pathlib import Path

from common import BUILD, ROOT

REPEAT = 5
AREAS = (("odgen/formats", "parse (odgen/formats)"), ("odgen/lint", "lint (odgen/lint)"),
         ("odgen/model", "model (odgen/model)"),
         ("odgen/codegen", "view-model (odgen/codegen)"), ("dict.", "templates (render)"),
         ("selftest.", "templates (render)"), ("jinja2", "jinja2 (template compile + runtime)"),
         ("importlib", "imports"), ("<frozen", "imports"))


# What was tried for the generation-speed targets, and what the measurements say is left.
TRIED = """What was tried for generation speed (4000 objects; in-process stage times before -> after):
reading keeps a section's values, lines and spellings in three dicts with the common key line read
inline, integer literals and values of a basic type read without the regex path and remembered
(parse 0.145 -> ~0.10 s); the OBJ lint checks share one walk over the dictionary (lint 0.095 ->
~0.04 s); compiled templates come from jinja2's bytecode cache (34 -> 2 ms); file-only commands run
without cyclic collection and end with os._exit after flushing (the teardown of a large model,
~30 ms). That brought `odgen lint` to 0.24x-0.26x of canopen (the goal, 0.25x, is met in
some runs).

For `odgen generate`: the large tables (value members, sub-entries, entries, name macros, accessors;
five rows per sub-entry) are printed by a `rows` filter, a printf-style line per row written in the
template and filled from the row's fields, instead of a jinja2 loop that yields every field and
piece of text separately (render 0.060 -> 0.034 s); the rows are NamedTuples or tuples, a
sub-entry's value in force, name identifier and comment are worked out once, its ODG_A_*/ODG_S_*
codes cached per combination, identifier() lowers ASCII names once, the NV layouts sort only the
persisted placements (view-model 0.138 -> 0.093 s, of which ~15 ms are the runtime configuration and
the perfect hash; with the benchmark's persistence group the NV layouts add 16 -> 13 ms); an options
entry's place is formatted once, not per matched sub-entry (place with the benchmark's options
24 -> 18 ms). Whole process 0.524 -> 0.431 s in one run (0.63x -> 0.52x canopen, objdictgen
6.4x -> 7.7x). Outside the stages the whole process spends ~35 ms starting the interpreter (site and
the editable install's finder ~20 ms, modules odgen imports anyway), ~15 ms importing the command
line and parsing arguments, ~5 ms reading the options file (tomllib), ~5 ms comparing the outputs
with the files already there, ~2 ms hashing the input.
Measured and dropped: reading each section's keys with one regex and dict(zip()) (slower than the
line loop for sections of a few keys, 5.5 vs 3.0 us for seven), reading a plain [section] line
inline, remembering int_literal() (no gain measurable); odgen from an installed wheel instead of
the editable install (no difference measurable in whole-process time); linting in a forked child
while the parent places, builds the view-model and renders (whole run 0.265 -> 0.250 s in-process:
the copy-on-write faults of the shared model cost the parent about half of the 35 ms of lint).
The command line now builds only the parser of the command that runs (-3.5 ms). What is left is
spread over every sub-entry in every stage (~35 us per sub-entry: parse 12, lint 5, place 2,
view-model 12, render 4) plus ~0.1 s of start-up and imports (jinja2 ~18 ms, making the 44
dataclasses of the modules generate imports ~20 ms, mostly the execs of their generated methods);
0.40x would need about 0.33 s, a reader and view-model with far fewer Python operations per
sub-entry."""


def stages(path: Path) -> dict[str, float]:
    """One generation, timed stage by stage by odgen's own pipeline (odgen.pipeline.run)."""
    start = time.perf_counter()
    from odgen.pipeline import STAGES, Request, run

    imported = time.perf_counter()
    result = run(Request(path, name="od"))  # the hash lookup: the default
    assert result.files, "the benchmark's input must generate"
    return {"import odgen": imported - start, **{stage: result.timings[stage] for stage in STAGES}}


def _area(filename: str) -> str:
    return next((label for key, label in AREAS if key in filename), "builtins + stdlib (called from every area), cli")


def _cprofile(eds: Path) -> tuple[float, dict[str, float], list[tuple[str, int, float, float]]]:
    work = BUILD / "profile"
    work.mkdir(parents=True, exist_ok=True)
    out = work / "generate.prof"
    subprocess.run([sys.executable, "-m", "cProfile", "-o", str(out), "-m", "odgen", "generate", str(eds), "-o",
                    str(work / "out"), "--name", "od"], check=True, capture_output=True, cwd=ROOT)
    stats = pstats.Stats(str(out))
    raw = stats.stats  # type: ignore[attr-defined]
    areas: dict[str, float] = {}
    for (filename, _, _), (_, _, tottime, _, _) in raw.items():
        areas[_area(filename)] = areas.get(_area(filename), 0.0) + tottime
    top = sorted(((f"{Path(fn).name}:{line}({name})", calls, tt, ct)
                  for (fn, line, name), (_, calls, tt, ct, _) in raw.items()), key=lambda t: -t[2])[:12]
    return stats.total_tt, areas, top  # type: ignore[attr-defined]


def run(eds: Path) -> dict[str, object]:
    child = [sys.executable, str(Path(__file__).resolve()), "--stages", str(eds)]
    samples = [json.loads(subprocess.run(child, capture_output=True, text=True, check=True, cwd=ROOT).stdout)
               for _ in range(REPEAT)]
    medians = {k: statistics.median(s[k] for s in samples) for k in samples[0]}
    total, areas, top = _cprofile(eds)
    total_stages = sum(medians.values())
    lines = [f"## Where `odgen generate` spends its time ({eds.name})", "",
             f"Stages, in process, fresh interpreter per run, median of {REPEAT}:", "",
             "| stage | seconds | share |", "|---|---:|---:|"]
    lines += [f"| {k} | {v:.3f} | {v / total_stages:.0%} |" for k, v in medians.items()]
    lines += [f"| total | {total_stages:.3f} | |", "",
              f"cProfile of the whole command ({total:.2f} s under the profiler), own time by area:", "",
              "| area | own time | share |", "|---|---:|---:|"]
    lines += [f"| {k} | {v:.3f} s | {v / total:.0%} |" for k, v in sorted(areas.items(), key=lambda kv: -kv[1])]
    lines += ["", "Top functions by own time:", "", "| function | calls | own | cumulative |", "|---|---:|---:|---:|"]
    lines += [f"| `{name}` | {calls} | {tt:.3f} s | {ct:.3f} s |" for name, calls, tt, ct in top]
    lines += ["", TRIED]
    return {"stages_s": medians, "cprofile_total_s": total, "areas_s": areas,
            "top": [list(t) for t in top], "markdown": "\n".join(lines) + "\n"}


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--stages":
        print(json.dumps(stages(Path(sys.argv[2]))))
    else:
        sys.exit("usage: profile_generate.py --stages FILE (run.py runs the profile)")
