"""Lint settings from a config file: `[tool.odgen]` in pyproject.toml or an odgen.toml.

The file is looked for upward from each linted file's folder; in one folder odgen.toml wins,
and a pyproject.toml without `[tool.odgen]` is passed over (as ruff does). Keys: select,
ignore, per-file-ignores (glob relative to the config file's folder -> rule ids), strict,
node-id, exclude (globs relative to the config file's folder, or a file or folder name: files
that `odgen lint FOLDER` or a glob would find are left out; a file named is still read).
Command-line options override the file: --select replaces its select, --ignore adds to its
ignore, --strict and --node-id replace. A rule id that names no rule (or no family
prefix) is a user mistake: exit 2 naming the closest ids, since a typo would quietly turn
checks off.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from dataclasses import dataclass, field
from fnmatch import fnmatch
from functools import cache
from pathlib import Path
from typing import Any

from ..errors import OdgenError

KEYS = ("select", "ignore", "per-file-ignores", "strict", "node-id", "exclude")


@dataclass(frozen=True)
class LintConfig:
    path: Path | None = None  # the file the settings came from
    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    per_file_ignores: tuple[tuple[str, tuple[str, ...]], ...] = field(default=())
    strict: bool = False
    node_id: int | None = None
    exclude: tuple[str, ...] = ()

    def excludes(self, file: Path) -> bool:
        """Whether an `exclude` pattern names the file: its path relative to the config file's
        folder, the folders on that path (`vendor` or `vendor/` leaves out a folder), or its name."""
        if self.path is None or not self.exclude:
            return False
        rel = _relative(file, self.path.parent)
        parts = rel.split("/")
        candidates = [rel, file.name, *("/".join(parts[:n]) for n in range(1, len(parts))), *parts[:-1]]
        return any(fnmatch(c, p.rstrip("/")) for p in self.exclude for c in candidates)

    def ignores_for(self, file: Path) -> tuple[str, ...]:
        """`ignore` plus the per-file-ignores whose glob matches the file (relative to the config's folder)."""
        if self.path is None or not self.per_file_ignores:
            return self.ignore
        rel = _relative(file, self.path.parent)
        extra = [rule for glob, rules in self.per_file_ignores if fnmatch(rel, glob) or fnmatch(file.name, glob)
                 for rule in rules]
        return self.ignore + tuple(extra)


def _relative(file: Path, folder: Path) -> str:
    try:
        return file.resolve().relative_to(folder.resolve()).as_posix()
    except ValueError:
        return file.as_posix()


def check_rule_ids(ids: Iterable[str], origin: str) -> None:
    """Every id must be a rule id or a prefix of one (`PDO`, `SYN01`)."""
    from ..catalogue import RULES, is_selector

    known = sorted(RULES)
    for rule in ids:
        if is_selector(rule):
            continue
        import difflib

        families = sorted({k.rstrip("0123456789") for k in known})
        close = difflib.get_close_matches(rule, known + families, n=3, cutoff=0.5)
        hint = f"; did you mean {', '.join(close)}?" if close else "; `odgen rules` lists them"
        raise OdgenError(f"{origin}: '{rule}' is not a rule id or prefix{hint}")


def find_config(start: Path) -> Path | None:
    folder = (start if start.is_dir() else start.parent).resolve()
    for here in (folder, *folder.parents):
        if (here / "odgen.toml").is_file():
            return here / "odgen.toml"
        pyproject = here / "pyproject.toml"
        if pyproject.is_file() and "odgen" in _tool_table(pyproject):
            return pyproject
    return None


def _tool_table(pyproject: Path) -> dict[str, Any]:
    tool = _read(pyproject).get("tool", {})
    if not isinstance(tool, dict):
        raise OdgenError(f"{pyproject}: `tool` must be a table (as in [tool.odgen]); correct the file, "
                         "or pass the settings with --config")
    return tool


@cache
def _read(path: Path) -> dict[str, Any]:
    # tomllib (and its datetime) only when a pyproject.toml or odgen.toml is there
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # exercised by the wheel test under the oldest Python
        import tomli as tomllib
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as err:
        raise OdgenError(f"{path}: cannot read: {err}") from None
    except tomllib.TOMLDecodeError as err:
        raise OdgenError(f"{path}: not valid TOML: {err}") from None


def _rules(value: object, where: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise OdgenError(f"{where} must be a list of rule ids, e.g. [\"PDO\", \"COM003\"]")
    ids = tuple(v.strip().upper() for v in value)
    check_rule_ids(ids, where)
    return ids


@cache
def load_config(path: Path) -> LintConfig:
    doc = _read(path)
    table = doc if path.name == "odgen.toml" else _tool_table(path).get("odgen", {})
    if not isinstance(table, dict):
        raise OdgenError(f"{path}: [tool.odgen] must be a table")
    section = f"{path}: " + ("" if path.name == "odgen.toml" else "[tool.odgen] ")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise OdgenError(f"{section}unknown key {unknown[0]!r}; known keys: {', '.join(KEYS)}")
    per_file = table.get("per-file-ignores", {})
    if not isinstance(per_file, dict):
        raise OdgenError(f"{section}per-file-ignores must be a table of glob = [rule ids]")
    strict = table.get("strict", False)
    node_id = table.get("node-id")
    if not isinstance(strict, bool):
        raise OdgenError(f"{section}strict must be true or false")
    if node_id is not None and (not isinstance(node_id, int) or isinstance(node_id, bool) or not 1 <= node_id <= 127):
        raise OdgenError(f"{section}node-id must be a number in 1..127")
    exclude = table.get("exclude", [])
    if not isinstance(exclude, list) or not all(isinstance(p, str) and p.strip() for p in exclude):
        raise OdgenError(f"{section}exclude must be a list of globs, e.g. [\"vendor/\", \"*_old.eds\"]")
    return LintConfig(path, _rules(table.get("select", []), f"{section}select"),
                      _rules(table.get("ignore", []), f"{section}ignore"),
                      tuple((glob, _rules(rules, f"{section}per-file-ignores {glob!r}"))
                            for glob, rules in per_file.items()),
                      strict, node_id, tuple(p.strip().removeprefix("./") for p in exclude))


def config_for(file: Path, explicit: Path | None = None) -> LintConfig:
    """The settings that apply to one linted file (`explicit`: --config given on the command line)."""
    path = explicit or find_config(file)
    return load_config(path) if path is not None else LintConfig()
