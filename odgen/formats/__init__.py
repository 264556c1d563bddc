"""Readers: one per input format, all producing the same model.

`load_path` picks the reader by file suffix (another suffix, such as .txt or .ini, needs the
format named: `--input-format`, since guessing would lint a file that is no description) and
returns the model, or None when the file could not be understood at all, with
the diagnostics found while reading.
"""

from __future__ import annotations

from pathlib import Path

from ..catalogue.syntax import SYN018
from ..diagnostics import Diagnostics, Loc
from ..choices import INPUT_FORMATS
from ..errors import OdgenError
from ..gcpause import no_cyclic_gc
from ..model import ObjectDictionary

MAX_BYTES = 16 * 1024 * 1024  # larger files are refused unread (SYN018): memory stays bounded
FORMATS = {".eds": "eds", ".dcf": "dcf", ".xdd": "xdd", ".xpd": "xdd", ".xdc": "xdc"}


def detect_format(path: Path, fmt: str | None = None) -> str:
    if fmt is not None:
        return fmt
    known = FORMATS.get(path.suffix.lower())
    if known is None:
        suffix = f"'{path.suffix}'" if path.suffix else "no suffix"
        raise OdgenError(f"{path}: {suffix} is not a description's suffix ({', '.join(FORMATS)}); "
                         f"name the format with --input-format {'|'.join(INPUT_FORMATS)}")
    return known


def read_bytes(path: Path, limit: int | None = None) -> bytes:
    """The file's bytes; with a limit, at most limit + 1 of them (enough to tell it is too large)."""
    try:
        with path.open("rb") as src:
            return src.read(-1 if limit is None else limit + 1)
    except OSError as err:
        raise OdgenError(f"{path}: cannot read: {err.strerror or err}") from None


def load_bytes(data: bytes, source: str, fmt: str) -> tuple[ObjectDictionary | None, Diagnostics]:
    with no_cyclic_gc():
        return _load_bytes(data, source, fmt)


def _load_bytes(data: bytes, source: str, fmt: str) -> tuple[ObjectDictionary | None, Diagnostics]:
    diags = Diagnostics()
    if len(data) > MAX_BYTES:
        diags.add(SYN018, Loc(source), f"file is larger than {MAX_BYTES >> 20} MiB; not read")
        return None, diags
    if fmt in ("xdd", "xdc"):
        from .xdd import load_xdd

        return load_xdd(data, source, diags), diags
    from .eds import load_eds

    return load_eds(data, source, diags, fmt), diags


def load_path(path: str | Path, fmt: str | None = None) -> tuple[ObjectDictionary | None, Diagnostics]:
    path = Path(path)
    fmt = detect_format(path, fmt)
    return load_bytes(read_bytes(path, MAX_BYTES), str(path), fmt)
