"""Where odgen's own files are: the only module that finds templates, schemas, runtime, CMake module and docs.

They ship inside the package as odgen.templates, odgen.schemas, odgen.runtime, odgen.cmake and odgen.docs
(pyproject.toml maps the repository's top-level folders there), so an installed odgen never
looks outside site-packages. In a source checkout (an editable install, or tests run from the
repository) those names do not import: setuptools' editable finder does not resolve namespace
packages below a regular one, so the folders are taken from the top of the checkout instead.
"""

from __future__ import annotations

import importlib.util
from functools import cache
from importlib import resources
from pathlib import Path

from .errors import OdgenError


CHECKOUT = Path(__file__).resolve().parent.parent  # a source checkout's top, if odgen runs from one


@cache
def _folder(package: str) -> Path:
    """A real directory (the C compiler, CMake and jinja2 read it by path, not through a reader)."""
    try:
        spec = importlib.util.find_spec(package)
    except ModuleNotFoundError:
        spec = None
    if spec is not None:
        root = resources.files(package)
        if isinstance(root, Path):
            return root
        # A folder without __init__.py is a namespace package: its reader is a MultiplexedPath.
        for location in spec.submodule_search_locations or []:
            if Path(location).is_dir():
                return Path(location)
    folder = CHECKOUT / package.rpartition(".")[2]
    if (CHECKOUT / "pyproject.toml").is_file() and folder.is_dir():
        return folder
    raise OdgenError(f"odgen is installed without its {package} files: reinstall it "
                     "(pip install --force-reinstall odgen)")


def templates_dir() -> Path:
    return _folder("odgen.templates")


def schema_path(name: str = "cia311-odgen.xsd") -> Path:
    return _folder("odgen.schemas") / name


def runtime_dir() -> Path:
    return _folder("odgen.runtime")


def cmake_dir() -> Path:
    return _folder("odgen.cmake")


def docs_dir() -> Path:
    """The docs/*.md pages; odgen's messages and generated files name them as docs/NAME.md."""
    return _folder("odgen.docs")
