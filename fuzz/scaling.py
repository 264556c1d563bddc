"""Inputs grown 1x, 4x, 16x and 64x: the CPU time per byte must stay flat.

Each family repeats one shape that could make a reader or a rule quadratic: many
objects, repeated sections or keys, long values, lines that are not INI, $NODEID
formulas, object-list entries, PDO maps, XML objects, deep nesting, long attributes.
"""

from __future__ import annotations

from collections.abc import Callable

from fuzz import mutate

FACTORS = (1, 4, 16, 64)
LINEAR = 3.0  # time per byte at 64x within this factor of 1x counts as linear

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


def largest(name: str) -> bytes:
    """The input saved as a regression when a family is not linear (the 1x one: the test replays it)."""
    return build(name, FACTORS[0])


def measure(name: str) -> list:
    fmt = FAMILIES[name][0]
    sizes, per_byte, failures = [], [], set()
    for factor in FACTORS:
        data = build(name, factor)
        outcomes = [mutate.check(data, fmt, 60.0) for _ in range(3)]
        failures.update(o.failure for o in outcomes if o.failure)
        sizes.append(len(data))
        per_byte.append(min(o.ns for o in outcomes) / len(data))
    ratio = per_byte[-1] / per_byte[0]
    verdict = "linear" if ratio < LINEAR and not failures else (
        ", ".join(sorted(failures)) if failures else f"superlinear: {ratio:.1f}x per byte")
    return [name, fmt, f"{sizes[0] / 1e3:.0f} .. {sizes[-1] / 1e3:.0f}",
            *(round(p) for p in per_byte), round(ratio, 2), verdict]


def run() -> dict:
    rows = [measure(name) for name in FAMILIES]
    return {"title": "Parser scaling: inputs grown 1x to 64x",
            "columns": ["family", "format", "size (kB)", *(f"ns/byte {f}x" for f in FACTORS),
                        "64x / 1x", "verdict"],
            "rows": rows,
            "notes": ["Time (best of 3, wall clock on a shared machine) of reading, linting and writing back "
                      f"as EDS, per input byte. A family is linear when the time per byte at 64x is within "
                      f"{LINEAR:g}x of 1x."]}
