"""examples/plasma-equipment: five descriptions from one table, a clean network lint, five node
programs built with gcc and clang, and the whole network run on vcan (every value crosses)."""

from __future__ import annotations

import filecmp
import subprocess
import sys
from pathlib import Path

import pytest

from .conftest import ROOT

EXAMPLE = ROOT / "examples" / "plasma-equipment"
ODGEN = str(Path(sys.executable).with_name("odgen"))
NODES = ("master", "hv_supply", "vacuum_gauge", "flow_meter", "inverter")


def run(cmd: list[str], **kw) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, capture_output=True, text=True, check=False, stdin=subprocess.DEVNULL, **kw)


def test_descriptions_are_what_describe_py_writes(tmp_path: Path) -> None:
    done = run([sys.executable, str(EXAMPLE / "describe.py"), str(tmp_path)])
    assert done.returncode == 0, done.stderr
    files = sorted(p.name for p in tmp_path.iterdir())
    assert files == sorted(f"{n}.eds" for n in NODES)
    assert filecmp.cmpfiles(tmp_path, EXAMPLE, files, shallow=False)[0] == files


def test_network_lint_is_clean() -> None:
    done = run([ODGEN, "lint", "--network", "plasma.toml", "--ignore", "COM004", "--strict"], cwd=EXAMPLE)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "0 error(s), 0 warning(s)" in done.stdout
    # without the ignore only the master's deliberately fixed PDO COB-IDs are reported
    done = run([ODGEN, "lint", "--network", "plasma.toml", "--format", "json"], cwd=EXAMPLE)
    assert '"COM004"' in done.stdout and "NET0" not in done.stdout and "PDO0" not in done.stdout


@pytest.fixture(scope="module")
def programs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The node programs, built by the example's Makefile with gcc (run) and clang (warnings)."""
    dirs = {cc: tmp_path_factory.mktemp(f"plasma-{cc}") for cc in ("gcc", "clang")}
    for cc, build in dirs.items():
        done = run(["make", "-s", "-C", str(EXAMPLE), f"CC={cc}", f"BUILD={build}", f"ODGEN={ODGEN}"])
        assert done.returncode == 0, done.stdout + done.stderr
        assert all((build / f"{n}-node").is_file() for n in NODES)
    return dirs["gcc"]


def test_network_runs_on_vcan(programs: Path, vcan_bus) -> None:
    done = vcan_bus.run([sys.executable, str(EXAMPLE / "run_network.py"), str(programs)], cwd=EXAMPLE, timeout=300)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output[-6000:]
    assert done.stdout.rstrip().splitlines()[-1] == "plasma network: ok", output[-6000:]
