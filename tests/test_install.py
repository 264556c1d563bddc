"""The installed package is the product: build the sdist and the wheel from it, install the wheel
into a fresh venv outside the source tree (under the oldest Python pyproject.toml declares, from
$ODGEN_OLDEST_PYTHON, which `make test` sets with tools/oldest-python.sh), and use it as a user
would from a temporary folder: lint, generate, check, profile, a CMake firmware project, the
licence, README and docs; and the release smoke test of `make release` on the same wheel.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib
import zipfile
from pathlib import Path

import pytest
import yaml

import odgen

from .test_docs_site import named_pages

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
XDD = ROOT / "tests" / "fixtures" / "xdd"


def _oldest_python() -> str:
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["requires-python"]
    wanted = re.fullmatch(r">=(\d+)\.(\d+)", declared)
    assert wanted, declared
    given = os.environ.get("ODGEN_OLDEST_PYTHON")
    if given:
        return given
    found = subprocess.run([str(ROOT / "tools" / "oldest-python.sh")], capture_output=True, text=True, check=False)
    if found.returncode != 0:
        pytest.skip(f"no Python {wanted.group(1)}.{wanted.group(2)} here ({found.stderr.strip()}); "
                    "`make test` installs it")
    return found.stdout.strip()


def run(cmd: list[str], cwd: Path, env: dict[str, str] | None = None,
        ok: bool = True) -> subprocess.CompletedProcess[str]:
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env, check=False, timeout=600)
    if ok:
        assert done.returncode == 0, f"{cmd}: {done.returncode}\n{done.stdout}{done.stderr}"
    return done


@pytest.fixture(scope="module")
def installed(dist: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A venv of the oldest declared Python with the wheel installed (no [can] extra); its bin/."""
    env_dir = tmp_path_factory.mktemp("venv")
    run([_oldest_python(), "-m", "venv", str(env_dir)], cwd=env_dir)
    wheel = next(dist.glob("odgen-*.whl"))
    run([str(env_dir / "bin" / "python"), "-m", "pip", "install", "-q", str(wheel)], cwd=env_dir)
    return env_dir / "bin"


def test_wheel_carries_templates_schemas_runtime_and_cmake(dist: Path) -> None:
    names = set(zipfile.ZipFile(next(dist.glob("odgen-*.whl"))).namelist())
    expected = {f"odgen/templates/{p.name}" for p in (ROOT / "templates").glob("*.j2")}
    expected |= {f"odgen/schemas/{p.name}" for p in (ROOT / "schemas").glob("*.xsd")}
    expected |= {f"odgen/runtime/{p.relative_to(ROOT / 'runtime').as_posix()}"
                 for p in (ROOT / "runtime").rglob("*") if p.suffix in (".c", ".h")}
    expected |= {"odgen/cmake/odgen.cmake"}
    version = odgen.__version__
    expected |= {f"odgen-{version}.data/data/share/odgen/cmake/{p.name}" for p in (ROOT / "cmake").glob("odgenConfig*")}
    expected |= {p.relative_to(ROOT).as_posix() for p in (ROOT / "odgen").rglob("*.py")}
    assert expected - names == set(), "missing from the wheel"


def test_installed_odgen_works_outside_the_source_tree(installed: Path, tmp_path: Path) -> None:
    odgen = str(installed / "odgen")
    version = run([odgen, "--version"], tmp_path).stdout
    assert version.startswith("odgen ")
    eds = shutil.copy(EXAMPLES / "io-node" / "io-node.eds", tmp_path)
    toml = shutil.copy(EXAMPLES / "io-node" / "io-node.toml", tmp_path)
    xdd = shutil.copy(XDD / "valid.xdd", tmp_path)
    assert "file(s) checked" in run([odgen, "lint", "io-node.eds"], tmp_path).stdout
    assert "file(s) checked" in run([odgen, "lint", Path(xdd).name], tmp_path).stdout  # the schema is found
    run([odgen, "generate", eds, "--options", toml, "-o", "out"], tmp_path)
    assert (tmp_path / "out" / "io_node.c").is_file() and (tmp_path / "out" / "io_node.h").is_file()
    run([odgen, "generate", eds, "--options", toml, "-o", "out", "--check"], tmp_path)
    assert "ok" in run([odgen, "check", eds, "--options", toml], tmp_path).stdout
    run([odgen, "profile", "ds401", "--di", "8", "--do", "8", "-o", "io.eds", "--generate", "gen"], tmp_path)
    generated = sorted(p.name for p in (tmp_path / "gen").iterdir())
    assert generated == ["ds401_app.h", "io.c", "io.h", "io_config.h"]
    runtime = Path(run([odgen, "--runtime-dir"], tmp_path).stdout.strip())
    assert (runtime / "odg.h").is_file() and installed.parent in runtime.parents
    assert (runtime / "profiles" / "ds401.c").is_file()  # the glue ds401_app.h configures


def test_can_commands_name_the_extra(installed: Path, tmp_path: Path) -> None:
    eds = shutil.copy(EXAMPLES / "io-node" / "io-node.eds", tmp_path)
    for command in (["node", eds], ["roundtrip", eds]):
        done = run([str(installed / "odgen"), *command], tmp_path, ok=False)
        assert done.returncode == 2 and "odgen[can]" in done.stderr, done.stderr


def _build(build: Path) -> str:
    done = run(["cmake", "--build", str(build)], build)
    return done.stdout


def _firmware_project(tmp_path: Path) -> Path:
    """examples/cmake-firmware with its description beside it, outside the repository."""
    if shutil.which("cmake") is None:
        pytest.fail("cmake is missing: `make sysdeps` installs it")
    project = tmp_path / "fw"
    shutil.copytree(EXAMPLES / "cmake-firmware", project)
    for name in ("io-node.eds", "io-node.toml"):
        shutil.copy(EXAMPLES / "io-node" / name, project)
    return project


def test_cmake_firmware_outside_the_repository(installed: Path, tmp_path: Path) -> None:
    """find odgen on PATH, include its module, build odgen::runtime; regenerate only when needed."""
    project = _firmware_project(tmp_path)
    env = dict(os.environ, PATH=f"{installed}{os.pathsep}{os.environ['PATH']}")
    build = tmp_path / "build"
    run(["cmake", "-S", str(project), "-B", str(build), f"-DIO_NODE_DIR={project}"], tmp_path, env=env)
    assert str(installed) in (build / "CMakeCache.txt").read_text(), "the installed odgen was used"
    first = _build(build)
    assert "odgen: object dictionary io_node" in first
    assert "looped back" in run([str(build / "firmware")], tmp_path).stdout
    assert "odgen:" not in (noop := _build(build)) and "Building C object" not in noop, noop
    (project / "io-node.eds").touch()
    touched = _build(build)
    assert "odgen: object dictionary" in touched and "Building C object" not in touched, touched
    eds = project / "io-node.eds"
    eds.write_text(eds.read_text().replace("ProductName=", "ProductName=New "), encoding="utf-8")
    changed = _build(build)
    assert "odgen: object dictionary" in changed and "io_node.c.o" in changed, changed
    options = project / "io-node.toml"
    options.write_text(options.read_text() + "\n", encoding="utf-8")
    assert "odgen: object dictionary" in _build(build)
    assert "looped back" in run([str(build / "firmware")], tmp_path).stdout


def test_find_package_finds_the_installed_odgen(installed: Path, tmp_path: Path) -> None:
    """The wheel puts odgenConfig.cmake into <venv>/share/odgen/cmake: with the venv's bin/ on PATH,
    find_package(odgen 0.1) needs nothing else; a version the installed odgen is not is refused."""
    project = _firmware_project(tmp_path)
    lists = project / "CMakeLists.txt"
    text = lists.read_text(encoding="utf-8")
    start, end = text.index("find_program(ODGEN_EXECUTABLE"), text.index('include("${ODGEN_CMAKE_DIR}/odgen.cmake")')
    lists.write_text(text[:start] + "find_package(odgen 0.1 REQUIRED)" + text[end + 41:], encoding="utf-8")
    env = dict(os.environ, PATH=f"{installed}{os.pathsep}{os.environ['PATH']}")
    build = tmp_path / "build"
    run(["cmake", "-S", str(project), "-B", str(build), f"-DIO_NODE_DIR={project}"], tmp_path, env=env)
    assert f"odgen_DIR:PATH={installed.parent}/share/odgen/cmake" in (build / "CMakeCache.txt").read_text()
    assert "odgen: object dictionary io_node" in _build(build)
    assert "looped back" in run([str(build / "firmware")], tmp_path).stdout
    lists.write_text(lists.read_text(encoding="utf-8").replace("odgen 0.1 REQUIRED", "odgen 99 REQUIRED"),
                     encoding="utf-8")
    refused = run(["cmake", "-S", str(project), "-B", str(tmp_path / "b99")], tmp_path, env=env, ok=False)
    version = odgen.__version__
    assert refused.returncode != 0 and f"odgenConfig.cmake, version: {version}" in refused.stderr, refused.stderr


def test_licence_readme_and_docs_from_the_installed_wheel(installed: Path, tmp_path: Path) -> None:
    """What a user of the wheel alone can read: the licence and README in the metadata, and every
    docs page odgen's messages and generated files name, in `odgen --docs-dir`."""
    probe = ("import importlib.metadata as m, pathlib, sys\n"
             "meta = m.metadata('odgen')\n"
             "licence = next(f for f in m.files('odgen') if f.name == 'LICENSE')\n"
             "print(meta['License-Expression'])\n"
             "print(pathlib.Path(licence.locate()).read_text().splitlines()[1].strip())\n"
             "sys.stdout.write(meta.get_payload())\n")
    shown = run([str(installed / "python"), "-c", probe], tmp_path).stdout.splitlines()
    assert shown[:2] == ["Apache-2.0", "Apache License"]
    assert "\n".join(shown[2:]).strip() == (ROOT / "README.md").read_text(encoding="utf-8").strip()
    docs = Path(run([str(installed / "odgen"), "--docs-dir"], tmp_path).stdout.strip())
    assert installed.parent in docs.parents
    assert sorted(p.name for p in docs.glob("*.md")) == sorted(p.name for p in (ROOT / "docs").glob("*.md"))
    runtime = Path(run([str(installed / "odgen"), "--runtime-dir"], tmp_path).stdout.strip())
    folders = {"docs": docs, "runtime": runtime}
    assert [f"{d}/{p}" for d, p in sorted(named_pages()) if not (folders[d] / p).is_file()] == []


def test_release_smoke_script_on_the_wheel(dist: Path, installed: Path, tmp_path: Path) -> None:
    """tools/release-smoke.sh, which `make release` and the release workflow run on their wheel, here
    on the venv the other tests installed the same wheel into (its install steps are the fixture's)."""
    env = dict(os.environ, ODGEN_SMOKE_INSTALLED="1")
    done = run(["bash", str(ROOT / "tools" / "release-smoke.sh"), str(dist), str(installed.parent)], tmp_path, env=env)
    assert f"odgen {odgen.__version__} from odgen-{odgen.__version__}-py3-none-any.whl works" in done.stdout
    (tmp_path / "two").mkdir()
    for wheel in ("odgen-0.1.0-py3-none-any.whl", "odgen-0.2.0-py3-none-any.whl"):
        (tmp_path / "two" / wheel).touch()
    refused = run(["bash", str(ROOT / "tools" / "release-smoke.sh"), str(tmp_path / "two"), str(installed.parent)],
                  tmp_path, env=env, ok=False)
    assert refused.returncode == 2 and "want one odgen wheel" in refused.stderr


def test_release_workflow_and_make_target_do_the_same() -> None:
    workflow = yaml.safe_load((ROOT / ".github" / "workflows" / "release.yml").read_text(encoding="utf-8"))
    assert workflow[True]["push"]["tags"] == ["v*"]  # YAML 1.1 reads the key `on` as True
    steps = " ".join(s.get("run", "") for s in workflow["jobs"]["release"]["steps"])
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    target = re.search(r"^release:.*?\n((?:\t.*\n)+)", makefile, re.MULTILINE)
    assert target, "no release target"
    for step in ("-m build --outdir dist .", "twine check --strict dist/*", "tools/release-smoke.sh dist "):
        assert step in steps and step in target.group(1), step
