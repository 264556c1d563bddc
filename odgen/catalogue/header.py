"""HDR: header sections [FileInfo], [DeviceInfo], [DummyUsage], [Comments]."""

from __future__ import annotations

from .rule import E, INFO, W, define

HDR001 = define(
    "HDR001", E, "required section missing", ref="CiA 306 table row H1",
    why="An EDS/DCF describes the device in [DeviceInfo] and lists its objects in [MandatoryObjects] "
    "(plus Optional/ManufacturerObjects). Without them tools cannot identify the device or find "
    "its objects; objdictgen refuses the file.",
    example="(no [DeviceInfo] section)",
    fix="Add the section with its keys.",
    blocking="The C is built from the object sections; the header sections do not change it.")

HDR002 = define(
    "HDR002", W, "unknown key in a header section", ref="CiA 306 table row H2",
    why="[FileInfo], [DeviceInfo] and [DeviceComissioning] have a fixed set of keys. Lely's dcfchk "
    "reports others as invalid entries, and a misspelt key (`BaudRate_100`) is silently ignored.",
    example="[DeviceInfo]\nBaudRate_100=1",
    fix="Correct the spelling, or remove the key (vendor notes go into [Comments]).")

HDR003 = define(
    "HDR003", W, "header value is not a valid number", ref="CiA 306 table rows H3, H6, H7",
    why="FileVersion and FileRevision are UNSIGNED8; VendorNumber, ProductNumber and RevisionNumber "
    "UNSIGNED32; NrOfRXPDO/NrOfTXPDO 0..512; CompactPDO a bit field 0..0x3F; "
    "DynamicChannelsSupported a count; a DCF's NodeID 1..127 (255: not yet configured by LSS). "
    "Tools read other text as 0 or refuse the file.",
    example="[FileInfo]\nFileVersion=1.0",
    fix="Write a decimal or 0x-hex number in the key's range (`FileVersion=1`).")

HDR004 = define(
    "HDR004", W, "EDSVersion is not 4.0", ref="CiA 306 table row H3 (verify)",
    why="CiA 306 files of this format declare `EDSVersion=4.0`; values such as 402 or 404 are device "
    "profile numbers written in the wrong key. (Row marked verify: warning.)",
    example="EDSVersion=402",
    fix="Write `EDSVersion=4.0`.")

HDR005 = define(
    "HDR005", W, "date or time not in CiA 306 format", ref="CiA 306 table row H3 (verify)",
    why="CreationDate/ModificationDate are written `mm-dd-yyyy` and CreationTime/ModificationTime "
    "`hh:mm` followed by AM or PM. Other forms (yyyy-mm-dd, 24-hour with seconds) are misread by "
    "tools that parse them. (Row marked verify: warning.)",
    example="CreationDate=2024-03-01\nCreationTime=14:05:00",
    fix="Write `CreationDate=03-01-2024` and `CreationTime=02:05PM`.")

HDR006 = define(
    "HDR006", W, "[DeviceInfo] flag is not 0 or 1", ref="CiA 306 table row H4",
    why="BaudRate_10 .. BaudRate_1000, SimpleBootUpMaster/Slave, GroupMessaging and LSS_Supported "
    "are booleans written 0 or 1.",
    example="BaudRate_250=yes",
    fix="Write 1 (supported) or 0 (not supported).")

HDR007 = define(
    "HDR007", W, "no bit rate supported", ref="CiA 306 table row H4",
    why="A device supports at least one CiA 301 bit rate; with every BaudRate_xxx 0 or absent, "
    "configuration tools have no bit rate to offer.",
    example="BaudRate_125=0\nBaudRate_250=0\n... (all 0)",
    fix="Set `BaudRate_xxx=1` for each bit rate the device supports.")

HDR008 = define(
    "HDR008", W, "DCF Baudrate not supported by the device", ref="CiA 306 table row H4",
    why="[DeviceComissioning] Baudrate is the configured bit rate in kbit/s; it must be one the "
    "device declares with BaudRate_xxx=1 in [DeviceInfo], or the node cannot join the network.",
    example="[DeviceInfo]\nBaudRate_500=0\n[DeviceComissioning]\nBaudrate=500",
    fix="Configure a supported bit rate, or correct [DeviceInfo].")

HDR009 = define(
    "HDR009", E, "Granularity outside 0..64", ref="CiA 306 table row H5",
    why="Granularity is the mapping granularity in bits, 0..64 (0: mapping not modifiable; 8: "
    "byte-wise, as CANopenNode needs). PDO mapping checks and generators depend on it. "
    "(Python canopen reads it as a boolean.)",
    example="Granularity=128",
    fix="Write the bit granularity the device supports, typically `Granularity=8`.",
    blocking="The runtime does not read Granularity; the mapping checks (PDO rules) stand on their own.")

HDR010 = define(
    "HDR010", W, "DynamicChannelsSupported and [DynamicChannels] disagree",
    ref="CiA 306 table row H8 (verify)",
    why="DynamicChannelsSupported is the number of dynamic channel segments (CiA 302 network "
    "variables); a count above 0 needs a [DynamicChannels] section describing them, and that "
    "section means nothing with a count of 0. (Row marked verify: warning.)",
    example="DynamicChannelsSupported=0\n[DynamicChannels]\nNrOfSeg=1",
    fix="Make the count and the section agree.")

HDR011 = define(
    "HDR011", E, "invalid [DummyUsage] entry", ref="CiA 306 table row H9",
    why="[DummyUsage] has keys Dummy0001..Dummy001B (the basic data type indices) with value 0 or 1; "
    "mapping a dummy entry depends on them. Lely refuses other keys and values.",
    example="[DummyUsage]\nDummy0005=yes",
    fix="Write `DummyXXXX=1` for each data type usable as a dummy mapping, 0 otherwise.",
    blocking="A dummy entry that is not enabled is reported where it is mapped (PDO001), which blocks.")

HDR012 = define(
    "HDR012", W, "[DeviceInfo]/[DeviceComissioning] differs from the identity object",
    ref="CiA 306 table row H10",
    why="VendorNumber, ProductNumber and RevisionNumber repeat 0x1018 sub1..sub3 (and a DCF's "
    "LSS_SerialNumber 0x1018 sub4). Masters compare the device's 0x1018 against the file, so a "
    "mismatch makes them reject a correct device (Lely warns about it).",
    example="VendorNumber=0x123\n[1018sub1]\nDefaultValue=0x456",
    fix="Make both carry the same number.")

HDR013 = define(
    "HDR013", W, "[Comments] Lines differs from its LineN keys", ref="CiA 306 table row H11",
    why="[Comments] declares `Lines=N` followed by Line1..LineN. Readers that loop over 1..N "
    "lose extra lines or stop at a missing one (python canopen raises).",
    example="[Comments]\nLines=3\nLine1=a\nLine2=b",
    fix="Set Lines to the number of LineN keys and number them from 1 without gaps.")

HDR014 = define(
    "HDR014", W, "[FileInfo] missing", ref="CiA 306 table row H1",
    why="CiA 306 files start with [FileInfo] (file name, version, EDSVersion, dates, author). Nothing "
    "technical depends on it, but without it nobody can tell which revision of the file this is; "
    "objdictgen refuses such files. (Lely's dcfgen writes DCFs without it.)",
    example="(no [FileInfo] section)",
    fix="Add [FileInfo] with at least FileName, FileVersion, FileRevision and EDSVersion=4.0.")

HDR015 = define(
    "HDR015", INFO, "DCF Baudrate not set (0)", ref="CiA 306 table row H4",
    why="CANopenEditor writes `Baudrate=0` into [DeviceComissioning] when no bit rate was chosen. "
    "It configures nothing (no device runs at 0 kbit/s), so it is noted, not checked against "
    "the supported rates as HDR008 does.",
    example="[DeviceComissioning]\nBaudrate=0",
    fix="Set the commissioned bit rate in kbit/s, or leave the note.")
