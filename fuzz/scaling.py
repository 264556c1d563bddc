"""Inputs grown 1x to 256x: the time per byte must stay flat.

Each family repeats one shape that could make a reader or a rule quadratic: many
objects, repeated sections or keys, long values, lines that are not INI, $NODEID
formulas, object-list entries, PDO maps, XML objects, deep nesting, long attributes.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

from fuzz import mutate

FACTORS = (1, 4, 16, 64, 256)
SAMPLE_NS = 300_000_000
LINEAR = 1.25  # time ~ size^k from 4x up (1x is mostly fixed costs): k below this counts as linear

_XDD = (mutate.ROOT / "tests" / "fixtures" / "xdd" / "valid.xdd").read_text(encoding="utf-8")
_EDS = (mutate.ROOT / "tests" / "fixtures" / "generate" / "plain.eds").read_text(encoding="utf-8")


def _var(i: int, default: str = "0") -> str:
    return (f"[{0x2000 + i % 0x3000:04X}]\nParameterName=Value {i}\nObjectType=0x7\nDataType=0x0007\n"
            f"AccessType=rw\nDefaultValue={default}\nPDOMapping=1\n\n")


def _eds_objects(n: int) -> str:
    return _EDS + "".join(_var(i) for i in range(40 * n))


def _eds_same_section(n: int) -> str:
    return _EDS + _var(0) * (40 * n)


def _eds_same_key(n: int) -> str:
    return _EDS + "[2000]\nParameterName=x\nDataType=0x0007\nAccessType=rw\n" + "DefaultValue=1\n" * (400 * n)


def _eds_long_value(n: int) -> str:
    return _EDS + "[2000]\nParameterName=" + "N" * (4000 * n) + "\nDataType=0x0007\nAccessType=rw\n"


def _eds_junk_lines(n: int) -> str:
    return _EDS + "this is not ini\n" * (300 * n)


def _eds_nodeid(n: int) -> str:
    return _EDS + "".join(_var(i, f"$NODEID+0x{i:X}") for i in range(40 * n))


def _eds_object_list(n: int) -> str:
    entries = "".join(f"{i + 1}=0x{0x2000 + i:04X}\n" for i in range(300 * n))
    return _EDS + f"[OptionalObjects]\nSupportedObjects={300 * n}\n{entries}"


def _eds_pdo_maps(n: int) -> str:
    maps = []
    for i in range(8 * n):
        subs = "".join(f"[{0x1A00 + i:04X}sub{s:X}]\nParameterName=m{s}\nDataType=0x0007\nAccessType=rw\n"
                       f"DefaultValue=0x20000008\n\n" for s in range(1, 9))
        maps.append(f"[{0x1A00 + i:04X}]\nParameterName=TPDO map {i}\nObjectType=0x9\nSubNumber=9\n\n"
                    f"[{0x1A00 + i:04X}sub0]\nParameterName=n\nDataType=0x0005\nAccessType=rw\nDefaultValue=8\n\n"
                    + subs)
    return _EDS + _var(0) + "".join(maps)


def _xdd_objects(n: int) -> str:
    objects = "".join(f'<CANopenObject index="{0x2100 + i % 0x3000:04X}" name="v{i}" objectType="7" '
                      f'dataType="0007" accessType="rw" defaultValue="{i}" PDOmapping="optional"/>\n'
                      for i in range(40 * n))
    return _XDD.replace("</CANopenObjectList>", objects + "</CANopenObjectList>")


def _xdd_nesting(n: int) -> str:
    return _XDD.replace("<ProfileSource/>", "<a>" * (60 * n) + "</a>" * (60 * n), 1)


def _xdd_long_attribute(n: int) -> str:
    return _XDD.replace('name="Error register"', f'name="{"E" * (4000 * n)}"', 1)


FAMILIES: dict[str, tuple[str, Callable[[int], str]]] = {
    "eds-objects": ("eds", _eds_objects), "eds-same-section": ("eds", _eds_same_section),
    "eds-same-key": ("eds", _eds_same_key), "eds-long-value": ("eds", _eds_long_value),
    "eds-junk-lines": ("eds", _eds_junk_lines), "eds-nodeid-formulas": ("eds", _eds_nodeid),
    "eds-object-list": ("eds", _eds_object_list), "eds-pdo-maps": ("eds", _eds_pdo_maps),
    "xdd-objects": ("xdd", _xdd_objects), "xdd-nesting": ("xdd", _xdd_nesting),
    "xdd-long-attribute": ("xdd", _xdd_long_attribute),
}


def build(name: str, factor: int) -> bytes:
    return FAMILIES[name][1](factor).encode("utf-8")


def smallest(name: str) -> bytes:
    """The input saved as a regression when a family is not linear (the test replays it)."""
    return build(name, FACTORS[0])


def measure(name: str) -> list:
    fmt = FAMILIES[name][0]
    sizes, per_byte, failures = [], [], set()
    for factor in FACTORS:
        data = build(name, factor)
        sizes.append(len(data))
        per_byte.append(_cpu_ns(data, fmt, failures) / len(data))
    exponent = growth(sizes[1:], [p * n for p, n in zip(per_byte[1:], sizes[1:], strict=True)])
    verdict = "linear" if exponent < LINEAR and not failures else (
        ", ".join(sorted(failures)) if failures else f"superlinear: time grows as size^{exponent:.2f}")
    return [name, fmt, f"{sizes[0] / 1e3:.0f} .. {sizes[-1] / 1e3:.0f}",
            *(round(p) for p in per_byte), round(exponent, 2), verdict]


def _cpu_ns(data: bytes, fmt: str, failures: set[str]) -> float:
    """CPU time of one run, averaged over runs adding up to SAMPLE_NS (the CPU clock ticks coarsely)."""
    runs, start = 0, time.process_time_ns()
    while True:
        outcome = mutate.check(data, fmt, 60.0)
        runs += 1
        if outcome.failure:
            failures.add(outcome.failure)
        spent = time.process_time_ns() - start
        if spent >= SAMPLE_NS or runs >= 100:
            return spent / runs


def growth(sizes: list[int], times: list[float]) -> float:
    """The exponent k of time ~ size^k, a least-squares fit on logarithms."""
    xs, ys = [math.log(n) for n in sizes], [math.log(max(t, 1.0)) for t in times]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys, strict=True)) / sum((x - mx) ** 2 for x in xs)


def run() -> dict:
    rows = [measure(name) for name in FAMILIES]
    return {"title": f"Parser scaling: inputs grown 1x to {FACTORS[-1]}x",
            "columns": ["family", "format", "size (kB)", *(f"ns/byte {f}x" for f in FACTORS),
                        f"exponent k ({FACTORS[1]}x..{FACTORS[-1]}x)", "verdict"],
            "rows": rows,
            "notes": ["CPU time of reading, linting and writing back as EDS, per input byte at each size "
                      f"(runs repeated until {SAMPLE_NS / 1e9:g} s of CPU, then averaged). k is the exponent of "
                      "time ~ size^k fitted from "
                      f"{FACTORS[1]}x to {FACTORS[-1]}x: 1 is linear, 2 quadratic; below {LINEAR:g} counts as "
                      "linear. Inputs of the nesting family beyond libxml2's depth limit are refused (XML001) "
                      "at once."]}
