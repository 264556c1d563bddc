"""The pre-commit hooks of .pre-commit-hooks.yaml, run by pre-commit itself in a temporary git repository,
and the CI examples of docs/ci.md.

pre-commit installs odgen from a repository revision, so the hooks are taken from a snapshot
of this working tree (tracked and new files) committed in a temporary repository.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib
from pathlib import Path

import pytest
import yaml

from odgen.cli import build_parser

from .conftest import FIXTURES, ROOT

EXAMPLE = ROOT / "examples" / "io-node"
BAD = FIXTURES / "syntax" / "SYN003.eds"
PRE_COMMIT = [sys.executable, "-m", "pre_commit"]


def git(cwd: Path, *args: str) -> str:
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.invalid",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.invalid")
    done = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, env=env, check=True)
    return done.stdout.strip()


@pytest.fixture(scope="module")
def snapshot(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    """This working tree as one commit of a temporary repository: (path, revision)."""
    shadow = tmp_path_factory.mktemp("odgen-snapshot")
    listed = git(ROOT, "ls-files", "--cached", "--others", "--exclude-standard", "-z").split("\0")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            (shadow / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, shadow / name)
    git(shadow, "init", "-q")
    git(shadow, "add", "-A")
    git(shadow, "commit", "-q", "-m", "snapshot")
    return shadow, git(shadow, "rev-parse", "HEAD")


@pytest.fixture(scope="module")
def home(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    """One pre-commit cache for the module: the hook environment is built once."""
    return dict(os.environ, PRE_COMMIT_HOME=str(tmp_path_factory.mktemp("pre-commit-home")), PRE_COMMIT_COLOR="never")


def _user_repo(path: Path, files: dict[str, bytes]) -> Path:
    path.mkdir()
    git(path, "init", "-q")
    for name, data in files.items():
        (path / name).parent.mkdir(parents=True, exist_ok=True)
        (path / name).write_bytes(data)
    git(path, "add", "-A")
    return path


def test_lint_hook_with_try_repo(snapshot: tuple[Path, str], home: dict[str, str], tmp_path: Path) -> None:
    good = {"devices/io-node.eds": (EXAMPLE / "io-node.eds").read_bytes(), "README.txt": b"not linted\n"}
    repo = _user_repo(tmp_path / "user", good)
    cmd = [*PRE_COMMIT, "try-repo", str(snapshot[0]), "odgen-lint", "--all-files"]
    passed = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=home, check=False)
    assert passed.returncode == 0 and "odgen lint" in passed.stdout, passed.stdout + passed.stderr
    (repo / "devices" / "bad.EDS").write_bytes(BAD.read_bytes())
    git(repo, "add", "-A")
    failed = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=home, check=False)
    assert failed.returncode == 1, failed.stdout + failed.stderr
    assert "devices/bad.EDS:4: error[SYN003]" in failed.stdout


def test_generate_check_hook(snapshot: tuple[Path, str], home: dict[str, str], tmp_path: Path) -> None:
    config = (f"repos:\n- repo: {snapshot[0]}\n  rev: {snapshot[1]}\n  hooks:\n  - id: odgen-generate-check\n"
              "    args: [io-node.eds, --options, io-node.toml, -o, generated]\n").encode()
    files = {name: (EXAMPLE / name).read_bytes() for name in ("io-node.eds", "io-node.toml")}
    repo = _user_repo(tmp_path / "user", {**files, ".pre-commit-config.yaml": config})
    subprocess.run([sys.executable, "-m", "odgen", "generate", "io-node.eds", "--options", "io-node.toml",
                    "-o", "generated"], cwd=repo, check=True)
    git(repo, "add", "-A")
    cmd = [*PRE_COMMIT, "run", "--all-files"]
    passed = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=home, check=False)
    assert passed.returncode == 0, passed.stdout + passed.stderr
    eds = repo / "io-node.eds"
    eds.write_text(eds.read_text().replace("ProductName=", "ProductName=New "))
    git(repo, "add", "-A")
    stale = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=home, check=False)
    assert stale.returncode == 1, stale.stdout + stale.stderr
    assert "generated/io_node.c: changed" in stale.stdout and "regenerate with: odgen generate" in stale.stdout


def _blocks(text: str, language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", text, re.DOTALL)


def _odgen_commands(text: str) -> list[list[str]]:
    commands = []
    for line in text.splitlines():
        line = line.strip().removeprefix("- ").removeprefix("run: ")
        if line.startswith("odgen "):
            commands.append(shlex.split(line.split("&&")[0].split("#")[0])[1:])
    return commands


def test_ci_examples_are_valid(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """docs/ci.md: the workflow, the GitLab job and the pre-commit config parse; their odgen commands too."""
    text = (ROOT / "docs" / "ci.md").read_text(encoding="utf-8")
    docs = [yaml.safe_load(block) for block in _blocks(text, "yaml")]
    workflow = next(d for d in docs if "jobs" in d)
    steps = workflow["jobs"]["odgen"]["steps"]
    upload = next(s for s in steps if s.get("uses", "").startswith("github/codeql-action/upload-sarif"))
    assert upload["with"]["sarif_file"] == "odgen.sarif"
    assert workflow["permissions"]["security-events"] == "write"
    gitlab = next(d for d in docs if "odgen" in d and "script" in d["odgen"])
    configs = [d["repos"][0] for d in docs if "repos" in d]
    declared = {h["id"]: h for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())}
    local = next(c for c in configs if c["repo"] == "local")["hooks"]
    for hook in local:  # the local form runs what the repository's hooks run, on the same files
        mine = declared[hook["id"]]
        assert (hook["entry"], hook["files"], hook.get("pass_filenames", True)) == \
            (mine["entry"], mine["files"], mine.get("pass_filenames", True)), hook["id"]
    hooks = next(c for c in configs if c["repo"] != "local")["hooks"]
    assert {h["id"] for h in hooks} == {h["id"] for h in local} == set(declared)
    tomllib.loads(_blocks(text, "toml")[0])
    commands = _odgen_commands("\n".join(_blocks(text, "yaml") + _blocks(text, "sh")))
    assert len(commands) >= 7 and any("--check" in c for c in commands)
    commands += [["generate", "--check", *h["args"]] for h in hooks if "args" in h]
    assert any("sarif" in c for c in _odgen_commands("\n".join(gitlab["odgen"]["script"])))
    parser = build_parser()
    (tmp_path / "devices").mkdir()
    (tmp_path / "devices" / "io-node.toml").write_text("")  # the options file the examples name
    monkeypatch.chdir(tmp_path)
    for argv in commands:
        parser.parse_args([a for a in argv if "*" not in a] + (["x.eds"] if argv[0] == "lint" else []))


def test_local_hooks_of_docs_ci(home: dict[str, str], tmp_path: Path) -> None:
    """docs/ci.md's `repo: local` config, as written there, with the installed odgen on PATH."""
    text = (ROOT / "docs" / "ci.md").read_text(encoding="utf-8")
    config = next(b for b in _blocks(text, "yaml") if "repo: local" in b)
    files = {f"devices/{name}": (EXAMPLE / name).read_bytes() for name in ("io-node.eds", "io-node.toml")}
    repo = _user_repo(tmp_path / "user", {**files, ".pre-commit-config.yaml": config.encode()})
    env = dict(home, PATH=f"{Path(sys.executable).parent}{os.pathsep}{home['PATH']}")
    subprocess.run([sys.executable, "-m", "odgen", "generate", "devices/io-node.eds", "--options",
                    "devices/io-node.toml", "-o", "firmware/od"], cwd=repo, check=True)
    git(repo, "add", "-A")
    cmd = [*PRE_COMMIT, "run", "--all-files"]
    passed = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=env, check=False)
    assert passed.returncode == 0 and "odgen lint" in passed.stdout, passed.stdout + passed.stderr
    (repo / "devices" / "bad.eds").write_bytes(BAD.read_bytes())
    git(repo, "add", "-A")
    failed = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, env=env, check=False)
    assert failed.returncode == 1 and "devices/bad.eds:4: error[SYN003]" in failed.stdout, failed.stdout
