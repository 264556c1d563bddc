"""Shared test helpers: where the corpus is, and linting a file in-process."""

from __future__ import annotations

import os
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


# The corpus files `make test` builds node programs of and checks on the bus (round trip and
# conformance battery: a few seconds each in the guest, and a build each); `make corpus`
# (ODGEN_CORPUS=all) checks every corpus file. Chosen by what each brings that the others do
# not (from the conformance verdicts of the whole corpus: together they run every check of the
# battery that runs on any corpus file, and give every reason of a skip and every kind of note
# it gives on the corpus), and by the rules decided on them:
CORPUS_SAMPLE = {
    "eyou__YiyouServo_V1.4.eds": "limits past the end of their type (HighLimit=65536 on an UNSIGNED16): the "
                                 "generated limits and the expected write cases take the type's end",
    "gocanopen__base.eds": "LSS_Supported=1 (lss.inquire runs), 0x1200 sub 1/2 described (sdo.server runs), "
                           "a SYNC period: 0x1019 refused while 0x1006 is not 0 (CiA 301)",
    "roscanopen__Elmo.dcf": "a DCF (ParameterValue) of a CiA 402 drive, 344 sub-entries; a 0x1016 sub 1 whose "
                            "HighLimit leaves no room for a node-id: nmt.hb-consumer skips saying so",
    "canopennode__DS301_profile.eds": "CANopenNode's storage layout (StorageLocation: object-level PERSIST_COMM, "
                                      "sub-level RAM): save/load takes a stored entry with a usable value",
    "lelycore__co-sdev.dcf": "Lely's DCF with every basic data type (ParameterValue)",
    "pycanopen__datatypes.eds": "every basic data type, in an EDS",
    "oresatmon__oresat_test.eds": "nothing a client may write: the skips of a read-only node",
    "canopeneditor__minimal_project.xdd": "an XDD (CiA 311)",
    "canopeneditor__DSP302-NMTMaster.xpd": "an XPD (CANopenEditor's XDD-format profile) of a CiA 302 master",
}


def full_corpus() -> bool:
    """Whether the tests that sample the corpus take all of it (`make corpus`: ODGEN_CORPUS=all)."""
    return os.environ.get("ODGEN_CORPUS", "") == "all"


def corpus_sample(files: list[Path]) -> list[Path]:
    """`files` in CORPUS_SAMPLE; all of them under ODGEN_CORPUS=all."""
    return files if full_corpus() else [p for p in files if p.name in CORPUS_SAMPLE]


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


# ---- running on every core (pytest-xdist) ------------------------------------------------------
# `make test` runs the suite in worker processes (`-n auto --dist loadgroup`, tests/README.md).
# A worker is a process of its own with its own session, so what tests share goes to one worker,
# as one xdist group, run there in collection order; every test gets its group here, so a test
# added later needs no marker of its own:
# - every test that uses the vcan bus (`vcan_bus`, directly or through another fixture): one
#   session, one guest, one bus for all, as without xdist (bus-side commands name vcan0, the
#   builds share build/node-cache, the reports in build/test-reports are written at its end);
# - every test that uses a session-scoped fixture of the suite (`dist`: the sdist and wheel), one
#   group per fixture, and every test of a module that uses a module-scoped fixture of that
#   module, one group per module: what the fixture builds is built once, as without xdist.
# xdist hands out the groups first, those of most tests first (the vcan group), so no long group
# starts last. A test with an `xdist_group` marker of its own keeps it.

VCAN_GROUP = "vcan"


def xdist_group(item: pytest.Item) -> str | None:
    """The group `item` must share a worker with, None when it can run anywhere."""
    names = getattr(item, "fixturenames", ())
    if "vcan_bus" in names:
        return VCAN_GROUP
    info = getattr(item, "_fixtureinfo", None)
    # the suite's own fixtures have a location (baseid); pytest's and plugins' have none
    shared = [d for name in names for d in getattr(info, "name2fixturedefs", {}).get(name, ())[-1:]
              if d.baseid and d.scope in ("session", "package", "module")]
    if not shared:
        return None
    widest = min(shared, key=lambda d: (d.scope == "module", d.argname))  # a session fixture before a module's
    return item.nodeid.split("::")[0] if widest.scope == "module" else f"{widest.scope}-{widest.argname}"


@pytest.hookimpl(tryfirst=True)  # before xdist's own hook reads the markers
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if item.get_closest_marker("xdist_group") is None and (group := xdist_group(item)) is not None:
            item.add_marker(pytest.mark.xdist_group(group))


def pytest_collection_finish(session: pytest.Session) -> None:
    """On a worker of `--dist loadgroup`: xdist marks a grouped test by its id (`...@vcan`); a test
    in a group without the mark would run on any worker (two guests, one bus shared by two runs)."""
    if os.environ.get("PYTEST_XDIST_WORKER") and getattr(session.config.option, "loadgroup", False):
        lost = [item.nodeid for item in session.items
                if item.get_closest_marker("xdist_group") is not None and "@" not in item.nodeid]
        if lost:
            message = (f"pytest-xdist does not keep the xdist groups with this pytest ({lost[0]} has none): "
                       "install the versions pyproject.toml's test extra names (make setup)")
            os.write(2, f"\n{message}\n".encode())  # a worker's own report of it is lost in xdist's
            pytest.exit(message, returncode=4)


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "xdist_group(name): run on the pytest-xdist worker of the group's other tests")


@pytest.fixture(scope="session")
def dist(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """sdist, then the wheel built from that sdist (python -m build does both), once per run:
    tests/test_install.py installs the wheel, tests/test_licence.py reads its metadata."""
    out = tmp_path_factory.mktemp("dist")
    done = subprocess.run([sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)], cwd=out,
                          capture_output=True, text=True, check=False, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return out
