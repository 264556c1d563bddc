"""The docs users reach: the mkdocs site builds from docs/ in strict mode (a broken link fails), and
every docs page odgen's messages and generated files name exists (tests/test_install.py checks the
same from an installed wheel).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

from .conftest import ROOT

# A page name as odgen prints it: docs/generate.md, runtime/NODE.md.
NAMED = re.compile(r"\b(docs|runtime)/([A-Za-z0-9_-]+\.md)\b")


def _mkdocs(config: Path, site: Path) -> subprocess.CompletedProcess[str]:
    # Not -q: mkdocs 1.6 then drops the anchor warnings before --strict counts them.
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config),
                           "-d", str(site)], capture_output=True, text=True, check=False, timeout=120)


def named_pages() -> set[tuple[str, str]]:
    """(folder, page) for every docs page named in odgen's code, templates and runtime."""
    sources = [*(ROOT / "odgen").rglob("*.py"), *(ROOT / "templates").glob("*.j2"),
               *(p for p in (ROOT / "runtime").rglob("*") if p.suffix in (".c", ".h"))]
    found = {m.groups() for p in sources for m in NAMED.finditer(p.read_text(encoding="utf-8"))}
    return {(folder, page) for folder, page in found if page != "NAME.md"}  # NAME.md: "any page"


def test_site_builds_strict(tmp_path: Path) -> None:
    done = _mkdocs(ROOT / "mkdocs.yml", tmp_path / "site")
    assert done.returncode == 0, done.stdout + done.stderr
    pages = sorted(p.stem for p in (ROOT / "docs").glob("*.md"))
    assert [p for p in pages if not (tmp_path / "site" / ("" if p == "index" else p) / "index.html").is_file()] == []
    for page, title in (("runtime", "odg runtime"), ("runtime/node", "odg node")):  # tools/mkdocs_hooks.py
        html = (tmp_path / "site" / page / "index.html").read_text(encoding="utf-8")
        assert f"<title>{title}" in html and "odg_init" in html


def test_a_broken_link_fails_the_build(tmp_path: Path) -> None:
    shutil.copytree(ROOT / "docs", tmp_path / "docs")
    shutil.copy(ROOT / "mkdocs.yml", tmp_path)
    shutil.copytree(ROOT / "tools", tmp_path / "tools", ignore=shutil.ignore_patterns("vcan"))
    shutil.copytree(ROOT / "runtime", tmp_path / "runtime", ignore=shutil.ignore_patterns("*.c", "*.h"))
    assert _mkdocs(tmp_path / "mkdocs.yml", tmp_path / "site").returncode == 0  # the copy builds as it is
    (tmp_path / "docs" / "broken.md").write_text("# Broken\n\nSee [the options](generat.md).\n", encoding="utf-8")
    done = _mkdocs(tmp_path / "mkdocs.yml", tmp_path / "site")
    assert done.returncode != 0 and "generat.md" in done.stdout + done.stderr
    (tmp_path / "docs" / "broken.md").write_text("# Anchor\n\nSee [x](generate.md#no-such-section).\n")
    assert _mkdocs(tmp_path / "mkdocs.yml", tmp_path / "site").returncode != 0


def test_every_page_odgen_names_exists() -> None:
    named = named_pages()
    assert ("docs", "persistence.md") in named and ("docs", "rules.md") in named
    assert [f"{d}/{p}" for d, p in sorted(named) if not (ROOT / d / p).is_file()] == []
    # figures live in docs/figures.md; benchmarks/ is not shipped, so odgen does not name it
    printed = [p for p in (ROOT / "odgen").rglob("*.py") if "benchmarks/results" in p.read_text(encoding="utf-8")]
    assert printed == []
