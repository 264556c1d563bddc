"""What every benchmark part shares: paths, inputs, timing, the peers' interpreter, targets."""

from __future__ import annotations

import re
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from pathlib import Path

from synth import synth_eds

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
BUILD = ROOT / "build" / "bench"
RESULTS = HERE / "results"
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
PEER_VENV = ROOT / "build" / "bench-venv"
PEER_PYTHON = PEER_VENV / "bin" / "python"
ODGEN = [sys.executable, "-m", "odgen"]

# The real inputs of ../shared/notes/peer-measurements.md (their names there) and the corpus file each is.
# ds402_cia402_slave: the notes took ros2_canopen's copy (23170 bytes); the corpus has ros_canopen's (23152).
PEER_INPUTS = {
    "sample_canopen": "pycanopen__sample.eds",
    "ds401_canfestival": "canfestival__DS401_Slave_Gui.eds",
    "ds402_cia402_slave": "roscanopen__cia402_slave.eds",
    "ds301_canopennode": "canopennode__DS301_profile.eds",
    "demodevice_canopendemo": "canopendemo__demoDevice.eds",
    "big_e35": "pycanopen__e35.eds",
}
SYNTH_SIZES = (250, 1000, 2000, 4000, 16000)


def synth_label(n: int) -> str:
    return f"synth_{n}_common"


def inputs(sizes: Sequence[int] = SYNTH_SIZES) -> dict[str, Path]:
    """The corpus inputs that are present, then the synthetic ones (written to build/bench)."""
    found = {label: CORPUS / name for label, name in PEER_INPUTS.items() if (CORPUS / name).is_file()}
    BUILD.mkdir(parents=True, exist_ok=True)
    for n in sizes:
        path = BUILD / f"{synth_label(n)}.eds"
        text = synth_eds(n)
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
        found[synth_label(n)] = path
    return found


@dataclass
class Run:
    seconds: float
    returncode: int
    error: str


def timed(cmd: Sequence[str], cwd: Path | None = None) -> Run:
    """Whole-process wall time of one run; what went wrong when it failed."""
    start = time.perf_counter()
    proc = subprocess.run(list(cmd), capture_output=True, text=True, errors="replace", cwd=cwd, check=False)
    seconds = time.perf_counter() - start
    return Run(seconds, proc.returncode, failure(proc.stderr + proc.stdout) if proc.returncode else "")


def failure(output: str) -> str:
    """odgen's rule ids with counts, else a tool's last error line."""
    rules = re.findall(r"error\[([A-Z]+[0-9]+)\]", output)
    if rules:
        return "lint errors " + " ".join(f"{r}x{rules.count(r)}" for r in sorted(set(rules)))
    lines = [re.sub(r"(/[^/\s:]+)+/", "", ln.strip()) for ln in output.splitlines() if ln.strip()]
    return next((ln for ln in reversed(lines) if "rror" in ln), lines[-1] if lines else "")[:120]


def interleaved(commands: dict[str, Callable[[], Run]], repeat: int, slow_s: float = 20.0) -> dict[str, list[Run]]:
    """Runs each command `repeat` times, taking turns, so load changes hit every tool alike. A command
    whose first run took longer than `slow_s` runs once: repeating it would not fit the time budget."""
    runs: dict[str, list[Run]] = {name: [] for name in commands}
    for _ in range(repeat):
        for name, command in commands.items():
            if not runs[name] or runs[name][0].seconds <= slow_s:
                runs[name].append(command())
    return runs


def median(runs: list[Run]) -> float:
    return statistics.median(r.seconds for r in runs)


@dataclass
class Target:
    """One goal of the issue with what this run measured."""
    name: str
    goal: str
    measured: str
    ratio: str
    met: bool | None  # None: could not be measured here

    def row(self) -> str:
        verdict = {True: "met", False: "**not met**", None: "not measured"}[self.met]
        return f"| {self.name} | {self.goal} | {self.measured} | {self.ratio} | {verdict} |"


def targets_json(targets: list[Target]) -> list[dict[str, object]]:
    return [asdict(t) for t in targets]

