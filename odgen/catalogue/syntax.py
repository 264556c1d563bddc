"""SYN: file syntax and value notation, reported while reading EDS/DCF."""

from __future__ import annotations

from .rule import E, INFO, W, define

SYN001 = define(
    "SYN001", E, "line is neither a section header nor key=value", ref="S1",
    why="CiA 306 files are INI: every non-blank line is `[section]`, `key=value` or a `;` comment. "
    "Other tools stop or silently drop such lines, so their meaning is lost.",
    example="[1000]\nParameterName Device type\n",
    fix="Add the missing `=` or turn the line into a `;` comment.",
    blocks=True,
    blocking="The reader cannot tell what the line meant, so the C may miss a value the file has.",
    no_repair="What the line was meant to say is unknown.")

SYN002 = define(
    "SYN002", E, "duplicate section", ref="S1",
    why="A section may appear once. Python canopen refuses the file, other tools keep one copy or "
    "the other; odgen keeps the first and ignores the repeat.",
    example="[1000]\nParameterName=Device type\n...\n[1000]\nParameterName=Again\n",
    fix="Merge the two sections into one.",
    blocks=True,
    blocking="Two definitions of one object: the C would follow one of them and not match the other.",
    no_repair="Which copy the device has is unknown.")

SYN003 = define(
    "SYN003", E, "duplicate key in a section", ref="S1",
    why="A key may appear once per section; readers disagree on which copy wins. odgen keeps the first.",
    example="[ManufacturerObjects]\nSupportedObjects=2\n1=0x2000\n1=0x2001\n",
    fix="Remove or renumber the repeated key.",
    blocks=True,
    blocking="Blocks when the copies differ in a section the C depends on (the C would follow one and not "
    "match the other); identical copies, and repeats in the object lists, [FileInfo] or [Comments], do not.",
    no_repair="Which of two different values the device has is unknown.")

SYN004 = define(
    "SYN004", W, "file is not UTF-8", ref="S1",
    why="Text with bytes that are not UTF-8 is read as Windows-1252, the usual encoding of old vendor "
    "files. Names with such characters may reach generated C or other tools garbled. UTF-16 and UTF-32 "
    "files (by their BOM, or NUL bytes beside an ASCII start) are decoded as such and reported too.",
    example="ParameterName=Gr\\xf6\\xdfe  (Latin-1/Windows-1252 bytes)",
    fix="Save the file as UTF-8 (or plain ASCII).")

SYN005 = define(
    "SYN005", E, "key outside any section", ref="S1",
    why="A key before the first `[section]` belongs to nothing and is ignored.",
    example="FileName=dev.eds\n[FileInfo]\n",
    fix="Move the key into the section it belongs to.",
    blocking="The key belongs to no object, so the dictionary is the same without it.")

SYN006 = define(
    "SYN006", W, "number with a leading zero", ref="S3",
    why="CiA 306 numbers follow C: a leading 0 means octal, so `010` is 8. Python canopen refuses "
    "such numbers (`VendorNumber=001`), others read them as decimal.",
    example="DefaultValue=010",
    fix="Write the number without leading zeros, or in hex (`0x08`).")

SYN007 = define(
    "SYN007", W, "$NODEID in a non-canonical form", ref="S4",
    why="CiA 306 writes node-id relative values as `$NODEID+<number>`. Lely and objdictgen accept only "
    "that form; `0x180+$NODEID`, lower case or spaces break them. odgen reads the value either way.",
    example="DefaultValue=0x180+$NODEID",
    fix="Write `$NODEID+0x180`.",
    repair="safe: written as `$NODEID+<number>`")

SYN008 = define(
    "SYN008", INFO, "signed value written as unsigned hex", ref="S3",
    why="A signed entry written as its bit pattern (`0xFFFF` for INTEGER16 -1) is read as two's "
    "complement, as python canopen does; Lely reports it as out of range.",
    example="DataType=0x0003\nDefaultValue=0xFFFF",
    fix="Write the signed value (`-1`) to be understood by every tool.")

SYN009 = define(
    "SYN009", W, "REAL value written as a bit pattern", ref="7.6",
    why="Tools disagree on REAL32/REAL64 values written as hex integers: Lely reads an IEEE 754 bit "
    "pattern, python canopen a number, CANopenEditor pastes the text into C. odgen reads the bit pattern.",
    example="DataType=0x0008\nDefaultValue=0x3F800000",
    fix="Write the value as a decimal number (`1.0`).")

SYN010 = define(
    "SYN010", W, "unknown section", ref="S5",
    why="The section is not one CiA 306 defines; its content is kept but not interpreted.",
    example="[MyVendorSettings]",
    fix="Remove the section, or move vendor data into manufacturer objects.")

SYN011 = define(
    "SYN011", E, "value cannot be read as the entry's data type", ref="O11/O12",
    why="A DefaultValue, ParameterValue or limit that does not parse as the entry's data type cannot be "
    "checked, generated or downloaded.",
    example="DataType=0x0007\nDefaultValue=Profile-specific",
    fix="Write a number (decimal or 0x hex), a `$NODEID+<number>`, or hex bytes for OCTET_STRING.",
    blocks=True,
    blocking="The C would hold no value, or another one, where the file has text it cannot read.",
    no_repair="What the text was meant to be is unknown.")

SYN012 = define(
    "SYN012", INFO, "keyword spelled with unusual letter case", ref="S2",
    why="Section and key names are case-insensitive for odgen and Lely, but python canopen compares "
    "keys case-sensitively and misses e.g. `Parametername`.",
    example="parametername=Device type",
    fix="Use the spelling of CiA 306 (`ParameterName`).")

SYN013 = define(
    "SYN013", E, "sub-object section without its object", ref="S6",
    why="`[XXXXsubY]` belongs to object XXXX, which has no `[XXXX]` section or is not an ARRAY/RECORD. "
    "Python canopen crashes on this; odgen ignores the sub-object.",
    example="[2000sub1]\nParameterName=Orphan\n(no [2000] section)",
    fix="Add the `[XXXX]` section with ObjectType=0x8 or 0x9, or remove the sub-object.",
    blocks=True,
    blocking="The sub-object has no object to belong to: the C would leave out what the file has.",
    no_repair="Which object the section belongs to is unknown.")

SYN014 = define(
    "SYN014", W, "inline comment after a value", ref="S1",
    why="CiA 306 comments are whole lines starting with `;`. Text after the value is cut at ` ;` as "
    "python canopen and Lely do, but other tools keep it as part of the value.",
    example="BaudRate_1000=1 ; fastest",
    fix="Put the comment on its own line.",
    cap=1)  # files that comment inline do so on every line: one finding and a count

SYN015 = define(
    "SYN015", E, "keyword value is not a number", ref="O2/O3/O7",
    why="ObjectType, DataType, SubNumber, CompactSubObj, PDOMapping, ObjFlags and header counts must be "
    "numbers; the entry cannot be understood otherwise.",
    example="ObjectType=VAR",
    fix="Write the number (`0x7`).",
    blocks=True,
    blocking="An empty value is read as absent, as every reader does, and does not block; other text blocks, since "
    "the C would miss the number the file has.",
    repair="safe: an empty keyword is removed",
    no_repair="Text that is not a number has no known meaning.")

SYN016 = define(
    "SYN016", E, "invalid compact sub-object section", ref="O14",
    why="`[XXXXName]`/`[XXXXValue]` list names/values of sub-objects of an object with CompactSubObj; "
    "`NrOfEntries` must equal the number of entries and every entry must be a sub-index 1..CompactSubObj.",
    example="[1003]\nCompactSubObj=2\n[1003Name]\nNrOfEntries=1\n3=Error 3",
    fix="Correct NrOfEntries and the sub-index keys, or add CompactSubObj to the object.",
    blocks=True,
    blocking="Blocks when values of a compact section are left out (the C would not match); a wrong NrOfEntries or "
    "a CompactSubObj above 254 (sub-index 255 is reserved by CiA 301) does not.",
    repair="safe: NrOfEntries set to the entries present; a CompactSubObj above 254 set to 254",
    no_repair="Values listed for an object without CompactSubObj, or under keys that are no sub-index, belong to "
    "nothing known.")

SYN017 = define(
    "SYN017", E, "invalid object section name", ref="S5",
    why="Object sections are `[XXXX]` or `[XXXXsubY]` with a 4-digit hex index and hex sub-index 0..FE.",
    example="[2000sub1FF]",
    fix="Use a sub-index 0..FE written in hex without 0x.",
    blocks=True,
    blocking="The section is not read, so the C would leave out an object the file has.",
    no_repair="Which object the section names is unknown.")

SYN018 = define(
    "SYN018", E, "file too large", ref="S1",
    why="Device descriptions are kilobytes to a few megabytes (the largest known XDD is 0.6 MB). A file "
    "above 16 MiB is refused unread, so a hostile or corrupt file cannot exhaust memory or time.",
    example="(a 100 MB file)",
    fix="Check that the file is a device description; split modules into separate files.",
    blocks=True,
    blocking="The file is not read at all.",
    no_repair="A file past the size limit is not read.")

SYN019 = define(
    "SYN019", W, "object section index without leading zeros", ref="S5",
    why="Object sections are named by a 4-digit hex index: `[00A0]`, not `[A0]`. Some generators drop "
    "the zeros; the section is read as the object it names (unless `[00A0]` exists too), so the object "
    "list finds it instead of reporting a listed object without a section.",
    example="[A0]\nParameterName=Vendor type",
    fix="Write the index with four digits: `[00A0]`.")

SYN020 = define(
    "SYN020", W, "integer value with a C suffix", ref="7.6",
    why="CiA 306 numbers follow `strtoul`, which stops at a suffix: `0x1234567890ABCDEFLL` (as "
    "CANopenNode's example files write INTEGER64 defaults) is not a number to a strict reader, and "
    "python canopen refuses it. The digits are unambiguous, so odgen reads them and drops the suffix.",
    example="[2120sub1]\nDataType=0x0015\nDefaultValue=0x1234567890ABCDEFLL",
    fix="Write the number without the suffix: `DefaultValue=0x1234567890ABCDEF`.")

SYN021 = define(
    "SYN021", E, "section with too many keys", ref="S1",
    why="No CiA 306 section needs more than 65,600 keys: an object list names at most 65,535 indices. "
    "Keys beyond that are counted and reported, not kept, so a corrupt or hostile file of millions of "
    "keys cannot fill memory; the description is incomplete, so generation refuses it.",
    example="[FileInfo]\n0=1\n1=1\n... (70,000 keys)",
    fix="Check that the file is a device description; remove the repeated or generated keys.",
    blocks=True,
    blocking="The section is not read whole, so the C would not match the file.",
    no_repair="A section past the key limit is not read.")
