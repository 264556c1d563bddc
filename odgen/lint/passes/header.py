"""HDR: the header sections of an EDS/DCF (CiA 306 rule table rows H1-H11).

[FileInfo], [DeviceInfo], [DeviceComissioning], [DummyUsage], [Comments] and
[DynamicChannels]. NrOfRXPDO/NrOfTXPDO (H6) and mapping offsets against
Granularity (H5, second half) are checked with the PDOs, in the pdo family.
"""

from __future__ import annotations

import re

from ...catalogue.header import (
    HDR001, HDR002, HDR003, HDR004, HDR005, HDR006, HDR007, HDR008, HDR009, HDR010, HDR011, HDR012, HDR013, HDR014,
    HDR015)
from ...diagnostics import Diagnostics, Loc
from ...model import Field, ObjectDictionary, Section, Sub, Value
from ...model.cia301 import IDENTITY
from .base import LintOptions, LintPass
from ...model.header import header_field, header_int
from ...model.values import number
from .common import gaps, granularity



KNOWN_KEYS = {
    # LastEDS names a DCF's source EDS; CANopenEditor, python canopen and gocanopen also write it
    # into EDS files, where it is harmless, so it is accepted in both.
    "fileinfo": ("FileName", "FileVersion", "FileRevision", "EDSVersion", "Description", "CreationTime",
                 "CreationDate", "CreatedBy", "ModificationTime", "ModificationDate", "ModifiedBy", "LastEDS"),
    "deviceinfo": ("VendorName", "VendorNumber", "ProductName", "ProductNumber", "RevisionNumber",
                   "OrderCode", "BaudRate_10", "BaudRate_20", "BaudRate_50", "BaudRate_125",
                   "BaudRate_250", "BaudRate_500", "BaudRate_800", "BaudRate_1000",
                   "SimpleBootUpMaster", "SimpleBootUpSlave", "Granularity", "DynamicChannelsSupported",
                   "GroupMessaging", "NrOfRXPDO", "NrOfTXPDO", "LSS_Supported", "CompactPDO",
                   # node guarding and safety keys written by CiA 306 v1.3 tools
                   "NG_Slave", "NG_Master", "NrOfNG_MonitoredNodes", "CANopenSafetySupported"),
    "devicecomissioning": ("NodeID", "NodeName", "NodeRefd", "Baudrate", "NetNumber", "NetworkName",
                           "NetRefd", "CANopenManager", "LSS_SerialNumber"),
}
BIT_RATES = (10, 20, 50, 125, 250, 500, 800, 1000)
FLAGS = tuple(f"BaudRate_{r}" for r in BIT_RATES) + (
    "SimpleBootUpMaster", "SimpleBootUpSlave", "GroupMessaging", "LSS_Supported", "NG_Slave", "NG_Master")
# key -> (section, valid values, how to say them) for numeric header values
NUMBERS = {
    "FileVersion": ("FileInfo", range(0x100), "0..255"),
    "FileRevision": ("FileInfo", range(0x100), "0..255"),
    "VendorNumber": ("DeviceInfo", range(0x1_0000_0000), "0..0xFFFFFFFF"),
    "ProductNumber": ("DeviceInfo", range(0x1_0000_0000), "0..0xFFFFFFFF"),
    "RevisionNumber": ("DeviceInfo", range(0x1_0000_0000), "0..0xFFFFFFFF"),
    "NrOfRXPDO": ("DeviceInfo", range(513), "0..512"),
    "NrOfTXPDO": ("DeviceInfo", range(513), "0..512"),
    "CompactPDO": ("DeviceInfo", range(0x40), "0..0x3F"),
    "DynamicChannelsSupported": ("DeviceInfo", range(0x10000), "0..65535"),
    "NodeID": ("DeviceComissioning", (*range(1, 128), 255), "1..127 or 255"),
}
_DATE_RE = re.compile(r"^(\d{1,2})-(\d{1,2})-(\d{4})$")
_TIME_RE = re.compile(r"^(\d{1,2}):(\d{2})\s?(AM|PM)$", re.IGNORECASE)
_DUMMY_RE = re.compile(r"^dummy([0-9a-f]{4})$", re.IGNORECASE)
_LINE_RE = re.compile(r"^line(\d+)$", re.IGNORECASE)


def _loc(od: ObjectDictionary, fld: Field | Section | None) -> Loc:
    return Loc(od.source, fld.line if fld is not None else 0)


# -- H1, H2 ----------------------------------------------------------------------

def required_sections(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    if od.format not in ("eds", "dcf"):
        return
    if od.section("FileInfo") is None:
        diags.add(HDR014, Loc(od.source), "[FileInfo] is missing")
    if od.section("DeviceInfo") is None:
        diags.add(HDR001, Loc(od.source), "[DeviceInfo] is missing")
    if "mandatoryobjects" not in od.object_lists:
        diags.add(HDR001, Loc(od.source), "[MandatoryObjects] is missing")


def header_keys(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for name, keys in KNOWN_KEYS.items():
        section = od.section(name)
        if section is None:
            continue
        known = {k.lower() for k in keys}
        for key, fld in section.fields.items():
            if key not in known:
                diags.add(HDR002, _loc(od, fld), f"'{fld.key}' is not a [{section.name}] key")


# -- H3 --------------------------------------------------------------------------

def header_numbers(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    for key, (section_name, valid, said) in NUMBERS.items():
        fld = header_field(od, section_name, key)
        if fld is None or fld.text.strip() == "":
            continue
        value = header_int(fld)
        if value is None and key == "NodeID":
            continue  # the reader reports an unreadable NodeID (SYN015)
        if value is None or value not in valid:
            what = "not a number" if value is None else f"outside {said}"
            diags.add(HDR003, _loc(od, fld), f"{fld.key}={fld.text.strip()} is {what}")


def file_info_formats(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    section = od.section("FileInfo")
    if section is None:
        return
    version = section.get("EDSVersion")
    if version is not None and not re.fullmatch(r"4(\.0+)?", version.text.strip()):
        diags.add(HDR004, _loc(od, version), f"EDSVersion={version.text.strip()}, expected 4.0")
    for key in ("CreationDate", "ModificationDate"):
        fld = section.get(key)
        if fld is not None and fld.text.strip() and not _valid_date(fld.text.strip()):
            diags.add(HDR005, _loc(od, fld), f"{fld.key}={fld.text.strip()} is not mm-dd-yyyy")
    for key in ("CreationTime", "ModificationTime"):
        fld = section.get(key)
        if fld is not None and fld.text.strip() and not _valid_time(fld.text.strip()):
            diags.add(HDR005, _loc(od, fld), f"{fld.key}={fld.text.strip()} is not hh:mm followed by AM or PM")


def _valid_date(text: str) -> bool:
    m = _DATE_RE.match(text)
    return m is not None and 1 <= int(m.group(1)) <= 12 and 1 <= int(m.group(2)) <= 31


def _valid_time(text: str) -> bool:
    m = _TIME_RE.match(text)
    return m is not None and int(m.group(1)) <= 12 and int(m.group(2)) <= 59


# -- H4 --------------------------------------------------------------------------

def device_flags(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    section = od.section("DeviceInfo")
    if section is None:
        return
    for key in FLAGS:
        fld = section.get(key)
        if fld is not None and header_int(fld) not in (0, 1):
            diags.add(HDR006, _loc(od, fld), f"{fld.key}={fld.text.strip()} is not 0 or 1")
    rates = _supported_rates(section)
    if not rates:
        diags.add(HDR007, _loc(od, section), "no BaudRate_xxx is 1")
    _commissioned_rate(od, rates, diags)


def _supported_rates(section: Section) -> set[int]:
    return {r for r in BIT_RATES if header_int(section.get(f"BaudRate_{r}")) == 1}


def _commissioned_rate(od: ObjectDictionary, rates: set[int], diags: Diagnostics) -> None:
    fld = header_field(od, "DeviceComissioning", "Baudrate")
    if fld is None or not rates or not fld.text.strip():
        return
    rate = header_int(fld)
    if rate == 0 and od.is_config:
        diags.add(HDR015, _loc(od, fld), "Baudrate=0: no bit rate configured")
        return
    if rate not in rates:
        listed = ", ".join(str(r) for r in sorted(rates))
        diags.add(HDR008, _loc(od, fld),
                  f"Baudrate={fld.text.strip()} is not a supported bit rate ({listed} kbit/s)")


# -- H5 --------------------------------------------------------------------------

def granularity_range(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    value, fld = granularity(od)
    if fld is not None and fld.text.strip() and (value is None or not 0 <= value <= 64):
        diags.add(HDR009, _loc(od, fld), f"Granularity={fld.text.strip()} is not a number 0..64")


# -- H8 --------------------------------------------------------------------------

def dynamic_channels(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    fld = header_field(od, "DeviceInfo", "DynamicChannelsSupported")
    count = header_int(fld)
    channels = od.section("DynamicChannels")
    if fld is not None and count is not None and count > 0 and channels is None:
        diags.add(HDR010, _loc(od, fld), f"DynamicChannelsSupported={fld.text.strip()} "
                  "but there is no [DynamicChannels] section")
    elif channels is not None and not count:
        said = f"={fld.text.strip()}" if fld is not None else " is absent"
        diags.add(HDR010, _loc(od, channels), f"[DynamicChannels] but DynamicChannelsSupported{said}")


# -- H9 --------------------------------------------------------------------------

def dummy_usage(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    section = od.section("DummyUsage")
    if section is None:
        return
    for fld in section.fields.values():
        m = _DUMMY_RE.match(fld.key)
        if m is None or not 0x0001 <= int(m.group(1), 16) <= 0x001B:
            diags.add(HDR011, _loc(od, fld), f"'{fld.key}' is not Dummy0001..Dummy001B")
        elif header_int(fld) not in (0, 1):
            diags.add(HDR011, _loc(od, fld), f"{fld.key}={fld.text.strip()} is not 0 or 1")


# -- H10 -------------------------------------------------------------------------

_IDENTITY = (("DeviceInfo", "VendorNumber", 1), ("DeviceInfo", "ProductNumber", 2),
             ("DeviceInfo", "RevisionNumber", 3), ("DeviceComissioning", "LSS_SerialNumber", 4))


def identity_numbers(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    identity = od.objects.get(IDENTITY)
    if identity is None or identity.is_var:
        return
    for section_name, key, subindex in _IDENTITY:
        fld = header_field(od, section_name, key)
        header = header_int(fld)
        value = _identity_value(od, identity.subs.get(subindex))
        device = number(value)
        if fld is None or header is None or value is None or device is None:
            continue
        if not value.nodeid and header != device:
            diags.add(HDR012, _loc(od, fld),
                      f"{key}={fld.text.strip()} but 0x1018sub{subindex} is {value.text.strip()}")


def _identity_value(od: ObjectDictionary, sub: Sub | None) -> Value | None:
    """A DCF's ParameterValue where written (even empty), else the DefaultValue."""
    if sub is None:
        return None
    if od.is_config and sub.parameter_value is not None:
        return sub.parameter_value
    return sub.default


# -- H11 -------------------------------------------------------------------------

def comment_lines(od: ObjectDictionary, diags: Diagnostics, options: LintOptions) -> None:
    section = od.section("Comments")
    if section is None:
        return
    lines_fld = section.get("Lines")
    numbers = {int(m.group(1)): f for f in section.fields.values() if (m := _LINE_RE.match(f.key))}
    declared = header_int(lines_fld)
    if lines_fld is None or declared is None:
        said = f"Lines={lines_fld.text.strip()} is not a number" if lines_fld else "no Lines key"
        if numbers or lines_fld is not None:
            diags.add(HDR013, _loc(od, lines_fld or section), f"{said} ({len(numbers)} LineN keys)")
        return
    parts = _line_mismatches(declared, set(numbers))
    if parts:
        diags.add(HDR013, _loc(od, lines_fld), f"Lines={lines_fld.text.strip()} but {'; '.join(parts)}")


def _line_mismatches(declared: int, numbers: set[int]) -> list[str]:
    """What differs between `Lines=declared` and the LineN keys present: missing ones, then extra ones."""
    missing, n_missing = gaps(declared, numbers, 3)
    extra = sorted(n for n in numbers if not 1 <= n <= declared)
    parts = []
    if missing:
        parts.append("no " + ", ".join(f"Line{n}" for n in missing) + (" ..." if n_missing > 3 else ""))
    if extra:
        parts.append(", ".join(f"Line{n}" for n in extra[:3]) + (" ..." if len(extra) > 3 else "") + " beyond it")
    return parts


# This family's lint passes, in the order they run.
PASSES: tuple[LintPass, ...] = (required_sections, header_keys, header_numbers, file_info_formats, device_flags,
                                granularity_range, dynamic_channels, dummy_usage, identity_numbers, comment_lines)
