"""The house's floors: docs/design.md ("Floors") says on which floor each package of odgen/ stands;
no module imports from a floor above its own, and no two packages import each other (directly or
round a longer cycle). Between the C runtime's files there is no include cycle, and no call cycle:
docs/design.md ("The runtime's levels") puts each file the firmware links on a level, and a file
calls only functions of files on lower levels (so no service of the node calls the hub).

Imports are read from the source with `ast` (a module imported only under `if TYPE_CHECKING:` is
an annotation, not an import). Calls are read from the objects the compiler makes of each file
(`nm`: the functions a file defines, and those it refers to but another file defines), so that
macros and conditional code count as the compiler sees them. The tests also run against small
made-up trees, so that a broken checker cannot pass by finding nothing.
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
from collections.abc import Iterable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from odgen import toolchain

from .conftest import ROOT

DESIGN = ROOT / "docs" / "design.md"


def floors(design: str) -> dict[str, int]:
    """Package or module name (first part under odgen/) -> floor number, from the design's table."""
    section = design.split("## Floors", 1)[1].split("\n## ", 1)[0]
    found: dict[str, int] = {}
    for line in section.splitlines():
        match = re.match(r"\|\s*(\d+)\s[^|]*\|([^|]*)\|", line)
        if match:
            for name in re.findall(r"`([\w.]+)`", match.group(2)):
                found[name] = int(match.group(1))
    return found


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> list[str]:
    """The odgen modules an import names (for `from . import a, b`: each of a and b)."""
    if node.level == 0:
        base = node.module or ""
        return [base] if base == "odgen" or base.startswith("odgen.") else []
    parts = module.split(".") if is_package else module.split(".")[:-1]
    parts = parts[: len(parts) - (node.level - 1)]
    if node.module:
        return [".".join([*parts, node.module])]
    return [".".join([*parts, alias.name]) for alias in node.names]


def _runtime_imports(tree: ast.Module) -> Iterable[ast.Import | ast.ImportFrom]:
    """Every import statement except those under `if TYPE_CHECKING:`."""
    skip: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip.update(id(n) for branch in node.body for n in ast.walk(branch))
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)) and id(node) not in skip:
            yield node


def imports(package_dir: Path) -> dict[str, set[str]]:
    """Module name -> the odgen modules it imports (at run time)."""
    found: dict[str, set[str]] = {}
    root = package_dir.parent
    for path in sorted(package_dir.rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        module = ".".join(parts[:-1] if is_package else parts)
        targets: set[str] = set()
        for node in _runtime_imports(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets.update(a.name for a in node.names if a.name.split(".")[0] == "odgen")
            else:
                targets.update(_resolve(module, is_package, node))
        found[module] = targets
    return found


def unit(module: str) -> str:
    """The package or top-level module a module belongs to: odgen.lint.passes.pdo -> lint."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def violations(graph: Mapping[str, set[str]], floor_of: Mapping[str, int]) -> list[str]:
    """Upward imports, units on no floor, and cycles between units."""
    problems = [f"{unit(m)} ({m}) is on no floor of docs/design.md" for m in sorted(graph)
                if unit(m) not in floor_of]
    edges: dict[str, set[str]] = {}
    for module, targets in graph.items():
        for target in targets:
            a, b = unit(module), unit(target)
            if a == b or a not in floor_of or b not in floor_of:
                continue
            edges.setdefault(a, set()).add(b)
            if floor_of[b] > floor_of[a]:
                problems.append(f"{module} imports {target}: floor {floor_of[a]} ({a}) up to {floor_of[b]} ({b})")
    problems += [f"import cycle: {' -> '.join(c)}" for c in cycles(edges)]
    return problems


def cycles(edges: Mapping[str, set[str]]) -> list[list[str]]:
    """One cycle for each strongly connected group of more than one node (or a node on itself)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []

    def visit(v: str) -> None:  # Tarjan's algorithm; the graphs here are a few dozen nodes
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                group.append(w)
                if w == v:
                    break
            if len(group) > 1 or v in edges.get(v, ()):
                found.append(sorted(group) + [sorted(group)[0]])

    for v in sorted(set(edges) | {w for ws in edges.values() for w in ws}):
        if v not in index:
            visit(v)
    return found


def includes(runtime: Path) -> dict[str, set[str]]:
    """Runtime file -> the runtime files it includes with "..." (by file name)."""
    names = {p.name for p in runtime.rglob("*.[ch]")}
    found: dict[str, set[str]] = {}
    for path in runtime.rglob("*.[ch]"):
        text = path.read_text(encoding="utf-8")
        found[path.name] = {n for n in re.findall(r'^\s*#\s*include\s+"([^"]+)"', text, re.M) if n in names}
    return found


def levels(design: str) -> dict[str, int]:
    """Runtime file -> level, from the design's table (each file named on its own, no patterns)."""
    section = design.split("## The runtime's levels", 1)[1].split("\n## ", 1)[0]
    found: dict[str, int] = {}
    for line in section.splitlines():
        match = re.match(r"\|\s*(\d+)\s*\|([^|]*)\|", line)
        if match:
            for name in re.findall(r"`([\w./]+\.c)`", match.group(2)):
                found[name] = int(match.group(1))
    return found


def compile_objects(sources: Sequence[Path], out: Path, flags: Sequence[str]) -> dict[str, Path]:
    """Each C file compiled on its own: file name relative to its runtime folder -> object."""
    cc = toolchain.compiler()
    out.mkdir(parents=True, exist_ok=True)

    def build(source: Path) -> tuple[str, Path]:
        name = source.relative_to(source.parents[1] if source.parent.name == "linux" else source.parent).as_posix()
        obj = out / (name.replace("/", "_") + ".o")
        done = subprocess.run([cc, *flags, "-c", str(source), "-o", str(obj)], capture_output=True, text=True,
                              check=False)
        assert done.returncode == 0, f"{source}: {done.stderr}"
        return name, obj

    with ThreadPoolExecutor(max_workers=4) as pool:
        return dict(pool.map(build, sources))


def calls(objects: Mapping[str, Path]) -> dict[str, set[str]]:
    """File -> the other files whose functions (or data) it refers to, read from the objects."""
    nm = shutil.which("nm")
    assert nm, "nm (binutils) is missing"
    defined: dict[str, str] = {}
    wanted: dict[str, set[str]] = {}
    for name, obj in objects.items():
        lines = subprocess.run([nm, "-P", "-g", str(obj)], capture_output=True, text=True, check=True).stdout
        wanted[name] = set()
        for row in (line.split() for line in lines.splitlines()):
            if len(row) >= 2 and row[1] == "U":
                wanted[name].add(row[0])
            elif len(row) >= 2 and row[1] in "TDRBCGS":
                defined[row[0]] = name
    return {name: {defined[s] for s in symbols if s in defined and defined[s] != name}
            for name, symbols in wanted.items()}


def call_violations(graph: Mapping[str, set[str]], level_of: Mapping[str, int]) -> list[str]:
    """Files on no level, calls to a level not below the caller's, and call cycles."""
    problems = [f"{name} is on no level of docs/design.md" for name in sorted(graph) if name not in level_of]
    edges: dict[str, set[str]] = {}
    for name, targets in sorted(graph.items()):
        for target in sorted(targets):
            if name not in level_of or target not in level_of:
                continue
            edges.setdefault(name, set()).add(target)
            if level_of[target] >= level_of[name]:
                problems.append(f"{name} calls {target}: level {level_of[name]} to level {level_of[target]}")
    problems += [f"call cycle: {' -> '.join(c)}" for c in cycles(edges)]
    return problems


RUNTIME_SOURCES = (*toolchain.CORE_SOURCES, *toolchain.SERVICE_SOURCES, *toolchain.MASTER_SOURCES,
                   *toolchain.HOST_SOURCES)
# Every switch on, so that each file's calls are all there (ODG_NODE_LSS is off by default).
CALL_FLAGS = (*toolchain.CFLAGS, "-DODG_NODE_LSS=1", *(f"-I{d}" for d in toolchain.include_dirs(node=True)))


# -- the house ---------------------------------------------------------------------

def test_every_package_is_on_a_floor_and_imports_only_downward() -> None:
    floor_of = floors(DESIGN.read_text(encoding="utf-8"))
    assert {"model", "lint", "place", "codegen", "pipeline", "cli"} <= set(floor_of)
    assert violations(imports(ROOT / "odgen"), floor_of) == []


def test_no_include_cycle_between_runtime_files() -> None:
    assert cycles(includes(ROOT / "runtime")) == []


@pytest.fixture(scope="module")
def runtime_calls(tmp_path_factory: pytest.TempPathFactory) -> dict[str, set[str]]:
    sources = [ROOT / "runtime" / name for name in RUNTIME_SOURCES]
    return calls(compile_objects(sources, tmp_path_factory.mktemp("calls"), CALL_FLAGS))


def test_runtime_files_call_only_lower_levels(runtime_calls: dict[str, set[str]]) -> None:
    level_of = levels(DESIGN.read_text(encoding="utf-8"))
    assert call_violations(runtime_calls, level_of) == []
    assert runtime_calls["odg_node.c"] >= {"odg_sdo.c", "odg_pdo.c", "odg_hb.c", "odg_err.c", "odg_node_io.c"}


def test_no_service_calls_the_hub(runtime_calls: dict[str, set[str]]) -> None:
    # the master stands above the node and uses its public API; the node's own files never call the hub
    below_master = set(runtime_calls) - set(toolchain.MASTER_SOURCES)
    assert [name for name in sorted(below_master) if "odg_node.c" in runtime_calls[name]] == []


# -- the checkers find what they must ------------------------------------------------

def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = tmp_path / "odgen" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return tmp_path / "odgen"


@pytest.mark.parametrize("files, expected", [
    ({"__init__.py": "", "model/__init__.py": "from ..lint import x\n", "lint/__init__.py": ""}, "up to"),
    ({"__init__.py": "", "lint/a.py": "from ..place.b import y\n", "place/b.py": "from ..lint import a\n"},
     "import cycle"),
    ({"__init__.py": "", "model/a.py": "import odgen.lint.passes\n", "lint/passes.py": ""}, "up to"),
    ({"__init__.py": "", "model/a.py": "from . import b\nfrom .. import lint\n", "model/b.py": "",
      "lint/__init__.py": ""}, "up to"),
    ({"__init__.py": "", "stray.py": ""}, "on no floor"),
])
def test_checker_finds_upward_imports_cycles_and_strays(tmp_path: Path, files: dict[str, str], expected: str) -> None:
    floor_of = {"odgen": 0, "model": 1, "lint": 3, "place": 3}
    problems = violations(imports(_tree(tmp_path, files)), floor_of)
    assert any(expected in p for p in problems), problems


def test_checker_ignores_annotations_only_imports(tmp_path: Path) -> None:
    files = {"__init__.py": "", "lint/__init__.py": "",
             "model/a.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from ..lint import x\n"}
    assert violations(imports(_tree(tmp_path, files)), {"odgen": 0, "model": 1, "lint": 3}) == []


def test_include_checker_finds_a_cycle(tmp_path: Path) -> None:
    (tmp_path / "a.h").write_text('#include "b.h"\n', encoding="utf-8")
    (tmp_path / "b.h").write_text('#include <stdint.h>\n#include "c.h"\n', encoding="utf-8")
    (tmp_path / "c.h").write_text('#  include "a.h"\n', encoding="utf-8")
    assert cycles(includes(tmp_path)) == [["a.h", "b.h", "c.h", "a.h"]]


def _objects(tmp_path: Path, files: dict[str, str]) -> dict[str, Path]:
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    return compile_objects([tmp_path / name for name in files], tmp_path / "obj", toolchain.CFLAGS)


def test_call_checker_finds_a_cycle_and_an_upward_call(tmp_path: Path) -> None:
    files = {"hub.c": "void hub(void);\nvoid svc(void);\nvoid hub(void) { svc(); }\n",
             "svc.c": "void hub(void);\nvoid low(void);\nvoid svc(void);\nvoid svc(void) { low(); }\n"
                      "static void (*back)(void) = hub;\nvoid low(void) { back(); }\n",
             "io.c": "void svc(void);\nvoid io(void);\nvoid io(void) { svc(); }\n"}
    graph = calls(_objects(tmp_path, files))
    assert graph == {"hub.c": {"svc.c"}, "svc.c": {"hub.c"}, "io.c": {"svc.c"}}
    problems = call_violations(graph, {"io.c": 0, "svc.c": 1, "hub.c": 2})
    assert "svc.c calls hub.c: level 1 to level 2" in problems
    assert "io.c calls svc.c: level 0 to level 1" in problems
    assert "call cycle: hub.c -> svc.c -> hub.c" in problems


def test_call_checker_finds_a_call_on_one_level_and_strays(tmp_path: Path) -> None:
    files = {"p_a.c": "void b(void);\nvoid a(void);\nvoid a(void) { b(); }\n",
             "p_b.c": "void a(void);\nvoid b(void);\nvoid b(void) { }\n",
             "stray.c": "void a(void);\nvoid s(void);\nvoid s(void) { a(); }\n"}
    problems = call_violations(calls(_objects(tmp_path, files)), {"p_a.c": 0, "p_b.c": 0})
    assert problems == ["stray.c is on no level of docs/design.md", "p_a.c calls p_b.c: level 0 to level 0"]
