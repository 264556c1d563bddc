"""The model-based persistence test: random firmware sequences through the C runtime, checked
against the rule set of docs/persistence.md ("The rule set") and odgen/place/migration.py.

A *layout set* is a few firmware versions of one device (v0..vK-1), each derived from the one
before by random changes (add, remove, widen, narrow, retype, move between groups, change limits,
resize strings and arrays, grow and shrink a region; one set in three pins regions to powers of
two, [[group]] region). They are generated and compiled once into
one host program (tests/runtime/model_main.c) over an in-memory NOR model of NV. A *sequence* is a
blank NV of one version's NAME_NV_SIZE (sometimes less; or a driver that shows each version
its own NAME_NV_SIZE of the same memory), then random steps: boot a version
(upgrades and rollbacks), write values, save (0x1010), load (0x1011), reboot, and power cuts
during a save, a load or a boot. The test keeps what was stored last for each group (under which
layout, in which region), and after every boot checks:

  R1  each entry serves the newest value stored for it (as migrate() carries it to this layout)
      or its default, never an older store;
  R2  when nothing in NV moved or was overwritten by another group's region, exactly what
      migrate() says: values, status (LOADED / MIGRATED / DEFAULTS) and counts;
  R3  a value stored and not served is reported (the storage EMCY's bits in boot_seen), unless
      the group's region was blank (a first boot); nothing lost, nothing reported;
  R4  save and load succeed on an NV of at least NAME_NV_SIZE; on a smaller NV every group
      boots NV_ERROR and save aborts 0x08000020;
  R5  a boot right after a successful save by the same version loads every group unchanged.

`run(seed, sets, sequences)` returns the violations found (each with its seed and step), so
the test in `make test` and the budget in `make fuzz` share everything.
"""

from __future__ import annotations

import random
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from odgen.pipeline import Request, generate, prepare
from odgen.place.layout import group_layouts
from odgen.place.migration import GroupLayout, migrate

from .test_migration_runtime import HEADER, from_image, to_image

ROOT = Path(__file__).resolve().parents[1]
RUNTIME = ROOT / "runtime"
CTESTS = ROOT / "tests" / "runtime"
LOADED, DEFAULTS, SIGNATURE, NV_ERROR, DAMAGED, MIGRATED = 0, 1, 2, 3, 4, 5
LOST_BITS = 1 << SIGNATURE | 1 << NV_ERROR | 1 << DAMAGED | 0x80
DATA_STORE = 0x08000020
GROUPS = ("app", "aux", "comm")
U8, U16, U32, I16, I32, VS = 0x05, 0x06, 0x07, 0x03, 0x04, 0x09
NUMBERS = {U8: (0, 0xFF), U16: (0, 0xFFFF), U32: (0, 0xFFFFFFFF), I16: (-0x8000, 0x7FFF),
           I32: (-0x80000000, 0x7FFFFFFF)}
WIDER = {U8: (U16, U32, I16, I32), U16: (U32, I32), I16: (I32,)}
NARROWER = {U32: (U16, U8), U16: (U8,), I32: (I16,)}
RETYPED = {U16: (I16,), I16: (U16,), U32: (I32,), I32: (U32,), U8: (VS,), VS: (U16,)}
POOL = tuple(range(0x2000, 0x2010))
BULK = 0x2200  # a large ARRAY of UNSIGNED32: grows and shrinks a region
PINNED = 1 << 40  # a set seed with this bit pins regions ([[group]] region) in its versions
SWITCH_CUTS = 1 << 41  # ... and with this one its sequences cut the power in a new version's first boot


@dataclass(frozen=True)
class Param:
    index: int
    dtype: int
    group: str
    default: int | str = 0
    high: int | None = None  # HighLimit (numbers)
    capacity: int = 0  # VISIBLE_STRING
    elements: int = 0  # an ARRAY of that many elements instead of a VAR


@dataclass
class Version:
    params: dict[int, Param]
    heartbeat: int = 1000
    options: str = ""  # more options-file text ([persist], [[group]] regions)
    pins: dict[str, int] = field(default_factory=dict)  # [[group]] regions pinned, by group name


# -- firmware versions -------------------------------------------------------------------------


def _new_param(rng: random.Random, index: int) -> Param:
    group = rng.choice(GROUPS)
    if index == BULK:  # mostly in the last group of the NV map, which can grow past the NV's end
        return Param(index, U32, rng.choice((*GROUPS, "aux", "aux")), 1, elements=rng.randrange(4, 20))
    dtype = rng.choice((U8, U16, U32, I16, I32, VS, U16))
    if dtype == VS:
        return Param(index, VS, group, "ab", capacity=rng.randrange(2, 12))
    low, high = NUMBERS[dtype]
    limit = rng.choice((None, None, rng.randrange(max(low, 0) + 10, min(high, 5000))))
    default = rng.randrange(max(low, -100), min(high, 100) if limit is None else min(limit, 100))
    if rng.random() < 0.2:
        return Param(index, dtype, group, default, limit, elements=rng.randrange(1, 6))
    return Param(index, dtype, group, default, limit)


def _mutate(rng: random.Random, v: Version) -> Version:
    params = dict(v.params)
    for _ in range(rng.randrange(1, 4)):
        kind = rng.choice(("add", "add", "remove", "widen", "narrow", "retype", "move", "move", "limits",
                           "capacity", "elements", "bulk", "bulk", "heartbeat"))
        have = sorted(params)
        p = params[rng.choice(have)] if have else None
        if kind == "add" or p is None:
            free = [i for i in POOL if i not in params]
            if free:
                index = rng.choice(free)
                params[index] = _new_param(rng, index)
        elif kind == "remove" and len(params) > 1:
            del params[p.index]
        elif kind in ("widen", "narrow", "retype") and p.index != BULK:
            table = {"widen": WIDER, "narrow": NARROWER, "retype": RETYPED}[kind]
            if p.dtype in table:
                dtype = rng.choice(table[p.dtype])
                params[p.index] = _retyped(p, dtype)
        elif kind == "move":
            params[p.index] = replace(p, group=rng.choice([g for g in GROUPS if g != p.group]))
        elif kind == "limits" and p.dtype in NUMBERS and p.index != BULK:
            top = min(3000, NUMBERS[p.dtype][1])
            high = rng.choice((None, rng.randrange(min(max(10, int(p.default) + 1), top), top + 1)))
            params[p.index] = replace(p, high=high)
        elif kind == "capacity" and p.dtype == VS:
            params[p.index] = replace(p, capacity=rng.randrange(2, 16))
        elif kind == "elements" and p.elements:
            params[p.index] = replace(p, elements=max(1, p.elements + rng.choice((-3, -1, 1, 2, 4))))
        elif kind == "bulk":
            if BULK in params:
                b = params[BULK]
                grown = rng.choice((b.elements + 6, b.elements * 2, max(1, b.elements // 3)))
                params[BULK] = replace(b, elements=grown)
            else:
                params[BULK] = _new_param(rng, BULK)
        elif kind == "heartbeat":
            return Version(params, rng.choice((500, 1000, 2000)))
    return Version(params, v.heartbeat)


def _retyped(p: Param, dtype: int) -> Param:
    if dtype == VS:
        return Param(p.index, VS, p.group, "ab", capacity=8, elements=p.elements)
    low, high = NUMBERS[dtype]
    default = p.default if isinstance(p.default, int) and low <= p.default <= min(high, p.high or high) else 1
    limit = p.high if p.high is not None and p.high <= high and default <= p.high else None
    return Param(p.index, dtype, p.group, default, limit, elements=p.elements)


def versions(rng: random.Random, count: int) -> list[Version]:
    first = Version({i: _new_param(rng, i) for i in rng.sample(POOL, rng.randrange(2, 6))})
    out = [first]
    while len(out) < count:
        out.append(_mutate(rng, rng.choice(out)))
    return out


def version(*params: Param, options: str = "", pins: dict[str, int] | None = None, heartbeat: int = 1000) -> Version:
    """A version of one's own (the sequence tests): its parameters, options text and pinned regions."""
    return Version({p.index: p for p in params}, heartbeat, options, dict(pins or {}))


def saves(index: int, values: list[str]) -> list[str]:
    """Commands that write each value (hex) to `index` sub 0 and save it (0x1010), in turn."""
    return [c for v in values for c in (f"set {index:04X} 00 {v}", "save")]


def pin(rng: random.Random, vs: list[Version]) -> None:
    """Pin the regions of some groups of some versions to powers of two ([[group]] region): a
    pinned region keeps its size whatever the layout, and changes only when the next version pins
    another size (or none), so slots sit where no default region puts them (build() doubles a pin
    the group has outgrown)."""
    for v in vs:
        if rng.random() < 0.7:
            present = sorted({p.group for p in v.params.values()} | {"comm"})
            chosen = rng.sample(present, rng.randrange(1, len(present) + 1))
            v.pins = {g: rng.choice((64, 128, 256, 512, 1024, 64, 128, 0x20000)) for g in chosen}


def eds(v: Version) -> str:
    params = sorted(v.params.values(), key=lambda p: p.index)
    lines = [HEADER.format(heartbeat=v.heartbeat), "[ManufacturerObjects]", f"SupportedObjects={len(params)}"]
    lines += [f"{n}=0x{p.index:04X}" for n, p in enumerate(params, start=1)]
    for p in params:
        if p.elements:
            lines += ["", f"[{p.index:04X}]", f"ParameterName=Array {p.index:04X}", "ObjectType=0x8",
                      f"SubNumber={p.elements + 1}", "", f"[{p.index:04X}sub0]",
                      "ParameterName=Highest sub-index supported", "ObjectType=0x7", "DataType=0x0005",
                      "AccessType=ro", f"DefaultValue={p.elements}"]
            for k in range(1, p.elements + 1):
                lines += ["", f"[{p.index:04X}sub{k:X}]", f"ParameterName=Element {k}", *_var(p)]
        else:
            lines += ["", f"[{p.index:04X}]", f"ParameterName=Parameter {p.index:04X}", *_var(p)]
    return "\n".join(lines) + "\n"


def _var(p: Param) -> list[str]:
    lines = ["ObjectType=0x7", f"DataType=0x{p.dtype:04X}", "AccessType=rw", f"DefaultValue={p.default}",
             "PDOMapping=0"]
    return lines + ([f"HighLimit={p.high}"] if p.high is not None else [])


def options(v: Version) -> str:
    text = v.options + "".join(f'[[group]]\nname = "{g}"\nregion = {r}\n\n' for g, r in sorted(v.pins.items()))
    text += '[[entry]]\nmatch = "0x1017"\nstorage = "persist:comm"\n'
    for p in sorted(v.params.values(), key=lambda p: p.index):
        text += f'\n[[entry]]\nmatch = "0x{p.index:04X}"\nstorage = "persist:{p.group}"\n'
        if p.capacity:
            text += f"capacity = {p.capacity}\n"
    return text


@dataclass
class Firmware:
    version: Version
    layouts: dict[str, GroupLayout]  # every group name of GROUPS, empty when the version has none
    regions: dict[str, tuple[int, int]]  # group -> (offset, size)
    nv_size: int = 0
    defaults: dict[tuple[int, int], str] = field(default_factory=dict)  # served on a blank NV


def build(vs: list[Version], work: Path) -> tuple[Path, list[Firmware]]:
    """Generate v0..vK-1 and compile them with the runtime into one program."""
    firmwares, includes, table, sizes = [], [], [], []
    for k, v in enumerate(vs):
        name = f"v{k}"
        (work / f"{name}.eds").write_text(eds(v), encoding="utf-8")
        (work / f"{name}.toml").write_text(options(v), encoding="utf-8")
        request = Request(work / f"{name}.eds", name=name, options=work / f"{name}.toml")
        result = generate(request)
        while not result.files and min(v.pins.values(), default=1 << 16) < 1 << 16:  # a group outgrew its pin
            v.pins = {g: 2 * r if r < 1 << 16 else r for g, r in v.pins.items()}
            (work / f"{name}.toml").write_text(options(v), encoding="utf-8")
            result = generate(request)
        assert result.files, [d.text() for d in result.refused]
        for fname, text in result.files.items():
            (work / fname).write_text(text, encoding="utf-8")
        prepared = prepare(request)
        assert prepared.od is not None and prepared.placements is not None
        layouts = group_layouts(prepared.od, prepared.placements)
        assert result.view is not None
        regions = {g.name: (g.offset, g.region) for g in result.view.persist.groups.values()}
        firmwares.append(Firmware(v, {g: layouts.get(g, GroupLayout(g)) for g in GROUPS}, regions))
        includes.append(f'#include "{name}.h"')
        table.append(f"&{name}")
        sizes.append(f"{name.upper()}_NV_SIZE")
    (work / "versions.h").write_text("\n".join(includes) + f"\n#define N_VERSIONS {len(vs)}u\n"
                                     f"static const odg_dict_t *const VERSIONS[] = {{{', '.join(table)}}};\n"
                                     f"static const uint32_t NV_SIZES[] = {{{', '.join(sizes)}}};\n",
                                     encoding="utf-8")
    exe = work / "model_main"
    sources = [CTESTS / "model_main.c", CTESTS / "nv_fault.c", *(RUNTIME / f for f in runtime_sources()),
               *(work / f"v{k}.c" for k in range(len(vs)))]
    cmd = [shutil.which("gcc") or "gcc", "-std=c99", "-O1", "-w", f"-I{work}", f"-I{RUNTIME}", f"-I{CTESTS}",
           *map(str, sources), "-o", str(exe)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr[-4000:]
    return exe, firmwares


def runtime_sources() -> list[str]:
    """The runtime's core and persistence sources (the persistence files as runtime/ has them)."""
    return ["odg.c", "odg_verify.c", *sorted(p.name for p in RUNTIME.glob("odg_persist*.c"))]


# -- sequences ---------------------------------------------------------------------------------


@dataclass
class Image:
    """What the newest committed image of a group holds, as the model knows it."""

    layout: GroupLayout
    values: dict[tuple[int, int], bytes]
    region: tuple[int, int]  # (offset, size) of the region it was written in


@dataclass
class Nv:
    size: int
    images: dict[str, list[Image | None]] = field(default_factory=dict)  # candidates, None: nothing
    written: dict[str, set[tuple[int, int]]] = field(default_factory=dict)  # regions each group used
    # the images written at each place (a group's region) since it was last erased
    placed: dict[tuple[str, int], list[Image]] = field(default_factory=dict)
    # images a firmware left behind: written at a place its NV map does not cover at all (past its
    # NAME_NV_SIZE), which nothing erases; docs/persistence.md says they may come back
    stale: dict[str, list[Image]] = field(default_factory=dict)
    # a firmware booted that could not see all of an image (past the NV its driver shows, or
    # past its NAME_NV_SIZE): what a later firmware finds there is not known exactly
    partial: bool = False


def script(rng: random.Random, fws: list[Firmware], switch_cuts: bool = False) -> list[tuple[str, ...]]:
    """One sequence: a blank NV, then steps (each a tuple: the command and what the model needs).
    Some sequences go back and forth between two versions (upgrade, rollback, upgrade ...). With
    `switch_cuts`, the first boot of a version after another may be cut by a power failure (the
    boot that migrates, stores home and scrubs)."""
    pair = rng.sample(range(len(fws)), 2) if rng.random() < 0.4 else None
    start = pair[0] if pair else rng.randrange(len(fws))
    size = rng.choice([fws[k].nv_size for k in (pair or range(len(fws)))])
    if rng.random() < 0.05:
        size = max(0, size - rng.choice((1, 8, 64)))
    window = pair is not None and rng.random() < 0.5  # the driver shows each firmware NAME_NV_SIZE bytes
    steps: list[tuple[str, ...]] = [(f"nv {fws[start].nv_size if window else size}",), (f"boot {start}",)]
    cur = start
    for _ in range(rng.randrange(4, 14)):
        r = rng.random()
        if r < 0.25:
            cur = (pair[1] if cur == pair[0] else pair[0]) if pair else rng.randrange(len(fws))
            steps += [(f"window {fws[cur].nv_size}",)] if window else []
            if switch_cuts and rng.random() < 0.5:
                steps += [(f"cut {rng.randrange(0, 600)}",), (f"boot {cur}", "cut"), ("power",)]
            steps.append((f"boot {cur}",))
        elif r < 0.6:
            for _ in range(rng.randrange(1, 4)):
                steps.append(_set(rng, fws[cur]))
            steps.append(("save",))
            if rng.random() < 0.3:
                steps.append((f"boot {cur}", "after-save"))
        elif r < 0.68:
            steps.append(("load",))
        elif r < 0.8:
            steps += [(f"cut {rng.randrange(0, 400)}",), (rng.choice(("save", "load", f"boot {cur}")), "cut"),
                      ("power",), (f"boot {cur}",)]
        else:
            steps.append((f"boot {cur}",))
    return steps


def load_script(rng: random.Random, fws: list[Firmware]) -> list[tuple[str, ...]]:
    """A sequence around the load mark (docs/persistence.md section 2): two versions in turn
    (regions that grow and shrink; in two sequences of five a driver that shows each version its
    own NAME_NV_SIZE), loads followed by a boot of the same version or of the other one, power
    cuts during a load, a save and the boot after a load. A power cut during a boot is of the
    version booted last: the model knows what such a boot leaves, not what the first boot of
    another version reported before its power failed."""
    pair = rng.sample(range(len(fws)), 2)
    cur = pair[0]
    window = rng.random() < 0.4
    size = max(fws[k].nv_size for k in pair)
    steps: list[tuple[str, ...]] = [(f"nv {fws[cur].nv_size if window else size}",), (f"boot {cur}",)]

    def switch() -> None:
        nonlocal cur
        cur = pair[1] if cur == pair[0] else pair[0]
        steps.extend([(f"window {fws[cur].nv_size}",)] if window else [])
        steps.append((f"boot {cur}",))

    def cut_boot() -> None:
        steps.extend([(f"cut {rng.randrange(0, 600)}",), (f"boot {cur}", "cut"), ("power",), (f"boot {cur}",)])

    for _ in range(rng.randrange(5, 16)):
        r = rng.random()
        if r < 0.2:
            switch()
        elif r < 0.4:
            steps.extend(_set(rng, fws[cur]) for _ in range(rng.randrange(1, 3)))
            steps.append(("save",))
        elif r < 0.65:
            steps.append(("load",))
            if rng.random() < 0.5:
                switch()
            if rng.random() < 0.5:
                cut_boot()
        elif r < 0.85:
            steps.extend([(f"cut {rng.randrange(0, 400)}",), (rng.choice(("save", "load", "load")), "cut"),
                          ("power",), (f"boot {cur}",)])
        else:
            cut_boot()
    return steps


def _set(rng: random.Random, fw: Firmware) -> tuple[str, ...]:
    entries = [(g, e) for g, layout in fw.layouts.items() for e in layout.entries
               if not (e.sub == 0 and any(x.index == e.index and x.sub for x in layout.entries))]
    _, e = rng.choice(entries)
    if e.data_type == VS:
        text = "".join(rng.choice("xyz") for _ in range(rng.randrange(0, e.length + 1)))
        return (f"set {e.index:04X} {e.sub:02X} {text.encode().hex()}", "set", f"{e.index}:{e.sub}")
    low, high = NUMBERS[e.data_type]
    high = min(high, int(e.high)) if e.high is not None else high
    value = rng.choice((low, high, rng.randrange(low, high + 1), 0, 1))
    raw = value.to_bytes(e.length, "little", signed=value < 0)
    return (f"set {e.index:04X} {e.sub:02X} {raw.hex()}", "set", f"{e.index}:{e.sub}")


# -- running and checking ----------------------------------------------------------------------


@dataclass
class Boot:
    blank: list[int]
    rc: int
    groups: list[dict[str, int]]
    seen: list[int]
    values: dict[tuple[int, int], str]


def _parse_boot(lines: list[str], at: int) -> tuple[Boot, int]:
    boot = Boot([], 0, [], [], {})
    while lines[at] != "end":
        w = lines[at].split()
        if w[0] == "blank":
            boot.blank.append(int(w[2]))
        elif w[0] == "rc":
            boot.rc = int(w[1], 16)
        elif w[0] == "group":
            boot.groups.append({w[k]: int(w[k + 1]) for k in range(2, len(w), 2)})
        elif w[0] == "seen":
            boot.seen = [int(x) for x in w[1:]]
        elif w[0] == "value":
            boot.values[(int(w[1], 16), int(w[2], 16))] = w[3] if len(w) > 3 else ""
        at += 1
    return boot, at + 1


def execute(exe: Path, commands: list[str]) -> list[str]:
    done = subprocess.run([str(exe)], input="\n".join(commands) + "\n", capture_output=True, text=True,
                          check=False, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    return done.stdout.splitlines()


@dataclass
class Violation:
    seed: int
    sequence: int
    step: int
    rule: str
    text: str

    def __str__(self) -> str:
        return f"set seed {self.seed} sequence {self.sequence} step {self.step}: {self.rule}: {self.text}"


class Checker:
    """The model of one sequence: follows its steps and the program's answers."""

    def __init__(self, fws: list[Firmware], seed: int, sequence: int) -> None:
        self.fws, self.seed, self.sequence = fws, seed, sequence
        self.nv = Nv(0)
        self.cur: Firmware | None = None
        self.served: dict[str, dict[tuple[int, int], bytes]] = {}
        self.violations: list[Violation] = []
        self.step = 0
        self.dirty = False  # a cut left the current boot's RAM unknown until the next boot
        # a boot was cut: the loss it found may have been replaced in NV (the migrated image, the
        # defaults) before it could report it, and the next boot finds nothing to report (a
        # known gap, docs/persistence.md section 4)
        self.cut_boot_before = False

    def bad(self, rule: str, text: str) -> None:
        self.violations.append(Violation(self.seed, self.sequence, self.step, rule, text))

    def working(self) -> bool:
        return self.cur is not None and self.nv.size >= self.cur.nv_size

    def feed(self, step: tuple[str, ...], lines: list[str], at: int) -> int:
        cmd = step[0]
        word = cmd.split()[0]
        if word == "boot":
            boot, at = _parse_boot(lines, at)
            if len(step) > 1 and step[1] == "cut":
                self.cut_boot(int(cmd.split()[1]))
            else:
                self.boot(self.fws[int(cmd.split()[1])], boot, after_save=len(step) > 1)
            return at
        answer = lines[at].split()
        at += 1
        if word == "nv":
            self.nv = Nv(int(cmd.split()[1]))
        elif word == "window":
            self.nv.size = int(cmd.split()[1])
        elif word == "set":
            self.set(step, int(answer[1], 16))
        elif word in ("save", "load"):
            self.command(word, int(answer[1], 16), cut=len(step) > 1)
        return at

    # the steps

    def set(self, step: tuple[str, ...], abort: int) -> None:
        if abort != 0:
            self.bad("model", f"{step[0]}: abort 0x{abort:08X} for a value inside the limits")
            return
        assert self.cur is not None
        index, sub = (int(x) for x in step[2].split(":"))
        for group, layout in self.cur.layouts.items():
            for e in layout.entries:
                if e.key == (index, sub):
                    self.served[group][e.key] = to_image(e, step[0].split()[3] if len(step[0].split()) > 3 else "")

    def command(self, word: str, abort: int, cut: bool) -> None:
        fw = self.cur
        assert fw is not None
        groups = [g for g in GROUPS if fw.layouts[g].entries]
        if cut and self.working():
            for g in groups:
                old = self.nv.images.get(g, [None])
                image = self._image(fw, g) if word == "save" else self._mark(fw, g)
                self.nv.images[g] = old + [image]
                self.nv.written.setdefault(g, set()).add(fw.regions[g])
                # it may be in NV, at the region's place, for a later rollback to come back to
                self.nv.placed.setdefault((g, fw.regions[g][0]), []).append(image)
            self.dirty = True
            return
        if cut:
            return
        if not self.working():
            if word == "save" and abort != DATA_STORE:
                self.bad("R4", f"save on an NV of {self.nv.size} bytes, below NAME_NV_SIZE {fw.nv_size}: "
                         f"abort 0x{abort:08X}, not 0x{DATA_STORE:08X}")
            return
        if abort != 0:
            self.bad("R4", f"{word} on working NV aborts 0x{abort:08X}")
            return
        for g in groups:
            self._commit(fw, g, self._image(fw, g) if word == "save" else self._mark(fw, g))

    @staticmethod
    def _lost(fw: Firmware, g: str, image: Image | None, got: dict[tuple[int, int], str],
              want: dict[tuple[int, int], tuple[str, str]]) -> bool:
        """A value of `image` stored and not served: served otherwise than migrate() says, or
        migrate() itself defaults or drops one."""
        if image is None:
            return False
        return any(got[k] != want[k][0] for k in got) or migrate(image.layout, fw.layouts[g], image.values).counts.lost

    def _commit(self, fw: Firmware, g: str, image: Image) -> None:
        """The image the runtime has written (or kept) as group g's newest, in its region."""
        self.nv.images[g] = [image]
        self.nv.written.setdefault(g, set()).add(fw.regions[g])
        self.nv.placed.setdefault((g, fw.regions[g][0]), []).append(image)

    def _left_behind(self, fw: Firmware) -> None:
        """Images at places the booting firmware's map does not cover: nothing erases them.
        Places inside another region are erased by that region's group at this boot. And images
        past the NV the driver shows this firmware: it cannot see them, so what it stores starts
        over, and a later firmware that sees both may take the hidden one (docs/persistence.md)."""
        for g, images in self.nv.images.items():
            for image in images:
                # past the NV the driver shows, or past NAME_NV_SIZE (where boot looks only at
                # the place slot A's header names)
                if image is not None and image.region[0] + image.region[1] > min(self.nv.size, fw.nv_size):
                    self.nv.partial = True  # what this firmware writes cannot reach all of it
                    # it may serve any image written at its own region's place (slot A), older too
                    earlier = self.nv.placed.get((g, fw.regions[g][0]), []) if fw.layouts[g].entries else []
                    for i in (image, *earlier):
                        if i not in self.nv.stale.get(g, []):
                            self.nv.stale.setdefault(g, []).append(i)
        for (g, offset), images in list(self.nv.placed.items()):
            if fw.layouts[g].entries and fw.regions[g][0] == offset:
                continue
            del self.nv.placed[(g, offset)]
            for image in images:
                if image.region[0] + image.region[1] > fw.nv_size:  # the regions tile 0 .. NAME_NV_SIZE
                    self.nv.stale.setdefault(g, []).append(image)

    def _image(self, fw: Firmware, g: str) -> Image:
        return Image(fw.layouts[g], dict(self.served[g]), fw.regions[g])

    @staticmethod
    def _mark(fw: Firmware, g: str) -> Image:
        """A load's mark (docs/persistence.md section 2): stored as a save is, its boot serves
        the defaults (DEFAULTS): an image of no entries, every entry new."""
        return Image(GroupLayout(g), {}, fw.regions[g])

    def cut_boot(self, k: int) -> None:
        self.cut_boot_before = True
        fw = self.fws[k]
        for g in GROUPS:
            if fw.layouts[g].entries and self.nv.size >= fw.nv_size:
                cands = self.nv.images.get(g, [None])
                self.nv.images[g] = cands + [self._migrated(fw, g, c) for c in cands]
                self.nv.written.setdefault(g, set()).add(fw.regions[g])
        self.dirty = True

    def _migrated(self, fw: Firmware, g: str, image: Image | None) -> Image | None:
        if image is None:
            return None
        m = migrate(image.layout, fw.layouts[g], image.values)
        values = {e.key: m.values[e.key] if m.values[e.key] is not None else to_image(e, fw.defaults[e.key])
                  for e in fw.layouts[g].entries}
        return Image(fw.layouts[g], values, fw.regions[g])

    def stable(self, fw: Firmware) -> bool:
        """Nothing in NV moved, no region of the running firmware holds another group's bytes, and
        every group's newest image lies inside the NV the driver shows."""
        if self.nv.partial:
            return False
        if any(i is not None and i.region[0] + i.region[1] > min(self.nv.size, fw.nv_size)
               for images in self.nv.images.values() for i in images):
            return False
        for g, regions in self.nv.written.items():
            mine = fw.regions.get(g)
            for offset, size in regions:
                if fw.layouts[g].entries and mine is not None and offset != mine[0]:
                    return False
                for other, (o2, s2) in fw.regions.items():
                    if other != g and fw.layouts[other].entries and offset < o2 + s2 and o2 < offset + size:
                        return False
        return True

    def boot(self, fw: Firmware, boot: Boot, after_save: bool) -> None:
        self.cur = fw
        groups = [g for g in GROUPS if fw.layouts[g].entries]
        self.served = {g: {} for g in GROUPS}
        if self.nv.size < fw.nv_size:
            if any(b["status"] != NV_ERROR for b in boot.groups):
                self.bad("R4", f"boot on an NV of {self.nv.size} bytes, below NAME_NV_SIZE {fw.nv_size}: "
                         f"statuses {[b['status'] for b in boot.groups]}, not NV_ERROR")
            for g in groups:
                self.served[g] = {e.key: to_image(e, boot.values.get(e.key, "")) for e in fw.layouts[g].entries}
            return
        stable = self.stable(fw) and not self.dirty
        self._left_behind(fw)
        lost = possible = False
        for n, g in enumerate(groups):
            layout, b = fw.layouts[g], boot.groups[n]
            got = {e.key: boot.values.get(e.key, "") for e in layout.entries}
            self.served[g] = {e.key: to_image(e, got[e.key]) for e in layout.entries}
            # images left behind at this region's place: the runtime may take one it can read
            # (inside its NV, or named by slot A's header)
            here = [i for i in self.nv.stale.get(g, []) if i.region[0] == fw.regions[g][0]]
            self.nv.stale[g] = [i for i in self.nv.stale.get(g, []) if i not in here]
            # those inside the NV stay where they are (the scrub keeps a group's own images at
            # its places), so a later rollback that cannot see the newest may still take one
            placed = self.nv.placed.setdefault((g, fw.regions[g][0]), [])
            inside = min(self.nv.size, fw.nv_size)
            placed[:0] = [i for i in here if i not in placed and i.region[0] + i.region[1] <= inside]
            cands = [*here, *self.nv.images.get(g, [None])]
            options = [(c, self._expect(fw, g, c)) for c in cands]
            match = [(c, want) for c, want in options if all(got[k] in (want[k][0], fw.defaults[k]) for k in got)]
            if not match:
                c, want = options[-1]
                wrong = [f"0x{k[0]:04X}sub{k[1]} {got[k]!r} (newest {want[k][0]!r}, default {fw.defaults[k]!r})"
                         for k in got if got[k] not in (want[k][0], fw.defaults[k])]
                self.bad("R1", f"v{self.fws.index(fw)} group {g}: an older store or another value served: "
                         + "; ".join(wrong[:3]))
                self.nv.images[g] = [self._as_served(fw, g)]
                continue
            exact = [(c, want) for c, want in match if all(got[k] == want[k][0] for k in got)]
            newest = self.nv.images.get(g, [None])
            self.nv.stale[g] += [i for i in here if i.region[0] + i.region[1] > min(self.nv.size, fw.nv_size)]
            first_boot = boot.blank[n] and b["status"] == DEFAULTS  # a blank region: nothing to report
            # what each image the served values fit says was lost: an image left behind (see
            # _left_behind) is one the runtime may take without knowing of the newer one
            flags = [self._lost(fw, g, c, got, want) and not first_boot and (c not in here or c in newest)
                     for c, want in (exact or match)]
            lost = lost or all(flags)
            possible = possible or any(flags)
            behind = [(c, want) for c, want in exact if c in here and c not in newest]
            c, want = (behind or exact or match)[-1]
            if stable and len(cands) == 1:
                self._exact(fw, g, c, b, got, want, after_save)
            if b["status"] != NV_ERROR:
                self._commit(fw, g, self._as_served(fw, g))
        self.dirty = False
        emcy = bool(boot.seen[0] & LOST_BITS)
        cut_before, self.cut_boot_before = self.cut_boot_before, False
        if lost and not emcy and not cut_before:
            self.bad("R3", f"v{self.fws.index(fw)}: values stored and not served, and no loss reported "
                     f"(statuses {[b['status'] for b in boot.groups]}, seen 0x{boot.seen[0]:02X})")
        if stable and not possible and emcy:
            self.bad("R3", f"v{self.fws.index(fw)}: a loss reported where nothing was lost "
                     f"(groups {boot.groups}, seen 0x{boot.seen[0]:02X})")

    def _expect(self, fw: Firmware, g: str, image: Image | None) -> dict[tuple[int, int], tuple[str, str]]:
        """Per entry: (the value migrate() serves from the image, as odg_read gives it; its action)."""
        layout = fw.layouts[g]
        if image is None:
            return {e.key: (fw.defaults[e.key], "none") for e in layout.entries}
        m = migrate(image.layout, layout, image.values)
        old = image.layout.by_key()
        out = {}
        for e in layout.entries:
            value = m.values[e.key]
            out[e.key] = (fw.defaults[e.key] if value is None else from_image(e, value),
                          "new" if e.key not in old else "stored")
        return out

    def _exact(self, fw: Firmware, g: str, image: Image | None, b: dict[str, int],
               got: dict[tuple[int, int], str], want: dict[tuple[int, int], tuple[str, str]],
               after_save: bool) -> None:
        tag = f"v{self.fws.index(fw)} group {g}"
        wrong = [k for k in got if got[k] != want[k][0]]
        if wrong:
            k = wrong[0]
            self.bad("R2", f"{tag}: 0x{k[0]:04X}sub{k[1]} serves {got[k]!r}, migrate() {want[k][0]!r}")
        if image is None or not image.layout.entries:  # nothing stored, or a load's mark
            if b["status"] != DEFAULTS:
                self.bad("R2", f"{tag}: nothing stored, status {b['status']} (not DEFAULTS)")
            return
        m = migrate(image.layout, fw.layouts[g], image.values)
        status = MIGRATED if m.counts.migrated else LOADED
        counts = {"kept": m.counts.kept, "converted": m.counts.converted, "defaulted": m.counts.defaulted,
                  "dropped": m.counts.dropped, "added": m.counts.added}
        if b["status"] != status or any(b[k] != v for k, v in counts.items()):
            self.bad("R2", f"{tag}: {b}, migrate() says status {status} {counts}")
        if after_save and b["status"] != LOADED:
            self.bad("R5", f"{tag}: status {b['status']} right after a save by the same version")

    def _as_served(self, fw: Firmware, g: str) -> Image:
        return Image(fw.layouts[g], dict(self.served[g]), fw.regions[g])


def run(seed: int, sets: int, sequences: int, work: Path | None = None) -> tuple[list[Violation], int]:
    """`sets` layout sets of 4 versions, `sequences` sequences each: the violations and the
    number of steps run."""
    out: list[Violation] = []
    steps = 0
    for s in range(sets):
        found, n = run_set(set_seed_of(seed, s), sequences, work)
        out += found
        steps += n
    return out, steps


def set_seed_of(seed: int, k: int) -> int:
    """The seed of a run's k-th layout set: one set in three pins regions (PINNED), and one set
    in two cuts the power in first boots after a version change (SWITCH_CUTS)."""
    return seed * 1000003 + k + (PINNED if k % 3 == 2 else 0) + (SWITCH_CUTS if k % 2 == 1 else 0)


def run_set(set_seed: int, sequences: int, work: Path | None = None,
            steps_of: Callable[[random.Random, list[Firmware]], list[tuple[str, ...]]] | None = None,
            ) -> tuple[list[Violation], int]:
    """One layout set (`set_seed` makes its versions and sequences): the violations and the steps.
    `steps_of` makes each sequence (default `script`; `load_script` for sequences around loads)."""
    out: list[Violation] = []
    with tempfile.TemporaryDirectory(dir=work) as tmp:
        rng = random.Random(set_seed)
        exe, fws = build(_versions(rng, set_seed), Path(tmp))
        _defaults(exe, fws)
        scripts = [steps_of(rng, fws) if steps_of else script(rng, fws, bool(set_seed & SWITCH_CUTS))
                   for _ in range(sequences)]
        lines = execute(exe, [st[0] for sc in scripts for st in sc])
    at = 0
    for n, sc in enumerate(scripts):
        checker = Checker(fws, set_seed, n)
        for k, st in enumerate(sc):
            checker.step = k
            at = checker.feed(st, lines, at)
        out += checker.violations
    return out, sum(len(sc) for sc in scripts)


def _versions(rng: random.Random, set_seed: int) -> list[Version]:
    """The 4 versions of a layout set, their regions pinned when the seed says so (PINNED)."""
    vs = versions(rng, 4)
    if set_seed & PINNED:
        pin(rng, vs)
    return vs


def run_script(vs: list[Version], commands: list[str], work: Path) -> tuple[list[Violation], list[Boot], list[str]]:
    """Fixed steps on versions of one's own: the rule set's violations, every boot, and the
    answers to the other commands (the regression tests of the issue's sequences)."""
    exe, fws = build(vs, work)
    _defaults(exe, fws)
    steps = [(c, "set", _key(c)) if c.startswith("set ") else (c,) for c in commands]
    lines = execute(exe, commands)
    checker, boots, answers, at = Checker(fws, 0, 0), [], [], 0
    for k, st in enumerate(steps):
        checker.step = k
        if st[0].startswith("boot"):
            boots.append(_parse_boot(lines, at)[0])
        else:
            answers.append(lines[at])
        at = checker.feed(st, lines, at)
    return checker.violations, boots, answers


def _key(command: str) -> str:
    index, sub = command.split()[1:3]
    return f"{int(index, 16)}:{int(sub, 16)}"


def _defaults(exe: Path, fws: list[Firmware]) -> None:
    """Each version's NAME_NV_SIZE and the values it serves on a blank NV."""
    commands = ["sizes"] + [c for k in range(len(fws)) for c in ("nv 65536", f"boot {k}")]
    lines = execute(exe, commands)
    sizes = [int(x) for x in lines[0].split()[1:]]
    at = 1
    for k, fw in enumerate(fws):
        fw.nv_size = sizes[k]
        boot, at = _parse_boot(lines, at + 1)
        fw.defaults = boot.values


def trace(set_seed: int, sequence: int) -> str:
    """The steps of one sequence with the program's answers and the versions' layouts, to read a
    violation (`python -c 'from tests.persist_model import trace; print(trace(SET_SEED, N))'`)."""
    with tempfile.TemporaryDirectory() as tmp:
        rng = random.Random(set_seed)
        exe, fws = build(_versions(rng, set_seed), Path(tmp))
        _defaults(exe, fws)
        scripts = [script(rng, fws, bool(set_seed & SWITCH_CUTS)) for _ in range(sequence + 1)]
        commands = [st[0] for st in scripts[sequence]]
        lines = execute(exe, commands)
    out = [f"v{k}: nv_size {fw.nv_size} regions {fw.regions} "
           + "; ".join(f"{g}: {[(hex(e.index), e.sub, e.data_type, e.length) for e in fw.layouts[g].entries]}"
                       for g in GROUPS if fw.layouts[g].entries) for k, fw in enumerate(fws)]
    out += ["> " + c for c in commands] + lines
    return "\n".join(out)
