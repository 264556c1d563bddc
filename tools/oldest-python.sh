#!/bin/sh
# Prints the path of an interpreter of the oldest Python pyproject.toml declares (requires-python
# ">=X.Y"), installing it from Debian's packages when the machine has none. `make test` runs the
# wheel smoke test (tests/test_install.py) with it.
set -e
cd "$(dirname "$0")/.."
ver=$(sed -n 's/^requires-python = ">=\([0-9][0-9.]*\)".*/\1/p' pyproject.toml)
[ -n "$ver" ] || { echo "oldest-python: no requires-python in pyproject.toml" >&2; exit 1; }
works() { [ -x "$1" ] && "$1" -c "import sys, venv, ensurepip; assert sys.version_info[:2] == tuple(map(int, '$ver'.split('.')))" 2>/dev/null; }
for cand in "$(command -v "python$ver" 2>/dev/null || true)" /usr/bin/python$ver /usr/local/bin/python$ver \
            "${PYENV_ROOT:-$HOME/.pyenv}"/versions/$ver*/bin/python$ver; do
    if works "$cand"; then echo "$cand"; exit 0; fi
done
if command -v apt-get >/dev/null 2>&1; then
    apt-get update -qq >&2
    if apt-get install -y -qq "python$ver" "python$ver-venv" >&2; then
        works "/usr/bin/python$ver" && { echo "/usr/bin/python$ver"; exit 0; }
    fi
fi
echo "oldest-python: Python $ver is not installed and the package sources offer no python$ver" >&2
exit 1
