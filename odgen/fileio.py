"""Output files are written whole or not at all: temporary file, fsync, then rename.

A temporary file is removed whatever stops the write (an error, Ctrl-C, SIGTERM: main() turns
SIGTERM into an exception so this cleanup runs). A rename replaces a symlink rather than
writing through it. Files whose content would not change are left alone, mtime included, so
a build system recompiles nothing when the generated output is the same.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Mapping
from pathlib import Path

from .errors import OdgenError

TMP_SUFFIX = ".tmp"


def temp_prefix(name: str) -> str:
    return f".{name}."


def _cannot(path: Path, err: OSError) -> OdgenError:
    return OdgenError(f"cannot write {path}: {err.strerror or err}")


def _write_temp(path: Path, text: str | bytes) -> str:
    import tempfile  # with shutil, bz2 and lzma: not paid by a lint that writes nothing

    try:
        fd, tmp = tempfile.mkstemp(prefix=temp_prefix(path.name), suffix=TMP_SUFFIX, dir=path.parent or ".")
    except OSError as err:
        raise _cannot(path, err) from None
    try:
        with os.fdopen(fd, "wb") as out:  # text as UTF-8 with \n line ends, bytes as they are
            out.write(text.encode("utf-8") if isinstance(text, str) else text)
            out.flush()
            os.fsync(out.fileno())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes 0600; outputs are ordinary files
    except BaseException as err:
        os.unlink(tmp)
        if isinstance(err, OSError):
            raise _cannot(path, err) from None
        raise
    return tmp


def write_atomic(path: str | Path, text: str) -> None:
    write_files({Path(path): text})


def unchanged(path: Path, text: str | bytes) -> bool:
    data = text.encode("utf-8") if isinstance(text, str) else text
    try:
        return path.is_file() and not path.is_symlink() and path.read_bytes() == data
    except OSError:
        return False


def write_files(files: Mapping[Path, str] | Mapping[Path, str | bytes], only_changed: bool = False) -> list[Path]:
    """Write several files as one step: every temp file first, then the renames. Returns those written."""
    todo = {path: text for path, text in files.items() if not (only_changed and unchanged(path, text))}
    temps: dict[Path, str] = {}
    try:
        for path, text in todo.items():
            temps[path] = _write_temp(path, text)
        for path, tmp in list(temps.items()):
            try:
                os.replace(tmp, path)
            except OSError as err:
                raise _cannot(path, err) from None
            del temps[path]
    finally:
        for tmp in temps.values():
            with contextlib.suppress(OSError):
                os.unlink(tmp)
    return list(todo)


def output_dir(path: Path) -> Path:
    """Create an output folder, or say why it cannot be (exit 2)."""
    if path.exists() and not path.is_dir():
        raise OdgenError(f"cannot write {path}: it is a file, not a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise OdgenError(f"cannot write {path}: {err.strerror or err}") from None
    return path


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask
