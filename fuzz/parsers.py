"""Fuzz the EDS/DCF and XDD readers, the linter and the EDS writer with structural mutants.

    python fuzz/parsers.py --inputs 1000000 [--guided 100000] [--jobs 2] [--seed 1] [--no-corpus]

Two engines: structural mutants drawn at random (--inputs), and coverage-guided
libFuzzer runs through atheris (--guided executions, fuzz/guided.py). Every input
(fuzz/mutate.py) must yield diagnostics or a model, never an exception,
within bounded CPU time. Afterwards the slowest inputs per byte are measured again and
flagged when far above the median, and families of inputs grown 1x..64x check that the
time per byte stays flat. Findings are minimised and saved under tests/fuzz/regressions/
(which `make test` replays) and make the run exit 1. Results: fuzz/results/parsers.json
and parsers-scaling.json, rendered into docs/robustness.md by fuzz/report.py.
"""

from __future__ import annotations

import argparse
import heapq
import json
import multiprocessing
import os
import random
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from array import array
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from fuzz import mutate, scaling  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
CHUNK = 2000
SLOW_KEEP = 8  # slowest inputs per byte each chunk hands back for measuring again
SLOW_FACTOR = 20.0  # time per byte this many times the median, confirmed on re-measure, is a finding
SLOW_FLOOR_NS = 50_000_000  # ... and the input took at least this long: below it, noise dominates
MIN_SIZE = 256  # the median is over inputs at least this large (fixed costs dominate tiny ones)


@dataclass
class Tally:
    inputs: int = 0
    models: int = 0
    bytes: int = 0
    ns: int = 0
    per_op: Counter = field(default_factory=Counter)
    per_op_models: Counter = field(default_factory=Counter)
    per_op_failures: Counter = field(default_factory=Counter)
    per_byte: array = field(default_factory=lambda: array("d"))
    slow: list = field(default_factory=list)  # (ns per byte, cpu ns, fmt, data, ops)
    findings: dict = field(default_factory=dict)  # signature -> (fmt, data, ops, detail)

    def merge(self, other: Tally) -> None:
        self.inputs += other.inputs
        self.models += other.models
        self.bytes += other.bytes
        self.ns += other.ns
        for mine, theirs in ((self.per_op, other.per_op), (self.per_op_models, other.per_op_models),
                             (self.per_op_failures, other.per_op_failures)):
            mine.update(theirs)
        self.per_byte.extend(other.per_byte)
        self.slow = heapq.nlargest(4 * SLOW_KEEP, self.slow + other.slow, key=lambda s: s[0])
        for sig, finding in other.findings.items():
            self.findings.setdefault(sig, finding)


_SEEDS: list[mutate.Seed] = []


def _init(with_corpus: bool) -> None:
    _SEEDS.extend(mutate.load_seeds(with_corpus))


def run_chunk(task: tuple[int, int, int]) -> Tally:
    base, chunk, count = task
    rng = random.Random(f"{base}:{chunk}")
    tally = Tally()
    for mutant in mutate.mutants(_SEEDS, rng, count):
        outcome = mutate.check(mutant.data, mutant.fmt)
        _count(tally, mutant, outcome)
    return tally


def _count(tally: Tally, mutant: mutate.Mutant, outcome: mutate.Outcome) -> None:
    size = len(mutant.data)
    tally.inputs += 1
    tally.models += outcome.model
    tally.bytes += size
    tally.ns += outcome.ns
    ops = {f"format:{mutant.fmt}", *mutant.ops}
    tally.per_op.update(ops)
    if outcome.model:
        tally.per_op_models.update(ops)
    if outcome.failure:
        tally.per_op_failures.update(ops)
        tally.findings.setdefault(outcome.failure, (mutant.fmt, mutant.data, mutant.ops, outcome.detail))
    if size >= MIN_SIZE:
        per_byte = outcome.ns / size
        tally.per_byte.append(per_byte)
        item = (per_byte, outcome.ns, mutant.fmt, mutant.data, mutant.ops)
        if len(tally.slow) < SLOW_KEEP:
            heapq.heappush(tally.slow, item)
        elif per_byte > tally.slow[0][0]:
            heapq.heapreplace(tally.slow, item)


def fuzz(inputs: int, jobs: int, seed: int, with_corpus: bool, minutes: float) -> tuple[Tally, float]:
    """Run the chunks; a new finding is written at once (unminimised) so a cut run keeps it."""
    tasks = [(seed, i, min(CHUNK, inputs - i * CHUNK)) for i in range((inputs + CHUNK - 1) // CHUNK)]
    total, start = Tally(), time.monotonic()
    with multiprocessing.Pool(jobs, initializer=_init, initargs=(with_corpus,)) as pool:
        for done, tally in enumerate(pool.imap_unordered(run_chunk, tasks), start=1):
            for failure, (fmt, data, ops, detail) in tally.findings.items():
                if failure not in total.findings:
                    path = mutate.save_regression(data, fmt, failure)
                    print(f"parsers: FINDING {failure} ({' '.join(ops)}) -> {path}\n{detail}", file=sys.stderr)
            total.merge(tally)
            wall = time.monotonic() - start
            if done % 25 == 0 or done == len(tasks):
                _progress(total, inputs, wall)
            if minutes and wall > minutes * 60:
                print(f"parsers: time budget of {minutes:g} min spent after {total.inputs} inputs", file=sys.stderr)
                pool.terminate()
                break
    return total, time.monotonic() - start


def _progress(total: Tally, inputs: int, wall: float) -> None:
    rate = total.inputs / wall if wall else 0.0
    eta = (inputs - total.inputs) / rate if rate else 0.0
    print(f"parsers: {total.inputs}/{inputs} inputs, {rate:.0f}/s, {len(total.findings)} findings, "
          f"eta {eta / 60:.1f} min", file=sys.stderr, flush=True)


def confirm_slow(total: Tally, median: float) -> list[dict]:
    """Measure the slowest inputs again (best of 3); those still far above the median are findings."""
    slow = []
    for _, _, fmt, data, ops in total.slow:
        best = min(mutate.check(data, fmt).ns for _ in range(3))
        again = best / len(data)
        entry = {"size": len(data), "format": fmt, "ns_per_byte": round(again), "ops": ops,
                 "factor": round(again / median, 1)}
        if again > SLOW_FACTOR * median and best > SLOW_FLOOR_NS:
            total.findings.setdefault("superlinear", (fmt, data, ops, f"{again / median:.0f}x the median time/byte"))
        slow.append(entry)
    return sorted(slow, key=lambda e: -e["factor"])


def save_findings(total: Tally) -> list[dict]:
    saved = []
    for failure, (fmt, data, ops, _detail) in sorted(total.findings.items()):
        small = data if failure == "superlinear" else mutate.minimise(data, fmt, failure)
        path = mutate.save_regression(small, fmt, failure)
        if small != data:  # the minimised input replaces the one saved when it was found
            mutate.save_regression(data, fmt, failure).unlink()
        print(f"parsers: {failure} minimised to {len(small)} bytes -> {path}", file=sys.stderr)
        saved.append({"failure": failure, "file": str(path.relative_to(mutate.ROOT)), "ops": ops})
    return saved


def table(total: Tally, wall: float, jobs: int, seed: int, slow: list[dict], saved: list[dict],
          median: float, requested: int) -> dict:
    rows = []
    for op in sorted(total.per_op, key=lambda o: (o.split(":")[0] if ":" in o else "", o)):
        n = total.per_op[op]
        rows.append([op, n, total.per_op_models[op], n - total.per_op_models[op], total.per_op_failures[op]])
    notes = [
        f"{total.inputs} inputs ({total.bytes / 1e6:.1f} MB) from {len(_SEEDS) or len(mutate.seed_files())} seed "
        f"files, random seed {seed}, {jobs} processes, {wall / 60:.1f} min wall, {total.ns / 1e9 / 60:.1f} "
        f"min summed over the inputs ({total.inputs / wall:.0f} inputs/s).",
        f"{total.models} inputs gave a model, {total.inputs - total.models} diagnostics only; "
        f"{len(saved)} findings{': ' + ', '.join(s['failure'] for s in saved) if saved else ''}.",
        f"Median CPU time per byte (inputs >= {MIN_SIZE} bytes): {median:.0f} ns; slowest per byte, measured "
        f"again: {slow[0]['ns_per_byte'] if slow else 0} ns ({slow[0]['factor'] if slow else 0}x the median, "
        f"{slow[0]['size'] if slow else 0} bytes). A finding needs {SLOW_FACTOR:g}x and "
        f"{SLOW_FLOOR_NS / 1e6:g} ms.",
        "A row counts the inputs a mutation (or encoding, line end, format) took part in; one input "
        "usually combines several.",
    ]
    if total.inputs < requested:
        notes.insert(1, f"Cut by the time budget: {total.inputs} of the {requested} inputs asked for ran.")
    return {"title": "Parser fuzzing: structural mutants of the seed files", "inputs": total.inputs,
            "summary": f"{total.inputs} inputs, {total.models} with a model, {len(saved)} findings; median "
                       f"{median:.0f} ns per byte, slowest {slow[0]['factor'] if slow else 0}x the median.",
            "findings": saved, "slowest": slow[:10],
            "columns": ["mutation", "inputs", "model", "diagnostics only", "findings"], "rows": rows, "notes": notes}


def grown(results: Path) -> int:
    """The scaling families; one that is not linear is a finding, saved at its smallest size."""
    table_scaling = scaling.run()
    saved = []
    for row in table_scaling["rows"]:
        if row[-1] != "linear":
            path = mutate.save_regression(scaling.smallest(row[0]), row[1], f"superlinear-{row[0]}")
            print(f"parsers: FINDING {row[0]}: {row[-1]} -> {path}", file=sys.stderr)
            saved.append(row[0])
    table_scaling["findings"] = saved
    worst = max(row[-2] for row in table_scaling["rows"])
    table_scaling["summary"] = (f"{len(table_scaling['rows'])} families grown {scaling.FACTORS[-1]}x, "
                                f"{len(table_scaling['rows']) - len(saved)} linear; largest exponent k = {worst:.2f}.")
    (results / "parsers-scaling.json").write_text(json.dumps(table_scaling, indent=1) + "\n")
    return len(saved)


def guided(executions: int, jobs: int, seed: int) -> tuple[dict, list[dict]]:
    """libFuzzer through atheris, `jobs` processes of executions/jobs runs each, from slices of the seeds."""
    try:
        from fuzz import guided as harness  # atheris is needed for this engine only
    except ImportError as err:
        print(f"parsers: coverage-guided fuzzing not run: {err}", file=sys.stderr)
        return {"title": "Coverage-guided parser fuzzing (atheris, libFuzzer)", "executions": 0, "findings": [],
                "columns": [], "rows": [], "notes": [f"Not run: {err} (atheris has wheels for Linux x86-64)."]}, []
    rows, saved = [], []
    with tempfile.TemporaryDirectory(prefix="odgen-guided-") as tmp:
        log = Path(tmp) / "findings.jsonl"
        procs = []
        for job in range(jobs):
            corpus = Path(tmp) / f"corpus{job}"
            harness.write_corpus(corpus, random.Random(seed + job))
            cmd = [sys.executable, str(Path(__file__).with_name("guided.py")), str(corpus),
                   f"-runs={executions // jobs}", f"-seed={seed + job}", "-max_len=65536", "-timeout=60",
                   "-print_final_stats=1"]
            err = open(Path(tmp) / f"job{job}.log", "w+", encoding="utf-8")  # noqa: SIM115 (closed below)
            env = dict(os.environ, ODGEN_FUZZ_FINDINGS=str(log))
            procs.append((subprocess.Popen(cmd, stdout=err, stderr=subprocess.STDOUT, env=env), err, corpus))
        start = time.monotonic()
        for job, (proc, err, corpus) in enumerate(procs):
            code = proc.wait()
            err.seek(0)
            rows.append(_guided_row(job, err.read(), code, time.monotonic() - start, corpus))
            err.close()
            if code != 0:
                saved.append({"failure": f"guided job {job} exited {code}", "file": "", "ops": ["guided"]})
        if log.exists():
            saved += [json.loads(line) for line in log.read_text(encoding="utf-8").splitlines()]
        shutil.rmtree(tmp, ignore_errors=True)
    total = sum(r[1] for r in rows)
    edges = max((r[2] for r in rows), default=0)
    return {"title": "Coverage-guided parser fuzzing (atheris, libFuzzer)", "executions": total,
            "summary": f"{total} executions, {len(saved)} findings, {edges} Python branch edges reached.",
            "findings": saved, "columns": ["job", "executions", "coverage (edges)", "features", "corpus files",
                                           "exec/s", "exit"],
            "rows": rows,
            "notes": [f"{total} executions in {jobs} libFuzzer processes over odgen's instrumented Python code "
                      "(odgen.formats, odgen.lint.passes, odgen.lint.driver, odgen.model), starting from slices of "
                      "every seed "
                      "file; half of the mutations are libFuzzer's byte mutations, half the structural ones.",
                      f"{len(saved)} findings."]}, saved


def _guided_row(job: int, log: str, code: int, wall: float, corpus: Path) -> list:
    def stat(name: str) -> int:
        found = re.findall(rf"stat::{name}:\s*(\d+)", log)
        return int(found[-1]) if found else 0
    cov = re.findall(r"cov: (\d+) ft: (\d+)", log)
    executions = stat("number_of_executed_units")
    edges, features = cov[-1] if cov else (0, 0)
    files = len(list(corpus.iterdir())) if corpus.is_dir() else 0
    if code != 0:
        print(log[-4000:], file=sys.stderr)
    return [job, executions, int(edges), int(features), files, round(executions / wall) if wall else 0, code]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", type=int, default=1_000_000)
    parser.add_argument("--guided", type=int, default=100_000, help="coverage-guided executions (0: none)")
    parser.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--max-minutes", type=float, default=0.0,
                        help="stop the structural engine after this long and report the inputs run (0: no limit)")
    parser.add_argument("--no-scaling", action="store_true", help="skip the inputs grown 1x..256x")
    parser.add_argument("--no-corpus", action="store_true", help="seed from the repository's files only")
    parser.add_argument("--results", type=Path, default=RESULTS)
    args = parser.parse_args(argv)
    args.results.mkdir(parents=True, exist_ok=True)
    found = structural(args) if args.inputs else 0
    if not args.no_scaling:
        found += grown(args.results)
    if args.guided:
        table_guided, saved_guided = guided(args.guided, args.jobs, args.seed)
        (args.results / "parsers-guided.json").write_text(json.dumps(table_guided, indent=1) + "\n")
        found += len(saved_guided)
    print(f"parsers: {found} findings", file=sys.stderr)
    return 1 if found else 0


def structural(args: argparse.Namespace) -> int:
    total, wall = fuzz(args.inputs, args.jobs, args.seed, not args.no_corpus, args.max_minutes)
    _init(not args.no_corpus)
    median = statistics.median(total.per_byte) if total.per_byte else 0.0
    slow = confirm_slow(total, median)
    saved = save_findings(total)
    result = table(total, wall, args.jobs, args.seed, slow, saved, median, args.inputs)
    (args.results / "parsers.json").write_text(json.dumps(result, indent=1, ensure_ascii=False) + "\n")
    print(f"parsers: {total.inputs} inputs, {len(saved)} findings", file=sys.stderr)
    return len(saved)


if __name__ == "__main__":
    sys.exit(main())
