#!/usr/bin/env bash
# Smoke test of a built wheel, as a user meets it: a fresh venv outside the checkout, the wheel
# alone, then the commands of the README. Used by `make release` and the release workflow.
#   tools/release-smoke.sh DIST_DIR VENV_DIR      (PYTHON: the interpreter, default python3)
# ODGEN_SMOKE_INSTALLED=1 takes VENV_DIR as it is, with that wheel installed already (the tests
# install it once for all their checks).
set -euo pipefail
dist=$(cd "$1" && pwd)
venv=$(realpath -m "$2")
here=$(cd "$(dirname "$0")/.." && pwd)
wheels=("$dist"/odgen-*.whl)
[ ${#wheels[@]} -eq 1 ] && [ -f "${wheels[0]}" ] || { echo "release-smoke: want one odgen wheel in $dist" >&2; exit 2; }
version=$(basename "${wheels[0]}" | cut -d- -f2)

if [ "${ODGEN_SMOKE_INSTALLED:-}" != 1 ]; then
  rm -rf "$venv"
  "${PYTHON:-python3}" -m venv "$venv"
  "$venv/bin/python" -m pip install -q "${wheels[0]}"
fi
odgen=$(cd "$venv/bin" && pwd)/odgen
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$here/examples/io-node/io-node.eds" "$here/examples/io-node/io-node.toml" "$work"
cd "$work"

[ "$("$odgen" --version)" = "odgen $version" ] || { echo "release-smoke: --version is not $version" >&2; exit 1; }
"$venv/bin/python" - <<'PY'
import importlib.metadata as m
meta, files = m.metadata("odgen"), [f.name for f in m.files("odgen") or []]
assert meta["License-Expression"] == "Apache-2.0" and "LICENSE" in files, "release-smoke: no licence"
assert "## Install" in (meta.get_payload() or ""), "release-smoke: no README in the metadata"
PY
"$odgen" lint io-node.eds
"$odgen" generate io-node.eds --options io-node.toml -o gen
"$odgen" check io-node.eds --options io-node.toml
"$odgen" profile ds401 --di 8 --do 8 -o io.eds --generate ds401
for page in index install compatibility generate persistence rules; do
  [ -f "$("$odgen" --docs-dir)/$page.md" ] || { echo "release-smoke: docs/$page.md is not in the wheel" >&2; exit 1; }
done
[ -f "$("$odgen" --runtime-dir)/odg.h" ] && [ -f "$("$odgen" --cmake-dir)/odgen.cmake" ]
echo "release-smoke: odgen $version from ${wheels[0]##*/} works in a fresh venv"
