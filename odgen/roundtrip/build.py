"""Build a CANopen node program from any description: generated dictionary + runtime + SocketCAN main.

Builds are cached by a hash of everything that goes into them, so `odgen node` and
`odgen roundtrip` start at once the second time.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..assets import runtime_dir
from ..pipeline import Request, Result, generate
from ..errors import OdgenError
from ..fileio import output_dir, write_files
from ..model import ObjectDictionary
from ..model.cia301 import COMMUNICATION_AREA
from ..model.datatypes import BASIC_TYPES
from ..toolchain import CFLAGS, NODE_MAIN, compiler, include_dirs, node_sources


def cache_dir() -> Path:
    base = os.environ.get("ODGEN_CACHE") or os.path.join(os.environ.get("XDG_CACHE_HOME", str(Path.home() / ".cache")),
                                                        "odgen")
    return Path(base) / "node"


def _stubs(functions: list[str]) -> str:
    """Hook functions the options name: the node program answers with the stored value only."""
    lines = ['#include "odg.h"']
    for fn in functions:
        lines.append(f"odg_abort_t {fn}(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, "
                     "uint32_t len, void *ctx);")
        lines.append(f"odg_abort_t {fn}(const odg_ref_t *ref, odg_hook_kind_t kind, const void *data, "
                     "uint32_t len, void *ctx)\n{\n    (void)ref; (void)kind; (void)data; (void)len; (void)ctx;\n"
                     "    return ODG_OK;\n}")
    return "\n".join(lines) + "\n"


def comm_bytes(od: ObjectDictionary | None) -> int:
    """At least what the node keeps of the communication values for reset communication
    (odg_node_comm_bytes, runtime/NODE.md): every number of 0x1000-0x1FFF, at 8 bytes each."""
    first, last = COMMUNICATION_AREA
    numbers = [sub for obj in (od.sorted_objects() if od is not None else []) if first <= obj.index <= last
               for sub in obj.sorted_subs() if (t := BASIC_TYPES.get(sub.data_type or 0)) is not None and t.is_numeric]
    return max(8 * len(numbers), 1)


def _digest(result: Result, sources: list[Path], cc: str, extra: Mapping[str, str] = {},
            defines: Sequence[str] = ()) -> str:
    h = hashlib.sha256(cc.encode())
    for name, text in sorted({**result.files, **extra}.items()):
        h.update(name.encode() + text.encode())
    h.update("|".join(defines).encode())
    for path in [*sources, runtime_dir() / NODE_MAIN]:
        h.update(path.read_bytes())
    for header in sorted(runtime_dir().glob("**/*.h")):
        h.update(header.read_bytes())
    return h.hexdigest()[:20]


def build_node(request: Request, extra: Mapping[str, str] | None = None, sources: Sequence[Path] = (),
               defines: Sequence[str] = ()) -> tuple[Path, Result]:
    """Generate and compile; returns the program path. Raises OdgenError when it cannot be built.

    `extra`: more generated files (name -> text) written beside the dictionary, its .c files
    compiled in; `sources`: application sources (e.g. odg_app_init/odg_app_tick, built with
    "ODG_APP" among `defines`); `defines`: NAME or NAME=VALUE for every file. The LSS slave is
    built in when the description supports LSS or the options ask for it (result.lss).
    """
    extra = dict(extra or {})
    result = generate(request)
    if not result.files or result.view is None:
        raise OdgenError(f"{request.input}: errors found, no dictionary to build")
    # room for every communication value: the host has it, so reset communication restores all
    defines = [*defines, f"ODG_NODE_COMM_BYTES={comm_bytes(result.od)}u", *(["ODG_NODE_LSS=1"] if result.lss else [])]
    node_main = runtime_dir() / NODE_MAIN
    if not node_main.is_file():
        raise OdgenError(f"the node program source {node_main} is missing")
    cc = compiler()
    runtime = node_sources()
    out = cache_dir() / _digest(result, [*runtime, *sources], cc, extra, defines)
    program = out / "node"
    if program.is_file():
        return program, result
    output_dir(out)
    # Renamed into place: a symlink planted in the cache is replaced, not written through.
    write_files({out / name: text for name, text in
                 {**result.files, **extra, "hook_stubs.c": _stubs(result.view.functions)}.items()})
    name = result.view.name
    cmd = [cc, *CFLAGS, "-O2", *(f"-I{d}" for d in include_dirs(node=True)), f"-I{out}", f"-DODG_DICT={name}",
           f'-DODG_DICT_HEADER="{name}.h"', *(f"-D{d}" for d in defines), str(out / f"{name}.c"),
           str(out / "hook_stubs.c"), *(str(out / n) for n in sorted(extra) if n.endswith(".c")), str(node_main),
           *map(str, [*runtime, *sources]), "-lm", "-o", str(out / "node.tmp")]
    (out / "node.tmp").unlink(missing_ok=True)  # the compiler would write through a planted link
    built = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if built.returncode != 0:
        raise OdgenError(f"building the node program failed:\n{built.stdout}{built.stderr}")
    os.replace(out / "node.tmp", program)
    return program, result
