"""Runtime names renamed for one word per concept keep their old names for one release
(CHANGELOG.md, Deprecated): code written against the old names builds and means the same."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from odgen import toolchain

RUNTIME = toolchain.include_dirs()[0]

OLD_NAMES = r"""
#include "odg_impl.h"
/* the storage class and its switch under their names before */
typedef char class_alias[ODG_S_STORE == ODG_S_COMMAND && ODG_S_COMMAND == 3u ? 1 : -1];
typedef char switch_alias[ODG_CFG_STORE == ODG_CFG_COMMAND ? 1 : -1];
int old_helpers(void);
int old_helpers(void)
{
    uint16_t v = 0;
    odg_store_(&v, 2, 0x1234u);
    return odg_load_(&v, 2) == 0x1234u && v == 0x1234u;
}
"""


def _cc(tmp_path: Path, *args: str) -> subprocess.CompletedProcess[str]:
    cc = shutil.which("gcc") or shutil.which("cc")
    if cc is None:
        pytest.skip("no C compiler")
    return subprocess.run([cc, *toolchain.CFLAGS, f"-I{RUNTIME}", *args], capture_output=True, text=True,
                          check=False, cwd=tmp_path)


@pytest.mark.parametrize("config", ["", "-DODG_CFG_STORE=0", "-DODG_CFG_COMMAND=0"])
def test_old_names_build_and_mean_the_same(tmp_path: Path, config: str) -> None:
    (tmp_path / "old.c").write_text(OLD_NAMES, encoding="utf-8")
    done = _cc(tmp_path, *([config] if config else []), "-c", "old.c", "-o", "old.o")
    assert done.returncode == 0, done.stderr


def test_no_migration_is_the_persist_migration_switch(tmp_path: Path) -> None:
    """-DODG_NO_MIGRATION leaves the migration out as ODG_CFG_PERSIST_MIGRATION 0 does, for every
    file that includes odg.h (one switch, decided there)."""
    probe = '#include "odg.h"\ntypedef char off[ODG_CFG_PERSIST_MIGRATION == 0 ? 1 : -1];\n'
    (tmp_path / "probe.c").write_text(probe, encoding="utf-8")
    assert _cc(tmp_path, "-DODG_NO_MIGRATION", "-c", "probe.c", "-o", "probe.o").returncode == 0
    assert _cc(tmp_path, "-c", "probe.c", "-o", "probe.o").returncode != 0
    done = _cc(tmp_path, "-DODG_NO_MIGRATION", "-c", str(RUNTIME / "odg_persist_migrate.c"), "-o", "m.o")
    assert done.returncode == 0, done.stderr
    symbols = subprocess.run(["nm", str(tmp_path / "m.o")], capture_output=True, text=True, check=True).stdout
    assert "odg_described_boot_" not in symbols
