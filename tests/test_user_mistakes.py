"""What a user gets wrong gets a clear answer: exit 2 and one sentence saying what to do (one test per case)."""

from __future__ import annotations

import errno
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from odgen import fileio
from odgen.cli import main
from odgen.pipeline import Request
from odgen.roundtrip.build import build_node

from .conftest import ROOT

EXAMPLE = ROOT / "examples" / "io-node" / "io-node.eds"
OPTIONS = ROOT / "examples" / "io-node" / "io-node.toml"
sys.path.insert(0, str(ROOT / "benchmarks"))
from synth import synth_eds  # noqa: E402


def _usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    return capsys.readouterr().err


def test_missing_options_file_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    missing = tmp_path / "missing.toml"
    for command in (["generate", str(EXAMPLE), "-o", str(tmp_path)], ["check", str(EXAMPLE)],
                    ["explain", str(EXAMPLE), "0x6000"]):
        err = _usage_error([*command, "--options", str(missing)], capsys)
        assert f"options file {missing} does not exist" in err and "io-node.eds" not in err


@pytest.mark.parametrize("kind", ["existing file", "under a file"])
def test_unwritable_output_folder(kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    blocker = tmp_path / "out"
    blocker.write_text("not a folder")
    out = blocker if kind == "existing file" else blocker / "sub"
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"odgen: cannot write {out}: ") and "internal error" not in err
    assert blocker.read_text() == "not a folder"


@pytest.mark.parametrize("command", ["node", "roundtrip"])
def test_no_socketcan_says_how_to_get_vcan(command: str, monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    def no_can(*args: object) -> socket.socket:
        raise OSError(errno.EAFNOSUPPORT, os.strerror(errno.EAFNOSUPPORT))

    monkeypatch.setattr(socket, "AF_CAN", 29, raising=False)
    monkeypatch.setattr(socket, "socket", no_can)
    assert main([command, str(EXAMPLE)]) == 2
    err = capsys.readouterr().err
    assert "no SocketCAN" in err and "modprobe vcan" in err and "tools/vcan" in err


def test_missing_can_interface_is_named(capsys: pytest.CaptureFixture[str]) -> None:
    if not hasattr(socket, "AF_CAN"):
        pytest.skip("this Python has no AF_CAN (not Linux)")
    assert main(["node", str(EXAMPLE), "--iface", "nosuchcan7"]) == 2
    err = capsys.readouterr().err
    assert "modprobe vcan" in err and ("nosuchcan7" in err or "no SocketCAN" in err)


def test_convert_refuses_to_overwrite_its_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    eds = tmp_path / "dev.eds"
    original = EXAMPLE.read_bytes().replace(b"\n", b"\r\n")  # convert writes LF line ends
    eds.write_bytes(original)
    assert main(["convert", str(eds), str(eds)]) == 2
    assert "is the input file" in capsys.readouterr().err and eds.read_bytes() == original
    assert main(["convert", str(eds), str(tmp_path / "." / "dev.eds")]) == 2
    assert main(["convert", "--force", str(eds), str(eds)]) == 0
    assert eds.read_bytes() == EXAMPLE.read_bytes() and main(["lint", str(eds)]) == 0


@pytest.mark.parametrize("suffix", [".txt", ".ini", ""])
def test_unknown_suffix_needs_input_format(suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / f"device{suffix}"
    path.write_bytes(EXAMPLE.read_bytes())
    assert main(["lint", str(path)]) == 2
    assert "--input-format" in capsys.readouterr().err
    assert main(["generate", str(path), "-o", str(tmp_path / "out")]) == 2
    assert main(["lint", "--input-format", "eds", str(path)]) == 0
    assert main(["generate", "--input-format", "eds", "--name", "dev", str(path), "-o", str(tmp_path / "out")]) == 0


def test_check_keep_replaces_symlinks(tmp_path: Path) -> None:
    keep = tmp_path / "keep"
    keep.mkdir()
    victim = tmp_path / "victim.c"
    victim.write_text("/* not odgen's */\n")
    (keep / "io_node.c").symlink_to(victim)
    assert main(["check", str(EXAMPLE), "--options", str(OPTIONS), "--keep", str(keep)]) == 0
    assert victim.read_text() == "/* not odgen's */\n"
    assert not (keep / "io_node.c").is_symlink() and "odgen" in (keep / "io_node.c").read_text()


def test_node_build_cache_replaces_symlinks(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ODGEN_CACHE", str(tmp_path / "cache"))
    request = Request(EXAMPLE, name="od", options=OPTIONS)
    program, _ = build_node(request)
    victim = tmp_path / "victim.c"
    victim.write_text("/* not odgen's */\n")
    program.unlink()
    (program.parent / "od.c").unlink()
    (program.parent / "od.c").symlink_to(victim)
    again, _ = build_node(request)
    assert again.is_file() and victim.read_text() == "/* not odgen's */\n"
    assert not (program.parent / "od.c").is_symlink()


def test_interrupted_write_leaves_no_temp_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0
    (out / "io_node.h").write_text("/* an older generation */\n")  # as if a run had renamed only the .c
    assert main(["generate", str(EXAMPLE), "-o", str(out), "--check"]) == 1
    assert "io_node.h: changed" in capsys.readouterr().err
    real_replace = os.replace

    def interrupted(src: str, dst: str) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "replace", interrupted)
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 130
    monkeypatch.setattr(os, "replace", real_replace)
    assert sorted(p.name for p in out.iterdir()) == ["io_node.c", "io_node.h", "io_node_config.h"], "temp files removed"
    assert main(["generate", str(EXAMPLE), "-o", str(out)]) == 0  # the next run repairs the pair
    assert main(["generate", str(EXAMPLE), "-o", str(out), "--check"]) == 0


def test_sigterm_during_generate_leaves_no_temp_files(tmp_path: Path) -> None:
    big = tmp_path / "big.eds"
    big.write_text(synth_eds(4000), encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    for delay in (0.3, 1.0, 2.0):  # before, during and near the end of writing
        proc = subprocess.Popen([sys.executable, "-m", "odgen", "generate", str(big), "-o", str(out)],
                                stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=120)
        assert proc.returncode in (0, 130, -signal.SIGTERM), err
        assert not [p.name for p in out.iterdir() if p.name.endswith(fileio.TMP_SUFFIX)]
        assert "Traceback" not in err
