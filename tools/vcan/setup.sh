#!/usr/bin/env bash
# Fetch what tools/vcan/run.py needs to boot a User-Mode Linux guest with SocketCAN:
# linux.uml, its CAN/vcan/overlay modules and a static busybox, from Debian's packages
# `user-mode-linux` and `busybox-static` (downloaded with apt-get, not installed).
#
# Idempotent: when the cache is complete it only checks it and exits. Cache directory:
# $ODGEN_VCAN_CACHE, default build/vcan/ under the repo. Progress goes to stderr; the
# last line on stdout is the cache directory.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
cache="${ODGEN_VCAN_CACHE:-$repo/build/vcan}"

# Modules to keep (path under the package's modules/<version>/kernel/), in load order.
modules=(
    fs/overlayfs/overlay.ko
    net/can/can.ko
    net/can/can-raw.ko
    net/can/can-bcm.ko
    net/can/can-gw.ko
    drivers/net/can/dev/can-dev.ko
    drivers/net/can/vcan.ko
    drivers/net/can/vxcan.ko
)

say() { echo "vcan-setup: $*" >&2; }
die() { say "error: $*"; exit 1; }

complete() {
    [ -f "$cache/.complete" ] && [ -x "$cache/linux.uml" ] && [ -x "$cache/busybox" ] || return 1
    local m
    for m in "${modules[@]}"; do
        [ -f "$cache/modules/$(basename "$m")" ] || return 1
    done
}

if complete; then
    echo "$cache"
    exit 0
fi

case "$cache" in
    *[[:space:],]*) die "cache path '$cache' must not contain whitespace or commas (it goes on the guest's kernel command line)";;
esac
for tool in apt-get dpkg-deb tar; do
    command -v "$tool" >/dev/null 2>&1 || die "'$tool' not found: this needs a Debian/Ubuntu host (or set ODGEN_VCAN_CACHE to a prepared cache)"
done

mkdir -p "$cache"
# Parallel runs (pytest -n, two make targets) share the cache: one fills it, the others wait.
exec 9>"$cache/.lock"
if command -v flock >/dev/null 2>&1; then
    flock -w 600 9 || die "timed out waiting for $cache/.lock"
fi
if complete; then
    echo "$cache"
    exit 0
fi

SECONDS=0
stage="$(mktemp -d "$cache/.stage.XXXXXX")"
trap 'rm -rf "$stage"' EXIT

sudo_if_needed() {
    if [ "$(id -u)" = 0 ]; then "$@";
    elif command -v sudo >/dev/null 2>&1; then sudo -n "$@";
    else return 1; fi
}

download() {
    # -o APT::Sandbox::User=root: the _apt user may not be able to write into $stage.
    (cd "$stage" && apt-get download -q -o APT::Sandbox::User=root user-mode-linux busybox-static) >&2
}

say "downloading user-mode-linux and busybox-static into $cache"
if ! download; then
    say "apt-get download failed; running apt-get update and trying again"
    sudo_if_needed apt-get update -qq >&2 || die "apt-get update failed"
    download || die "apt-get download user-mode-linux busybox-static failed"
fi

uml_deb=$(ls "$stage"/user-mode-linux_*.deb)
bb_deb=$(ls "$stage"/busybox-static_*.deb)

patterns=(./usr/bin/linux.uml)
for m in "${modules[@]}"; do patterns+=("./usr/lib/uml/modules/*/kernel/$m"); done
mkdir -p "$stage/x"
dpkg-deb --fsys-tarfile "$uml_deb" | tar -x -C "$stage/x" --wildcards "${patterns[@]}"
dpkg-deb --fsys-tarfile "$bb_deb" | tar -x -C "$stage/x" ./bin/busybox

kver=$(ls "$stage/x/usr/lib/uml/modules")
[ "$(echo "$kver" | wc -l)" = 1 ] || die "expected one module directory in the package, found: $kver"

rm -rf "$cache/modules"
mkdir -p "$cache/modules"
for m in "${modules[@]}"; do
    cp "$stage/x/usr/lib/uml/modules/$kver/kernel/$m" "$cache/modules/"
done
install -m 755 "$stage/x/bin/busybox" "$cache/busybox"
install -m 755 "$stage/x/usr/bin/linux.uml" "$cache/linux.uml"
"$cache/busybox" true || die "the downloaded busybox does not run on this host"

{
    echo "kernel=$kver"
    echo "user-mode-linux=$(dpkg-deb -f "$uml_deb" Version)"
    echo "busybox-static=$(dpkg-deb -f "$bb_deb" Version)"
    # Load order for run.py (dependencies first).
    printf 'modules='
    for m in "${modules[@]}"; do printf '%s ' "$(basename "$m" .ko)"; done
    echo
} >"$cache/.complete"

rm -rf "$stage"
say "ready in ${SECONDS} s: $(du -sh "$cache" | cut -f1) in $cache (kernel $kver)"
echo "$cache"
