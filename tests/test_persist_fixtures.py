"""NV images written by the runtime before the rule set of docs/persistence.md was enforced
(tests/fixtures/nv, both formats: "ODG2" with migration, "ODG1" without) still load: the
same firmware serves what was stored (LOADED), and with migration a firmware that adds a
parameter keeps every stored value. The fixtures were written by that runtime (one store: the
newest image in slot B; two stores: in slot A) and are never regenerated."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from .test_migration_runtime import BASE, LOADED, MIGRATED, Param, eds, firmware, run

FIX = Path(__file__).resolve().parent / "fixtures" / "nv"
U32, VS = 0x07, 0x09
PARAMS = (*BASE, Param(0x2003, U32, "42", "0", "100000"), Param(0x2010, VS, "abc", capacity=8),
          Param(0x2020, 0x06, "5", elements=3))
OFF = "[persist]\nmigration = false\n"

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")


@pytest.fixture(scope="module")
def firmwares(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The fixtures' firmware in both formats, and one that adds a parameter: built once."""
    tmp = tmp_path_factory.mktemp("fixtures")
    return {"odg2": firmware(tmp, "odg2", PARAMS, 1000, False)[0],
            "odg1": firmware(tmp, "odg1", PARAMS, 1000, False, OFF)[0],
            "added": firmware(tmp, "added", (*PARAMS, Param(0x2004, U32, "77")), 1000, False)[0]}


def stored(name: str) -> dict[tuple[int, int], str]:
    out = {}
    for line in (FIX / f"{name}.txt").read_text(encoding="utf-8").splitlines():
        index, sub, *value = line.split()
        out[(int(index, 16), int(sub, 16))] = value[0] if value else ""
    return out


def test_fixture_description_is_the_one_the_images_were_written_for() -> None:
    assert eds(PARAMS, 1000, False) == (FIX / "od.eds").read_text(encoding="utf-8")


@pytest.mark.parametrize("fmt", ["odg2", "odg1"])
@pytest.mark.parametrize("image", ["one_store", "two_stores"])
def test_images_of_the_earlier_runtime_load(fmt: str, image: str, tmp_path: Path, firmwares: dict[str, Path]) -> None:
    exe = firmwares[fmt]
    nv = tmp_path / "od.nv"
    nv.write_bytes((FIX / f"{fmt}_{image}.nv").read_bytes())
    got = run(exe, nv, "dump")
    assert [g["status"] for g in got.groups] == [LOADED, LOADED]
    assert got.values == stored(f"{fmt}_{image}")
    assert got.seen[0] == 1 << LOADED


@pytest.mark.parametrize("image", ["one_store", "two_stores"])
def test_images_of_the_earlier_runtime_migrate(image: str, tmp_path: Path, firmwares: dict[str, Path]) -> None:
    """A firmware that adds a parameter: every stored value kept, the new one its default, and
    nothing reported lost."""
    exe = firmwares["added"]
    nv = tmp_path / "od.nv"
    nv.write_bytes((FIX / f"odg2_{image}.nv").read_bytes())
    got = run(exe, nv, "dump")
    want = stored(f"odg2_{image}")
    assert got.groups[0]["status"] == MIGRATED and got.groups[1]["status"] == LOADED
    assert {k: v for k, v in got.values.items() if k != (0x2004, 0)} == want
    assert got.values[(0x2004, 0)] == "4D000000"
    assert not got.seen[0] & 0x80
