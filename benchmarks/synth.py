"""Synthetic EDS files for benchmarks: N objects over 0x2000-0x5FFF.

About 60% VAR / 20% ARRAY / 20% RECORD of the common types (BOOLEAN,
INTEGER8..64, UNSIGNED8..64, REAL32/64, VISIBLE_STRING, OCTET_STRING), plus
0x1000, 0x1001 and 0x1018: the shape the peer measurements used. Seeded, so a
given N always gives the same file.
"""

from __future__ import annotations

import argparse
import random
from pathlib import Path

COMMON_TYPES = (0x01, 0x02, 0x03, 0x04, 0x15, 0x05, 0x06, 0x07, 0x1B, 0x08, 0x11, 0x09, 0x0A)
HEADER = """[FileInfo]
FileName=synth_{n}.eds
FileVersion=1
FileRevision=0
EDSVersion=4.0
Description=synthetic benchmark input, {n} objects, seed {seed}

[DeviceInfo]
VendorName=synthetic
VendorNumber=0x00000000
ProductName=synth_{n}
ProductNumber=0x00000001
RevisionNumber=0x00000001
BaudRate_10=0
BaudRate_20=0
BaudRate_50=0
BaudRate_125=1
BaudRate_250=1
BaudRate_500=1
BaudRate_800=0
BaudRate_1000=1
SimpleBootUpMaster=0
SimpleBootUpSlave=1
Granularity=8
DynamicChannelsSupported=0
GroupMessaging=0
NrOfRXPDO=0
NrOfTXPDO=0
LSS_Supported=0

[DummyUsage]
Dummy0001=0
Dummy0002=0
Dummy0003=0
Dummy0004=0
Dummy0005=0
Dummy0006=0
Dummy0007=0

[MandatoryObjects]
SupportedObjects=3
1=0x1000
2=0x1001
3=0x1018

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x00000000
PDOMapping=0

[1001]
ParameterName=Error register
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=0
PDOMapping=1

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Highest sub-index supported
ObjectType=0x7
DataType=0x0005
AccessType=ro
DefaultValue=1
PDOMapping=0

[1018sub1]
ParameterName=Vendor-ID
ObjectType=0x7
DataType=0x0007
AccessType=ro
DefaultValue=0x00000000
PDOMapping=0

[OptionalObjects]
SupportedObjects=0
"""


def _default(dtype: int) -> str:
    if dtype == 0x09:
        return "text"
    if dtype == 0x0A:
        return "00 01"
    return "0"


def _var(index: int, sub: int | None, name: str, dtype: int, access: str) -> str:
    section = f"{index:04X}" if sub is None else f"{index:04X}sub{sub:X}"
    mappable = int(dtype not in (0x09, 0x0A) and access == "ro")
    return (f"[{section}]\nParameterName={name}\nObjectType=0x7\nDataType=0x{dtype:04X}\n"
            f"AccessType={access}\nDefaultValue={_default(dtype)}\nPDOMapping={mappable}\n\n")


def _container(rng: random.Random, index: int, code: int) -> str:
    count = rng.randint(1, 4)
    text = f"[{index:04X}]\nParameterName=Object {index:04X}\nObjectType=0x{code:X}\nSubNumber={count + 1}\n\n"
    text += (f"[{index:04X}sub0]\nParameterName=Highest sub-index supported\nObjectType=0x7\n"
             f"DataType=0x0005\nAccessType=ro\nDefaultValue={count}\nPDOMapping=0\n\n")
    dtype = rng.choice(COMMON_TYPES)
    for sub in range(1, count + 1):
        if code == 0x9:
            dtype = rng.choice(COMMON_TYPES)
        text += _var(index, sub, f"Element {sub}", dtype, "rw")
    return text


def synth_eds(n: int, seed: int = 1) -> str:
    rng = random.Random(seed)
    indices = sorted(rng.sample(range(0x2000, 0x6000), n))
    parts = [HEADER.format(n=n, seed=seed), f"[ManufacturerObjects]\nSupportedObjects={n}\n"]
    parts += [f"{k}=0x{index:04X}\n" for k, index in enumerate(indices, start=1)]
    parts.append("\n")
    for index in indices:
        roll = rng.random()
        if roll < 0.6:
            parts.append(_var(index, None, f"Object {index:04X}", rng.choice(COMMON_TYPES),
                              rng.choice(("ro", "rw"))))
        else:
            parts.append(_container(rng, index, 0x8 if roll < 0.8 else 0x9))
    return "".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("objects", type=int)
    parser.add_argument("output", type=Path)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    args.output.write_text(synth_eds(args.objects, args.seed), encoding="utf-8")


if __name__ == "__main__":
    main()
