#!/usr/bin/env python3
"""Run a command with working SocketCAN vcan interfaces; relay its output and exit status.

    tools/vcan/run.py [--iface vcan0 ...] [--timeout S] [--mode auto|host|uml] -- CMD ARGS...

When the host can have vcan (the interfaces already exist, or `ip link add ... type vcan`
works), CMD runs on the host. Otherwise one User-Mode Linux guest is booted (no root, no
KVM; see tools/vcan/README.md): the host's / read-only through hostfs under a tmpfs
overlay, the repo (and --rw dirs) mounted read-write, the CAN modules loaded and the
interfaces created; CMD runs there in the same cwd with the same environment, its
stdout/stderr stream back through files in a shared run directory, and its exit status
comes back through a file too.

Exit status: CMD's own; 124 when --timeout expired; 125 when the harness itself failed
(messages prefixed `vcan-run:` on stderr). Standard library only.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
SETUP = HERE / "setup.sh"

EXIT_TIMEOUT = 124
EXIT_HARNESS = 125
ARPHRD_CAN = "280"
DEFAULT_TIMEOUT = 300.0
# Load order when the cache's .complete does not say (dependencies first).
DEFAULT_MODULES = ["overlay", "can", "can-raw", "can-bcm", "can-gw", "can-dev", "vcan", "vxcan"]
# Not carried into the guest: shell bookkeeping that means nothing there.
ENV_DROP = {"PWD", "OLDPWD", "SHLVL", "_"}

VERBOSE = False


def _env_flag(name: str) -> bool:
    return os.environ.get(name, "").lower() in ("1", "true", "yes", "on")

T0 = time.monotonic()


class HarnessError(Exception):
    """The harness (not the command) failed; exit 125."""


def log(msg: str) -> None:
    print(f"vcan-run: {msg}", file=sys.stderr, flush=True)


def vlog(msg: str) -> None:
    if VERBOSE:
        log(f"[{time.monotonic() - T0:6.2f}s] {msg}")


# --------------------------------------------------------------------------- host mode


def _ip(*args: str) -> bool:
    if not shutil.which("ip"):
        return False
    r = subprocess.run(["ip", *args], stdin=subprocess.DEVNULL, capture_output=True, text=True)
    if r.returncode != 0:
        vlog(f"ip {' '.join(args)}: {r.stderr.strip()}")
    return r.returncode == 0


def _iface_state(name: str) -> str:
    """'missing', 'not-can', 'down' or 'up'."""
    d = Path("/sys/class/net", name)
    if not d.exists():
        return "missing"
    try:
        if (d / "type").read_text().strip() != ARPHRD_CAN:
            return "not-can"
        up = int((d / "flags").read_text().strip(), 16) & 0x1
    except (OSError, ValueError):
        return "not-can"
    return "up" if up else "down"


def host_can_ready(ifaces: list[str]) -> bool:
    """True when every interface exists and is up on the host (creating them if we can)."""
    try:
        socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    except (OSError, AttributeError) as e:
        vlog(f"host has no AF_CAN sockets ({e})")
        return False
    for name in ifaces:
        state = _iface_state(name)
        if state == "missing":
            _ip("link", "add", "dev", name, "type", "vcan")
            state = _iface_state(name)
        if state == "down":
            _ip("link", "set", "up", name)
            state = _iface_state(name)
        if state != "up":
            vlog(f"host interface {name}: {state}")
            return False
    return True


def run_on_host(cmd: list[str], ifaces: list[str], timeout: float) -> int:
    env = dict(os.environ, ODGEN_VCAN="host", ODGEN_VCAN_IFACES=",".join(ifaces))
    proc = subprocess.Popen(cmd, env=env, start_new_session=True)
    try:
        rc = proc.wait(timeout=timeout)
        return 128 - rc if rc < 0 else rc  # killed by a signal: report it as a shell would
    except subprocess.TimeoutExpired:
        log(f"timeout: '{shlex.join(cmd)}' still running after {timeout:g} s; killed")
        _killpg(proc.pid)
        proc.wait()
        return EXIT_TIMEOUT
    finally:
        if proc.poll() is None:
            _killpg(proc.pid)
            proc.wait()


# --------------------------------------------------------------------------- UML mode


def cache_dir() -> Path:
    return Path(os.environ.get("ODGEN_VCAN_CACHE") or REPO / "build" / "vcan").resolve()


def ensure_cache() -> tuple[Path, list[str]]:
    cache = cache_dir()
    if not (cache / ".complete").is_file():
        log(f"no guest kernel in {cache} yet: running {SETUP.relative_to(REPO)}")
        # stdout of setup.sh goes to our stderr: our stdout belongs to the command.
        r = subprocess.run(["bash", str(SETUP)], stdin=subprocess.DEVNULL, stdout=sys.stderr)
        if r.returncode != 0:
            raise HarnessError(f"{SETUP.relative_to(REPO)} failed (exit {r.returncode})")
    modules = DEFAULT_MODULES
    for line in (cache / ".complete").read_text().splitlines():
        if line.startswith("modules="):
            modules = line.split("=", 1)[1].split()
    for f in [cache / "linux.uml", cache / "busybox", *(cache / "modules" / f"{m}.ko" for m in modules)]:
        if not f.is_file():
            raise HarnessError(f"{f} is missing: remove {cache} and run {SETUP}")
    return cache, modules


def _plain_path(p: str | Path, what: str) -> str:
    """Paths go on the kernel command line, a #! line and into `mount -o`: keep them plain."""
    s = str(p)
    if any(c.isspace() for c in s) or "," in s or "'" in s:
        raise HarnessError(f"{what} '{s}' contains whitespace, a comma or a quote; the guest cannot use it")
    return s


def _mount_flags(path: str) -> set[str]:
    """Options of the mount that holds `path` (from /proc/mounts)."""
    best, flags = "", set()
    try:
        for line in Path("/proc/mounts").read_text().splitlines():
            parts = line.split()
            if len(parts) >= 4:
                mnt = parts[1].replace("\\040", " ")
                if (path == mnt or path.startswith(mnt.rstrip("/") + "/")) and len(mnt) >= len(best):
                    best, flags = mnt, set(parts[3].split(","))
    except OSError:
        pass
    return flags


def guest_env(ifaces: list[str], cwd: str) -> list[str]:
    env = {k: v for k, v in os.environ.items() if k not in ENV_DROP and "\0" not in v}
    env.update(PWD=cwd, ODGEN_VCAN="uml", ODGEN_VCAN_IFACES=",".join(ifaces))
    env.setdefault("PATH", "/usr/local/bin:/usr/bin:/bin:/usr/local/sbin:/usr/sbin:/sbin")
    env.setdefault("HOME", os.path.expanduser("~"))
    return [f"{k}={v}" for k, v in env.items()]


INIT = r"""#!{bb} sh
# PID 1 of the guest (generated by tools/vcan/run.py). Host / is the read-only root.
B={bb}
R={run}
T={stamp}
N=$R/root
PATH=/usr/sbin:/usr/bin:/sbin:/bin
export PATH
off() {{ $B sync; $B poweroff -f; while :; do $B sleep 1; done; }}
fail() {{ echo "$*" > $R/error; off; }}
$B mount -t proc proc /proc
# The run directory read-write: status, output and log files land on the host.
$B mount -t hostfs -o $R none $R || off
exec > $R/guest.log 2>&1
$T +'guest up %s.%N'
for m in {modules}; do
    $B insmod {moddir}/$m.ko || fail "insmod $m.ko failed"
done
for i in {ifaces}; do
    $B ip link add dev $i type vcan || fail "ip link add dev $i type vcan failed"
    $B ip link set up $i || fail "ip link set up $i failed"
done
$B ip link set up lo
# A writable view of the host's /: tmpfs overlay on the read-only hostfs root.
$B mount -t tmpfs -o mode=755 tmpfs $R/t || fail "tmpfs mount failed"
$B mkdir -p $R/t/upper $R/t/work
$B mount -t overlay -o lowerdir=/,upperdir=$R/t/upper,workdir=$R/t/work overlay $N || fail "overlay mount failed"
$B mount -t proc proc $N/proc
$B mount -t sysfs sysfs $N/sys
$B mount -t devtmpfs devtmpfs $N/dev
$B mkdir -p $N/dev/pts $N/dev/shm
$B mount -t devpts -o newinstance,ptmxmode=0666 devpts $N/dev/pts
$B mount -t tmpfs -o mode=1777 tmpfs $N/dev/shm
for d in {rw}; do
    $B mount -t hostfs -o $d none $N$d || fail "cannot mount $d read-write"
done
$T +'command start %s.%N'
$B chroot $N /bin/sh $R/job.sh < /dev/null > $R/stdout 2> $R/stderr &
wait $!
echo $? > $R/status.tmp
$T +'command end %s.%N'
$B mv $R/status.tmp $R/status
# Leftovers (daemons the command started) would keep files open: end them.
kill -9 -1
off
"""

# Runs under the host's own /bin/sh and env inside the chroot (the host's userland).
JOB = r"""cd {cwd} || exit 125
exec /usr/bin/env -i {env} {cmd}
"""


class Tail(threading.Thread):
    """Copy what the guest appends to `src` to `dst` while the guest runs."""

    def __init__(self, src: Path, dst, done: threading.Event):
        super().__init__(daemon=True)
        self.src, self.dst, self.done = src, dst, done

    def run(self) -> None:
        with open(self.src, "rb") as f:
            while True:
                finished = self.done.is_set()
                chunk = f.read(65536)
                if chunk:
                    try:
                        self.dst.write(chunk)
                        self.dst.flush()
                    except (OSError, ValueError):
                        pass  # the reader went away (closed pipe): keep draining
                    continue
                if finished:
                    return
                self.done.wait(0.05)


def _killpg(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pid, signal.SIGKILL)


def run_in_uml(cmd: list[str], ifaces: list[str], timeout: float, rw: list[str], mem: str, keep: bool) -> int:
    cache, modules = ensure_cache()
    bb = _plain_path(cache / "busybox", "cache path")
    cwd = os.getcwd()
    rw_dirs = sorted({_plain_path(Path(d).resolve(), "read-write directory") for d in [str(REPO), *rw]}, key=len)
    for d in rw_dirs:
        if d == "/" or not os.path.isdir(d):
            raise HarnessError(f"read-write directory '{d}' is not a directory below /")
    tmp_base = tempfile.gettempdir()
    # The guest reaches the run directory through hostfs before anything else is mounted,
    # but its own /dev (devtmpfs), /proc and /sys hide the host's.
    if any(c.isspace() or c in ",'" for c in tmp_base) or tmp_base.startswith(("/dev/", "/proc/", "/sys/")):
        tmp_base = "/tmp"
    run = Path(tempfile.mkdtemp(prefix="odgen-vcan-", dir=tmp_base))
    vlog(f"run dir {run}")
    try:
        _plain_path(run, "run directory")
        for d in ("t", "root"):
            (run / d).mkdir()
        for f in ("stdout", "stderr", "guest.log"):
            (run / f).touch()
        init = run / "init"
        init.write_text(
            INIT.format(
                bb=bb,
                run=run,
                modules=" ".join(modules),
                moddir=cache / "modules",
                ifaces=" ".join(ifaces),
                rw=" ".join(rw_dirs),
                # Timestamps for --verbose (GNU date has %N, busybox's has not); else a no-op.
                stamp="/usr/bin/date" if VERBOSE and os.path.exists("/usr/bin/date") else ":",
            )
        )
        init.chmod(0o755)
        (run / "job.sh").write_text(
            JOB.format(
                cwd=shlex.quote(cwd),
                env=" ".join(shlex.quote(e) for e in guest_env(ifaces, cwd)),
                cmd=shlex.join(cmd),
            )
        )

        console = open(run / "console.log", "wb")  # noqa: SIM115 - closed in finally
        # UML maps its guest RAM from an (unlinked) file in $TMPDIR/$TMP/$TEMP, else /dev/shm;
        # that must allow PROT_EXEC and is best in RAM: prefer /dev/shm over the caller's TMPDIR.
        uml_env = {k: v for k, v in os.environ.items() if k not in ("TMPDIR", "TMP", "TEMP")}
        shm_ok = os.access("/dev/shm", os.W_OK) and "noexec" not in _mount_flags("/dev/shm")
        uml_env["TMPDIR"] = "/dev/shm" if shm_ok else str(run)
        argv = [
            str(cache / "linux.uml"),
            f"mem={mem}",
            "quiet",
            # Boot in ~0.2 s instead of ~1.3 s: skip the RAID6 benchmark (nothing here uses
            # md/btrfs RAID) and the 256 legacy BSD ptys (devpts serves ptys).
            "initcall_blacklist=raid6_select_algo",
            "pty.legacy_count=0",
            "con=null",
            "ssl=null",
            f"con0=null,fd:{console.fileno()}",
            "root=/dev/root",
            "rootfstype=hostfs",
            "rootflags=/",
            "ro",
            f"init={init}",
            f"uml_dir={run}",
            "umid=uml",
        ]
        vlog("booting: " + " ".join(argv))
        launched = time.time()
        proc = subprocess.Popen(
            argv,
            stdin=subprocess.DEVNULL,
            stdout=console,
            stderr=console,
            pass_fds=(console.fileno(),),
            env=uml_env,
            start_new_session=True,
        )
        done = threading.Event()
        tails = [
            Tail(run / "stdout", sys.stdout.buffer, done),
            Tail(run / "stderr", sys.stderr.buffer, done),
        ]
        for t in tails:
            t.start()
        timed_out = False
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
        finally:
            # Whatever UML left (its helper processes share its process group).
            _killpg(proc.pid)
            proc.wait()
            console.close()
            done.set()
            for t in tails:
                t.join()
        vlog(f"guest exited ({proc.returncode})")
        if VERBOSE:
            _report_timings(run, launched)

        status_file = run / "status"
        if timed_out:
            log(f"timeout: '{shlex.join(cmd)}' in the guest still running after {timeout:g} s; guest killed")
            return EXIT_TIMEOUT
        if status_file.is_file():
            try:
                return int(status_file.read_text().strip())
            except ValueError:
                pass
        error = (run / "error").read_text().strip() if (run / "error").is_file() else ""
        raise HarnessError(
            f"the guest stopped without an exit status (linux.uml exit {proc.returncode})"
            + (f": {error}" if error else "")
            + "\n--- guest log ---\n"
            + _tail_text(run / "guest.log")
            + "\n--- guest console ---\n"
            + _tail_text(run / "console.log")
        )
    finally:
        if keep:
            log(f"kept {run}")
        else:
            shutil.rmtree(run, ignore_errors=True)


def _tail_text(path: Path, lines: int = 30) -> str:
    try:
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    except OSError:
        return "(none)"


def _report_timings(run: Path, launched: float) -> None:
    """Guest and host share the clock (UML reads the host's time)."""
    stamps = {}
    try:
        for line in (run / "guest.log").read_text().splitlines():
            key, _, value = line.rpartition(" ")
            if key in ("guest up", "command start", "command end"):
                stamps[key] = float(value)
    except (OSError, ValueError):
        return
    if "guest up" in stamps and "command start" in stamps:
        log(
            f"launch to init {stamps['guest up'] - launched:.2f} s, "
            f"to command start {stamps['command start'] - launched:.2f} s"
        )
    if "command start" in stamps and "command end" in stamps:
        log(f"command ran {stamps['command end'] - stamps['command start']:.2f} s in the guest")


# --------------------------------------------------------------------------- main


def _on_signal(signum, _frame):
    raise KeyboardInterrupt(signum)


def main(argv: list[str] | None = None) -> int:
    global VERBOSE
    p = argparse.ArgumentParser(
        prog="tools/vcan/run.py",
        description="Run CMD with SocketCAN vcan interfaces (host vcan, else a User-Mode Linux guest).",
        epilog="Exit status: CMD's; 124 on timeout; 125 when the harness failed.",
    )
    p.add_argument(
        "--iface", action="append", metavar="NAME", help="vcan interface to provide (repeatable; default vcan0)"
    )
    p.add_argument(
        "--mode",
        choices=("auto", "host", "uml"),
        default=os.environ.get("ODGEN_VCAN_MODE", "auto"),
        help="host: use the host's vcan; uml: always boot the guest; auto (default): host when it can",
    )
    p.add_argument(
        "--timeout",
        type=float,
        default=float(os.environ.get("ODGEN_VCAN_TIMEOUT", DEFAULT_TIMEOUT)),
        help=f"seconds before CMD (and the guest) is killed, exit 124 (default {DEFAULT_TIMEOUT:g})",
    )
    p.add_argument(
        "--rw",
        action="append",
        default=[],
        metavar="DIR",
        help="extra host directory writable from the guest (the repo always is; other writes are discarded)",
    )
    p.add_argument("--mem", default=os.environ.get("ODGEN_VCAN_MEM", "1024M"), help="guest memory (default 1024M)")
    p.add_argument("--keep", action="store_true", default=_env_flag("ODGEN_VCAN_KEEP"),
                   help="keep the guest's run directory (logs) for debugging")
    p.add_argument("-v", "--verbose", action="store_true", default=_env_flag("ODGEN_VCAN_VERBOSE"),
                   help="say what happens, with timings, on stderr")
    p.add_argument("cmd", nargs=argparse.REMAINDER, help="-- CMD ARGS...")
    args = p.parse_args(argv)
    VERBOSE = args.verbose
    cmd = args.cmd[1:] if args.cmd[:1] == ["--"] else args.cmd
    if not cmd:
        p.error("no command given (tools/vcan/run.py [options] -- CMD ARGS...)")
    ifaces = args.iface or ["vcan0"]
    for name in ifaces:
        if not name or len(name) > 15 or not all(c.isalnum() or c in "-_." for c in name):
            p.error(f"bad interface name {name!r}")
    rw = list(args.rw) + [d for d in os.environ.get("ODGEN_VCAN_RW", "").split(":") if d]

    signal.signal(signal.SIGTERM, _on_signal)
    try:
        if args.mode != "uml" and host_can_ready(ifaces):
            vlog(f"using the host's {', '.join(ifaces)}")
            return run_on_host(cmd, ifaces, args.timeout)
        if args.mode == "host":
            raise HarnessError(f"the host cannot provide {', '.join(ifaces)} (--mode host)")
        return run_in_uml(cmd, ifaces, args.timeout, rw, args.mem, args.keep)
    except HarnessError as e:
        log(f"error: {e}")
        return EXIT_HARNESS
    except KeyboardInterrupt as e:
        log("interrupted")
        return 128 + (e.args[0] if e.args and isinstance(e.args[0], int) else signal.SIGINT)


if __name__ == "__main__":
    sys.exit(main())
