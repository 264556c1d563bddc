"""The licence: Apache-2.0 in LICENSE and in the wheel's metadata, an SPDX line in every runtime and
template file (new files included), and none in what odgen generates, which is the user's.
"""

from __future__ import annotations

import email
import hashlib
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

import odgen

from .conftest import ROOT

SPDX = "SPDX-License-Identifier: Apache-2.0"
# sha256 of the Apache License 2.0 as the ASF publishes it (LICENSE-2.0.txt): the text is not edited.
APACHE_2_0_SHA256 = "cfc7749b96f63bd31c3c42b5c471bf756814053e847c10f3eb003417bc523d30"
URL_PLACEHOLDER = "https://example.invalid/odgen"
EXAMPLE = ROOT / "examples" / "io-node"


def _git_files(*folders: str) -> list[Path]:
    """Tracked and new (not ignored) files: a file added without its SPDX line fails before commit."""
    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z", *folders],
                            cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return sorted(ROOT / name for name in set(filter(None, listed.split("\0"))) if (ROOT / name).is_file())


def test_licence_file_is_the_apache_2_0_text() -> None:
    text = (ROOT / "LICENSE").read_bytes()
    assert hashlib.sha256(text).hexdigest() == APACHE_2_0_SHA256


def test_pyproject_declares_the_licence_as_an_spdx_expression() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert project["license"] == "Apache-2.0" and project["license-files"] == ["LICENSE"]
    # PEP 639: with an expression, a "License ::" classifier is an error at upload.
    assert not [c for c in project["classifiers"] if c.startswith("License ::")]


def test_every_runtime_file_carries_the_spdx_line() -> None:
    files = _git_files("runtime")
    assert len(files) > 20, files
    expected = {".c": f"/* {SPDX} */", ".h": f"/* {SPDX} */", ".md": f"<!-- {SPDX} -->"}
    wrong = [str(p.relative_to(ROOT)) for p in files
             if p.read_text(encoding="utf-8").splitlines()[0] != expected.get(p.suffix, SPDX)]
    assert wrong == [], f"first line must be the SPDX line ({expected}): {wrong}"


def test_every_template_carries_it_in_a_jinja_comment() -> None:
    """A jinja comment: the template is Apache-2.0, what it renders is the user's and carries none."""
    files = _git_files("templates")
    assert len(files) >= 7, files
    wrong = [str(p.relative_to(ROOT)) for p in files
             if not p.read_text(encoding="utf-8").splitlines()[0].startswith("{# " + SPDX)]
    assert wrong == [], wrong


def test_generated_files_carry_no_licence(tmp_path: Path) -> None:
    odgen_cmd = [sys.executable, "-m", "odgen"]
    eds, options = EXAMPLE / "io-node.eds", EXAMPLE / "io-node.toml"
    for argv in (["generate", str(eds), "--options", str(options), "-o", "gen"],
                 ["profile", "ds401", "--di", "8", "--do", "8", "-o", "io.eds", "--generate", "ds401"],
                 ["report", str(eds), "-o", "report.html"], ["report", str(eds), "-o", "report.md"]):
        done = subprocess.run(odgen_cmd + argv, cwd=tmp_path, capture_output=True, text=True, check=False)
        assert done.returncode in (0, 1), done.stderr
    outputs = sorted(p for p in tmp_path.rglob("*") if p.is_file() and p.suffix in (".c", ".h", ".html", ".md"))
    assert len(outputs) == 9, outputs
    assert [p.name for p in outputs if "SPDX" in p.read_text(encoding="utf-8")] == []
    headers = [p for p in outputs if p.suffix in (".c", ".h")]
    assert all("This file is yours" in p.read_text(encoding="utf-8") for p in headers)


def test_readme_says_the_generated_files_are_the_users() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "Apache-2.0" in readme and "no licence attaches to them" in readme


def test_project_addresses_are_written_once() -> None:
    """The placeholder addresses live in pyproject.toml only: one place for the maintainers to fill in."""
    elsewhere = [str(p.relative_to(ROOT)) for p in _git_files()
                 if p.name != "pyproject.toml" and p.suffix in (".md", ".yml", ".yaml", ".toml", ".py", ".cfg")
                 and p != Path(__file__) and URL_PLACEHOLDER in p.read_text(encoding="utf-8", errors="replace")]
    assert elsewhere == []


def test_wheel_metadata(dist: Path) -> None:
    """What an installer and a package index read: licence, its file, URLs, version, readme."""
    wheel = zipfile.ZipFile(next(dist.glob("odgen-*.whl")))
    info = f"odgen-{odgen.__version__}.dist-info"
    metadata = email.message_from_string(wheel.read(f"{info}/METADATA").decode("utf-8"))
    assert metadata["Version"] == odgen.__version__
    assert metadata["License-Expression"] == "Apache-2.0"
    assert metadata.get_all("License-File") == ["LICENSE"]
    assert hashlib.sha256(wheel.read(f"{info}/licenses/LICENSE")).hexdigest() == APACHE_2_0_SHA256
    urls = dict(u.split(", ", 1) for u in metadata.get_all("Project-URL"))
    assert {"Homepage", "Documentation", "Repository", "Issues", "Changelog"} <= set(urls)
    assert metadata.get_all("Classifier") and metadata["Keywords"]
    assert metadata["Description-Content-Type"] == "text/markdown"
    assert metadata.get_payload().strip() == (ROOT / "README.md").read_text(encoding="utf-8").strip()


def test_sdist_carries_licence_changelog_and_docs(dist: Path) -> None:
    sdist = next(dist.glob("odgen-*.tar.gz"))
    top = f"odgen-{odgen.__version__}"
    with tarfile.open(sdist) as archive:
        names = set(archive.getnames())
    files = ("LICENSE", "README.md", "CHANGELOG.md", "mkdocs.yml", "tools/mkdocs_hooks.py")
    wanted = {f"{top}/{name}" for name in files}
    wanted |= {f"{top}/docs/{p.name}" for p in (ROOT / "docs").glob("*.md")}
    assert wanted - names == set()
