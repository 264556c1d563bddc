"""Differential check against python canopen's EDS import on the same files.

For every corpus EDS/DCF that `canopen.import_od` loads, odgen must find the same
indices, sub-indices, data types, access types and default values, except for
these justified differences, each filtered explicitly below:

1. Dummy objects: canopen adds enabled [DummyUsage] types as objects 0x0001-0x0007;
   odgen keeps them as the [DummyUsage] section (they are not objects of the file).
2. CompactSubObj: canopen creates sub0 as rw with no default; CiA 306 defines it as
   UNSIGNED8, ro, default = the CompactSubObj count, as odgen does.
3. Complex data types (DataType > 0x1B, e.g. 0x20-0x23): canopen degrades them to
   DOMAIN; odgen keeps the declared code.
4. DOMAIN defaults: CiA 306 gives DOMAIN no DefaultValue; canopen turns some into
   bytes and drops others, odgen keeps the text. Not compared.
5. Signed entries written as unsigned hex (0xFFFF for INTEGER16): canopen keeps the
   out-of-range number 65535, odgen the two's complement -1 (reported as SYN008).
6. Values canopen cannot read and drops (BOOLEAN `false`, leading-zero octal): odgen
   reads them and notes the form; compared only when canopen has a value.
Granularity (canopen reads it as a bool) is a header key, not part of this comparison.
"""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from odgen.formats import load_path
from odgen.model import Obj, Sub
from odgen.model.datatypes import BASIC_TYPES

from .conftest import corpus_params

canopen = pytest.importorskip("canopen")
NODE_ID = 1


def _import_canopen(path: Path):
    logging.disable(logging.CRITICAL)
    try:
        return canopen.import_od(str(path), node_id=NODE_ID)
    except Exception:  # canopen fails on some real files; those are not compared
        return None
    finally:
        logging.disable(logging.NOTSET)


def _their_subs(obj) -> dict:
    if isinstance(obj, canopen.objectdictionary.ODVariable):
        return {0: obj}
    return dict(obj.subindices)


def _compare_default(sub: Sub, var, where: str, problems: list[str]) -> None:
    dtype = BASIC_TYPES.get(sub.data_type or 0)
    if dtype is None or dtype.kind == "domain" or var.default is None:  # 3, 4, 6
        return
    ours = sub.default.resolve(NODE_ID) if sub.default is not None else None
    theirs = var.default
    if dtype.kind == "int" and isinstance(theirs, int) and theirs > (dtype.max or 0):
        theirs -= 1 << dtype.bits  # 5
    close = dtype.kind == "real" and ours is not None and theirs is not None \
        and abs(float(ours) - float(theirs)) <= 1e-6 * max(1.0, abs(float(theirs)))
    if close:
        return
    if ours != theirs:
        problems.append(f"{where} default {ours!r} != {theirs!r}")


def _compare_sub(obj: Obj, sub: Sub | None, var, problems: list[str]) -> None:
    where = f"0x{obj.index:04X}sub{var.subindex}"
    if sub is None:
        problems.append(f"{where} missing in odgen")
        return
    if sub.compact and sub.subindex == 0:  # 2
        return
    if sub.data_type != var.data_type and BASIC_TYPES.get(sub.data_type or 0) is not None:  # 3
        problems.append(f"{where} data type {sub.data_type} != {var.data_type}")
    if sub.access != var.access_type:
        problems.append(f"{where} access {sub.access} != {var.access_type}")
    _compare_default(sub, var, where, problems)


@pytest.mark.parametrize("path", corpus_params(".eds", ".dcf"))
def test_same_dictionary_as_canopen(path: Path) -> None:
    theirs = _import_canopen(path)
    if theirs is None:
        pytest.skip(f"canopen cannot import {path.name}")
    ours, _ = load_path(path)
    assert ours is not None
    their_indices = {i for i in theirs.indices if i > 0x0007}  # 1
    assert set(ours.objects) == their_indices
    problems: list[str] = []
    for index in sorted(their_indices):
        obj = ours.objects[index]
        for subindex, var in sorted(_their_subs(theirs[index]).items()):
            _compare_sub(obj, obj.subs.get(subindex), var, problems)
    assert not problems, "\n".join(problems[:20])
