"""Shared test helpers: where the corpus is, and linting a file in-process."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from odgen.pipeline import Request, generate
from odgen.lint.driver import FileResult, lint_path
from odgen.lint.passes import LintOptions

ROOT = Path(__file__).resolve().parents[1]
CORPUS = ROOT.parent / "shared" / "corpus" / "files"
FIXTURES = Path(__file__).resolve().parent / "fixtures"
BUILD = ROOT / "build" / "test-reports"


def corpus_files(*suffixes: str) -> list[Path]:
    """Every corpus file with one of the suffixes (all when none given); [] when absent."""
    if not CORPUS.is_dir():
        return []
    files = sorted(p for p in CORPUS.iterdir() if p.is_file())
    return [p for p in files if not suffixes or p.suffix.lower() in suffixes]


def generates(path: Path) -> bool:
    """Whether `odgen generate` writes a dictionary for the file (no blocking finding)."""
    return bool(generate(Request(path, name="od")).files)


def corpus_params(*suffixes: str) -> list:
    files = corpus_files(*suffixes)
    if not files:
        return [pytest.param(None, marks=pytest.mark.skip(reason="../shared/corpus is absent"))]
    return [pytest.param(p, id=p.name) for p in files]


def lint(path: Path, **options) -> FileResult:
    return lint_path(path, LintOptions(**options))


def expectations(path: Path) -> list[str]:
    """`; expect: LINE: severity[RULE]: message` lines of a fixture (XML: `<!-- expect: ... -->`)."""
    out = []
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        for marker in ("; expect: ", "<!-- expect: "):
            if line.startswith(marker):
                out.append(line[len(marker):].removesuffix(" -->").strip())
    return out


def rendered(result: FileResult) -> list[str]:
    """Diagnostics as `LINE: severity[RULE]: message`, without the file name."""
    prefix = f"{result.source}:"
    return [d.text().removeprefix(prefix) for d in result.diagnostics]


# ---- the one vcan session of a test run -------------------------------------------------------
# Every CAN test asks for `vcan_bus` and runs its bus-side command through it: on the host's
# vcan when it has one, else in one User-Mode Linux guest booted at the first use and shared
# by all (tools/vcan/bus.py). Each CAN test's duration (with its fixtures' setup: building,
# booting the guest) lands in build/test-reports/can-tests.*.

def _load_bus_module():
    import importlib.util

    spec = importlib.util.spec_from_file_location("odgen_vcan_bus", ROOT / "tools" / "vcan" / "bus.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_CAN_TESTS: list[dict[str, object]] = []
_SETUP_SECONDS: dict[str, float] = {}  # a CAN test's fixtures (building, the guest's boot) count too


@pytest.fixture(scope="session")
def vcan_bus(tmp_path_factory: pytest.TempPathFactory):
    """The shared vcan session; commands may write under pytest's temporary directories and the repo."""
    import subprocess

    setup = subprocess.run(["bash", str(ROOT / "tools" / "vcan" / "setup.sh")], capture_output=True, text=True,
                           timeout=600, check=False)
    if setup.returncode != 0:
        pytest.fail(f"tools/vcan/setup.sh failed (exit {setup.returncode}); no vcan session:\n{setup.stderr}")
    bus = _load_bus_module().VcanBus(tmp_path_factory.getbasetemp())
    yield bus
    status = bus.close()
    _write_can_report(bus)
    assert status in (None, 0), f"the vcan guest ended with status {status}"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo):
    outcome = yield
    report = outcome.get_result()
    if "vcan_bus" not in getattr(item, "fixturenames", ()):
        return
    if report.when == "setup":
        _SETUP_SECONDS[item.nodeid] = report.duration
    elif report.when == "call":
        seconds = _SETUP_SECONDS.pop(item.nodeid, 0.0) + report.duration
        _CAN_TESTS.append({"test": item.nodeid, "outcome": report.outcome, "seconds": round(seconds, 3)})


def _write_can_report(bus) -> None:
    import json

    BUILD.mkdir(parents=True, exist_ok=True)
    doc = {"where": bus.where, "tests": _CAN_TESTS, "commands": bus.log}
    (BUILD / "can-tests.json").write_text(json.dumps(doc, indent=2) + "\n", encoding="utf-8")
    lines = [f"# CAN tests ({'host vcan' if bus.host else 'one User-Mode Linux guest'})", "",
             "| test | outcome | seconds |", "|---|---|---|"]
    lines += [f"| {t['test']} | {t['outcome']} | {t['seconds']} |" for t in _CAN_TESTS]
    lines += ["", "| command | where | exit | seconds |", "|---|---|---|---|"]
    lines += [f"| {' '.join(map(str, c['argv'])).replace('|', '/')} | {c['where']} | {c['status']} | {c['seconds']} |"
              for c in bus.log]
    (BUILD / "can-tests.md").write_text("\n".join(lines) + "\n", encoding="utf-8")


@pytest.fixture(scope="session")
def dist(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """sdist, then the wheel built from that sdist (python -m build does both), once per run:
    tests/test_install.py installs the wheel, tests/test_licence.py reads its metadata."""
    out = tmp_path_factory.mktemp("dist")
    done = subprocess.run([sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)], cwd=out,
                          capture_output=True, text=True, check=False, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return out
