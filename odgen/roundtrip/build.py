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
    built in when the description supports LSS or the options ask for it (NAME_config.h says so).
    """
    extra = dict(extra or {})
    result = generate(request)
    if not result.files or result.view is None:
        raise OdgenError(f"{request.input}: errors found, no dictionary to build")
    # NAME_config.h sizes the node (PDOs, mapping, communication values, LSS: docs/generate.md)
    defines = [*defines, f'ODG_CONFIG="{result.view.name}_config.h"']
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
