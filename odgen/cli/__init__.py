"""Command line: one module per command, each with `add_parser` (its arguments) and `run`.

Exit codes: 0 clean, 1 findings (errors, or warnings under --strict),
2 usage error or unreadable input. Only odgen's own bugs raise past main(),
and then as one line unless --debug asks for the traceback.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import importlib
import os
import signal
import sys
from collections.abc import Sequence
from types import ModuleType
from typing import NoReturn

from .. import __version__
from ..errors import OdgenError

# The commands in the order `odgen --help` lists them; each is the module odgen.cli.<name>.
# A run imports only its command's module, and that module imports what it uses when it runs:
# `odgen lint` of an EDS and `odgen --version` start without jinja2, lxml or canopen.
COMMANDS = ("lint", "fix", "convert", "generate", "explain", "check", "node", "roundtrip", "profile", "network", "diff",
            "report", "conformance", "rules", "rule")


def _command(name: str) -> ModuleType:
    return importlib.import_module(f"{__name__}.{name}")


class _PrintAndExit(argparse.Action):
    """--cmake-dir, --runtime-dir, --toolchain cmake: what a firmware build asks the installed odgen."""

    def __init__(self, option_strings: list[str], dest: str, what: str, nargs: int | None = 0, **kw: object) -> None:
        self.what = what
        super().__init__(option_strings, dest, nargs=nargs, **kw)  # type: ignore[arg-type]

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: object,
                 option_string: str | None = None) -> None:
        from .. import assets, toolchain

        texts = {"cmake-dir": lambda: f"{assets.cmake_dir()}\n", "runtime-dir": lambda: f"{assets.runtime_dir()}\n",
                 "docs-dir": lambda: f"{assets.docs_dir()}\n",
                 "toolchain": lambda: toolchain.SCRIPTS[str(values[0])]()}  # type: ignore[index]
        sys.stdout.write(texts[self.what]())
        parser.exit(0)


class _Parser(argparse.ArgumentParser):
    """argparse, with a suggestion for a mistyped option or command (`--stats`: did you mean --statistics?)."""

    def error(self, message: str) -> NoReturn:
        self.print_usage(sys.stderr)
        self.exit(2, f"{self.prog}: error: {message}{self._suggestion(message)}\n")

    def _suggestion(self, message: str) -> str:
        import difflib
        import re

        unknown = re.match(r"unrecognized arguments: (.*)", message)
        choice = re.match(r"argument command: invalid choice: '([^']*)'", message)
        if unknown:
            words = [w.split("=", 1)[0] for w in unknown.group(1).split() if w.startswith("-")]
            known = _option_strings(self)
        elif choice:
            words, known = [choice.group(1)], list(COMMANDS)
        else:
            return ""
        hints = [close[0] for w in words for close in [difflib.get_close_matches(w, known, n=1, cutoff=0.6)] if close]
        return f" (did you mean {', '.join(hints)}?)" if hints else ""


def _option_strings(parser: argparse.ArgumentParser) -> list[str]:
    """Every option of the parser and of its commands' parsers."""
    found: list[str] = []
    for action in parser._actions:
        found += [o for o in action.option_strings if o.startswith("--")]
        if isinstance(action, argparse._SubParsersAction):
            for sub in dict.fromkeys(action.choices.values()):
                found += _option_strings(sub)
    return found


def _add_location_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--cmake-dir", action=_PrintAndExit, what="cmake-dir",
                        help="print the folder of odgen.cmake (include it from a CMake project)")
    parser.add_argument("--runtime-dir", action=_PrintAndExit, what="runtime-dir",
                        help="print the folder of the C runtime's sources and headers")
    parser.add_argument("--docs-dir", action=_PrintAndExit, what="docs-dir",
                        help="print the folder of odgen's documentation (the docs/*.md pages odgen's messages name)")
    parser.add_argument("--toolchain", action=_PrintAndExit, what="toolchain", nargs=1, choices=["cmake", "make"],
                        help="print the runtime's sources and C flags as CMake (or make) variables")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The `odgen` parser; with `command` (one of COMMANDS) that command's arguments only: the
    parsers of all thirteen commands take ~7 ms to build, one about half of that."""
    parser = _Parser(prog="odgen", description="CANopen EDS/DCF/XDD linter and C generator")
    parser.add_argument("--version", action="version", version=f"odgen {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks of internal errors")
    _add_location_options(parser)
    commands = parser.add_subparsers(dest="command", required=True)
    for name in COMMANDS:
        if command in (None, name):
            _command(name).add_parser(commands)
    return parser


def _terminate(signum: int, frame: object) -> None:
    """SIGTERM ends odgen as Ctrl-C does, so half-written temporary files are removed on the way out."""
    raise KeyboardInterrupt


# Commands that only read and write files: once their output is flushed, the interpreter's teardown
# (a last collection, then freeing every object of a large model) is time the user waits for and
# nothing needs; these end with os._exit.
QUICK_EXIT = frozenset({"lint", "convert", "generate", "explain", "rules", "rule", "diff"})


def run() -> None:
    """The `odgen` command."""
    args = _arguments(None)
    quick = args.command in QUICK_EXIT
    if quick:  # no cyclic collection at all: the process ends without one anyway (gcpause.py)
        gc.disable()
    try:
        code = _dispatch(args)
    except KeyboardInterrupt:  # SIGTERM just as _dispatch put the previous handler back
        code = 130
    if quick and sys.getprofile() is None and sys.gettrace() is None:  # profilers write at exit
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):  # a closed pipe: nothing more reaches the reader
                stream.flush()
        os._exit(code)
    raise SystemExit(code)


def main(argv: Sequence[str] | None = None) -> int:
    return _dispatch(_arguments(argv))


def _arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    words = list(sys.argv[1:] if argv is None else argv)
    # The command is the first word that is not an option (the options before it take no value but
    # --toolchain's, which ends the run); anything else gets the whole parser, to list the commands.
    command = next((w for w in words if not w.startswith("-")), None)
    args = build_parser(command if command in COMMANDS else None).parse_args(words)
    args.argv = words  # for the command `generate --check` suggests
    return args


def _dispatch(args: argparse.Namespace) -> int:
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return int(_command(args.command).run(args))
    except OdgenError as err:
        print(f"odgen: {err}", file=sys.stderr)
        return err.exit_code
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # the reader went away (`odgen explain ... | head`): nothing more to say
        _quiet_stdout()
        return 141  # 128 + SIGPIPE, what a shell reports for a writer a pipe ended
    except Exception as err:  # odgen's own bug: one line, traceback on request
        if args.debug:
            raise
        print(f"odgen: internal error: {type(err).__name__}: {err} (run with --debug for the traceback)",
              file=sys.stderr)
        return 3
    finally:
        signal.signal(signal.SIGTERM, previous)


def _quiet_stdout() -> None:
    """Point stdout at /dev/null so that the flush at exit does not fail on the closed pipe again."""
    with contextlib.suppress(OSError):
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
