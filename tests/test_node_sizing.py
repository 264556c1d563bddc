"""The dictionary sizes the node: NAME_config.h carries every ODG_NODE_* limit (docs/generate.md,
"The node's limits"), an options file may lower them, and what a lowered limit leaves out is
refused at generation (GEN010), never dropped at run time.

test_node.py runs tests/node/test_node_wide.c (8 TPDOs, 8 RPDOs, 32 mapping entries) built with
nothing but ODG_CONFIG; here: the limits themselves, the refusals, and that the bytes the
generator computes for the communication values are the bytes the runtime counts.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from odgen import toolchain
from odgen.pipeline import Request, generate

from .conftest import FIXTURES, ROOT
from .cprog import build, run

NODE_TESTS = ROOT / "tests" / "node"
RUNTIME = ROOT / "runtime"
WIDE = NODE_TESTS / "wide-node.eds"


def limits(config: str) -> dict[str, int]:
    return {m: int(v) for m, v in re.findall(r"#define (ODG_NODE_\w+) (\d+)u?\b", config)}


def config_of(eds: Path, options: str | None, tmp_path: Path) -> tuple[dict[str, int], list[str]]:
    path = None
    if options is not None:
        path = tmp_path / "node.toml"
        path.write_text(options)
    result = generate(Request(eds, name="od", options=path))
    return limits(result.files.get("od_config.h", "")), [d.text() for d in result.diags.sorted()]


def test_the_dictionary_decides_every_limit(tmp_path: Path) -> None:
    got, _ = config_of(WIDE, None, tmp_path)
    assert got == {"ODG_NODE_MAX_RPDO": 8, "ODG_NODE_MAX_TPDO": 8, "ODG_NODE_MAX_MAP": 32, "ODG_NODE_MAX_HB": 1,
                   "ODG_NODE_COMM_BYTES": got["ODG_NODE_COMM_BYTES"], "ODG_NODE_MAX_ERRORS": 8,
                   "ODG_NODE_EMCY_QUEUE": 4, "ODG_NODE_LSS": 0, "ODG_NODE_SDO_BLOCK": 1}
    lss, _ = config_of(NODE_TESTS / "lss-node.eds", None, tmp_path)
    assert lss["ODG_NODE_LSS"] == 1 and lss["ODG_NODE_MAX_HB"] >= 1


def test_options_lower_limits_the_description_does_not_need(tmp_path: Path) -> None:
    got, diags = config_of(WIDE, "[node]\nerrors = 2\nemcy_queue = 1\ncomm_bytes = 0\ntpdo = 8\nrpdo = 100\n",
                           tmp_path)
    assert not diags
    assert (got["ODG_NODE_MAX_ERRORS"], got["ODG_NODE_EMCY_QUEUE"], got["ODG_NODE_COMM_BYTES"]) == (2, 1, 0)
    assert (got["ODG_NODE_MAX_TPDO"], got["ODG_NODE_MAX_RPDO"]) == (8, 8)  # more than the description: no use


@pytest.mark.parametrize(("options", "block"), [
    (None, 1), ("[node]\nsdo_block = true\n", 1), ("[node]\nsdo_block = false\n", 0),
    ("[node]\nsdo_block = false\nlss = true\nerrors = 2\n", 0),
])
def test_sdo_block_switch_reaches_the_config(options: str | None, block: int, tmp_path: Path) -> None:
    got, diags = config_of(WIDE, options, tmp_path)
    assert not diags
    assert got["ODG_NODE_SDO_BLOCK"] == block
    assert got["ODG_NODE_MAX_RPDO"] == 8  # nothing else changes


@pytest.mark.parametrize("value", ["0", '"no"', "[]"])
def test_sdo_block_takes_true_or_false(value: str, tmp_path: Path) -> None:
    got, diags = config_of(WIDE, f"[node]\nsdo_block = {value}\n", tmp_path)
    assert got == {}, "refused: nothing generated"
    assert any("GEN001" in d and "sdo_block = true or false" in d for d in diags), diags


def test_what_a_lowered_limit_leaves_out_is_refused(tmp_path: Path) -> None:
    got, diags = config_of(WIDE, "[node]\nrpdo = 7\nmapping = 31\n", tmp_path)
    assert got == {}, "refused: nothing generated"
    assert [d.split("error[GEN010]: ")[1][:11] for d in diags] == ["0x1407 RPDO", "0x1600sub32", "0x1A00sub32"]
    assert all(":" in d.split(" ")[0] for d in diags), "file:line"
    consumers, diags = config_of(NODE_TESTS / "pdo-node.eds", "[node]\nheartbeat_consumers = 1\n", tmp_path)
    assert consumers == {} and "0x1016sub2" in diags[0] and "[node] heartbeat_consumers = 1" in diags[0]


def test_bad_node_keys_are_gen001_at_their_line(tmp_path: Path) -> None:
    _, diags = config_of(WIDE, "[node]\nlss = false\ntpdos = 4\nmapping = 65\nerrors = true\n", tmp_path)
    assert [d.split(": ", 1)[0].rsplit("/", 1)[1] for d in diags] == ["node.toml:3", "node.toml:4", "node.toml:5"]
    assert all("error[GEN001]" in d for d in diags)
    assert "use lss, sdo_block or rpdo, tpdo" in diags[0] and "0..64" in diags[1] and "1..255" in diags[2]


def test_the_cli_refuses_and_writes_nothing(tmp_path: Path) -> None:
    (tmp_path / "cap.toml").write_text("[node]\ntpdo = 4\n")
    done = subprocess.run([sys.executable, "-m", "odgen", "generate", str(WIDE), "-o", str(tmp_path / "out"),
                           "--options", str(tmp_path / "cap.toml")], capture_output=True, text=True, check=False)
    assert done.returncode != 0 and "GEN010" in done.stderr + done.stdout
    assert not (tmp_path / "out").exists()


def test_communication_bytes_are_what_the_runtime_counts(tmp_path: Path) -> None:
    """ODG_NODE_COMM_BYTES == odg_node_comm_bytes(&dict) for dictionaries with strings, packed
    arrays, persistence groups and LSS: reset communication restores every communication value."""
    main = tmp_path / "main.c"
    main.write_text('#include "odg_node.h"\n#include "od.h"\n#include "check.h"\n'
                    "int main(void)\n{\n    CHECK_EQ(odg_init(&od, 5), 0);\n"
                    "    CHECK_EQ(odg_node_comm_bytes(&od), ODG_NODE_COMM_BYTES);\n"
                    "    CHECK(ODG_NODE_COMM_BYTES > 0u);\n    return done();\n}\n")
    hooks = tmp_path / "hooks.c"
    for eds, options in ((FIXTURES / "generate" / "alltypes.eds", FIXTURES / "generate" / "alltypes.toml"),
                         (NODE_TESTS / "lss-node.eds", NODE_TESTS / "lss-node.toml")):
        out = tmp_path / eds.stem
        result = generate(Request(eds, name="od", options=options))
        out.mkdir()
        for name, text in result.files.items():
            (out / name).write_text(text)
        assert result.view is not None
        hooks.write_text('#include "od.h"\n' + "".join(
            f"odg_abort_t {fn}(const odg_ref_t *r, odg_hook_kind_t k, const void *d, uint32_t n, void *c)\n"
            "{\n    (void)r; (void)k; (void)d; (void)n; (void)c;\n    return ODG_OK;\n}\n"
            for fn in result.view.functions))
        exe = out / "comm"
        build("gcc", ("-O1", '-DODG_CONFIG="od_config.h"'),
              (main, hooks, out / "od.c", *toolchain.core_sources(), *toolchain.service_sources()),
              (out, RUNTIME, ROOT / "tests" / "runtime"), exe)
        run(exe, tmp_path)


def test_a_build_without_the_configuration_says_what_it_leaves_out(tmp_path: Path) -> None:
    """odg_node_unserved: 0 built with wide_node_config.h; built with odg_node.h's defaults (4 + 4
    PDOs, 8 mapping entries), TPDOs and RPDOs 5-8 and the two 32-entry mappings are left out."""
    result = generate(Request(WIDE, name="wide_node"))
    for name, text in result.files.items():
        (tmp_path / name).write_text(text)
    main = tmp_path / "main.c"
    main.write_text('#include "odg_node.h"\n#include "wide_node.h"\n#include "check.h"\n'
                    "int main(void)\n{\n    CHECK_EQ(odg_node_unserved(&wide_node), EXPECTED);\n"
                    "    return done();\n}\n")
    for flags, expected in ((('-DODG_CONFIG="wide_node_config.h"',), 0), ((), 4 + 4 + 2)):
        exe = tmp_path / f"unserved{expected}"
        build("gcc", ("-O1", *flags, f"-DEXPECTED={expected}u"),
              (main, tmp_path / "wide_node.c", *toolchain.core_sources(), *toolchain.service_sources()),
              (tmp_path, RUNTIME, ROOT / "tests" / "runtime"), exe)
        run(exe, tmp_path)
